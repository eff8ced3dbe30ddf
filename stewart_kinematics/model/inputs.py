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
The checks of the kinematics' arguments: poses, leg lengths, a position with its rotation.

Each public function of the kinematics checks its arguments here, where they enter, and hands
the checked arrays inward: the formulas (:mod:`.formulas`) and the solver
(:mod:`.forward_solver`) trust them. :func:`as_poses` and :func:`as_leg_lengths` are the checks
the rest of the package uses too; :func:`single_values` is the fast check of one pose or one
set of leg lengths, in floats (numpy's per-call overhead would cost more than the check), and
:func:`finite_result` says why a result is not finite. Messages name the argument and show what
was given (:func:`stewart_kinematics.model.arrays.preview`).
"""

import math

import numpy as np

from stewart_kinematics.model.arrays import as_float_array, check_finite_output, preview

#: The dtype of a float array.
_FLOAT = np.dtype(float)


def as_rows(values, name) -> np.ndarray:
    """Return ``values`` as a float array of shape (6,) or (N, 6), or raise ValueError."""
    values = as_float_array(values, name)
    if values.ndim not in (1, 2) or values.shape[-1] != 6:
        raise ValueError(f'{name} must have shape (6,) or (N, 6), got {values.shape}')
    return values


def as_poses(poses, name='poses') -> np.ndarray:
    """
    Check and convert poses ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).

    :param poses: shape (6,) or (N, 6).
    :returns: a float array of the same shape.
    :raises ValueError: if the shape is wrong or a value is not finite.
    """
    poses = as_rows(poses, name)
    if not np.all(np.isfinite(poses)):
        bad = np.unique(np.argwhere(~np.isfinite(np.atleast_2d(poses)))[:, 0])
        raise ValueError(f'{name} must be finite; pose(s) {bad[:10].tolist()} are not')
    return poses


def as_leg_lengths(lengths, name='leg lengths') -> np.ndarray:
    """
    Check and convert leg lengths (metres).

    :param lengths: shape (6,) or (N, 6).
    :returns: a float array of the same shape.
    :raises ValueError: if the shape is wrong or a length is not finite and positive.
    """
    if type(lengths) is np.ndarray and lengths.shape == (6,) and lengths.dtype == _FLOAT:
        # One set of six floats (fk_node's per message): checked in floats; a sum of finite
        # numbers can overflow, and then the full checks below decide.
        values = lengths.tolist()
        if math.isfinite(sum(values)) and min(values) > 0.0:
            return lengths
    lengths = as_rows(lengths, name)
    allowed = valid_lengths(lengths)
    if not np.all(allowed):
        first_bad = np.atleast_2d(lengths)[~np.atleast_1d(allowed)][0]
        raise ValueError(f'{name} must be finite and positive (metres), got {first_bad.tolist()}')
    return lengths


def valid_lengths(lengths):
    """Where each set of six lengths, shape (..., 6), is finite and positive: shape (...)."""
    return np.all(np.isfinite(lengths) & (lengths > 0.0), axis=-1)


def as_position_rotation(position, rotation):
    """Positions (..., 3) and rotation matrices (..., 3, 3) as float arrays, shapes checked."""
    position = as_float_array(position, 'position')
    rotation = as_float_array(rotation, 'rotation')
    if position.shape == (3,) and rotation.shape == (3, 3):   # one pose: the common case
        return position, rotation
    if position.shape[-1:] != (3,) or rotation.shape[-2:] != (3, 3):
        raise ValueError(f'position must have shape (3,) or (N, 3) and rotation (3, 3) or '
                         f'(N, 3, 3), got {position.shape} and {rotation.shape}')
    try:
        np.broadcast_shapes(position.shape[:-1], rotation.shape[:-2])
    except ValueError:
        raise ValueError(f'position {position.shape} and rotation {rotation.shape} must hold '
                         'the same number of poses, or one of them a single one') from None
    return position, rotation


def finite_result(result, what, position, rotation):
    """Return ``result``, or say why it is not finite: a non-finite input, or an overflow."""
    if isinstance(result, np.ndarray) and result.size <= 36 and all(
            map(math.isfinite, result.ravel().tolist())) or np.all(np.isfinite(result)):
        return result
    for name, values in (('position', position), ('rotation', rotation)):
        if not np.all(np.isfinite(values)):
            raise ValueError(f'{name} must be finite, got {preview(values)}')
    return check_finite_output(result, what, 'the position and rotation')


def is_real(value) -> bool:
    """Whether ``value`` is a real number (a bool is not)."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, (bool, np.bool_))


def single_values(values, positive=False):
    """
    Six floats of one pose or one set of leg lengths, or None to leave it to the full checks.

    The fast path of the argument checks for one solve: None unless ``values`` is an array,
    list or tuple of six numbers that are finite (and positive, with ``positive``), so that
    :func:`as_poses` and :func:`as_leg_lengths` say what is wrong, or see a batch.

    :returns: a list of six floats, or None.
    """
    if type(values) is np.ndarray:   # exactly: a matrix or masked array takes the full checks
        if values.shape != (6,) or values.dtype.kind not in 'iuf':
            return None
        if values.dtype == _FLOAT:  # the common case: six Python floats at once
            values = values.tolist()
            # A sum of floats is finite only when each one is (else: the full checks).
            if math.isfinite(sum(values)) and (not positive or min(values) > 0.0):
                return values
            return None
        values = values.tolist()
    elif not isinstance(values, (list, tuple)) or len(values) != 6:
        return None
    # Numbers only: a string or a bool is left to the full checks, which refuse it.
    if not all(type(value) in (float, int) for value in values):
        return None
    try:
        values = [float(value) for value in values]
    except OverflowError:   # an integer beyond the float range
        return None
    low = 0.0 if positive else -math.inf
    return values if all(low < value < math.inf for value in values) else None
