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
Managed nodes driven as an adversary would, and the process-level cases of managed nodes.

Transitions in a wrong order, twice, by unknown labels and ids, a flood of change_state calls,
SIGINT in every state; several nodes in one process (stewart_platform --autostart), and
unmanaged nodes unchanged.
"""

import subprocess

from geometry_msgs.msg import Pose
from helpers import CLIENT_DEPTH, pose_message, stop_cleanly
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState
import numpy as np
import pytest
import reference
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray
from test_lifecycle_processes import config_args, HOME, Lifecycle, listen, QUIET_TIME

pytestmark = pytest.mark.process


def test_transitions_in_a_wrong_order_are_refused_and_the_node_goes_on(
        client, start_node, config_directory):
    """Every transition not available from the state is refused; the state does not move."""
    node = start_node('ik_node', config_args(config_directory))
    lifecycle = Lifecycle(client, 'ik_node', [node])

    for transition in ('activate', 'deactivate', 'cleanup', 'fly', '',
                       Transition.TRANSITION_ACTIVATE, 99, 255):
        assert not lifecycle.change(transition), transition
        assert lifecycle.state() == 'unconfigured'
    assert lifecycle.change('configure')
    for transition in ('configure', 'deactivate', 'fly'):   # configure twice: refused
        assert not lifecycle.change(transition), transition
        assert lifecycle.state() == 'inactive'
    assert lifecycle.change('activate')
    for transition in ('activate', 'configure', 'cleanup'):
        assert not lifecycle.change(transition), transition
        assert lifecycle.state() == 'active'
    # Only the successful transitions were announced.
    assert lifecycle.goals() == [
        ('unconfigured', 'configuring'), ('configuring', 'inactive'),
        ('inactive', 'activating'), ('activating', 'active')]
    assert node.running()
    assert stop_cleanly(node)


# serial: with two workers, DDS dropped all but 3 of the kept responses in a CI run.
@pytest.mark.serial
def test_a_flood_of_change_state_calls_leaves_a_working_node(
        client, start_node, config_directory):
    """
    Answer a flood of 300 change_state requests and work on.

    The requests cycle through every transition (most refused in the state they find): the
    node answers what its service queue kept (keep last 10: DDS drops the rest, as for any ROS
    service), ends in a primary state, and works.
    """
    node = start_node('ik_node', config_args(config_directory))
    lifecycle = Lifecycle(client, 'ik_node', [node])
    labels = ('configure', 'activate', 'deactivate', 'cleanup', 'activate', 'configure')
    futures = []
    for index in range(300):
        request = ChangeState.Request()
        request.transition.label = labels[index % len(labels)]
        if index % 7 == 0:   # by id too, most of them not available from the state
            request.transition.label = ''
            request.transition.id = index % 100
        futures.append(lifecycle.change_client.call_async(request))
    answered = []

    def quiet():
        answered.append(sum(future.done() for future in futures))
        return len(answered) > 10 and answered[-1] == answered[-11] and answered[-1] > 0
    client.wait(quiet, 'the node answering the flood', [node])
    assert answered[-1] >= 10 and node.running()
    state = lifecycle.state()
    assert state in ('unconfigured', 'inactive', 'active')
    goals = lifecycle.goals()
    for start, goal in goals[1::2]:
        assert goal in ('unconfigured', 'inactive', 'active'), (start, goal)
    # Bring it to active from wherever it is, and it answers a pose.
    if state == 'unconfigured':
        assert lifecycle.change('configure')
    if lifecycle.state() == 'inactive':
        assert lifecycle.change('activate')
    lengths = listen(client, Float64MultiArray, '/leg_lengths')
    target = client.node.create_publisher(Pose, '/target_pose', CLIENT_DEPTH)
    client.wait(lambda: target.get_subscription_count() >= 1, 'target_pose matched', [node])
    client.spin_for(0.5)
    target.publish(pose_message(HOME))
    client.wait(lambda: lengths, 'leg_lengths after the flood', [node])
    assert stop_cleanly(node)


def test_configure_and_cleanup_again_and_again_release_the_worker_processes(
        client, start_node, config_directory):
    """fk_node's margin worker process: none is left after each cleanup, none piles up."""
    node = start_node('fk_node', config_args(
        config_directory, '--params-file', str(config_directory / 'solver.yaml'),
        '-p', 'assembly_mode_margin_period:=0.2'))
    lifecycle = Lifecycle(client, 'fk_node', [node])
    lengths = client.node.create_publisher(Float64MultiArray, '/leg_lengths', CLIENT_DEPTH)
    poses = listen(client, Pose, '/estimated_pose')
    home = list(reference.leg_lengths(HOME))

    def children(pid):
        result = subprocess.run(['pgrep', '-P', str(pid)], capture_output=True, text=True,
                                check=False)
        return result.stdout.split()

    def workers():
        """Return the worker processes: children of multiprocessing's forkserver, a child."""
        found = []
        for child in children(node.process.pid):
            try:
                with open(f'/proc/{child}/cmdline', 'rb') as stream:
                    if b'forkserver' in stream.read():
                        found += children(child)
            except OSError:
                continue
        return found

    for cycle in range(3):
        assert lifecycle.change('configure') and lifecycle.change('activate')
        client.wait(lambda: lengths.get_subscription_count() >= 1, 'leg_lengths matched',
                    [node])
        client.spin_for(0.3)
        lengths.publish(Float64MultiArray(data=home))
        client.wait(lambda: len(poses) > cycle, 'estimated_pose', [node])
        client.wait(workers, 'the margin worker process running', [node])
        assert lifecycle.change('deactivate') and lifecycle.change('cleanup')
        client.wait(lambda: not workers(), 'no worker process left after cleanup', [node])
    assert stop_cleanly(node)


