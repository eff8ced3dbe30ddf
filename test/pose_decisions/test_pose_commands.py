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
Unit tests of stewart_kinematics.pose_decisions.pose_commands.CommandCheck (pure numpy, no ROS).

Expected leg lengths are computed here from the paper's tables, leg by leg with the textbook
rotation matrices; leg velocities are checked against central differences of those lengths.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics import (
    ActuatorLimits,
    CommandCheck,
    FrameTree,
    Geometry,
    PoseLimits,
    Transform,
)

pytestmark = pytest.mark.core

#: Tables 1 and 2 of the paper: base and platform joints, metres, as in paper_platform.yaml.
#: Written as the file writes them (not millimetres / 1000), so that a joint can sit exactly on
#: another.
BASE = np.array([(0.0486989, 0.2196666, 0.0), (0.1658874, 0.1520078, 0.0),
                 (0.1658874, -0.1520078, 0.0), (0.0486989, -0.2196666, 0.0),
                 (-0.2145863, -0.0676588, 0.0), (-0.2145863, 0.0676588, 0.0)])
PLATFORM = np.array([(-0.051303, 0.1409539, 0.275), (0.1477212, 0.0260472, 0.275),
                     (0.1477212, -0.0260472, 0.257), (-0.051303, -0.1409539, 0.275),
                     (-0.0964181, -0.1149067, 0.275), (-0.0964181, 0.1149067, 0.275)])
HOME = (0.0, 0.0, 0.4325, 0.0, 0.0, 0.0)
TILTED = (-0.02, 0.03, 0.45, math.radians(-5.0), math.radians(8.0), math.radians(-30.0))
#: Limits of config/example_limits.yaml.
EXAMPLE_LIMITS = {'leg_length_min': 0.65, 'leg_length_max': 0.9,
                  'base_joint_max_angle': math.radians(35.0),
                  'platform_joint_max_angle': math.radians(35.0),
                  'max_jacobian_condition': 50.0}


def geometry(**limits):
    """Build the paper's platform with the given limits (cone angles in radians)."""
    return Geometry(base_joints=BASE, platform_joints=PLATFORM, home_pose=np.array(HOME),
                    limits=PoseLimits(**limits))


rotation_zyx = reference.rotation_zyx


def lengths_by_hand(position, rotation):
    """|t + R p_i - b_i| leg by leg, for this module's joint tables."""
    return reference.leg_lengths_of_matrix(position, rotation, BASE, PLATFORM)


def test_an_allowed_pose_gives_its_leg_lengths():
    """Position and matrix, or the pose vector: the lengths of the paper's equation 1."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    rotation = rotation_zyx(*TILTED[3:])
    command = check.pose(TILTED[:3], rotation)
    assert command.accepted and command.reason == '' and command.violations == ()
    assert_allclose(command.lengths, lengths_by_hand(TILTED[:3], rotation), rtol=0.0,
                    atol=1e-15)
    assert_allclose(check.pose_vector(TILTED).lengths, command.lengths, rtol=0.0, atol=1e-15)


def test_a_pose_from_a_quaternion_is_the_pose_of_its_matrix():
    """pose_quaternion normalises (x, y, z, w) as geometry_msgs has it, and refuses a zero one."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    quaternion = 3.0 * reference.quaternion_from_euler(*TILTED[3:])   # not unit
    command = check.pose_quaternion(TILTED[:3], quaternion)
    assert command.accepted
    assert_allclose(command.lengths, lengths_by_hand(TILTED[:3], rotation_zyx(*TILTED[3:])),
                    rtol=0.0, atol=1e-14)
    zero = check.pose_quaternion(TILTED[:3], (0.0, 0.0, 0.0, 0.0))
    assert not zero.accepted and zero.refusal.code == 'invalid_pose'
    assert check.pose_quaternion((0.0, math.nan, 0.45), quaternion).refusal.code == 'invalid_pose'


