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
follow_joint_trajectory closed over mock_platform, both as processes: the whole stack.

mock_platform follows leg_trajectory (as joint_trajectory_controller would) or joint_commands
with its first-order lag and publishes joint_states; trajectory_node checks the goal against
them. A good goal succeeds, in either execution; a stalled leg breaks the path tolerance; a
biased sensor breaks the goal tolerance; the refusals have their codes; a new goal preempts;
a cancel brings the simulated legs to rest within their limits. The client is the MoveIt-like
one of test_follow_joint_trajectory.py.
"""

from action_msgs.msg import GoalStatus
from control_msgs.action import FollowJointTrajectory
from control_msgs.msg import JointTolerance
from helpers import SpinningClient
import numpy as np
import pytest
from sensor_msgs.msg import JointState
from stewart_kinematics.ros.node_main import create_executor
from test_follow_joint_trajectory import (
    CARTESIAN,
    duration,
    goal,
    HOME,
    LEGS,
    legs_of,
    MoveItLikeClient,
)
from trajectory_msgs.msg import JointTrajectory

pytestmark = pytest.mark.process

Result = FollowJointTrajectory.Result


@pytest.fixture
def client(ros):
    """Spin a client node in its own thread on the single-threaded executor (actions)."""
    client = SpinningClient(ros.create_node('stewart_mock_action_client'),
                            create_executor('single_threaded'), 100)
    yield client
    client.close()


def files(config_directory):
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'example_limits.yaml')]


@pytest.mark.parametrize('execution', ['leg_trajectory', 'stream'])
def test_closed_loop_over_mock_platform(client, start_node, config_directory, execution):
    """Succeeds over mock_platform; a stalled leg and a biased sensor give their codes."""
    mock = start_node('mock_platform', files(config_directory) + ['-p', 'time_constant:=0.02'])
    node = start_node('trajectory_node', files(config_directory) + [
        '-p', "mode:='off'", '-p', 'publish_rate:=100.0',
        '-p', f"action_execution:='{execution}'"])
    states = []
    client.subscribe(JointState, '/joint_states', states.append)
    action = MoveItLikeClient(client, [node, mock])
    client.wait(lambda: len(states) > 5, 'joint_states from mock_platform', [node, mock])
    # trajectory_node hears them too (the client's subscription and the node's).
    client.wait(lambda: client.node.count_subscribers('/joint_states') >= 2,
                'trajectory_node subscribed to joint_states', [node, mock])
    client.settle()
    target = HOME + [0.01, -0.01, 0.01, 0.0, 0.02, 0.0]
    status, code, text = action.run(goal(LEGS, [2.0], [legs_of(target)]))
    assert (status, code) == (GoalStatus.STATUS_SUCCEEDED, Result.SUCCESSFUL), text
    measured = np.array(states[-1].position)[[list(states[-1].name).index(n) for n in LEGS]]
    np.testing.assert_allclose(measured, legs_of(target), rtol=0, atol=0.002)
    status, code, text = action.run(goal(CARTESIAN, [2.0], [HOME]))
    assert (status, code) == (GoalStatus.STATUS_SUCCEEDED, Result.SUCCESSFUL), text

    _set(client, mock, 'stalled_legs', "'leg_3'")
    tight = [JointTolerance(name=name, position=0.004) for name in LEGS]
    status, code, text = action.run(goal(LEGS, [2.0], [legs_of(target)], path_tolerance=tight))
    assert (status, code) == (GoalStatus.STATUS_ABORTED, Result.PATH_TOLERANCE_VIOLATED), text
    assert 'leg_3 position error' in text
    _set(client, mock, 'stalled_legs', "''")
    _set(client, mock, 'position_bias', '[0.0, 0.0, 0.0, 0.0, 0.006, 0.0]')
    status, code, text = action.run(goal(LEGS, [2.0], [legs_of(HOME)],
                                         goal_time_tolerance=duration(0.5)))
    assert (status, code) == (GoalStatus.STATUS_ABORTED, Result.GOAL_TOLERANCE_VIOLATED), text
    assert 'leg_5 position error' in text
    assert node.running() and mock.running()


def test_refusals_preemption_and_cancel_over_mock_platform(client, start_node, config_directory):
    """
    The other codes, preemption and cancel, over mock_platform (goals sent on leg_trajectory).

    INVALID_JOINTS, INVALID_GOAL (a limit) and OLD_HEADER_TIMESTAMP leave the legs at rest; a
    new goal preempts the running one with JTC's words; a cancel ends the next CANCELED and the
    measured legs slow to rest within leg_velocity_max and leg_acceleration_max (0.05 m/s,
    0.25 m/s^2 in example_limits.yaml), no jump.
    """
    mock = start_node('mock_platform', files(config_directory) + ['-p', 'time_constant:=0.02'])
    node = start_node('trajectory_node', files(config_directory) + [
        '-p', "mode:='off'", '-p', 'publish_rate:=100.0'])
    states, sent = [], []
    client.subscribe(JointState, '/joint_states', states.append)
    client.subscribe(JointTrajectory, '/leg_trajectory', sent.append)
    action = MoveItLikeClient(client, [node, mock])
    client.wait(lambda: client.node.count_subscribers('/joint_states') >= 2,
                'trajectory_node subscribed to joint_states', [node, mock])
    client.wait(lambda: len(states) > 5, 'joint_states from mock_platform', [node, mock])
    client.settle()

    status, code, text = action.run(goal(LEGS[:5] + ['elbow'], [1.0], [legs_of(HOME)]))
    assert (status, code) == (GoalStatus.STATUS_ABORTED, Result.INVALID_JOINTS), text
    status, code, text = action.run(goal(LEGS, [30.0], [legs_of(HOME) + 0.3]))
    assert code == Result.INVALID_GOAL and 'leg_length_max' in text, text
    old = goal(LEGS, [1.0], [legs_of(HOME)])
    old.trajectory.header.stamp.sec = 1000
    status, code, text = action.run(old)
    assert code == Result.OLD_HEADER_TIMESTAMP, text
    assert np.abs(np.array(states[-1].velocity)).max() == 0.0   # nothing moved

    first = action.send(goal(LEGS, [4.0], [legs_of(HOME + [0.0, 0.0, 0.04, 0.0, 0.0, 0.0])]))
    client.wait(lambda: np.abs(states[-1].velocity).max() > 0.01, 'the legs moving',
                [node, mock])
    second = action.send(goal(LEGS, [3.0], [legs_of(HOME - [0.0, 0.0, 0.03, 0.0, 0.0, 0.0])]))
    status, code, text = action.result(first)
    assert (status, code, text) == (GoalStatus.STATUS_ABORTED, Result.INVALID_GOAL,
                                    'Current goal preempted by new incoming action.')
    client.wait(lambda: np.min(states[-1].velocity) < -0.01, 'the second goal moving',
                [node, mock])
    cancelled_at, trajectories = len(states), len(sent)
    future = second.cancel_goal_async()
    client.wait(future.done, 'cancel response', [node, mock])
    status, _, text = action.result(second)
    assert status == GoalStatus.STATUS_CANCELED, text
    client.wait(lambda: len(states) > cancelled_at + 10
                and np.abs(states[-1].velocity).max() == 0.0, 'the legs at rest',
                [node, mock], timeout=10.0)
    # From integer nanoseconds after the first: seconds since 1970 in a float lose 0.2 us.
    nanoseconds = [m.header.stamp.sec * 10**9 + m.header.stamp.nanosec for m in states]
    stamps = np.array([(value - nanoseconds[0]) * 1e-9 for value in nanoseconds])
    velocities = np.array([m.velocity for m in states])
    assert np.abs(velocities).max() <= 0.05 * (1 + 1e-9)
    accelerations = np.diff(velocities, axis=0) / np.diff(stamps)[:, None]
    assert np.abs(accelerations).max() <= 0.25 * (1 + 1e-6)
    # What trajectory_node sent on the cancel: a braking from the motion's speed, within the
    # limits, ending at rest; not a stop.
    assert len(sent) == trajectories + 1
    braking = sent[-1]
    times = np.array([point.time_from_start.sec + point.time_from_start.nanosec * 1e-9
                      for point in braking.points])
    rates = np.array([point.velocities for point in braking.points])
    # From the speed of the motion (over 0.01 m/s), no sooner than the limit allows.
    assert np.abs(rates[0]).max() > 0.01 and len(times) >= 3
    assert times[-1] >= np.abs(rates[0]).max() / 0.25 * (1 - 1e-9)
    assert np.abs(rates).max() <= 0.05 * (1 + 1e-9)
    assert np.abs(np.diff(rates, axis=0) / np.diff(times)[:, None]).max() <= 0.25 * (1 + 1e-6)
    np.testing.assert_allclose(rates[-1], 0.0, atol=1e-12)
    assert node.running() and mock.running()


def _set(client, mock, name, value):
    """Set a parameter of mock_platform through its parameter service, and wait for it."""
    from rcl_interfaces.srv import SetParameters
    from rclpy.parameter import Parameter
    import yaml
    service = client.node.create_client(SetParameters, '/mock_platform/set_parameters')
    assert service.wait_for_service(timeout_sec=10.0)
    request = SetParameters.Request(
        parameters=[Parameter(name, value=yaml.safe_load(value)).to_parameter_msg()])
    future = service.call_async(request)
    client.wait(future.done, f'set {name}', [mock])
    assert all(result.successful for result in future.result().results), future.result()
