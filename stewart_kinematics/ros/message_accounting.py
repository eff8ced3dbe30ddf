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

A rejection or a warning carries the core's :class:`~stewart_kinematics.findings.Finding`:
its code is what rejections are counted by, its message what the log and ``/diagnostics`` say.
As diagnostic_updater does, a node publishes one diagnostic_msgs/msg/DiagnosticArray every
:data:`REPORT_PERIOD`, never one per message, so a flood of bad input cannot flood
``/diagnostics``: one status per input topic with the counters, the counts by code and the
latest rejection and warning with their details. The log says each kind of rejection at most
once per :data:`WARNING_PERIOD`, kind by kind, so a flood of one kind does not hide another.

Nor can a large message flood them: the core describes a large input by its size and a short
preview (:func:`stewart_kinematics.model.arrays.preview`), and here, where the text is emitted,
every log line and every string of a status (its message, each key and each value) is cut to
:data:`MAX_TEXT_LENGTH` characters with a note of how much was cut (:func:`bounded`), whatever
a finding says.
"""

import time

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

from stewart_kinematics.findings import Finding
from stewart_kinematics.ros.interfaces import DIAGNOSTICS_TOPIC
from stewart_kinematics.ros.node_main import create_output_publisher

#: Seconds between two log lines of the same kind of rejection or warning, per input.
WARNING_PERIOD = 1.0
#: Seconds between two DiagnosticArrays of a node.
REPORT_PERIOD = 1.0
#: Hardware id of the statuses of a node in the root namespace; a namespaced node's is this
#: followed by its namespace (``stewart_platform/platform_a``), one per platform.
HARDWARE_ID = 'stewart_platform'
#: Longest log line, and longest string of a /diagnostics status (message, key, value), that a
#: node's accounting emits, characters; a longer one is cut, ending with a note of how much.
#: Above the longest reason the core writes itself (a pose that breaks every limit: 34
#: violations, about 3,000 characters), so that only an input echoed whole is ever cut.
MAX_TEXT_LENGTH = 4000
#: Characters of a log line kept for the topic and the counters around a finding's message.
LOG_LINE_ROOM = 200


def bounded(text: str, limit: int = MAX_TEXT_LENGTH) -> str:
    """
    Return ``text``, or if it is longer than ``limit`` its start and a note of what was cut.

    The result is never longer than ``limit`` characters: ``'... [12,345 more characters
    cut]'`` ends a cut one.

    :param text: a log line or a diagnostic string.
    :param limit: the most characters to return (at least 64).
    """
    if len(text) <= limit:
        return text
    kept = limit - len(_cut_note(len(text)))   # the note of the most that can be cut
    return text[:kept] + _cut_note(len(text) - kept)


def _cut_note(count: int) -> str:
    return f'... [{count:,} more characters cut]'


def _reason(finding: Finding) -> str:
    """Return a finding's message for a log line, cut to leave room for the line's counters."""
    return bounded(finding.message, MAX_TEXT_LENGTH - LOG_LINE_ROOM)


class NodeDiagnostics:
    """
    A node's ``/diagnostics`` publisher and its report timer, shared by all its inputs.

    One publisher and one timer per node, not per input: rclpy's executor walks every
    publisher's event handlers and every timer at each wait, so each one costs every message.

    :param node: the rclpy node.
    """

    def __init__(self, node):
        self.node = node
        self.inputs = []
        #: Other statuses in the same array: objects whose ``report()`` returns one.
        self.reporters = []
        namespace = node.get_namespace()
        self.hardware_id = HARDWARE_ID + ('' if namespace == '/' else namespace)
        self.publisher = create_output_publisher(node, DIAGNOSTICS_TOPIC)
        node.create_timer(REPORT_PERIOD, self.publish_report)

    def accounting(self, input_topic: str) -> 'MessageAccounting':
        """Return the accounting of one input topic, reported with the others."""
        accounting = MessageAccounting(self, input_topic)
        self.inputs.append(accounting)
        return accounting

    def publish_report(self):
        """Publish one status per input, then the other reporters', in one array stamped now."""
        array = DiagnosticArray(status=[source.report()
                                        for source in self.inputs + self.reporters])
        array.header.stamp = self.node.get_clock().now().to_msg()
        self.publisher.publish(array)


