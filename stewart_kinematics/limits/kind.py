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
What a kind of limit declares about itself: its parameters, its bounds, its evaluators.

Each kind's module (:mod:`.stroke`, :mod:`.joint_cones`, ...) holds one :class:`LimitKind`,
``KIND``, beside its evaluator, and :data:`stewart_kinematics.limits.kinds.LIMIT_KINDS` lists
them. Everything that lists limits derives from that list: the limits model's evaluators and
report order, the limit settings (:class:`~stewart_kinematics.limits.settings.PoseLimits`),
the parameter specs, the workspace markers and figures, calibration's write-out, the cue's
margins and the documentation's tables. Nothing here imports ROS.
"""

from dataclasses import dataclass
from typing import Callable, Optional, Tuple

from stewart_kinematics.model.validators import first_reason, Validator

#: Where a parameter's value is kept: the pose limits' settings, or the actuators' limits.
POSE, ACTUATOR = 'pose', 'actuator'


@dataclass(frozen=True)
class LimitParameter:
    """
    One parameter of a limit kind: the ROS parameter and the setting it becomes.

    :param name: the parameter's name, as a parameter file gives it (``leg_length_max``,
        ``base_joint_max_angle_deg``).
    :param unit: the parameter's unit (``m``, ``deg``, ``m/s``; ``''`` for a ratio).
    :param default: the parameter's default, in its unit; it is also the value that sets no
        limit (0 for a lower bound, ``inf`` or the largest angle for an upper one).
    :param description: the parameter's description, with its unit, for its spec and tables.
    :param validators: its allowed values, in the parameter's unit
        (:mod:`stewart_kinematics.model.validators`): the parameter file, the settings and the
        documentation use these, and no other, bounds.
    :param setting: the setting's name, in SI units (``base_joint_max_angle``); the parameter's
        name when empty.
    :param to_setting: the parameter's value to the setting's (``math.radians``); ``None``:
        the same value.
    :param to_parameter: the inverse (``math.degrees``), for writing the parameter back.
    :param keeps: :data:`POSE` (kept by :class:`~.settings.PoseLimits`) or :data:`ACTUATOR`
        (kept by :class:`stewart_kinematics.ActuatorLimits`, as ``setting``).
    :param note: a rule between parameters that the validators cannot say, for the tables
        (``< leg_length_max``); the kind's :attr:`LimitKind.rules` check it.
    """

    name: str
    unit: str
    default: float
    description: str
    validators: Tuple[Validator, ...]
    setting: str = ''
    to_setting: Optional[Callable[[float], float]] = None
    to_parameter: Optional[Callable[[float], float]] = None
    keeps: str = POSE
    note: str = ''

    @property
    def setting_name(self) -> str:
        """Return the setting's name (SI units)."""
        return self.setting or self.name

    @property
    def setting_default(self) -> float:
        """Return the default in SI units: the value that sets no limit."""
        return self.setting_value(self.default)

    def setting_value(self, value: float) -> float:
        """Return the setting's value (SI units) of a parameter value."""
        return value if self.to_setting is None else self.to_setting(value)

    def parameter_value(self, value: float) -> float:
        """Return the parameter's value of a setting's value (SI units)."""
        return value if self.to_parameter is None else self.to_parameter(value)

    def setting_reason(self, value: float) -> str:
        """
        Say why a setting's value (SI units) is not allowed, or return ``''``.

        The parameter's own validators, converted to SI units where the units differ.
        """
        validators = self.validators if self.to_setting is None else tuple(
            rule.converted(self.to_setting) for rule in self.validators)
        return first_reason(validators, self.setting_name, value)


@dataclass(frozen=True)
class BoundLook:
    """
    How one bound of a kind is reported and drawn: a workspace boundary met there.

    :param name: the bound's name, as its :class:`~.base.Bound` and violations give it.
    :param label: its legend in the workspace figures.
    :param colour: ``(r, g, b)``, each in [0, 1]: its colour in the figures and markers.
    :param relative: whether its excess is compared as a share of the allowed value (a
        dimensionless bound such as the condition number) when excesses of several limits are
        compared (:func:`stewart_kinematics.cueing.limit_margins.limit_margins`).
    """

    name: str
    label: str
    colour: Tuple[float, float, float]
    relative: bool = False


@dataclass(frozen=True)
class LimitKind:
    """
    One kind of limit: everything about it, declared in its own module.

    :param name: the kind's name (``stroke``).
    :param title: its name in the documentation's tables (``Actuator stroke``).
    :param meaning: what it limits, for the documentation's table of limits.
    :param evaluator: the name of its evaluator class, for the documentation.
    :param parameters: its :class:`LimitParameter` objects.
    :param bounds: the :class:`BoundLook` of each bound its pose evaluator reports, in report
        order (empty for a kind of leg states alone).
    :param leg_state_names: the names of the bounds its leg-state evaluators report, in order.
    :param pose_evaluator: ``(geometry, limits) -> Limit``: the evaluator of its pose limits,
        from a geometry and its :class:`~.settings.PoseLimits`; ``None`` for none.
    :param leg_state_evaluators: ``(limits, actuator_limits, slack) -> (Limit, ...)``: its
        evaluators of leg states (lengths and their derivatives); ``None`` for none.
    :param rules: checks between its parameters, ``limits -> reason or ''`` (SI settings).
    :param narrowed: ``(limits, margins) -> {setting: value}``: its settings drawn in by the
        cue's margins (:class:`CueMargins`), only those that are set; ``None``: kept as they are.
    """

    name: str
    title: str
    meaning: str
    evaluator: str
    parameters: Tuple[LimitParameter, ...]
    bounds: Tuple[BoundLook, ...] = ()
    leg_state_names: Tuple[str, ...] = ()
    pose_evaluator: Optional[Callable] = None
    leg_state_evaluators: Optional[Callable] = None
    rules: Tuple[Callable, ...] = ()
    narrowed: Optional[Callable] = None


@dataclass(frozen=True)
class CueMargins:
    """
    How far inside its limits the motion cue keeps, for :attr:`LimitKind.narrowed`.

    :param length: metres off each end of a length limit.
    :param angle: radians off each angle limit.
    :param condition: the share of a condition-number limit kept, in (0, 1].
    """

    length: float
    angle: float
    condition: float
