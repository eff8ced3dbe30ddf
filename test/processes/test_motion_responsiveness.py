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
trajectory_node as a process stays responsive whatever it is sent, and stops when asked.

The inputs of issue 20: a trajectory whose last point is at 2^31 - 1 s (before, it killed the
node, or hung it with retiming); a trajectory whose check takes seconds (before: inside the
subscription callback, the node deaf meanwhile); SIGINT during that check; a tool frame
changed at run time (before: accepted, and not applied). The node is the console script with
the shipped parameter files, as a user starts it; the test's own node talks to it over topics
and its parameter services.

No assertion is timed: responsiveness is shown by order (parameter requests answered while
the long trajectory is still being checked: it is then superseded, not finished) and a stop by
the exit code and the log; ``benchmarks/motion_benchmark.py --node`` measures the latencies.
"""

import math
import signal

from diagnostic_msgs.msg import DiagnosticArray
from helpers import trajectory_message
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import GetParameters, SetParameters
import reference
from trajectory_msgs.msg import JointTrajectory, MultiDOFJointTrajectory

pytestmark = pytest.mark.process

HOME = np.array(reference.HOME)
DEPTH = 10
TOOL_POSITION = [0.02, -0.01, 0.06]
#: Waypoints of the long trajectory: 3899 segments of 2.56 s, 256 samples each: 998,145
#: samples, just within a check's budget, several seconds of work.
LONG_WAYPOINTS = 3900
LONG_DURATION = 9981.44


def node_args(config_directory, namespace, *extra):
    """Return the arguments of a trajectory_node: shipped files, no ramp, a namespace."""
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'example_limits.yaml'),
            '-p', "mode:='off'", '-p', 'publish_rate:=20.0', '-r', f'__ns:={namespace}',
            *extra]


def short_trajectory():
    """Home, 2 cm up, home, over 10 s."""
    return trajectory_message([0.0, 5.0, 10.0],
                              [HOME, HOME + [0.0, 0.0, 0.02, 0.0, 0.0, 0.0], HOME], frame_id='')


def long_trajectory():
    """Slow waves about home over 9981 s, 3900 waypoints: checked for seconds."""
    times = np.linspace(0.0, LONG_DURATION, LONG_WAYPOINTS)
    phase = 2.0 * math.pi * times / LONG_DURATION
    return trajectory_message(times, HOME + 0.01 * np.outer(
        1.0 - np.cos(phase), [1.0, 1.0, 1.0, 0.0, 0.0, 0.0]), frame_id='')


class Session:
    """The test's node: trajectory publishers, leg_trajectory, /diagnostics, parameters."""

    def __init__(self, client, processes):
        """Watch ``/diagnostics``; fail waits when one of ``processes`` exits."""
        self.client, self.processes = client, processes
        self.statuses = []
        client.node.create_subscription(DiagnosticArray, '/diagnostics',
                                        lambda array: self.statuses.extend(array.status), 100)
        self.received, self.publishers, self.services = {}, {}, {}

    def add(self, namespace):
        """Publish to ``namespace``'s pose_trajectory and record its leg_trajectory."""
        self.received[namespace] = []
        self.client.node.create_subscription(
            JointTrajectory, f'{namespace}/leg_trajectory', self.received[namespace].append,
            DEPTH)
        self.publishers[namespace] = self.client.node.create_publisher(
            MultiDOFJointTrajectory, f'{namespace}/pose_trajectory', DEPTH)
        for kind, service in (('get', GetParameters), ('set', SetParameters)):
            self.services[namespace, kind] = self.client.node.create_client(
                service, f'{namespace}/trajectory_node/{kind}_parameters')

    def connect(self):
        """Wait until every publisher is matched and every parameter service is there."""
        self.client.wait(lambda: all(
            publisher.get_subscription_count() >= 1 for publisher in self.publishers.values())
            and all(service.service_is_ready() for service in self.services.values()),
            'the trajectory nodes matched', self.processes)

    def call(self, namespace, kind, request):
        """Call a parameter service of ``namespace`` and wait for the answer."""
        future = self.services[namespace, kind].call_async(request)
        self.client.wait(future.done, f'{kind}_parameters of {namespace} answered',
                         self.processes)
        return future.result()

    def count(self, namespace, key):
        """Return the latest value of ``key`` in the pose_trajectory status of a node (0)."""
        name = f'{namespace}/trajectory_node: pose_trajectory'
        for status in reversed(self.statuses):
            if status.name == name:
                return int(next((value.value for value in status.values
                                 if value.key == key), 0))
        return 0

    def wait_count(self, namespace, key, count):
        """Wait until /diagnostics reports ``key`` >= ``count`` for a node's pose_trajectory."""
        self.client.wait(lambda: self.count(namespace, key) >= count,
                         f'{key} >= {count} on {namespace}', self.processes)


