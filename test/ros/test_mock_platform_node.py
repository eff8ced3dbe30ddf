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
mock_platform in the test's process on a simulated clock: stamps, trajectories, jumps, efforts.

The test's node publishes /clock in steps of 10 ms and the commands, on one executor with the
node, so every joint state is stamped with a known time: a trajectory stamped in the future is
followed from its stamp exactly on its interpolation (no lag, no rate limits), a clock that
goes back holds the legs, a jump of 10^6 s moves them one max_time_step, and with masses the
efforts are the static leg forces.
"""

from pathlib import Path

from builtin_interfaces.msg import Duration, Time
from diagnostic_msgs.msg import DiagnosticArray
import numpy as np
from numpy.testing import assert_allclose, assert_array_equal
import pytest
from rclpy.exceptions import ParameterException
from rclpy.executors import SingleThreadedExecutor
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray

from stewart_kinematics import leg_forces, load_geometry
from stewart_kinematics.ros.mock_platform import MockPlatform
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
NAMES = [f'leg_{leg}' for leg in range(1, 7)]
#: Nanoseconds of one step of the simulated clock (the node's 100 Hz).
STEP = 10_000_000


class SimRig:
    """A mock_platform on a simulated clock, and the test's node that drives the clock."""

    def __init__(self, ros, spin_until, *files, parameters=()):
        arguments = ['--ros-args', '-p', 'use_sim_time:=true']
        for name in ('paper_platform.yaml',) + files:
            arguments += ['--params-file', str(CONFIG / name)]
        for parameter in parameters:
            arguments += ['-p', parameter]
        self.node = MockPlatform(cli_args=arguments)
        self.client = ros.create_node('mock_test_client')
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self.executor.add_node(self.client)
        self.spin_until = spin_until
        self.states, self.statuses = [], []
        self.clock = self.client.create_publisher(Clock, '/clock', 10)
        self.client.create_subscription(JointState, 'joint_states', self.states.append, 100)
        self.client.create_subscription(
            DiagnosticArray, '/diagnostics',
            lambda array: self.statuses.extend(array.status), 100)
        self.publishers = {topic: self.client.create_publisher(kind, topic, 10)
                           for kind, topic in ((Float64MultiArray, 'leg_lengths'),
                                               (JointTrajectory, 'leg_trajectory'))}
        assert spin_until(self.executor, lambda: self.clock.get_subscription_count() >= 1 and all(
            p.get_subscription_count() >= 1 for p in self.publishers.values()) and len(
            self.client.get_publishers_info_by_topic('/joint_states')) >= 1)

    def close(self):
        """Destroy both nodes."""
        self.executor.shutdown()
        self.client.destroy_node()
        self.node.destroy_node()

    def tick(self, nanoseconds):
        """Set the simulated clock and spin until a joint state of that stamp arrived."""
        self.clock.publish(Clock(clock=Time(sec=nanoseconds // 10**9,
                                            nanosec=nanoseconds % 10**9)))
        return self.spin_until(self.executor, lambda: self.states and stamp(
            self.states[-1]) == nanoseconds, 5.0)

    def tick_any(self, nanoseconds):
        """Set the simulated clock and spin until any new joint state arrived."""
        count = len(self.states)
        self.clock.publish(Clock(clock=Time(sec=nanoseconds // 10**9,
                                            nanosec=nanoseconds % 10**9)))
        return self.spin_until(self.executor, lambda: len(self.states) > count, 5.0)

    def send(self, topic, message):
        """Publish a command and let the node take it."""
        count = self.node.accounting[topic].received
        self.publishers[topic].publish(message)
        assert self.spin_until(self.executor,
                               lambda: self.node.accounting[topic].received > count, 5.0)


def stamp(message):
    """Return a message's stamp, integer nanoseconds."""
    return message.header.stamp.sec * 10**9 + message.header.stamp.nanosec


def positions(message):
    """Return the positions of a JointState, leg_1..leg_6."""
    return np.array([message.position[list(message.name).index(name)] for name in NAMES])


@pytest.fixture
def make_rig(ros, spin_until):
    """Provide a factory of SimRigs (files, then ``parameters``), closed when the test ends."""
    rigs = []

    def make(*files, parameters=()):
        rigs.append(SimRig(ros, spin_until, *files, parameters=parameters))
        return rigs[-1]
    yield make
    for rig in rigs:
        rig.close()


