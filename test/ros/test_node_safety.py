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
In-process tests of the nodes' safety behaviour: limits, bad input, diagnostics, accounting.

Each node is built with config/paper_platform.yaml and config/example_limits.yaml (plus
solver.yaml or table3_ramp.yaml), with parameter overrides where a test needs tighter limits.
A probe node feeds the node's input topic and records its outputs and ``/diagnostics``
(diagnostic_msgs/msg/DiagnosticArray). A refused message must publish no output; the node must
pass on the core's finding (recorded here as the node hands it to its accounting), and the
report on /diagnostics, one a second, must carry the counters, the counts by reason and the
latest reason. The decisions themselves are tested without ROS in test_pose_commands.py and
test_pose_tracker.py.

The poses used against the limits were chosen with the values printed beside them; the
functions of stewart_kinematics.limits that give those values are tested in test_limits.py.
"""

import math
from pathlib import Path
import threading

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import Pose, Twist
from helpers import pose_message, raw_pose_message
import numpy as np
from numpy.testing import assert_allclose
import pytest
import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter
from reference import leg_lengths as plain_lengths, quaternion_from_euler
from std_msgs.msg import Float64MultiArray

from stewart_kinematics import inverse_kinematics, platform_twist
from stewart_kinematics.parameters import load_geometry
from stewart_kinematics.ros import trajectory_node
from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.node_main import create_executor
from stewart_kinematics.ros.trajectory_node import TrajectoryNode
import yaml

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
PLATFORM_FILE = str(CONFIG_DIRECTORY / 'paper_platform.yaml')
LIMITS_FILE = str(CONFIG_DIRECTORY / 'example_limits.yaml')
SOLVER_FILE = str(CONFIG_DIRECTORY / 'solver.yaml')
RAMP_FILE = str(CONFIG_DIRECTORY / 'table3_ramp.yaml')
IK_ARGS = ['--ros-args', '--params-file', PLATFORM_FILE, '--params-file', LIMITS_FILE]
FK_ARGS = IK_ARGS + ['--params-file', SOLVER_FILE]
RAMP_ARGS = IK_ARGS + ['--params-file', RAMP_FILE]

HOME = (0.0, 0.0, 0.4325, 0.0, 0.0, 0.0)
TILTED = (-0.02, 0.03, 0.45, math.radians(-5.0), math.radians(8.0), math.radians(-30.0))
#: Last row of the paper's Table 3: 100 mm, 150 mm, 532.5 mm, 15 deg, -15 deg, 20 deg.
TABLE3_END = (0.1, 0.15, 0.5325, math.radians(15.0), math.radians(-15.0), math.radians(20.0))
#: Second row of Table 3: every leg differs from home by more than 5 mm (about 15 mm).
TABLE3_ROW_1 = (0.01, 0.015, 0.4425, math.radians(1.5), math.radians(-1.5), math.radians(2.0))
#: One step beyond the end of Table 3: legs 0.757 m to 0.854 m, inside example_limits, but
#: leg 4 turns 36.7 deg at its platform joint (limit 35 deg); condition number about 18.
BEYOND_TABLE3 = (0.11, 0.165, 0.5425, math.radians(16.5), math.radians(-16.5),
                 math.radians(22.0))

#: Tighter limits for the IK tests, on top of example_limits.yaml (legs 0.65 m to 0.90 m).
IK_TIGHT_LIMITS = {'base_joint_max_angle_deg': 12.1, 'max_jacobian_condition': 12.0}
#: Raised 0.1875 m: legs 1, 2, 4, 5, 6 are 0.904 m (> 0.90 m), leg 3 0.886 m; joints turn
#: 2.2 deg; condition 11.6.
STROKE_POSE = (0.0, 0.0, 0.62, 0.0, 0.0, 0.0)
#: Moved 0.15 m along x: leg 3 turns 12.14 deg at its base joint (> 12.1 deg), the others at
#: most 12.02 deg; legs 0.713 m to 0.758 m; condition 11.3.
CONE_POSE = (0.15, 0.0, 0.4325, 0.0, 0.0, 0.0)
#: Raised and tilted 15 deg about x and y: condition 13.3 (> 12); joints turn at most 8 deg
#: at the base and 15 deg at the platform; legs 0.699 m to 0.835 m.
SINGULAR_POSE = (0.0, 0.0, 0.5, math.radians(15.0), math.radians(15.0), 0.0)
#: Leg lengths inside example_limits that no pose has (Newton-Raphson diverges from home,
#: and from 2000 random starts none converges).
IMPOSSIBLE_LENGTHS = [0.9, 0.65, 0.9, 0.65, 0.9, 0.65]


# Messages and poses ---------------------------------------------------------------------------

def lengths_message(values):
    """Build a bare Float64MultiArray of leg lengths."""
    return Float64MultiArray(data=[float(v) for v in values])


def paper_geometry():
    """Return the paper's geometry, without limits."""
    return load_geometry(PLATFORM_FILE)


