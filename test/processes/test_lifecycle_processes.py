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
Managed (lifecycle) nodes across processes: every transition through the standard services.

Each node runs as its console script with ``-p managed:=true``; the test's client drives it
with lifecycle_msgs/srv/ChangeState and GetState, as ``ros2 lifecycle set`` and nav2's
lifecycle manager do, listens on its outputs and on ``~/transition_event``. Expected values
are written out here (the leg formula of ``reference``, the limits of example_limits.yaml).
"""

import time

from geometry_msgs.msg import Pose
from helpers import (CLIENT_DEPTH, DEADLINE, fail_with_output, pose_message, stop_cleanly,
                     trajectory_message)
from lifecycle_msgs.msg import TransitionEvent
from lifecycle_msgs.srv import ChangeState, GetAvailableTransitions, GetState
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rcl_interfaces.srv import SetParameters
from rclpy.parameter import Parameter
import reference
from sensor_msgs.msg import Imu, JointState
from std_msgs.msg import Float64MultiArray
from std_srvs.srv import Trigger
from trajectory_msgs.msg import JointTrajectory, MultiDOFJointTrajectory

pytestmark = pytest.mark.process

#: example_limits.yaml: leg speed and acceleration limits, m/s and m/s^2.
VELOCITY_MAX, ACCELERATION_MAX = 0.05, 0.25
#: The paper's home pose.
HOME = np.array(reference.TABLE_3[0])
#: Seconds a test listens to make sure nothing comes (a pause, never a wait for data).
QUIET_TIME = 1.0


def config_args(config_directory, *extra, managed=True):
    """ROS arguments: the shipped platform and example limits, managed, then ``extra``."""
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'example_limits.yaml'),
            *(['-p', 'managed:=true'] if managed else []), *extra]


class Lifecycle:
    """A managed node's lifecycle services and transition events, seen from the test client."""

    def __init__(self, client, node_name, processes):
        """Create the service clients and subscribe to ``/<node_name>/transition_event``."""
        self.client, self.processes = client, processes
        node = client.node
        self.change_client = node.create_client(ChangeState, f'/{node_name}/change_state')
        self.state_client = node.create_client(GetState, f'/{node_name}/get_state')
        self.transitions_client = node.create_client(
            GetAvailableTransitions, f'/{node_name}/get_available_transitions')
        self.events = []
        self.subscription = node.create_subscription(
            TransitionEvent, f'/{node_name}/transition_event', self.events.append, CLIENT_DEPTH)
        client.wait(lambda: all(service.service_is_ready() for service in (
            self.change_client, self.state_client, self.transitions_client)),
            f'the lifecycle services of {node_name}', processes)
        client.wait(lambda: self.subscription.get_publisher_count() >= 1,
                    f'{node_name}/transition_event matched', processes)
        # A ready service may still lose its answer, the node not yet matched with this
        # client's response reader ("failed to send response (timeout)": a stop's CI failed
        # so on configure). Ask the idempotent get_state, again each second, until it answers.
        deadline = time.monotonic() + DEADLINE
        while True:
            future = self.state_client.call_async(GetState.Request())
            if client.look_for(future.done, 1.0) or time.monotonic() > deadline:
                break
        client.wait(future.done, f'an answer of {self.state_client.srv_name}', processes)

    def call(self, service, request):
        """Call a service and return its response (fail with the nodes' output if none)."""
        future = service.call_async(request)
        self.client.wait(future.done, f'an answer of {service.srv_name}', self.processes)
        return future.result()

    def change(self, transition) -> bool:
        """Ask for a transition by label (``configure``, ...) or id; return ``success``."""
        request = ChangeState.Request()
        if isinstance(transition, str):
            request.transition.label = transition
        else:
            request.transition.id = transition
        return self.call(self.change_client, request).success

    def state(self) -> str:
        """Return the label of the node's state."""
        return self.call(self.state_client, GetState.Request()).current_state.label

    def available(self):
        """Return the labels of the transitions available now."""
        response = self.call(self.transitions_client, GetAvailableTransitions.Request())
        return sorted(item.transition.label for item in response.available_transitions)

    def goals(self):
        """Return the (start, goal) labels of every transition event received."""
        return [(event.start_state.label, event.goal_state.label) for event in self.events]


