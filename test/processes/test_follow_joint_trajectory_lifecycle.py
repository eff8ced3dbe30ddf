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
follow_joint_trajectory on a managed trajectory_node: goals only while active.

Inactive, a goal is rejected (as joint_trajectory_controller rejects one); a goal running when
the node is deactivated is aborted with the controller's words, and its streamed commands
brake to rest within the leg acceleration limit; after cleanup and a new configure the action
answers again.
"""

from action_msgs.msg import GoalStatus
from control_msgs.action import FollowJointTrajectory
from helpers import SpinningClient
import numpy as np
import pytest
from stewart_kinematics.ros.node_main import create_executor
from test_follow_joint_trajectory import (
    ACCELERATION_MAX,
    goal,
    HOME,
    LEGS,
    legs_of,
    MoveItLikeClient,
    Platform,
)
from test_lifecycle_processes import Lifecycle

pytestmark = pytest.mark.process

Result = FollowJointTrajectory.Result


@pytest.fixture
def client(ros):
    """Spin a client node in its own thread on the single-threaded executor (actions)."""
    client = SpinningClient(ros.create_node('stewart_lifecycle_action_client'),
                            create_executor('single_threaded'), 100)
    yield client
    client.close()


def test_goals_only_while_active_and_deactivate_brakes(client, start_node, config_directory):
    """Rejected inactive; aborted and braked on deactivate; answered again after cleanup."""
    node = start_node('trajectory_node', [
        '--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
        '--params-file', str(config_directory / 'example_limits.yaml'), '-p', 'managed:=true',
        '-p', "mode:='off'", '-p', 'publish_rate:=100.0', '-p', "action_execution:='stream'"])
    lifecycle = Lifecycle(client, 'trajectory_node', [node])
    platform = Platform(client, legs_of(HOME))
    assert lifecycle.change('configure')
    action = MoveItLikeClient(client, [node])
    client.wait(lambda: platform.publisher.get_subscription_count() >= 1,
                'joint_states matched', [node])
    future = action.action.send_goal_async(goal(LEGS, [1.0], [legs_of(HOME)]))
    client.wait(future.done, 'goal response', [node])
    assert not future.result().accepted

    assert lifecycle.change('activate')
    client.settle()
    far = HOME + [0.0, 0.0, 0.04, 0.0, 0.0, 0.0]
    handle = action.send(goal(LEGS, [2.0], [legs_of(far)]))
    client.wait(lambda: len(platform.commands) > 0
                and np.abs(platform.commands[-1][2]).max() > 0.01, 'moving', [node])
    assert lifecycle.change('deactivate')
    status, code, text = action.result(handle)
    assert (status, code) == (GoalStatus.STATUS_ABORTED, Result.INVALID_GOAL)
    assert text == 'Current goal cancelled during deactivate transition.'
    # Until the braking reached rest (a fixed 0.5 s could end before it on a loaded machine).
    client.wait(lambda: np.abs(platform.commands[-1][2]).max() <= 1e-9, 'the legs braked to rest',
                [node])
    times = np.array([command[0] for command in platform.commands])
    positions = np.array([command[1] for command in platform.commands])
    carried = np.array([command[2] for command in platform.commands])
    intervals = np.diff(times)[:, None]
    velocities = np.diff(positions, axis=0) / intervals
    accelerations = np.diff(velocities, axis=0) / (0.5 * (intervals[1:] + intervals[:-1]))
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-6)
    np.testing.assert_allclose(carried[-1], 0.0, atol=1e-9)

    assert lifecycle.change('cleanup') and lifecycle.change('configure')
    assert lifecycle.change('activate')
    client.settle()
    status, code, text = action.run(goal(LEGS, [2.0], [legs_of(HOME)]))
    assert (status, code) == (GoalStatus.STATUS_SUCCEEDED, Result.SUCCESSFUL), text
    assert node.running()
