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
Inverse dynamics: the actuators' forces that move the platform, its payload and the legs.

:func:`leg_forces` gives the six axial forces of a pose, or of a pose moving with a twist and
an acceleration; :func:`platform_wrench` the wrench that leg forces exert on the platform. One
pose, shape (6,), or a batch, shape (N, 6), with no Python loop over the poses; one pose is
computed in floats, with the batch's operations in the same order (the same forces to the bit,
in a fifth of the time). Conventions (doc/dynamics.md): base frame, SI units; a twist is
``[v, w]``, the velocity of the platform frame's origin and the angular velocity; an
acceleration is ``[dv/dt, dw/dt]``; a leg force is positive when it pushes the platform away
from the base.
"""

import math

import numpy as np

from stewart_kinematics.dynamics.mass_properties import MassProperties
from stewart_kinematics.dynamics.wrenches import body_wrench, leg_wrench
from stewart_kinematics.model.arrays import check_finite_output, preview
from stewart_kinematics.model.formulas import batch_legs, constants_of, single_legs, twist_rows
from stewart_kinematics.model.inputs import as_poses, single_values
from stewart_kinematics.model.rotations import zyx_entries
from stewart_kinematics.model.velocities import SingularPoseError

#: Poses per block of a batch: the temporaries of one block stay in the processor's cache.
BLOCK_SIZE = 2048
#: A twist or acceleration not given: at rest.
_AT_REST = (0.0,) * 6


class _Singular(Exception):
    """A block of poses holds a singular one: ``first``, its index in the block."""

    def __init__(self, first):
        super().__init__(first)
        self.first = first


def leg_forces(geometry, poses, twists=None, accelerations=None, *,
               mass_properties: MassProperties = None) -> np.ndarray:
    """
    Axial forces of the six actuators that hold the platform at a pose, or move it.

    Inverse dynamics of the platform and its payload (rigid bodies) and of the legs (two
    bodies each, turning with the leg without spin), with frictionless joints; see
    doc/dynamics.md for the model.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
    :param twists: ``[vx, vy, vz, wx, wy, wz]``: the velocity of the platform frame's origin
        and the platform's angular velocity, both in the base frame (m/s, rad/s), shape (6,)
        or (N, 6); None (the default): at rest.
    :param accelerations: their time derivatives ``[dv/dt, dw/dt]`` (m/s^2, rad/s^2), base
        frame, shape (6,) or (N, 6); None (the default): zero.
    :param mass_properties: the masses and gravity, a :class:`MassProperties`; ``None`` (the
        default): the geometry's own (:attr:`~stewart_kinematics.Geometry.mass_properties`),
        every mass 0 when it has none.
    :returns: forces f_1..f_6 in newtons, positive when a leg pushes the platform away from the
        base, shape (6,), or (N, 6) when any argument is a batch (one row broadcasts against
        N). Exactly 0 when every mass is 0.
    :raises SingularPoseError: (a ValueError) at a singular pose, where no leg forces balance
        the load (near one, the forces grow without bound).
    :raises ValueError: if an argument is malformed or not finite, the numbers of rows differ,
        or the forces overflow (values beyond the float range).

    >>> from stewart_kinematics import MassProperties, RigidBody, leg_forces, load_geometry
    >>> geometry = load_geometry('config/paper_platform.yaml')
    >>> payload = RigidBody(20.0, [0.0, 0.0, 0.1], name='payload')
    >>> leg_forces(geometry, [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0],
    ...            mass_properties=MassProperties(payload=payload)).round(2)
    array([32.91, 33.73, 32.81, 33.39, 33.52, 32.95])
    """
    if mass_properties is None:
        mass_properties = masses_of(geometry)
    if not isinstance(mass_properties, MassProperties):
        raise ValueError(f'mass_properties must be a MassProperties, got '
                         f'{preview(mass_properties)} ({type(mass_properties).__name__})')
    pose = single_values(poses)
    twist = _AT_REST if twists is None else single_values(twists)
    acceleration = _AT_REST if accelerations is None else single_values(accelerations)
    if pose is not None and twist is not None and acceleration is not None:
        if mass_properties.massless:
            return np.zeros(6)
        try:
            forces = _single_forces(constants_of(geometry), pose, tuple(twist) + tuple(
                acceleration), mass_properties)
        except (ZeroDivisionError, np.linalg.LinAlgError):   # a leg of length 0, or a
            forces = None                                    # singular pose: named below
        if forces is not None and math.isfinite(forces.sum()):
            return forces
    poses, motions = _checked_batch(poses, twists, accelerations)
    if mass_properties.massless:
        return np.zeros(poses.shape)
    shape = poses.shape
    batch, motions = poses.reshape(-1, 6), motions.reshape(-1, 12)
    forces = np.empty(batch.shape)
    constants = constants_of(geometry)
    with np.errstate(all='ignore'):   # an overflow or a singular pose is refused below
        for start in range(0, len(batch), BLOCK_SIZE):
            stop = start + BLOCK_SIZE
            try:
                forces[start:stop] = _batch_forces(
                    constants, batch[start:stop], motions[start:stop], mass_properties)
            except _Singular as singular:
                first = start + singular.first
                where = f'pose {first}' if len(shape) == 2 else 'the pose'
                raise SingularPoseError(
                    f'{where} is singular: no leg forces balance the load there (its '
                    f'Jacobian is singular), got {preview(batch[first].tolist())}')
    return check_finite_output(forces.reshape(shape), 'the leg forces',
                               'the poses, twists and accelerations')


def platform_wrench(geometry, poses, forces) -> np.ndarray:
    """
    Wrench that the six leg forces exert on the platform: ``J^T f``.

    Leg ``i`` pushes on its platform joint, at ``R p_i`` from the platform frame's origin, with
    ``f_i u_i`` (``u_i`` its unit vector, from the base joint to the platform joint).

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
    :param forces: leg forces f_1..f_6 in newtons, positive pushing the platform away from the
        base, shape (6,) or (N, 6).
    :returns: ``[Fx, Fy, Fz, Mx, My, Mz]``: the force (N) and its moment (N m) about the
        platform frame's origin, both in the base frame; shape (6,) or (N, 6). A leg of length
        0 has no direction and adds nothing.
    :raises ValueError: if an argument is malformed or not finite, the numbers of rows differ,
        or the wrench overflows.
    """
    pose, values = single_values(poses), single_values(forces)
    if pose is not None and values is not None:
        entries = _entries(pose[3:], math.cos, math.sin)
        try:
            rows = twist_rows(single_legs(constants_of(geometry), pose[:3], entries))
        except ZeroDivisionError:   # a leg of length 0: the batch path gives it no direction
            rows = None
        if rows is not None:
            wrench = _transposed_product([rows[column::6] for column in range(6)], values)
            if math.isfinite(sum(wrench)):
                return np.array(wrench)
    poses = as_poses(poses)
    forces = as_poses(forces, 'forces')
    shape = _common_shape(poses, forces, 'forces')
    batch = np.broadcast_to(poses, shape).reshape(-1, 6)
    values = np.ascontiguousarray(np.broadcast_to(forces, shape).reshape(-1, 6).T)
    with np.errstate(all='ignore'):   # an overflow is refused below
        entries = _entries(batch[:, 3:].T, np.cos, np.sin)
        lengths, vectors = batch_legs(constants_of(geometry), batch[:, :3], entries)
        lengths = np.where(lengths == 0.0, 1.0, lengths)   # as twist_jacobian: a zero row
        wrench = np.stack(_transposed_product(twist_rows([(lengths, *vectors)]), values), -1)
    return check_finite_output(wrench.reshape(shape), 'the platform wrench', 'the forces')


def masses_of(geometry) -> MassProperties:
    """Return the masses a geometry carries, or every mass 0 when it carries none."""
    masses = getattr(geometry, 'mass_properties', None)
    return _MASSLESS if masses is None else masses


_MASSLESS = MassProperties()


def _entries(angles, cos, sin):
    """Rotation entries of Euler angles ``(alpha, beta, gamma)`` (floats or arrays)."""
    alpha, beta, gamma = angles
    return zyx_entries(cos(alpha), sin(alpha), cos(beta), sin(beta), cos(gamma), sin(gamma))


def _leg_bodies(mass_properties):
    """``(m1, d1, m2, d2, I1 + I2)`` of :func:`~.wrenches.leg_wrench`."""
    lower, upper = mass_properties.leg_lower, mass_properties.leg_upper
    return (lower.mass, lower.center_of_mass, upper.mass, upper.center_of_mass,
            lower.inertia + upper.inertia)


def _single_forces(constants, pose, motion, mass_properties):
    """
    Leg forces of one pose, shape (6,).

    :raises ZeroDivisionError: at a leg of length 0.
    :raises numpy.linalg.LinAlgError: at a singular pose.
    """
    entries = _entries(pose[3:], math.cos, math.sin)
    legs = single_legs(constants, pose[:3], entries)
    transposed, wrench = _single_system(legs, entries, motion, mass_properties)
    return np.linalg.solve(transposed, wrench)


def _single_system(legs, entries, motion, mass_properties):
    """
    Return the linear system of one pose's leg forces: ``(J^T, wrench)``, ``J^T f = wrench``.

    :param legs: per leg ``(l, lx, ly, lz, ax, ay, az)``, floats.
    :param entries: the nine entries of the platform-to-base rotation, floats.
    :param motion: the platform's motion terms, as :func:`~.wrenches.body_wrench` takes them.
    :returns: the (6, 6) transposed Jacobian's array and the six wrench terms (N, N m).
    """
    gravity = mass_properties.gravity
    fx, fy, fz, mx, my, mz = body_wrench(entries, motion, mass_properties.moving_body, gravity)
    if not mass_properties.legs_massless:
        leg_bodies = _leg_bodies(mass_properties)
        for leg in legs:
            gx, gy, gz, nx, ny, nz = leg_wrench(leg, motion, leg_bodies, gravity)
            fx, fy, fz, mx, my, mz = fx + gx, fy + gy, fz + gz, mx + nx, my + ny, mz + nz
    return np.array(twist_rows(legs)).reshape(6, 6).T, [fx, fy, fz, mx, my, mz]


def _batch_forces(constants, poses, motions, mass_properties):
    """
    Leg forces of a block of poses, shape (n, 6).

    :raises _Singular: naming the first singular pose.
    """
    entries = _entries(np.ascontiguousarray(poses[:, 3:].T), np.cos, np.sin)
    lengths, vectors = batch_legs(constants, poses[:, :3], entries)
    if not np.all(np.isfinite(lengths)):   # an overflow: refused as such by the caller
        return np.full(poses.shape, math.nan)
    transposed, wrench = _balance(entries, lengths, vectors, tuple(
        np.ascontiguousarray(motions.T)), mass_properties)
    try:
        return np.linalg.solve(transposed, wrench)[..., 0]
    except np.linalg.LinAlgError:   # LAPACK found a pivot of 0: which pose has it
        singular = np.flatnonzero(~(np.linalg.det(transposed) != 0.0))
        raise _Singular(int(singular[0]) if singular.size else 0) from None


def static_forces_of_legs(lengths, vectors, rotation, mass_properties) -> np.ndarray:
    """
    Return the static leg forces of poses given by their legs, as the pose limits read them.

    The same terms as :func:`leg_forces` with every twist and acceleration 0, from the legs
    of :class:`stewart_kinematics.limits.base.PoseLegs` rather than the poses.

    :param lengths: leg lengths, metres, shape (6, n).
    :param vectors: ``(lx, ly, lz, ax, ay, az)``: leg vectors and rotated platform joints,
        each (6, n), metres, base frame.
    :param rotation: the nine entries of each platform-to-base rotation, each (n,).
    :param mass_properties: a :class:`MassProperties`.
    :returns: leg forces, newtons, shape (6, n), positive pushing; NaN for every leg of a
        singular pose or one whose legs are not finite (no forces balance the load there).
    """
    count = lengths.shape[1]
    if mass_properties.massless:
        return np.zeros((6, count))
    forces = np.full((count, 6), math.nan)
    with np.errstate(all='ignore'):
        finite = np.isfinite(lengths).all(axis=0)
        transposed, wrench = _balance(rotation, lengths, vectors, tuple(
            np.zeros((12, count))), mass_properties)
        transposed, wrench = transposed[finite], wrench[finite]
        try:
            forces[finite] = np.linalg.solve(transposed, wrench)[..., 0]
        except np.linalg.LinAlgError:   # a singular pose: solved one by one, NaN there
            regular = np.linalg.det(transposed) != 0.0
            solved = np.full((len(transposed), 6), math.nan)
            solved[regular] = np.linalg.solve(transposed[regular], wrench[regular])[..., 0]
            forces[finite] = solved
    forces[~np.isfinite(forces).all(axis=1)] = math.nan
    return forces.T


def single_static_forces_of_legs(legs, rotation, mass_properties) -> list:
    """
    :func:`static_forces_of_legs` of one pose, in floats: the same terms, in the same order.

    :param legs: per leg ``(l, lx, ly, lz, ax, ay, az)``, floats
        (:func:`stewart_kinematics.model.formulas.legs_of`).
    :param rotation: the nine entries of the platform-to-base rotation, floats.
    :param mass_properties: a :class:`MassProperties`.
    :returns: six forces, newtons; NaN for every leg of a singular pose or one whose forces
        are not finite.
    """
    if mass_properties.massless:
        return [0.0] * 6
    try:
        forces = _single_static_forces(legs, rotation, mass_properties)
    except (ZeroDivisionError, np.linalg.LinAlgError):   # a leg of length 0: singular
        return [math.nan] * 6
    return forces if all(map(math.isfinite, forces)) else [math.nan] * 6


def _single_static_forces(legs, entries, mass_properties):
    """Return the forces of :func:`single_static_forces_of_legs`; raise where singular."""
    transposed, wrench = _single_system(legs, entries, _AT_REST * 2, mass_properties)
    with np.errstate(all='ignore'):
        return np.linalg.solve(transposed, wrench).tolist()


def _balance(entries, lengths, vectors, motion, mass_properties):
    """
    Return ``(J^T, wrench)`` of a block of poses: shapes (n, 6, 6) and (n, 6, 1).

    The leg forces f solve ``J^T f = wrench``: the wrench the legs must exert on the platform.
    """
    lengths = np.where(lengths == 0.0, 1.0, lengths)   # a zero row: singular, refused
    gravity = mass_properties.gravity
    wrench = body_wrench(entries, motion, mass_properties.moving_body, gravity)
    if not mass_properties.legs_massless:
        terms = leg_wrench((lengths, *vectors), motion, _leg_bodies(mass_properties), gravity)
        wrench = list(wrench)
        for leg in range(6):   # leg by leg, in the order of the one-pose path
            for column in range(6):
                wrench[column] = wrench[column] + terms[column][leg]
    transposed = np.stack(twist_rows([(lengths, *vectors)])).transpose(2, 0, 1)   # (n, 6, 6)
    return transposed, np.stack(np.broadcast_arrays(*wrench), axis=-1)[..., None]


def _transposed_product(columns, forces):
    """``J^T f``, six sums in leg order, from the twist Jacobian's columns and the forces."""
    wrench = []
    for column in columns:
        total = column[0] * forces[0]
        for leg in range(1, 6):
            total = total + column[leg] * forces[leg]
        wrench.append(total)
    return wrench


def _common_shape(poses, values, name):
    """Return the broadcast shape of poses and values, or refuse rows that do not match."""
    try:
        return np.broadcast_shapes(poses.shape, values.shape)
    except ValueError:
        raise ValueError(f'poses {poses.shape} and {name} {values.shape} must hold the same '
                         'number of rows, or one of them a single one') from None


def _checked_batch(poses, twists, accelerations):
    """Poses (..., 6) and their motions (..., 12), checked and broadcast to one shape."""
    poses = as_poses(poses)
    twists = np.zeros(6) if twists is None else as_poses(twists, 'twists')
    accelerations = (np.zeros(6) if accelerations is None
                     else as_poses(accelerations, 'accelerations'))
    shape = _common_shape(poses, twists, 'twists')
    shape = _common_shape(np.empty(shape), accelerations, 'accelerations')
    motions = np.concatenate([np.broadcast_to(twists, shape),
                              np.broadcast_to(accelerations, shape)], axis=-1)
    return np.broadcast_to(poses, shape), motions