def double_array(name, values):
    """Return an rcl_interfaces Parameter holding a double array."""
    return Parameter(name=name, value=ParameterValue(
        type=ParameterType.PARAMETER_DOUBLE_ARRAY, double_array_value=list(values)))


def test_a_time_of_2_to_the_31_seconds_is_refused_and_the_node_answers_on(
        client, start_node, config_directory):
    """Retiming on: the absurd time is refused with the reason; parameters, then a good one."""
    node = start_node('trajectory_node', node_args(config_directory, '/huge', '-p',
                                                   'retime:=true'))
    session = Session(client, [node])
    session.add('/huge')
    session.connect()
    session.publishers['/huge'].publish(trajectory_message(
        [0.0, 1.0, 2.0 ** 31 - 1.0], [HOME, HOME + [0.0, 0.0, 0.02, 0.0, 0.0, 0.0], HOME],
        frame_id=''))
    session.wait_count('/huge', 'rejected invalid_trajectory', 1)
    answer = session.call('/huge', 'get', GetParameters.Request(names=['retime']))
    assert answer.values[0].bool_value is True
    session.publishers['/huge'].publish(short_trajectory())
    client.wait(lambda: session.received['/huge'], 'a leg_trajectory', [node])
    assert node.running()


def test_the_node_answers_while_a_long_trajectory_is_checked_and_sigint_stops_it(
        client, start_node, config_directory):
    """
    A 10^4 s trajectory of a million samples: parameters answered while it is checked.

    The short trajectory sent afterwards supersedes it: so it was still being checked when the
    parameters were answered. Then the long one again, and SIGINT while it is checked: the
    node cancels the check and exits with 0.
    """
    node = start_node('trajectory_node', node_args(config_directory, '/long'))
    session = Session(client, [node])
    session.add('/long')
    session.connect()
    session.publishers['/long'].publish(long_trajectory())
    session.wait_count('/long', 'received', 1)
    for _ in range(5):
        answer = session.call('/long', 'get', GetParameters.Request(names=['validation_rate']))
        assert answer.values[0].double_value == 1000.0
    result = session.call('/long', 'set', SetParameters.Request(
        parameters=[double_array('tool_frame_position', [0.0, 0.0, 0.0])]))
    assert result.results[0].successful
    session.publishers['/long'].publish(short_trajectory())
    client.wait(lambda: session.received['/long'], 'the short trajectory', [node])
    session.wait_count('/long', 'rejected superseded', 1)
    session.wait_count('/long', 'published', 1)

    session.publishers['/long'].publish(long_trajectory())
    session.wait_count('/long', 'received', 3)
    client.spin_for(0.5)   # the worker is in the check now (it takes seconds)
    node.send_signal(signal.SIGINT)
    assert node.stop() == 0, node.output()
    assert 'pose_trajectory: planning cancelled, the node stops' in node.output()


def test_a_tool_frame_set_at_run_time_acts_like_one_set_at_start_up(
        client, start_node, config_directory):
    """The same tool-frame trajectory to both: the same leg_trajectory, point for point."""
    position = '[' + ', '.join(str(value) for value in TOOL_POSITION) + ']'
    nodes = [start_node('trajectory_node', node_args(
                 config_directory, '/start', '-p', f'tool_frame_position:={position}')),
             start_node('trajectory_node', node_args(config_directory, '/changed'))]
    session = Session(client, nodes)
    for namespace in ('/start', '/changed'):
        session.add(namespace)
    session.connect()
    result = session.call('/changed', 'set', SetParameters.Request(
        parameters=[double_array('tool_frame_position', TOOL_POSITION)]))
    assert result.results[0].successful
    tool_poses = HOME + [0.0, 0.0, 0.06, 0.0, 0.0, 0.0] + np.array(
        [[0.0] * 6, [0.01, 0.0, 0.01, 0.0, 0.03, 0.05], [0.0, -0.01, 0.0, 0.04, 0.0, 0.0]])
    for namespace in ('/start', '/changed'):
        session.publishers[namespace].publish(
            trajectory_message([0.0, 4.0, 8.0], tool_poses, frame_id=''))
    client.wait(lambda: session.received['/start'] and session.received['/changed'],
                'both leg_trajectory messages', nodes)
    first, second = session.received['/start'][0], session.received['/changed'][0]
    assert len(first.points) == len(second.points)
    assert_allclose([p.positions for p in first.points], [p.positions for p in second.points],
                    rtol=0, atol=1e-12)
    # And not the platform-frame answer: at 4 s the legs are those of the platform pose that
    # puts the tool there (tool 6 cm above the platform, the tool poses 6 cm above home).
    at_four = next(p for p in first.points if p.time_from_start.sec == 4
                   and p.time_from_start.nanosec == 0)
    pose = tool_poses[1]
    rotation = reference.rotation_zyx(*pose[3:])
    platform = np.concatenate([pose[:3] - rotation @ TOOL_POSITION, pose[3:]])
    assert_allclose(at_four.positions, reference.leg_lengths(platform), rtol=0, atol=1e-9)
