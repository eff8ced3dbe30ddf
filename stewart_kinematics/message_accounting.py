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

#: Seconds between two log lines of the same warning.
WARNING_PERIOD = 1.0
#: Seconds between two summaries on /diagnostics.
SUMMARY_PERIOD = 1.0
#: Hardware id of every diagnostic status of the package.
HARDWARE_ID = 'stewart_platform'


class MessageAccounting:
    """
    Count the messages a node receives, publishes and rejects, and report rejections.

    :param node: the rclpy node.
    :param input_topic: the topic whose messages are counted, for the status name.
    """

    def __init__(self, node, input_topic: str):
        self.node = node
        self.topic = input_topic
        self.status_name = f'{node.get_fully_qualified_name()}: {input_topic}'
        self.received = self.published = self.rejected = 0
        self.last_rejection = ''
        self.rejected_at_last_summary = 0
        self.diagnostics = node.create_publisher(DiagnosticArray, '/diagnostics', 100)
        node.create_timer(SUMMARY_PERIOD, self.publish_summary)

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
        self._send(DiagnosticStatus.ERROR, reason, values)

    def warn(self, message: str, values=()):
        """Publish a WARN status about a message that was still used, and log it (throttled)."""
        self.node.get_logger().warning(message, throttle_duration_sec=WARNING_PERIOD)
        self._send(DiagnosticStatus.WARN, message, values)

    def counters(self):
        """Return the counters as ``(key, value)`` pairs, for a status."""
        return (('received', self.received), ('published', self.published),
                ('rejected', self.rejected))

    def publish_summary(self):
        """Publish the counters: OK, or WARN when messages were rejected since the last one."""
        new_rejections = self.rejected - self.rejected_at_last_summary
        self.rejected_at_last_summary = self.rejected
        if new_rejections:
            self._send(DiagnosticStatus.WARN,
                       f'{new_rejections} message(s) rejected; last: {self.last_rejection}')
        else:
            self._send(DiagnosticStatus.OK, 'running')

    def _send(self, level, message, values=()):
        status = DiagnosticStatus(
            level=level, name=self.status_name, message=message, hardware_id=HARDWARE_ID,
            values=[KeyValue(key=str(key), value=str(value))
                    for key, value in (*self.counters(), *values)])
        array = DiagnosticArray(status=[status])
        array.header.stamp = self.node.get_clock().now().to_msg()
        self.diagnostics.publish(array)


def violation_values(violations):
    """Return ``(key, value)`` status pairs of :class:`~stewart_kinematics.limits.Violation`."""
    pairs = []
    for violation in violations:
        unit = f' {violation.unit}' if violation.unit else ''
        key = violation.limit + (f' leg {violation.leg}' if violation.leg else '')
        pairs.append((key, f'{violation.value:.6g}{unit} (limit {violation.allowed:.6g}{unit})'))
    return pairs
