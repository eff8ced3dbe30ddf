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
What every evaluator of the limits model shares: bounds, the arrays they read, their interface.

An evaluator (:class:`Limit`) checks one kind of limit, such as the actuator stroke. It names
its :class:`Bound` objects (``leg_length_min`` and ``leg_length_max``) and computes their values
from arrays laid out leg by pose, shape (k, n): k = 6 legs, 15 pairs of legs or 1 (the whole
platform), n poses or instants. The same code runs on one pose (n = 1) and on a million.

The arrays come from the core's single formulas: :class:`PoseLegs` holds the legs of n poses
as :func:`stewart_kinematics.model.inverse.leg_arrays` gives them (lengths, leg vectors,
rotated platform joints) with the rotation entries of
:func:`stewart_kinematics.model.rotations.zyx_entries`; :class:`LegSamples` holds leg lengths
and their time derivatives. Nothing here imports ROS.
"""

from dataclasses import dataclass
from typing import List, Tuple

import numpy as np

from stewart_kinematics.limits.violation import Violation
from stewart_kinematics.model.formulas import constants_of, single_legs
from stewart_kinematics.model.inverse import leg_arrays
from stewart_kinematics.model.rotations import zyx_entries

#: What a bound is about: each leg (6 rows), each pair of legs (15 rows), the platform (1 row).
LEG, PAIR, PLATFORM = 'leg', 'pair', 'platform'
#: The 15 pairs of legs (1..6), in the row order of a :data:`PAIR` bound: (1, 2), (1, 3), ...
LEG_PAIRS = tuple((i + 1, j + 1) for i in range(6) for j in range(i + 1, 6))


@dataclass(frozen=True)
class Bound:
    """
    One named limit: the largest (or smallest) value a quantity may take.

    :param name: the limit's parameter name, such as ``leg_length_max``; Violations carry it.
    :param allowed: the limit, SI units (metres, radians, m/s, ...).
    :param upper: True when values must stay at or below ``allowed``, False at or above.
    :param subject: :data:`LEG`, :data:`PAIR` or :data:`PLATFORM`: what a row of values is.
    :param unit: the unit of the values a :class:`Violation` reports.
    :param scale: SI value times this is the value in ``unit`` (degrees per radian for angles).
    :param slack: relative slack on ``allowed``, for rounding only (sampled leg speeds).
    """

    name: str
    allowed: float
    upper: bool
    subject: str
    unit: str
    scale: float = 1.0
    slack: float = 0.0

    def broken(self, values: np.ndarray) -> np.ndarray:
        """Where ``values`` break the bound; NaN (a quantity that does not exist) breaks it."""
        if self.upper:
            return ~(values <= self.allowed * (1.0 + self.slack))
        return ~(values >= self.allowed)

    def holds(self, value: float) -> bool:
        """Whether one value (a float) keeps the bound: :meth:`broken`'s comparison, negated."""
        if self.upper:
            return value <= self.allowed * (1.0 + self.slack)
        return value >= self.allowed

    def excess(self, values: np.ndarray) -> np.ndarray:
        """How far beyond the bound, SI units: positive where broken, minus the margin left."""
        return values - self.allowed if self.upper else self.allowed - values

    def violation(self, row: int, value: float) -> Violation:
        """Return the :class:`Violation` of row ``row`` (a leg, a pair, the platform)."""
        leg = other = None
        if self.subject == LEG:
            leg = row + 1
        elif self.subject == PAIR:
            leg, other = LEG_PAIRS[row]
        return Violation(self.name, leg, value * self.scale, self.allowed * self.scale,
                         self.unit, other)


