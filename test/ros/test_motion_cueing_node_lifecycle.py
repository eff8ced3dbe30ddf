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
A managed motion_cueing_node starts from park on activate and stops to park on deactivate.

As the ``start`` and ``stop`` services do: activate moves the platform up from park over
``soft_start_time`` (stepped by the node's timer, cueing once it rests at neutral), deactivate
brakes it to rest and takes it down to park, and answers once it is parked. Before, activate
cued at once from home and deactivate only braked to rest where the platform was. Checked on
the ``target_pose`` messages the node publishes (legs from the paper's tables), against the
leg velocity and acceleration limits of example_limits.yaml, by divided differences over the
times the commands are sent. The node's callbacks are called directly, in real time. About 6 s.
"""

import math
from pathlib import Path
import time

import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.lifecycle import TransitionCallbackReturn
import reference
from sensor_msgs.msg import Imu

from stewart_kinematics.cueing.motion_cueing import CUEING, PARKED, STARTING
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
ARGUMENTS = ['--ros-args', '--params-file', str(CONFIG / 'paper_platform.yaml'),
             '--params-file', str(CONFIG / 'example_limits.yaml'),
             '--params-file', str(CONFIG / 'motion_cueing.yaml'),
             '-p', 'managed:=true', '-p', 'soft_start_time:=0.6', '-p', 'soft_stop_time:=0.6']
SUCCESS = TransitionCallbackReturn.SUCCESS
G = 9.80665
#: example_limits.yaml's leg limits, m/s and m/s^2.
VELOCITY_MAX, ACCELERATION_MAX = 0.05, 0.25
PERIOD = 0.02


def imu(stamp, force_x):
    """Return a vehicle_imu sample: a forward specific force, at rest otherwise (seconds)."""
    message = Imu()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(int(stamp * 1e9), 10 ** 9)
    message.linear_acceleration.x, message.linear_acceleration.z = force_x, G
    return message


def legs(message):
    """|t + R p_i - b_i| of a Pose message, leg by leg, from the paper's tables."""
    p, o = message.position, message.orientation
    return np.array(reference.leg_lengths_of_matrix(
        [p.x, p.y, p.z], reference.quaternion_matrix(o.x, o.y, o.z, o.w)))


@pytest.fixture
def node(ros):
    """Make a managed motion_cueing_node; its commands are recorded with their send times."""
    made = MotionCueingNode(cli_args=ARGUMENTS)
    made.sent = []
    yield made
    made.destroy_node()


def record(made):
    """Record each target_pose message with the time its command is sent, seconds."""
    publisher = made.target_publisher
    prepare, times = publisher.prepare, []

    def prepared(verdict, *extra):
        times.append(verdict.time)
        return prepare(verdict, *extra)
    publisher.prepare = prepared
    publisher._publisher.publish = lambda message: made.sent.append((times[-1], message))


def operate_until(made, done, seconds):
    """Call the node's timer every period in real time until ``done()`` or ``seconds``."""
    deadline = time.monotonic() + seconds
    while not done() and time.monotonic() < deadline:
        made.on_watchdog()
        time.sleep(PERIOD)
    return done()


def assert_within_leg_limits(sent, what):
    """Divided differences of the legs over the send times: within the velocity and accel."""
    times = np.array([moment for moment, _ in sent])
    lengths = np.array([legs(message) for _, message in sent])
    assert np.all(np.diff(times) > 0.0), what
    velocity = np.diff(lengths, axis=0) / np.diff(times)[:, None]
    assert np.max(np.abs(velocity)) <= VELOCITY_MAX * (1.0 + 1e-6), what
    middle = 0.5 * (times[2:] - times[:-2])
    acceleration = np.diff(velocity, axis=0) / middle[:, None]
    assert np.max(np.abs(acceleration)) <= ACCELERATION_MAX * (1.0 + 1e-6), what


def test_activate_starts_from_park_and_deactivate_stops_to_park(node):
    assert node.trigger_configure() == SUCCESS
    record(node)
    park = node.cueing.park_pose
    park_legs = np.array(reference.leg_lengths(park))
    assert node.cueing.mode == PARKED
    assert node.trigger_activate() == SUCCESS
    assert node.cueing.mode == STARTING          # the transition answered at once
    assert operate_until(node, lambda: node.cueing.mode == CUEING, 5.0)
    started = len(node.sent)
    assert started > 10
    first = legs(node.sent[0][1])
    home = legs(node.sent[started - 1][1])
    # Up from park: the first command is a small step above park, the last is home.
    assert np.all(first < home)
    # Cue a sustained forward force for a second, in real time, then deactivate mid-cue.
    origin = time.monotonic()
    while time.monotonic() - origin < 1.0:
        node.on_imu(imu(10.0 + time.monotonic() - origin, 3.0))
        time.sleep(0.01)
    cued = len(node.sent)
    assert cued > started + 20
    assert np.max(np.abs(legs(node.sent[-1][1]) - home)) > 1e-4   # moving, away from home
    cue_poses = []
    node.cue_publisher.get_subscription_count = lambda: 1
    node.cue_publisher.publish = cue_poses.append
    assert node.trigger_deactivate() == SUCCESS
    assert not node.active and node.cueing.mode == PARKED
    assert len(node.sent) > cued + 10
    # cue_pose is stamped with each stop command's time as the gate checked it (the clock's
    # origin plus it), not the clock's now, which stands still under a simulated clock.
    stops = [moment for moment, _ in node.sent[-len(cue_poses):]]
    stamps = [pose.header.stamp.sec * 1_000_000_000 + pose.header.stamp.nanosec
              for pose in cue_poses]
    assert len(cue_poses) > 10
    assert_allclose(np.array(stamps) - node.clock_origin_ns, np.array(stops) * 1e9,
                    rtol=0.0, atol=1.0)
    # Ended at park, arrived at rest: the last step a few micrometres at most.
    last = legs(node.sent[-1][1])
    assert_allclose(legs(node.sent[-2][1]), last, rtol=0.0, atol=1e-5)
    assert_allclose(last, node.cueing.limiter.lengths, rtol=0.0, atol=1e-9)
    assert_allclose(last, legs(node.sent[0][1]), rtol=0.0, atol=5e-4)   # where it started
    assert_allclose(last, park_legs, rtol=0.0, atol=1e-9)
    assert_within_leg_limits(node.sent, 'start, cue and stop')
    # Activate again: from park once more.
    assert node.trigger_activate() == SUCCESS and node.cueing.mode == STARTING
    assert operate_until(node, lambda: node.cueing.mode == CUEING, 5.0)
    assert node.trigger_deactivate() == SUCCESS and node.cueing.mode == PARKED
    assert_within_leg_limits(node.sent, 'the whole run')


def test_an_activate_deactivate_flood_ends_parked_within_the_limits(node):
    assert node.trigger_configure() == SUCCESS
    record(node)
    for round_ in range(4):
        assert node.trigger_activate() == SUCCESS
        operate_until(node, lambda: False, 0.04 * round_)   # cut the start short, or not
        assert node.trigger_deactivate() == SUCCESS
        assert node.cueing.mode == PARKED, round_
        # Services while inactive do nothing; the platform stays parked.
    assert node.sent, 'no command was sent'
    assert_within_leg_limits(node.sent, 'the flood')
    assert_allclose(legs(node.sent[-1][1]), node.cueing.limiter.lengths, rtol=0.0, atol=1e-9)
    assert math.isfinite(node.sent[-1][0])
