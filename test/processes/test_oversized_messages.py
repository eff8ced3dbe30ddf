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
Oversized messages on every input of every node, as processes: short logs, short diagnostics.

Issue 27: one ``leg_lengths`` message of 10^6 values was refused by fk_node with a reason that
echoed every value, a 5 MB log line and 10 MB of text in every ``/diagnostics`` array. Here
every node of :data:`~stewart_kinematics.ros.interfaces.NODE_INTERFACES` is started from its
console script, and every topic it subscribes to gets one message per field that a sender can
make as large as it likes (:meth:`fuzzing.fuzz_messages.MessageFuzzer.oversized`: a million
numbers in ``data`` or ``position``, 10^5 joint names, 10^4 trajectory points or path poses, a
``frame_id`` of a million characters; fixed-size fields such as an Imu's covariances cannot
grow, and a Pose or a Twist has none). Then the node must still run and answer a service, every
message must be counted on ``/diagnostics``, every line of its log must be at most
:data:`~fuzzing.output_invariants.MAX_LOG_LINE` characters and every string of its statuses at
most :data:`~stewart_kinematics.ros.message_accounting.MAX_TEXT_LENGTH`.
"""

import random

from diagnostic_msgs.msg import DiagnosticArray
from fuzzing.fuzz_client import DiagnosticsLog
from fuzzing.fuzz_messages import MessageFuzzer
from fuzzing.fuzz_targets import parameter_files, plausible_hints
from fuzzing.output_invariants import log_problems
import pytest
from rcl_interfaces.srv import ListParameters

from stewart_kinematics.ros.interfaces import NODE_INTERFACES, SUBSCRIPTION
from stewart_kinematics.ros.message_accounting import MAX_TEXT_LENGTH

pytestmark = pytest.mark.process

#: Depth of the test's publishers (reliable, keep last): every oversized message of one topic
#: is queued at once.
QUEUE_DEPTH = 20
#: Seconds between two oversized messages: one of 8 MB takes DDS a moment on loopback.
SEND_PERIOD = 0.1
#: What the issue saw, as the node's diagnostics must now say it: the input topic and the
#: preview of the input's size in its last rejection.
ISSUE_CASES = {'fk_node': ('leg_lengths', '(1,000,000 values)')}


class StatusTexts:
    """A /diagnostics callback: the longest string of any status, and the latest values."""

    def __init__(self, log: DiagnosticsLog):
        """Feed ``log`` (the counters) too."""
        self.log = log
        self.longest = (0, '')
        self.values = {}

    def __call__(self, array: DiagnosticArray):
        """Measure every string of every status; keep each status's values."""
        self.log(array)
        for status in array.status:
            texts = [status.name, status.message, status.hardware_id]
            texts += [text for pair in status.values for text in (pair.key, pair.value)]
            for text in texts:
                if len(text) > self.longest[0]:
                    self.longest = (len(text), f'{status.name}: {text[:200]}')
            self.values[status.name] = {pair.key: pair.value for pair in status.values}


def received_counts(log: DiagnosticsLog, fqn: str, topics):
    """Return the ``received`` counter of each input topic's status, 0 before its first."""
    latest = log.reports(fqn).latest
    return {topic: latest.get(f'{fqn}: {topic}', {}).get('received', 0) for topic in topics}


# telemetry_bridge has no topic input: its oversized datagrams (64 kB) are in
# test_telemetry_bridge.py.
@pytest.mark.parametrize('node', sorted(node for node, interface in NODE_INTERFACES.items()
                                        if interface.of_kind(SUBSCRIPTION)))
def test_oversized_messages_leave_short_logs_and_diagnostics(client, start_node, node):
    """Every oversized field of every input: the node runs, answers, logs and reports briefly."""
    files = parameter_files(node)
    arguments = ['--ros-args']
    for path in files:
        arguments += ['--params-file', str(path)]
    process = start_node(node, arguments)
    fqn = '/' + node
    log = DiagnosticsLog()
    texts = StatusTexts(log)
    client.node.create_subscription(DiagnosticArray, '/diagnostics', texts, 100)
    hints = plausible_hints(files, node)
    inputs = []
    for endpoint in NODE_INTERFACES[node].of_kind(SUBSCRIPTION):
        generator = MessageFuzzer(endpoint.message_type, random.Random(27), hints, endpoint.name)
        publisher = client.node.create_publisher(endpoint.message_type, endpoint.name,
                                                 QUEUE_DEPTH)
        inputs.append((endpoint.name, publisher, generator))
    client.wait(lambda: all(publisher.get_subscription_count() for _, publisher, _ in inputs)
                and log.count(fqn) >= 1, f'{node} matched on its inputs and reporting',
                [process])

    sent = {topic: 0 for topic, _, _ in inputs}
    what = []
    for topic, publisher, generator in inputs:
        for place in generator.oversized_places():
            message, done = generator.oversized(place)
            publisher.publish(message)
            sent[topic] += 1
            what.append(f'{topic}: {"; ".join(done)}')
            client.spin_for(SEND_PERIOD)
    assert sum(sent.values()) >= 1, f'{node}: no input with a field that can be oversized'
    client.wait(lambda: received_counts(log, fqn, sent) == sent,
                f'{node} counting every oversized message ({sent} sent: {what})', [process])
    reports = log.count(fqn)
    client.wait(lambda: log.count(fqn) >= reports + 1, f'{node} reporting after them',
                [process])

    service = client.node.create_client(ListParameters, f'{fqn}/list_parameters')
    assert service.wait_for_service(timeout_sec=10.0), f'{node} offers no list_parameters'
    answer = service.call_async(ListParameters.Request())
    client.wait(answer.done, f'{node} answering list_parameters', [process])
    assert process.running()
    output = process.output()
    assert not log_problems(output), log_problems(output)
    assert texts.longest[0] <= MAX_TEXT_LENGTH, texts.longest
    if node in ISSUE_CASES:
        topic, words = ISSUE_CASES[node]
        values = texts.values[f'{fqn}: {topic}']
        assert words in values['last rejection'] and words in output, values