@pytest.mark.parametrize('state', [
    'unconfigured', 'configure_failed', 'inactive', 'active', 'active_streaming'])
def test_sigint_in_every_state_exits_cleanly(client, start_node, config_directory, state):
    """SIGINT (Ctrl-C) in any state: exit code 0, no traceback, no worker left."""
    extra = ['-p', 'command_rate:=100.0']
    if state == 'configure_failed':
        extra += ['-p', 'leg_velocity_max:=-1.0']
    node = start_node('ik_node', config_args(config_directory, *extra))
    lifecycle = Lifecycle(client, 'ik_node', [node])
    if state == 'configure_failed':
        assert not lifecycle.change('configure')
    elif state != 'unconfigured':
        assert lifecycle.change('configure')
    if state.startswith('active'):
        assert lifecycle.change('activate')
    if state == 'active_streaming':
        commands = listen(client, JointState, '/joint_commands')
        target = client.node.create_publisher(Pose, '/target_pose', CLIENT_DEPTH)
        client.wait(lambda: target.get_subscription_count() >= 1, 'target_pose matched',
                    [node])
        client.spin_for(0.3)
        target.publish(pose_message(HOME + [0.0, 0.0, 0.03, 0.0, 0.0, 0.0]))
        client.wait(lambda: commands and np.abs(commands[-1].velocity).max() > 0.0,
                    'the stream moving', [node])
    assert stop_cleanly(node)


def test_unmanaged_nodes_have_no_lifecycle_interface(client, start_node, config_directory):
    """Without managed (ros2 run): no lifecycle service or event; it answers at once."""
    node = start_node('ik_node', config_args(config_directory, managed=False))
    lengths = listen(client, Float64MultiArray, '/leg_lengths')
    target = client.node.create_publisher(Pose, '/target_pose', CLIENT_DEPTH)
    client.wait(lambda: target.get_subscription_count() >= 1, 'target_pose matched', [node])
    client.spin_for(0.5)
    target.publish(pose_message(HOME))
    client.wait(lambda: lengths, 'leg_lengths', [node])
    # By the node's own graph entries (another test's managed ik_node may linger in discovery).
    services = {name for name, _ in client.node.get_service_names_and_types_by_node(
        'ik_node', '/')}
    topics = {name for name, _ in client.node.get_publisher_names_and_types_by_node(
        'ik_node', '/')}
    assert '/ik_node/set_parameters' in services and '/leg_lengths' in topics
    assert not {name for name in services if name.endswith('_state') or 'transition' in name}
    assert '/ik_node/transition_event' not in topics
    assert stop_cleanly(node)


@pytest.mark.parametrize('autostart', [True, False])
def test_stewart_platform_managed_with_and_without_autostart(
        client, start_node, config_directory, autostart):
    """
    Run three managed nodes in one process, with and without --autostart.

    --autostart true brings each to active (a pose is answered through ik_node and fk_node);
    without it each waits, unconfigured. Shutting the three down ends the process.
    """
    node = start_node('stewart_platform', [
        '--play-ramp', 'true', '--autostart', str(autostart).lower(),
        *config_args(config_directory, '--params-file', str(config_directory / 'solver.yaml'),
                     '--params-file', str(config_directory / 'table3_ramp.yaml'),
                     '-p', "mode:='off'")])
    names = ('ik_node', 'fk_node', 'trajectory_node')
    lifecycles = {name: Lifecycle(client, name, [node]) for name in names}
    expected = 'active' if autostart else 'unconfigured'
    assert {name: lifecycle.state() for name, lifecycle in lifecycles.items()} == {
        name: expected for name in names}
    if autostart:
        poses = listen(client, Pose, '/estimated_pose')
        target = client.node.create_publisher(Pose, '/target_pose', CLIENT_DEPTH)
        client.wait(lambda: target.get_subscription_count() >= 1, 'target_pose matched',
                    [node])
        client.spin_for(0.5)
        target.publish(pose_message(HOME))
        client.wait(lambda: poses, 'estimated_pose through both nodes', [node])
    else:   # nothing built: not even the subscriptions
        client.spin_for(QUIET_TIME)
        assert client.node.count_subscribers('/target_pose') == 0
    for name in names:
        assert lifecycles[name].change('shutdown'), name
    client.wait(lambda: not node.running(), 'the process ends with its nodes finalized', [])
    assert stop_cleanly(node)
