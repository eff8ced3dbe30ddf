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
The pose limits' settings: where the platform may be, the home of every limit's value.

:class:`PoseLimits` holds one value per setting of the pose limit kinds
(:data:`~stewart_kinematics.limits.kinds.LIMIT_KINDS`), in SI units, checked with the bounds
their parameters declare; the leg rates are kept by :class:`stewart_kinematics.ActuatorLimits`.
A :class:`stewart_kinematics.Geometry` is given its limits (``Geometry(..., limits=...)``) and
asks them whether its home pose is allowed; a parameter file gives both
(:func:`stewart_kinematics.load_geometry`). Nothing here imports ROS.
"""

from typing import Any, Dict, Mapping

from stewart_kinematics.limits import kinds
from stewart_kinematics.limits.kind import CueMargins
from stewart_kinematics.limits.limit_model import LimitModel
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.rotations import euler_zyx_to_matrix


class PoseLimits:
    """
    The values of the pose limits, SI units; every one not given sets no limit.

    One keyword per setting of the pose limit kinds, in SI units (metres, radians): today
    ``leg_length_min``, ``leg_length_max`` (m), ``base_joint_max_angle``,
    ``platform_joint_max_angle`` (rad, in (0, pi]), ``max_jacobian_condition`` (>= 1) and
    ``leg_radius`` (m, in [0, 1]). Read them as attributes (``limits.leg_length_max``).
    Immutable; :meth:`replace` gives a copy with some changed.

    :raises ValueError: for a name that is no pose limit's setting, a value outside the bounds
        of its parameter (converted to SI units; the same rule a parameter file meets), or
        values that break a rule between them (``leg_length_min < leg_length_max``), naming
        the setting, the value and what is allowed.

    >>> import math
    >>> from stewart_kinematics import PoseLimits
    >>> limits = PoseLimits(leg_length_max=0.9, base_joint_max_angle=math.radians(40.0))
    >>> limits.leg_length_max, limits.leg_length_min, limits.is_set('leg_radius')
    (0.9, 0.0, False)
    >>> PoseLimits(leg_radius=2.0)
    Traceback (most recent call last):
    ...
    ValueError: leg_radius must be in [0, 1], got 2.0
    """

    __slots__ = ('_values',)

    def __init__(self, **values):
        settings = kinds.pose_settings()
        unknown = sorted(set(values) - set(settings))
        if unknown:
            raise ValueError(f'{unknown[0]!r} is not a pose limit; the pose limits are '
                             f'{", ".join(settings)}')
        checked = {name: _checked(parameter, values.get(name, parameter.setting_default))
                   for name, parameter in settings.items()}
        object.__setattr__(self, '_values', checked)
        for kind in kinds.LIMIT_KINDS:
            for rule in kind.rules:
                reason = rule(self)
                if reason:
                    raise ValueError(reason)

    @classmethod
    def from_parameters(cls, values: Mapping[str, Any]) -> 'PoseLimits':
        """
        Return the limits that parameter values give, in the parameters' units.

        :param values: parameter name (``base_joint_max_angle_deg``, ...) -> value; others are
            ignored, and a missing one sets no limit.
        """
        return cls(**{parameter.setting_name: parameter.setting_value(values[parameter.name])
                      for parameter in kinds.pose_settings().values()
                      if parameter.name in values})

    def __getattr__(self, name):
        values = object.__getattribute__(self, '_values') if name != '_values' else None
        if values is None or name not in values:
            raise AttributeError(f'{type(self).__name__} has no setting {name!r}')
        return values[name]

    def __setattr__(self, name, value):
        raise AttributeError(f'{type(self).__name__} is immutable; use replace()')

    def __reduce__(self):
        return (_restore, (self.values(),))

    def __eq__(self, other):
        return isinstance(other, PoseLimits) and self.values() == other.values()

    def __hash__(self):
        return hash(tuple(self.values().items()))

    def __repr__(self):
        given = ', '.join(f'{name}={value!r}' for name, value in self.values().items()
                          if self.is_set(name))
        return f'{type(self).__name__}({given})'

    def values(self) -> Dict[str, float]:
        """Return setting name -> value, SI units, every setting (those not set included)."""
        return dict(self._values)

    def parameters(self) -> Dict[str, float]:
        """Return parameter name -> value, in the parameters' units, as a file writes them."""
        return {parameter.name: parameter.parameter_value(self._values[name])
                for name, parameter in kinds.pose_settings().items()}

    def is_set(self, name: str) -> bool:
        """Whether the setting ``name`` sets a limit (its value is not the one that sets none)."""
        return self._values[name] != kinds.pose_settings()[name].setting_default

    def replace(self, **changes) -> 'PoseLimits':
        """Return a copy with some settings changed (SI units), checked as on construction."""
        return type(self)(**{**self._values, **changes})

    def narrowed(self, margins: CueMargins) -> 'PoseLimits':
        """
        Return these limits drawn in by the cue's margins; limits not set stay unset.

        Each kind says how its values narrow (:attr:`~.kind.LimitKind.narrowed`).

        :raises ValueError: if the narrowed values are not allowed.
        """
        changes = {}
        for kind in kinds.LIMIT_KINDS:
            if kind.narrowed is not None:
                changes.update(kind.narrowed(self, margins))
        return self.replace(**changes)

    def check_home(self, geometry) -> None:
        """
        Refuse a geometry whose home pose breaks these limits, naming every violation.

        Called by :class:`stewart_kinematics.Geometry` on construction, with itself.

        :raises ValueError: listing the violations (two legs that collide there included).
        """
        violations = LimitModel.of_geometry(geometry).check_pose(
            geometry.home_pose[:3], euler_zyx_to_matrix(geometry.home_pose[3:]))
        if violations:
            raise ValueError('the home pose breaks the limits: '
                             + '; '.join(str(violation) for violation in violations))


def limits_of(geometry) -> PoseLimits:
    """Return the limits of a geometry: its :attr:`limits`, or none set when it has none."""
    limits = geometry.limits
    return PoseLimits() if limits is None else limits


def _checked(parameter, value) -> float:
    """Return a setting as a float, or refuse what is not one number its rules allow."""
    name = parameter.setting_name
    array = as_float_array(value, name)
    if array.shape != ():
        raise ValueError(f'{name} must be one number, got {preview(value)}')
    reason = parameter.setting_reason(float(array))
    if reason:
        raise ValueError(reason)
    return float(array)


def _restore(values) -> PoseLimits:
    return PoseLimits(**values)
