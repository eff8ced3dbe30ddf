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
What the node and process tests build the same way: messages, clients, stopping a node.

The test's own clients (:class:`TopicClient`, spun by the test's thread, and
:class:`SpinningClient`, spun by a thread of its own) are made by conftest's ``client`` and
``spinning_client`` fixtures; :class:`Recorder` collects a client's topics. The messages are
built from numbers the tests state, with the textbook quaternion of test/reference.py, never with
the package's own conversions. ROS messages are imported here: the core tier does not import
this module.
"""

import socket
import threading
import time

from builtin_interfaces.msg import Duration
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Pose, Transform
import pytest
import reference
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

#: Seconds a test waits for data: DDS discovery on loopback has multi-second tails.
DEADLINE = 20.0
#: Seconds a client lets discovery finish after its endpoints matched (a pause, not a wait).
SETTLE_TIME = 0.5
#: Depth of a client's subscriptions and publishers: deep enough for every message of a test.
CLIENT_DEPTH = 100


def quaternion(alpha, beta, gamma):
    """Quaternion ``(x, y, z, w)`` of ``Rz(gamma) Ry(beta) Rx(alpha)``, as floats."""
    return tuple(float(value) for value in reference.quaternion_from_euler(alpha, beta, gamma))


def pose_message(pose, scale=1.0):
    """
    Build the geometry_msgs/msg/Pose of ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).

    :param scale: a factor on the quaternion (1: a unit quaternion).
    """
    return raw_pose_message(pose[:3], [scale * q for q in quaternion(*pose[3:])])


def raw_pose_message(position, orientation_xyzw=(0.0, 0.0, 0.0, 1.0)):
    """Build a geometry_msgs/msg/Pose with exactly these numbers, valid or not."""
    message = Pose()
    message.position.x, message.position.y, message.position.z = (float(v) for v in position)
    orientation = message.orientation
    orientation.x, orientation.y, orientation.z, orientation.w = (
        float(v) for v in orientation_xyzw)
    return message


def trajectory_message(times, poses, frame_id='stewart_base'):
    """
    Build a trajectory_msgs/msg/MultiDOFJointTrajectory of the platform through the poses.

    :param times: the waypoints' times from the start, seconds.
    :param poses: the waypoints ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).
    :param frame_id: the header's frame ('' counts as the node's base frame).
    """
    message = MultiDOFJointTrajectory(joint_names=['platform'])
    message.header.frame_id = frame_id
    for time_from_start, pose in zip(times, poses):
        transform = Transform()
        transform.translation.x, transform.translation.y, transform.translation.z = (
            float(v) for v in pose[:3])
        rotation = transform.rotation
        rotation.x, rotation.y, rotation.z, rotation.w = quaternion(*pose[3:])
        nanoseconds = int(round(time_from_start * 1e9))
        message.points.append(MultiDOFJointTrajectoryPoint(
            transforms=[transform], velocities=[], accelerations=[],
            time_from_start=Duration(sec=nanoseconds // 10**9, nanosec=nanoseconds % 10**9)))
    return message


def free_udp_port():
    """
    Return a UDP port of loopback that nobody uses now, for a telemetry_bridge under test.

    The bridge's default port (47800) is one per machine: two pytest-xdist workers, or two
    runs of the suite, would take it from each other.
    """
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


def fail_with_output(message, processes):
    """Fail the test with ``message`` and the exit code and output of each process."""
    report = [message]
    for process in processes:
        code = process.stop()
        report.append(f'--- {process.name} (exit code {code}) ---\n{process.output()}')
    pytest.fail('\n'.join(report))


def stop_cleanly(process):
    """Stop a node process with SIGINT: it exits 0 without a traceback; return its output."""
    code = process.stop()
    output = process.output()
    assert code == 0 and 'Traceback' not in output, f'{process.name} exited {code}:\n{output}'
    return output


class TopicClient:
    """The test's own node and executor, spun by the test, with waits that fail with output."""

    def __init__(self, node, executor, spin_until):
        """Wrap the test's node, the executor that spins it and conftest's spin_until."""
        self.node = node
        self.executor = executor
        self._spin_until = spin_until

    def wait(self, condition, what, processes=()):
        """
        Spin until ``condition()`` holds; fail after :data:`DEADLINE` s or when a process exits.

        :param what: the awaited condition in words, for the failure message.
        :param processes: the NodeProcess instances that must keep running meanwhile.
        """
        def done():
            return condition() or not all(process.running() for process in processes)

        self._spin_until(self.executor, done, DEADLINE)
        if not condition():
            fail_with_output(f'{what}: not within {DEADLINE} s', processes)

    def spin_for(self, seconds):
        """Spin for ``seconds``: a settle time or a throttle window, never a wait for data."""
        end = time.monotonic() + seconds
        self._spin_until(self.executor, lambda: time.monotonic() >= end, seconds + 1.0)

    def look_for(self, condition, seconds) -> bool:
        """Spin until ``condition()`` holds, ``seconds`` at most; return whether it holds."""
        self._spin_until(self.executor, condition, seconds)
        return bool(condition())