class MessageAccounting:
    """
    Count the messages of one input: received, published, rejected by code, warned about.

    Made by :meth:`NodeDiagnostics.accounting`.

    :param diagnostics: the node's :class:`NodeDiagnostics`.
    :param input_topic: the topic whose messages are counted, for the status name and the log.
    """

    def __init__(self, diagnostics: NodeDiagnostics, input_topic: str):
        self.diagnostics = diagnostics
        self.node = diagnostics.node
        self.topic = input_topic
        self.status_name = f'{self.node.get_fully_qualified_name()}: {input_topic}'
        self.received = self.published = self.rejected = self.warned = 0
        #: Rejections and warnings counted by their finding's code, since the start.
        self.rejections_by_code = {}
        self.warnings_by_code = {}
        self.last_rejection = self.last_warning = None
        self._reported = (0, 0)
        self._log_throttle = LogThrottle(self.node.get_logger(), WARNING_PERIOD)

    def receive(self):
        """Count a message received."""
        self.received += 1

    def publish(self, publisher, message, *extra):
        """Publish the output of a received message and count it (``extra``: for a command)."""
        publisher.publish(message, *extra)
        self.published += 1

    def use(self):
        """
        Count a message used without an output of its own (fk_node's ``anchor_pose``).

        It counts with the published ones: every message still ends as one output or one
        rejection.
        """
        self.published += 1

    def reject(self, refusal: Finding):
        """
        Count a rejected message by its code and log why (throttled per code).

        :param refusal: the core's finding, or the node's for a message it cannot convert.
        """
        self.rejected += 1
        count = self.rejections_by_code[refusal.code] = (
            self.rejections_by_code.get(refusal.code, 0) + 1)
        self.last_rejection = refusal
        self._log_throttle.log(
            'rejected ' + refusal.code,
            f'{self.topic} rejected: {_reason(refusal)} ({self.rejected} rejected so far, '
            f'{count} of them {refusal.code})')

    def warn(self, warning: Finding):
        """Count a warning about a message that was still used, and log it (throttled per code)."""
        self.warned += 1
        self.warnings_by_code[warning.code] = self.warnings_by_code.get(warning.code, 0) + 1
        self.last_warning = warning
        self._log_throttle.log('warned ' + warning.code, f'{self.topic}: {_reason(warning)}')

    def report(self) -> DiagnosticStatus:
        """
        Return this input's status since the last report.

        ERROR when messages were rejected since then, WARN when only warnings came, else OK.
        The values are the counters since the start: ``received``, ``published``,
        ``rejected``, ``rejected <code>`` and ``warned <code>`` for each code seen, then the
        latest rejection (``last rejection`` and its details) and the latest warning
        (``last warning`` and its details). Each string is :func:`bounded`.
        """
        new_rejections = self.rejected - self._reported[0]
        new_warnings = self.warned - self._reported[1]
        self._reported = (self.rejected, self.warned)
        if new_rejections:
            level = DiagnosticStatus.ERROR
            message = (f'{new_rejections} message(s) rejected since the last report; last: '
                       f'{self.last_rejection.message}')
        elif new_warnings:
            level = DiagnosticStatus.WARN
            message = (f'{new_warnings} warning(s) since the last report; last: '
                       f'{self.last_warning.message}')
        else:
            level, message = DiagnosticStatus.OK, 'running'
        values = [('received', self.received), ('published', self.published),
                  ('rejected', self.rejected)]
        values += [(f'rejected {code}', count)
                   for code, count in sorted(self.rejections_by_code.items())]
        values += [(f'warned {code}', count)
                   for code, count in sorted(self.warnings_by_code.items())]
        for key, finding in (('last rejection', self.last_rejection),
                             ('last warning', self.last_warning)):
            if finding is not None:
                values += [(key, finding.message), *finding.details]
        return DiagnosticStatus(
            level=level, name=self.status_name, message=bounded(message),
            hardware_id=self.diagnostics.hardware_id,
            values=[KeyValue(key=bounded(str(key)), value=bounded(str(value)))
                    for key, value in values])


class LogThrottle:
    """
    Log warnings at most once per period for each kind, saying how many were left out.

    Each line is :func:`bounded` to :data:`MAX_TEXT_LENGTH` characters.

    rclpy's own throttle is per call site, so one flood would hide every other kind of warning
    logged from the same line.

    :param logger: an rclpy logger.
    :param period: seconds between two lines of one kind (monotonic clock).
    """

    def __init__(self, logger, period: float):
        self.logger = logger
        self.period = period
        self._last = {}
        self._skipped = {}

    def log(self, kind: str, message: str):
        """Log ``message`` as a warning unless a line of ``kind`` was logged within the period."""
        now = time.monotonic()
        last = self._last.get(kind)
        if last is not None and now - last < self.period:
            self._skipped[kind] = self._skipped.get(kind, 0) + 1
            return
        skipped = self._skipped.pop(kind, 0)
        self._last[kind] = now
        self.logger.warning(bounded(message + (f' [{skipped} more like it not logged]'
                                               if skipped else '')))
