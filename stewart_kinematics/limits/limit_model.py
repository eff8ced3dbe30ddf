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
The limits model: every limit of a platform and its actuators, and every check made of them.

A :class:`LimitModel` is built from a :class:`stewart_kinematics.Geometry` with its
:class:`~stewart_kinematics.limits.settings.PoseLimits` (where the platform may be: stroke,
joint cones, singularity margin, leg collisions) and :class:`stewart_kinematics.ActuatorLimits`
(how fast the legs may move: velocity, acceleration, jerk). It composes the evaluators of the
limits that are set, one per kind, in the order of
:data:`~stewart_kinematics.limits.kinds.LIMIT_KINDS`, and every check in the package goes
through it::

    model = LimitModel(geometry, actuator_limits)
    model.check_pose(position, rotation)      # one pose: [Violation, ...], empty if allowed
    checks = model.check_poses(poses)         # N poses at once: a LimitChecks of arrays
    checks.allowed, checks.violations(k)
    model.check_leg_states(lengths=..., velocities=..., accelerations=..., jerks=...)

Adding a limit is adding a kind to that list (see its module). Nothing here imports ROS.
"""

import math
from typing import Dict, List, Optional

import numpy as np

from stewart_kinematics.limits import kinds
from stewart_kinematics.limits.base import (
    LEG,
    LegSamples,
    PAIR,
    PLATFORM,
    PoseLegs,
    row_violations,
    violations_in,
)
from stewart_kinematics.limits.leg_rates import LegRate
from stewart_kinematics.limits.singularity import SingularityMargin
from stewart_kinematics.limits.violation import Violation
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.inputs import as_poses

#: Poses per block of a vectorised check: the temporaries of a block stay in the processor's
#: cache (measured fastest between 512 and 2048).
CHECK_BLOCK_SIZE = 1024

#: The attribute of a geometry that keeps its pose limits' model (see LimitModel.of_geometry).
_MODEL_ATTRIBUTE = '_limit_model'


class LimitModel:
    """
    Every limit of a platform and its actuators: the evaluators of those that are set.

    :param geometry: a :class:`stewart_kinematics.Geometry`, or ``None`` for leg-state
        limits alone.
    :param actuator_limits: leg velocity, acceleration and jerk limits; ``None``: none.
    :param rate_slack: relative slack on those limits, for the rounding of sampled motion
        (:data:`~stewart_kinematics.limits.leg_rates.RATE_SLACK` for a trajectory's samples or
        a stream's steps); 0 (the default) checks them strictly, as for a twist.
    :param limits: the pose limits' :class:`~stewart_kinematics.limits.settings.PoseLimits`;
        ``None`` (the default): the geometry's own (``geometry.limits``).

    The evaluators are those of :data:`~stewart_kinematics.limits.kinds.LIMIT_KINDS`, in its
    order: each kind's pose evaluator (of the geometry and the limits) and its leg-state
    evaluators (of the limits and the actuator limits), those with a bound set.
    """

    def __init__(self, geometry=None, actuator_limits: Optional[ActuatorLimits] = None, *,
                 rate_slack: float = 0.0, limits=None):
        self.geometry = geometry
        if limits is None and geometry is not None:
            limits = geometry.limits
        #: The pose limits' settings, or ``None`` for none.
        self.limits = limits
        self.actuator_limits = actuator_limits or ActuatorLimits()
        pose_limits, leg_state_limits = [], []
        for kind in kinds.LIMIT_KINDS:
            if kind.pose_evaluator is not None and geometry is not None and limits is not None:
                pose_limits.append(kind.pose_evaluator(geometry, limits))
            if kind.leg_state_evaluators is not None:
                leg_state_limits += kind.leg_state_evaluators(limits, self.actuator_limits,
                                                              rate_slack)
        #: The evaluators of the pose limits that are set, in report order.
        self.pose_limits = tuple(limit for limit in pose_limits if limit.bounds)
        #: The evaluators of the leg-state limits that are set, in report order.
        self.leg_state_limits = tuple(limit for limit in leg_state_limits if limit.bounds)
        self._bounds = {bound.name: bound
                        for limit in self.pose_limits + self.leg_state_limits
                        for bound in limit.bounds}

    @classmethod
    def of_geometry(cls, geometry) -> 'LimitModel':
        """
        Return the model of a geometry's pose limits, built once per geometry and kept on it.

        Kept as an attribute of the geometry (a cycle the garbage collector frees with it), not
        in a table keyed by geometry: a table's value holding its key would keep every
        geometry alive.
        """
        model = geometry.__dict__.get(_MODEL_ATTRIBUTE)
        if model is None:
            model = cls(geometry)
            object.__setattr__(geometry, _MODEL_ATTRIBUTE, model)
        return model

    @property
    def pose_limit_names(self):
        """Names of the pose limits that are set, in report order (``LIMIT_NAMES``)."""
        return tuple(bound.name for limit in self.pose_limits for bound in limit.bounds)

    def bound(self, name: str):
        """
        Return the :class:`~stewart_kinematics.limits.base.Bound` of a limit that is set.

        :raises KeyError: for a limit that is not set, naming those that are.
        """
        try:
            return self._bounds[name]
        except KeyError:
            raise KeyError(f'{name} is not set in this model; set: {list(self._bounds)}') \
                from None

    def evaluator(self, kind: type):
        """Return the first evaluator of a kind (a class such as :class:`Stroke`), or ``None``."""
        return next((limit for limit in self.pose_limits + self.leg_state_limits
                     if isinstance(limit, kind)), None)

    # One pose ---------------------------------------------------------------------------------

    def check_pose(self, position, rotation, *, condition=None) -> List[Violation]:
        """
        Every limit that one pose breaks; empty when the pose is allowed.

        :param position: platform position in the base frame, metres, shape (3,).
        :param rotation: platform-to-base rotation matrix, shape (3, 3).
        :param condition: the pose's condition number when already known (a forward
            kinematics result carries it), so that it is not computed twice.
        :raises ValueError: if the position or the rotation is malformed or not finite, or
            the pose is so far away that its leg lengths overflow; any other pose gets its list,
            a platform joint on its base joint included (a leg of zero length breaks the
            singularity margin and the joint cones, having no direction).
        """
        position = as_float_array(position, 'position')
        rotation = as_float_array(rotation, 'rotation')
        if position.shape != (3,) or rotation.shape != (3, 3):
            raise ValueError(f'expected a position (3,) and a rotation (3, 3), got shapes '
                             f'{position.shape} and {rotation.shape}')
        position, entries = position.tolist(), rotation.ravel().tolist()
        if not all(map(math.isfinite, position + entries)):
            raise ValueError(f'pose must be finite, got position {position}')
        if not self.pose_limits:
            return []
        legs = PoseLegs.of_pose(self.geometry, position, entries)
        if not all(math.isfinite(leg[0]) for leg in legs.floats):
            raise ValueError(f'leg lengths must be finite (metres), got '
                             f'{[leg[0] for leg in legs.floats]}: a pose beyond any reach')
        return self.violations_of(legs, condition=condition)

    def pose_legs(self, position, rotation) -> PoseLegs:
        """
        Return the legs of one pose, as every pose limit reads them (for :meth:`violations_of`).

        In floats (:meth:`PoseLegs.of_pose`), with their arrays built when read.

        :param position: metres, shape (3,), finite; ``rotation``: shape (3, 3), finite.
        """
        return PoseLegs.of_pose(self.geometry, np.asarray(position, dtype=float).tolist(),
                                np.asarray(rotation, dtype=float).ravel().tolist())

    def violations_of(self, legs: PoseLegs, *, condition=None) -> List[Violation]:
        """
        Every pose limit that the one pose of ``legs`` breaks, in report order.

        Each evaluator's one-pose path (:meth:`~.base.Limit.violations_of_one`: floats where
        its formulas run on them), the same violations as :meth:`check_poses` gives the pose.

        :param legs: :meth:`pose_legs` of a pose whose lengths are finite.
        :param condition: its condition number when already known, or ``None``.
        """
        violations = []
        for limit in self.pose_limits:
            if condition is not None and isinstance(limit, SingularityMargin):
                violations += row_violations(limit.bounds[0], (float(condition),))
            else:
                violations += limit.violations_of_one(legs)
        return violations

    # Many poses -------------------------------------------------------------------------------

    def check_poses(self, poses, *, every_reason: bool = True,
                    exact: bool = True) -> 'LimitChecks':
        """
        Every limit that each of a batch of poses breaks, vectorised.

        No Python loop runs over the poses: stroke and joint cones cost well under a
        microsecond a pose, the 15 leg pairs of the collision check about half of one, the
        singularity margin (one small singular value decomposition a pose) a few.

        :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
        :param every_reason: with False, the dear limits (singularity margin, leg collisions)
            are evaluated only for the poses that keep the cheap ones (stroke, joint cones):
            elsewhere their values are NaN and they count as kept. ``allowed`` is the same
            either way; only the reasons listed for a refused pose may be fewer.
        :param exact: with False, a condition number proved within the margin is not computed
            (NaN); ``allowed`` is the same either way.
        :returns: a :class:`LimitChecks`; ``.violations(k)`` gives pose k's list, as
            :meth:`check_pose` gives it.
        :raises ValueError: if a pose has the wrong shape or a non-finite value.
        """
        poses = np.atleast_2d(as_poses(poses))
        return self._check(len(poses), lambda block: PoseLegs.of_poses(
            self.geometry, poses[block]), self.pose_limits, every_reason, exact)

    def check_pose_matrices(self, positions, rotations, *, every_reason: bool = True,
                            exact: bool = True) -> 'LimitChecks':
        """
        :meth:`check_poses` of positions (N, 3) and rotation matrices (N, 3, 3), checked finite.

        :raises ValueError: if the shapes disagree or a value is not finite.
        """
        positions = as_float_array(positions, 'positions')
        rotations = as_float_array(rotations, 'rotations')
        if (positions.ndim != 2 or positions.shape[1:] != (3,)
                or rotations.shape != (len(positions), 3, 3)):
            raise ValueError(f'expected positions (N, 3) and rotations (N, 3, 3), got shapes '
                             f'{positions.shape} and {rotations.shape}')
        if not (np.all(np.isfinite(positions)) and np.all(np.isfinite(rotations))):
            raise ValueError('positions and rotations must be finite')
        return self._check(len(positions), lambda block: PoseLegs.of_matrices(
            self.geometry, positions[block], rotations[block]), self.pose_limits, every_reason,
            exact)

    # Leg states -------------------------------------------------------------------------------

    def check_leg_states(self, lengths=None, velocities=None, accelerations=None,
                         jerks=None) -> 'LimitChecks':
        """
        Every leg-state limit that each of N samples breaks: stroke, velocity, acceleration, jerk.

        Only the quantities given are checked (the trajectory check, say, gives velocities and
        accelerations, and checks the stroke on the poses).

        :param lengths: metres, shape (6,) or (N, 6); ``velocities`` (m/s),
            ``accelerations`` (m/s^2) and ``jerks`` (m/s^3) likewise.
        :returns: a :class:`LimitChecks` of the limits of the quantities given.
        :raises ValueError: if the shapes differ or are not (N, 6).
        """
        given = {name: np.atleast_2d(as_float_array(values, name))
                 for name, values in (('lengths', lengths), ('velocities', velocities),
                                      ('accelerations', accelerations), ('jerks', jerks))
                 if values is not None}
        shapes = {values.shape for values in given.values()}
        if len(shapes) > 1 or any(len(shape) != 2 or shape[1] != 6 for shape in shapes):
            raise ValueError(f'leg states must share one shape (N, 6), got {shapes}')
        samples = LegSamples(**{name: values.T for name, values in given.items()})
        limits = tuple(limit for limit in self.leg_state_limits
                       if getattr(samples, limit.quantity) is not None)
        return self._check(samples.count, samples.take, limits, True, True)

    def leg_state_violations(self, lengths=None, velocities=None, accelerations=None,
                             jerks=None) -> List[Violation]:
        """
        Every leg-state limit that one sample breaks: :meth:`check_leg_states` of one sample.

        The per-step check of a stream and of a twist: the evaluators on the one sample,
        without the arrays of a batch.

        :param lengths: metres, shape (6,); ``velocities``, ``accelerations`` and ``jerks``
            likewise, each optional (its limits are then not checked).
        :raises ValueError: if a quantity given does not have shape (6,).
        """
        given = {}
        for name, values in (('lengths', lengths), ('velocities', velocities),
                             ('accelerations', accelerations), ('jerks', jerks)):
            if values is not None:
                values = as_float_array(values, name)
                if values.shape != (6,):
                    raise ValueError(f'{name} of one leg state must have shape (6,), got '
                                     f'{values.shape}')
                given[name] = values[:, None]
        samples = LegSamples(**given)
        violations = []
        for limit in self.leg_state_limits:
            if getattr(samples, limit.quantity) is None:
                continue
            violations += violations_in(limit.bounds, limit.evaluate(samples))
        return violations

    def leg_state_allowed(self, **sample) -> bool:
        """
        Whether one leg state keeps every leg-state limit: the fast path of a stream's step.

        The same comparisons as :meth:`leg_state_violations` (tested equal, NaN and infinity
        included), in floats: a few microseconds where the arrays cost tens.

        :param sample: ``lengths``, ``velocities``, ``accelerations``, ``jerks`` (those given),
            each six floats: a list (the fast path) or anything :meth:`leg_state_violations`
            takes.
        :raises ValueError: for a quantity that is not six numbers.
        """
        for name, values in sample.items():
            if type(values) is not list or len(values) != 6:
                sample[name] = _six_floats(values, name)
        try:
            return all(limit.allows(sample) for limit in self.leg_state_limits
                       if limit.quantity in sample)
        except TypeError:   # a list of six that are not all numbers
            sample = {name: _six_floats(values, name) for name, values in sample.items()}
            return all(limit.allows(sample) for limit in self.leg_state_limits
                       if limit.quantity in sample)

    def leg_velocity_scale(self, velocities) -> float:
        """
        Return the largest factor in (0, 1] that brings leg velocities within the limit.

        1.0 without a velocity limit. For a twist scaled uniformly to the limit.

        :param velocities: m/s, finite, any shape.
        :raises ValueError: if a velocity is not a finite number (no factor brings it within).
        """
        velocities = as_float_array(velocities, 'velocities')
        if not np.all(np.isfinite(velocities)):
            raise ValueError(f'velocities must be finite (m/s), got {preview(velocities)}')
        rates = [limit for limit in self.leg_state_limits
                 if isinstance(limit, LegRate) and limit.quantity == 'velocities']
        return rates[0].scale(velocities) if rates else 1.0

    # The vectorised check ---------------------------------------------------------------------

    def _check(self, count, arrays_of, limits, every_reason, exact) -> 'LimitChecks':
        """
        Run the evaluators ``limits`` block by block over ``count`` poses or samples.

        :param arrays_of: a block (slice) -> the evaluators' arrays of that block.
        """
        bounds = [bound for limit in limits for bound in limit.bounds]
        values = {bound.name: np.full((_ROWS[bound.subject], count), np.nan)
                  for bound in bounds}
        broken = {bound.name: np.zeros((_ROWS[bound.subject], count), dtype=bool)
                  for bound in bounds}
        allowed = np.ones(count, dtype=bool)
        cheap = [limit for limit in limits if not limit.dear]
        dear = [limit for limit in limits if limit.dear]
        for start in range(0, count, CHECK_BLOCK_SIZE):
            block = slice(start, min(start + CHECK_BLOCK_SIZE, count))
            arrays = arrays_of(block)
            for limit in cheap:
                _store(limit, limit.evaluate(arrays, exact), block, values, broken, allowed)
            if not dear:
                continue
            kept = allowed[block]
            if every_reason or kept.all():
                subset, target = arrays, block
            else:
                columns = np.flatnonzero(kept)
                if not columns.size:
                    continue
                subset, target = arrays.take(columns), start + columns
            results = [limit.evaluate(subset, exact) for limit in dear]
            for limit, result in zip(dear, results):
                _store(limit, result, target, values, broken, allowed)
        return LimitChecks(self, tuple(bounds), values, broken, allowed)


def _store(limit, results, target, values, broken, allowed):
    """Write one evaluator's results at ``target`` (a block or columns); clear ``allowed``."""
    for bound, (bound_values, bound_broken) in zip(limit.bounds, results):
        values[bound.name][:, target] = bound_values
        broken[bound.name][:, target] = bound_broken
        allowed[target] &= ~np.any(bound_broken, axis=0)