def lengths_of(pose):
    """Return the leg lengths of a pose by closed-form inverse kinematics."""
    return inverse_kinematics(paper_geometry(), np.array(pose, dtype=float))


def assert_pose_message(message, pose, tolerance=1e-9):
    """Check a Pose against (X, Y, Z, alpha, beta, gamma): position, then quaternion."""
    position = [message.position.x, message.position.y, message.position.z]
    orientation = message.orientation
    quaternion = [orientation.x, orientation.y, orientation.z, orientation.w]
    assert_allclose(position, pose[:3], rtol=0.0, atol=tolerance)
    assert_allclose(quaternion, quaternion_from_euler(*pose[3:]), rtol=0.0, atol=tolerance)


# Diagnostics ----------------------------------------------------------------------------------

def values_of(status):
    """Return a DiagnosticStatus's key-value pairs as a dict."""
    return {pair.key: pair.value for pair in status.values}


def counters_of(status):
    """Return the (received, published, rejected) counters a status carries, as integers."""
    values = values_of(status)
    return tuple(int(values[key]) for key in ('received', 'published', 'rejected'))


class Probe:
    """A node that publishes a node's input and records its outputs and /diagnostics."""

    def __init__(self, input_type=None, input_topic=None, outputs=()):
        """Create the probe: ``outputs`` are (topic, type) pairs to record."""
        self.node = Node('safety_probe')
        self.publisher = (None if input_type is None
                          else self.node.create_publisher(input_type, input_topic, 10))
        self.received = {}
        for topic, message_type in outputs:
            self.received[topic] = []
            self.node.create_subscription(message_type, topic, self.received[topic].append, 100)
        self.statuses = []
        self.node.create_subscription(
            DiagnosticArray, '/diagnostics', lambda array: self.statuses.extend(array.status),
            100)

    def statuses_of(self, node, level=None):
        """Return the statuses ``node`` published for its first input, of one level or all."""
        name = node.accounting.status_name
        return [status for status in self.statuses
                if status.name == name and (level is None or status.level == level)]


def record_findings(node):
    """
    Record, in order, every finding the node's inputs reject or warn with.

    :returns: ``(refusals, warnings)``, two lists the node's accountings append to.
    """
    refusals, warnings = [], []
    for accounting in node.accounting.diagnostics.inputs:
        for name, found in (('reject', refusals), ('warn', warnings)):
            original = getattr(accounting, name)

            def record(finding, original=original, found=found):
                found.append(finding)
                original(finding)
            setattr(accounting, name, record)
    return refusals, warnings


@pytest.fixture
def start(node_rig):
    """
    Return a starter of a node and a Probe on one executor, with every topic connected.

    ``start_nodes(node_class, cli_args, overrides, input_type, input_topic, outputs)`` returns
    ``(node, probe, executor)``; ``overrides`` maps parameter names to values.
    """
    def start_nodes(node_class, cli_args, overrides, input_type, input_topic, outputs):
        parameters = [Parameter(name, value=value) for name, value in overrides.items()]
        node = node_rig.add(node_class(cli_args=cli_args, parameter_overrides=parameters))
        probe = Probe(input_type, input_topic, outputs)
        node_rig.add(probe.node)
        recorded = {'/' + topic for topic, _ in outputs}
        watched = [p for p in node.publishers if p.topic_name in recorded]
        assert len(watched) == len(recorded)
        watched.append(node.accounting.diagnostics.publisher)
        [subscription] = [s for s in node.subscriptions if s.topic_name == '/' + input_topic]

        node_rig.connect(lambda: (probe.publisher.get_subscription_count() >= 1
                                  and subscription.get_publisher_count() >= 1
                                  and all(p.get_subscription_count() >= 1 for p in watched)),
                         'node and probe')
        return node, probe, node_rig.executor
    return start_nodes