def test_a_pose_beyond_the_limits_is_refused_with_every_violation():
    """Raised 0.1875 m: legs 1, 2, 4, 5, 6 beyond 0.9 m, each listed; nothing to command."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    raised = (0.0, 0.0, 0.62, 0.0, 0.0, 0.0)
    expected = lengths_by_hand(raised[:3], np.eye(3))
    assert [leg for leg in range(1, 7) if expected[leg - 1] > 0.9] == [1, 2, 4, 5, 6]
    command = check.pose_vector(raised)
    assert not command.accepted and command.lengths is None
    assert command.refusal.code == 'out_of_limits'
    assert [(v.limit, v.leg) for v in command.violations] == [
        ('leg_length_max', leg) for leg in (1, 2, 4, 5, 6)]
    for leg in (1, 2, 4, 5, 6):
        assert f'leg {leg}: leg_length_max 0.9 m broken by' in command.reason
        value = dict(command.refusal.details)[f'leg_length_max leg {leg}']
        assert value.startswith(f'{expected[leg - 1]:.6g} m')
    assert check.last_pose is None


@pytest.mark.parametrize('limits', [{}, {'max_jacobian_condition': 50.0}, EXAMPLE_LIMITS],
                         ids=['no limits', 'only max_jacobian_condition', 'example limits'])
def test_a_platform_joint_on_its_base_joint_is_refused_not_raised(limits):
    """Leg 1 of length exactly 0 has no direction: refused as unreachable, never a 0 length."""
    check = CommandCheck(geometry(**limits))
    position = BASE[0] - PLATFORM[0]
    assert lengths_by_hand(position, np.eye(3))[0] == 0.0
    command = check.pose(position, np.eye(3))
    assert not command.accepted and command.lengths is None
    assert command.refusal.code == 'unreachable'
    assert 'a platform joint on its base joint' in command.reason


@pytest.mark.parametrize('position', [(0.0, 0.0, 1e200), (1e155, 0.0, 0.4325)])
def test_a_pose_whose_lengths_overflow_is_refused(position):
    """Lengths that overflow to inf are never commanded."""
    command = CommandCheck(geometry(**EXAMPLE_LIMITS)).pose(position, np.eye(3))
    assert command.refusal.code == 'unreachable'
    assert 'finite and positive' in command.reason


@pytest.mark.parametrize('position, rotation, words', [
    ((math.nan, 0.0, 0.4), np.eye(3), 'position must be finite'),
    ((0.0, math.inf, 0.4), np.eye(3), 'position must be finite'),
    ((0.0, 0.0, 0.4), np.full((3, 3), math.nan), 'rotation must be finite'),
    ((0.0, 0.0, 0.4), 2.0 * np.eye(3), 'rotation must be a rotation matrix'),
    ((0.0, 0.0, 0.4), np.diag([1.0, 1.0, -1.0]), 'determinant +1'),
    ((0.0, 0.4), np.eye(3), 'expected a position (3,)'),
    ((0.0, 0.0, 0.4), np.eye(4), 'rotation matrix (3, 3)'),
])
def test_a_malformed_pose_is_refused_with_what_is_wrong(position, rotation, words):
    """NaN, infinity, a matrix that is no rotation, wrong shapes: invalid_pose, with words."""
    command = CommandCheck(geometry(**EXAMPLE_LIMITS)).pose(position, rotation)
    assert command.refusal.code == 'invalid_pose'
    assert words in command.reason


def test_a_malformed_pose_vector_is_refused():
    """Five numbers or a NaN angle in the pose vector: invalid_pose."""
    check = CommandCheck(geometry())
    for pose in ([0.0] * 5, [0.0, 0.0, 0.4, math.nan, 0.0, 0.0]):
        assert check.pose_vector(pose).refusal.code == 'invalid_pose'


def test_no_finite_pose_raises_or_gives_a_bad_length():
    """
    4000 finite poses from 1e-300 m to 1e300 m and angles to 1e6 rad, every limit set.

    Each comes back accepted with six finite, positive lengths, or refused with a reason.
    """
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    generator = np.random.default_rng(9)
    magnitudes = 10.0 ** generator.uniform(-300.0, 300.0, size=(4000, 6))
    poses = magnitudes * generator.choice([-1.0, 1.0], size=(4000, 6))
    poses[:1000, :3] = HOME[:3] + generator.uniform(-0.3, 0.3, size=(1000, 3))
    poses[:1000, 3:] = generator.uniform(-1.0, 1.0, size=(1000, 3))
    accepted = 0
    for pose in poses:
        command = check.pose_vector(pose)
        if command.accepted:
            accepted += 1
            assert np.all(np.isfinite(command.lengths)) and np.all(command.lengths > 0.0)
        else:
            assert command.lengths is None and command.reason
    assert accepted > 0


def test_twist_gives_the_rates_of_the_lengths_at_the_last_accepted_pose():
    """Leg velocities match central differences of the lengths; a refused pose changes nothing."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    before = check.twist([0.01, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert not before.accepted and before.refusal.code == 'no_pose_yet'
    rotation = rotation_zyx(*TILTED[3:])
    assert check.pose(TILTED[:3], rotation).accepted
    assert not check.pose_vector((0.0, 0.0, 0.62, 0.0, 0.0, 0.0)).accepted
    twist = np.array([0.02, -0.01, 0.03, 0.2, -0.1, 0.3])
    command = check.twist(twist)
    assert command.accepted

    def lengths_at(time):
        # Rotation by the angle vector w * time (Rodrigues), applied in the base frame.
        turn = reference.rotation_vector_matrix(twist[3:] * time)
        return lengths_by_hand(np.array(TILTED[:3]) + twist[:3] * time, turn @ rotation)
    step = 1e-6
    expected = (lengths_at(step) - lengths_at(-step)) / (2.0 * step)
    assert_allclose(command.velocities, expected, rtol=0.0, atol=1e-9)