class PoseLegs:
    """
    The legs of n poses, leg by pose: what every pose limit reads.

    :param lengths: leg lengths, metres, shape (6, n).
    :param vectors: ``(lx, ly, lz, ax, ay, az)``: leg vectors ``t + R p_i - b_i`` and rotated
        platform joints ``R p_i``, each (6, n), metres, base frame.
    :param rotation: ``(r11, ..., r33)``, the entries of each platform-to-base rotation, each
        shape (n,).

    The legs of one pose (:meth:`of_pose`) also keep :attr:`floats`, the same figures as
    Python floats, which the evaluators' one-pose paths (:meth:`Limit.violations_of_one`)
    read; their arrays are then built only when an evaluator asks for them.
    """

    __slots__ = ('_lengths', '_vectors', '_rotation', 'floats', 'float_rotation')

    def __init__(self, lengths, vectors, rotation):
        self._lengths, self._vectors, self._rotation = lengths, vectors, rotation
        #: One pose: per leg ``(l, lx, ly, lz, ax, ay, az)`` in floats
        #: (:func:`stewart_kinematics.model.formulas.legs_of`); ``None`` for a batch.
        self.floats = None
        #: One pose: the nine rotation entries ``(r11, ..., r33)`` as floats; else ``None``.
        self.float_rotation = None

    @classmethod
    def of_pose(cls, geometry, position, rotation) -> 'PoseLegs':
        """
        Legs of one pose: position (three floats) and rotation entries (nine floats, by rows).

        Computed in floats (:func:`stewart_kinematics.model.formulas.single_legs`, the one leg
        formula), as :func:`~stewart_kinematics.model.inverse.leg_arrays` computes one pose:
        the same values to the bit.
        """
        legs = cls(None, None, None)
        legs.floats = single_legs(constants_of(geometry), position, rotation)
        legs.float_rotation = rotation
        return legs

    @classmethod
    def of_poses(cls, geometry, poses) -> 'PoseLegs':
        """Legs of poses ``[X, Y, Z, alpha, beta, gamma]``, shape (n, 6), already checked."""
        cosines, sines = np.cos(poses[:, 3:]), np.sin(poses[:, 3:])
        rotation = zyx_entries(cosines[:, 0], sines[:, 0], cosines[:, 1], sines[:, 1],
                               cosines[:, 2], sines[:, 2])
        return cls(*leg_arrays(geometry, poses[:, :3], rotation), rotation)

    @classmethod
    def of_matrices(cls, geometry, positions, rotations) -> 'PoseLegs':
        """Legs of positions (n, 3) and rotation matrices (n, 3, 3), already checked."""
        rotation = tuple(rotations[:, row, column] for row in range(3) for column in range(3))
        return cls(*leg_arrays(geometry, positions, rotation), rotation)

    def _arrays(self):
        """Build the arrays of one pose's :attr:`floats`, as ``leg_arrays`` builds them."""
        columns = np.array(self.floats).T[:, :, None]   # (7, 6, 1): views of one array
        self._lengths = columns[0]
        self._vectors = tuple(columns[1:])

    @property
    def lengths(self):
        """Leg lengths, metres, shape (6, n)."""
        if self._lengths is None:
            self._arrays()
        return self._lengths

    @property
    def vectors(self):
        """``(lx, ly, lz, ax, ay, az)``, each (6, n), metres, base frame."""
        if self._vectors is None:
            self._arrays()
        return self._vectors

    @property
    def rotation(self):
        """``(r11, ..., r33)``, each shape (n,)."""
        if self._rotation is None:
            self._rotation = tuple(np.array([entry]) for entry in self.float_rotation)
        return self._rotation

    @property
    def count(self) -> int:
        """Return n, the number of poses."""
        return 1 if self.floats is not None else self.lengths.shape[1]

    def take(self, columns) -> 'PoseLegs':
        """Return the legs of some of the poses: ``columns``, indices into the n poses."""
        return PoseLegs(self.lengths[:, columns],
                        tuple(vector[:, columns] for vector in self.vectors),
                        tuple(entry[columns] for entry in self.rotation))


