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
Property tests of payload identification: exact on exact forces, and hostile forces refused.

Random payloads (0.5 to 200 kg, centres within 0.2 m) at random poses tilted up to 9 degrees
on the paper's platform with the example masses: the forces of the package's inverse dynamics
give the payload back to 1e-9, whatever the platform and legs weigh (they are subtracted). A
NaN, an infinity or a value too large for any actuator in the forces, or poses and forces of
different shapes, are refused naming the forces, never with numpy's words or a warning.
"""

from dataclasses import replace

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import assert_refused, budget, covers, floats, HUGE, NON_FINITE, with_bad_entry
import pytest
from stewart_kinematics import identify_payload, leg_forces, load_geometry, RigidBody

pytestmark = pytest.mark.core

GEOMETRY = load_geometry(['config/paper_platform.yaml', 'config/example_masses.yaml'])


def poses_of(seed, count=8):
    """Random poses within 3 cm and 0.15 rad of home."""
    rng = np.random.default_rng(seed)
    return GEOMETRY.home_pose + np.hstack([rng.uniform(-0.03, 0.03, (count, 3)),
                                           rng.uniform(-0.15, 0.15, (count, 3))])


def forces_of(payload, poses):
    """Return the example platform's and legs' forces carrying ``payload``."""
    masses = replace(GEOMETRY.mass_properties, payload=payload)
    return leg_forces(GEOMETRY, poses, mass_properties=masses)


@covers('identify_payload', 'PayloadEstimate')
@budget(20)
@given(mass=floats(0.5, 200.0), center=st.tuples(*[floats(-0.2, 0.2)] * 3),
       seed=st.integers(0, 2 ** 32 - 1))
def test_exact_forces_give_the_payload_back(mass, center, seed):
    """The fit is linear and exact: the payload to 1e-9, residuals at rounding, no warning."""
    poses = poses_of(seed)
    estimate = identify_payload(GEOMETRY, poses, forces_of(
        RigidBody(mass, center, name='payload'), poses))
    assert_allclose(estimate.mass, mass, rtol=1e-9)
    assert_allclose(estimate.center_of_mass, center, rtol=0.0, atol=1e-9)
    assert not estimate.warnings
    assert np.max(np.abs(estimate.residuals)) < 1e-9 * mass * 9.80665
    assert estimate.parameters()['payload_mass'] == estimate.mass


@covers('identify_payload')
@budget(20)
@given(data=st.data(), bad=st.one_of(NON_FINITE, HUGE), seed=st.integers(0, 2 ** 32 - 1))
def test_hostile_forces_are_refused_naming_them(data, bad, seed):
    """One NaN, infinity or huge value among the forces: a ValueError naming the forces."""
    poses = poses_of(seed)
    forces = data.draw(with_bad_entry(forces_of(RigidBody(20.0, name='payload'), poses), bad))
    assert_refused(lambda: identify_payload(GEOMETRY, poses, forces), ['forces'])


@covers('identify_payload')
@budget(10)
@given(rows=st.integers(0, 12), columns=st.integers(0, 8))
def test_forces_of_another_shape_are_refused(rows, columns):
    """Forces that are not one row of six per pose: refused naming them."""
    poses = poses_of(0)
    if (rows, columns) == (8, 6):
        return
    assert_refused(lambda: identify_payload(GEOMETRY, poses, np.ones((rows, columns))),
                   ['forces'])
