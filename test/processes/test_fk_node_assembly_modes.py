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
fk_node as a process: the assembly-mode margin, an ambiguous start, and the ambiguity flag.

The lengths are those of the end of the paper's Table 3, computed here with the leg formula
written out in numpy. There the nearest other real mode lies 0.2385 m and 135.3 deg away
(combined distance 0.427 m; test_assembly_modes.py checks it against a multi-start search).
And those of issue 27's sweep (the home pose turned in yaw from 0 to -120 degrees, through a
fold near -89.6 degrees, where the tracker goes on in the other assembly mode:
test_ambiguity.py).
"""

import math

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import Pose, PoseStamped
import numpy as np
import pytest
from reference import (
    HOME,
    leg_lengths,
    quaternion_from_euler,
    quaternion_matrix,
    rotation_angle,
    rotation_zyx,
    TABLE_3_END,
)
from std_msgs.msg import Float64MultiArray
from std_srvs.srv import Trigger

pytestmark = pytest.mark.process

CLIENT_DEPTH = 100
SETTLE_TIME = 0.5
MARGIN_STATUS = '/fk_node: assembly mode margin'
LENGTHS_STATUS = '/fk_node: leg_lengths'
AMBIGUITY_STATUS = '/fk_node: assembly mode ambiguity'
ANCHOR_STATUS = '/fk_node: anchor_pose'


class FkProcess:
    """fk_node as a process with extra parameters, and the client's endpoints."""

    def __init__(self, client, start_node, config_directory, parameters, files=()):
        arguments = ['--ros-args']
        for name in ('paper_platform.yaml', 'solver.yaml', *files):
            arguments += ['--params-file', str(config_directory / name)]
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

    def sweep(self, degrees):
        """Publish the lengths of each yaw, one at a time, each answered by a pose."""
        for angle in degrees:
            count = len(self.poses)
            self.publish(leg_lengths(yawed(angle)))
            self.client.wait(lambda: len(self.poses) > count, f'the pose of yaw {angle} deg',
                             [self.process])

    def next_status(self, name, condition, what):
        """Wait for a status of ``name`` that arrives from now on and meets ``condition``."""
        self.statuses[name] = []
        return self.wait_for_status(name, condition, what)

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


def yawed(degrees):
    """Return the home pose turned ``degrees`` about z: (X, Y, Z, alpha, beta, gamma)."""
    return HOME[:5] + (math.radians(degrees),)


def pose_errors(message, truth):
    """Position (m) and rotation angle (deg) from a Pose message to a pose."""
    position = [message.position.x, message.position.y, message.position.z]
    orientation = message.orientation
    quaternion = [orientation.x, orientation.y, orientation.z, orientation.w]
    return (math.dist(position, truth[:3]), math.degrees(
        rotation_angle(quaternion_matrix(*quaternion), rotation_zyx(*truth[3:]))))


