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
leg_forces and platform_wrench against independent formulations.

Lagrange's equations of the 13 bodies at 40 digits (lagrange_oracle.py), static and moving,
with and without leg masses, on 6-6, 6-3 and 3-3 platforms, to 1e-9 relative; the power
balance ``sum f_i dl_i/dt = d(T + U)/dt`` along random smooth trajectories; massless legs
against ``J^-T`` times a Newton-Euler wrench written here; zero masses give zero forces.
"""

from pathlib import Path

import lagrange_oracle as oracle
import numpy as np
import pytest

from stewart_kinematics import (
    euler_zyx_to_matrix,
    leg_forces,
    LegBody,
    load_geometry,
    MassProperties,
    platform_wrench,
    RigidBody,
    twist_jacobian,
)

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
GEOMETRIES = {name: load_geometry(CONFIG / file) for name, file in (
    ('6-6', 'paper_platform.yaml'), ('6-3', 'platform_6_3.yaml'),
    ('3-3', 'platform_3_3.yaml'))}
PLATFORM = (7.5, [0.01, 0.02, 0.03], [0.12, 0.14, 0.22, 0.01, -0.004, 0.02])
PAYLOAD = (20.0, [0.0, 0.03, 0.1], [0.3, 0.25, 0.2, 0.0, 0.01, 0.0])
LOWER = (1.5, 0.2, 0.02)
UPPER = (0.8, 0.25, 0.01)
TILTED_GRAVITY = [0.3, -0.2, -9.8]
#: The tests' tolerance: relative to the largest force.
RELATIVE = 1e-9


def mass_properties(legs=True, gravity=TILTED_GRAVITY):
    """Return the package's masses of the bodies above."""
    return MassProperties(platform=RigidBody(*PLATFORM), payload=RigidBody(*PAYLOAD),
                          leg_lower=LegBody(*LOWER) if legs else LegBody(),
                          leg_upper=LegBody(*UPPER) if legs else LegBody(), gravity=gravity)


def oracle_platform(geometry, legs=True, gravity=TILTED_GRAVITY):
    """Return the oracle's bodies: the same numbers, nothing else of the package."""
    return oracle.Platform(geometry.base_joints.tolist(), geometry.platform_joints.tolist(),
                           [PLATFORM, PAYLOAD], LOWER if legs else (0, 0, 0),
                           UPPER if legs else (0, 0, 0), gravity)


def home(geometry):
    return geometry.home_pose


def motion_case(geometry, seed, moving=True):
    """``q, dq, ddq`` about the home pose, and the package's twist and acceleration of them."""
    rng = np.random.default_rng(seed)
    q = home(geometry) + rng.uniform(-1, 1, 6) * [0.03, 0.03, 0.03, 0.08, 0.08, 0.1]
    dq = rng.uniform(-1, 1, 6) * [0.2, 0.2, 0.2, 0.5, 0.5, 0.5] * moving
    ddq = rng.uniform(-1, 1, 6) * [2.0, 2.0, 2.0, 4.0, 4.0, 4.0] * moving
    twist, acceleration = oracle.twist_and_acceleration(*map(oracle.as_mp, (q, dq, ddq)))
    return q, dq, ddq, np.array(twist, dtype=float), np.array(acceleration, dtype=float)


def assert_relative(actual, expected, relative=RELATIVE):
    expected = np.array(expected, dtype=float)
    np.testing.assert_allclose(actual, expected, rtol=0.0,
                               atol=relative * np.abs(expected).max())


@pytest.mark.parametrize('design', ['6-6', '6-3', '3-3'])
@pytest.mark.parametrize('legs', [False, True], ids=['massless legs', 'leg masses'])
@pytest.mark.parametrize('moving', [False, True], ids=['static', 'moving'])
def test_leg_forces_match_lagranges_equations(design, legs, moving):
    geometry = GEOMETRIES[design]
    q, dq, ddq, twist, acceleration = motion_case(geometry, seed=len(design) + 2 * legs + moving,
                                                  moving=moving)
    expected = oracle_platform(geometry, legs).leg_forces(*map(oracle.as_mp, (q, dq, ddq)))
    forces = leg_forces(geometry, q, twist if moving else None,
                        acceleration if moving else None, mass_properties=mass_properties(legs))
    assert_relative(forces, expected)
    # The batch path, on the same pose among others, gives the same.
    batch = leg_forces(geometry, np.stack([home(geometry), q]), np.stack([twist, twist]),
                       np.stack([acceleration, acceleration]) * moving,
                       mass_properties=mass_properties(legs))
    if moving:
        assert_relative(batch[1], expected)


def test_a_moving_platform_needs_other_forces_than_a_still_one():
    """The dynamic terms matter: the oracle's moving case differs from statics by far more."""
    geometry = GEOMETRIES['6-6']
    q, _, _, twist, acceleration = motion_case(geometry, seed=3)
    moving = leg_forces(geometry, q, twist, acceleration, mass_properties=mass_properties())
    still = leg_forces(geometry, q, mass_properties=mass_properties())
    assert np.abs(moving - still).max() > 1e3 * RELATIVE * np.abs(still).max()


