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

:func:`preview` is how every message of the package shows an input it refuses: whole when it
is small (a pose, a rotation matrix), else its first values and its size, so that an input of a
million values or a frame id of ten megabytes makes a message of one short line, not one of
megabytes in a log and in ``/diagnostics``.

Array-likes (the rule every public function and decision follows, doc/python_api.md): an
argument is what ``numpy.asarray`` makes of it, always a plain ``ndarray``. An ``np.matrix``
is its 2-D array, so six lengths in a matrix have shape (1, 6); a masked array with a masked
entry is refused, naming the entries (a masked value is no number to use, and the data under
the mask is not used); a masked array with nothing masked is its data.
"""

from collections.abc import Sequence
import reprlib

import numpy as np

#: Array kinds taken as numbers: signed and unsigned integers, floats.
_NUMBER_KINDS = 'iuf'
#: An input of at most this many values is shown whole, each as ``repr`` shows it (the
#: shortest text that reads back as the same float): a pose (6), a rotation matrix (9), the
#: joints of a base (18), and a few more or less when one is missing or too many.
PREVIEW_WHOLE = 24
#: Values shown of a larger input, before ``...`` and its size.
PREVIEW_VALUES = 6
#: Characters shown of a longer string (a frame id, a joint name), before ``...`` and its length.
PREVIEW_CHARACTERS = 60
#: Nesting levels shown; deeper ones are ``[...]``.
PREVIEW_DEPTH = 3
#: Longest text :func:`preview` returns, whatever the input.
PREVIEW_MAX = 600


class _LimitedRepr(reprlib.Repr):
    """reprlib's limited repr; an object whose own repr fails is shown as ``<TypeName>``."""

    def repr_instance(self, obj, level):
        """Return the limited repr of an object, or ``<TypeName>`` when its repr fails."""
        try:
            text = repr(obj)
        except Exception:   # noqa: B902 - any error of a user's __repr__
            return f'<{type(obj).__name__}>'
        if len(text) > self.maxother:
            half = max(0, (self.maxother - 3) // 2)
            text = text[:half] + '...' + text[len(text) - (self.maxother - 3 - half):]
        return text


#: The repr of anything else (a dict, a set, an object), limited as :func:`preview` is.
_OTHER = _LimitedRepr()
_OTHER.maxlevel = PREVIEW_DEPTH
_OTHER.maxstring = _OTHER.maxother = PREVIEW_CHARACTERS
_OTHER.maxdict = _OTHER.maxset = _OTHER.maxfrozenset = _OTHER.maxdeque = PREVIEW_VALUES
_OTHER.maxlist = _OTHER.maxtuple = _OTHER.maxarray = PREVIEW_VALUES


def preview(values) -> str:
    """
    Describe an input for a message: whole when small, else its first values and its size.

    Up to :data:`PREVIEW_WHOLE` values are shown whole, as ``repr`` of their list shows them
    (``[0.1, 0.2, nan, 0.4, 0.5, 0.6]``); a larger array or sequence shows its first
    :data:`PREVIEW_VALUES`, ``...`` and how many it has (``[0.7, 0.7, 0.7, 0.7, 0.7, 0.7, ...]
    (1,000,000 values)``, with the shape of an array of more than one dimension); a string
    longer than :data:`PREVIEW_CHARACTERS` its start, ``...`` and its length. The text is never
    longer than :data:`PREVIEW_MAX` characters, and its cost grows with what is shown, not with
    the input (no ``tolist()`` or ``repr`` of the whole): call it only to build a message.

    :param values: anything: an array, a (nested) list or tuple, a string, a number.
    :returns: one line of at most :data:`PREVIEW_MAX` characters.

    >>> preview([0.7, 0.7, 0.7, 0.7, 0.7, float('nan')])
    '[0.7, 0.7, 0.7, 0.7, 0.7, nan]'
    >>> preview(np.arange(1e6))
    '[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, ...] (1,000,000 values)'
    >>> text = preview('f' * 10 ** 7)   # a frame id of 10 MB
    >>> text.endswith("fff'... (10,000,000 characters)"), len(text)
    (True, 89)
    """
    try:
        text = _preview(values, PREVIEW_DEPTH)
    except Exception:   # noqa: B902 - a user's object whose repr or len fails
        text = f'<{type(values).__name__}>'
    return text if len(text) <= PREVIEW_MAX else text[:PREVIEW_MAX - 3] + '...'


def seconds_text(time: float) -> str:
    """
    Write a time in seconds for a message: to the nanosecond, as a stamp is given.

    A time beyond a billion years in seconds (a finite 1e308, say) is written in nine
    significant digits instead of its 300 digits before the point.

    >>> seconds_text(1732000000.5), seconds_text(-1e308)
    ('1732000000.500000000', '-1e+308')
    """
    return f'{time:.9f}' if abs(time) < 1e17 else f'{time:.9g}'


def _preview(values, depth: int) -> str:
    """Return :func:`preview` of one value, with ``depth`` levels of nesting left to show."""
    if isinstance(values, (str, bytes, bytearray)):
        if len(values) <= PREVIEW_CHARACTERS:
            return repr(values)
        return f'{values[:PREVIEW_CHARACTERS]!r}... ({len(values):,} characters)'
    if isinstance(values, np.ndarray):
        if values.ndim == 0:
            return _preview(values.item(), depth)
        if values.size <= PREVIEW_WHOLE:
            return _preview(values.tolist(), depth)
        shape = '' if values.ndim == 1 else f'shape {values.shape}: '
        # The first values in C order, without a copy of the whole (np.asarray: a matrix
        # stays two-dimensional when flattened).
        head = _items(np.asarray(values).flat[:PREVIEW_VALUES].tolist(), depth - 1)
        return f'[{head}, ...] ({shape}{_count(values.size)})'
    if isinstance(values, np.generic):
        return _preview(values.item(), depth)
    if isinstance(values, (list, tuple)) or (
            isinstance(values, Sequence) and not isinstance(values, range)):
        opening, closing = ('(', ')') if isinstance(values, tuple) else ('[', ']')
        count = len(values)
        if depth <= 0:
            return f'{opening}...{closing} ({_count(count)})'
        if count <= PREVIEW_WHOLE:
            single = ',' if isinstance(values, tuple) and count == 1 else ''
            return f'{opening}{_items(values, depth - 1)}{single}{closing}'
        head = _items([values[index] for index in range(PREVIEW_VALUES)], depth - 1)
        return f'{opening}{head}, ...{closing} ({_count(count)})'
    if isinstance(values, int) and values.bit_length() > 4 * PREVIEW_CHARACTERS:
        return f'an integer of {values.bit_length():,} bits'   # repr refuses 4300+ digits
    if values is None or isinstance(values, (bool, int, float, complex)):
        return repr(values)
    return _OTHER.repr(values)


def _count(count: int) -> str:
    """Return ``'1 value'``, ``'1,000,000 values'``."""
    return f'{count:,} value' + ('' if count == 1 else 's')


def _items(values, depth: int) -> str:
    """Return the previews of a few values, comma-separated."""
    return ', '.join(_preview(value, depth) for value in values)


#: The dtype of the arrays the core computes with.
_FLOAT = np.dtype(float)


def as_float_array(values, name: str) -> np.ndarray:
    """
    Return ``values`` as a plain float array, or refuse them naming the argument.

    What ``numpy.asarray`` makes of ``values``, as a plain ``ndarray`` (never a subclass):

    - an ``np.matrix`` is its 2-D array: six numbers in a matrix have shape (1, 6), which a
      caller that wants shape (6,) refuses by its shape check (and a batch function takes as
      one row);
    - a masked array (``numpy.ma``), or a list whose items are masked arrays or
      ``numpy.ma.masked``, is refused if any entry is masked, naming the masked entries by
      index: a masked value is no number to use, and the data under the mask is not used. With
      nothing masked it is its data;
    - objects with ``__array__`` (a pandas Series or DataFrame), ``memoryview`` and
      ``array.array`` are the numbers they hold; an ``__array__`` that raises is refused with
      what it raised.

    :param values: numbers: a number, a (nested) list or tuple of numbers, or a numeric array.
    :param name: the argument's name, as the message should give it.
    :raises ValueError: for strings, bytes, booleans, complex numbers, ``None``, dicts,
        generators, ragged lists, masked entries and anything else that is not numbers, or
        numbers beyond the float range.
    """
    if type(values) is np.ndarray:   # exactly: a subclass (matrix, masked) is converted below
        if values.dtype == _FLOAT:   # the common case, first: no conversion to make
            return values
        if values.dtype.kind in _NUMBER_KINDS:
            return values.astype(float)
    values = _unmasked(values, name)
    try:
        array = np.asarray(values)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f'{name} must be an array of numbers of one shape (not ragged), got '
                         f'{preview(values)}') from None
    except Exception as error:   # noqa: B902 - a user's __array__ may raise anything
        raise ValueError(f'{name} could not be read as an array: {type(error).__name__}: '
                         f'{preview(str(error))}') from None
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