@pytest.mark.parametrize('twist', [[0.0] * 5, [math.nan, 0.0, 0.0, 0.0, 0.0, 0.0]])
def test_a_malformed_twist_is_refused(twist):
    """Five numbers or NaN: invalid_twist."""
    check = CommandCheck(geometry())
    assert check.pose_vector(HOME).accepted
    command = check.twist(twist)
    assert command.refusal.code == 'invalid_twist' and command.velocities is None


def test_a_pose_given_by_quaternion_is_the_same_pose():
    """(x, y, z, w) of Rz(0.3): the lengths of the matrix; scaled by -2, the same; zero refused."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    position = (0.01, -0.02, 0.45)
    quaternion = (0.0, 0.0, math.sin(0.15), math.cos(0.15))
    expected = lengths_by_hand(position, rotation_zyx(0.0, 0.0, 0.3))
    for scale in (1.0, -2.0):
        command = check.pose_quaternion(position, np.multiply(scale, quaternion))
        assert command.accepted
        assert_allclose(command.lengths, expected, rtol=0.0, atol=1e-15)
    for bad, words in (((0.0, 0.0, 0.0, 0.0), 'zero quaternion'),
                       ((math.nan, 0.0, 0.0, 1.0), 'must be finite'),
                       ((0.0, 0.0, 1.0), 'shape')):
        command = check.pose_quaternion(position, bad)
        assert command.refusal.code == 'invalid_pose' and words in command.reason
    refused = check.pose_quaternion((math.inf, 0.0, 0.45), quaternion)
    assert 'position must be finite' in refused.reason


# Twists against the leg velocity limit ----------------------------------------------------

#: The speed limits of config/example_limits.yaml.
SPEEDS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)


def checked_at(pose, **options):
    """Return a CommandCheck with the example limits and speeds, at an accepted ``pose``."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS), SPEEDS, **options)
    assert check.pose_vector(pose).accepted
    return check


def test_a_twist_within_the_velocity_limit_gives_its_leg_velocities():
    """1 cm/s along x: the rows [u_i, R p_i x u_i] of test/reference.py times the twist."""
    check = checked_at(TILTED)
    twist = np.array([0.01, 0.0, 0.0, 0.0, 0.0, 0.02])
    command = check.twist(twist)
    assert command.accepted and command.scale == 1.0 and command.warnings == ()
    expected = reference.twist_jacobian(TILTED, BASE, PLATFORM) @ twist
    assert_allclose(command.velocities, expected, rtol=0.0, atol=1e-15)
    assert np.max(np.abs(command.velocities)) < 0.05


def test_a_twist_beyond_the_velocity_limit_is_refused_naming_each_leg():
    """1 m/s: every leg faster than 0.05 m/s is listed; nothing to command."""
    check = checked_at(TILTED)
    twist = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    expected = reference.twist_jacobian(TILTED, BASE, PLATFORM) @ twist
    command = check.twist(twist)
    assert not command.accepted and command.velocities is None
    assert command.refusal.code == 'too_fast'
    fast = [leg for leg in range(1, 7) if abs(expected[leg - 1]) > 0.05]
    assert fast and [key for key, _ in command.refusal.details] == [
        f'leg_velocity_max leg {leg}' for leg in fast]
    for leg in fast:
        assert f'leg {leg}: leg_velocity_max 0.05 m/s broken by' in command.reason


