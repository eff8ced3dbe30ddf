# Copyright 2026 stewart_kinematics developers
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.

"""
mock_platform as a process: leg commands in, joint states that converge within the limits out.

mock_platform runs as a console script with the shipped parameter files (the paper's platform,
the example limits: legs 0.65 to 0.90 m, 0.05 m/s, 0.25 m/s^2, and config/mock_platform.yaml).
The test's own node sends joint_commands, leg_lengths and a leg_trajectory and watches
joint_states: every message within the stroke, its velocities within the limit, the change
of velocity between two messages (by their stamps) within the acceleration limit, and the legs
at the command in the end. With fk_node the loop closes: the pose fk_node estimates from the
simulated legs is the pose whose lengths were commanded. Faults set through the parameter
service show on joint_states: a stalled leg stays, noise has the asked deviation.
"""

from builtin_interfaces.msg import Duration
from geometry_msgs.msg import Pose
from helpers import pose_message, Recorder
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import SetParameters
import reference
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint
import yaml

pytestmark = pytest.mark.process

LENGTH_MIN, LENGTH_MAX, VELOCITY_MAX, ACCELERATION_MAX = 0.65, 0.90, 0.05, 0.25
NAMES = [f'leg_{leg}' for leg in range(1, 7)]
#: How close the legs come to a command they have reached, metres.
REACHED = 1e-6


def mock_args(config_directory, *extra):
    """Return ROS arguments: the paper's platform, the example limits, mock_platform's file."""
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'example_limits.yaml'),
            '--params-file', str(config_directory / 'mock_platform.yaml'), *extra]


def home_lengths(config_directory):
    """Return the joints and the leg lengths of the home pose (Table 3's first row)."""
    with open(config_directory / 'paper_platform.yaml', encoding='utf-8') as stream:
        parameters = yaml.safe_load(stream)['/**']['ros__parameters']
    geometry = (np.reshape(parameters['base_joints'], (6, 3)),
                np.reshape(parameters['platform_joints'], (6, 3)))
    return geometry, np.array(reference.leg_lengths(reference.HOME, *geometry))


def positions(message):
    """Return the positions of a JointState in the order leg_1..leg_6."""
    return np.array([message.position[list(message.name).index(name)] for name in NAMES])


def stamps(messages):
    """Return the stamps of messages, seconds after the first (from integer nanoseconds: exact)."""
    nanoseconds = [m.header.stamp.sec * 10**9 + m.header.stamp.nanosec for m in messages]
    return np.array([value - nanoseconds[0] for value in nanoseconds]) * 1e-9


def check_limits(messages):
    """Check every joint state within the stroke, the velocity and the acceleration limits."""
    lengths = np.array([positions(message) for message in messages])
    velocities = np.array([message.velocity for message in messages])
    assert lengths.min() >= LENGTH_MIN and lengths.max() <= LENGTH_MAX
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    times = stamps(messages)
    assert np.all(np.diff(times) > 0.0)
    accelerations = np.diff(velocities, axis=0) / np.diff(times)[:, None]
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-6)
    # Positions move by the published velocities.
    assert_allclose(np.diff(lengths, axis=0), velocities[1:] * np.diff(times)[:, None],
                    atol=1e-9)


def set_parameter(client, process, name, value):
    """Set a parameter of mock_platform through its service; return the result."""
    service = client.node.create_client(SetParameters, '/mock_platform/set_parameters')
    client.wait(service.service_is_ready, 'the parameter service', [process])
    if isinstance(value, str):
        typed = ParameterValue(type=ParameterType.PARAMETER_STRING, string_value=value)
    elif isinstance(value, int):
        typed = ParameterValue(type=ParameterType.PARAMETER_INTEGER, integer_value=value)
    elif isinstance(value, float):
        typed = ParameterValue(type=ParameterType.PARAMETER_DOUBLE, double_value=value)
    else:
        typed = ParameterValue(type=ParameterType.PARAMETER_DOUBLE_ARRAY, double_array_value=value)
    future = service.call_async(SetParameters.Request(
        parameters=[Parameter(name=name, value=typed)]))
    client.wait(future.done, f'the set of {name}', [process])
    return future.result().results[0]


def reached(recorder, lengths, count_from, legs=slice(None)):
    """Whether the latest joint state has ``lengths`` (metres) within REACHED."""
    received = recorder.received['joint_states']
    return len(received) > count_from and np.abs(
        positions(received[-1])[legs] - np.asarray(lengths)[legs]).max() < REACHED