#: Masked entries a refusal names, at most.
_MASKED_SHOWN = 10


def _unmasked(values, name: str):
    """
    Return the data of a masked array with nothing masked; anything else as it is.

    A list or tuple is looked into one level deep (rows that are masked arrays, or
    ``numpy.ma.masked`` among numbers).

    :raises ValueError: naming the masked entries, if any entry is masked.
    """
    if isinstance(values, np.ma.MaskedArray):
        entries = np.argwhere(np.ma.getmaskarray(values)).tolist()
        data = np.ma.getdata(values)
    elif isinstance(values, (list, tuple)) and any(isinstance(item, np.ma.MaskedArray)
                                                   for item in values):
        entries = [[row] + entry for row, item in enumerate(values)
                   if isinstance(item, np.ma.MaskedArray)
                   for entry in np.argwhere(np.ma.getmaskarray(item)).tolist()]
        data = [np.ma.getdata(item) if isinstance(item, np.ma.MaskedArray) else item
                for item in values]
    else:
        return values
    if not entries:
        return data
    if entries == [[]]:   # a masked scalar
        raise ValueError(f'{name} must be a number, not masked (fill it, or give a float)')
    shown = [entry[0] if len(entry) == 1 else entry for entry in entries[:_MASKED_SHOWN]]
    more = (f' and {len(entries) - _MASKED_SHOWN} more' if len(entries) > _MASKED_SHOWN
            else '')
    raise ValueError(f'{name} must be numbers, not masked: entries {shown}{more} are masked '
                     '(fill them, or give a plain array)')


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
