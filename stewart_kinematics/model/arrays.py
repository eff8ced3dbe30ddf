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
The one conversion of a public function's array argument: numbers in, a float array out.

``numpy.asarray(values, dtype=float)`` turns ``'1.5'`` and ``True`` into numbers without a word,
and answers a ragged list, a dict or a complex number with its own messages ("setting an
array element with a sequence", "float() argument must be ..."), which name no argument.
:func:`as_float_array` refuses each of them with a ``ValueError`` that names the argument and
shows what was given; :func:`check_finite_output` refuses a result that overflowed.
"""

import numpy as np

#: Array kinds taken as numbers: signed and unsigned integers, floats.
_NUMBER_KINDS = 'iuf'
#: Characters of a given value shown in a message.
_PREVIEW_LENGTH = 60


def preview(values) -> str:
    """Return a short ``repr`` of a value for an error message."""
    text = repr(values.tolist() if isinstance(values, np.ndarray) else values)
    return text if len(text) <= _PREVIEW_LENGTH else text[:_PREVIEW_LENGTH - 3] + '...'


#: The dtype of the arrays the core computes with.
_FLOAT = np.dtype(float)


def as_float_array(values, name: str) -> np.ndarray:
    """
    Return ``values`` as a float array, or refuse them naming the argument.

    :param values: numbers: a number, a (nested) list or tuple of numbers, or a numeric array.
    :param name: the argument's name, as the message should give it.
    :raises ValueError: for strings, booleans, complex numbers, ``None``, ragged lists and
        anything else that is not numbers, or numbers beyond the float range.
    """
    if isinstance(values, np.ndarray):
        if values.dtype == _FLOAT:   # the common case, first: no conversion to make
            return values
        if values.dtype.kind in _NUMBER_KINDS:
            return values.astype(float)
    try:
        array = np.asarray(values)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f'{name} must be an array of numbers of one shape (not ragged), got '
                         f'{preview(values)}') from None
    if array.dtype.kind in _NUMBER_KINDS:
        return array.astype(float, copy=False)
    if array.dtype.kind == 'O' and not any(isinstance(item, (str, bytes, bool, type(None)))
                                           for item in array.ravel().tolist()):
        try:   # numbers numpy keeps as objects: Decimal, Fraction, very large integers
            return array.astype(float)
        except (TypeError, ValueError, OverflowError):
            pass
    raise ValueError(f'{name} must be numbers within the float range, got {preview(values)} '
                     f'({type(values).__name__})')


def check_finite_output(values, what: str, cause: str) -> np.ndarray:
    """
    Return ``values`` if every one is finite, else refuse them: an overflow is no result.

    :param values: a computed array.
    :param what: what it is, for the message (``'the twist'``).
    :param cause: the inputs to blame, for the message (``'the leg velocities'``).
    :raises ValueError: if a value is infinite or NaN.
    """
    if not np.all(np.isfinite(values)):
        raise ValueError(f'{what} of {cause}: not finite (beyond the float range, about '
                         '1.8e308); the inputs are too large')
    return values