class LegSamples:
    """
    Leg lengths and their time derivatives at n instants, leg by instant (leg-state limits).

    Each is shape (6, n), or ``None`` when not given (its limits are then not checked).

    :param lengths: metres.
    :param velocities: m/s.
    :param accelerations: m/s^2.
    :param jerks: m/s^3.
    """

    __slots__ = ('lengths', 'velocities', 'accelerations', 'jerks')

    def __init__(self, lengths=None, velocities=None, accelerations=None, jerks=None):
        self.lengths, self.velocities = lengths, velocities
        self.accelerations, self.jerks = accelerations, jerks

    @property
    def count(self) -> int:
        """Return n, the number of instants."""
        given = [values for values in (self.lengths, self.velocities, self.accelerations,
                                       self.jerks) if values is not None]
        return given[0].shape[1] if given else 0

    def take(self, columns) -> 'LegSamples':
        """Return the samples at some of the instants."""
        return LegSamples(*(None if values is None else values[:, columns] for values in (
            self.lengths, self.velocities, self.accelerations, self.jerks)))


class Limit:
    """
    An evaluator: one kind of limit, checked on arrays of poses or of leg samples.

    A subclass sets :attr:`bounds` (the limits it checks, those that are set) and implements
    :meth:`values`; :meth:`evaluate` then says where each bound is broken. :attr:`dear` marks
    an evaluator that costs far more a pose than the others (a singular value decomposition,
    the 15 pairs of legs): a check that needs only the decision runs it where the cheap ones
    pass (see :meth:`stewart_kinematics.limits.LimitModel.check_poses`).
    """

    #: The bounds this evaluator checks, in the order it reports them.
    bounds: Tuple[Bound, ...] = ()
    #: For an evaluator of leg states: the field of :class:`LegSamples` it reads.
    quantity = None
    #: Whether it costs far more a pose than the cheap ones (stroke, joint cones).
    dear = False

    def values(self, arrays) -> Tuple[np.ndarray, ...]:
        """
        Return the values of each bound, SI units, one array (k, n) per bound (may be shared).

        :param arrays: a :class:`PoseLegs` (pose limits) or :class:`LegSamples` (leg states).
        """
        raise NotImplementedError

    def allows(self, sample: dict) -> bool:
        """
        Whether one sample keeps every bound, in floats: the fast path of one leg state.

        :param sample: quantity name (``lengths``, ``velocities``, ...) -> six floats; only
            evaluators of leg states implement it, with :meth:`values`' quantity.
        """
        raise NotImplementedError

    def evaluate(self, arrays, exact: bool = True) -> Tuple[Tuple[np.ndarray, np.ndarray], ...]:
        """
        Values and where each bound is broken: ``((values (k, n), broken (k, n)), ...)``.

        :param exact: False lets an evaluator skip a value it can prove within its bound
            (NaN there, not broken); the decision is the same.
        """
        return tuple((values, bound.broken(values))
                     for bound, values in zip(self.bounds, self.values(arrays)))

    def violations_of_one(self, legs) -> List[Violation]:
        """
        Every bound that the one pose of ``legs`` breaks, in report order (bound, then row).

        :param legs: a :class:`PoseLegs` of one pose. This runs :meth:`evaluate` on its arrays;
            an evaluator whose formulas run on floats too overrides it with them (a fraction
            of the arrays' cost on one pose).
        """
        return violations_in(self.bounds, self.evaluate(legs))


def violations_in(bounds, results) -> List[Violation]:
    """Return the violations of one pose or sample (column 0) in an evaluator's results."""
    return [bound.violation(row, float(values[row, 0]))
            for bound, (values, broken) in zip(bounds, results) if broken.any()
            for row in np.flatnonzero(broken[:, 0])]


def row_violations(bound, values) -> List[Violation]:
    """
    Return the violations of one bound by one pose's values, floats by row: where not held.

    The comparisons of :meth:`Bound.broken` in floats (NaN breaks the bound).
    """
    holds = bound.holds
    return [bound.violation(row, value) for row, value in enumerate(values) if not holds(value)]