class SpinningClient:
    """The test's node, spun by a background thread, with waits that fail with node output."""

    #: Seconds between two looks at a wait's condition.
    POLL_PERIOD = 0.01

    def __init__(self, node, executor, depth):
        """Spin ``node`` on ``executor`` in a background thread until :meth:`close`."""
        self.node = node
        self.executor = executor
        self.depth = depth
        self.executor.add_node(node)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, name='client_spin', daemon=True)
        self._thread.start()

    def _spin(self):
        while not self._stop.is_set():
            self.executor.spin_once(timeout_sec=0.05)

    def close(self):
        """Stop spinning and destroy the node."""
        self._stop.set()
        self._thread.join()
        self.executor.shutdown()
        self.node.destroy_node()

    def subscribe(self, message_type, topic, callback):
        """Subscribe ``callback`` to ``topic``, reliable, of the client's depth."""
        return self.node.create_subscription(message_type, topic, callback, self.depth)

    def publisher(self, message_type, topic):
        """Return a publisher on ``topic``, reliable, of the client's depth."""
        return self.node.create_publisher(message_type, topic, self.depth)

    def look_for(self, condition, seconds) -> bool:
        """Wait until ``condition()`` holds, ``seconds`` at most; return whether it holds."""
        return self.wait(condition, '', timeout=seconds, fail=False)

    def wait(self, condition, what, processes=(), timeout=DEADLINE, fail=True):
        """
        Wait until ``condition()`` holds, for ``timeout`` s at most or until a process exits.

        :param what: the awaited condition in words, for the failure message.
        :param processes: the NodeProcess instances that must keep running meanwhile.
        :param fail: fail the test when the condition does not hold in time; else return.
        :returns: whether the condition holds.
        """
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline or not all(p.running() for p in processes):
                break
            time.sleep(self.POLL_PERIOD)
        if condition():
            return True
        if fail:
            fail_with_output(f'{what}: not within {timeout} s', processes)
        return False

    def settle(self):
        """Let discovery finish on every side (a pause, never a wait for data)."""
        time.sleep(SETTLE_TIME)


class Recorder:
    """A TopicClient's subscriptions and publishers, with waits that name what they wait for."""

    def __init__(self, client, nodes):
        """Record on ``client``; fail a wait when one of ``nodes`` exits."""
        self.client, self.nodes = client, nodes
        self.received, self.subscriptions, self.publishers = {}, [], {}
        self.statuses = []
        self.subscriptions.append(client.node.create_subscription(
            DiagnosticArray, '/diagnostics', lambda array: self.statuses.extend(array.status),
            CLIENT_DEPTH))

    def subscribe(self, message_type, topic):
        """Collect the messages of ``topic`` in ``received[topic]``."""
        self.received[topic] = []
        self.subscriptions.append(self.client.node.create_subscription(
            message_type, topic, self.received[topic].append, CLIENT_DEPTH))

    def advertise(self, message_type, topic):
        """Create a publisher on ``topic``."""
        self.publishers[topic] = self.client.node.create_publisher(
            message_type, topic, CLIENT_DEPTH)

    def matched(self):
        """Whether every publisher and subscription (but /diagnostics) has matched."""
        return (all(p.get_subscription_count() >= 1 for p in self.publishers.values())
                and all(s.get_publisher_count() >= 1 for s in self.subscriptions[1:]))

    def connect(self):
        """Wait until every publisher and subscription (but /diagnostics) matched, settle."""
        self.client.wait(self.matched, 'every topic matched', self.nodes)
        self.client.spin_for(SETTLE_TIME)

    def wait_for(self, topic, count):
        """Wait until ``count`` messages arrived on ``topic``."""
        self.client.wait(lambda: len(self.received[topic]) >= count,
                         f'{count} messages on {topic}', self.nodes)

    def rejection(self, status_name, code):
        """Wait for a /diagnostics status named ``status_name`` counting a ``code`` rejection."""
        def found():
            return [status for status in self.statuses if status.name == status_name
                    and any(value.key == f'rejected {code}' for value in status.values)]
        self.client.wait(found, f'a {code} rejection in {status_name} on /diagnostics',
                         self.nodes)
        return found()[-1]