def listen(client, message_type, topic):
    """Collect the messages of ``topic``."""
    received = []
    client.node.create_subscription(message_type, topic, received.append, CLIENT_DEPTH)
    return received


def set_parameter(client, lifecycle, node_name, name, value):
    """Set one parameter through the node's set_parameters service; return the result."""
    service = client.node.create_client(SetParameters, f'/{node_name}/set_parameters')
    client.wait(service.service_is_ready, f'{node_name}/set_parameters', lifecycle.processes)
    request = SetParameters.Request(parameters=[Parameter(name, value=value).to_parameter_msg()])
    return lifecycle.call(service, request).results[0]


def joint_arrays(messages):
    """Return stamps (s), positions and velocities (N, 6) of JointState messages."""
    stamps = np.array([m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 for m in messages])
    return (stamps, np.array([m.position for m in messages]),
            np.array([m.velocity for m in messages]))


def test_ik_node_every_transition_and_a_stream_braked_to_rest(
        client, start_node, config_directory):
    """
    Take ik_node, streaming at 100 Hz, through every transition.

    Unconfigured and inactive it publishes nothing and never acts later on what came
    meanwhile; active it streams; deactivated mid-stream it brakes to rest within the
    velocity and acceleration limits, then is silent; cleanup removes its topics, configure
    and activate work again; shutdown ends the process (0).
    """
    node = start_node('ik_node', config_args(config_directory, '-p', 'command_rate:=100.0'))
    lifecycle = Lifecycle(client, 'ik_node', [node])
    lengths = listen(client, Float64MultiArray, '/leg_lengths')
    commands = listen(client, JointState, '/joint_commands')
    target = client.node.create_publisher(Pose, '/target_pose', CLIENT_DEPTH)
    far = HOME + [0.0, 0.0, 0.03, 0.0, 0.0, 0.0]

    assert lifecycle.state() == 'unconfigured'
    assert lifecycle.available() == ['configure', 'shutdown']
    assert client.node.count_publishers('/leg_lengths') == 0   # nothing built yet
    assert lifecycle.change('configure') and lifecycle.state() == 'inactive'
    client.wait(lambda: target.get_subscription_count() >= 1, 'target_pose matched', [node])
    client.wait(lambda: client.node.count_publishers('/joint_commands') >= 1,
                'joint_commands advertised', [node])
    client.spin_for(0.5)
    # Inactive: the pose is ignored, and not acted on once active.
    target.publish(pose_message(far))
    # The log line says the pose arrived (a fixed wait could end before it under load).
    client.wait(lambda: 'target_pose: message ignored, the node is not active' in node.output(),
                'the pose ignored while inactive, in the log', [node])
    client.spin_for(QUIET_TIME)
    assert lengths == [] and commands == []
    assert lifecycle.change('activate') and lifecycle.state() == 'active'
    client.spin_for(QUIET_TIME)
    assert lengths == [] and commands == []

    # Active: the pose is answered and the stream moves toward it.
    target.publish(pose_message(far))
    client.wait(lambda: lengths, 'leg_lengths of the pose', [node])
    assert_allclose(lengths[0].data, reference.leg_lengths(far),
                    rtol=0, atol=1e-12)
    client.wait(lambda: commands and np.abs(commands[-1].velocity).max() > 0.6 * VELOCITY_MAX,
                'the stream at speed', [node])
    assert lifecycle.change('deactivate') and lifecycle.state() == 'inactive'
    # The braking commands, sent during the transition, may arrive after its answer: count
    # from the last, at rest (else one still on its way counted as sent after deactivate).
    client.wait(lambda: np.abs(commands[-1].velocity).max() <= 1e-12,
                'the braking command at rest', [node])
    sent = len(commands)
    client.spin_for(QUIET_TIME)
    assert len(commands) == sent, 'joint_commands published after deactivate'
    stamps, positions, velocities = joint_arrays(commands)
    # At rest, short of the target: braked, not arrived.
    assert_allclose(velocities[-1], 0.0, rtol=0, atol=1e-12)
    target_lengths = reference.leg_lengths(far)
    assert np.abs(positions[-1] + 0.0 - np.array(target_lengths)).max() > 1e-3
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    # The final deceleration: each braking command a stream period after the last on the
    # command gate's time line, every leg slowed by at most leg_acceleration_max per period,
    # to rest (the stream's velocities are its plan's, braking included: no jump).
    speed = np.abs(velocities).max(axis=1)
    start = len(speed) - 1
    while start > 0 and speed[start - 1] >= speed[start]:
        start -= 1
    steps = np.abs(np.diff(velocities[start:], axis=0))
    assert len(steps) >= 5, speed
    assert np.all(steps <= ACCELERATION_MAX * 0.01 * (1 + 1e-6)), steps
    # Stamped with their times on that line (exactly a period apart), so that the rates their
    # stamps give are those checked: before, the clock's now, late by the send each time, and
    # all one stamp under a simulated clock, which stands still meanwhile.
    # The last five are braking commands at least (it takes over 0.1 s from 0.6 of the speed
    # limit); nanoseconds, rounded each: 1 ns either way.
    braking = [m.header.stamp.sec * 1_000_000_000 + m.header.stamp.nanosec
               for m in commands[-6:]]
    assert np.all(np.abs(np.diff(braking) - 10_000_000) <= 1), np.diff(braking)
    assert 'braked to rest' in node.output()

    # Cleanup: the topics go; configure and activate again: it answers again.
    assert lifecycle.change('cleanup') and lifecycle.state() == 'unconfigured'
    client.wait(lambda: client.node.count_publishers('/leg_lengths') == 0,
                'leg_lengths gone after cleanup', [node])
    assert lifecycle.change('configure') and lifecycle.change('activate')
    client.wait(lambda: target.get_subscription_count() >= 1, 'target_pose matched', [node])
    client.spin_for(0.5)
    target.publish(pose_message(HOME))
    client.wait(lambda: len(lengths) >= 2, 'leg_lengths after configure again', [node])

    assert lifecycle.change('shutdown')
    client.wait(lambda: not node.running(), 'the process ends after shutdown', [])
    assert stop_cleanly(node)
    assert lifecycle.goals() == [
        ('unconfigured', 'configuring'), ('configuring', 'inactive'),
        ('inactive', 'activating'), ('activating', 'active'),
        ('active', 'deactivating'), ('deactivating', 'inactive'),
        ('inactive', 'cleaningup'), ('cleaningup', 'unconfigured'),
        ('unconfigured', 'configuring'), ('configuring', 'inactive'),
        ('inactive', 'activating'), ('activating', 'active'),
        ('active', 'shuttingdown'), ('shuttingdown', 'finalized')]