def test_the_fold_sweep_is_flagged_on_diagnostics_until_reset_or_anchored(
        client, start_node, config_directory):
    """
    fk_node warns from the fold on; reset_tracker and a known pose on anchor_pose clear it.

    The status is WARN and every pose is counted with the warning; after the anchor the node
    follows the true mode.
    """
    fk = FkProcess(client, start_node, config_directory, {})
    degrees = np.linspace(0.0, -120.0, 241)
    ok = fk.wait_for_status(AMBIGUITY_STATUS, lambda s: s.level == DiagnosticStatus.OK,
                            'the ambiguity status, OK before any motion')
    assert values_of(ok)['ambiguous'] == 'False'
    fk.sweep(degrees)
    position, angle = pose_errors(fk.poses[-1], yawed(-120.0))
    assert position == pytest.approx(0.0398, abs=1e-4) and angle == pytest.approx(60.77, abs=0.01)
    warned = fk.next_status(AMBIGUITY_STATUS, lambda s: s.level == DiagnosticStatus.WARN,
                            'the ambiguity status at WARN')
    values = values_of(warned)
    assert values['ambiguous'] == 'True' and values['cause'] in ('near_singularity',
                                                                 'assembly_mode_margin')
    assert 're-anchor' in warned.message
    lengths_status = fk.next_status(
        LENGTHS_STATUS, lambda s: 'warned ambiguous_estimate' in values_of(s),
        'the ambiguous estimates counted')
    # From -86.5 deg on: 68 of the 241 poses at least (the margin may flag earlier).
    assert int(values_of(lengths_status)['warned ambiguous_estimate']) >= 68

    service = client.node.create_client(Trigger, 'reset_tracker')
    client.wait(service.service_is_ready, 'reset_tracker offered', [fk.process])
    future = service.call_async(Trigger.Request())
    client.wait(future.done, 'reset_tracker answered', [fk.process])
    assert future.result().success
    cleared = fk.next_status(AMBIGUITY_STATUS, lambda s: s.level == DiagnosticStatus.OK,
                             'the ambiguity status OK after reset_tracker')
    assert values_of(cleared)['anchored_by'] == 'a reset'

    fk.sweep(degrees)
    fk.next_status(AMBIGUITY_STATUS, lambda s: s.level == DiagnosticStatus.WARN,
                   'the ambiguity status at WARN again')
    anchor = client.node.create_publisher(PoseStamped, 'anchor_pose', CLIENT_DEPTH)
    client.wait(lambda: anchor.get_subscription_count() >= 1, 'fk_node subscribed anchor_pose',
                [fk.process])
    known = PoseStamped()
    known.header.frame_id = 'stewart_base'
    truth = yawed(-120.0)
    known.pose.position.x, known.pose.position.y, known.pose.position.z = truth[:3]
    (known.pose.orientation.x, known.pose.orientation.y, known.pose.orientation.z,
     known.pose.orientation.w) = quaternion_from_euler(*truth[3:])
    anchor.publish(known)
    cleared = fk.next_status(AMBIGUITY_STATUS, lambda s: s.level == DiagnosticStatus.OK,
                             'the ambiguity status OK after anchor_pose')
    assert values_of(cleared)['anchored_by'] == 'a known pose'
    fk.sweep(np.linspace(-120.5, -125.0, 10))
    assert pose_errors(fk.poses[-1], yawed(-125.0))[0] < 1e-9
    anchor_status = fk.next_status(ANCHOR_STATUS, lambda s: values_of(s)['received'] == '1',
                                   'the anchor counted')
    assert values_of(anchor_status)['published'] == '1'
    # A known pose in a frame fk_node cannot place is refused with the reason.
    known.header.frame_id = 'camera'
    anchor.publish(known)
    refused = fk.next_status(ANCHOR_STATUS, lambda s: s.level == DiagnosticStatus.ERROR,
                             'the anchor in a wrong frame refused')
    assert "frame 'camera'" in refused.message
    assert values_of(refused)['rejected wrong_frame'] == '1'
    fk.next_status(AMBIGUITY_STATUS, lambda s: s.level == DiagnosticStatus.OK,
                   'the ambiguity status still OK')


def test_a_margin_that_rules_out_every_other_mode_clears_the_flag(
        client, start_node, config_directory):
    """
    Within the example limits the end of Table 3 has one real mode: its margin re-anchors.

    Lengths with no solution break the chain (flagged); the same lengths as before then come
    again, whose margin (computed once, the lengths unchanged) finds no other mode.
    """
    fk = FkProcess(client, start_node, config_directory,
                   {'assembly_mode_margin_period': 0.2}, files=('example_limits.yaml',))
    fk.publish(leg_lengths(TABLE_3_END))
    fk.wait_for_status(MARGIN_STATUS, lambda s: values_of(s).get('modes_within_limits') == '1',
                       'the margin: one mode within the limits')
    fk.publish([0.9, 0.65, 0.9, 0.65, 0.9, 0.65])
    warned = fk.next_status(AMBIGUITY_STATUS, lambda s: s.level == DiagnosticStatus.WARN,
                            'the ambiguity status at WARN after a solve that failed')
    assert values_of(warned)['cause'] == 'no_solution'
    fk.publish(leg_lengths(TABLE_3_END))
    cleared = fk.next_status(AMBIGUITY_STATUS, lambda s: s.level == DiagnosticStatus.OK,
                             'the ambiguity status OK after the margin')
    assert values_of(cleared)['anchored_by'] == (
        'pose 2, where no other real assembly mode lay within the limits')
    assert len(fk.poses) == 2
