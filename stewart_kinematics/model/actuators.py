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
The six leg actuators as a motion controller sees them: their limits, names and zeros.

:class:`ActuatorLimits` holds how fast the legs may move (velocity, acceleration, jerk), the
limits that timed motion must respect (:mod:`stewart_kinematics.trajectories`,
:mod:`stewart_kinematics.motion.streaming`). They are kept apart from
:class:`stewart_kinematics.Geometry`, which says *where* the platform may be (stroke, joint
cones, singularity margin) and is checked on every single pose: a pose has no speed, and the
IK and FK paths never need these limits.

:class:`ActuatorInterface` maps leg lengths to the positions an actuator driver or ros2_control
uses: joint names, and each actuator's zero as a leg length (``position = length - offset``).

Nothing here imports ROS.
"""

from dataclasses import dataclass, field
import math
from typing import Sequence, Tuple

import numpy as np

from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.validators import first_reason, InRange

#: The allowed values of each leg rate limit (m/s, m/s^2, m/s^3): ``inf`` for no limit. The
#: leg-rate limit kind (:mod:`stewart_kinematics.limits.leg_rates`) declares its parameters with
#: these rules, which :class:`ActuatorLimits` checks, so a parameter file and a Python caller
#: meet one rule.
RATE_MAX_RULES = (InRange(0.0, math.inf, low_inclusive=False),)
#: Default joint names of the legs, leg 1..6.
DEFAULT_JOINT_NAMES = ('leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5', 'leg_6')


@dataclass(frozen=True)
class ActuatorLimits:
    """
    How fast every leg may change its length; ``inf`` means no limit.

    :param velocity_max: largest leg velocity, metres per second, > 0.
    :param acceleration_max: largest leg acceleration, metres per second squared, > 0.
    :param jerk_max: largest leg jerk, metres per second cubed, > 0.
    :raises ValueError: if a limit is not positive (NaN included).
    """

    velocity_max: float = math.inf
    acceleration_max: float = math.inf
    jerk_max: float = math.inf

    def __post_init__(self):
        for name in ('velocity_max', 'acceleration_max', 'jerk_max'):
            value = as_float_array(getattr(self, name), f'leg_{name}')
            if value.shape != ():
                raise ValueError(f'leg_{name} must be one number, got {preview(value)}')
            value = float(value)
            # The rule of the parameter leg_<name>: > 0, .inf allowed.
            reason = first_reason(RATE_MAX_RULES, f'leg_{name}', value)
            if reason:
                raise ValueError(f'{reason} (.inf for no limit)')
            object.__setattr__(self, name, value)

    @property
    def limits_speed(self) -> bool:
        """Return whether a velocity or an acceleration limit is set."""
        return math.isfinite(self.velocity_max) or math.isfinite(self.acceleration_max)

    def scaled(self, speed_scale: float) -> 'ActuatorLimits':
        """
        Limits of the same motion played ``speed_scale`` times as fast.

        Playing a trajectory at ``1 / speed_scale`` of its duration scales its velocities by
        ``speed_scale``, its accelerations by its square and its jerks by its cube.

        :param speed_scale: in (0, 1].
        :raises ValueError: if ``speed_scale`` is not in (0, 1].
        """
        if not (isinstance(speed_scale, (int, float, np.integer, np.floating))
                and not isinstance(speed_scale, bool) and 0.0 < speed_scale <= 1.0):
            raise ValueError(f'speed_scale must be in (0, 1], got {speed_scale!r}')
        return ActuatorLimits(self.velocity_max * speed_scale,
                              self.acceleration_max * speed_scale ** 2,
                              self.jerk_max * speed_scale ** 3)


@dataclass(frozen=True, eq=False)
class ActuatorInterface:
    """
    The legs as six prismatic joints: names and zeros, as JointState and JointTrajectory use.

    :param joint_names: six distinct, non-empty names, leg 1..6.
    :param offsets: each actuator's zero as a leg length, metres, shape (6,): an actuator's
        position is its leg length minus its offset.
    :raises ValueError: if there are not six distinct names or six finite offsets.
    """

    joint_names: Tuple[str, ...] = DEFAULT_JOINT_NAMES
    offsets: np.ndarray = field(default_factory=lambda: np.zeros(6))

    def __post_init__(self):
        names = tuple(self.joint_names)
        if len(names) != 6 or len(set(names)) != 6 or not all(
                isinstance(name, str) and name for name in names):
            raise ValueError(f'joint_names must be 6 distinct, non-empty names, got '
                             f'{preview(names)}')
        offsets = np.array(as_float_array(self.offsets, 'actuator_offsets'))
        if offsets.shape != (6,) or not np.all(np.isfinite(offsets)):
            raise ValueError(f'actuator_offsets must be 6 finite values (metres), got '
                             f'{preview(offsets)}')
        offsets.flags.writeable = False
        object.__setattr__(self, 'joint_names', names)
        object.__setattr__(self, 'offsets', offsets)

    def positions(self, lengths) -> np.ndarray:
        """
        Actuator positions of leg lengths: ``length - offset``, metres.

        :param lengths: shape (6,) or (N, 6), metres.
        :raises ValueError: for what is not numbers of that shape.
        """
        return _rows_of_six(lengths, 'lengths') - self.offsets

    def lengths(self, positions) -> np.ndarray:
        """
        Leg lengths of actuator positions: ``position + offset``, metres.

        :param positions: shape (6,) or (N, 6), metres.
        :raises ValueError: for what is not numbers of that shape.
        """
        return _rows_of_six(positions, 'positions') + self.offsets

    def concerns(self, names: Sequence[str]) -> bool:
        """
        Whether a message naming ``names`` is about these legs: it names at least one of them.

        Two platforms may share one ``joint_states``: a message that names none of these joints
        is another platform's, to be skipped (not refused: nothing is wrong with it).

        :param names: the joint names of a JointState, in any order.
        """
        return any(name in names for name in self.joint_names)

    def order(self, names: Sequence[str]) -> np.ndarray:
        """
        Where each leg's joint is in a message's list of names (other joints are ignored).

        :param names: the joint names of a JointState or JointTrajectory, in any order.
        :returns: indices into ``names``, leg 1..6, shape (6,).
        :raises ValueError: naming the joints that are missing or repeated.
        """
        names = list(names)
        missing = [name for name in self.joint_names if name not in names]
        repeated = [name for name in self.joint_names if names.count(name) > 1]
        if missing or repeated:
            problems = []
            if missing:
                problems.append('missing ' + ', '.join(missing))
            if repeated:
                problems.append('repeated ' + ', '.join(repeated))
            raise ValueError(f'joint names {preview(names)}: {"; ".join(problems)} (legs are '
                             f'{", ".join(self.joint_names)})')
        return np.array([names.index(name) for name in self.joint_names])


def _rows_of_six(values, name) -> np.ndarray:
    """Return ``values`` as floats of shape (6,) or (N, 6), or raise ValueError naming them."""
    values = as_float_array(values, name)
    if values.ndim not in (1, 2) or values.shape[-1] != 6:
        raise ValueError(f'{name} must have shape (6,) or (N, 6), got {values.shape}')
    return values