#: Rows of a bound's values: 6 legs, 15 pairs or the platform.
_ROWS = {LEG: 6, PAIR: 15, PLATFORM: 1}


class LimitChecks:
    """
    The limit checks of N poses (or leg samples) as arrays: which limits each breaks, by how much.

    Only the limits that are set are checked: ``broken`` has a key for each of them, and the
    values of the others are ``None``. Arrays are pose by leg: (N, 6) per leg, (N, 15) per pair
    of legs (in the order of :data:`~stewart_kinematics.limits.base.LEG_PAIRS`), (N,) for the
    whole platform.

    :param model: the :class:`LimitModel` that checked them.
    :param bounds: the bounds checked, in report order.
    :param values: per limit name, its values, SI units, leg by pose (k, N).
    :param broken: per limit name, where it is broken, (k, N).
    :param allowed: shape (N,), True where nothing is broken.
    """

    def __init__(self, model, bounds, values, broken, allowed):
        self.model, self.bounds, self.allowed = model, bounds, allowed
        self._values, self._broken = values, broken

    def __len__(self):
        return len(self.allowed)

    @property
    def geometry(self):
        """Return the geometry whose limits were checked."""
        return self.model.geometry

    def values(self, limit: str) -> np.ndarray:
        """
        Return the values of a limit that is set, SI units: (N, 6), (N, 15) or (N,).

        :raises KeyError: for a limit that was not checked.
        """
        values = self._values[self._checked(limit).name]
        return values[0] if values.shape[0] == 1 else values.T

    @property
    def broken(self) -> Dict[str, np.ndarray]:
        """Per limit name, in report order, where it is broken: (N, 6), (N, 15) or (N,)."""
        return {name: mask[0] if mask.shape[0] == 1 else mask.T
                for name, mask in self._broken.items()}

    @property
    def lengths(self) -> Optional[np.ndarray]:
        """Leg lengths, metres, (N, 6), or ``None`` without a stroke limit."""
        return self._optional('leg_length_max', 'leg_length_min')

    @property
    def base_angles(self) -> Optional[np.ndarray]:
        """Cone angles at the base joints, radians, (N, 6), or ``None`` without that cone."""
        return self._optional('base_joint_max_angle')

    @property
    def platform_angles(self) -> Optional[np.ndarray]:
        """Cone angles at the platform joints (platform frame), radians, (N, 6), or ``None``."""
        return self._optional('platform_joint_max_angle')

    @property
    def condition(self) -> Optional[np.ndarray]:
        """Condition numbers of the dimensionless Jacobian, (N,), or ``None`` without a margin."""
        return self._optional('max_jacobian_condition')

    @property
    def leg_distances(self) -> Optional[np.ndarray]:
        """Distances between the legs' axes, metres, (N, 15), or ``None`` without leg_radius."""
        return self._optional('leg_collision')

    def excess(self, limit: str) -> np.ndarray:
        """
        Return how far beyond ``limit`` each pose is, SI units: positive where broken.

        Zero or negative where kept: minus the margin left.

        :param limit: one of the keys of ``broken``.
        :returns: the shape of :meth:`values`.
        :raises KeyError: for a limit that is not set.
        """
        bound = self._checked(limit)
        excess = bound.excess(self._values[limit])
        return excess[0] if excess.shape[0] == 1 else excess.T

    def broken_limits(self, index: int) -> List[str]:
        """Names of the limits that pose ``index`` breaks, in report order."""
        return [name for name, mask in self._broken.items() if mask[:, index].any()]

    def violations(self, index: int) -> List[Violation]:
        """Return the :class:`Violation` list of pose ``index``, as ``check_pose`` gives it."""
        return [bound.violation(row, float(self._values[bound.name][row, index]))
                for bound in self.bounds
                for row in np.flatnonzero(self._broken[bound.name][:, index])]

    def first_refused(self) -> Optional[int]:
        """Return the index of the first pose or sample that breaks a limit, or ``None``."""
        refused = np.flatnonzero(~self.allowed)
        return int(refused[0]) if refused.size else None

    def _checked(self, limit):
        for bound in self.bounds:
            if bound.name == limit:
                return bound
        raise KeyError(f'{limit} is not set in this geometry; checked: '
                       f'{[bound.name for bound in self.bounds]}')

    def _optional(self, *names):
        for name in names:
            if name in self._values:
                return self.values(name)
        return None


def _six_floats(values, name) -> list:
    """Return one leg state's quantity as six floats, or raise ValueError naming it."""
    values = as_float_array(values, name)
    if values.shape != (6,):
        raise ValueError(f'{name} of one leg state must have shape (6,), got {values.shape}')
    return values.tolist()
