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
motion_cueing_node and ik_node as processes: a stream of sensor_msgs/Imu in, leg lengths out.

The test client plays a drive (a sustained push, a turn, a multi-sine) on ``vehicle_imu`` at
200 Hz; motion_cueing_node's ``target_pose`` goes to a real ik_node, whose ``leg_lengths`` the
client collects: every length within the example limits' stroke, equal to the lengths of the
cue's pose by the textbook formula, and ik_node refuses nothing. Then bad input, over the wire,
is refused and counted on /diagnostics, and the reset service answers.
"""

import math

from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Pose
import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import leg_lengths_of_matrix, quaternion_matrix
from sensor_msgs.msg import Imu, JointState
from std_msgs.msg import Float64MultiArray
from std_srvs.srv import Trigger

pytestmark = pytest.mark.process

G = 9.80665
DEPTH = 100
RATE = 200.0
#: Samples published before waiting for their answers, within the queues of depth 100.
BATCH = 40
#: example_limits.yaml's leg velocity and acceleration limits.
VELOCITY_MAX, ACCELERATION_MAX = 0.05, 0.25


def imu(stamp_ns, force, rate=(0.0, 0.0, 0.0)):
    """sensor_msgs/msg/Imu with a stamp in nanoseconds."""
    message = Imu()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    (message.linear_acceleration.x, message.linear_acceleration.y,
     message.linear_acceleration.z) = force
    message.angular_velocity.x, message.angular_velocity.y, message.angular_velocity.z = rate
    return message


def drive(seconds=8.0):
    """Return a push forward, a left turn with yaw rate, a 1 Hz and 2 Hz sine, then rest."""
    messages = []
    for k in range(int(seconds * RATE)):
        t = k / RATE
        force = [0.0, 0.0, G]
        rate = [0.0, 0.0, 0.0]
        if 0.5 <= t < 3.0:
            force[0] = 3.0
        if 2.0 <= t < 5.0:
            force[1], rate[2] = 4.0, 0.25
        if 5.0 <= t < 7.0:
            force[0] += 0.8 * math.sin(2.0 * math.pi * t) + 0.5 * math.sin(4.0 * math.pi * t)
        messages.append(imu(1_000_000_000 + k * 5_000_000, force, rate))
    return messages


def expected_leg_lengths(message):
    """|t + R p_i - b_i| of a Pose message, leg by leg, from the paper's tables."""
    o = message.orientation
    position = np.array([message.position.x, message.position.y, message.position.z])
    return leg_lengths_of_matrix(position, quaternion_matrix(o.x, o.y, o.z, o.w)).tolist()


