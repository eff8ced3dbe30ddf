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
Motion across real processes: trajectories in, JointTrajectory out; streamed commands.

``trajectory_node``, ``ik_node`` and ``fk_node`` run as console-script processes with the
shipped parameter files (the paper's platform and the example limits: legs 0.65 to 0.90 m,
0.05 m/s, 0.25 m/s^2, 2.5 m/s^3). The test's own node publishes trajectories, paths and poses
and checks what comes out. Expected leg lengths come from the geometry read with PyYAML and
the leg formula written out here; velocities are checked against finite differences of the
published positions: nothing is shared with the package's code.
"""


from geometry_msgs.msg import Pose, PoseStamped
from helpers import pose_message, Recorder, trajectory_message
from nav_msgs.msg import Path
import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory, MultiDOFJointTrajectory
import yaml

pytestmark = pytest.mark.process

VELOCITY_MAX, ACCELERATION_MAX, JERK_MAX = 0.05, 0.25, 2.5
#: Rate of the points of leg_trajectory in these tests, hertz.
POINT_RATE = 200.0
#: The paper's Table 3: X, Y, Z (m), alpha, beta, gamma (rad), rows 0..10.
TABLE_3 = np.array(reference.TABLE_3)
HOME = TABLE_3[0]


def read_geometry(path):
    """Read the base and platform joints (6, 3) of a parameter file's ``/**`` section."""
    with open(path, encoding='utf-8') as stream:
        parameters = yaml.safe_load(stream)['/**']['ros__parameters']
    return (np.reshape(parameters['base_joints'], (6, 3)),
            np.reshape(parameters['platform_joints'], (6, 3)))


def pose_lengths(geometry, pose):
    """Leg lengths ``|t + R p_i - b_i|`` of a pose for ``geometry = (base, platform)``, metres."""
    return np.array(reference.leg_lengths(pose, *geometry))


def path_message(poses):
    """nav_msgs/Path through the poses, without timing."""
    message = Path()
    message.header.frame_id = 'stewart_base'
    message.poses = [PoseStamped(pose=pose_message(pose)) for pose in poses]
    return message


def point_arrays(message):
    """Return times (s), positions, velocities, accelerations (N, 6) of a JointTrajectory."""
    times = np.array([p.time_from_start.sec + p.time_from_start.nanosec * 1e-9
                      for p in message.points])
    return (times, np.array([p.positions for p in message.points]),
            np.array([p.velocities for p in message.points]),
            np.array([p.accelerations for p in message.points]))


def config_args(config_directory, *extra):
    """Return ROS arguments: the shipped platform and example limits, then ``extra``."""
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'example_limits.yaml'), *extra]


