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
The workspace under the leg force limit: a heavy payload shrinks the travel ranges and volume.

The static forces are computed here from the statics alone (``J^T f`` = the payload's weight
and its moment about the platform origin, with the textbook rotation matrices of
test/reference.py and numpy's solver), and each end of a travel range stopped by a force limit
is located again by bisection on those forces: the package's end must be where the first leg
reaches ``leg_force_max`` (or ``leg_force_min``), and the leg named must be that leg.
"""

import math
from pathlib import Path

import numpy as np
import pytest
import reference

from stewart_kinematics import findings, load_geometry, MassProperties, RigidBody
from stewart_kinematics.analysis import workspace
from stewart_kinematics.analysis.capabilities import geometry_report, parameters_report
from stewart_kinematics.limits import LIMIT_NAMES
from stewart_kinematics.parameters import read_parameter_files

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
GRAVITY = 9.80665
#: The payload of the documentation's worked example: 20 kg, 0.1 m above the platform origin.
PAYLOAD = RigidBody(20.0, [0.0, 0.0, 0.1], name='payload')
#: A payload off the axis, so that tilting it makes some legs pull.
OFFSET_PAYLOAD = RigidBody(20.0, [0.05, -0.03, 0.2], name='payload')
#: Push limit that binds with PAYLOAD (about 33 N per leg at home), N.
FORCE_MAX = 60.0


@pytest.fixture(scope='module')
def limited():
    """Return the paper's platform under the example limits, no masses."""
    return load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])


def loaded(geometry, payload=PAYLOAD, **force_limits):
    """Return ``geometry`` carrying ``payload`` (massless platform and legs), force limits set."""
    return geometry.__class__(
        geometry.base_joints, geometry.platform_joints, geometry.home_pose,
        limits=geometry.limits.replace(**force_limits),
        mass_properties=MassProperties(payload=payload))


def static_forces(geometry, payload, poses):
    """Solve ``J^T f = [m g, (R c) x m g]`` per pose: the legs hold the payload still, N."""
    poses = np.atleast_2d(poses)
    rotations = reference.rotations_zyx(poses[:, 3:])
    arms = np.einsum('nij,kj->nki', rotations, geometry.platform_joints)
    legs = poses[:, None, :3] + arms - geometry.base_joints
    units = legs / np.linalg.norm(legs, axis=-1, keepdims=True)
    transposed = np.concatenate([units, np.cross(arms, units)], axis=-1).transpose(0, 2, 1)
    weight = np.array([0.0, 0.0, payload.mass * GRAVITY])
    centres = rotations @ np.asarray(payload.center_of_mass)
    wrench = np.concatenate([np.broadcast_to(weight, centres.shape),
                             np.cross(centres, weight)], axis=-1)
    return np.linalg.solve(transposed, wrench[..., None])[..., 0]


def force_end(geometry, payload, axis, sign, breaks, scan_step=5e-4, tolerance=1e-9):
    """
    Return ``(move, leg)``: where along the ray the first leg breaks ``breaks(forces)``.

    Scanned at ``scan_step`` from the home pose, then bisected to ``tolerance``; ``leg`` is
    1..6, the leg that breaks first (the largest excess just beyond the end).
    """
    home = geometry.home_pose

    def pose(move):
        moved = home.copy()
        moved[axis] += sign * move
        return moved

    inside = 0.0
    while not breaks(static_forces(geometry, payload, pose(inside + scan_step))[0]).any():
        inside += scan_step
        assert inside < 3.0, 'no force limit along this ray'
    outside = inside + scan_step
    while outside - inside > tolerance:
        middle = 0.5 * (inside + outside)
        if breaks(static_forces(geometry, payload, pose(middle))[0]).any():
            outside = middle
        else:
            inside = middle
    leg = int(np.argmax(breaks(static_forces(geometry, payload, pose(outside))[0]))) + 1
    return sign * inside, leg


