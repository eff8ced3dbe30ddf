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
The one formula of each wrench term of the inverse dynamics: one pose in floats, a batch in arrays.

As in :mod:`stewart_kinematics.model.formulas`, each formula runs on floats (one pose: numpy's
per-call overhead would cost more than the arithmetic) and on numpy arrays (a batch, poses
along the last axis) with the same operations in the same order, so that one pose and a batch
give the same forces to the bit. Base frame, SI units. ``motion`` is the platform's twist and
its derivative, twelve values: ``(vx, vy, vz, wx, wy, wz, dvx, dvy, dvz, dwx, dwy, dwz)``, the
velocity and acceleration of the platform frame's origin and the angular velocity and
acceleration. The equations of motion (doc/dynamics.md) are ``J^T f = w``: :func:`body_wrench`
and :func:`leg_wrench` give the terms of ``w``; LAPACK solves for ``f`` (``numpy.linalg.solve``,
the same routine for one pose and for each pose of a batch).
"""


def body_wrench(rotation_entries, motion, body, gravity):
    """
    Wrench the legs must exert on the platform and its payload to move them: ``[F, M]``.

    ``F = m (a_c - g)`` and ``M = r_c x F + R (I a_p + w_p x I w_p)``, the moment about the
    platform frame's origin, with ``r_c = R c`` the centre of mass, ``a_c = a + dw x r_c + w x
    (w x r_c)`` its acceleration, ``w_p = R^T w`` and ``a_p = R^T dw`` the angular velocity and
    acceleration in the platform frame (where the inertia ``I`` is constant).

    :param rotation_entries: ``(r11, ..., r33)`` of the platform-to-base rotation.
    :param motion: see the module's docstring.
    :param body: ``(mass, (cx, cy, cz), (i11, ..., i33))`` of
        :attr:`~.mass_properties.MassProperties.moving_body`.
    :param gravity: ``(gx, gy, gz)``, m/s^2, base frame.
    :returns: ``(Fx, Fy, Fz, Mx, My, Mz)``, newtons and newton metres, base frame.
    """
    r11, r12, r13, r21, r22, r23, r31, r32, r33 = rotation_entries
    vx, vy, vz, wx, wy, wz, ax, ay, az, ex, ey, ez = motion
    mass, (cx, cy, cz), (i11, i12, i13, i21, i22, i23, i31, i32, i33) = body
    gx, gy, gz = gravity
    px = r11 * cx + r12 * cy + r13 * cz
    py = r21 * cx + r22 * cy + r23 * cz
    pz = r31 * cx + r32 * cy + r33 * cz
    sx = wy * pz - wz * py
    sy = wz * px - wx * pz
    sz = wx * py - wy * px
    fx = mass * (ax + (ey * pz - ez * py) + (wy * sz - wz * sy) - gx)
    fy = mass * (ay + (ez * px - ex * pz) + (wz * sx - wx * sz) - gy)
    fz = mass * (az + (ex * py - ey * px) + (wx * sy - wy * sx) - gz)
    ox = r11 * wx + r21 * wy + r31 * wz
    oy = r12 * wx + r22 * wy + r32 * wz
    oz = r13 * wx + r23 * wy + r33 * wz
    dx = r11 * ex + r21 * ey + r31 * ez
    dy = r12 * ex + r22 * ey + r32 * ez
    dz = r13 * ex + r23 * ey + r33 * ez
    hx = i11 * ox + i12 * oy + i13 * oz
    hy = i21 * ox + i22 * oy + i23 * oz
    hz = i31 * ox + i32 * oy + i33 * oz
    nx = i11 * dx + i12 * dy + i13 * dz + (oy * hz - oz * hy)
    ny = i21 * dx + i22 * dy + i23 * dz + (oz * hx - ox * hz)
    nz = i31 * dx + i32 * dy + i33 * dz + (ox * hy - oy * hx)
    return (fx, fy, fz,
            py * fz - pz * fy + (r11 * nx + r12 * ny + r13 * nz),
            pz * fx - px * fz + (r21 * nx + r22 * ny + r23 * nz),
            px * fy - py * fx + (r31 * nx + r32 * ny + r33 * nz))


def leg_wrench(leg, motion, leg_bodies, gravity):
    """
    Return what one leg's own mass adds to the wrench the legs exert: ``[G, r x G]``.

    The leg runs from its base joint to its platform joint at ``r = R p`` from the platform's
    origin, which moves at ``V = v + w x r`` and accelerates at ``A = a + dw x r + w x (w x r)``.
    With ``u`` the leg's direction and ``l`` its length, ``dl/dt = u . V``, ``du/dt = (V - u
    dl/dt) / l`` and ``d2u/dt2 = (A - u d2l/dt2 - 2 dl/dt du/dt) / l``, where ``d2l/dt2 = u . A
    + l |du/dt|^2``. The lower body's centre (at ``d1`` from the base joint) accelerates at
    ``d1 d2u/dt2``, the upper body's (at ``d2`` from the platform joint) at ``A - d2
    d2u/dt2``; both turn at ``u x du/dt`` (no spin about the leg), with angular acceleration
    ``u x d2u/dt2``. By virtual work, the leg's inertia and weight load the platform joint with

        ``G = Q2 + P (d1 Q1 - d2 Q2 + (I1 + I2) d2u/dt2) / l``,

    ``Q1 = m1 (d1 d2u/dt2 - g)``, ``Q2 = m2 (A - d2 d2u/dt2 - g)``, ``P = 1 - u u^T``.

    :param leg: ``(l, lx, ly, lz, rx, ry, rz)`` of
        :func:`stewart_kinematics.model.formulas.legs_of` (no length 0).
    :param motion: see the module's docstring.
    :param leg_bodies: ``(m1, d1, m2, d2, I1 + I2)``: the lower and upper bodies' masses (kg)
        and distances from their joints (m), and the sum of their transverse inertias (kg m^2).
    :param gravity: ``(gx, gy, gz)``, m/s^2, base frame.
    :returns: ``(Gx, Gy, Gz, Mx, My, Mz)``: ``G`` and its moment about the platform origin.
    """
    length, lx, ly, lz, rx, ry, rz = leg
    vx, vy, vz, wx, wy, wz, ax, ay, az, ex, ey, ez = motion
    lower_mass, lower_distance, upper_mass, upper_distance, inertia = leg_bodies
    gx, gy, gz = gravity
    inverse = 1.0 / length
    ux, uy, uz = lx * inverse, ly * inverse, lz * inverse
    sx = wy * rz - wz * ry
    sy = wz * rx - wx * rz
    sz = wx * ry - wy * rx
    jx, jy, jz = vx + sx, vy + sy, vz + sz
    kx = ax + (ey * rz - ez * ry) + (wy * sz - wz * sy)
    ky = ay + (ez * rx - ex * rz) + (wz * sx - wx * sz)
    kz = az + (ex * ry - ey * rx) + (wx * sy - wy * sx)
    rate = ux * jx + uy * jy + uz * jz
    dx = (jx - rate * ux) * inverse
    dy = (jy - rate * uy) * inverse
    dz = (jz - rate * uz) * inverse
    rate_rate = ux * kx + uy * ky + uz * kz + length * (dx * dx + dy * dy + dz * dz)
    twice = rate + rate
    cx = (kx - rate_rate * ux - twice * dx) * inverse
    cy = (ky - rate_rate * uy - twice * dy) * inverse
    cz = (kz - rate_rate * uz - twice * dz) * inverse
    qx = upper_mass * (kx - upper_distance * cx - gx)
    qy = upper_mass * (ky - upper_distance * cy - gy)
    qz = upper_mass * (kz - upper_distance * cz - gz)
    hx = lower_distance * (lower_mass * (lower_distance * cx - gx)) - upper_distance * qx + (
        inertia * cx)
    hy = lower_distance * (lower_mass * (lower_distance * cy - gy)) - upper_distance * qy + (
        inertia * cy)
    hz = lower_distance * (lower_mass * (lower_distance * cz - gz)) - upper_distance * qz + (
        inertia * cz)
    axial = ux * hx + uy * hy + uz * hz
    tx = qx + (hx - axial * ux) * inverse
    ty = qy + (hy - axial * uy) * inverse
    tz = qz + (hz - axial * uz) * inverse
    return tx, ty, tz, ry * tz - rz * ty, rz * tx - rx * tz, rx * ty - ry * tx
