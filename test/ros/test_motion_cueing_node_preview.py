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
motion_cueing_node's ``vehicle_preview``: the drive to come, taken by the MPC, or refused.

A brake step told in advance on the topic (through the middleware) tilts the MPC's cue before
the braking begins; the same samples without it leave the cue level. Malformed previews are
refused with their reason, counted on the diagnostics, and the node goes on cueing.
"""

import math
from pathlib import Path

from geometry_msgs.msg import Twist
import numpy as np
import pytest
from rclpy.parameter import Parameter
from sensor_msgs.msg import Imu

from stewart_kinematics.cueing.mpc_cueing import TILT
from stewart_kinematics.cueing.scenarios import scenario
from stewart_kinematics.ros.message_conversions import duration_message
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
from stewart_kinematics.ros.node_main import create_executor
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = ['--params-file', str(CONFIG / 'paper_platform.yaml'),
         '--params-file', str(CONFIG / 'example_limits.yaml'),
         '--params-file', str(CONFIG / 'motion_cueing.yaml'),
         '--params-file', str(CONFIG / 'motion_cueing_preview.yaml')]
G = 9.80665
START_NS = 5_000_000_000
DEPTH = 10


def imu(stamp_ns, force, rate, frame_id=''):
    """sensor_msgs/msg/Imu of the vehicle's specific force and angular velocity."""
    message = Imu()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    message.header.frame_id = frame_id
    (message.linear_acceleration.x, message.linear_acceleration.y,
     message.linear_acceleration.z) = (float(value) for value in force)
    (message.angular_velocity.x, message.angular_velocity.y,
     message.angular_velocity.z) = (float(value) for value in rate)
    return message


def preview_message(stamp_ns, offsets, forces, rates, frame_id=''):
    """trajectory_msgs/msg/MultiDOFJointTrajectory: the drive to come, point by point."""
    message = MultiDOFJointTrajectory()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    message.header.frame_id = frame_id
    for offset, force, rate in zip(offsets, forces, rates):
        point = MultiDOFJointTrajectoryPoint()
        point.time_from_start = duration_message(float(offset))
        point.accelerations.append(_twist(linear=force))
        point.velocities.append(_twist(angular=rate))
        message.points.append(point)
    return message


def _twist(linear=(0.0, 0.0, 0.0), angular=(0.0, 0.0, 0.0)):
    """geometry_msgs/msg/Twist of a linear and an angular part."""
    twist = Twist()
    twist.linear.x, twist.linear.y, twist.linear.z = (float(value) for value in linear)
    twist.angular.x, twist.angular.y, twist.angular.z = (float(value) for value in angular)
    return twist


def make_node(*overrides):
    """Return a motion_cueing_node with the preview preset (and ``overrides``), sends recorded."""
    node = MotionCueingNode(cli_args=['--ros-args'] + FILES,
                            parameter_overrides=list(overrides))
    node.sent = []
    node.target_publisher._publisher.publish = node.sent.append
    return node


def cue_until_braking(node, told):
    """Cue the brake step up to its onset (told in advance or not); return the MPC's tilt."""
    drive = scenario('brake_step')
    stamps = START_NS + np.round(drive.times * 1e9).astype(np.int64)
    if told:
        node.on_preview(preview_message(int(stamps[0]), drive.times - drive.times[0],
                                        drive.specific_force, drive.angular_velocity))
    onset = int(np.flatnonzero(np.abs(drive.specific_force[:, 0]) > 0.05)[0])
    for k in range(onset + 1):
        node.on_imu(imu(int(stamps[k]), drive.specific_force[k], drive.angular_velocity[k]))
    braking_sign = np.sign(np.mean(drive.specific_force[onset:onset + 100, 0]))
    return node.cueing.washout.state[TILT].copy(), braking_sign, onset


def test_a_preview_on_the_topic_tilts_the_cue_before_the_braking(ros, spin_until):
    """
    The brake step, published on vehicle_preview through the middleware, reaches the MPC.

    At the braking's onset the MPC's pitch is beyond half a degree, of the sign that gives the
    braking's force (``f_x = -g pitch``); without the preview the same samples leave it level.
    """
    node = make_node()
    client = ros.create_node('preview_client')
    executor = create_executor()
    executor.add_node(node)
    executor.add_node(client)
    try:
        publisher = client.create_publisher(MultiDOFJointTrajectory, 'vehicle_preview', DEPTH)
        assert spin_until(executor, lambda: publisher.get_subscription_count() >= 1)
        drive = scenario('brake_step')
        publisher.publish(preview_message(START_NS, drive.times - drive.times[0],
                                          drive.specific_force, drive.angular_velocity))
        accounting = node.preview_accounting
        assert spin_until(executor, lambda: accounting.received == 1)
        assert accounting.rejected == 0 and accounting.published == 1
        tilt, braking_sign, onset = cue_until_braking(node, told=False)   # already told
        assert len(node.sent) == onset + 1
        assert -np.sign(tilt[1]) == braking_sign
        assert abs(tilt[1]) > math.radians(0.5)
    finally:
        executor.shutdown()
        node.destroy_node()
        client.destroy_node()
    untold = make_node()
    try:
        level, _, _ = cue_until_braking(untold, told=False)
        assert abs(level[1]) < math.radians(0.01)
    finally:
        untold.destroy_node()