def test_a_binding_push_limit_shrinks_the_ranges_to_where_a_leg_reaches_it(limited):
    free = workspace.travel_ranges(limited)
    heavy = workspace.travel_ranges(loaded(limited, leg_force_max=FORCE_MAX))
    stopped_by_force = 0
    for axis, (before, after) in enumerate(zip(free.axes, heavy.axes)):
        for end, sign in (('negative', -1.0), ('positive', 1.0)):
            limit = getattr(after, f'{end}_limit')
            if limit == 'leg_force_max':
                stopped_by_force += 1
                move, leg = force_end(limited, PAYLOAD, axis, sign,
                                      lambda forces: forces > FORCE_MAX)
                tolerance = heavy.tolerance[0 if axis < 3 else 1]
                np.testing.assert_allclose(getattr(after, end), move, rtol=0.0,
                                           atol=2 * tolerance, err_msg=f'{after.axis} {end}')
                assert getattr(after, f'{end}_leg') == leg, f'{after.axis} {end}'
                # The payload took away travel that the other limits allowed.
                assert abs(getattr(after, end)) < abs(getattr(before, end)) - 1e-3
            else:
                # A ray the forces do not stop ends where it did without the payload.
                assert limit == getattr(before, f'{end}_limit')
                assert getattr(after, end) == getattr(before, end)
    # With 60 N (home: 33 N a leg), the tilts and the horizontal moves are stopped by forces.
    assert stopped_by_force >= 8
    assert heavy.axes[4].positive_limit == 'leg_force_max'
    np.testing.assert_allclose(np.degrees(heavy.axes[4].positive), 8.11, atol=0.01)
    np.testing.assert_allclose(np.degrees(free.axes[4].positive), 16.83, atol=0.01)


def test_a_push_limit_below_the_lowered_forces_shrinks_the_z_range(limited):
    # Lowering the platform leans the legs a little more: their static forces grow slowly
    # (leg 2: 33.73 N at home, 33.85 N 50 mm lower), so a push limit just above the home
    # forces cuts the downward travel (without it: leg_length_min at -52 mm).
    home_forces = static_forces(limited, PAYLOAD, limited.home_pose)[0]
    force_max = float(home_forces.max()) + 0.05
    heavy = workspace.travel_ranges(loaded(limited, leg_force_max=force_max))
    z = heavy.axes[2]
    move, leg = force_end(limited, PAYLOAD, 2, -1.0, lambda forces: forces > force_max)
    assert z.negative_limit == 'leg_force_max'
    assert z.negative_leg == leg
    np.testing.assert_allclose(z.negative, move, rtol=0.0, atol=2e-7)
    assert -0.052 < z.negative < -0.001


def test_a_pull_limit_is_named_leg_force_min_with_the_leg_that_pulls(limited):
    force_min = -5.0
    heavy = workspace.travel_ranges(loaded(limited, OFFSET_PAYLOAD, leg_force_min=force_min))
    named = 0
    for axis, travel in enumerate(heavy.axes):
        for end, sign in (('negative', -1.0), ('positive', 1.0)):
            if getattr(travel, f'{end}_limit') != 'leg_force_min':
                continue
            named += 1
            move, leg = force_end(limited, OFFSET_PAYLOAD, axis, sign,
                                  lambda forces: forces < force_min)
            np.testing.assert_allclose(getattr(travel, end), move, rtol=0.0, atol=2e-7)
            assert getattr(travel, f'{end}_leg') == leg
    assert named >= 2


def test_the_force_limit_shrinks_the_volume_and_bounds_the_slices_where_a_leg_reaches_it(
        limited):
    geometry = loaded(limited, leg_force_max=FORCE_MAX)
    free = workspace.workspace_volume(limited, resolution=0.02)
    heavy = workspace.workspace_volume(geometry, resolution=0.02)
    assert heavy.volume < 0.2 * free.volume
    # The forces hardly change with the height: the force limit bounds the workspace across
    # x and y, where an XY slice meets it.
    cut = workspace.workspace_slice(geometry, 'XY', resolution=(0.005, 0.005))
    on_force = cut.boundary_limit == LIMIT_NAMES.index('leg_force_max')
    assert on_force.sum() > 20
    points = np.zeros((on_force.sum(), 6))
    points[:] = limited.home_pose
    points[:, :2] = cut.boundary[on_force]
    peaks = static_forces(limited, PAYLOAD, points).max(axis=1)
    # Each point is reachable and within 1e-7 m of the boundary: its largest force is at
    # most the limit and within a millinewton of it.
    assert np.all(peaks <= FORCE_MAX)
    np.testing.assert_allclose(peaks, FORCE_MAX, rtol=0.0, atol=1e-3)
    legs = static_forces(limited, PAYLOAD, points).argmax(axis=1) + 1
    np.testing.assert_array_equal(cut.boundary_leg[on_force], legs)