def start_ik(start, overrides=None):
    """Start an IkNode with the example limits (and ``overrides``) and its probe."""
    return start(IkNode, IK_ARGS, overrides or {}, Pose, 'target_pose',
                 [('leg_lengths', Float64MultiArray), ('leg_extensions', Float64MultiArray)])


def start_fk(start, overrides=None):
    """Start an FkNode with the example limits (and ``overrides``) and its probe."""
    return start(FkNode, FK_ARGS, overrides or {}, Float64MultiArray, 'leg_lengths',
                 [('estimated_pose', Pose)])


def wait_for_report(spin_until, executor, probe, node, received):
    """Spin until a report of the node's first input counts ``received`` messages; return it."""
    def found():
        return [s for s in probe.statuses_of(node) if counters_of(s)[0] == received]
    assert spin_until(executor, found), (
        f'no report with received={received}: '
        f'{[(s.message, values_of(s)) for s in probe.statuses_of(node)]}')
    return found()[0]


# ik_node --------------------------------------------------------------------------------------

def test_ik_refuses_poses_beyond_each_limit_and_says_why(start, spin_until):
    """Stroke, joint cone and singularity margin: no lengths, a reason naming leg and limit."""
    node, probe, executor = start_ik(start, IK_TIGHT_LIMITS)
    refusals, _ = record_findings(node)
    lengths, extensions = probe.received['leg_lengths'], probe.received['leg_extensions']
    for pose in (STROKE_POSE, CONE_POSE, SINGULAR_POSE):
        probe.publisher.publish(pose_message(pose))
    # Poses from one publisher arrive in order: the answer to this good pose comes after any
    # answer to the three bad ones, so one answer of each kind means they produced none.
    probe.publisher.publish(pose_message(HOME))
    assert spin_until(executor, lambda: len(lengths) >= 1 and len(extensions) >= 1)
    assert (len(lengths), len(extensions)) == (1, 1)
    assert_allclose(lengths[0].data, node.geometry.home_leg_lengths, rtol=0.0, atol=1e-12)
    assert_allclose(extensions[0].data, np.zeros(6), rtol=0.0, atol=1e-15)

    stroke, cone, singular = refusals
    for refusal in refusals:
        assert refusal.code == 'out_of_limits'
        assert refusal.message.startswith('the pose is out of the limits: ')

    for leg in (1, 2, 4, 5, 6):
        assert f'leg {leg}: leg_length_max 0.9 m broken by' in stroke.message
        assert f'leg_length_max leg {leg}' in dict(stroke.details)
    assert 'leg 3' not in stroke.message
    assert stroke.message.count('leg_length_max') == 5

    assert 'leg 3: base_joint_max_angle 12.1 deg broken by' in cone.message
    assert cone.message.count('base_joint_max_angle') == 1
    assert dict(cone.details)['base_joint_max_angle leg 3'].endswith(
        'deg (limit 12.1 deg, excess 0.0369 deg)')

    assert 'platform: max_jacobian_condition 12 broken by' in singular.message
    assert 'leg ' not in singular.message
    assert float(dict(singular.details)['max_jacobian_condition'].split()[0]) > 12.0
    assert (node.accounting.received, node.accounting.published,
            node.accounting.rejected) == (4, 1, 3)

    # On /diagnostics: one report a second with the counts by reason and the latest reason.
    report = wait_for_report(spin_until, executor, probe, node, 4)
    values = values_of(report)
    assert report.hardware_id == 'stewart_platform'
    assert counters_of(report) == (4, 1, 3)
    assert values['rejected out_of_limits'] == '3'
    assert values['last rejection'] == singular.message
    assert float(values['max_jacobian_condition'].split()[0]) > 12.0
    errors = probe.statuses_of(node, DiagnosticStatus.ERROR)
    assert errors and 'rejected since the last report; last: the pose is out of the limits' in (
        errors[-1].message)


