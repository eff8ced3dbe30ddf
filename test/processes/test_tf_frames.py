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
TF and the user and tool frames across processes: what fk_node and ik_node broadcast and accept.

ik_node and fk_node run as console-script processes with a user frame (a work piece beside the
base, turned 90 degrees) and a tool frame (a tool centre point above the platform, tilted). The
test's node reads ``/tf`` and ``/tf_static`` (tf2_msgs/msg/TFMessage: the stand-in built into
the venv, or a ROS installation's), sends poses of the tool frame in the user frame, changes the
tool frame at run time through the parameter service, and checks every number against frames
composed here with 4x4 matrices.
"""

import math
import os

from builtin_interfaces.msg import Time
from geometry_msgs.msg import Pose, PoseStamped
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import SetParameters
from rclpy.qos import DurabilityPolicy, QoSProfile
from reference import (
    leg_lengths,
    quaternion_from_euler,
    quaternion_matrix,
    rotation_zyx,
    TABLE_3,
)
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Header
from tf2_msgs.msg import TFMessage

pytestmark = pytest.mark.process

#: The frames of the test, as parameters: metres and degrees.
FRAMES = """\
/**:
  ros__parameters:
    user_frame: 'work'
    user_frame_position: [0.5, -0.2, 0.05]
    user_frame_orientation_deg: [0.0, 0.0, 90.0]
    tool_frame: 'tcp'
    tool_frame_position: [0.02, -0.01, 0.1]
    tool_frame_orientation_deg: [5.0, -10.0, 15.0]
"""
USER = (0.5, -0.2, 0.05, 0.0, 0.0, math.radians(90.0))
TOOL = (0.02, -0.01, 0.1, math.radians(5.0), math.radians(-10.0), math.radians(15.0))
STAMP = Time(sec=42, nanosec=7)
SETTLE_TIME = 0.5


def matrix(pose):
    """4x4 homogeneous matrix of ``[X, Y, Z, alpha, beta, gamma]``."""
    result = np.eye(4)
    result[:3, :3] = rotation_zyx(*pose[3:])
    result[:3, 3] = pose[:3]
    return result


def message_matrix(translation, rotation):
    """4x4 matrix of a message's translation (x, y, z) and quaternion (x, y, z, w)."""
    result = np.eye(4)
    result[:3, :3] = quaternion_matrix(rotation.x, rotation.y, rotation.z, rotation.w)
    result[:3, 3] = [translation.x, translation.y, translation.z]
    return result


def pose_of(homogeneous):
    """geometry_msgs/msg/Pose of a 4x4 matrix (via Euler angles ZYX)."""
    rotation = homogeneous[:3, :3]
    beta = -math.asin(rotation[2, 0])
    alpha = math.atan2(rotation[2, 1], rotation[2, 2])
    gamma = math.atan2(rotation[1, 0], rotation[0, 0])
    message = Pose()
    message.position.x, message.position.y, message.position.z = homogeneous[:3, 3].tolist()
    o = message.orientation
    o.x, o.y, o.z, o.w = quaternion_from_euler(alpha, beta, gamma)
    return message


def euler_of(homogeneous):
    """``[X, Y, Z, alpha, beta, gamma]`` of a 4x4 matrix."""
    rotation = homogeneous[:3, :3]
    return np.array([*homogeneous[:3, 3], math.atan2(rotation[2, 1], rotation[2, 2]),
                     -math.asin(rotation[2, 0]), math.atan2(rotation[1, 0], rotation[0, 0])])


def transforms(messages):
    """Every TransformStamped received, by (parent, child), the latest last."""
    found = {}
    for message in messages:
        for transform in message.transforms:
            found[(transform.header.frame_id, transform.child_frame_id)] = transform
    return found


@pytest.fixture
def frames_file(tmp_path):
    """Write the frames' parameter file; return its path."""
    path = tmp_path / 'frames.yaml'
    path.write_text(FRAMES)
    return path


def test_fk_node_broadcasts_the_platform_and_the_frames(
        client, start_node, config_directory, frames_file):
    """/tf: base -> platform with the stamp of the lengths; /tf_static: user and tool frames."""
    node = start_node('fk_node', [
        '--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
        '--params-file', str(frames_file), '-p', 'estimated_pose_frame:=work'])
    tf, tf_static, stamped, plain = [], [], [], []
    client.node.create_subscription(TFMessage, '/tf', tf.append, 100)
    client.node.create_subscription(PoseStamped, 'estimated_pose_stamped', stamped.append, 10)
    client.node.create_subscription(Pose, 'estimated_pose', plain.append, 10)
    publisher = client.node.create_publisher(JointState, 'joint_states', 10)
    client.wait(lambda: publisher.get_subscription_count() >= 1, 'fk_node subscribed', [node])
    # Transient local: a late subscriber still gets the static frames.
    client.node.create_subscription(
        TFMessage, '/tf_static', tf_static.append,
        QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
    client.wait(lambda: len(transforms(tf_static)) == 2, 'both static frames', [node])
    client.wait(lambda: client.node.count_publishers('/tf') >= 1
                and client.node.count_publishers('estimated_pose_stamped') >= 1,
                'fk_node publishes /tf', [node])
    client.spin_for(SETTLE_TIME)

    platform = TABLE_3[4]
    publisher.publish(JointState(header=Header(stamp=STAMP),
                                 name=[f'leg_{leg}' for leg in range(1, 7)],
                                 position=leg_lengths(platform)))
    client.wait(lambda: tf and stamped and plain, '/tf and both estimated poses', [node])

    statics = transforms(tf_static)
    user = statics[('stewart_base', 'work')].transform
    tool = statics[('stewart_platform', 'tcp')].transform
    assert_allclose(message_matrix(user.translation, user.rotation), matrix(USER), atol=1e-12)
    assert_allclose(message_matrix(tool.translation, tool.rotation), matrix(TOOL), atol=1e-12)

    [(key, broadcast)] = transforms(tf).items()
    assert key == ('stewart_base', 'stewart_platform')
    assert (broadcast.header.stamp.sec, broadcast.header.stamp.nanosec) == (42, 7)
    assert_allclose(message_matrix(broadcast.transform.translation, broadcast.transform.rotation),
                    matrix(platform), rtol=0, atol=1e-9)

    tool_in_base = matrix(platform) @ matrix(TOOL)
    assert stamped[0].header.frame_id == 'work'
    assert (stamped[0].header.stamp.sec, stamped[0].header.stamp.nanosec) == (42, 7)
    assert_allclose(message_matrix(stamped[0].pose.position, stamped[0].pose.orientation),
                    np.linalg.inv(matrix(USER)) @ tool_in_base, rtol=0, atol=1e-9)
    assert_allclose(message_matrix(plain[0].position, plain[0].orientation), tool_in_base,
                    rtol=0, atol=1e-9)


def set_parameter(client, node_name, name, values, processes):
    """Set a double array parameter through the node's service; return the result."""
    service = client.node.create_client(SetParameters, f'/{node_name}/set_parameters')
    client.wait(service.service_is_ready, f'{node_name} parameter service', processes)
    future = service.call_async(SetParameters.Request(parameters=[Parameter(
        name=name, value=ParameterValue(type=ParameterType.PARAMETER_DOUBLE_ARRAY,
                                        double_array_value=values))]))
    client.wait(future.done, f'set {name}', processes)
    return future.result().results[0]


def test_ik_node_takes_tool_poses_in_the_user_frame_and_a_new_tool_at_run_time(
        client, start_node, config_directory, frames_file):
    """A tool pose in the user frame commands its platform pose; a new tool applies next."""
    node = start_node('ik_node', [
        '--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
        '--params-file', str(frames_file), '-p', 'publish_commanded_tf:=true'])
    lengths, tf = [], []
    client.node.create_subscription(Float64MultiArray, 'leg_lengths', lengths.append, 10)
    client.node.create_subscription(TFMessage, '/tf', tf.append, 100)
    publisher = client.node.create_publisher(PoseStamped, 'target_pose_stamped', 10)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and client.node.count_publishers('/tf') >= 1
                and client.node.count_publishers('leg_lengths') >= 1, 'ik_node matched', [node])
    client.spin_for(SETTLE_TIME)

    platform = matrix(TABLE_3[6])
    # The tool pose in the user frame that puts the platform at Table 3's row 6.
    target = np.linalg.inv(matrix(USER)) @ platform @ matrix(TOOL)
    message = PoseStamped(header=Header(stamp=STAMP, frame_id='work'), pose=pose_of(target))
    publisher.publish(message)
    client.wait(lambda: lengths and tf, 'lengths and the commanded frame', [node])
    assert_allclose(lengths[0].data, leg_lengths(euler_of(platform)), rtol=0, atol=1e-9)
    [(key, commanded)] = transforms(tf).items()
    assert key == ('stewart_base', 'stewart_platform_commanded')
    assert (commanded.header.stamp.sec, commanded.header.stamp.nanosec) == (42, 7)
    assert_allclose(message_matrix(commanded.transform.translation, commanded.transform.rotation),
                    platform, rtol=0, atol=1e-9)

    # The tool frame moves to the platform frame's origin: the same target now places the
    # platform frame itself (orientation of the tool kept).
    result = set_parameter(client, 'ik_node', 'tool_frame_position', [0.0, 0.0, 0.0], [node])
    assert result.successful, result.reason
    publisher.publish(message)
    client.wait(lambda: len(lengths) == 2, 'lengths with the new tool frame', [node])
    tool = matrix(TOOL)
    tool[:3, 3] = 0.0
    moved = matrix(USER) @ target @ np.linalg.inv(tool)
    assert_allclose(lengths[1].data, leg_lengths(euler_of(moved)), rtol=0, atol=1e-9)

    refused = set_parameter(client, 'ik_node', 'tool_frame_position', [0.0, 0.0], [node])
    assert not refused.successful
    assert 'tool_frame_position' in refused.reason and '3' in refused.reason


def test_without_tf2_msgs_fk_node_says_so_and_works_on(
        client, start_node, config_directory, tmp_path):
    """With tf2_msgs unimportable, fk_node logs why there is no /tf and still estimates."""
    hidden = tmp_path / 'hide_tf2_msgs' / 'tf2_msgs'
    hidden.mkdir(parents=True)
    (hidden / '__init__.py').write_text("raise ImportError('tf2_msgs hidden by the test')\n")
    env = dict(os.environ, PYTHONPATH=str(hidden.parent))
    node = start_node('fk_node', ['--ros-args', '--params-file',
                                  str(config_directory / 'paper_platform.yaml')], env=env)
    estimates = []
    client.node.create_subscription(Pose, 'estimated_pose', estimates.append, 10)
    publisher = client.node.create_publisher(Float64MultiArray, 'leg_lengths', 10)
    client.wait(lambda: publisher.get_subscription_count() >= 1, 'fk_node subscribed', [node])
    client.spin_for(SETTLE_TIME)
    client.wait(lambda: estimates or publisher.publish(
        Float64MultiArray(data=leg_lengths(TABLE_3[0]))), 'an estimated pose', [node])
    assert 'tf2_msgs is not installed, so nothing is broadcast on /tf' in node.output()
    assert client.node.count_publishers('/tf') == 0
