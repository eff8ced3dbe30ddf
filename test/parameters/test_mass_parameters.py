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
The mass parameters (platform, payload, leg bodies, gravity) build the MassProperties they state.

Each bad value is refused naming its parameter, before any force is computed; the payload's
parameters may change at run time, the others are read only.
"""

import math
from pathlib import Path

import numpy as np
import pytest
from stewart_kinematics import load_geometry
from stewart_kinematics.dynamics import leg_forces, platform_wrench
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import (
    GEOMETRY_PARAMETERS,
    mass_properties_from_parameters,
    MASS_SPECS,
    read_parameter_files,
)

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_masses.yaml']


@pytest.fixture(scope='module')
def values():
    """Return the paper's platform with the example masses, as parameter values."""
    return read_parameter_files(FILES)


def test_example_file_gives_the_masses_it_states(values):
    masses = mass_properties_from_parameters(values)
    assert (masses.platform.mass, masses.payload.mass) == (8.0, 20.0)
    assert masses.payload.center_of_mass == (0.0, 0.0, 0.375)
    assert masses.platform.inertia == (0.125, 0.125, 0.25, 0.0, 0.0, 0.0)
    assert (masses.leg_lower.mass, masses.leg_lower.center_of_mass,
            masses.leg_lower.inertia) == (1.5, 0.2, 0.02)
    assert (masses.leg_upper.mass, masses.leg_upper.center_of_mass,
            masses.leg_upper.inertia) == (0.5, 0.25, 0.01)
    assert masses.gravity == (0.0, 0.0, -9.80665)


def test_without_mass_parameters_every_mass_is_zero_and_gravity_standard():
    masses = mass_properties_from_parameters(read_parameter_files(FILES[:1]))
    assert masses.massless
    assert masses.gravity == (0.0, 0.0, -9.80665)


def test_mass_parameters_are_geometry_parameters_and_only_the_payload_changes_at_run_time():
    names = {spec.name for spec in GEOMETRY_PARAMETERS}
    expected = {f'{body}_{field}' for body in ('platform', 'payload', 'leg_lower', 'leg_upper')
                for field in ('mass', 'center_of_mass', 'inertia')} | {'gravity'}
    assert {spec.name for spec in MASS_SPECS} == expected
    assert expected <= names
    changeable = {spec.name for spec in MASS_SPECS if not spec.read_only}
    assert changeable == {'payload_mass', 'payload_center_of_mass', 'payload_inertia'}
    masses = {f'{body}_mass' for body in ('platform', 'payload', 'leg_lower', 'leg_upper')}
    assert {spec.name: spec.default for spec in MASS_SPECS
            if spec.name in masses} == dict.fromkeys(masses, 0.0)


def test_static_payload_is_carried_by_the_legs(values):
    """Massless legs: the legs' wrench on the platform balances the payload's weight alone."""
    only_payload = {**values, 'platform_mass': 0.0, 'platform_inertia': [0.0] * 6,
                    'leg_lower_mass': 0.0, 'leg_lower_inertia': 0.0,
                    'leg_upper_mass': 0.0, 'leg_upper_inertia': 0.0}
    masses = mass_properties_from_parameters(only_payload)
    geometry = load_geometry(FILES)
    pose = np.array([0.01, -0.02, 0.45, 0.05, -0.03, 0.1])
    forces = leg_forces(geometry, pose, mass_properties=masses)
    wrench = platform_wrench(geometry, pose, forces)
    weight = 20.0 * 9.80665
    # About the platform frame's origin, in the base frame: the lever is R c.
    lever = euler_zyx_to_matrix(pose[3:]) @ np.array([0.0, 0.0, 0.375])
    np.testing.assert_allclose(wrench[:3], [0.0, 0.0, weight], rtol=0, atol=1e-9)
    np.testing.assert_allclose(wrench[3:], np.cross(lever, [0.0, 0.0, weight]),
                               rtol=0, atol=1e-9)


NAN = math.nan
BAD_VALUES = [
    ('payload_mass', -1.0, 'payload_mass'),
    ('payload_mass', NAN, 'payload_mass'),
    ('platform_mass', math.inf, 'platform_mass'),
    ('leg_lower_mass', 1e308, 'leg_lower_mass'),
    ('leg_upper_mass', 'heavy', 'leg_upper_mass'),
    ('payload_center_of_mass', [0.0, 0.0], 'payload_center_of_mass'),
    ('payload_center_of_mass', [0.0, 0.0, 1e308], 'payload_center_of_mass'),
    ('platform_center_of_mass', [0.0, NAN, 0.0], 'platform_center_of_mass'),
    ('payload_inertia', [0.2, 0.2, 0.2, 0.0, 0.0], 'payload_inertia'),
    ('payload_inertia', [0.2, -0.2, 0.2, 0.0, 0.0, 0.0], 'positive semi-definite'),
    ('payload_inertia', [0.2, 0.2, 0.2, 0.5, 0.0, 0.0], 'positive semi-definite'),
    ('payload_inertia', [0.1, 0.1, 0.5, 0.0, 0.0, 0.0], 'triangle inequality'),
    ('platform_inertia', [1e300, 1e300, 1e300, 0.0, 0.0, 0.0], '1e150'),
    ('platform_inertia', [0.1, 0.1, 0.1, 0.0, 0.0, math.inf], 'platform_inertia'),
    ('leg_lower_inertia', -0.01, 'leg_lower_inertia'),
    ('leg_lower_center_of_mass', NAN, 'leg_lower_center_of_mass'),
    ('leg_upper_center_of_mass', 1e308, 'leg_upper_center_of_mass'),
    ('gravity', [0.0, 0.0, NAN], 'gravity'),
    ('gravity', [0.0, 0.0, -1e308], 'gravity'),
    ('gravity', [[0.0, 0.0, -9.8]], 'gravity'),
]


@pytest.mark.parametrize('name, value, words', BAD_VALUES,
                         ids=[f'{name}={value!r}' for name, value, _ in BAD_VALUES])
def test_bad_value_is_refused_naming_the_parameter(values, name, value, words):
    with pytest.raises(ValueError) as error:
        mass_properties_from_parameters({**values, name: value})
    message = str(error.value)
    assert name in message and words in message, message
    assert '\n' not in message


def test_inertia_without_mass_is_refused_naming_both_parameters(values):
    with pytest.raises(ValueError, match="'leg_upper_mass' and 'leg_upper_inertia'"):
        mass_properties_from_parameters({**values, 'leg_upper_mass': 0.0})
    with pytest.raises(ValueError, match="'payload_mass' and 'payload_inertia'"):
        mass_properties_from_parameters({**values, 'payload_mass': 0.0})


def test_inertia_of_a_rod_on_its_triangle_limit_is_allowed(values):
    """A thin rod along z: Izz = 0 and Ixx = Iyy, the triangle inequality met with equality."""
    masses = mass_properties_from_parameters(
        {**values, 'payload_inertia': [0.3, 0.3, 0.0, 0.0, 0.0, 0.0]})
    assert masses.payload.inertia == (0.3, 0.3, 0.0, 0.0, 0.0, 0.0)