def test_ik_counts_every_message_as_one_output_or_one_rejection(start, spin_until, capfd):
    """NaN, infinity, zero and NaN quaternions, out of reach: counted refusals, throttled log."""
    node, probe, executor = start_ik(start)
    unit = [0.0, 0.0, 0.0, 1.0]
    good = [pose_message(HOME), pose_message(TILTED), pose_message(TABLE3_END)]
    bad = [
        ('position must be finite', raw_pose_message([math.nan, 0.0, 0.4325], unit)),
        ('position must be finite', raw_pose_message([0.0, 0.0, math.inf], unit)),
        ('position must be finite', raw_pose_message([0.0, -math.inf, 0.4325], unit)),
        ('zero quaternion', raw_pose_message([0.0, 0.0, 0.4325], [0.0, 0.0, 0.0, 0.0])),
        ('quaternion components must be finite',
         raw_pose_message([0.0, 0.0, 0.4325], [0.0, math.nan, 0.0, 1.0])),
        ('quaternion components must be finite',
         raw_pose_message([0.0, 0.0, 0.4325], [math.inf, 0.0, 0.0, 1.0])),
        ('out of the limits', pose_message(STROKE_POSE)),
        ('out of the limits', pose_message((0.0, 0.0, 0.3, 0.0, 0.0, 0.0))),
    ]
    bad_messages = [message for _, message in bad]
    mixed = ([good[0]] + bad_messages[:3] + [good[1]] + bad_messages[3:6] + [good[2]]
             + bad_messages[6:])
    # One at a time: a burst longer than the queues (depth 10) would lose the oldest.
    for count, message in enumerate(mixed, start=1):
        probe.publisher.publish(message)
        assert spin_until(executor, lambda: node.accounting.received >= count)
    report = wait_for_report(spin_until, executor, probe, node, len(mixed))
    assert counters_of(report) == (11, 3, 8)
    assert spin_until(executor, lambda: len(probe.received['leg_extensions']) >= 3)
    assert len(probe.received['leg_lengths']) == 3
    assert len(probe.received['leg_extensions']) == 3
    for message, pose in zip(probe.received['leg_lengths'], (HOME, TILTED, TABLE3_END)):
        assert_allclose(message.data, lengths_of(pose), rtol=0.0, atol=1e-12)

    # Counted by reason: six poses that are no poses, two out of the limits.
    values = values_of(report)
    assert (values['rejected invalid_pose'], values['rejected out_of_limits']) == ('6', '2')
    assert values['last rejection'].startswith('the pose is out of the limits: ')
    assert 'leg_length_min leg 1' in values
    assert [s.level for s in probe.statuses_of(node)].count(DiagnosticStatus.ERROR) >= 1
    # The log says each reason at most once a second, reason by reason: the flood of six
    # invalid poses does not hide the two out of the limits.
    captured = capfd.readouterr()
    log = captured.out + captured.err
    logged = log.count('rejected so far')
    assert 2 <= logged < len(bad), log
    assert 'target_pose rejected: position must be finite' in log, log
    assert 'target_pose rejected: the pose is out of the limits' in log, log


def test_ik_normalises_a_non_unit_quaternion_and_warns_once(start, spin_until, capfd):
    """Quaternions of norm 2, 0.5 and 3 give the unit one's lengths; one warning in the log."""
    node, probe, executor = start_ik(start)
    lengths = probe.received['leg_lengths']
    for count, scale in enumerate((1.0, 2.0, 0.5, -3.0), start=1):
        probe.publisher.publish(pose_message(TILTED, scale=scale))
        assert spin_until(executor, lambda: len(lengths) >= count), f'{len(lengths)} answers'
    for message in lengths[1:]:
        assert_allclose(message.data, lengths[0].data, rtol=0.0, atol=1e-12)
    assert_allclose(lengths[0].data, lengths_of(TILTED), rtol=0.0, atol=1e-12)
    assert (node.accounting.received, node.accounting.published,
            node.accounting.rejected) == (4, 4, 0)
    captured = capfd.readouterr()
    log = captured.out + captured.err
    assert log.count('normalised') == 1, log
    assert 'orientation has norm 2, not 1: normalised' in log


#: A pose that puts platform joint 1 exactly on base joint 1 (identity rotation, position
#: b_1 - p_1 of the paper's Tables 1 and 2): leg 1 has length 0.0 and no direction.
JOINT_ON_JOINT_POSITION = (0.1000019, 0.0787127, -0.275)


@pytest.mark.parametrize('overrides', [{}, {'max_jacobian_condition': 50.0}],
                         ids=['no limits', 'only max_jacobian_condition'])
