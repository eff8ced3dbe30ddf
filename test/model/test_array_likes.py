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
Array-likes at every public entry point of the core: each one works, or is refused in words.

The rule (doc/python_api.md, :func:`stewart_kinematics.model.arrays.as_float_array`): an
argument is what ``numpy.asarray`` makes of it, as a plain array. An ``np.matrix`` is its 2-D
array (six lengths in a matrix have shape (1, 6): refused where (6,) is expected, one pose
where a batch (N, 6) is taken); a masked array with a masked entry is refused, naming the
masked entries (a masked value is no number to use); one with nothing masked is its data, as
are objects with ``__array__`` (pandas), memoryviews and ``array.array``; generators, strings,
bytes, dicts, ragged lists and objects whose ``__array__`` fails are refused.

Each entry point gets each array-like made from a valid argument (and from one with a zero, a
NaN or a negative entry). A decision object must never raise: it accepts, or refuses with a
reason in the package's words. A function must answer as it does for the equivalent plain
array, or raise ``ValueError`` (never IndexError, TypeError or numpy's own message).
"""

import array
import dataclasses
import math
import warnings

from hypothesis import given, strategies as st
import numpy as np
from properties import budget, LIMITED, NUMPY_WORDS, PAPER
import pytest

from stewart_kinematics import (
    ActuatorInterface,
    ActuatorLimits,
    assembly_mode_margin,
    assembly_modes,
    calibrate,
    CommandCheck,
    CommandFilter,
    euler_zyx_to_matrix,
    euler_zyx_to_quaternion,
    forward_kinematics,
    FrameTree,
    Geometry,
    inverse_kinematics,
    jacobian,
    leg_lengths,
    leg_vectors,
    leg_velocities,
    LimitModel,
    matrix_to_euler_zyx,
    matrix_to_quaternion,
    measurement_poses,
    MotionPlanner,
    orientation_workspace,
    platform_twist,
    PoseTracker,
    PoseTrajectory,
    quaternion_to_euler_zyx,
    quaternion_to_matrix,
    Ramp,
    TimedTrajectory,
    Transform,
    travel_ranges,
    twist_jacobian,
    workspace_slice,
    workspace_volume,
)
from stewart_kinematics import limits
from stewart_kinematics.cueing import MotionCueing
from stewart_kinematics.findings import Decision, Finding
from stewart_kinematics.model.arrays import as_float_array

pytestmark = pytest.mark.core

#: numpy's own words, beyond those of properties.NUMPY_WORDS: no refusal may speak them.
MORE_NUMPY_WORDS = ('not aligned', 'same number of dimensions', 'boolean index',
                    'values to unpack', 'must be a string or a real number',
                    'could not convert string', 'would be ambiguous', 'truth value',
                    'matmul', 'dimension(s)', 'out of bounds', 'object is not iterable')

HOME = PAPER.home_pose
HOME_LENGTHS = PAPER.home_leg_lengths
POSITION = HOME[:3]
ROTATION = euler_zyx_to_matrix([0.05, -0.03, 0.1])
QUATERNION = np.array([0.0, 0.0, math.sin(0.05), math.cos(0.05)])
TWIST = np.array([0.01, -0.02, 0.005, 0.03, 0.0, -0.01])
LIMITS = ActuatorLimits(0.05, 0.25, 2.5)


class ArrayLike:
    """A pandas-like object: no ndarray, its numbers come from ``__array__``."""

    def __init__(self, values):
        self.values = values

    def __array__(self, dtype=None, copy=None):
        return np.asarray(self.values, dtype=dtype)


class BrokenArray:
    """An object whose ``__array__`` fails (a closed data source)."""

    def __array__(self, dtype=None, copy=None):
        raise RuntimeError('the data source is closed')

    def __repr__(self):
        return 'BrokenArray()'


# What each variant must do: as the valid value itself, as the plain array numpy makes of it,
# refused naming its masked entries, or refused.
SAME, PLAIN, MASKED, REFUSED = 'same', 'plain', 'masked', 'refused'


def matrix(values):
    """Return the values as an ``np.matrix``, without its pending deprecation warning."""
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', PendingDeprecationWarning)
        return np.matrix(values)


def variants(good):
    """
    Array-likes made from a valid argument ``good``: ``(name, value, expected)`` triples.

    :param good: the valid argument, an array of one to three dimensions (matrices for two at
        most).
    """
    good = np.array(good, dtype=float)
    flat = good.ravel().tolist()
    masked_first = np.zeros(good.shape, dtype=bool)
    masked_first.flat[0] = True
    nan_first = good.copy()
    nan_first.flat[0] = math.nan
    if good.ndim == 1:
        ragged = [flat[:1], flat[1:]]
        list_with_masked = [np.ma.masked] + flat[1:]
    else:
        ragged = good.tolist()
        ragged[-1] = ragged[-1][:-1]
        row_mask = masked_first[0]
        list_with_masked = [np.ma.masked_array(row, mask=row_mask) for row in good]
    found = [
        ('tuple', tuple(good.tolist()), SAME),
        ('object array', good.astype(object), SAME),
        ('__array__ object', ArrayLike(good), SAME),
        ('memoryview', memoryview(good.copy()), SAME),
        ('masked, none masked', np.ma.masked_array(good, mask=False), SAME),
        ('masked, one masked', np.ma.masked_array(good, mask=masked_first), MASKED),
        ('masked NaN', np.ma.masked_array(nan_first, mask=masked_first), MASKED),
        ('list holding a masked value', list_with_masked, MASKED),
        ('generator', (value for value in flat), REFUSED),
        ('string', str(flat), REFUSED),
        ('bytes', good.tobytes(), REFUSED),
        ('dict', dict(enumerate(flat)), REFUSED),
        ('ragged list', ragged, REFUSED),
        ('broken __array__', BrokenArray(), REFUSED),
    ]
    for entry, name in ((0.0, 'zero'), (math.nan, 'NaN'), (-1.0, 'negative')):
        bad = good.copy()
        bad.flat[0] = entry
        found.append((f'masked array with an unmasked {name}', np.ma.masked_array(bad), PLAIN))
        if good.ndim <= 2:    # a matrix has two dimensions
            found.append((f'matrix with a {name}', matrix(bad), PLAIN))
    if good.ndim <= 2:
        found += [
            ('matrix', matrix(good), PLAIN),
            ('masked matrix', np.ma.masked_array(matrix(good), mask=False), PLAIN),
            ('masked matrix, one masked', np.ma.masked_array(
                matrix(good), mask=np.atleast_2d(masked_first)), MASKED)]
    if good.ndim == 1:
        found.append(('array.array', array.array('d', flat), SAME))
    return found


def plain(value):
    """Return the plain array numpy makes of ``value`` (its data, for a masked array)."""
    return np.asarray(np.ma.getdata(value))


# The entry points: name, kind, the call with the value in one argument, and a valid value.
DECISION, FUNCTION = 'decision', 'function'


def cueing_step(**arguments):
    """Return a fresh MotionCueing's decision on one sample (at rest but for ``arguments``)."""
    sample = {'time': 0.0, 'specific_force': [0.0, 0.0, 9.81], 'angular_velocity': [0.0] * 3}
    sample.update(arguments)
    return MotionCueing(LIMITED).cue(**sample)


def filter_target(lengths):
    """Return a fresh CommandFilter's answer to a target."""
    return CommandFilter(LIMITS, 0.01, LIMITED.home_leg_lengths, LIMITED).set_target(lengths)


def filter_reset(lengths):
    """Return a fresh CommandFilter's answer to a reset."""
    return CommandFilter(LIMITS, 0.01, LIMITED.home_leg_lengths, LIMITED).reset(lengths)


def tracker_update(lengths):
    """Return a fresh PoseTracker's estimate."""
    return PoseTracker(LIMITED).update(lengths)


def tracker_update_twist(velocities):
    """
    Return a fresh PoseTracker's twist of an update with leg velocities, or why there is none.

    The pose is accepted whatever the velocities are; velocities it cannot use leave the
    estimate without a twist and with a warning, here the refusal.
    """
    estimate = PoseTracker(LIMITED).update(LIMITED.home_leg_lengths, velocities)
    assert estimate.accepted, estimate.reason
    if estimate.twist is None:
        (warning,) = estimate.warnings
        return warning
    return estimate


def checked_twist(twist):
    """Return a fresh CommandCheck's leg velocities for a twist at home."""
    check = CommandCheck(LIMITED, LIMITS)
    check.pose_vector(LIMITED.home_pose)
    return check.twist(twist)


def checked_tool_twist(twist):
    """Return a fresh CommandCheck's leg velocities for a twist about a tool point, at home."""
    check = CommandCheck(LIMITED, LIMITS)
    check.pose_vector(LIMITED.home_pose)
    return check.tool_twist(twist, FrameTree(tool_pose=Transform([0.0, 0.0, 0.1], np.eye(3))))


PATH_POSITIONS = np.array([[0.0, 0.0, 0.45], [0.01, 0.0, 0.45], [0.01, 0.01, 0.46]])
PATH_QUATERNIONS = np.array([[0.0, 0.0, 0.0, 1.0]] * 3)


def planned_path(positions=PATH_POSITIONS, quaternions=PATH_QUATERNIONS):
    """Return a MotionPlanner's plan of a path."""
    return MotionPlanner(LIMITED, LIMITS).plan_path(positions, quaternions)


def planned_trajectory(times=(0.0, 1.0, 2.0), positions=PATH_POSITIONS,
                       quaternions=PATH_QUATERNIONS):
    """Return a MotionPlanner's plan of timed waypoints."""
    return MotionPlanner(LIMITED, LIMITS).plan_trajectory(times, positions, quaternions)


CALIBRATION_POSES = measurement_poses(PAPER, 30).poses
CALIBRATION_POSITIONS = inverse_kinematics(PAPER, CALIBRATION_POSES)
TIMED = TimedTrajectory.as_given(PoseTrajectory.from_poses([0.0, 1.0], [HOME, HOME + 0.01]))
TOOL_FRAMES = FrameTree(tool_frame='tool', tool_pose=Transform.from_pose(
    [0.0, 0.0, 0.1, 0.0, 0.0, 0.0]))


ENTRY_POINTS = [
    # Decision objects: they never raise.
    ('CommandCheck.pose_vector', DECISION, lambda v: CommandCheck(LIMITED).pose_vector(v),
     LIMITED.home_pose),
    ('CommandCheck.pose position', DECISION, lambda v: CommandCheck(LIMITED).pose(v, ROTATION),
     POSITION),
    ('CommandCheck.pose rotation', DECISION, lambda v: CommandCheck(LIMITED).pose(POSITION, v),
     ROTATION),
    ('CommandCheck.pose_quaternion position', DECISION,
     lambda v: CommandCheck(LIMITED).pose_quaternion(v, QUATERNION), POSITION),
    ('CommandCheck.pose_quaternion quaternion', DECISION,
     lambda v: CommandCheck(LIMITED).pose_quaternion(POSITION, v), QUATERNION),
    ('CommandCheck.tool_pose position', DECISION,
     lambda v: CommandCheck(LIMITED).tool_pose(v, QUATERNION), POSITION),
    ('CommandCheck.tool_pose quaternion', DECISION,
     lambda v: CommandCheck(LIMITED).tool_pose(POSITION, v), QUATERNION),
    ('CommandCheck.twist', DECISION, checked_twist, TWIST),
    ('CommandCheck.tool_twist', DECISION, checked_tool_twist, TWIST),
    ('PoseTracker.update', DECISION, tracker_update, LIMITED.home_leg_lengths),
    ('PoseTracker.update velocities', DECISION,
     tracker_update_twist, [0.001] * 6),
    ('PoseTracker.twist', DECISION, lambda v: PoseTracker(LIMITED).twist(v), [0.001] * 6),
    ('CommandFilter.set_target', DECISION, filter_target, LIMITED.home_leg_lengths + 0.01),
    ('CommandFilter.reset', DECISION, filter_reset, LIMITED.home_leg_lengths + 0.01),
    ('MotionCueing.cue specific_force', DECISION,
     lambda v: cueing_step(specific_force=v), [0.5, 0.0, 9.81]),
    ('MotionCueing.cue angular_velocity', DECISION,
     lambda v: cueing_step(angular_velocity=v), [0.0, 0.1, 0.0]),
    ('MotionPlanner.plan_path positions', DECISION, lambda v: planned_path(positions=v),
     PATH_POSITIONS),
    ('MotionPlanner.plan_path quaternions', DECISION, lambda v: planned_path(quaternions=v),
     PATH_QUATERNIONS),
    ('MotionPlanner.plan_trajectory times', DECISION, lambda v: planned_trajectory(times=v),
     [0.0, 1.0, 2.0]),
    # Functions: they raise ValueError for what they cannot use.
    ('PoseTracker.reset', FUNCTION, lambda v: PoseTracker(LIMITED).reset(v), LIMITED.home_pose),
    ('CommandFilter lengths', FUNCTION, lambda v: CommandFilter(LIMITS, 0.01, v, LIMITED),
     LIMITED.home_leg_lengths),
    ('inverse_kinematics', FUNCTION, lambda v: inverse_kinematics(PAPER, v), HOME),
    ('inverse_kinematics batch', FUNCTION, lambda v: inverse_kinematics(PAPER, v),
     [HOME, HOME + 0.01]),
    ('forward_kinematics', FUNCTION, lambda v: forward_kinematics(PAPER, v), HOME_LENGTHS),
    ('forward_kinematics batch', FUNCTION, lambda v: forward_kinematics(PAPER, v),
     [HOME_LENGTHS, HOME_LENGTHS + 0.01]),
    ('forward_kinematics initial_guess', FUNCTION,
     lambda v: forward_kinematics(PAPER, HOME_LENGTHS, v), HOME),
    ('leg_lengths position', FUNCTION, lambda v: leg_lengths(PAPER, v, ROTATION), POSITION),
    ('leg_lengths rotation', FUNCTION, lambda v: leg_lengths(PAPER, POSITION, v), ROTATION),
    ('leg_vectors position', FUNCTION, lambda v: leg_vectors(PAPER, v, ROTATION), POSITION),
    ('jacobian', FUNCTION, lambda v: jacobian(PAPER, v), HOME),
    ('twist_jacobian rotation', FUNCTION, lambda v: twist_jacobian(PAPER, POSITION, v),
     ROTATION),
    ('leg_velocities poses', FUNCTION, lambda v: leg_velocities(PAPER, v, TWIST), HOME),
    ('leg_velocities twists', FUNCTION, lambda v: leg_velocities(PAPER, HOME, v), TWIST),
    ('platform_twist velocities', FUNCTION, lambda v: platform_twist(PAPER, HOME, v),
     [0.001] * 6),
    ('euler_zyx_to_matrix', FUNCTION, euler_zyx_to_matrix, [0.1, 0.2, 0.3]),
    ('euler_zyx_to_quaternion', FUNCTION, euler_zyx_to_quaternion, [0.1, 0.2, 0.3]),
    ('matrix_to_euler_zyx', FUNCTION, matrix_to_euler_zyx, ROTATION),
    ('matrix_to_quaternion', FUNCTION, matrix_to_quaternion, ROTATION),
    ('quaternion_to_matrix', FUNCTION, quaternion_to_matrix, QUATERNION),
    ('quaternion_to_euler_zyx', FUNCTION, quaternion_to_euler_zyx, QUATERNION),
    ('LimitModel.check_pose position', FUNCTION,
     lambda v: LimitModel(LIMITED).check_pose(v, ROTATION), POSITION),
    ('LimitModel.check_pose rotation', FUNCTION,
     lambda v: LimitModel(LIMITED).check_pose(POSITION, v), ROTATION),
    ('LimitModel.check_poses', FUNCTION, lambda v: LimitModel(LIMITED).check_poses(v),
     [HOME, HOME + 0.01]),
    ('LimitModel.check_pose_matrices positions', FUNCTION,
     lambda v: LimitModel(LIMITED).check_pose_matrices(v, [ROTATION]), [POSITION]),
    ('LimitModel.check_leg_states lengths', FUNCTION,
     lambda v: LimitModel(LIMITED, LIMITS).check_leg_states(lengths=v), HOME_LENGTHS),
    ('LimitModel.leg_state_violations velocities', FUNCTION,
     lambda v: LimitModel(LIMITED, LIMITS).leg_state_violations(velocities=v), [0.01] * 6),
    ('LimitModel.leg_velocity_scale', FUNCTION,
     lambda v: LimitModel(LIMITED, LIMITS).leg_velocity_scale(v), [0.01] * 6),
    ('Geometry base_joints', FUNCTION,
     lambda v: Geometry(base_joints=v, platform_joints=PAPER.platform_joints), PAPER.base_joints),
    ('Geometry home_pose', FUNCTION,
     lambda v: Geometry(PAPER.base_joints, PAPER.platform_joints, home_pose=v), HOME),
    ('Transform position', FUNCTION, lambda v: Transform(v, ROTATION), POSITION),
    ('Transform rotation', FUNCTION, lambda v: Transform(POSITION, v), ROTATION),
    ('Transform.from_pose', FUNCTION, Transform.from_pose, HOME),
    ('Transform.apply', FUNCTION, lambda v: Transform(POSITION, ROTATION).apply(v),
     [[0.1, 0.2, 0.3]]),
    ('FrameTree.platform_in_base', FUNCTION,
     lambda v: FrameTree().platform_in_base(v, ROTATION), POSITION),
    ('ActuatorInterface offsets', FUNCTION, lambda v: ActuatorInterface(offsets=v), [0.1] * 6),
    ('ActuatorInterface.positions', FUNCTION,
     lambda v: ActuatorInterface().positions(v), HOME_LENGTHS),
    ('PoseTrajectory.from_poses times', FUNCTION,
     lambda v: PoseTrajectory.from_poses(v, [HOME, HOME + 0.01]), [0.0, 1.0]),
    ('PoseTrajectory.from_poses poses', FUNCTION,
     lambda v: PoseTrajectory.from_poses([0.0, 1.0], v), [HOME, HOME + 0.01]),
    ('PoseTrajectory.from_quaternions quaternions', FUNCTION,
     lambda v: PoseTrajectory.from_quaternions([0.0, 1.0], PATH_POSITIONS[:2], v),
     PATH_QUATERNIONS[:2]),
    ('PoseTrajectory.sample', FUNCTION,
     lambda v: PoseTrajectory.from_poses([0.0, 1.0], [HOME, HOME + 0.01]).sample(v),
     [0.0, 0.5, 1.0]),
    ('Ramp start', FUNCTION, lambda v: Ramp(v, np.full(6, 0.01), HOME + 0.05), HOME),
    ('Ramp.sample', FUNCTION, lambda v: Ramp(HOME, np.full(6, 0.01), HOME + 0.05).sample(
        v, 10.0), [0.0, 1.0, 2.0]),
    ('travel_ranges pose', FUNCTION, lambda v: travel_ranges(LIMITED, v), LIMITED.home_pose),
    ('MotionCueing.step specific_force', FUNCTION,
     lambda v: MotionCueing(LIMITED).step(0.0, v, [0.0] * 3), [0.5, 0.0, 9.81]),
    ('LimitModel.check_leg_states jerks', FUNCTION,
     lambda v: LimitModel(LIMITED, LIMITS).check_leg_states(jerks=v), [[0.1] * 6] * 2),
    ('LimitModel.leg_state_allowed', FUNCTION,
     lambda v: LimitModel(LIMITED, LIMITS).leg_state_allowed(accelerations=v), [0.1] * 6),
    ('limits.check_pose rotation', FUNCTION,
     lambda v: limits.check_pose(LIMITED, POSITION, v), ROTATION),
    ('limits.check_poses_array', FUNCTION, lambda v: limits.check_poses_array(LIMITED, v),
     [HOME, HOME + 0.01]),
    ('limits.leg_length_violations', FUNCTION,
     lambda v: limits.leg_length_violations(LIMITED, v), HOME_LENGTHS),
    ('limits.joint_angles position', FUNCTION,
     lambda v: limits.joint_angles(LIMITED, v, ROTATION), POSITION),
    ('limits.joint_angles rotation', FUNCTION,
     lambda v: limits.joint_angles(LIMITED, POSITION, v), ROTATION),
    ('FrameTree.tool_pose_vector', FUNCTION, lambda v: FrameTree().tool_pose_vector(v), HOME),
    ('FrameTree.tool_pose_vector, a tool frame', FUNCTION,
     lambda v: TOOL_FRAMES.tool_pose_vector(v), HOME),
    ('FrameTree.platform_in_base, a tool frame', FUNCTION,
     lambda v: TOOL_FRAMES.platform_in_base(v, ROTATION), POSITION),
    ('FrameTree.platform_pose_vectors', FUNCTION,
     lambda v: TOOL_FRAMES.platform_pose_vectors(v), [HOME]),
    ('FrameTree.platform_twist_from_tool', FUNCTION,
     lambda v: TOOL_FRAMES.platform_twist_from_tool(v, ROTATION), TWIST),
    ('FrameTree.platform_motion positions', FUNCTION,
     lambda v: TOOL_FRAMES.platform_motion(v, [ROTATION]), [POSITION]),
    ('PoseTrajectory positions', FUNCTION,
     lambda v: PoseTrajectory([0.0, 1.0], v, [ROTATION] * 2), PATH_POSITIONS[:2]),
    ('PoseTrajectory rotations', FUNCTION,
     lambda v: PoseTrajectory([0.0, 1.0], PATH_POSITIONS[:2], v), [ROTATION] * 2),
    ('PoseTrajectory velocities', FUNCTION,
     lambda v: PoseTrajectory([0.0, 1.0], PATH_POSITIONS[:2], [ROTATION] * 2, v,
                              np.zeros((2, 3))), np.full((2, 3), 0.01)),
    ('PoseTrajectory.path positions', FUNCTION,
     lambda v: PoseTrajectory.path(PAPER, v, [ROTATION] * 3), PATH_POSITIONS),
    ('TimedTrajectory.sample', FUNCTION, TIMED.sample, [0.0, 0.5, 1.0]),
    ('TimedTrajectory.legs', FUNCTION, lambda v: TIMED.legs(PAPER, v), [0.0, 0.5, 1.0]),
    ('Ramp.from_table', FUNCTION,
     lambda v: Ramp.from_table(v, [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325], [0.0] * 3,
                               [1.5, -1.5, 2.0], [15.0, -15.0, 20.0]), [0.0, 0.0, 0.4325]),
    ('workspace_slice pose', FUNCTION,
     lambda v: workspace_slice(LIMITED, 'XY', v, resolution=0.05), LIMITED.home_pose),
    ('workspace_volume orientation', FUNCTION,
     lambda v: workspace_volume(LIMITED, v, resolution=0.05), [0.0, 0.0, 0.0]),
    ('orientation_workspace position', FUNCTION,
     lambda v: orientation_workspace(LIMITED, v, resolution=0.2), LIMITED.home_pose[:3]),
    ('assembly_modes lengths', FUNCTION, lambda v: assembly_modes(PAPER, v), HOME_LENGTHS),
    ('assembly_mode_margin pose', FUNCTION,
     lambda v: assembly_mode_margin(LIMITED, v), LIMITED.home_pose),
    ('calibrate poses', FUNCTION,
     lambda v: calibrate(PAPER, v, CALIBRATION_POSITIONS), CALIBRATION_POSES),
    ('calibrate actuator_positions', FUNCTION,
     lambda v: calibrate(PAPER, CALIBRATION_POSES, v), CALIBRATION_POSITIONS),
]


#: Where an entry point answers otherwise, and why: (entry, variant) -> the answer it gives.
#: leg_state_allowed's fast path (a stream's every step) reads a list of six as six floats;
#: ``numpy.ma.masked`` among them compares as not within the limits: False, the safe answer.
OTHERWISE = {
    ('LimitModel.leg_state_allowed', 'list holding a masked value'): ('accepted', False)}


def fingerprint(value, depth=0):
    """Return a comparable summary of a result: arrays by their bits, objects by their fields."""
    if isinstance(value, np.ndarray):
        return ('array', value.shape, np.nan_to_num(value.astype(float), nan=1e300).tobytes()
                if value.dtype.kind in 'biuf' else repr(value.tolist()))
    if isinstance(value, (bool, int, float, str, type(None), np.generic)):
        return ('nan',) if isinstance(value, float) and math.isnan(value) else value
    if depth > 3:
        return type(value).__name__
    if isinstance(value, (list, tuple)):
        return tuple(fingerprint(item, depth + 1) for item in value)
    if isinstance(value, dict):
        return tuple((key, fingerprint(item, depth + 1)) for key, item in value.items())
    if dataclasses.is_dataclass(value):
        return (type(value).__name__,) + tuple(
            fingerprint(getattr(value, field.name), depth + 1)
            for field in dataclasses.fields(value) if not field.name.startswith('_'))
    if hasattr(value, '__dict__'):
        return (type(value).__name__,) + tuple(
            (key, fingerprint(item, depth + 1)) for key, item in sorted(vars(value).items())
            if not key.startswith('_'))
    return type(value).__name__


def outcome(kind, call, value):
    """
    Return ``('accepted', fingerprint)`` or ``('refused', reason)``; fail on anything else.

    A decision refuses by its answer (a refused Decision, or a Finding where ``None`` means
    accepted); a function by ``ValueError``. A decision that raises, or a function that raises
    anything but ``ValueError``, fails the test with the exception.
    """
    try:
        with warnings.catch_warnings():
            warnings.simplefilter('ignore', PendingDeprecationWarning)
            result = call(value)
    except ValueError as error:
        if kind == DECISION:
            raise AssertionError(f'a decision raised ValueError: {error}') from error
        return 'refused', str(error)
    if isinstance(result, Decision):
        return ('accepted', fingerprint(result)) if result.accepted else ('refused',
                                                                          result.reason)
    if isinstance(result, Finding):
        return 'refused', result.message
    return 'accepted', fingerprint(result)


@pytest.mark.parametrize('name, kind, call, good', ENTRY_POINTS,
                         ids=[entry[0] for entry in ENTRY_POINTS])
def test_every_array_like_works_or_is_refused_in_words(name, kind, call, good):
    """Each variant: as its plain equivalent, or refused (masks named); nothing else raised."""
    reference = outcome(kind, call, np.array(good, dtype=float))
    assert reference[0] == 'accepted', f'the valid argument is refused: {reference[1]}'
    failures = []
    for variant, value, expected in variants(good):
        try:
            answer = outcome(kind, call, value)
        except Exception as error:   # noqa: B902 - what the test is about
            failures.append(f'{variant}: raised {type(error).__name__}: {error}')
            continue
        if (name, variant) in OTHERWISE:
            if answer != OTHERWISE[name, variant]:
                failures.append(f'{variant}: {answer}, expected {OTHERWISE[name, variant]}')
            continue
        if expected == SAME:
            wanted = reference
        elif expected == PLAIN:
            wanted = outcome(kind, call, plain(value))
        else:
            wanted = ('refused', None)
        if answer[0] != wanted[0]:
            failures.append(f'{variant}: {answer[0]} ({answer[1]!s:.100}), expected {wanted[0]}')
        elif answer[0] == 'accepted' and answer[1] != wanted[1]:
            failures.append(f'{variant}: accepted, but not as {expected}')
        elif answer[0] == 'refused':
            reason = answer[1]
            if any(words in reason for words in NUMPY_WORDS + MORE_NUMPY_WORDS):
                failures.append(f"{variant}: refused in numpy's words: {reason}")
            if expected == MASKED and 'masked' not in reason:
                failures.append(f'{variant}: refused without naming the mask: {reason}')
    assert not failures, f'{name}:\n' + '\n'.join(failures)


# The rule itself, in the one conversion ------------------------------------------------------

@budget(100)
@given(st.integers(1, 4).flatmap(lambda rows: st.lists(
    st.lists(st.booleans(), min_size=3, max_size=3), min_size=rows, max_size=rows)))
def test_a_masked_entry_is_refused_by_index(mask):
    """Any mask: refused naming exactly the masked entries (by index), or the data if none."""
    mask = np.array(mask)
    values = np.ma.masked_array(np.arange(mask.size, dtype=float).reshape(mask.shape), mask=mask)
    if not mask.any():
        converted = as_float_array(values, 'values')
        assert type(converted) is np.ndarray and np.array_equal(converted, values.data)
        return
    with pytest.raises(ValueError) as raised:
        as_float_array(values, 'values')
    message = str(raised.value)
    named = np.argwhere(mask).tolist()
    more = f' and {len(named) - 10} more' if len(named) > 10 else ''
    assert message == (f'values must be numbers, not masked: entries {named[:10]}{more} are '
                       'masked (fill them, or give a plain array)'), message


def test_a_matrix_is_its_plain_two_dimensional_array():
    """np.matrix(six lengths) is shape (1, 6): a batch of one for a batch function."""
    lengths = matrix(HOME_LENGTHS)
    converted = as_float_array(lengths, 'lengths')
    assert type(converted) is np.ndarray and converted.shape == (1, 6)
    result = forward_kinematics(PAPER, lengths)
    assert result.pose.shape == (1, 6) and bool(result.converged[0])
    np.testing.assert_allclose(result.pose[0], HOME, rtol=0.0, atol=1e-12)
    estimate = PoseTracker(PAPER).update(lengths)
    assert not estimate.accepted and 'shape (1, 6)' in estimate.reason


def test_the_matrix_of_a_zero_length_is_refused_not_an_index_error():
    """The defect of issue 27: PoseTracker.update raised IndexError for np.matrix of a zero."""
    for entry in (0.0, math.nan, -0.5):
        lengths = HOME_LENGTHS.copy()
        lengths[2] = entry
        estimate = PoseTracker(PAPER).update(matrix(lengths))
        assert not estimate.accepted and estimate.refusal.code == 'invalid_lengths'
        estimate = PoseTracker(PAPER).update(np.ma.masked_array(lengths, mask=[0, 0, 1, 0, 0, 0]))
        assert not estimate.accepted and 'entries [2] are masked' in estimate.reason


class Unprintable:
    """Not numbers, and its ``repr`` fails too."""

    def __repr__(self):
        raise RuntimeError('no repr')


@pytest.mark.parametrize('value, message', [
    (np.ma.masked, 'x must be a number, not masked (fill it, or give a float)'),
    (np.ma.masked_array(2.0, mask=True), 'x must be a number, not masked'),
    (BrokenArray(), 'x could not be read as an array: RuntimeError: '
                    "'the data source is closed'"),
    (Unprintable(), 'x must be numbers within the float range, got <Unprintable> '
                    '(Unprintable)'),
    ([np.ma.masked_array([1.0, 2.0], mask=[0, 1]), np.ma.masked_array([3.0, 4.0], mask=[1, 0])],
     'x must be numbers, not masked: entries [[0, 1], [1, 0]] are masked'),
    (np.ma.masked_array(np.arange(12.0), mask=np.arange(12) % 1 == 0),
     'x must be numbers, not masked: entries [0, 1, 2, 3, 4, 5, 6, 7, 8, 9] and 2 more are '
     'masked'),
], ids=['masked constant', 'masked scalar', 'broken __array__', 'unprintable', 'masked rows',
        'many masked'])
def test_the_conversion_says_what_it_cannot_use(value, message):
    """The one conversion's sentences: masks by index, a failing __array__ by what it raised."""
    with pytest.raises(ValueError) as raised:
        as_float_array(value, 'x')
    assert str(raised.value).startswith(message), str(raised.value)


def test_a_plain_float_array_is_passed_through_and_a_subclass_is_not():
    """The fast path is kept for plain float arrays only: no copy, the very object."""
    values = np.arange(6.0)
    assert as_float_array(values, 'x') is values
    for subclass in (matrix(values), np.ma.masked_array(values), values.view(np.recarray)):
        converted = as_float_array(subclass, 'x')
        assert type(converted) is np.ndarray, type(subclass)
        np.testing.assert_array_equal(converted.ravel(), values)