@pytest.mark.parametrize('seed', range(4))
def test_power_balance_along_random_smooth_trajectories(seed):
    """``sum f_i dl_i/dt = d(T + U)/dt`` on a sum of sines, at a random time."""
    geometry = GEOMETRIES['6-6' if seed < 2 else '6-3']
    rng = np.random.default_rng(100 + seed)
    amplitude = rng.uniform(-1, 1, (2, 6)) * [0.02, 0.02, 0.02, 0.06, 0.06, 0.06]
    frequency = rng.uniform(0.5, 3.0, (2, 6))
    phase = rng.uniform(0, 2 * np.pi, (2, 6))
    t = rng.uniform(0, 5)
    angle = frequency * t + phase
    q = home(geometry) + (amplitude * np.sin(angle)).sum(0)
    dq = (amplitude * frequency * np.cos(angle)).sum(0)
    ddq = -(amplitude * frequency ** 2 * np.sin(angle)).sum(0)
    twist, acceleration = oracle.twist_and_acceleration(*map(oracle.as_mp, (q, dq, ddq)))
    platform = oracle_platform(geometry)
    rates = np.array(platform.leg_rates(oracle.as_mp(q), oracle.as_mp(dq)), dtype=float)
    energy_rate = float(platform.energy_rate(*map(oracle.as_mp, (q, dq, ddq))))
    forces = leg_forces(geometry, q, np.array(twist, dtype=float),
                        np.array(acceleration, dtype=float), mass_properties=mass_properties())
    power = forces @ rates
    assert abs(power - energy_rate) <= RELATIVE * np.abs(forces * rates).sum()


def newton_euler_wrench(pose, twist, acceleration, bodies, gravity):
    """Return the wrench on platform and payload, body by body, about the platform origin."""
    rotation = euler_zyx_to_matrix(pose[3:])
    v, w, a, dw = twist[:3], twist[3:], acceleration[:3], acceleration[3:]
    del v
    force, moment = np.zeros(3), np.zeros(3)
    for mass, center, inertia in bodies:
        arm = rotation @ center
        body_force = mass * (a + np.cross(dw, arm) + np.cross(w, np.cross(w, arm)) - gravity)
        ixx, iyy, izz, ixy, ixz, iyz = inertia
        tensor = rotation @ np.array([[ixx, ixy, ixz], [ixy, iyy, iyz],
                                      [ixz, iyz, izz]]) @ rotation.T
        force += body_force
        moment += np.cross(arm, body_force) + tensor @ dw + np.cross(w, tensor @ w)
    return np.concatenate([force, moment])


@pytest.mark.parametrize('design', ['6-6', '3-3'])
@pytest.mark.parametrize('moving', [False, True])
def test_massless_legs_give_the_inverse_transposed_jacobian_times_the_wrench(design, moving):
    geometry = GEOMETRIES[design]
    q, _, _, twist, acceleration = motion_case(geometry, seed=7, moving=moving)
    masses = mass_properties(legs=False)
    wrench = newton_euler_wrench(q, twist, acceleration, [
        (body.mass, np.array(body.center_of_mass), body.inertia)
        for body in (masses.platform, masses.payload)], np.array(masses.gravity))
    jacobian = twist_jacobian(geometry, q[:3], euler_zyx_to_matrix(q[3:]))
    expected = np.linalg.solve(jacobian.T, wrench)
    forces = leg_forces(geometry, q, twist, acceleration, mass_properties=masses)
    assert_relative(forces, expected, 1e-12)
    # And the legs' wrench on the platform is that wrench.
    assert_relative(platform_wrench(geometry, q, forces), wrench, 1e-12)


def test_static_payload_on_the_axis_is_carried_by_vertical_force_equal_to_its_weight():
    geometry = GEOMETRIES['6-6']
    masses = MassProperties(payload=RigidBody(20.0, [0.0, 0.0, 0.1]))
    forces = leg_forces(geometry, home(geometry), mass_properties=masses)
    wrench = platform_wrench(geometry, home(geometry), forces)
    np.testing.assert_allclose(wrench, [0, 0, 20.0 * 9.80665, 0, 0, 0], rtol=0, atol=1e-12)
    assert np.all(forces > 0)   # every leg pushes


def test_platform_wrench_is_the_transposed_jacobian_times_the_forces():
    geometry = GEOMETRIES['6-3']
    rng = np.random.default_rng(5)
    poses = home(geometry) + rng.uniform(-0.03, 0.03, (20, 6))
    forces = rng.uniform(-500, 500, (20, 6))
    wrench = platform_wrench(geometry, poses, forces)
    for pose, force, row in zip(poses, forces, wrench):
        jacobian = twist_jacobian(geometry, pose[:3], euler_zyx_to_matrix(pose[3:]))
        np.testing.assert_allclose(row, jacobian.T @ force, rtol=0, atol=1e-12 * 500)
        assert platform_wrench(geometry, pose, force).tobytes() == row.tobytes()


def test_every_mass_zero_gives_exactly_zero_forces():
    geometry = GEOMETRIES['6-6']
    poses = home(geometry) + np.random.default_rng(1).uniform(-0.03, 0.03, (5, 6))
    huge = np.full((5, 6), 1e300)
    assert np.array_equal(leg_forces(geometry, poses, huge, huge,
                                     mass_properties=MassProperties()), np.zeros((5, 6)))
    assert np.array_equal(leg_forces(geometry, poses[0], mass_properties=MassProperties(
        gravity=[1.0, 2.0, 3.0])), np.zeros(6))


def test_gravity_is_a_parameter():
    """Zero gravity at rest: no forces; reversed gravity: reversed forces."""
    geometry = GEOMETRIES['6-6']
    pose = home(geometry) + [0.01, 0.0, 0.02, 0.05, 0.0, 0.0]
    down = leg_forces(geometry, pose, mass_properties=mass_properties(gravity=[0, 0, -9.8]))
    up = leg_forces(geometry, pose, mass_properties=mass_properties(gravity=[0, 0, 9.8]))
    none = leg_forces(geometry, pose, mass_properties=mass_properties(gravity=[0, 0, 0]))
    np.testing.assert_allclose(up, -down, rtol=1e-14, atol=0)
    np.testing.assert_allclose(none, 0.0, atol=1e-12)
