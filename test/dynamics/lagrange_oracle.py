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
An independent oracle of the inverse dynamics: Lagrange's equations of all 13 bodies, at 40 digits.

Nothing here comes from the package. The generalised coordinates are the pose ``q = [X, Y, Z,
alpha, beta, gamma]`` itself; the kinetic energy ``T(q, dq)`` and the potential ``U(q)`` are
written from the bodies' positions alone (platform, payload, and each leg's lower and upper
body), and every velocity and derivative is a numerical derivative at 40 significant digits
(mpmath, fourth-order central differences), accurate to far better than the 1e-9 the tests ask.
Then ``J_q^T f = d/dt dT/d(dq) - dT/dq + dU/dq`` with ``J_q = dl/dq`` gives the leg forces.

The package's conventions enter only through what the oracle returns to compare with: the
twist ``[v, w]`` and its derivative, computed here from ``q``, ``dq`` and ``ddq`` (``w`` from
``dR/dt R^T``).
"""

import mpmath as mp

mp.mp.dps = 40
#: Steps of the central differences: in positions (and in time), and in velocities.
STEP = mp.mpf('1e-8')
VELOCITY_STEP = mp.mpf('0.5')


def derivative(function, x):
    """Fourth-order central difference of ``function`` (a number or a list of them) at ``x``."""
    values = [function(x + k * STEP) for k in (-2, -1, 1, 2)]
    if isinstance(values[0], list):
        return [(a - 8 * b + 8 * c - d) / (12 * STEP) for a, b, c, d in zip(*values)]
    a, b, c, d = values
    return (a - 8 * b + 8 * c - d) / (12 * STEP)


def rotation(alpha, beta, gamma):
    """``Rz(gamma) Ry(beta) Rx(alpha)`` as an mpmath matrix."""
    ca, sa, cb, sb, cg, sg = (mp.cos(alpha), mp.sin(alpha), mp.cos(beta), mp.sin(beta),
                              mp.cos(gamma), mp.sin(gamma))
    rx = mp.matrix([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
    ry = mp.matrix([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])
    rz = mp.matrix([[cg, -sg, 0], [sg, cg, 0], [0, 0, 1]])
    return rz * ry * rx


def _vector(values):
    return mp.matrix([mp.mpf(value) for value in values])


def _tensor(entries):
    ixx, iyy, izz, ixy, ixz, iyz = (mp.mpf(value) for value in entries)
    return mp.matrix([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


class Platform:
    """
    The bodies of a platform, in mpmath: joints, two rigid bodies, two-body legs, gravity.

    :param base_joints: (6, 3) metres; ``platform_joints`` likewise (platform frame).
    :param rigid_bodies: ``(mass, centre (3), inertia [Ixx, Iyy, Izz, Ixy, Ixz, Iyz])`` each.
    :param lower: ``(mass, distance from the base joint, transverse inertia)``; ``upper``
        likewise from the platform joint.
    :param gravity: (3,), base frame.
    """

    def __init__(self, base_joints, platform_joints, rigid_bodies, lower, upper, gravity):
        self.base = [_vector(joint) for joint in base_joints]
        self.platform = [_vector(joint) for joint in platform_joints]
        self.bodies = [(mp.mpf(mass), _vector(center), _tensor(inertia))
                       for mass, center, inertia in rigid_bodies]
        self.lower = [mp.mpf(value) for value in lower]
        self.upper = [mp.mpf(value) for value in upper]
        self.gravity = _vector(gravity)

    def positions(self, q):
        """Rotation, body centres, leg directions and lengths at ``q``: a flat list of numbers."""
        position = mp.matrix(q[:3])
        turn = rotation(*q[3:])
        values = list(turn)
        for _, center, _ in self.bodies:
            values += list(position + turn * center)
        for base, joint in zip(self.base, self.platform):
            top = position + turn * joint
            leg = top - base
            length = mp.sqrt(sum(entry ** 2 for entry in leg))
            direction = leg / length
            values += list(base + self.lower[1] * direction)
            values += list(top - self.upper[1] * direction)
            values += list(direction) + [length]
        return values

    def lengths(self, q):
        """Return the six leg lengths at ``q``."""
        return self.positions(q)[9 + 3 * len(self.bodies) + 9::10]

    def kinetic_energy(self, q, dq):
        """``T(q, dq)``: every velocity the derivative of a position along ``dq``."""
        now = self.positions(q)
        rates = derivative(lambda s: self.positions([a + s * b for a, b in zip(q, dq)]), 0)
        turn = mp.matrix(3, 3)
        turn_rate = mp.matrix(3, 3)
        for k in range(9):
            turn[k // 3, k % 3], turn_rate[k // 3, k % 3] = now[k], rates[k]
        spin = turn_rate * turn.T
        omega = mp.matrix([spin[2, 1], spin[0, 2], spin[1, 0]])
        energy = mp.mpf(0)
        index = 9
        for mass, _, inertia in self.bodies:
            velocity = rates[index:index + 3]
            world_inertia = turn * inertia * turn.T
            energy += mass * sum(v ** 2 for v in velocity) / 2
            energy += (omega.T * world_inertia * omega)[0] / 2
            index += 3
        for _ in range(6):
            lower_velocity = rates[index:index + 3]
            upper_velocity = rates[index + 3:index + 6]
            u = mp.matrix(now[index + 6:index + 9])
            du = mp.matrix(rates[index + 6:index + 9])
            leg_omega = [u[1] * du[2] - u[2] * du[1], u[2] * du[0] - u[0] * du[2],
                         u[0] * du[1] - u[1] * du[0]]
            energy += self.lower[0] * sum(v ** 2 for v in lower_velocity) / 2
            energy += self.upper[0] * sum(v ** 2 for v in upper_velocity) / 2
            energy += (self.lower[2] + self.upper[2]) * sum(w ** 2 for w in leg_omega) / 2
            index += 10
        return energy

    def potential_energy(self, q):
        """``U(q) = -sum m g . c``."""
        now = self.positions(q)
        energy = mp.mpf(0)
        index = 9
        for mass, _, _ in self.bodies:
            energy -= mass * sum(g * c for g, c in zip(self.gravity, now[index:index + 3]))
            index += 3
        for _ in range(6):
            lower, upper = now[index:index + 3], now[index + 3:index + 6]
            energy -= self.lower[0] * sum(g * c for g, c in zip(self.gravity, lower))
            energy -= self.upper[0] * sum(g * c for g, c in zip(self.gravity, upper))
            index += 10
        return energy

    def momentum(self, q, dq, j):
        """``dT/d(dq_j)``: exact for a quadratic form, with a large step."""
        def energy(step):
            return self.kinetic_energy(q, [v + (step if k == j else 0) for k, v in
                                           enumerate(dq)])
        return (energy(VELOCITY_STEP) - energy(-VELOCITY_STEP)) / (2 * VELOCITY_STEP)

    def generalised_forces(self, q, dq, ddq):
        """``d/dt dT/d(dq) - dT/dq + dU/dq`` at ``q(0)`` of ``q(t) = q + dq t + ddq t^2 / 2``."""
        forces = []
        for j in range(6):
            def along(t, j=j):
                return self.momentum([a + b * t + c * t * t / 2 for a, b, c in zip(q, dq, ddq)],
                                     [b + c * t for b, c in zip(dq, ddq)], j)

            def shifted(x, j=j):
                return [a + (x if k == j else 0) for k, a in enumerate(q)]
            forces.append(derivative(along, 0)
                          - derivative(lambda x: self.kinetic_energy(shifted(x), dq), 0)
                          + derivative(lambda x: self.potential_energy(shifted(x)), 0))
        return forces

    def leg_forces(self, q, dq, ddq):
        """Leg forces: ``J_q^T f = Q``, ``J_q = dl/dq``."""
        jacobian = mp.matrix(6, 6)
        for j in range(6):
            column = derivative(lambda x: self.lengths(
                [a + (x if k == j else 0) for k, a in enumerate(q)]), 0)
            for i in range(6):
                jacobian[i, j] = column[i]
        return list(mp.lu_solve(jacobian.T, mp.matrix(self.generalised_forces(q, dq, ddq))))

    def energy_rate(self, q, dq, ddq):
        """``d(T + U)/dt`` at ``t = 0`` of ``q(t) = q + dq t + ddq t^2 / 2``."""
        def energy(t):
            return (self.kinetic_energy([a + b * t + c * t * t / 2 for a, b, c in
                                         zip(q, dq, ddq)], [b + c * t for b, c in zip(dq, ddq)])
                    + self.potential_energy([a + b * t + c * t * t / 2 for a, b, c in
                                             zip(q, dq, ddq)]))
        return derivative(energy, 0)

    def leg_rates(self, q, dq):
        """``dl/dt`` along ``dq``."""
        return derivative(lambda s: self.lengths([a + s * b for a, b in zip(q, dq)]), 0)


def angular_velocity(q, dq):
    """``w`` of ``dR/dt R^T`` (base frame) along ``dq``."""
    turn = rotation(*q[3:])
    rates = derivative(lambda s: list(rotation(*[a + s * b for a, b in zip(q[3:], dq[3:])])), 0)
    turn_rate = mp.matrix(3, 3)
    for k in range(9):
        turn_rate[k // 3, k % 3] = rates[k]
    spin = turn_rate * turn.T
    return [spin[2, 1], spin[0, 2], spin[1, 0]]


def twist_and_acceleration(q, dq, ddq):
    """Return the twist and acceleration at 0 of ``q(t) = q + dq t + ddq t^2 / 2``."""
    omega = angular_velocity(q, dq)
    rate = derivative(lambda t: angular_velocity(
        [a + b * t + c * t * t / 2 for a, b, c in zip(q, dq, ddq)],
        [b + c * t for b, c in zip(dq, ddq)]), 0)
    return list(dq[:3]) + omega, list(ddq[:3]) + rate


def as_mp(values):
    """Floats to mpmath numbers (exactly)."""
    return [mp.mpf(float(value)) for value in values]