def test_joint_commands_leg_lengths_and_a_trajectory_are_followed_within_the_limits(
        client, start_node, config_directory):
    """Each command reached in turn, every joint state within the limits; bad ones refused."""
    _, home = home_lengths(config_directory)
    node = start_node('mock_platform', mock_args(config_directory))
    recorder = Recorder(client, [node])
    recorder.subscribe(JointState, 'joint_states')
    for message_type, topic in ((JointState, 'joint_commands'),
                                (Float64MultiArray, 'leg_lengths'),
                                (JointTrajectory, 'leg_trajectory')):
        recorder.advertise(message_type, topic)
    recorder.connect()
    recorder.wait_for('joint_states', 5)
    first = recorder.received['joint_states'][0]
    assert_allclose(positions(first), home, atol=1e-12)
    assert list(first.name) == NAMES and len(first.effort) == 0

    # joint_commands, its joints in another order: 1 cm up on every leg, 1 mm more per leg.
    target = home + 0.01 + 0.001 * np.arange(6)
    order = [5, 3, 1, 0, 2, 4]
    recorder.publishers['joint_commands'].publish(JointState(
        name=[NAMES[i] for i in order], position=[float(target[i]) for i in order]))
    count = len(recorder.received['joint_states'])
    client.wait(lambda: reached(recorder, target, count), 'the joint command reached', [node])

    # leg_lengths: 2 cm below home.
    target = home - 0.02
    recorder.publishers['leg_lengths'].publish(Float64MultiArray(data=target.tolist()))
    client.wait(lambda: reached(recorder, target, count), 'the leg lengths reached', [node])

    # Refused: NaN, a leg beyond the stroke, a wrong name; the legs stay where they were.
    bad = [JointState(name=NAMES, position=[0.7] * 5 + [float('nan')]),
           JointState(name=NAMES, position=[0.7] * 5 + [1e308]),
           JointState(name=NAMES[:5] + ['leg_7'], position=[0.7] * 6)]
    for message in bad:
        recorder.publishers['joint_commands'].publish(message)
    recorder.publishers['leg_lengths'].publish(Float64MultiArray(data=[0.7] * 5))
    status = recorder.rejection('/mock_platform: joint_commands', 'invalid_leg_command')
    assert {value.key: value.value for value in status.values}['rejected'] == '3'
    recorder.rejection('/mock_platform: leg_lengths', 'invalid_leg_command')
    recorder.publishers['leg_trajectory'].publish(JointTrajectory(joint_names=NAMES, points=[
        JointTrajectoryPoint(positions=[float('inf')] * 6, time_from_start=Duration(sec=1))]))
    recorder.rejection('/mock_platform: leg_trajectory', 'invalid_leg_command')
    client.spin_for(0.3)
    assert_allclose(positions(recorder.received['joint_states'][-1]), target, atol=REACHED)

    # A trajectory from now: 1 cm above home at 1 s, 2 cm at 2 s; its last point reached.
    points = [JointTrajectoryPoint(positions=(home + 0.01).tolist(),
                                   time_from_start=Duration(sec=1)),
              JointTrajectoryPoint(positions=(home + 0.02).tolist(),
                                   time_from_start=Duration(sec=2))]
    recorder.publishers['leg_trajectory'].publish(JointTrajectory(joint_names=NAMES,
                                                                  points=points))
    sent = len(recorder.received['joint_states'])
    target = home + 0.02
    client.wait(lambda: reached(recorder, target, sent), 'the trajectory followed', [node])
    messages = recorder.received['joint_states']
    times = stamps(messages[sent:])
    # Not before 2 s after it was sent (its last point is at 2 s), nor long after.
    assert 1.9 < times[-1] - times[0] < 4.0
    check_limits(messages)


