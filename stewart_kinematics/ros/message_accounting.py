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
Accounting of a node's input: every message ends as exactly one output or one rejection.

Rejections are logged (at most once per :data:`WARNING_PERIOD` for each call site) and
published at once on ``/diagnostics`` (diagnostic_msgs/msg/DiagnosticArray, as ROS diagnostic
tools expect) with the reason; a summary with the counters follows every
:data:`SUMMARY_PERIOD`.
"""

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

from stewart_kinematics.ros.node_main import create_output_publisher

#: Seconds between two log lines of the same warning.
WARNING_PERIOD = 1.0
#: Seconds between two summaries on /diagnostics.
SUMMARY_PERIOD = 1.0
#: Hardware id of every diagnostic status of the package.
HARDWARE_ID = 'stewart_platform'


class NodeDiagnostics:
    """
    A node's ``/diagnostics`` publisher and its summary timer, shared by all its inputs.

    One publisher and one timer per node, not per input: rclpy's executor walks every
    publisher's event handlers and every timer at each wait, so each one costs every message.

    :param node: the rclpy node.
    """

    def __init__(self, node):
        self.node = node
        self.inputs = []
        self.publisher = create_output_publisher(node, DiagnosticArray, '/diagnostics', 100)
        node.create_timer(SUMMARY_PERIOD, self.publish_summary)

    def accounting(self, input_topic: str) -> 'MessageAccounting':
        """Return the accounting of one input topic, reported with the others."""
        accounting = MessageAccounting(self, input_topic)
        self.inputs.append(accounting)
        return accounting

    def publish_summary(self):
        """Publish one status per input with its counters, in one array."""
        self.send([accounting.summary() for accounting in self.inputs])

    def send(self, statuses):
        """Publish statuses as one DiagnosticArray stamped now."""
        array = DiagnosticArray(status=statuses)
        array.header.stamp = self.node.get_clock().now().to_msg()
        self.publisher.publish(array)


class MessageAccounting:
    """
    Count the messages a node receives, publishes and rejects, and report rejections.

    Made by :meth:`NodeDiagnostics.accounting`.

    :param diagnostics: the node's :class:`NodeDiagnostics`.
    :param input_topic: the topic whose messages are counted, for the status name.
    """

    def __init__(self, diagnostics: NodeDiagnostics, input_topic: str):
        self.diagnostics = diagnostics
        self.node = diagnostics.node
        self.topic = input_topic
        self.status_name = f'{self.node.get_fully_qualified_name()}: {input_topic}'
        self.received = self.published = self.rejected = 0
        self.last_rejection = ''
        self.rejected_at_last_summary = 0

    def receive(self):
        """Count a message received."""
        self.received += 1

    def publish(self, publisher, message):
        """Publish the output of a received message and count it."""
        publisher.publish(message)
        self.published += 1

    def reject(self, reason: str, values=()):
        """
        Count a rejected message, log why and publish an ERROR status with the reason.

        :param reason: a sentence a user can act on.
        :param values: extra ``(key, value)`` pairs for the status, such as iterations.
        """
        self.rejected += 1
        self.last_rejection = reason
        self.node.get_logger().warning(
            f'{reason} ({self.rejected} rejected so far)', throttle_duration_sec=WARNING_PERIOD)
        self.diagnostics.send([self.status(DiagnosticStatus.ERROR, reason, values)])

    def warn(self, message: str, values=()):
        """Publish a WARN status about a message that was still used, and log it (throttled)."""
        self.node.get_logger().warning(message, throttle_duration_sec=WARNING_PERIOD)
        self.diagnostics.send([self.status(DiagnosticStatus.WARN, message, values)])

    def counters(self):
        """Return the counters as ``(key, value)`` pairs, for a status."""
        return (('received', self.received), ('published', self.published),
                ('rejected', self.rejected))

    def summary(self) -> DiagnosticStatus:
        """Return the counters' status: OK, or WARN when messages were rejected since the last."""
        new_rejections = self.rejected - self.rejected_at_last_summary
        self.rejected_at_last_summary = self.rejected
        if new_rejections:
            return self.status(
                DiagnosticStatus.WARN,
                f'{new_rejections} message(s) rejected; last: {self.last_rejection}')
        return self.status(DiagnosticStatus.OK, 'running')

    def status(self, level, message, values=()) -> DiagnosticStatus:
        """Return a status of this input with the counters and ``values``."""
        return DiagnosticStatus(
            level=level, name=self.status_name, message=message, hardware_id=HARDWARE_ID,
            values=[KeyValue(key=str(key), value=str(value))
                    for key, value in (*self.counters(), *values)])


def violation_values(violations):
    """Return ``(key, value)`` status pairs of :class:`~stewart_kinematics.limits.Violation`."""
    pairs = []
    for violation in violations:
        unit = f' {violation.unit}' if violation.unit else ''
        key = violation.limit + (f' leg {violation.leg}' if violation.leg else '')
        pairs.append((key, f'{violation.value:.6g}{unit} (limit {violation.allowed:.6g}{unit})'))
    return pairs
