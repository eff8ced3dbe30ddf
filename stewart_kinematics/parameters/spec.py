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
The declaration of one ROS parameter, with the validators it uses.

Each :class:`ParameterSpec` gives a parameter's name, type, default (``None``: required),
description with its unit, read-only flag and validators: objects of
:mod:`stewart_kinematics.model.validators` (re-exported here), each of which checks a value
(``''`` when it is allowed, else a sentence that names the parameter, the value and what is
allowed) and describes itself. A spec's :attr:`~ParameterSpec.constraints`, the allowed values
in words that the documentation's tables and the ROS descriptors show, is composed from those
descriptions, so it cannot say other than the check does::

    >>> spec = ParameterSpec('head_position', DOUBLE_ARRAY, 'metres', default=[0.0, 0.0, 0.5],
    ...                      validators=(FixedLength(3), Finite(), InRange(-10.0, 10.0)))
    >>> spec.constraints
    '3 values in [-10, 10]'
    >>> spec.check([0.0, 0.0, 11.0])
    "parameter 'head_position' must be in [-10, 10], got [0.0, 0.0, 11.0]"

Nothing here imports ROS.
"""

import array
from dataclasses import dataclass
import math
from typing import Any, Tuple

from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.validators import (
    DistinctNames,
    Finite,
    FixedLength,
    FrameName,
    InRange,
    NonEmpty,
    OneOf,
    Validator,
    ZeroOrInRange,
)


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
    :param validators: checks run on every value, at start-up and on every run-time change
        (:class:`~stewart_kinematics.model.validators.Validator` objects, which describe
        themselves for :attr:`constraints`).
    :param note: what is allowed beyond what the validators say, in words, for a rule they
        cannot check alone (between parameters, such as ``< leg_length_max``; or checked
        where the value is used, such as joints that are not collinear); ``''`` for none.
    """

    name: str
    value_type: str
    description: str
    default: Any = None
    read_only: bool = False
    validators: Tuple[Validator, ...] = ()
    note: str = ''

    @property
    def constraints(self) -> str:
        """
        Return the allowed values in words: the validators' descriptions, then the note.

        Phrased for the type (``'3 values in [-10, 10]'``, ``'> 0; .inf allowed'``,
        ``"'refuse' or 'scale'"``); ``''`` when any value of the type is allowed.
        """
        parts = (describe(self.value_type, self.validators), self.note)
        return '; '.join(part for part in parts if part)

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


def describe(value_type: str, validators) -> str:
    """
    Compose the descriptions of a parameter's validators into the allowed values, in words.

    Numbers: ``'in (0, 100]'``; ``'finite, >= 0'`` (finite said only where no bound implies
    it); ``'> 0; .inf allowed'`` (a bound open to infinity, without :class:`Finite`). Arrays:
    ``'3 values in [-180, 180]'``, ``'18 finite values'``, ``'6 distinct, non-empty names'``.
    Strings: ``"a frame name (no spaces, no leading '/') or ''"``, ``"'table' or 'off'"``.

    :param value_type: the parameter's type (:data:`DOUBLE`, ...).
    :param validators: its validators.
    :returns: the text, or ``''`` when nothing but the type is required.
    """
    length = next((f'{rule.length} ' for rule in validators if isinstance(rule, FixedLength)),
                  '')
    kinds = {type(rule) for rule in validators}
    words = [rule.describe() for rule in validators
             if not isinstance(rule, (FixedLength, Finite, NonEmpty, FrameName, DistinctNames))]
    if value_type in (STRING, STRING_ARRAY):
        if FrameName in kinds:
            words.insert(0, FrameName().describe() + ('' if NonEmpty in kinds else " or ''"))
        elif NonEmpty in kinds:
            words.insert(0, NonEmpty().describe())
        if value_type == STRING_ARRAY:
            names = DistinctNames().describe() if DistinctNames in kinds else 'names'
            words.insert(0, (length + names).strip())
        return ', '.join(words)
    if value_type == BOOL:
        return ', '.join(words)
    # Numbers: a bound on both ends (or a list of values) already rules out NaN and infinity.
    bounded = any(isinstance(rule, (OneOf, ZeroOrInRange)) or (
        isinstance(rule, InRange) and -math.inf < rule.low and rule.high < math.inf)
        for rule in validators)
    finite = Finite in kinds and not bounded
    if value_type == DOUBLE_ARRAY:
        text = ' '.join([f'{length}{"finite " if finite else ""}values'] + words)
    else:
        text = ', '.join((['finite'] if finite else []) + words)
    if Finite not in kinds and any(isinstance(rule, InRange) and rule.allows_infinity
                                   for rule in validators):
        text += '; .inf allowed'
    if Finite not in kinds and any(isinstance(rule, InRange) and rule.low == -math.inf
                                   and rule.low_inclusive for rule in validators):
        text += '; -.inf allowed'
    return text