def _point_without_acceleration():
    """Return a preview whose second point has no acceleration (no specific force)."""
    message = preview_message(START_NS, [0.0, 0.1], [[0.0, 0.0, G]] * 2, [[0.0] * 3] * 2)
    message.points[1].accelerations.clear()
    return message


def _malformed(stamp=False):
    """
    Return a preview whose header.stamp (``stamp``) or last time_from_start has 4e9 nanosec.

    Malformed: before, taken as 4 s later (rclpy does not check nanosec), silently.
    """
    message = preview_message(START_NS, [0.0, 0.1], [[0.0, 0.0, G]] * 2, [[0.0] * 3] * 2)
    (message.header.stamp if stamp else message.points[1].time_from_start).nanosec = 4 * 10 ** 9
    return message


@pytest.mark.parametrize('make, words', [
    (_malformed, "preview point 1's time_from_start is malformed: nanosec 4000000000"),
    (lambda: _malformed(stamp=True), 'header.stamp is malformed: nanosec 4000000000'),
    (_point_without_acceleration, 'preview point 1 must have one acceleration'),
    (lambda: preview_message(START_NS, [0.0, 0.1], [[0.0, 0.0, G], [math.nan, 0.0, G]],
                             [[0.0] * 3] * 2), 'must be finite: sample 1'),
    (lambda: preview_message(START_NS, [0.0, 0.1], [[0.0, 0.0, G], [1e308, 0.0, G]],
                             [[0.0] * 3] * 2), 'absurd'),
    (lambda: preview_message(START_NS, [0.1, 0.1], [[0.0, 0.0, G]] * 2, [[0.0] * 3] * 2),
     'must increase'),
    # It said 'preview times must have shape (M,) with M >= 1, got (0,)'.
    (lambda: preview_message(START_NS, [], [], []), 'the preview has no points'),
    (lambda: preview_message(START_NS, [0.0], [[0.0, 0.0, G]], [[0.0] * 3], 'camera'),
     "frame 'camera'"),
])
def test_bad_previews_are_refused_with_the_reason_and_cueing_goes_on(ros, make, words):
    """Each is refused (invalid_preview, its reason logged and counted); samples still cue."""
    node = make_node()
    try:
        node.on_preview(make())
        accounting = node.preview_accounting
        assert accounting.rejections_by_code == {'invalid_preview': 1}
        assert words in accounting.last_rejection.message
        assert node.cueing.input_preview is None
        for k in range(3):
            node.on_imu(imu(START_NS + k * 10_000_000, (0.5, 0.0, G), (0.0, 0.0, 0.0)))
        assert len(node.sent) == 3
        assert node.accounting.rejected == 0
    finally:
        node.destroy_node()


def test_a_preview_to_the_classical_washout_is_refused_saying_why(ros):
    """The classical washout has no horizon: the preview is refused, naming cueing_method."""
    node = make_node(Parameter('cueing_method', value='classical'))
    try:
        node.on_preview(preview_message(START_NS, [0.0], [[0.0, 0.0, G]], [[0.0] * 3]))
        rejection = node.preview_accounting.last_rejection
        assert rejection.code == 'invalid_preview'
        assert 'needs cueing_method mpc' in rejection.message
    finally:
        node.destroy_node()


def test_a_preview_stamped_before_the_samples_is_refused_and_counted(ros):
    """
    A preview left unstamped (0) while vehicle_imu is at 5 s has nothing to come: refused.

    It was counted as used and did nothing. Each preview counts once: received = used +
    refused; the samples keep being cued.
    """
    node = make_node()
    try:
        for k in range(3):
            node.on_imu(imu(START_NS + k * 10_000_000, (0.0, 0.0, G), (0.0, 0.0, 0.0)))
        node.on_preview(preview_message(0, [0.0, 0.5], [[0.0, 0.0, G]] * 2, [[0.0] * 3] * 2))
        accounting = node.preview_accounting
        assert accounting.rejections_by_code == {'invalid_preview': 1}
        assert 'not after the last sample' in accounting.last_rejection.message
        node.on_preview(preview_message(START_NS, [0.0, 0.5], [[0.0, 0.0, G]] * 2,
                                        [[0.0] * 3] * 2))
        assert (accounting.received, accounting.published, accounting.rejected) == (2, 1, 1)
        node.on_imu(imu(START_NS + 30_000_000, (0.0, 0.0, G), (0.0, 0.0, 0.0)))
        assert len(node.sent) == 4
    finally:
        node.destroy_node()