def test_fk_node_bad_parameter_fails_configure_and_is_fixed(
        client, start_node, config_directory):
    """
    Fail fk_node's configure with a stroke limit not allowed, then fix it.

    Configure fails with the reason in the log, the node stays unconfigured and alive; set
    right, it configures, activates and estimates poses.
    """
    node = start_node('fk_node', config_args(config_directory, '-p', 'leg_length_max:=-1.0'))
    lifecycle = Lifecycle(client, 'fk_node', [node])
    poses = listen(client, Pose, '/estimated_pose')
    lengths = client.node.create_publisher(Float64MultiArray, '/leg_lengths', CLIENT_DEPTH)

    assert not lifecycle.change('configure')
    assert lifecycle.state() == 'unconfigured' and node.running()
    assert "configure failed, the node stays unconfigured: parameter 'leg_length_max' must " \
        'be in' in node.output()
    assert lifecycle.goals()[-1] == ('configuring', 'unconfigured')
    # Read-only, but settable while unconfigured; a bad value is still refused.
    refused = set_parameter(client, lifecycle, 'fk_node', 'leg_length_max', float('nan'))
    assert not refused.successful and 'leg_length_max' in refused.reason
    assert set_parameter(client, lifecycle, 'fk_node', 'leg_length_max', 0.9).successful
    assert lifecycle.change('configure') and lifecycle.state() == 'inactive'
    # Configured, the read-only parameter is read-only again.
    refused = set_parameter(client, lifecycle, 'fk_node', 'leg_length_max', 0.95)
    assert not refused.successful and 'read-only while the node is configured' in refused.reason
    home = reference.leg_lengths(HOME)
    client.wait(lambda: lengths.get_subscription_count() >= 1, 'leg_lengths matched', [node])
    client.spin_for(0.5)
    lengths.publish(Float64MultiArray(data=list(home)))
    client.spin_for(QUIET_TIME)
    assert poses == []
    assert lifecycle.change('activate')
    client.spin_for(0.5)
    assert poses == []
    lengths.publish(Float64MultiArray(data=list(home)))
    client.wait(lambda: poses, 'estimated_pose once active', [node])
    assert_allclose([poses[0].position.x, poses[0].position.y, poses[0].position.z],
                    HOME[:3], rtol=0, atol=1e-9)
    # Inactive again: silent.
    assert lifecycle.change('deactivate')
    lengths.publish(Float64MultiArray(data=list(home)))
    client.spin_for(QUIET_TIME)
    assert len(poses) == 1
    # Shutdown from inactive.
    assert lifecycle.change('shutdown')
    client.wait(lambda: not node.running(), 'the process ends after shutdown', [])
    assert stop_cleanly(node)


