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
The second bound of issue 27, where a node emits text: its log lines and /diagnostics strings.

The core describes a large input by a preview (test_input_preview.py); here a finding of ten
million characters, as no core message is any more, goes through a node's accounting
(:mod:`stewart_kinematics.ros.message_accounting`) on a real rclpy node: every log line and
every string of the status comes out at most ``MAX_TEXT_LENGTH`` characters, says how much was
cut, and the status keeps its layout and counters. And the bound cuts nothing the core writes
itself: the reason of a pose that breaks nearly every limit fits whole in a log line.
"""

from pathlib import Path

import numpy as np
import pytest

from stewart_kinematics import CommandCheck, findings
from stewart_kinematics.findings import Finding
from stewart_kinematics.parameters import load_geometry
from stewart_kinematics.ros.message_accounting import (
    bounded,
    LOG_LINE_ROOM,
    MAX_TEXT_LENGTH,
    NodeDiagnostics,
)

pytestmark = pytest.mark.node

#: Characters of the oversized finding.
LONG = 10 ** 7
CONFIG = Path(__file__).resolve().parents[2] / 'config'


class RecordingLogger:
    """A logger that keeps its warnings."""

    def __init__(self):
        """Start with no line."""
        self.lines = []

    def warning(self, message):
        """Keep a warning."""
        self.lines.append(message)


def test_bounded_keeps_short_text_and_cuts_long_text_to_the_limit():
    assert bounded('x' * MAX_TEXT_LENGTH) == 'x' * MAX_TEXT_LENGTH
    for length in (MAX_TEXT_LENGTH + 1, 12_345, LONG):
        text = bounded('y' * length)
        assert len(text) <= MAX_TEXT_LENGTH
        kept = text.index('.')
        assert text.endswith(f'... [{length - kept:,} more characters cut]')
    assert len(bounded('z' * 500, 100)) <= 100


def test_a_huge_finding_gives_bounded_log_lines_and_diagnostics(ros):
    node = ros.create_node('accounting_bound_test')
    try:
        diagnostics = NodeDiagnostics(node)
        accounting = diagnostics.accounting('leg_lengths')
        logger = RecordingLogger()
        accounting._log_throttle.logger = logger
        accounting.receive()
        accounting.reject(Finding(findings.INVALID_LENGTHS, 'v' * LONG, (('detail', 'd' * LONG),)))
        accounting.receive()
        accounting.warn(Finding(findings.QUATERNION_NOT_UNIT, 'w' * LONG))
        status = accounting.report()
    finally:
        node.destroy_node()
    assert len(logger.lines) == 2
    for line in logger.lines:
        assert len(line) <= MAX_TEXT_LENGTH and 'more characters cut]' in line
    assert logger.lines[0].startswith('leg_lengths rejected: vvv')
    assert logger.lines[0].endswith('(1 rejected so far, 1 of them invalid_lengths)')
    assert len(status.message) <= MAX_TEXT_LENGTH and status.message.startswith('1 message(s)')
    values = {pair.key: pair.value for pair in status.values}
    assert list(values) == ['received', 'published', 'rejected', 'rejected invalid_lengths',
                            'warned quaternion_not_unit', 'last rejection', 'detail',
                            'last warning']
    assert (values['received'], values['published'], values['rejected']) == ('2', '0', '1')
    for key, value in values.items():
        assert len(value) <= MAX_TEXT_LENGTH, key
    for key in ('last rejection', 'detail', 'last warning'):
        assert values[key].endswith('more characters cut]'), key


def test_the_longest_reason_the_core_writes_is_not_cut():
    """Poses far beyond every limit (up to 29 violations, 2,400 characters) fit in a log line."""
    check = CommandCheck(load_geometry([CONFIG / 'paper_platform.yaml',
                                        CONFIG / 'example_limits.yaml']))
    rng = np.random.default_rng(27)
    poses = np.column_stack([rng.uniform(-0.6, 0.6, (3000, 2)), rng.uniform(0.0, 1.2, 3000),
                             rng.uniform(-1.5, 1.5, (3000, 3))])
    longest = max((check.pose_vector(pose) for pose in poses),
                  key=lambda command: len(command.reason or ''))
    assert len(longest.violations) >= 25 and len(longest.reason) > 2000
    assert len(longest.reason) <= MAX_TEXT_LENGTH - LOG_LINE_ROOM