def test_ik_refuses_a_pose_with_a_zero_length_leg(start, spin_until, overrides):
    """
    A platform joint on its base joint: refused with the reason, the node stays up.

    With only the singularity margin set, the limit check used to divide by the zero length
    inside the callback (ZeroDivisionError out of the executor); now the pose is refused.
    """
    node, probe, executor = start(IkNode, IK_ARGS[:3], overrides, Pose, 'target_pose',
                                  [('leg_lengths', Float64MultiArray)])
    refusals, _ = record_findings(node)
    geometry = node.geometry
    assert_allclose(np.array(JOINT_ON_JOINT_POSITION) + geometry.platform_joints[0],
                    geometry.base_joints[0], rtol=0.0, atol=0.0)
    lengths = probe.received['leg_lengths']
    probe.publisher.publish(raw_pose_message(JOINT_ON_JOINT_POSITION, [0.0, 0.0, 0.0, 1.0]))
    probe.publisher.publish(pose_message(TILTED))
    assert spin_until(executor, lambda: len(lengths) >= 1)
    assert len(lengths) == 1
    assert_allclose(lengths[0].data, lengths_of(TILTED), rtol=0.0, atol=1e-12)
    [refusal] = refusals
    assert refusal.code == 'unreachable'
    assert 'leg lengths must be finite and positive' in refusal.message
    assert 'a platform joint on its base joint' in refusal.message
    assert (node.accounting.received, node.accounting.published,
            node.accounting.rejected) == (2, 1, 1)


@pytest.mark.parametrize('cli_args', [IK_ARGS[:3], IK_ARGS], ids=['no limits', 'example limits'])
def test_ik_refuses_a_finite_pose_whose_leg_lengths_overflow(start, spin_until, cli_args):
    """Positions of 1e200 m and 1e155 m (legs overflow to inf): refused, the node keeps going."""
    node, probe, executor = start(IkNode, cli_args, {}, Pose, 'target_pose',
                                  [('leg_lengths', Float64MultiArray)])
    refusals, _ = record_findings(node)
    lengths = probe.received['leg_lengths']
    unit = [0.0, 0.0, 0.0, 1.0]
    probe.publisher.publish(raw_pose_message([0.0, 0.0, 1e200], unit))
    probe.publisher.publish(raw_pose_message([1e155, 0.0, 0.4325], unit))
    # Poses from one publisher arrive in order: one answer to this one means none to those.
    probe.publisher.publish(pose_message(HOME))
    assert spin_until(executor, lambda: len(lengths) >= 1)
    assert len(lengths) == 1
    assert_allclose(lengths[0].data, node.geometry.home_leg_lengths, rtol=0.0, atol=1e-12)
    assert [refusal.code for refusal in refusals] == ['unreachable'] * 2
    for refusal in refusals:
        assert 'finite and positive' in refusal.message, refusal.message
    assert (node.accounting.received, node.accounting.published,
            node.accounting.rejected) == (3, 1, 2)


def test_run_time_parameter_changes_are_validated(ros):
    """An invalid value is refused with a reason and the old value stays; geometry is fixed."""
    ik = IkNode(cli_args=IK_ARGS)
    fk = FkNode(cli_args=FK_ARGS)
    try:
        [result] = ik.set_parameters([Parameter('leg_length_max', value=2.0)])
        assert not result.successful
        assert 'leg_length_max' in result.reason
        assert ik.get_parameter('leg_length_max').value == 0.9
        assert ik.geometry.leg_length_max == 0.9

        for name, value in (('near_singularity_condition', 0.5),
                            ('assembly_guard_position_change', 0.0),
                            ('assembly_guard_angle_change_deg', 200.0),
                            ('max_iterations', 0)):
            old = getattr(fk.tracker.settings, name)
            [result] = fk.set_parameters([Parameter(name, value=value)])
            assert not result.successful, name
            assert name in result.reason and repr(value) in result.reason, result.reason
            assert fk.get_parameter(name).value == old
            assert getattr(fk.tracker.settings, name) == old
        # A value of the wrong type is refused by rclpy itself, before the validator.
        [result] = fk.set_parameters([Parameter('tolerance', value='small')])
        assert not result.successful and 'type' in result.reason
        assert fk.tracker.settings.tolerance == fk.get_parameter('tolerance').value == 1e-12

        for name, value in (('near_singularity_condition', 50.0), ('pose_tolerance', 1e-8)):
            [result] = fk.set_parameters([Parameter(name, value=value)])
            assert result.successful, result.reason
            assert getattr(fk.tracker.settings, name) == value
    finally:
        ik.destroy_node()
        fk.destroy_node()


