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
motion_cueing_node in this process: its interface, its outputs, its refusals, reset, watchdog.

The node and a test client share one executor; messages go through the middleware on a
private, local domain (conftest).
"""

import math
from pathlib import Path

from geometry_msgs.msg import AccelStamped, Pose, PoseStamped
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.exceptions import ParameterException
import reference
from reference import quaternion_from_euler
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu
from std_srvs.srv import Trigger

from stewart_kinematics.ros.interfaces import MOTION_CUEING_NODE, PUBLISHER, SERVICE, SUBSCRIPTION
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
from stewart_kinematics.ros.node_main import create_executor

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
ARGUMENTS = ['--ros-args', '--params-file', str(CONFIG / 'paper_platform.yaml'),
             '--params-file', str(CONFIG / 'example_limits.yaml'),
             '--params-file', str(CONFIG / 'motion_cueing.yaml')]
G = 9.80665
DEPTH = 100
#: Messages published before waiting for their answers: well within the queues.
BATCH = 40


def imu(stamp_ns, force=(0.0, 0.0, G), rate=(0.0, 0.0, 0.0)):
    """sensor_msgs/msg/Imu with a stamp in nanoseconds, a specific force and a rate."""
    message = Imu()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    message.header.frame_id = 'base_link'
    acceleration, velocity = message.linear_acceleration, message.angular_velocity
    acceleration.x, acceleration.y, acceleration.z = force
    velocity.x, velocity.y, velocity.z = rate
    return message


class Rig:
    """
    The node, a client node and one executor, with the client's publisher and inboxes.

    With ``simulated_time`` the node runs on ``/clock``, which the rig sets to each message's
    stamp before sending it: the platform is paced by the node's clock (the times its commands
    are sent), so a burst of messages is the vehicle's motion in the stamps' time, not in the
    few milliseconds the burst takes.
    """

    def __init__(self, ros, spin_until, arguments, simulated_time=True):
        self.simulated_time = simulated_time
        if simulated_time:
            arguments = arguments + ['-p', 'use_sim_time:=true']
        self.node = MotionCueingNode(cli_args=arguments)
        self.client = ros.create_node('cueing_test_client')
        self.executor = create_executor()
        self.executor.add_node(self.node)
        self.executor.add_node(self.client)
        self.spin_until = spin_until
        self.publisher = self.client.create_publisher(Imu, 'vehicle_imu', DEPTH)
        self.clock = self.client.create_publisher(Clock, '/clock', DEPTH)
        self.inbox = {'target_pose': [], 'cue_pose': [], 'perceived_accel': []}
        for topic, kind in (('target_pose', Pose), ('cue_pose', PoseStamped),
                            ('perceived_accel', AccelStamped)):
            self.client.create_subscription(kind, topic, self.inbox[topic].append, DEPTH)
        assert spin_until(self.executor, lambda: (
            self.publisher.get_subscription_count() >= 1
            and all(self.client.count_publishers(topic) >= 1 for topic in self.inbox)))

    def send(self, messages, wait_for=None):
        """
        Publish in batches that fit the queues, waiting after each for its target poses.

        On simulated time, one message at a time, each after ``/clock`` reached its stamp.

        :param wait_for: target poses expected for the whole list (default: one per message).
        """
        if self.simulated_time:
            accounting = self.node.accounting
            for message in messages:
                stamp = message.header.stamp
                self.clock.publish(Clock(clock=stamp))
                target = stamp.sec * 1_000_000_000 + stamp.nanosec
                assert self.spin_until(self.executor, lambda: (
                    self.node.get_clock().now().nanoseconds == target))
                received = accounting.received
                self.publisher.publish(message)
                assert self.spin_until(self.executor, lambda: accounting.received > received)
            return
        if wait_for is not None:
            start = len(self.inbox['target_pose'])
            for message in messages:
                self.publisher.publish(message)
            assert self.spin_until(self.executor,
                                   lambda: len(self.inbox['target_pose']) >= start + wait_for)
            return
        for first in range(0, len(messages), BATCH):
            batch = messages[first:first + BATCH]
            start = len(self.inbox['target_pose'])
            for message in batch:
                self.publisher.publish(message)
            assert self.spin_until(
                self.executor, lambda: len(self.inbox['target_pose']) >= start + len(batch))

    def close(self):
        """Destroy both nodes."""
        self.executor.shutdown()
        self.node.destroy_node()
        self.client.destroy_node()


@pytest.fixture
def rig(ros, spin_until):
    """Make a node with the shipped files, and its client."""
    made = Rig(ros, spin_until, ARGUMENTS)
    yield made
    made.close()


def test_node_offers_exactly_its_declared_interface(rig):
    """Subscriptions, publishers and services as ros/interfaces.py declares them."""
    node = rig.node

    def type_name(kind, message_type):
        module = message_type.__module__.split('.')[0]
        return f'{module}/{"srv" if kind == SERVICE else "msg"}/{message_type.__name__}'

    # /clock: the time source's on simulated time (the rig's), not one of the node's own.
    offered = {(SUBSCRIPTION, s.topic_name.lstrip('/'), type_name(SUBSCRIPTION, s.msg_type))
               for s in node.subscriptions if s.topic_name != '/clock'}
    offered |= {(PUBLISHER, p.topic_name.lstrip('/'), type_name(PUBLISHER, p.msg_type))
                for p in node.publishers if p.topic_name not in ('/rosout', '/parameter_events')}
    offered |= {(SERVICE, s.srv_name.lstrip('/'), type_name(SERVICE, s.srv_type))
                for s in node.services if '/' not in s.srv_name.lstrip('/')}   # not ~/...
    declared = {(e.kind, e.name.lstrip('/'), e.type_name) for e in MOTION_CUEING_NODE.endpoints}
    assert offered == declared


def test_each_sample_gives_a_pose_a_stamped_cue_and_the_felt_force(rig):
    """100 samples of a 2 m/s^2 push: 100 target poses; stamps carried; felt force one behind."""
    start = 1_700_000_000_000_000_000
    messages = [imu(start + k * 10_000_000, force=(2.0, 0.0, G)) for k in range(100)]
    rig.send(messages)
    poses, cues, felt = (rig.inbox[topic] for topic in ('target_pose', 'cue_pose',
                                                        'perceived_accel'))
    assert rig.spin_until(rig.executor, lambda: len(felt) >= 98 and len(cues) >= 100)
    assert len(poses) == 100
    for message, cue in zip(messages, cues):
        assert cue.header.stamp == message.header.stamp
        assert cue.header.frame_id == 'stewart_base'
    assert [m.header.stamp for m in felt] == [m.header.stamp for m in messages[1:99]]
    assert felt[0].header.frame_id == 'stewart_platform'
    # The platform moves forward and tilts back: the felt force grows toward the push.
    assert poses[-1].position.x > 0.0 and felt[-1].accel.linear.x > 0.1
    assert rig.node.accounting.published == 100 and rig.node.accounting.rejected == 0


def test_the_leg_rates_hold_in_the_time_the_commands_are_sent(rig):
    """
    The legs of target_pose keep their rate limits in the node's (simulated) time.

    The rig sets /clock to each sample's stamp before sending it, so the commands' times are
    known exactly: 3 s of a hard, noisy drive at 100 Hz; the leg lengths of every target_pose
    (by the reference formula) move within leg_velocity_max and leg_acceleration_max.
    """
    rng = np.random.default_rng(7)
    start = 30_000_000_000
    messages = [imu(start + k * 10_000_000, force=tuple([0.0, 0.0, G] + rng.normal(0.0, 15.0, 3)),
                    rate=tuple(rng.normal(0.0, 2.0, 3))) for k in range(300)]
    rig.send(messages)
    poses = rig.inbox['target_pose'][-300:]
    lengths = np.array([reference.leg_lengths_of_matrix(
        [pose.position.x, pose.position.y, pose.position.z],
        reference.quaternion_matrix(pose.orientation.x, pose.orientation.y, pose.orientation.z,
                                    pose.orientation.w)) for pose in poses])
    velocities = np.diff(lengths, axis=0) / 0.01
    accelerations = np.diff(velocities, axis=0) / 0.01
    assert np.ptp(lengths, axis=0).max() > 1e-3
    assert np.abs(velocities).max() <= 0.05 * (1 + 1e-9)
    assert np.abs(accelerations).max() <= 0.25 * (1 + 1e-9)


def test_bad_values_are_refused_counted_and_ease_home(rig):
    """Refuse NaN and absurd samples with the reason, yet publish a pose (at rest)."""
    start = 10_000_000_000
    rig.send([imu(start + k * 10_000_000, force=(0.0, 4.0, G)) for k in range(300)])
    leaning = rig.inbox['target_pose'][-1]
    bad = [imu(start + (300 + k) * 10_000_000,
               force=(math.nan, 0.0, G) if k % 2 else (500.0, 0.0, G)) for k in range(1500)]
    rig.send(bad)
    accounting = rig.node.accounting
    assert accounting.rejected == 1500
    assert accounting.rejections_by_code == {'invalid_vehicle_motion': 1500}
    assert 'specific_force' in accounting.last_rejection.message
    home = rig.node.cueing.geometry.home_pose
    last = rig.inbox['target_pose'][-1]
    assert abs(leaning.orientation.x) > 1e-3
    assert np.linalg.norm([last.position.x, last.position.y, last.position.z - home[2]]) < 1e-3
    assert abs(last.orientation.x) < math.radians(0.1) / 2.0


def test_repeated_and_backward_stamps_publish_nothing(rig):
    """A repeated or earlier stamp: refused as time_not_increasing, no pose for it."""
    rig.send([imu(5_000_000_000), imu(5_010_000_000)])
    before = len(rig.inbox['target_pose'])
    for stamp in (5_010_000_000, 5_000_000_000):
        rig.publisher.publish(imu(stamp))
    rig.send([imu(5_020_000_000)], wait_for=1)
    assert len(rig.inbox['target_pose']) == before + 1
    assert rig.node.accounting.rejections_by_code == {'time_not_increasing': 2}


def test_a_malformed_stamp_is_refused_and_does_not_block_the_samples_after_it(rig):
    """
    A stamp of nanosec 4e9 (not below 1e9): refused saying so, the next samples are cued.

    Before, it was taken as 4 s on (rclpy does not check nanosec): every good sample after it
    was refused as backward until input_timeout.
    """
    rig.send([imu(5_000_000_000), imu(5_010_000_000)])
    before = len(rig.inbox['target_pose'])
    malformed = imu(5_020_000_000)
    malformed.header.stamp.nanosec = 4_000_000_000
    rig.publisher.publish(malformed)
    rig.send([imu(5_030_000_000), imu(5_040_000_000)])
    assert len(rig.inbox['target_pose']) == before + 2
    accounting = rig.node.accounting
    assert accounting.rejections_by_code == {'time_not_increasing': 1}
    assert 'header.stamp is malformed: nanosec 4000000000' in accounting.last_rejection.message


def test_reset_service_washes_out_to_neutral(rig):
    """A reset mid-turn: the platform glides home while the vehicle is at rest."""
    start = 20_000_000_000
    rig.send([imu(start + k * 10_000_000, force=(1.0, 4.0, G), rate=(0.0, 0.0, 0.2))
              for k in range(300)])
    client = rig.client.create_client(Trigger, 'reset')
    assert rig.spin_until(rig.executor, client.service_is_ready)
    future = client.call_async(Trigger.Request())
    assert rig.spin_until(rig.executor, future.done)
    assert future.result().success and 'neutral' in future.result().message
    rig.send([imu(start + (300 + k) * 10_000_000) for k in range(1000)])
    last = rig.inbox['target_pose'][-1]
    home = rig.node.cueing.geometry.home_pose
    assert np.linalg.norm([last.position.x, last.position.y, last.position.z - home[2]]) < 1e-3


def test_watchdog_eases_home_when_the_input_stops(ros, spin_until):
    """input_timeout 0.2 s: after the stream stops, poses keep coming until the platform rests."""
    made = Rig(ros, spin_until, ARGUMENTS + ['-p', 'input_timeout:=0.2'], simulated_time=False)
    try:
        made.send([imu(k * 10_000_000, force=(0.0, 4.0, G)) for k in range(300)])
        count = len(made.inbox['target_pose'])
        home = made.node.cueing.geometry.home_pose

        def home_again():
            last = made.inbox['target_pose'][-1]
            return (len(made.inbox['target_pose']) > count
                    and abs(last.position.y) < 1e-4 and abs(last.orientation.x) < 1e-5)
        assert spin_until(made.executor, home_again, timeout=60.0)
        assert made.node.cueing.settled(1e-4)
        assert abs(made.inbox['target_pose'][-1].position.z - home[2]) < 1e-4
    finally:
        made.close()


def test_target_pose_is_the_tool_frame_pose(ros, spin_until):
    """With a tool frame set, target_pose carries the tool frame's pose (ik_node's input)."""
    made = Rig(ros, spin_until, ARGUMENTS + ['-p', 'tool_frame_position:=[0.0, 0.0, 0.3]'])
    try:
        made.send([imu(k * 10_000_000, force=(0.0, 0.0, G)) for k in range(3)])
        target = made.inbox['target_pose'][-1]
        home = made.node.cueing.geometry.home_pose
        assert_allclose([target.position.x, target.position.y, target.position.z],
                        home[:3] + [0.0, 0.0, 0.3], atol=1e-12)
        assert_allclose([target.orientation.x, target.orientation.y, target.orientation.z,
                         target.orientation.w], quaternion_from_euler(0.0, 0.0, 0.0),
                        atol=1e-12)
    finally:
        made.close()


@pytest.mark.parametrize('override, name', [
    ('tilt_rate_max_deg:=-3.0', 'tilt_rate_max_deg'),
    ('translation_frequency:=[1.0, 1.0]', 'translation_frequency'),
    ('translation_order:=4', 'translation_order'),
    ('leg_length_margin:=0.5', 'leg_length_margin'),
])
def test_bad_parameters_stop_the_start(ros, override, name):
    """A parameter out of range fails the construction with its name."""
    # Without motion_cueing.yaml: its node section would win over a -p override (rcl's rule).
    with pytest.raises((ParameterException, ValueError), match=name):
        MotionCueingNode(cli_args=ARGUMENTS[:5] + ['-p', override])


@pytest.fixture
def wall_clock_rig(ros, spin_until):
    """Make a node on the wall clock (its watchdog's time passes by itself), and its client."""
    made = Rig(ros, spin_until, ARGUMENTS, simulated_time=False)
    yield made
    made.close()


def test_one_stamp_far_in_the_future_does_not_freeze_the_node(wall_clock_rig):
    """
    A message stamped 2**31 - 1 s, then the stream as before: cued again after input_timeout.

    Found by the node fuzzer: the absurd stamp was taken as the latest time, every later
    message was refused as ``time_not_increasing`` until 2038, and, each refused message counting
    as input, the watchdog never eased the platform home: one message froze the platform. Now a
    stream refused for its time counts as no input: after input_timeout the platform eases home
    and the next message starts a new time line.
    """
    start_ns = 1_000 * 1_000_000_000
    wall_clock_rig.send([imu(start_ns + index * 10_000_000) for index in range(5)])
    accounting = wall_clock_rig.node.accounting
    published = accounting.published
    wall_clock_rig.publisher.publish(imu((2 ** 31 - 1) * 1_000_000_000 + 999_999_999))
    assert wall_clock_rig.spin_until(wall_clock_rig.executor, lambda: accounting.received == 6)

    def stream_cued_again():
        stamp = start_ns + int(stream_cued_again.index * 10_000_000)
        stream_cued_again.index += 1
        wall_clock_rig.publisher.publish(imu(stamp))
        wall_clock_rig.executor.spin_once(timeout_sec=0.01)
        return accounting.published > published + 1

    stream_cued_again.index = 5
    timeout = wall_clock_rig.node.cueing.settings.input_timeout
    assert wall_clock_rig.spin_until(wall_clock_rig.executor, stream_cued_again,
                                     5.0 + 4 * timeout), (
        f'still refused after {stream_cued_again.index} messages: '
        f'{accounting.rejections_by_code}')
    assert accounting.rejections_by_code.get('time_not_increasing', 0) >= 1


def test_held_samples_end_counted_as_used_so_every_sample_adds_up(ros, spin_until):
    """Parked, a sample is not cued: counted used (with cueing_held), received = used + refused."""
    rig = Rig(ros, spin_until, ARGUMENTS + ['-p', 'start_parked:=true'])
    try:
        rig.send([imu(2_000_000_000 + k * 10_000_000) for k in range(5)])
        rig.send([imu(2_040_000_000)])   # a repeated stamp: refused
        accounting = rig.node.accounting
        assert accounting.received == 6
        assert accounting.warnings_by_code == {'cueing_held': 5}
        assert accounting.rejections_by_code == {'time_not_increasing': 1}
        # Before: the five held samples were neither published nor refused.
        assert accounting.published + accounting.rejected == accounting.received
        assert rig.inbox['target_pose'] == []
    finally:
        rig.close()