@pytest.mark.parametrize('problem, reason', [
    ('leg_lenth_max: 0.9', "unknown parameter(s) 'leg_lenth_max'"),
    ('leg_length_max: "0.9"', "parameter 'leg_length_max' must be of type double"),
], ids=['misspelt_name', 'wrong_type'])
def test_bad_parameter_file_fails_configure_and_the_node_shuts_down(
        client, start_node, config_directory, tmp_path, problem, reason):
    """A file a node cannot take: configure fails naming it; the node answers shutdown."""
    path = tmp_path / 'bad.yaml'
    path.write_text(f'/**:\n  ros__parameters:\n    {problem}\n', encoding='utf-8')
    node = start_node('trajectory_node', config_args(
        config_directory, '--params-file', str(path), '-p', "mode:='off'"))
    lifecycle = Lifecycle(client, 'trajectory_node', [node])

    assert not lifecycle.change('configure')
    assert lifecycle.state() == 'unconfigured' and node.running()
    assert reason in node.output()
    assert not lifecycle.change('configure')     # it stays wrong: refused again
    assert lifecycle.change('shutdown')
    client.wait(lambda: not node.running(), 'the process ends after shutdown', [])
    assert stop_cleanly(node)


def test_trajectory_node_plays_only_while_active(client, start_node, config_directory):
    """
    Play the ramp only while active.

    The ramp, looping: nothing while inactive, poses once active, none after deactivate; a
    trajectory received while inactive is never planned.
    """
    node = start_node('trajectory_node', config_args(
        config_directory, '--params-file', str(config_directory / 'table3_ramp.yaml'),
        '-p', 'loop:=true', '-p', 'min_subscribers:=1'))
    lifecycle = Lifecycle(client, 'trajectory_node', [node])
    poses = listen(client, Pose, '/target_pose')
    trajectories = listen(client, JointTrajectory, '/leg_trajectory')
    trajectory = client.node.create_publisher(
        MultiDOFJointTrajectory, '/pose_trajectory', CLIENT_DEPTH)

    assert lifecycle.change('configure')
    client.wait(lambda: trajectory.get_subscription_count() >= 1, 'pose_trajectory matched',
                [node])
    client.spin_for(0.5)
    trajectory.publish(trajectory_message([0.0, 1.0], [HOME, HOME]))
    client.spin_for(QUIET_TIME)
    assert poses == [] and trajectories == []
    assert lifecycle.change('activate')
    client.wait(lambda: len(poses) >= 5, 'ramp poses once active', [node])
    assert trajectories == []   # the one received while inactive was not planned
    assert lifecycle.change('deactivate')
    played = len(poses)
    client.spin_for(QUIET_TIME)
    assert len(poses) == played, 'target_pose published after deactivate'
    assert lifecycle.change('cleanup') and lifecycle.change('shutdown')
    client.wait(lambda: not node.running(), 'the process ends after shutdown', [])
    assert stop_cleanly(node)


