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
Simulated time across processes: trajectory_node with ``use_sim_time`` plays to ``/clock``.

The test's node publishes ``/clock`` (rosgraph_msgs/msg/Clock) as a simulator would; the
trajectory node and ik_node, console-script processes, run on it. The ramp reaches its middle
after 5 simulated seconds, however long that takes on the wall clock, and publishes nothing
while the clock stands still, however long it stands; ik_node stamps its joint commands and its
diagnostics with the simulated time.
"""

from builtin_interfaces.msg import Time
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Pose
from helpers import DEADLINE
import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import quaternion_from_euler
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState

pytestmark = pytest.mark.process

#: The ramp: Table 3 over 10 simulated seconds, sampled every 0.1 simulated second.
DURATION = 10.0
PERIOD_NS = 100_000_000
#: The simulated time at the start, nanoseconds (any value: the ramp counts from its start).
START_NS = 1000 * 1_000_000_000
#: Wall-clock seconds the clock stands still while the test watches for poses.
STILL_SECONDS = 1.0
#: Until the ramp starts: simulated time per tick (trajectory_node checks for subscribers
#: every 0.05 s), and wall-clock seconds to wait for a pose after each tick: long, for the
#: pose to be that tick's (one later than this, under load, would shift the start a tick).
WAIT_TICK_NS = 50_000_000
TICK_WAIT = 2.0
#: Wall-clock seconds after which a tick is sent again, the pose of its time not yet come.
RETICK = 0.5


def table3_pose(elapsed):
    """
    Table 3 ramp at ``elapsed`` of 10 s: X, Y, Z in metres, then the quaternion (x, y, z, w).

    Written out: linear from the first row to the last (the rows are evenly spaced).
    """
    fraction = min(max(elapsed / DURATION, 0.0), 1.0)
    position = np.array([0.0, 0.0, 0.4325]) + fraction * np.array([0.1, 0.15, 0.1])
    quaternion = quaternion_from_euler(*np.radians(fraction * np.array([15.0, -15.0, 20.0])))
    return np.concatenate([position, quaternion])


def stamp_ns(message):
    """Return the header stamp of a message, nanoseconds."""
    return message.header.stamp.sec * 1_000_000_000 + message.header.stamp.nanosec


def as_vector(message: Pose):
    """Return the position and quaternion of a Pose, as one array."""
    p, o = message.position, message.orientation
    return np.array([p.x, p.y, p.z, o.x, o.y, o.z, o.w])


def test_the_ramp_plays_at_the_simulated_rate_and_stops_with_the_clock(
        client, start_node, config_directory):
    """5 simulated seconds take the ramp to its middle; a still clock publishes nothing."""
    platform = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
                '-p', 'use_sim_time:=true']
    commands, diagnostics = [], []
    # ik_node first: the ramp waits for two subscribers of target_pose, ik_node and the test.
    ik_node = start_node('ik_node', platform)
    client.node.create_subscription(JointState, 'joint_commands', commands.append, 100)
    client.node.create_subscription(DiagnosticArray, '/diagnostics', diagnostics.append, 100)
    # The ramp parameters' defaults are Table 3's.
    node = start_node('trajectory_node', [
        *platform, '-p', 'mode:=interpolate', '-p', f'duration:={DURATION}',
        '-p', 'publish_rate:=10.0', '-p', 'min_subscribers:=2', '-p', 'start_delay:=0.0'])
    clock = client.node.create_publisher(Clock, '/clock', 10)
    client.wait(lambda: clock.get_subscription_count() >= 2
                and client.node.count_publishers('joint_commands') >= 1,
                'trajectory_node and ik_node on /clock', [node, ik_node])

    def tick(nanoseconds):
        clock.publish(Clock(clock=Time(sec=nanoseconds // 1_000_000_000,
                                       nanosec=nanoseconds % 1_000_000_000)))

    # Both nodes on the simulated clock before the ramp may start (it waits for the test's
    # subscription below). rclpy takes /clock best effort: a tick sent before a node's reader
    # matched is lost, and ik_node, its clock still at 0, would stamp the ramp's next command
    # 0 for good (the likely cause of "the pose and the command of t = 0.1 s: not within
    # 20 s", twice in one session). The same time again moves nothing.
    for _ in range(4):
        tick(START_NS)
        client.spin_for(0.25)
    poses = []
    client.node.create_subscription(Pose, 'target_pose', poses.append, 100)
    # Both subscribers in the graph first: the first tick then most likely starts the ramp.
    client.wait(lambda: client.node.count_subscribers('target_pose') >= 2,
                'ik_node and the test on target_pose', [node, ik_node])

    # The node checks for its subscribers on a timer of the simulated clock: tick until it
    # sees both and starts, with time for each tick's pose to arrive. The ramp starts then.
    start = START_NS + WAIT_TICK_NS
    tick(start)
    for _ in range(20):
        if client.look_for(lambda: poses, TICK_WAIT):
            break
        start += WAIT_TICK_NS
        tick(start)
    client.wait(lambda: poses, 'the first pose', [node, ik_node])
    assert_allclose(as_vector(poses[0]), table3_pose(0.0), rtol=0, atol=1e-12)

    now = start
    # ik_node may take a pose before the tick it was sampled at: its stamp is then the tick
    # before, a simulated time either way.
    for _ in range(50):   # 5 simulated seconds, in steps of one sample period
        now += PERIOD_NS
        tick(now)
        elapsed = (now - start) / 1e9

        def arrived(elapsed=elapsed, now=now):
            return (np.allclose(as_vector(poses[-1]), table3_pose(elapsed), rtol=0, atol=1e-9)
                    and commands and now - PERIOD_NS <= stamp_ns(commands[-1]) <= now)
        # rclpy takes /clock best effort, depth 1: a tick can be lost. The same time again,
        # as a simulator keeps publishing it, until the pose comes (or the deadline).
        for _ in range(int(DEADLINE / RETICK)):
            if client.look_for(arrived, RETICK):
                break
            tick(now)
        client.wait(arrived, f'the pose and the command of t = {elapsed:.1f} s',
                    [node, ik_node])
    assert_allclose(as_vector(poses[-1]), table3_pose(5.0), rtol=0, atol=1e-9)

    count = len(poses)
    tick(now)   # the same time again: the clock stands still
    client.spin_for(STILL_SECONDS)
    assert len(poses) == count, 'poses published while the simulated clock stood still'
    # ik_node reports once a simulated second: 5 reports, stamped on the clock's ticks.
    stamps = [stamp_ns(array) for array in diagnostics
              if any(status.name.startswith('/ik_node') for status in array.status)]
    assert 4 <= len(stamps) <= 6, stamps
    assert all(START_NS <= stamp <= now for stamp in stamps), stamps

    now += 6 * 1_000_000_000   # a jump past the end: the last row, and the ramp is done
    tick(now)
    client.wait(lambda: np.allclose(as_vector(poses[-1]), table3_pose(DURATION),
                                    rtol=0, atol=1e-9), 'the last row', [node, ik_node])