@pytest.mark.parametrize('twist', [
    [1.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 3.0, -2.0, 1.0],
    [0.03, -0.04, 0.02, 0.1, 0.2, -0.3], [999.0, -999.0, 999.0, 999.0, -999.0, 999.0]])
def test_a_twist_scaled_to_the_limit_never_exceeds_it_and_keeps_its_direction(twist):
    """With twist_over_limit 'scale': the fastest leg exactly at 0.05 m/s, never above."""
    check = checked_at(TILTED, twist_over_limit='scale')
    twist = np.array(twist)
    unscaled = reference.twist_jacobian(TILTED, BASE, PLATFORM) @ twist
    command = check.twist(twist)
    assert command.accepted
    assert np.max(np.abs(command.velocities)) <= 0.05
    if np.max(np.abs(unscaled)) > 0.05:
        assert np.max(np.abs(command.velocities)) == pytest.approx(0.05, rel=1e-14)
        assert command.scale == pytest.approx(0.05 / np.max(np.abs(unscaled)), rel=1e-12)
        assert_allclose(command.velocities, command.scale * unscaled, rtol=1e-12, atol=1e-18)
        [warning] = command.warnings
        assert warning.code == 'twist_scaled' and dict(warning.details)['scale']
    else:
        assert command.scale == 1.0


@pytest.mark.parametrize('policy', ['refuse', 'scale'])
@pytest.mark.parametrize('twist, words', [
    ([1e308, 0.0, 0.0, 0.0, 0.0, 0.0], 'no motion of a platform'),
    ([0.0, 0.0, 0.0, 0.0, 0.0, -1e4], 'no motion of a platform'),
    ([math.nan, 0.0, 0.0, 0.0, 0.0, 0.0], 'six finite numbers'),
    ([0.0, math.inf, 0.0, 0.0, 0.0, 0.0], 'six finite numbers'),
    ([0.0] * 7, 'six finite numbers')],
    ids=['1e308', '1e4 rad/s', 'nan', 'inf', 'seven'])
def test_a_twist_that_is_no_motion_is_refused_whatever_the_policy(policy, twist, words):
    """NaN, inf, 1e308 or absurd speeds: invalid_twist with the reason, never scaled."""
    command = checked_at(TILTED, twist_over_limit=policy).twist(twist)
    assert command.refusal.code == 'invalid_twist' and words in command.reason
    assert command.velocities is None


def test_an_unknown_twist_policy_is_refused():
    """Only 'refuse' and 'scale'."""
    with pytest.raises(ValueError, match='twist_over_limit must be one of'):
        CommandCheck(geometry(), SPEEDS, twist_over_limit='clamp')


# ik_node's whole decision on a message: frames and quaternions ------------------------------

def test_tool_pose_accepts_the_base_and_user_frames_and_refuses_others():
    """A pose in an unknown frame is wrong_frame; the user frame moves it; '' is the base."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    user = Transform.from_pose([0.01, 0.0, 0.0, 0.0, 0.0, 0.0])
    frames = FrameTree(user_frame='work', user_pose=user)
    quaternion = reference.quaternion_from_euler(*TILTED[3:])
    in_base = check.tool_pose(TILTED[:3], quaternion, frames, '')
    assert in_base.accepted
    assert_allclose(in_base.position, TILTED[:3], rtol=0.0, atol=0.0)
    in_user = check.tool_pose(np.subtract(TILTED[:3], [0.01, 0.0, 0.0]), quaternion, frames,
                              'work')
    assert in_user.accepted
    assert_allclose(in_user.lengths, in_base.lengths, rtol=0.0, atol=1e-15)
    wrong = check.tool_pose(TILTED[:3], quaternion, frames, 'map')
    assert wrong.refusal.code == 'wrong_frame' and "'map'" in wrong.reason


def test_tool_pose_normalises_a_quaternion_with_a_warning():
    """Norm 2: the unit quaternion's lengths, and a quaternion_not_unit warning."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    quaternion = reference.quaternion_from_euler(*TILTED[3:])
    unit = check.tool_pose(TILTED[:3], quaternion)
    doubled = check.tool_pose(TILTED[:3], 2.0 * quaternion)
    assert unit.warnings == () and doubled.accepted
    assert_allclose(doubled.lengths, unit.lengths, rtol=0.0, atol=1e-15)
    [warning] = doubled.warnings
    assert warning.code == 'quaternion_not_unit' and 'norm 2, not 1: normalised' in warning.message
    refused = check.tool_pose((0.0, 0.0, 0.62), 2.0 * quaternion)   # out of the stroke too
    assert refused.refusal.code == 'out_of_limits' and refused.warnings == doubled.warnings


