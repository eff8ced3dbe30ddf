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
One broken limit, as every check of the limits model reports it.

Nothing here imports ROS.
"""

from dataclasses import dataclass
from typing import Optional, Tuple


@dataclass(frozen=True)
class Violation:
    """
    One limit that a pose, a pair of legs or a leg state breaks.

    :param limit: the limit's parameter name, such as ``leg_length_max``.
    :param leg: the leg concerned, 1..6, or ``None`` for the whole platform.
    :param value: the value reached, in ``unit``: a length, an angle, a condition number, a
        leg speed, or (``leg_collision``) the distance between two legs' axes.
    :param allowed: the limit, in ``unit`` (for ``leg_collision``, ``2 * leg_radius``).
    :param unit: ``m``, ``deg``, ``m/s``, ``m/s^2``, ``m/s^3`` or ``''`` (condition number).
    :param other_leg: the second leg of a pair (``leg_collision``), else ``None``.
    """

    limit: str
    leg: Optional[int]
    value: float
    allowed: float
    unit: str
    other_leg: Optional[int] = None

    @property
    def excess(self) -> float:
        """By how much the limit is broken, in ``unit``, always positive."""
        return abs(self.value - self.allowed)

    @property
    def legs(self) -> Tuple[Optional[int], ...]:
        """Return the legs concerned: ``(3,)``, ``(2, 3)`` for a pair, ``(None,)``: platform."""
        return (self.leg,) if self.other_leg is None else (self.leg, self.other_leg)

    @property
    def subject(self) -> str:
        """Return who breaks it, in words: ``leg 3``, ``legs 2 and 3`` or ``platform``."""
        if self.other_leg is not None:
            return f'legs {self.leg} and {self.other_leg}'
        return f'leg {self.leg}' if self.leg else 'platform'

    def __str__(self):
        unit = f' {self.unit}' if self.unit else ''
        if self.other_leg is not None:
            return (f'{self.subject}: {self.limit}, clearance {self.value - self.allowed:.6g}'
                    f'{unit} (axes {self.value:.6g}{unit} apart, {self.allowed:.6g}{unit} '
                    'needed)')
        return (f'{self.subject}: {self.limit} {self.allowed:.6g}{unit} broken by '
                f'{self.excess:.6g}{unit} (value {self.value:.6g}{unit})')
