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
Validators: the rules a value must keep, as data that checks a value and describes itself.

In the spirit of generate_parameter_library's ``bounds<>``, ``fixed_size<>`` and ``one_of<>``,
each validator holds its rule as data (bounds, a length, the choices) and has two faces:

- ``validator(name, value)`` checks a parameter's value, ``validator.reason(subject, value)``
  any named value: ``''`` when the value is allowed, else one sentence that names the value and
  what is allowed;
- ``validator.describe()`` says what is allowed, in words (``'in [0, 10000]'``): the parameter
  tables of the documentation and the parameters' descriptors print it, so the text cannot
  drift from the check (:attr:`stewart_kinematics.parameters.ParameterSpec.constraints`
  composes a parameter's descriptions).

The parameter specs (:mod:`stewart_kinematics.parameters.declarations`) hold these objects, and so
do the limit kinds' parameters (:class:`stewart_kinematics.limits.LimitParameter`), which the limit
settings check with: here, in model/, because every folder of the core may import it. A validator
checks a value of the right type (numbers, or a list of them; a string; a list of strings): the
type is checked before it.

>>> bound = InRange(0.0, 10.0, low_inclusive=False)
>>> bound.describe()
'in (0, 10]'
>>> bound('tilt_damping', 0.0)
"parameter 'tilt_damping' must be in (0, 10], got 0.0"
>>> bound('tilt_damping', 1.0)
''
"""

import array
from dataclasses import dataclass
import ipaddress
import math
from typing import Any, Callable, Tuple

import numpy as np

from stewart_kinematics.model.arrays import preview

#: The containers a value of several numbers or names comes in (rclpy hands double arrays over
#: as ``array.array('d')``).
_SEQUENCES = (list, tuple, array.array)


def _items(value):
    """Return the values of an array, or a number alone as a list of one."""
    return value if isinstance(value, _SEQUENCES) else [value]


def _number(value: float) -> str:
    """Write a bound as the documentation shows it: ``0.002``, ``10000``, ``inf``."""
    return f'{value:g}'


class Validator:
    """
    A rule a value must keep: checks a value (:meth:`reason`) and describes itself.

    Subclasses define :meth:`reason` and :meth:`describe`; calling a validator checks a
    parameter's value, named as a parameter.
    """

    def __call__(self, name: str, value: Any) -> str:
        """Check the value of parameter ``name``: ``''``, or why it is not allowed."""
        return self.reason(f"parameter '{name}'", value)

    def reason(self, subject: str, value: Any) -> str:
        """
        Check a value: ``''`` if it is allowed, else one sentence saying why.

        :param subject: what the value is, to open the sentence (``"parameter 'x'"``,
            ``'leg_radius'``).
        """
        raise NotImplementedError

    def describe(self) -> str:
        """Say what is allowed, in words, as the documentation's tables show it."""
        raise NotImplementedError

    def converted(self, convert: Callable[[float], float]) -> 'Validator':
        """
        Return this rule for values in other units (``math.radians`` for a rule in degrees).

        A rule without numbers (a length, finiteness) is returned as it is.
        """
        return self


@dataclass(frozen=True)
class Finite(Validator):
    """Require a finite number, or an array of finite numbers (no NaN, no infinity)."""

    def reason(self, subject: str, value: Any) -> str:
        """Refuse NaN and infinities."""
        if not all(math.isfinite(item) for item in _items(value)):
            return f'{subject} must be finite, got {preview(value)}'
        return ''

    def describe(self) -> str:
        """Return ``'finite'``."""
        return 'finite'


@dataclass(frozen=True)
class InRange(Validator):
    """
    Require a number (or every number of an array) within bounds.

    :param low: the lowest allowed value (``-inf``: no lower bound).
    :param high: the highest allowed value (``inf``: no upper bound; with ``high_inclusive``,
        infinity itself is allowed).
    :param low_inclusive: whether ``low`` itself is allowed.
    :param high_inclusive: whether ``high`` itself is allowed.
    """

    low: float
    high: float
    low_inclusive: bool = True
    high_inclusive: bool = True

    def __post_init__(self):
        if not self.low <= self.high:
            raise ValueError(f'InRange needs low <= high, got {self.low!r}, {self.high!r}')

    def contains(self, value: float) -> bool:
        """Whether one number is within the bounds (NaN never is)."""
        above_low = value >= self.low if self.low_inclusive else value > self.low
        below_high = value <= self.high if self.high_inclusive else value < self.high
        return above_low and below_high

    @property
    def interval(self) -> str:
        """Return the bounds as an interval: ``'(0, 10]'``, ``'[1, inf]'``."""
        return (('[' if self.low_inclusive else '(') + f'{_number(self.low)}, '
                f'{_number(self.high)}' + (']' if self.high_inclusive else ')'))

    @property
    def allows_infinity(self) -> bool:
        """Whether ``inf`` itself is allowed (a limit that ``.inf`` turns off)."""
        return self.high == math.inf and self.high_inclusive

    def reason(self, subject: str, value: Any) -> str:
        """Refuse a number outside the bounds (NaN included), naming the interval."""
        if not all(self.contains(item) for item in _items(value)):
            return f'{subject} must be in {self.interval}, got {preview(value)}'
        return ''

    def describe(self) -> str:
        """Return ``'in [low, high]'``, or ``'> low'`` / ``'>= low'`` without an upper bound."""
        if self.high == math.inf and self.low > -math.inf:
            return ('>= ' if self.low_inclusive else '> ') + _number(self.low)
        if self.low == -math.inf and self.high < math.inf:
            return ('<= ' if self.high_inclusive else '< ') + _number(self.high)
        return f'in {self.interval}'

    def converted(self, convert: Callable[[float], float]) -> 'InRange':
        """Convert both bounds (``math.radians``): the same interval in other units."""
        return InRange(convert(self.low), convert(self.high), low_inclusive=self.low_inclusive,
                       high_inclusive=self.high_inclusive)


@dataclass(frozen=True)
class ZeroOrInRange(Validator):
    """
    Require 0 (a feature turned off) or a number within ``[low, high]``.

    :param low: the lowest allowed value other than 0 (above 0).
    :param high: the highest allowed value.
    """

    low: float
    high: float

    def reason(self, subject: str, value: Any) -> str:
        """Refuse a number that is neither 0 nor within the bounds."""
        if value == 0.0 or InRange(self.low, self.high).contains(value):
            return ''
        return (f'{subject} must be 0.0 or in [{_number(self.low)}, {_number(self.high)}], got '
                f'{preview(value)}')

    def describe(self) -> str:
        """Return ``'0.0 or in [low, high]'``."""
        return f'0.0 or in [{_number(self.low)}, {_number(self.high)}]'

    def converted(self, convert: Callable[[float], float]) -> 'ZeroOrInRange':
        """Return the same rule with the bounds converted."""
        return ZeroOrInRange(convert(self.low), convert(self.high))


@dataclass(frozen=True)
class FixedLength(Validator):
    """
    Require an array of exactly ``length`` elements.

    :param length: the number of elements.
    """

    length: int

    def reason(self, subject: str, value: Any) -> str:
        """Refuse an array of another length."""
        if len(value) != self.length:
            return (f'{subject} must have exactly {self.length} elements, got {len(value)}: '
                    f'{preview(list(value))}')
        return ''

    def describe(self) -> str:
        """Return ``'<length> values'``."""
        return f'{self.length} values'


class OneOf(Validator):
    """
    Require one of the given values (strings, or integers such as a filter's order).

    :param allowed: every allowed value, in the order the documentation lists them.
    """

    def __init__(self, *allowed):
        if not allowed:
            raise ValueError('OneOf needs at least one allowed value')
        self.allowed: Tuple[Any, ...] = allowed

    def __eq__(self, other) -> bool:
        return isinstance(other, OneOf) and other.allowed == self.allowed

    def __hash__(self) -> int:
        return hash(self.allowed)

    def __repr__(self) -> str:
        return f'OneOf{self.allowed!r}'

    def reason(self, subject: str, value: Any) -> str:
        """Refuse any other value (``True`` is not the integer 1 here)."""
        if isinstance(value, bool) or value not in self.allowed:
            return (f'{subject} must be one of {", ".join(map(str, self.allowed))}; got '
                    f'{preview(value)}')
        return ''

    def describe(self) -> str:
        """Return ``"'a', 'b' or 'c'"`` (strings quoted), ``'1 or 2'``."""
        shown = [repr(value) if isinstance(value, str) else str(value) for value in self.allowed]
        return shown[0] if len(shown) == 1 else f'{", ".join(shown[:-1])} or {shown[-1]}'


@dataclass(frozen=True)
class NonEmpty(Validator):
    """Require a non-empty string."""

    def reason(self, subject: str, value: Any) -> str:
        """Refuse ``''``."""
        return '' if value else f'{subject} must not be empty'

    def describe(self) -> str:
        """Return ``'not empty'``."""
        return 'not empty'


#: Longest frame name taken, characters: a name goes into every stamped output and /tf_static,
#: and a longer one is a mistake, not a frame (the soak found 10,000 on /tf_static).
MAX_FRAME_NAME_LENGTH = 256


@dataclass(frozen=True)
class FrameName(Validator):
    """
    Require a tf frame name (or ``''``): no spaces, no leading slash (tf2 refuses those).

    At most :data:`MAX_FRAME_NAME_LENGTH` characters.
    """

    def reason(self, subject: str, value: Any) -> str:
        """Refuse a name with a space or a leading ``/``, or a name too long."""
        if value.startswith('/') or any(character.isspace() for character in value):
            return (f"{subject} must be a frame name without spaces or a leading '/', got "
                    f'{preview(value)}')
        if len(value) > MAX_FRAME_NAME_LENGTH:
            return (f'{subject} must be a frame name of at most {MAX_FRAME_NAME_LENGTH} '
                    f'characters, got {len(value)}')
        return ''

    def describe(self) -> str:
        """Return what a frame name may not hold."""
        return (f"a frame name (no spaces, no leading '/', at most {MAX_FRAME_NAME_LENGTH} "
                'characters)')


@dataclass(frozen=True)
class DistinctNames(Validator):
    """Require non-empty, distinct strings (joint names)."""

    def reason(self, subject: str, value: Any) -> str:
        """Refuse an empty name or a name given twice."""
        if not all(value) or len(set(value)) != len(value):
            return (f'{subject} must hold distinct, non-empty names, got '
                    f'{preview(list(value))}')
        return ''

    def describe(self) -> str:
        """Return ``'distinct, non-empty names'``."""
        return 'distinct, non-empty names'


@dataclass(frozen=True)
class LegSelection(Validator):
    """
    Require legs named by number (1..6) or by name, separated by commas or spaces, or ``''``.

    Whether a name is one of the platform's joint names is a rule between parameters, checked
    where the names are known.
    """

    def reason(self, subject: str, value: Any) -> str:
        """Refuse a number other than 1..6, or a word that is neither a number nor a name."""
        for word in value.replace(',', ' ').split():
            if word.isdigit() and word in ('1', '2', '3', '4', '5', '6'):
                continue
            if word[0].isdigit() or not all(c.isalnum() or c == '_' for c in word):
                return (f'{subject} must name legs by number 1..6 or by joint name, separated '
                        f'by commas or spaces, got {preview(word)} in {preview(value)}')
        return ''

    def describe(self) -> str:
        """Return what a selection of legs may hold."""
        return "leg numbers 1..6 or joint names, separated by commas or spaces, or ''"


@dataclass(frozen=True)
class IPv4Address(Validator):
    """Require an IPv4 address in dotted decimal (``'127.0.0.1'``, ``'0.0.0.0'``): a socket's."""

    def reason(self, subject: str, value: Any) -> str:
        """Refuse anything ``ipaddress.IPv4Address`` refuses (names, IPv6, leading zeros)."""
        try:
            ipaddress.IPv4Address(value)
        except ValueError:
            return (f"{subject} must be an IPv4 address such as '127.0.0.1' or '0.0.0.0', got "
                    f'{preview(value)}')
        return ''

    def describe(self) -> str:
        """Return what an address may be."""
        return "an IPv4 address, such as '127.0.0.1' or '0.0.0.0'"


def first_reason(validators, subject: str, value: Any) -> str:
    """
    Check a value against several validators in order.

    :param validators: the :class:`Validator` objects.
    :param subject: what the value is, for the sentence (``'leg_radius'``).
    :returns: ``''`` if every validator allows the value, else the first reason it is refused.
    """
    for validator in validators:
        reason = validator.reason(subject, value)
        if reason:
            return reason
    return ''


#: Relative tolerance of the checks of an inertia tensor (positive semi-definite, triangle
#: inequality), of its trace: what rounding the entries written in a file may break.
INERTIA_TOLERANCE = 1e-9
#: Largest magnitude of an inertia tensor's entry, kg m^2: beyond it the principal moments
#: are not computed reliably (and their squares overflow).
INERTIA_ENTRY_MAX = 1e150


@dataclass(frozen=True)
class InertiaTensor(Validator):
    """
    Require the six entries ``[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]`` of an inertia tensor (kg m^2).

    As URDF's ``<inertia>`` element writes them. The tensor must be positive semi-definite and
    its principal moments must keep the triangle inequality (each at most the sum of the other
    two), both to :data:`INERTIA_TOLERANCE` of the trace; every entry below
    :data:`INERTIA_ENTRY_MAX`. A value that is not six finite numbers is left to
    :class:`FixedLength` and :class:`Finite`.
    """

    def reason(self, subject: str, value: Any) -> str:
        """Refuse a tensor that is not positive semi-definite or breaks the triangle inequality."""
        entries = list(_items(value))
        if len(entries) != 6 or not all(math.isfinite(item) for item in entries):
            return ''
        if not all(abs(item) < INERTIA_ENTRY_MAX for item in entries):
            return (f'{subject} must have entries below 1e150 kg m^2, got '
                    f'{preview(value)}')
        ixx, iyy, izz, ixy, ixz, iyz = entries
        with np.errstate(all='ignore'):
            moments = np.linalg.eigvalsh(np.array(
                [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]))
        tolerance = INERTIA_TOLERANCE * abs(ixx + iyy + izz)
        low, middle, high = moments.tolist()
        if low < -tolerance:
            return (f'{subject} must be positive semi-definite (principal moments >= 0), '
                    f'got {preview(value)} with principal moments '
                    f'{low:.6g}, {middle:.6g}, {high:.6g}')
        if low + middle < high - tolerance:
            return (f'{subject} must keep the triangle inequality of its principal moments '
                    f'(each at most the sum of the other two), got '
                    f'{preview(value)} with principal moments '
                    f'{low:.6g}, {middle:.6g}, {high:.6g}')
        return ''

    def describe(self) -> str:
        """Return the rule in words."""
        return ('forming an inertia tensor (positive semi-definite, principal moments within '
                'the triangle inequality)')