# fk_node --------------------------------------------------------------------------------------

def test_fk_publishes_no_pose_for_lengths_it_cannot_solve(start, spin_until):
    """Out of the limits, impossible, non-convergent, pose out of the limits: refused, no pose."""
    node, probe, executor = start_fk(start)
    refusals, _ = record_findings(node)
    poses = probe.received['estimated_pose']

    def refuse(values, count):
        probe.publisher.publish(lengths_message(values))
        assert spin_until(executor, lambda: len(refusals) >= count), (
            f'{len(refusals)} of {count} refusals')
        return refusals[-1]

    too_long = refuse([0.95] * 6, 1)
    assert too_long.code == 'out_of_limits'
    assert too_long.message.startswith('the leg lengths are out of the limits: ')
    for leg in range(1, 7):
        assert f'leg {leg}: leg_length_max 0.9 m broken by 0.05 m' in too_long.message
        assert f'leg_length_max leg {leg}' in dict(too_long.details)

    impossible = refuse(IMPOSSIBLE_LENGTHS, 2)
    assert impossible.code == 'no_solution'
    assert impossible.message.startswith('no pose found for leg lengths [0.9, 0.65, 0.9')
    values = dict(impossible.details)
    assert int(values['iterations']) >= 1
    assert float(values['residual_m']) > 1e-3

    beyond = refuse(lengths_of(BEYOND_TABLE3), 3)
    assert beyond.message.startswith('the pose of these leg lengths is out of the limits: ')
    assert 'leg 4: platform_joint_max_angle 35 deg broken by' in beyond.message
    assert 'platform_joint_max_angle leg 4' in dict(beyond.details)

    [result] = node.set_parameters([Parameter('max_iterations', value=1)])
    assert result.successful, result.reason
    slow = refuse(lengths_of(TABLE3_END), 4)
    assert 'no convergence within 1 iterations' in slow.message
    values = dict(slow.details)
    assert values['iterations'] == '1'
    assert float(values['residual_m']) > node.tracker.settings.tolerance
    assert poses == []

    [result] = node.set_parameters([Parameter('max_iterations', value=50)])
    assert result.successful, result.reason
    probe.publisher.publish(lengths_message(lengths_of(TABLE3_END)))
    assert spin_until(executor, lambda: len(poses) >= 1)
    assert len(poses) == 1
    assert_pose_message(poses[0], TABLE3_END)
    assert (node.accounting.received, node.accounting.published,
            node.accounting.rejected) == (5, 1, 4)

    report = wait_for_report(spin_until, executor, probe, node, 5)
    values = values_of(report)
    assert counters_of(report) == (5, 1, 4)
    assert (values['rejected out_of_limits'], values['rejected no_solution']) == ('2', '2')
    assert values['last rejection'] == slow.message
    assert values['iterations'] == '1'
    # Condition about 17 is below the default near_singularity_condition of 100: no warning.
    assert not [s for s in probe.statuses_of(node) if 'near a singularity' in s.message]
    # But the lengths with no solution broke the chain of solutions: the pose may be another
    # assembly mode's until the tracker is re-anchored (test_ambiguity.py).
    assert values['last warning'].startswith('the estimate may be in another assembly mode')
    assert values['cause'] == 'no_solution'


def test_fk_warns_near_a_singularity_and_still_publishes(start, spin_until):
    """With near_singularity_condition 5 (home is about 9.5) the home pose comes with a WARN."""
    node, probe, executor = start_fk(start, {'near_singularity_condition': 5.0})
    refusals, warnings = record_findings(node)
    poses = probe.received['estimated_pose']
    probe.publisher.publish(lengths_message(lengths_of(HOME)))

    def warned():
        return [s for s in probe.statuses_of(node, DiagnosticStatus.WARN)
                if 'near a singularity' in s.message]
    assert spin_until(executor, lambda: len(poses) >= 1 and warned())
    assert_pose_message(poses[0], HOME)
    [warning] = warned()
    values = values_of(warning)
    assert float(values['jacobian_condition']) == pytest.approx(9.54, abs=0.01)
    assert values['warned near_singularity'] == '1'
    # Beyond the singularity margin the estimate is also flagged ambiguous (test_ambiguity.py).
    assert values['warned ambiguous_estimate'] == '1'
    assert [finding.code for finding in warnings] == ['near_singularity', 'ambiguous_estimate']
    assert 'near_singularity_condition 5' in warnings[0].message
    assert refusals == []
    assert (node.accounting.received, node.accounting.published,
            node.accounting.rejected) == (1, 1, 0)