def test_cue_drives_ik_node_within_the_stroke(client, start_node, config_directory):
    """Every leg length ik_node publishes for the cue is within [0.65, 0.90] m, none refused."""
    files = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
             '--params-file', str(config_directory / 'example_limits.yaml')]
    cueing = start_node('motion_cueing_node', files + [
        '--params-file', str(config_directory / 'motion_cueing.yaml')])
    ik = start_node('ik_node', files + ['-p', f'queue_depth:={DEPTH}'])
    targets, lengths, reports = [], [], []
    node = client.node
    node.create_subscription(Pose, 'target_pose', targets.append, DEPTH)
    node.create_subscription(Float64MultiArray, 'leg_lengths', lengths.append, DEPTH)
    node.create_subscription(DiagnosticArray, '/diagnostics', reports.append, DEPTH)
    publisher = node.create_publisher(Imu, 'vehicle_imu', DEPTH)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and node.count_publishers('target_pose') >= 1
                and node.count_subscribers('target_pose') >= 2
                and node.count_publishers('leg_lengths') >= 1,
                'motion_cueing_node and ik_node connected', [cueing, ik])
    client.spin_for(0.5)

    messages = drive()
    for first in range(0, len(messages), BATCH):
        batch = messages[first:first + BATCH]
        for message in batch:
            publisher.publish(message)
        wanted = first + len(batch)
        client.wait(lambda: len(lengths) >= wanted and len(targets) >= wanted,
                    f'{wanted} target poses and leg lengths', [cueing, ik])

    assert len(targets) == len(lengths) == len(messages)
    data = np.array([message.data for message in lengths])
    assert data.min() >= 0.65 and data.max() <= 0.90
    moved = 0.0
    for target, measured in zip(targets, data):
        assert_allclose(measured, expected_leg_lengths(target), atol=1e-9)
        moved = max(moved, abs(target.position.x), abs(target.position.y))
    assert moved > 0.02  # the cue did move the platform
    # The leg rates are those of the times the commands were sent (the node's clock), which
    # this burst does not show: they are checked exactly on a simulated clock driven in
    # lockstep (test/ros/test_motion_cueing_node.py) and by the core
    # (test/cueing/test_cueing_commands.py). Here:
    # the gate passed every command as the follower gave it (no braking, no refusal).

    def rejected(code):
        return any(value.key == f'rejected {code}' for report in reports
                   for status in report.status if status.name.endswith('vehicle_imu')
                   for value in status.values)
    client.spin_for(1.5)   # one more report
    assert not rejected('command_braking') and not rejected('too_fast')

    # Bad input over the wire: refused with the reason on /diagnostics; reset answers.
    for index, force in enumerate(((math.nan, 0.0, G), (0.0, 1e308, G))):
        publisher.publish(imu(1_000_000_000 + (len(messages) + index) * 5_000_000, force))

    def refused():
        return any(value.key == 'rejected invalid_vehicle_motion' and value.value == '2'
                   for report in reports for status in report.status
                   if status.name.endswith('vehicle_imu') for value in status.values)
    client.wait(refused, '2 refusals of vehicle_imu on /diagnostics', [cueing, ik])
    service = node.create_client(Trigger, 'reset')
    client.wait(service.service_is_ready, 'the reset service', [cueing])
    future = service.call_async(Trigger.Request())
    client.wait(future.done, 'the reset answer', [cueing])
    assert future.result().success
    for process in (cueing, ik):
        assert process.stop() == 0, process.output()
        assert 'Traceback' not in process.output()


def test_the_chain_as_launched_keeps_the_leg_rates_at_the_stamps_of_joint_commands(
        client, start_node, config_directory):
    """
    The how-to's chain, a drive at the leg limits played in real time at 100 Hz.

    motion_cueing_node keeps the leg rates at the times it sends each pose; the transport
    delivers them unevenly (8 ms for a step checked over 10 ms: 0.06 m/s by ik_node's clock,
    measured). ik_node streaming at ``command_rate`` (as motion_cueing.launch.py starts it)
    keeps them at the stamps of ``joint_commands``, what the drives get.
    """
    files = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
             '--params-file', str(config_directory / 'example_limits.yaml')]
    cueing = start_node('motion_cueing_node', files + [
        '--params-file', str(config_directory / 'cueing_presets' / 'car.yaml')])
    ik = start_node('ik_node', files + ['-p', 'command_rate:=100.0'])
    commands = []
    node = client.node
    node.create_subscription(JointState, 'joint_commands', commands.append, 1000)
    publisher = node.create_publisher(Imu, 'vehicle_imu', DEPTH)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and node.count_subscribers('target_pose') >= 1
                and node.count_publishers('joint_commands') >= 1,
                'the chain connected', [cueing, ik])
    client.spin_for(0.5)
    # Full pushes that change sign every second or so: the cue at the leg limits.
    origin = node.get_clock().now().nanoseconds
    for k in range(500):
        t = k / 100.0
        force = [6.0 * math.copysign(1.0, math.sin(1.5 * t)),
                 5.0 * math.copysign(1.0, math.cos(1.1 * t)), G]
        publisher.publish(imu(origin + k * 10_000_000, force))
        client.spin_for(0.01)
    client.wait(lambda: len(commands) > 300, 'the stream of joint_commands', [cueing, ik])
    stamps = np.array([m.header.stamp.sec * 1_000_000_000 + m.header.stamp.nanosec
                       for m in commands]) * 1e-9
    positions = np.array([m.position for m in commands])
    assert np.all(np.diff(stamps) > 0.0)
    velocity = np.diff(positions, axis=0) / np.diff(stamps)[:, None]
    acceleration = np.diff(velocity, axis=0) / (0.5 * (stamps[2:] - stamps[:-2]))[:, None]
    assert np.abs(velocity).max() > 0.5 * VELOCITY_MAX   # a drive at the limits
    assert np.abs(velocity).max() <= VELOCITY_MAX * (1.0 + 1e-6)
    assert np.abs(acceleration).max() <= ACCELERATION_MAX * (1.0 + 1e-6)
