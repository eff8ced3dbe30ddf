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
The stand-in control_msgs has Jazzy's type hashes, so that a real MoveIt or rqt client talks to it.

Since Iron, ROS 2 matches publishers, subscriptions, services and actions by type name *and*
RIHS01 type hash (REP 2011): a definition that differs from Jazzy's control_msgs in one field
would build and run here, yet a MoveIt on a ROS installation would never see our action. The
stand-in (test/resources/control_msgs/, built by scripts/build_interfaces.sh) copies the jazzy
branch's three definition files unchanged; the hashes below are those of that definition
(control_msgs 5.x: FollowJointTrajectory, JointTolerance and JointComponentTolerance are the
same in every Jazzy release from 5.0.0 to 5.8.0), pinned here so that any change to a file, or
to how it is generated, fails.

The same rosidl generators in this venv give the hashes that are published for Jazzy's own
types (std_msgs/String, sensor_msgs/Range, rosgraph_msgs/Clock, as ROS tools print them), so the
pipeline that computed the pinned values is Jazzy's.
"""

import json
from pathlib import Path
import sys

import pytest

pytestmark = pytest.mark.node

#: Jazzy's RIHS01 hashes of control_msgs' FollowJointTrajectory and the types it is made of.
JAZZY_CONTROL_MSGS = {
    'control_msgs/action/FollowJointTrajectory':
        'RIHS01_738ebcb7a2d7cfa42f9f1001cc99ce3a4383d1cfe508015d9be8485e4b1c66f6',
    'control_msgs/action/FollowJointTrajectory_Goal':
        'RIHS01_8a9060704b269608f5a340934cc26e66869dd14bdac29e2e7fd9ec8b9882d205',
    'control_msgs/action/FollowJointTrajectory_Result':
        'RIHS01_8002e99ed2c14c6faa522f2a93c26d744c5982f254f9e98ff9c6f19789bdb220',
    'control_msgs/action/FollowJointTrajectory_Feedback':
        'RIHS01_3fd0aaecf71725121ae1ff7f01098a5e0da581e672be18a6b2c286cb43d96b49',
    'control_msgs/action/FollowJointTrajectory_FeedbackMessage':
        'RIHS01_80398fcb9674a79081a9906e2ccf0c804dd7cb15e22e362e606ee87186beab71',
    'control_msgs/action/FollowJointTrajectory_SendGoal':
        'RIHS01_b13789dddc325a7a962825c45e28c77d37237ec129dd0c34dc5994562938c57f',
    'control_msgs/action/FollowJointTrajectory_GetResult':
        'RIHS01_e3ceb38e3e1867c8dc0f46014df26e90eb93422f27e9e97f936e07f94be4bc8b',
    'control_msgs/msg/JointTolerance':
        'RIHS01_c254f9cece0f3b733017b6990fd46d1326e25242d6b8844398c97d9a88e7d648',
    'control_msgs/msg/JointComponentTolerance':
        'RIHS01_739ea7566931944d33830fa10f1bf5e7a7fbdc3172bce7a7eaac642bd6e3ffa4',
}
#: Published RIHS01 hashes of Jazzy types that come with the ROS wheels.
PUBLISHED_JAZZY = {
    'std_msgs/msg/String':
        'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18',
    'sensor_msgs/msg/Range':
        'RIHS01_b42b62562e93cbfe9d42b82fe5994dfa3d63d7d5c90a317981703f7388adff3a',
    'rosgraph_msgs/msg/Clock':
        'RIHS01_692f7a66e93a3c83e71765d033b60349ba68023a8c689a79e48078bcb5c58564',
}


def installed_hashes(interface: str) -> dict:
    """Return the type hashes rosidl generated for ``interface`` (package/kind/Name)."""
    path = Path(sys.prefix) / 'share' / f'{interface}.json'
    with open(path, encoding='utf-8') as stream:
        return {entry['type_name']: entry['hash_string']
                for entry in json.load(stream)['type_hashes']}


def test_the_venvs_generators_give_the_published_jazzy_hashes():
    """The rosidl pipeline of this venv reproduces hashes published for Jazzy's types."""
    for type_name, expected in PUBLISHED_JAZZY.items():
        assert installed_hashes(type_name)[type_name] == expected, type_name


def test_the_stand_in_control_msgs_has_jazzys_hashes():
    """Every type of the action and its two tolerance messages hashes as in Jazzy."""
    hashes = installed_hashes('control_msgs/action/FollowJointTrajectory')
    hashes.update(installed_hashes('control_msgs/msg/JointTolerance'))
    hashes.update(installed_hashes('control_msgs/msg/JointComponentTolerance'))
    for type_name, expected in JAZZY_CONTROL_MSGS.items():
        assert hashes.get(type_name) == expected, type_name


def test_the_action_carries_jazzys_hash_on_the_wire(ros, spin_until):
    """An action server's feedback topic is announced with Jazzy's FeedbackMessage hash."""
    from control_msgs.action import FollowJointTrajectory
    from rclpy.action import ActionServer
    from rclpy.executors import SingleThreadedExecutor

    node = ros.create_node('hash_probe')
    server = ActionServer(node, FollowJointTrajectory, 'follow_joint_trajectory',
                          lambda goal: FollowJointTrajectory.Result())
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    topic = '/follow_joint_trajectory/_action/feedback'
    try:
        assert spin_until(executor, lambda: node.get_publishers_info_by_topic(topic), 5.0)
        (endpoint,) = node.get_publishers_info_by_topic(topic)
        assert endpoint.topic_type == 'control_msgs/action/FollowJointTrajectory_FeedbackMessage'
        assert str(endpoint.topic_type_hash) == JAZZY_CONTROL_MSGS[
            'control_msgs/action/FollowJointTrajectory_FeedbackMessage']
    finally:
        server.destroy()
        executor.shutdown()
        node.destroy_node()