def test_fk_refuses_a_jump_to_another_solution(start, spin_until):
    """Unchanged lengths solved 0.1 m from the last pose are refused; then the node moves on."""
    node, probe, executor = start_fk(start)
    refusals, _ = record_findings(node)
    poses = probe.received['estimated_pose']
    home_lengths = lengths_of(HOME)
    probe.publisher.publish(lengths_message(home_lengths))
    assert spin_until(executor, lambda: len(poses) >= 1)
    assert_allclose(node.tracker.last_lengths, home_lengths, rtol=0.0, atol=0.0)
    # The tracker believes the platform 0.1 m along x, as if it had followed another branch.
    believed = np.array(HOME) + [0.1, 0.0, 0.0, 0.0, 0.0, 0.0]
    node.tracker.last_pose, node.tracker.last_solution = believed, None
    probe.publisher.publish(lengths_message(home_lengths))
    assert spin_until(executor, lambda: len(refusals) >= 1)
    [jump] = refusals
    assert jump.code == 'assembly_mode_jump'
    assert 'another assembly mode' in jump.message
    assert 'the solution jumped 0.1 m and ' in jump.message
    assert (node.accounting.received, node.accounting.published,
            node.accounting.rejected) == (2, 1, 1)
    assert_allclose(node.tracker.last_pose, believed, rtol=0.0, atol=0.0)
    # Lengths 15 mm away are a motion, not a jump: solved and published.
    probe.publisher.publish(lengths_message(lengths_of(TABLE3_ROW_1)))
    assert spin_until(executor, lambda: len(poses) >= 2)
    assert len(poses) == 2
    assert_pose_message(poses[1], TABLE3_ROW_1)


def test_fk_refuses_a_twist_beyond_the_singularity_margin(start, spin_until):
    """
    Leg velocities at a pose beyond the margin give no twist, with the reason; within, one.

    With near_singularity_condition 5 the home pose (condition about 9.5) is beyond the margin:
    there the leg velocities would hardly determine the twist (the defect: 1 mm/s on every leg
    turned into 4300 rad/s near the singularity, and fk_node published it).
    """
    node, probe, executor = start(FkNode, FK_ARGS, {'near_singularity_condition': 5.0},
                                  Float64MultiArray, 'leg_velocities',
                                  [('estimated_twist', Twist)])
    refusals, _ = record_findings(node)
    twists = probe.received['estimated_twist']
    velocities = lengths_message([0.001] * 6)
    probe.publisher.publish(velocities)
    assert spin_until(executor, lambda: len(refusals) >= 1)
    [refusal] = refusals
    assert refusal.code == 'near_singularity'
    assert 'above the limit 5 (the singularity margin' in refusal.message
    [result] = node.set_parameters([Parameter('near_singularity_condition', value=100.0)])
    assert result.successful, result.reason
    probe.publisher.publish(velocities)
    assert spin_until(executor, lambda: len(twists) >= 1)
    assert len(twists) == 1
    expected = platform_twist(paper_geometry(), HOME, [0.001] * 6)
    twist = twists[0]
    assert_allclose([twist.linear.x, twist.linear.y, twist.linear.z, twist.angular.x,
                     twist.angular.y, twist.angular.z], expected, rtol=0.0, atol=1e-15)
    accounting = node.velocity_accounting
    assert (accounting.received, accounting.published, accounting.rejected) == (2, 1, 1)


# trajectory_node ------------------------------------------------------------------------------

def ramp_pose(fraction):
    """Return the Table 3 ramp's pose a fraction 0..1 of the way from its start to its end."""
    return tuple(h + fraction * (e - h) for h, e in zip(HOME, TABLE3_END))


def assert_refusal_lists(message, failing, times, samples):
    """Check a refusal: count, then each failing sample (10 at most) with index and time."""
    assert message.startswith(
        f'ramp refused: {len(failing)} of {samples} samples break the limits of the geometry')
    lines = message.splitlines()[1:]
    listed = failing[:10]
    for line, index in zip(lines, listed):
        assert line.strip().startswith(f'sample {index} at t={times[index]:.3f} s, pose ')
        assert 'leg_length_max 0.8 m broken by' in line
    if len(failing) > 10:
        assert lines[-1].strip() == f'... and {len(failing) - 10} more'
        assert len(lines) == 11
    else:
        assert len(lines) == len(failing)


