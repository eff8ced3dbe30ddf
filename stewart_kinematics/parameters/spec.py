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
The declaration of one ROS parameter, and the validators a declaration uses.

Each :class:`ParameterSpec` gives a parameter's name, type, default (``None``: required),
description with its unit, read-only flag and validators. A validator takes ``(name, value)``
and returns ``''`` when the value is allowed, else a sentence that names the parameter, the
value and what is allowed. Nothing here imports ROS.
"""

import array
from dataclasses import dataclass
import math
from typing import Any, Callable, Tuple

from stewart_kinematics.model.arrays import preview


Validator = Callable[[str, Any], str]


class NullString(str):
    """
    The string rcl makes of YAML's null: an unquoted ``null``, ``Null``, ``NULL`` or ``~``.

    rcl reads ``name: null`` as the string ``'null'``; the parameter files are read the same
    way, but with this mark, so that a refusal says the value was empty (null), not a string
    written in quotes.
    """

    __slots__ = ()


class OutOfRangeNumber(str):
    """
    A number rcl reads as a string: beyond a double's range, or below its normal range.

    C's strtod sets ERANGE for ``1e999`` and for ``1e-400`` or ``5e-324`` (a subnormal), and
    rcl then keeps the text as a string. Marked so that a refusal says why.
    """

    __slots__ = ()


# Parameter types, spelled as in rcl_interfaces/msg/ParameterType.
BOOL = 'bool'
INTEGER = 'integer'
DOUBLE = 'double'
STRING = 'string'
DOUBLE_ARRAY = 'double_array'
STRING_ARRAY = 'string_array'

_PYTHON_TYPES = {
    BOOL: (bool,),
    INTEGER: (int,),
    DOUBLE: (float,),
    STRING: (str,),
    # rclpy hands double arrays from parameter services over as array.array('d').
    DOUBLE_ARRAY: (list, tuple, array.array),
    STRING_ARRAY: (list, tuple),
}


@dataclass(frozen=True)
class ParameterSpec:
    """
    Declaration of one ROS parameter.

    :param name: parameter name.
    :param value_type: one of ``bool``, ``integer``, ``double``, ``string``, ``double_array``.
    :param description: what it means, with its unit.
    :param default: value used when no parameter file sets it; ``None`` makes it required.
    :param read_only: True where a change at run time makes no sense (the geometry).
    :param validators: checks run on every value, at start-up and on every run-time change.
    :param constraints: the allowed values in words, for the documentation table.
    """

    name: str
    value_type: str
    description: str
    default: Any = None
    read_only: bool = False
    validators: Tuple[Validator, ...] = ()
    constraints: str = ''

    def check(self, value) -> str:
        """
        Check a value against the type and the validators.

        :returns: ``''`` if the value is allowed, else the first reason it is not.
        """
        if value is None:
            if self.default is None:
                return (f"parameter '{self.name}' is required ({self.description}); set it in "
                        'a parameter file')
            return ''
        reason = self.type_reason(value)
        if reason:
            return reason
        for validator in self.validators:
            reason = validator(self.name, value)
            if reason:
                return reason
        return ''

    def type_reason(self, value) -> str:
        """
        Check the type of a value alone (not ``None``), strictly as rcl types parameters.

        :returns: ``''`` if the type is right, else the reason, with a hint for a quoted
            number, an integer written for a double, a null (empty) value or a number
            beyond a double's range.
        """
        marked = _marked_string_of(value, self.value_type)
        if marked is not None:
            where = '' if marked is value else ' in the list'
            if isinstance(marked, NullString):
                return (f"parameter '{self.name}' must be of type {self.value_type}, got "
                        f'{marked}{where} (an empty value in YAML, which ROS reads as the '
                        f"string '{marked}'): write a value, or remove the line to keep the "
                        'default')
            return (f"parameter '{self.name}' must be of type {self.value_type}, got "
                    f'{_short(marked)}{where} (beyond the range of a double: a size from '
                    '2.2e-308 to 1.8e308, or 0; ROS reads it as a string)')
        # Strict as rcl is: YAML's 1 is an integer, and a double parameter wants 1.0.
        if not isinstance(value, _PYTHON_TYPES[self.value_type]) or (
                self.value_type == INTEGER and isinstance(value, bool)):
            hint = ''
            if self.value_type == DOUBLE and isinstance(value, int) and not isinstance(
                    value, bool):
                hint = ' (write 1.0, not 1)'
            elif isinstance(value, str) and self.value_type in (DOUBLE, INTEGER, BOOL) and (
                    _reads_as_number_or_bool(value)):
                hint = ' (a value in quotes is a string: write it without quotes)'
            return (f"parameter '{self.name}' must be of type {self.value_type}, got "
                    f'{preview(value)} ({type(value).__name__}){hint}')
        if self.value_type == DOUBLE_ARRAY and not all(
                isinstance(item, float) and not isinstance(item, bool) for item in value):
            return (f"parameter '{self.name}' must be a list of floating-point numbers, got "
                    f'{preview(list(value))} (write 1.0, not 1, and no quotes)')
        if self.value_type == STRING_ARRAY and not all(isinstance(item, str) for item in value):
            return (f"parameter '{self.name}' must be a list of strings, got "
                    f'{preview(list(value))}')
        return ''


def _reads_as_number_or_bool(text: str) -> bool:
    """Whether a string would be a number or a bool without its quotes (roughly as rcl)."""
    if text.strip().lower() in ('true', 'false', 'yes', 'no', 'on', 'off', 'y', 'n'):
        return True
    try:
        float(text)
    except ValueError:
        return text.strip().lower().startswith(('0x', '+0x', '-0x'))
    return True


def _short(text: str) -> str:
    """Return ``text`` as it is, or its start and its length when it is long."""
    return text if len(text) <= 60 else f'{text[:60]}... ({len(text)} characters)'


def _marked_string_of(value, value_type: str):
    """
    Return the string rcl made of a null or a number out of range that makes ``value`` wrong.

    :returns: the :class:`NullString` or :class:`OutOfRangeNumber` (alone, or the first in a
        list) when the type wants no string there, else ``None``.
    """
    marks = (NullString, OutOfRangeNumber)
    if isinstance(value, marks):
        return None if value_type == STRING else value
    if isinstance(value, (list, tuple)) and value_type != STRING_ARRAY:
        return next((item for item in value if isinstance(item, marks)), None)
    return None


def fixed_length(length: int) -> Validator:
    """Require an array of exactly ``length`` elements."""
    def validate(name, value):
        if len(value) != length:
            return (f"parameter '{name}' must have exactly {length} elements, "
                    f'got {len(value)}: {preview(list(value))}')
        return ''
    return validate


def finite(name, value) -> str:
    """Require a finite number, or an array of finite numbers."""
    values = value if isinstance(value, _PYTHON_TYPES[DOUBLE_ARRAY]) else [value]
    if not all(math.isfinite(item) for item in values):
        return f"parameter '{name}' must be finite, got {preview(value)}"
    return ''


def in_range(low: float, high: float, *, low_inclusive: bool = True,
             high_inclusive: bool = True) -> Validator:
    """Require a number (or every element of an array) within ``[low, high]``."""
    def validate(name, value):
        values = value if isinstance(value, _PYTHON_TYPES[DOUBLE_ARRAY]) else [value]
        for item in values:
            above_low = item >= low if low_inclusive else item > low
            below_high = item <= high if high_inclusive else item < high
            if not (above_low and below_high):
                interval = (('[' if low_inclusive else '(') + f'{low:g}, {high:g}'
                            + (']' if high_inclusive else ')'))
                return f"parameter '{name}' must be in {interval}, got {preview(value)}"
        return ''
    return validate


def zero_or_in_range(low: float, high: float) -> Validator:
    """Require 0 (a feature turned off) or a number within ``[low, high]``."""
    within = in_range(low, high)

    def validate(name, value):
        if value == 0.0 or not within(name, value):
            return ''
        return (f"parameter '{name}' must be 0.0 or in [{low:g}, {high:g}], got "
                f'{preview(value)}')
    return validate


def one_of(*allowed: str) -> Validator:
    """Require one of the given strings."""
    def validate(name, value):
        if value not in allowed:
            return f"parameter '{name}' must be one of {', '.join(allowed)}; got {preview(value)}"
        return ''
    return validate


def distinct_names(name, value) -> str:
    """Require non-empty, distinct strings (joint names)."""
    if not all(value) or len(set(value)) != len(value):
        return (f"parameter '{name}' must hold distinct, non-empty names, got "
                f'{preview(list(value))}')
    return ''


#: The legs as the actuator interface sees them: shared by every JointState and


def frame_name(name, value) -> str:
    """Require a tf frame name: no spaces, no leading slash (tf2 refuses those)."""
    if value.startswith('/') or any(character.isspace() for character in value):
        return (f"parameter '{name}' must be a frame name without spaces or a leading '/', "
                f'got {preview(value)}')
    return ''


def non_empty(name, value) -> str:
    """Require a non-empty string."""
    return '' if value else f"parameter '{name}' must not be empty"


#: The frame tree (stewart_kinematics.model.frames): names, and the user and tool frames' poses.