def test_every_mass_0_leaves_the_ranges_as_they_are(limited):
    free = workspace.travel_ranges(limited)
    massless = limited.__class__(limited.base_joints, limited.platform_joints,
                                 limited.home_pose,
                                 limits=limited.limits.replace(leg_force_max=1.0,
                                                               leg_force_min=-1.0),
                                 mass_properties=MassProperties())
    np.testing.assert_array_equal(workspace.travel_ranges(massless).as_array(),
                                  free.as_array())
    assert workspace.travel_ranges(massless).axes == free.axes


def test_a_slice_names_the_leg_that_pulls_most_beyond_leg_force_min(limited):
    # Far tilts make several legs pull beyond the limit at once: the leg named is the one
    # whose pull exceeds it most (a negative limit must not turn the comparison round).
    force_min = -2.0
    geometry = limited.__class__(
        limited.base_joints, limited.platform_joints, limited.home_pose,
        limits=limited.limits.__class__(leg_force_min=force_min),
        mass_properties=MassProperties(payload=OFFSET_PAYLOAD))
    extent = ((-math.radians(40.0), math.radians(40.0)),
              (-math.radians(40.0), math.radians(40.0)))
    result = workspace.workspace_slice(geometry, ('alpha', 'beta'), extent=extent,
                                       resolution=(math.radians(2.0), math.radians(2.0)))
    refused = result.limit == LIMIT_NAMES.index('leg_force_min')
    alpha, beta = np.meshgrid(result.u, result.v)
    poses = np.zeros((refused.sum(), 6))
    poses[:] = limited.home_pose
    poses[:, 3], poses[:, 4] = alpha[refused], beta[refused]
    forces = static_forces(limited, OFFSET_PAYLOAD, poses)
    several = np.sum(forces < force_min, axis=1) >= 2
    assert several.sum() > 20, 'the slice must hold points where several legs pull too much'
    np.testing.assert_array_equal(result.leg[refused], forces.argmin(axis=1) + 1)


def test_the_geometry_report_gives_the_force_margins_at_home(limited):
    report = geometry_report(loaded(limited, leg_force_max=FORCE_MAX, leg_force_min=-10.0))
    forces = static_forces(limited, PAYLOAD, limited.home_pose)[0]
    margins = {margin.limit: margin for margin in report.margins}
    np.testing.assert_allclose(margins['leg_force_max'].margin, FORCE_MAX - forces.max(),
                               rtol=1e-12)
    assert margins['leg_force_max'].subject == f'leg {forces.argmax() + 1}'
    np.testing.assert_allclose(margins['leg_force_min'].margin, forces.min() + 10.0,
                               rtol=1e-12)
    assert margins['leg_force_min'].subject == f'leg {forces.argmin() + 1}'
    assert 'leg_force_max 60 N: at home 33.7283 N (leg 2), margin 26.27 N' in report.text()
    assert report.travel.axes[4].positive_limit == 'leg_force_max'
    # Without masses, the force limits are set but not checked: no margin.
    bare = geometry_report(limited.__class__(
        limited.base_joints, limited.platform_joints, limited.home_pose,
        limits=limited.limits.replace(leg_force_max=FORCE_MAX)))
    assert not [margin for margin in bare.margins if margin.limit.startswith('leg_force')]


def test_a_payload_too_heavy_for_the_home_pose_is_reported_naming_leg_force_max():
    values = read_parameter_files([CONFIG / 'paper_platform.yaml',
                                   CONFIG / 'example_limits.yaml'])
    values.update(payload_mass=20.0, payload_center_of_mass=[0.0, 0.0, 0.1], leg_force_max=30.0)
    report = parameters_report(values)
    assert not report.usable and 'leg_force_max' in report.home_refusal
    assert [warning.code for warning in report.warnings] == [findings.LIMIT_BROKEN_AT_HOME]
    margin = next(margin for margin in report.margins if margin.limit == 'leg_force_max')
    assert margin.broken and margin.subject == 'leg 2'
    assert '[limit_broken_at_home] the home pose breaks leg_force_max 30 N: at home 33.7' in (
        report.text())