@pytest.fixture
def ramp_probe(ros):
    """Return a probe node recording target_pose, on its own executor."""
    executor = create_executor()
    probe = Probe(outputs=[('target_pose', Pose)])
    executor.add_node(probe.node)
    yield probe, executor
    executor.shutdown()
    probe.node.destroy_node()


def test_trajectory_refuses_a_ramp_that_breaks_a_limit(ramp_probe, spin_until):
    """With legs of at most 0.80 m rows 7 to 10 fail: ValueError listing them, nothing played."""
    probe, executor = ramp_probe
    failing = [row for row in range(11) if max(plain_lengths(ramp_pose(row / 10.0))) > 0.80]
    assert failing == [7, 8, 9, 10]
    overrides = [Parameter('leg_length_max', value=0.80), Parameter('row_period', value=0.02),
                 Parameter('start_delay', value=0.0)]
    with pytest.raises(ValueError) as raised:
        TrajectoryNode(cli_args=RAMP_ARGS, parameter_overrides=overrides)
    message = str(raised.value)
    assert_refusal_lists(message, failing, [0.02 * row for row in range(11)], 11)
    assert 'sample 6 ' not in message
    assert 'leg 3: leg_length_max 0.8 m' in message.splitlines()[1]
    assert not spin_until(executor, lambda: probe.received['target_pose'], timeout=0.3)
    assert probe.node.count_publishers('/target_pose') == 0


def test_trajectory_plays_a_ramp_within_the_example_limits(ramp_probe, spin_until):
    """The example limits keep the whole Table 3 ramp: its 11 rows are played."""
    probe, executor = ramp_probe
    overrides = [Parameter('row_period', value=0.02), Parameter('start_delay', value=0.0),
                 Parameter('min_subscribers', value=1)]
    node = TrajectoryNode(cli_args=RAMP_ARGS, parameter_overrides=overrides)
    try:
        executor.add_node(node)
        poses = probe.received['target_pose']
        assert spin_until(executor, lambda: len(poses) >= 11), f'{len(poses)} of 11 rows'
        assert_pose_message(poses[0], HOME)
        assert_pose_message(poses[10], TABLE3_END)
    finally:
        executor.remove_node(node)
        node.destroy_node()


def test_trajectory_checks_every_sample_in_interpolate_mode(ramp_probe):
    """Interpolate mode checks its own samples: 41 over 4 s, failing ones listed by time."""
    duration, rate = 4.0, 10.0
    times = np.append(np.arange(0.0, duration, 1.0 / rate), duration)
    assert len(times) == 41
    failing = [index for index, time in enumerate(times)
               if max(plain_lengths(ramp_pose(time / duration))) > 0.80]
    assert len(failing) > 10
    overrides = [Parameter('leg_length_max', value=0.80), Parameter('mode', value='interpolate'),
                 Parameter('duration', value=duration), Parameter('publish_rate', value=rate)]
    with pytest.raises(ValueError) as raised:
        TrajectoryNode(cli_args=RAMP_ARGS, parameter_overrides=overrides)
    assert_refusal_lists(str(raised.value), failing, times, 41)


def test_trajectory_main_returns_1_for_a_refused_ramp(tmp_path, capfd):
    """main() logs the refusal, with the failing samples, and returns 1."""
    tight = tmp_path / 'tight_limits.yaml'
    tight.write_text(yaml.safe_dump({'/**': {'ros__parameters': {'leg_length_max': 0.8}}}),
                     encoding='utf-8')
    arguments = ['trajectory_node'] + RAMP_ARGS + ['--params-file', str(tight)]
    # A node that wrongly plays the ramp would spin forever: stop it after a deadline.
    watchdog = threading.Timer(10.0, rclpy.try_shutdown)
    watchdog.start()
    try:
        code = trajectory_node.main(arguments)
    finally:
        watchdog.cancel()
    assert code == 1
    assert not rclpy.ok()
    captured = capfd.readouterr()
    log = captured.out + captured.err
    assert 'cannot start: ramp refused: 4 of 11 samples' in log
    assert 'sample 7 at t=7.000 s' in log
