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

from stewart_kinematics.limits.base import Bound, LEG, Limit


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
    def of(cls, geometry) -> 'Stroke':
        """Return the stroke of a :class:`stewart_kinematics.Geometry`."""
        return cls(geometry.leg_length_min, geometry.leg_length_max)

    def values(self, arrays):
        """Return the leg lengths, (6, n), for each bound."""
        return (arrays.lengths,) * len(self.bounds)

    def allows(self, sample: dict) -> bool:
        """Whether six lengths (floats, ``sample['lengths']``) keep the stroke."""
        lengths = sample['lengths']
        return all(bound.holds(length) for bound in self.bounds for length in lengths)