def test_trajectories_checked_timed_and_refused(client, start_node, config_directory):
    """
    Two trajectory_nodes, as timed (/given) and retiming (/retimed), each with its joint names.

    /given: Table 3 one row a second in, leg_trajectory out whose positions at the waypoints
    are the IK of the waypoints (1e-9 m) and whose velocities and accelerations match finite
    differences; a too-fast segment and an unreachable waypoint refused with their reasons
    and nothing published. /retimed (with play): a too-fast trajectory and a path without
    timing, both retimed within every leg limit at every point, and played on target_pose.
    """
    geometry = read_geometry(config_directory / 'paper_platform.yaml')
    names = {'given': [f'given_{leg}' for leg in range(1, 7)],
             'retimed': [f'retimed_{leg}' for leg in range(1, 7)]}
    nodes = [start_node('trajectory_node', config_args(
        config_directory, '-r', f'__ns:=/{namespace}', '-p', "mode:='off'",
        '-p', f'publish_rate:={POINT_RATE}', '-p', f'retime:={str(retime).lower()}',
        '-p', 'joint_names:=[' + ', '.join(f"'{n}'" for n in names[namespace]) + ']',
        '-p', f'play:={str(retime).lower()}'))
        for namespace, retime in (('given', False), ('retimed', True))]
    recorder = Recorder(client, nodes)
    for namespace in names:
        recorder.subscribe(JointTrajectory, f'/{namespace}/leg_trajectory')
        recorder.advertise(MultiDOFJointTrajectory, f'/{namespace}/pose_trajectory')
    recorder.advertise(Path, '/retimed/pose_path')
    recorder.subscribe(Pose, '/retimed/target_pose')
    recorder.connect()

    # As timed: Table 3, one row a second.
    recorder.publishers['/given/pose_trajectory'].publish(
        trajectory_message(np.arange(11.0), TABLE_3))
    recorder.wait_for('/given/leg_trajectory', 1)
    message = recorder.received['/given/leg_trajectory'][0]
    assert list(message.joint_names) == names['given']
    times, positions, velocities, accelerations = point_arrays(message)
    assert times[0] == 0.0 and times[-1] == 10.0
    assert np.all(np.diff(times) <= 1.0 / POINT_RATE + 1e-9)
    at_waypoints = np.searchsorted(times, np.arange(11.0))
    assert_allclose(times[at_waypoints], np.arange(11.0), atol=1e-9)
    assert_allclose(positions[at_waypoints],
                    np.array([pose_lengths(geometry, pose) for pose in TABLE_3]),
                    rtol=0, atol=1e-9)
    # Central differences away from the waypoints, where the accelerations jump.
    step = 1.0 / POINT_RATE
    inner = np.array([i for i in range(1, len(times) - 1)
                      if abs(times[i] - round(times[i])) > 1.5 * step])
    assert len(inner) > 1500
    differences = (positions[inner + 1] - positions[inner - 1]) / (2.0 * step)
    assert_allclose(differences, velocities[inner], rtol=0, atol=1e-6)
    differences = (velocities[inner + 1] - velocities[inner - 1]) / (2.0 * step)
    assert_allclose(differences, accelerations[inner], rtol=0, atol=1e-6)
    assert np.abs(velocities).max() <= VELOCITY_MAX

    # Refused: a 5 cm lift in 0.3 s, then a waypoint beyond the stroke; nothing published.
    lift = np.array([HOME, HOME + [0.0, 0.0, 0.05, 0.0, 0.0, 0.0],
                     HOME + [0.0, 0.0, 0.05, 0.0, 0.0, 0.0]])
    recorder.publishers['/given/pose_trajectory'].publish(
        trajectory_message([0.0, 0.3, 5.0], lift))
    status = recorder.rejection('/given/trajectory_node: pose_trajectory', 'too_fast')
    assert 'between points 0 and 1' in status.message
    assert 'leg_acceleration_max' in status.message or 'leg_velocity_max' in status.message
    unreachable = np.array([HOME, HOME + [0.0, 0.0, 0.25, 0.0, 0.0, 0.0], HOME])
    recorder.publishers['/given/pose_trajectory'].publish(
        trajectory_message([0.0, 10.0, 20.0], unreachable))
    status = recorder.rejection('/given/trajectory_node: pose_trajectory', 'out_of_limits')
    assert 'leg_length_max' in status.message and 'between points 0 and 1' in status.message
    assert len(recorder.received['/given/leg_trajectory']) == 1

    # Retimed: the too-fast lift, and Table 3 as a path without timing.
    recorder.publishers['/retimed/pose_trajectory'].publish(
        trajectory_message([0.0, 0.3, 5.0], lift))
    recorder.wait_for('/retimed/leg_trajectory', 1)
    recorder.publishers['/retimed/pose_path'].publish(path_message(TABLE_3))
    recorder.wait_for('/retimed/leg_trajectory', 2)
    lift_out, table_out = recorder.received['/retimed/leg_trajectory']
    for message, poses in ((lift_out, lift), (table_out, TABLE_3)):
        assert list(message.joint_names) == names['retimed']
        times, positions, velocities, accelerations = point_arrays(message)
        assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
        assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-9)
        assert_allclose(positions[[0, -1]], [pose_lengths(geometry, poses[0]),
                                             pose_lengths(geometry, poses[-1])], atol=1e-9)
        speeds = np.abs(np.diff(positions, axis=0)) / np.diff(times)[:, None]
        assert speeds.max() <= VELOCITY_MAX * (1 + 1e-9)
    # Table 3 retimed: about 3 s instead of 10; the lift no faster than its limits allow.
    assert 2.5 < point_arrays(table_out)[0][-1] < 4.0
    # With play, the path's poses follow on target_pose and end at its last waypoint.
    played = recorder.received['/retimed/target_pose']

    def at_the_end():
        return played and np.allclose([played[-1].position.x, played[-1].position.y,
                                       played[-1].position.z], TABLE_3[-1][:3], atol=1e-9)
    recorder.client.wait(at_the_end, 'the played path at its last waypoint', nodes)
    assert len(played) > 100
    for node in nodes:
        assert node.running()


