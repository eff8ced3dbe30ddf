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
Inverse kinematics: the leg vectors and leg lengths of poses, in closed form.

``l_i = |t + R p_i - b_i|`` (the paper's equation 1, :func:`~.formulas.legs_of`) for poses
``[X, Y, Z, alpha, beta, gamma]`` (:func:`inverse_kinematics`) or positions with rotation
matrices (:func:`leg_lengths`, :func:`leg_vectors`): one pose, shape (6,), or a batch, shape
(N, 6), with no Python loop over the poses. :func:`leg_arrays` gives the limits model the legs
of a batch in its layout. Metres and radians, base frame.
"""

import math

import numpy as np

from stewart_kinematics.model.arrays import as_float_array, check_finite_output
from stewart_kinematics.model.formulas import (
    batch_euler_legs,
    batch_legs,
    batch_rotation_legs,
    broadcast_pose,
    constants_of,
    single_euler_legs,
    single_legs,
)
from stewart_kinematics.model.inputs import as_poses, as_position_rotation, finite_result
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

#: Poses per block of a batched inverse kinematics: the temporaries of one block stay in the
#: processor's cache, which doubles the throughput of batches of millions.
IK_BLOCK_SIZE = 4096


def leg_vectors(geometry, position, rotation) -> np.ndarray:
    """
    Leg vectors ``t + R p_i - b_i`` from each base joint to its platform joint.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param position: platform origin in the base frame, metres, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation matrix, shape (3, 3) or (N, 3, 3).
    :returns: in the base frame, metres, shape (6, 3) or (N, 6, 3).
    :raises ValueError: as :func:`leg_lengths`.
    """
    position, rotation = as_position_rotation(position, rotation)
    constants = constants_of(geometry)
    if position.shape == (3,) and rotation.shape == (3, 3):
        legs = single_legs(constants, position.tolist(), rotation.ravel().tolist())
        vectors = np.array([leg[1:4] for leg in legs])
    else:
        shape, (_, vectors) = batch_rotation_legs(constants,
                                                  *broadcast_pose(position, rotation))
        vectors = np.stack(vectors[:3], axis=-1).transpose(1, 0, 2).reshape(shape + (6, 3))
    return finite_result(vectors, 'the leg vectors', position, rotation)


def leg_vectors_from_euler(geometry, poses) -> np.ndarray:
    """
    Leg vectors of poses ``[X, Y, Z, alpha, beta, gamma]``; see :func:`leg_vectors`.

    :returns: base frame, metres, shape (6, 3) or (N, 6, 3).
    """
    poses = as_poses(poses)
    return leg_vectors(geometry, poses[..., :3], euler_zyx_to_matrix(poses[..., 3:]))


def leg_lengths(geometry, position, rotation) -> np.ndarray:
    """
    Inverse kinematics for a pose given as position and rotation matrix.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param position: metres, base frame, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation matrix, shape (3, 3) or (N, 3, 3); build it
        from a quaternion with :func:`stewart_kinematics.model.rotations.quaternion_to_matrix`.
    :returns: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    :raises ValueError: if a shape is wrong, the numbers of poses differ, a value is not
        finite or the lengths overflow. The rotation is not checked to be one.
    """
    position, rotation = as_position_rotation(position, rotation)
    constants = constants_of(geometry)
    if position.shape == (3,) and rotation.shape == (3, 3):
        legs = single_legs(constants, position.tolist(), rotation.ravel().tolist())
        lengths = [leg[0] for leg in legs]
        if all(map(math.isfinite, lengths)):
            return np.array(lengths)
        lengths = np.array(lengths)
    else:
        shape, (lengths, _) = batch_rotation_legs(constants,
                                                  *broadcast_pose(position, rotation))
        lengths = lengths.T.reshape(shape + (6,))
    return finite_result(lengths, 'the leg lengths', position, rotation)


def inverse_kinematics(geometry, poses) -> np.ndarray:
    """
    Leg lengths of one pose or a batch of poses (closed form).

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` in metres and radians, shape (6,) or (N, 6).
    :returns: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    :raises ValueError: if a pose has the wrong shape or a non-finite value, or its lengths
        overflow (a coordinate beyond about 1e154 m).

    >>> from stewart_kinematics import inverse_kinematics, load_geometry
    >>> geometry = load_geometry('config/paper_platform.yaml')
    >>> inverse_kinematics(geometry, [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0])
    array([0.71885487, 0.71885488, 0.70114644, 0.71885487, 0.71885488, 0.71885488])
    """
    poses = as_float_array(poses, 'poses')
    constants = constants_of(geometry)
    if poses.shape == (6,):
        values = poses.tolist()
        if all(map(math.isfinite, values)):
            lengths = single_euler_legs(constants, values, with_vectors=False)
            # One test for six: a sum of lengths is finite only if each is (an overflow
            # beyond that, near 1e307 m, takes the batch path, which names it).
            if math.isfinite(sum(lengths)):
                return np.array(lengths)
    poses = as_poses(poses)
    batch = np.atleast_2d(poses)
    lengths = np.empty((batch.shape[0], 6))
    with np.errstate(over='ignore', invalid='ignore'):   # an overflow is refused below
        for start in range(0, batch.shape[0], IK_BLOCK_SIZE):
            stop = start + IK_BLOCK_SIZE
            lengths[start:stop] = batch_euler_legs(constants, batch[start:stop], False).T
    return check_finite_output(lengths.reshape(poses.shape), 'the leg lengths', 'the poses')


# The leg arrays of a batch, for the limits model (stewart_kinematics.limits), which evaluates
# every limit on them: the formulas above, exposed in their batch layout (legs by poses).

def leg_arrays(geometry, positions, rotation_entries):
    """
    Legs of a batch of poses, leg by pose: :func:`legs_of`, the one leg formula, on arrays.

    :param positions: platform origins in the base frame, metres, shape (n, 3).
    :param rotation_entries: ``(r11, r12, ..., r33)`` of the platform-to-base rotations, nine
        arrays (n,): :func:`stewart_kinematics.model.rotations.zyx_entries` of Euler angles,
        or the entries of rotation matrices.
    :returns: ``(lengths, (lx, ly, lz, ax, ay, az))``: the leg lengths, shape (6, n), and the
        components of the leg vectors ``t + R p_i - b_i`` and of the rotated platform joints
        ``R p_i``, each (6, n), metres, base frame. One pose (n = 1) is computed in floats,
        as :func:`leg_lengths` computes one pose: the same values to the bit, three times
        faster than the arrays.
    """
    positions = np.asarray(positions, dtype=float)
    if positions.shape == (1, 3):
        legs = np.array(single_legs(constants_of(geometry), positions[0].tolist(),
                                    [float(entry[0]) for entry in rotation_entries]))
        return legs[:, 0:1], tuple(legs[:, column:column + 1] for column in range(1, 7))
    return batch_legs(constants_of(geometry), positions, rotation_entries)