def test_the_loop_closes_from_ik_node_through_the_simulated_legs_to_fk_node(
        client, start_node, config_directory):
    """
    Table 3's row 4 on ik_node's target_pose: fk_node's estimate is row 4 (1e-6 m, rad).

    As doc/mock_platform.md closes the loop: ik_node's joint_commands drive mock_platform,
    fk_node reads its joint_states (its own leg_lengths remapped away from ik_node's).
    """
    pose = np.array(reference.TABLE_3[4])
    files = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
             '--params-file', str(config_directory / 'example_limits.yaml')]
    nodes = [start_node('ik_node', files),
             start_node('mock_platform', mock_args(config_directory, '-p', 'time_constant:=0.02',
                                                   '-p', "command_input:='joint_commands'")),
             start_node('fk_node', files + ['--params-file', str(config_directory / 'solver.yaml'),
                                            '-r', 'leg_lengths:=commanded_leg_lengths_unused'])]
    recorder = Recorder(client, nodes)
    recorder.subscribe(Pose, 'estimated_pose')
    recorder.subscribe(JointState, 'joint_states')
    recorder.advertise(Pose, 'target_pose')
    recorder.connect()
    # mock_platform subscribes joint_commands: ik_node builds them (only while subscribed).
    client.wait(lambda: client.node.count_subscribers('joint_commands') >= 1,
                "mock_platform's joint_commands subscription", nodes)
    recorder.wait_for('estimated_pose', 1)
    recorder.publishers['target_pose'].publish(pose_message(pose))

    expected = reference.quaternion_from_euler(*pose[3:])

    def pose_error():
        """Return the larger of the position error (m) and rotation angle (rad), or inf."""
        received = recorder.received['estimated_pose']
        if not received:
            return np.inf
        position, orientation = received[-1].position, received[-1].orientation
        return max(np.abs(np.array([position.x, position.y, position.z]) - pose[:3]).max(),
                   reference.quaternion_angle(expected, [orientation.x, orientation.y,
                                                         orientation.z, orientation.w]))

    client.wait(lambda: pose_error() < 1e-6,
                "fk_node's pose at the commanded one", nodes)


def test_a_stalled_leg_and_noise_set_at_run_time_show_on_joint_states(
        client, start_node, config_directory):
    """leg_3 stalled: it stays while the others go; then 1 mm noise of that deviation, no bias."""
    _, home = home_lengths(config_directory)
    node = start_node('mock_platform', mock_args(config_directory))
    recorder = Recorder(client, [node])
    recorder.subscribe(JointState, 'joint_states')
    recorder.advertise(Float64MultiArray, 'leg_lengths')
    recorder.connect()
    assert set_parameter(client, node, 'stalled_legs', 'leg_3').successful
    refused = set_parameter(client, node, 'stalled_legs', 'leg_9')
    assert not refused.successful and 'leg_9' in refused.reason
    target = home + 0.01
    recorder.publishers['leg_lengths'].publish(Float64MultiArray(data=target.tolist()))
    count = len(recorder.received['joint_states'])
    moving = [0, 1, 3, 4, 5]
    client.wait(lambda: reached(recorder, target, count, moving), 'the other legs moved',
                [node])
    assert_allclose(positions(recorder.received['joint_states'][-1])[2], home[2], atol=1e-12)
    check_limits(recorder.received['joint_states'])

    # Moving again, then 1 mm of noise: 300 joint states at rest.
    assert set_parameter(client, node, 'stalled_legs', '').successful
    client.wait(lambda: reached(recorder, target, count), 'leg_3 moved again', [node])
    assert set_parameter(client, node, 'noise_seed', 3).successful
    assert set_parameter(client, node, 'position_noise', 0.001).successful
    # The first noisy state marks the change (states sent before it may still be arriving:
    # a fixed wait lost that race once under load).
    client.wait(lambda: np.any(positions(recorder.received['joint_states'][-1]) != target),
                'the first noisy joint state', [node])
    start = len(recorder.received['joint_states'])
    recorder.wait_for('joint_states', start + 300)
    noisy = np.array([positions(m) for m in recorder.received['joint_states'][start:]])
    errors = noisy - target
    # 1800 samples: the mean within 5 standard errors, the deviation within 15 %.
    assert np.abs(errors.mean()) < 5 * 0.001 / np.sqrt(errors.size)
    assert_allclose(errors.std(), 0.001, rtol=0.15)

    # No noise, 2 mm of bias on leg 6: exactly that offset, on leg 6 only.
    assert set_parameter(client, node, 'position_noise', 0.0).successful
    bias = [0.0, 0.0, 0.0, 0.0, 0.0, 0.002]
    assert set_parameter(client, node, 'position_bias', bias).successful
    client.wait(lambda: np.allclose(positions(recorder.received['joint_states'][-1]),
                                    target + bias, rtol=0.0, atol=1e-12),
                'a joint state with the bias and no noise', [node])
    count = len(recorder.received['joint_states'])
    recorder.wait_for('joint_states', count + 20)   # and it stays so
    after = np.array([positions(m) for m in recorder.received['joint_states'][count:]])
    assert_allclose(after, np.tile(target + bias, (len(after), 1)), rtol=0.0, atol=1e-12)
    refused = set_parameter(client, node, 'position_bias', [0.0] * 5 + [float('nan')])
    assert not refused.successful and 'position_bias' in refused.reason
