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
The numbers doc/dynamics.md states, recomputed: its worked example, its travel ranges, its figures.

The ramp's forces are computed again here with Newton-Euler for the point-mass payload (its
weight and inertial force at its centre, their moment about the platform origin, ``f = J^-T
w``), from the poses, twists and accelerations of the figure script; the page's doctests (run
by the site build) show the arrays, this test the sentences and the table around them.
"""

import importlib.util
import math
from pathlib import Path
import re

import numpy as np
import pytest
import reference

from stewart_kinematics import load_geometry, MassProperties

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / 'doc' / 'dynamics.md'
GRAVITY = np.array([0.0, 0.0, -9.80665])


def load_script():
    """Import scripts/figures/dynamics.py, which draws the page's figures."""
    spec = importlib.util.spec_from_file_location('dynamics_figures',
                                                  ROOT / 'scripts' / 'figures' / 'dynamics.py')
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope='module')
def script():
    """Return the figure script as a module."""
    return load_script()


@pytest.fixture(scope='module')
def page():
    """Return the page's text, lines joined (a sentence may wrap anywhere)."""
    return ' '.join(PAGE.read_text(encoding='utf-8').split())


@pytest.fixture(scope='module')
def ramp(script):
    """Return the ramp's ``(times, poses, static, moving, twists, accelerations)``."""
    geometry = load_geometry(script.CONFIG)
    return (geometry,) + script.ramp_forces(geometry, MassProperties(payload=script.PAYLOAD))


def newton_euler(geometry, payload, poses, twists, accelerations):
    """Return the leg forces that move the point-mass ``payload`` along the samples, N."""
    rotations = reference.rotations_zyx(poses[:, 3:])
    arms = np.einsum('nij,kj->nki', rotations, geometry.platform_joints)
    legs = poses[:, None, :3] + arms - geometry.base_joints
    units = legs / np.linalg.norm(legs, axis=-1, keepdims=True)
    transposed = np.concatenate([units, np.cross(arms, units)], axis=-1).transpose(0, 2, 1)
    centres = rotations @ np.asarray(payload.center_of_mass)
    omega, alpha = twists[:, 3:], accelerations[:, 3:]
    acceleration = (accelerations[:, :3] + np.cross(alpha, centres)
                    + np.cross(omega, np.cross(omega, centres)))
    force = payload.mass * (acceleration - GRAVITY)
    wrench = np.concatenate([force, np.cross(centres, force)], axis=-1)
    return np.linalg.solve(transposed, wrench[..., None])[..., 0]


def test_the_ramp_forces_are_newton_euler_of_the_payload(ramp, script):
    geometry, times, poses, static, moving, twists, accelerations = ramp
    assert len(times) == 201 and times[-1] == 2.0
    expected = newton_euler(geometry, script.PAYLOAD, poses, twists, accelerations)
    np.testing.assert_allclose(moving, expected, rtol=0.0, atol=1e-9)
    still = newton_euler(geometry, script.PAYLOAD, poses, 0.0 * twists, 0.0 * accelerations)
    np.testing.assert_allclose(static, still, rtol=0.0, atol=1e-9)
    # The page's doctest: home and the end of the ramp.
    np.testing.assert_allclose(static[0], [32.91, 33.73, 32.81, 33.39, 33.52, 32.95], atol=0.005)
    np.testing.assert_allclose(moving[-1], [113.7, 118.0, -68.2, 62.5, 5.5, -54.5], atol=0.05)


def test_the_sentences_of_the_worked_example(ramp, page):
    geometry, times, poses, static, moving, twists, accelerations = ramp
    linear = np.linalg.norm(accelerations[:, :3], axis=1)
    angular = np.linalg.norm(accelerations[:, 3:], axis=1)
    assert (f'up to {linear.max():.1f} m/s^2 and {angular.max():.1f} rad/s^2 here, in the first '
            'and last 0.2 s') in page
    # Accelerated in the first and last 0.2 s; in between, constant speed and a nearly
    # constant rate of turn.
    middle = (times > 0.2 + 1e-9) & (times < 1.8 - 1e-9)
    assert np.abs(accelerations[middle, :3]).max() < 1e-9
    assert 0.03 < angular[middle].max() < 0.04
    assert 'turns at a nearly constant rate, below 0.04 rad/s^2' in page
    np.testing.assert_allclose(linear[[0, -1]], linear.max(), rtol=1e-12)
    change = np.abs(moving - static).max()
    assert round(change) == 75 and 'change the forces by up to 75 N' in page
    assert (round(static[:, 1].min()), round(static[:, 1].max())) == (34, 103)
    assert '(leg 2: from 34 to 103 N)' in page
    assert (round(moving[-1, 2]), round(static[-1, 2])) == (-68, -2)
    assert 'leg 3 pulls 68 N while the payload stops, against 2 N once it stands' in page
    assert np.all(static[-1, [2, 4]] < 0) and 'legs 3 and 5 already pull' in page
    assert (f'static forces from {static.min():.1f} to {static.max():.1f} N') in page
    assert 'weight, 196.13 N' in page
    np.testing.assert_allclose(20.0 * 9.80665, 196.133)


def test_the_travel_range_table_and_its_sentences(script, page):
    geometry = load_geometry(script.CONFIG)
    without, with_payload = script.payload_travel_ranges(geometry)
    table = script.markdown_table(without, with_payload)
    assert ' '.join(table.split()) in page, (
        'doc/dynamics.md: the travel range table is out of date; run '
        'scripts/figures/dynamics.py')
    assert script.FORCE_LIMITS == {'leg_force_min': -60.0, 'leg_force_max': 120.0}
    assert '(`leg_force_max: 120.0`, `leg_force_min: -60.0`)' in page
    before, after = without.as_array(), with_payload.as_array()
    # Sideways: less than half; the turn: 59 degrees; Z and the tilts stay.
    assert np.all(np.abs(after[:2]) < 0.5 * np.abs(before[:2]))
    assert round(math.degrees(after[5, 1])) == 59 and 'the turn to 59 degrees' in page
    np.testing.assert_array_equal(after[2:5], before[2:5])
    for axis in with_payload.axes[2:5]:
        assert 'leg_length' in axis.negative_limit and 'leg_length' in axis.positive_limit
    # Raising or lowering the payload hardly changes the forces.
    from stewart_kinematics import leg_forces
    masses = MassProperties(payload=script.PAYLOAD)
    lowered = geometry.home_pose - [0.0, 0.0, 0.05, 0.0, 0.0, 0.0]
    home, low = (leg_forces(geometry, pose, mass_properties=masses)[1]
                 for pose in (geometry.home_pose, lowered))
    assert f'(leg 2: {home:.1f} N at home, {low:.1f} N 50 mm lower)' in page


def test_the_figures_are_on_the_page_and_drawn(page, script, tmp_path):
    for name in ('leg_forces_ramp.png', 'travel_ranges_payload.png'):
        assert f'(figures/{name})' in page
        data = (ROOT / 'docs' / name).read_bytes()
        assert data[:8] == b'\x89PNG\r\n\x1a\n' and len(data) > 10_000, name
    assert re.search(r'drawn by `scripts/figures/dynamics.py`', page)