def test_streamed_commands_and_two_hexapods_on_one_joint_states(
        client, start_node, config_directory):
    """
    Two hexapods share /joint_states, each with its own joint names and offsets.

    /a: ik_node streams joint_commands at 100 Hz through the filter (onto /joint_states),
    within the velocity, acceleration and jerk limits, converging on the IK of the target
    minus the offsets; /b: ik_node commands directly. Each fk_node reads its own joints from
    the shared /joint_states and estimates its own platform.
    """
    geometry = read_geometry(config_directory / 'paper_platform.yaml')
    offsets = {'a': 0.5, 'b': 0.6}
    nodes = []
    for namespace in ('a', 'b'):
        joints = '[' + ', '.join(f"'{namespace}_leg_{leg}'" for leg in range(1, 7)) + ']'
        common = ['-r', f'__ns:=/{namespace}', '-p', f'joint_names:={joints}',
                  '-p', f'actuator_offsets:=[{", ".join([str(offsets[namespace])] * 6)}]']
        streaming = ['-p', 'command_rate:=100.0'] if namespace == 'a' else []
        nodes.append(start_node('ik_node', config_args(
            config_directory, *common, *streaming, '-r', 'joint_commands:=/joint_states')))
        nodes.append(start_node('fk_node', config_args(
            config_directory, *common, '-r', 'joint_states:=/joint_states',
            '-r', 'leg_lengths:=unused_lengths')))
    recorder = Recorder(client, nodes)
    recorder.subscribe(JointState, '/joint_states')
    for namespace in ('a', 'b'):
        recorder.subscribe(Pose, f'/{namespace}/estimated_pose')
        recorder.advertise(Pose, f'/{namespace}/target_pose')
    recorder.connect()
    # /b's one command must reach /b's fk_node too, not only the recorder: both fk_nodes and
    # both ik_nodes on /joint_states first (a command sent before its reader matched is lost,
    # which failed this test once under load), then time for them to match each other.
    recorder.client.wait(lambda: client.node.count_subscribers('/joint_states') >= 3
                         and client.node.count_publishers('/joint_states') >= 2,
                         'both ik_nodes and both fk_nodes on /joint_states', nodes)
    client.spin_for(0.5)

    target_a, target_b = TABLE_3[3], TABLE_3[8]
    recorder.publishers['/a/target_pose'].publish(pose_message(target_a))
    recorder.publishers['/b/target_pose'].publish(pose_message(target_b))
    expected_a = pose_lengths(geometry, target_a) - offsets['a']

    def settled():
        mine = [m for m in recorder.received['/joint_states'] if m.name[0] == 'a_leg_1']
        return len(mine) > 2 and np.allclose(mine[-1].position, expected_a, atol=1e-12) and (
            np.allclose(mine[-1].velocity, 0.0, atol=1e-12))
    recorder.client.wait(settled, '/a streamed commands settled on the target', nodes)
    recorder.client.wait(lambda: any(
        m.name[0] == 'b_leg_1' for m in recorder.received['/joint_states']), '/b command', nodes)

    # A refused target (beyond the stroke) leaves the command where it was heading.
    refused = target_a + [0.0, 0.0, 0.3, 0.0, 0.0, 0.0]
    recorder.publishers['/a/target_pose'].publish(pose_message(refused))
    count = len(recorder.received['/joint_states'])
    recorder.client.wait(lambda: len(recorder.received['/joint_states']) > count + 20,
                         '20 more commands', nodes)
    assert_allclose(recorder.received['/joint_states'][-1].position, expected_a, atol=1e-12)
    assert all(m.name[0] == 'a_leg_1' for m in recorder.received['/joint_states'][count:])

    streamed = [m for m in recorder.received['/joint_states'] if m.name[0] == 'a_leg_1']
    direct = [m for m in recorder.received['/joint_states'] if m.name[0] == 'b_leg_1']
    assert list(streamed[0].name) == [f'a_leg_{leg}' for leg in range(1, 7)]
    positions = np.array([m.position for m in streamed])
    velocities = np.array([m.velocity for m in streamed])
    # From the home pose to row 3 of Table 3 (legs move up to 3.5 cm): about 1 s at 100 Hz.
    assert len(streamed) > 50
    assert_allclose(positions[0], pose_lengths(geometry, HOME) - offsets['a'], atol=0.01)
    # Each step covers the time since the last on the node's clock: judged by the stamps.
    nanoseconds = np.array([m.header.stamp.sec * 1_000_000_000 + m.header.stamp.nanosec
                            for m in streamed])
    steps = np.diff(nanoseconds) * 1e-9
    assert np.all(steps > 0.0)
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    assert (np.abs(np.diff(positions, axis=0)) / steps[:, None]).max() <= (
        VELOCITY_MAX * (1 + 1e-9))
    accelerations = np.diff(velocities, axis=0) / steps[:, None]
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-6)
    jerks = np.diff(accelerations, axis=0) / (0.5 * (steps[1:] + steps[:-1]))[:, None]
    assert np.abs(jerks).max() <= 2.0 * JERK_MAX
    assert_allclose(direct[-1].position, pose_lengths(geometry, target_b) - offsets['b'],
                    atol=1e-12)

    # Each fk_node finds its own platform from its own joints of the shared topic.
    for namespace, target in (('a', target_a), ('b', target_b)):
        topic = f'/{namespace}/estimated_pose'

        def reached(topic=topic, target=target):
            poses = recorder.received[topic]
            return poses and np.allclose(
                [poses[-1].position.x, poses[-1].position.y, poses[-1].position.z],
                target[:3], atol=1e-9)
        recorder.client.wait(reached, f'{topic} at its target', nodes)
    for node in nodes:
        assert node.running()
