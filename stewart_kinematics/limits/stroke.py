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
The actuator stroke: ``leg_length_min <= l_i <= leg_length_max`` for every leg.

Checked on the legs of poses (:class:`~stewart_kinematics.limits.base.PoseLegs`) and on leg
lengths given directly (:class:`~stewart_kinematics.limits.base.LegSamples`: measured lengths,
streamed commands). Nothing here imports ROS.
"""

import math

from stewart_kinematics.limits.base import Bound, LEG, Limit, row_violations
from stewart_kinematics.limits.kind import BoundLook, LimitKind, LimitParameter
from stewart_kinematics.model.validators import Finite, InRange


class Stroke(Limit):
    """
    Evaluator of ``leg_length_min`` and ``leg_length_max``, metres, per leg.

    :param leg_length_min: shortest allowed leg length, metres (0: not set).
    :param leg_length_max: longest allowed leg length, metres (``inf``: not set).
    """

    quantity = 'lengths'

    def __init__(self, leg_length_min: float, leg_length_max: float):
        self.bounds = tuple(
            Bound(name, allowed, upper, LEG, 'm')
            for name, allowed, upper, is_set in (
                ('leg_length_min', leg_length_min, False, leg_length_min > 0.0),
                ('leg_length_max', leg_length_max, True, leg_length_max < math.inf))
            if is_set)

    @classmethod
    def of(cls, limits) -> 'Stroke':
        """Return the stroke of a :class:`~stewart_kinematics.limits.settings.PoseLimits`."""
        return cls(limits.leg_length_min, limits.leg_length_max)

    def values(self, arrays):
        """Return the leg lengths, (6, n), for each bound."""
        return (arrays.lengths,) * len(self.bounds)

    def violations_of_one(self, legs):
        """See :meth:`Limit.violations_of_one`: the lengths in floats."""
        lengths = [leg[0] for leg in legs.floats] if legs.floats is not None else \
            legs.lengths[:, 0].tolist()
        return [violation for bound in self.bounds
                for violation in row_violations(bound, lengths)]

    def allows(self, sample: dict) -> bool:
        """Whether six lengths (floats, ``sample['lengths']``) keep the stroke."""
        lengths = sample['lengths']
        return all(bound.holds(length) for bound in self.bounds for length in lengths)


def _ordered(limits) -> str:
    """Refuse a stroke whose ends are not in order, naming both."""
    if limits.leg_length_min < limits.leg_length_max:
        return ''
    return ('leg length limits must satisfy leg_length_min < leg_length_max, got '
            f'leg_length_min={limits.leg_length_min!r}, leg_length_max={limits.leg_length_max!r}')


def _narrowed(limits, margins) -> dict:
    """Each end of the stroke that is set, drawn in by the length margin."""
    changes = {}
    if limits.leg_length_min > 0.0:
        changes['leg_length_min'] = limits.leg_length_min + margins.length
    if math.isfinite(limits.leg_length_max):
        changes['leg_length_max'] = limits.leg_length_max - margins.length
    return changes


def _evaluator(geometry, limits) -> Stroke:
    return Stroke.of(limits)


#: The stroke: its parameters, bounds and evaluators (a pose limit and a leg-state limit).
KIND = LimitKind(
    name='stroke',
    title='Actuator stroke',
    meaning='Every leg length within `[min, max]`.',
    evaluator='Stroke',
    parameters=(
        LimitParameter(
            'leg_length_min', 'm', 0.0,
            'Shortest allowed leg length (actuator fully retracted), metres; 0.0 for no limit',
            (Finite(), InRange(0.0, math.inf)), note='< leg_length_max'),
        LimitParameter(
            'leg_length_max', 'm', math.inf,
            'Longest allowed leg length (actuator fully extended), metres; .inf for no limit',
            (InRange(0.0, math.inf, low_inclusive=False),), note='> leg_length_min'),
    ),
    bounds=(BoundLook('leg_length_min', 'leg_length_min (stroke)', (0.12, 0.47, 0.71)),
            BoundLook('leg_length_max', 'leg_length_max (stroke)', (0.84, 0.15, 0.16))),
    pose_evaluator=_evaluator,
    leg_state_names=('leg_length_min', 'leg_length_max'),
    leg_state_evaluators=lambda limits, actuator_limits, slack: (
        () if limits is None else (Stroke.of(limits),)),
    rules=(_ordered,),
    narrowed=_narrowed,
)