def imu(stamp, force_x):
    """Return a vehicle_imu sample: a forward specific force, at rest otherwise, stamped."""
    message = Imu()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(int(stamp * 1e9), 10 ** 9)
    message.linear_acceleration.x, message.linear_acceleration.z = force_x, 9.81
    return message


def pose_legs(pose):
    """Return the leg lengths of a Pose, metres."""
    p, o = pose.position, pose.orientation
    return reference.leg_lengths_of_matrix(
        [p.x, p.y, p.z], reference.quaternion_matrix(o.x, o.y, o.z, o.w))


def test_motion_cueing_node_starts_from_park_and_stops_to_park(
        client, start_node, config_directory):
    """
    motion_cueing_node's activate starts from park, its deactivate stops to park.

    Inactive: samples ignored, reset answers that it is inactive; active: up from park, then
    cues; deactivated mid-cue: the platform brakes and parks, then nothing is published.
    """
    node = start_node('motion_cueing_node', config_args(
        config_directory, '--params-file', str(config_directory / 'motion_cueing.yaml'),
        '-p', 'soft_start_time:=0.5', '-p', 'soft_stop_time:=0.5'))
    lifecycle = Lifecycle(client, 'motion_cueing_node', [node])
    poses = listen(client, Pose, '/target_pose')
    samples = client.node.create_publisher(Imu, '/vehicle_imu', CLIENT_DEPTH)
    reset = client.node.create_client(Trigger, '/reset')

    assert lifecycle.change('configure')
    client.wait(lambda: samples.get_subscription_count() >= 1 and reset.service_is_ready(),
                'vehicle_imu matched', [node])
    client.spin_for(0.5)
    for index in range(20):
        samples.publish(imu(1.0 + 0.01 * index, 3.0))
    answer = lifecycle.call(reset, Trigger.Request())
    assert not answer.success and 'not active' in answer.message
    client.spin_for(QUIET_TIME)
    assert poses == []
    assert lifecycle.change('activate')
    start = time.monotonic()
    index = 0
    # 1.5 s of samples, and on until over 10 poses came (a deadline, not a fixed time: the
    # answers lag on a loaded machine).
    while time.monotonic() - start < 1.5 or len(poses) <= 10:
        if time.monotonic() - start > 1.5 + DEADLINE or not node.running():
            fail_with_output(f'{len(poses)} poses after {index} samples', [node])
        index += 1
        samples.publish(imu(10.0 + 0.01 * index, 3.0))
        client.spin_for(0.01)
    assert lifecycle.change('deactivate')
    # The stop to park is sent during the transition and may arrive after its answer: count
    # from the park pose (else one still on its way counted as sent after deactivate).
    client.wait(lambda: abs(min(pose_legs(poses[-1])) - 0.66) <= 1e-6, 'the park pose', [node])
    sent = len(poses)
    client.spin_for(QUIET_TIME)
    assert len(poses) == sent, 'target_pose published after deactivate'
    legs = np.array([pose_legs(p) for p in poses[-2:]])
    # The last command is park (the shortest leg 10 mm above the stroke's 0.65 m,
    # leg_length_margin), arrived at rest: the last step a few micrometres.
    assert_allclose(legs[-1], legs[-2], rtol=0, atol=1e-5)
    assert_allclose(legs[-1].min(), 0.66, rtol=0, atol=1e-6)
    assert 'stopped to park' in node.output()
    assert lifecycle.change('shutdown')
    client.wait(lambda: not node.running(), 'the process ends after shutdown', [])
    assert stop_cleanly(node)