def test_a_trajectory_stamped_later_is_followed_from_its_stamp_on_its_interpolation(make_rig):
    """No lag, no rate limits: on the set point until 11 s, then exactly on the line."""
    rig = make_rig(parameters=['time_constant:=0.0'])
    home = load_geometry(CONFIG / 'paper_platform.yaml').home_leg_lengths
    assert rig.tick(10 * 10**9)
    assert_allclose(positions(rig.states[-1]), home, atol=1e-12)
    rig.send('leg_lengths', Float64MultiArray(data=(home + 0.002).tolist()))
    message = JointTrajectory(joint_names=NAMES[::-1], points=[
        JointTrajectoryPoint(positions=(home + 0.01)[::-1].tolist(),
                             time_from_start=Duration(sec=0)),
        JointTrajectoryPoint(positions=(home + 0.03)[::-1].tolist(),
                             time_from_start=Duration(sec=1))])
    message.header.stamp = Time(sec=11)
    rig.send('leg_trajectory', message)
    for nanoseconds in range(10 * 10**9 + STEP, 12 * 10**9 + 20 * STEP, STEP):
        assert rig.tick(nanoseconds)
        time = nanoseconds * 1e-9
        expected = (home + 0.002 if time < 11.0 else home + 0.01 + 0.02 * min(time - 11.0, 1.0))
        assert_allclose(positions(rig.states[-1]), expected, atol=1e-9, err_msg=str(time))


def test_a_clock_that_goes_back_or_jumps_never_makes_a_leg_jump(make_rig):
    """Back to 50 s: the legs hold; 10^6 s ahead: they move one step of 0.1 s at most."""
    rig = make_rig('example_limits.yaml', parameters=['max_time_step:=0.1'])
    home = load_geometry(CONFIG / 'paper_platform.yaml').home_leg_lengths
    assert rig.tick(100 * 10**9)
    rig.send('leg_lengths', Float64MultiArray(data=(home + 0.05).tolist()))
    for step in range(1, 101):
        assert rig.tick(100 * 10**9 + step * STEP)
    before = positions(rig.states[-1])
    velocity = np.array(rig.states[-1].velocity)
    assert np.all(before > home + 0.01)
    # Back to 50 s, then the next tick: joint states go on from there (rcl's timer ticks one
    # period after a jump back).
    rig.clock.publish(Clock(clock=Time(sec=50)))
    assert rig.spin_until(rig.executor,
                          lambda: rig.node.get_clock().now().nanoseconds == 50 * 10**9, 5.0)
    assert rig.tick_any(50 * 10**9 + STEP)
    assert stamp(rig.states[-1]) < 51 * 10**9
    assert_array_equal(positions(rig.states[-1]), before)
    assert rig.tick_any(10**6 * 10**9)
    moved = positions(rig.states[-1]) - before
    # 0.1 s more at most: at the velocity limit 0.05 m/s, 5 mm (and the 10 ms step before).
    assert np.all(moved > 0.0) and np.all(moved <= 0.05 * 0.11 + 1e-12)
    assert np.all(np.abs(velocity) <= 0.05)
    # Counted on the legs' status at the next report (the report timer runs on this clock).
    assert rig.tick(10**6 * 10**9 + 100 * STEP)
    assert rig.spin_until(rig.executor, lambda: any(
        status.name == '/mock_platform: legs' and {
            value.key: value.value for value in status.values}.get(
            'warned clock_jump', '0') == '2' for status in rig.statuses), 5.0)


def test_with_masses_the_efforts_are_the_leg_forces_of_the_legs_pose(make_rig):
    """At rest at home: the static leg forces of the example masses, in newtons."""
    rig = make_rig('example_limits.yaml', 'example_masses.yaml')
    geometry = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml',
                              CONFIG / 'example_masses.yaml'])
    assert rig.tick(10**9)
    assert rig.tick(10**9 + STEP)
    efforts = np.array(rig.states[-1].effort)
    assert_allclose(efforts, leg_forces(geometry, geometry.home_pose), atol=1e-6)
    # About a sixth of the weight each (28 kg and the legs, on legs about 54 degrees up).
    assert np.all(efforts > 30.0) and np.all(efforts < 120.0)


@pytest.mark.parametrize('parameter, words', [
    ('initial_leg_lengths:=[0.5, 0.5, 0.5, 0.5, 0.5, 0.5]',
     'initial leg lengths: refused leg command: leg 1 length 0.5 m is outside the stroke'),
    ("stalled_legs:='leg_7'", "'leg_7' is neither a joint name"),
    ("stalled_legs:='0'", "parameter 'stalled_legs' must name legs by number 1..6"),
    ("command_input:='joint_states'", "parameter 'command_input' must be one of all"),
])
def test_a_bad_start_parameter_stops_the_start_with_the_reason(ros, parameter, words):
    """Initial lengths beyond the stroke, an unknown leg, an unknown input: refused."""
    arguments = ['--ros-args', '--params-file', str(CONFIG / 'paper_platform.yaml'),
                 '--params-file', str(CONFIG / 'example_limits.yaml'), '-p', parameter]
    with pytest.raises((ParameterException, ValueError)) as raised:
        MockPlatform(cli_args=arguments).destroy_node()
    assert words in str(raised.value)
