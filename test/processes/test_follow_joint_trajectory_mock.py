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
biased sensor breaks the goal tolerance. The client is the MoveIt-like one of
test_follow_joint_trajectory.py.
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
