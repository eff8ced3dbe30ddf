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
motion_cueing_node with ``cueing_method: mpc``: a slalom cued, an intensity change taken.

Before, a cueing_intensity set at run time was refused with the MPC ("this washout takes no
gain change at run time"). The node's callbacks are called directly, as its executor would;
the limits are checked on the published poses by the limits model. About 3 s.
"""

from pathlib import Path

from geometry_msgs.msg import Pose
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.parameter import Parameter
from sensor_msgs.msg import Imu

from stewart_kinematics.cueing.limit_margins import pose_violations
from stewart_kinematics.cueing.mpc_cueing import MpcCueing
from stewart_kinematics.cueing.scenarios import scenario
from stewart_kinematics.model.rotations import quaternion_to_matrix
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = ['--params-file', str(CONFIG / 'paper_platform.yaml'),
         '--params-file', str(CONFIG / 'example_limits.yaml'),
         '--params-file', str(CONFIG / 'motion_cueing.yaml')]


def imu(stamp_ns, force, rate):
    """sensor_msgs/msg/Imu of the vehicle's specific force and angular velocity."""
    message = Imu()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    (message.linear_acceleration.x, message.linear_acceleration.y,
     message.linear_acceleration.z) = (float(value) for value in force)
    (message.angular_velocity.x, message.angular_velocity.y,
     message.angular_velocity.z) = (float(value) for value in rate)
    return message


@pytest.fixture
def node(ros):
    """Make a motion_cueing_node with the MPC, its target_pose messages recorded."""
    made = MotionCueingNode(cli_args=['--ros-args'] + FILES, parameter_overrides=[
        Parameter('cueing_method', value='mpc'), Parameter('gain_ramp_time', value=0.5)])
    made.sent = []
    made.target_publisher._publisher.publish = made.sent.append
    yield made
    made.destroy_node()


def pose_of(message: Pose):
    """Return a Pose's position (3,) and rotation matrix (3, 3)."""
    orientation = message.orientation
    return (np.array([message.position.x, message.position.y, message.position.z]),
            quaternion_to_matrix(np.array([orientation.x, orientation.y, orientation.z,
                                           orientation.w])))


def test_a_slalom_through_the_mpc_node_keeps_the_limits_and_takes_an_intensity(node):
    """3 s of slalom, cueing_intensity 0.4 set mid-way: finite poses within every limit."""
    assert isinstance(node.cueing.washout, MpcCueing)
    drive = scenario('slalom')
    settings = node.cueing.settings
    configured = np.concatenate([settings.mpc_force_scale, settings.rotation_scale[:2]])
    samples = 300
    for k in range(samples):
        if k == 150:
            [result] = node.set_parameters([Parameter('cueing_intensity', value=0.4)])
            assert result.successful, result.reason
        node.on_imu(imu(1_000_000_000 + int(round(drive.times[k] * 1e9)),
                        drive.specific_force[k], drive.angular_velocity[k]))
    assert len(node.sent) == samples
    geometry = node.cueing.geometry
    for message in node.sent:
        position, rotation = pose_of(message)
        assert np.all(np.isfinite(position)) and np.all(np.isfinite(rotation))
        assert pose_violations(geometry, position, rotation) == []
    # The slalom moved the platform, and the intensity reached the MPC's aim after the ramp.
    positions = np.array([pose_of(message)[0] for message in node.sent])
    assert np.ptp(positions[:, 1]) > 1e-3
    assert node.cueing.controls.cueing_intensity == 0.4
    assert_allclose(node.cueing.washout.reference_scale, 0.4 * configured, rtol=1e-12)
