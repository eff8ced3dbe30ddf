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
fk_node as a process: the assembly-mode margin on /diagnostics, and an ambiguous start refused.

The lengths are those of the end of the paper's Table 3, computed here with the leg formula
written out in numpy. There the nearest other real mode lies 0.2385 m and 135.3 deg away
(combined distance 0.427 m; test_assembly_modes.py checks it against a multi-start search).
"""

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import Pose
import pytest
from reference import leg_lengths, TABLE_3_END
from std_msgs.msg import Float64MultiArray

pytestmark = pytest.mark.process

CLIENT_DEPTH = 100
SETTLE_TIME = 0.5
MARGIN_STATUS = '/fk_node: assembly mode margin'
LENGTHS_STATUS = '/fk_node: leg_lengths'


class FkProcess:
    """fk_node as a process with extra parameters, and the client's endpoints."""

    def __init__(self, client, start_node, config_directory, parameters):
        arguments = ['--ros-args',
                     '--params-file', str(config_directory / 'paper_platform.yaml'),
                     '--params-file', str(config_directory / 'solver.yaml')]
        for name, value in parameters.items():
            arguments += ['-p', f'{name}:={value}']
        self.process = start_node('fk_node', arguments)
        self.client = client
        self.statuses = {}
        self.poses = []
        node = client.node
        node.create_subscription(DiagnosticArray, '/diagnostics', self.on_diagnostics,
                                 CLIENT_DEPTH)
        node.create_subscription(Pose, 'estimated_pose', self.poses.append, CLIENT_DEPTH)
        self.publisher = node.create_publisher(Float64MultiArray, 'leg_lengths', CLIENT_DEPTH)
        client.wait(lambda: self.publisher.get_subscription_count() >= 1,
                    'fk_node subscribed to leg_lengths', [self.process])
        client.spin_for(SETTLE_TIME)

    def on_diagnostics(self, array):
        for status in array.status:
            self.statuses.setdefault(status.name, []).append(status)

    def publish(self, lengths):
        self.publisher.publish(Float64MultiArray(data=[float(value) for value in lengths]))

    def wait_for_status(self, name, condition, what):
        self.client.wait(lambda: any(condition(status) for status in self.statuses.get(name, [])),
                         what, [self.process])
        return next(status for status in self.statuses[name] if condition(status))


def values_of(status):
    return {item.key: item.value for item in status.values}


def test_margin_reported_on_diagnostics_and_warned_below_the_parameter(
        client, start_node, config_directory):
    fk = FkProcess(client, start_node, config_directory, {
        'assembly_mode_margin_period': 0.2, 'assembly_mode_margin_warning': 1.0})
    fk.publish(leg_lengths(TABLE_3_END))
    status = fk.wait_for_status(MARGIN_STATUS, lambda s: 'margin_position_m' in values_of(s),
                                'the assembly-mode margin on /diagnostics')
    values = values_of(status)
    assert float(values['margin_position_m']) == pytest.approx(0.2385, abs=1e-3)
    assert float(values['margin_angle_deg']) == pytest.approx(135.3, abs=0.1)
    assert values['modes_within_limits'] == '4'
    assert values['search_complete'] == 'True'
    # 0.427 m combined < 1.0 m: a warning with the distances.
    assert status.level == DiagnosticStatus.WARN
    assert '0.2385 m and 135.3 deg' in status.message
    assert len(fk.poses) == 1   # the pose itself went out as usual


def test_ambiguous_start_refused_with_the_reason(client, start_node, config_directory):
    fk = FkProcess(client, start_node, config_directory, {'refuse_ambiguous_start': 'true'})
    fk.publish(leg_lengths(TABLE_3_END))
    status = fk.wait_for_status(
        LENGTHS_STATUS, lambda s: 'rejected ambiguous_assembly_mode' in values_of(s),
        'the ambiguous start rejected on /diagnostics')
    assert status.level == DiagnosticStatus.ERROR
    assert '4 assembly modes lie within the limits' in status.message
    assert fk.poses == []