def test_a_message_quaternion_is_checked_once_and_converted_as_the_gate_converts_it(monkeypatch):
    """
    tool_pose checks the quaternion where it enters, and converts it as before, to the bit.

    Issue 28: it was normalised (and checked) by tool_pose, then twice more on the way to the
    rotation matrix. The matrix must stay the one the command gate computes for what a node
    sends on (platform_of_tool_message), so that the two agree exactly.
    """
    from stewart_kinematics.pose_decisions import pose_commands
    from stewart_kinematics.limits import command_gate
    frames = FrameTree(user_frame='work', user_pose=Transform.from_pose([0.01] + [0.0] * 5))
    cases = [(quaternion, frame_id) for frame_id in ('', 'work') for quaternion in (
        reference.quaternion_from_euler(*TILTED[3:]),
        2.0 * reference.quaternion_from_euler(*TILTED[3:]),
        np.array([1e-3, -2e-3, 0.5, 3.0]), np.array([0.0, 0.0, 0.0, 1e200]),
        np.array([0.1, 0.2, 0.3, 0.4]) * (1.0 + 1e-7))]
    expected = [command_gate.platform_of_tool_message(np.array(TILTED[:3]), quaternion, frames,
                                                      frame_id) for quaternion, frame_id in cases]
    calls = []
    for module in (pose_commands, command_gate):
        def counted(quaternion, normalise=module.normalize_quaternion):
            calls.append(1)
            return normalise(quaternion)
        monkeypatch.setattr(module, 'normalize_quaternion', counted)
    check = CommandCheck(geometry())
    for (quaternion, frame_id), (position, rotation) in zip(cases, expected):
        calls.clear()
        command = check.tool_pose(TILTED[:3], quaternion, frames, frame_id)
        assert len(calls) == 1, frame_id
        assert np.array_equal(command.position, position)
        assert np.array_equal(command.rotation, rotation)
    for bad in ([0.0] * 4, [math.nan, 0.0, 0.0, 1.0], [1.0, 2.0, 3.0]):
        refusal = check.tool_pose(TILTED[:3], bad).refusal
        assert refusal.code == 'invalid_pose', bad


def test_a_pose_vector_is_checked_once_and_its_matrix_is_euler_zyx_to_matrix(monkeypatch):
    """The angles checked by pose_vector are not checked again; the same matrix to the bit."""
    from stewart_kinematics.model import rotations
    poses = np.vstack([reference.random_poses(20, seed=43), [TILTED, HOME]])
    expected = [rotations.euler_zyx_to_matrix(pose[3:]) for pose in poses]
    check = CommandCheck(geometry())
    monkeypatch.setattr(rotations, '_euler_angles', lambda angles: pytest.fail('checked again'))
    for pose, rotation in zip(poses, expected):
        command = check.pose_vector(pose)
        assert np.array_equal(command.rotation, rotation)
    assert check.pose_vector([0.0, 0.0, 0.45, math.nan, 0.0, 0.0]).refusal.code == 'invalid_pose'


def test_a_refused_pose_reports_where_the_platform_would_have_been():
    """Markers show a refused pose: position, rotation and the legs at fault are given."""
    check = CommandCheck(geometry(**EXAMPLE_LIMITS))
    command = check.pose_vector((0.0, 0.0, 0.62, 0.0, 0.0, 0.0))
    assert_allclose(command.position, (0.0, 0.0, 0.62), rtol=0.0, atol=0.0)
    assert_allclose(command.rotation, np.eye(3), rtol=0.0, atol=0.0)
    assert command.legs_at_fault == (1, 2, 4, 5, 6)


def test_the_twist_policy_parameter_takes_refuse_or_scale():
    """twist_over_limit is checked by its spec: 'refuse' (the default) or 'scale'."""
    from stewart_kinematics.parameters import StreamingSettings
    assert StreamingSettings().twist_over_limit == 'refuse'
    assert StreamingSettings(twist_over_limit='scale').twist_over_limit == 'scale'
    with pytest.raises(ValueError, match='twist_over_limit'):
        StreamingSettings(twist_over_limit='clamp')
