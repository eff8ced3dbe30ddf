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
Tests of stewart_kinematics.analysis.workspace against independent computations written here.

The limits are evaluated here from their definitions in the README (leg vectors from the
textbook rotation matrices, cone angles with arccos, the condition number with
``numpy.linalg.cond``), not with stewart_kinematics.limits. Travel ranges are compared with a
brute-force scan along each axis, volumes with Monte Carlo estimates, and boundary points are
checked to lie within a micrometre of a limit.
"""

import math

import numpy as np
import pytest
import reference

from stewart_kinematics import load_geometry
from stewart_kinematics.analysis import workspace
from stewart_kinematics.limits import LIMIT_NAMES

pytestmark = pytest.mark.core


@pytest.fixture(scope='module')
def limited():
    """Return the paper's platform under the example limits."""
    from pathlib import Path
    config = Path(__file__).resolve().parents[2] / 'config'
    return load_geometry([config / 'paper_platform.yaml', config / 'example_limits.yaml'])


def limits_by_hand(geometry, poses):
    """
    Return (allowed (N,), broken (N, 6) per limit in LIMIT_NAMES order) from the definitions.

    The condition number and the leg collisions are computed only where stroke and cones pass
    (they are the slow part), the collisions with the textbook segment distance of
    test/reference.py.
    """
    poses = np.atleast_2d(poses)
    rotations = reference.rotations_zyx(poses[:, 3:])
    rotated = np.einsum('nij,kj->nki', rotations, geometry.platform_joints)
    legs = poses[:, None, :3] + rotated - geometry.base_joints
    lengths = np.linalg.norm(legs, axis=-1)
    units = legs / lengths[..., None]
    home = geometry.home_pose
    home_rotation = reference.rotations_zyx(home[None, 3:])[0]
    home_legs = home[:3] + geometry.platform_joints @ home_rotation.T - geometry.base_joints
    home_units = home_legs / np.linalg.norm(home_legs, axis=-1, keepdims=True)
    base_angles = np.arccos(np.clip(np.einsum('nki,ki->nk', units, home_units), -1.0, 1.0))
    in_platform = np.einsum('nji,nkj->nki', rotations, units)        # R^T u
    platform_home = home_units @ home_rotation                         # R_home^T u_home
    platform_angles = np.arccos(np.clip(np.einsum('nki,ki->nk', in_platform, platform_home),
                                        -1.0, 1.0))
    broken = np.zeros((len(poses), 6), dtype=bool)
    broken[:, 0] = np.any(lengths < geometry.leg_length_min, axis=-1)
    broken[:, 1] = np.any(lengths > geometry.leg_length_max, axis=-1)
    broken[:, 2] = np.any(base_angles > geometry.base_joint_max_angle, axis=-1)
    broken[:, 3] = np.any(platform_angles > geometry.platform_joint_max_angle, axis=-1)
    others = ~np.any(broken[:, :4], axis=-1)
    if math.isfinite(geometry.max_jacobian_condition) and np.any(others):
        centred = geometry.platform_joints - geometry.platform_joints.mean(axis=0)
        rho = math.sqrt(np.mean(np.sum(centred ** 2, axis=-1)))
        moments = np.cross(rotated[others], units[others]) / rho
        jacobians = np.concatenate([units[others], moments], axis=-1)
        broken[others, 4] = np.linalg.cond(jacobians) > geometry.max_jacobian_condition
    if geometry.leg_radius and np.any(others):
        tops = poses[others, None, :3] + rotated[others]                 # platform joints
        first, second = np.triu_indices(6, 1)
        distances = reference.segment_distance(
            geometry.base_joints[first], tops[:, first], geometry.base_joints[second],
            tops[:, second])
        broken[others, 5] = np.any(distances < 2.0 * geometry.leg_radius, axis=-1)
    return ~np.any(broken, axis=-1), broken


def first_refused(geometry, start, axis, sign, step, span):
    """Return the offset of the first refused sample on a ray, or None within the span."""
    offsets = sign * step * np.arange(1, int(span / step) + 1)
    poses = np.repeat(start[None, :], len(offsets), axis=0)
    poses[:, axis] += offsets
    allowed, _ = limits_by_hand(geometry, poses)
    refused = np.flatnonzero(~allowed)
    return None if refused.size == 0 else offsets[refused[0]]


def brute_force_range(geometry, start, axis, sign, span):
    """Return (end of the range to 1e-6, limits broken just beyond it) by two fine scans."""
    coarse = 1e-4
    outside = first_refused(geometry, start, axis, sign, coarse, span)
    if outside is None:
        return sign * span, set()
    near = start.copy()
    near[axis] += outside - sign * coarse
    fine = first_refused(geometry, near, axis, sign, 1e-6, 1.01 * coarse)
    end = outside - sign * coarse + fine
    beyond = start.copy()
    beyond[axis] += end
    _, broken = limits_by_hand(geometry, beyond)
    return end - sign * 1e-6, {LIMIT_NAMES[k] for k in np.flatnonzero(broken[0])}


@pytest.mark.parametrize('start', ['home', 'moved'])
def test_travel_ranges_match_a_brute_force_scan(limited, start):
    pose = (None if start == 'home' else
            limited.home_pose + np.array([0.03, -0.02, 0.05, 0.05, -0.08, 0.3]))
    ranges = workspace.travel_ranges(limited, pose)
    begin = limited.home_pose if pose is None else pose
    for axis, travel in enumerate(ranges.axes):
        assert travel.axis == workspace.AXES[axis]
        for sign, end, limit in ((-1.0, travel.negative, travel.negative_limit),
                                 (1.0, travel.positive, travel.positive_limit)):
            expected, broken = brute_force_range(limited, begin, axis, sign, 2.0)
            # Both within 1e-6 (m or rad) of the boundary, each on its own side.
            assert abs(end - expected) <= 2.1e-6, (travel.axis, sign, end, expected)
            assert limit in broken, (travel.axis, sign, limit, broken)


def test_every_axis_of_the_paper_platform_is_stopped_by_a_limit(limited):
    ranges = workspace.travel_ranges(limited)
    table = ranges.table()
    for travel in ranges.axes:
        assert travel.negative < 0.0 < travel.positive
        assert travel.negative_limit in LIMIT_NAMES and travel.positive_limit in LIMIT_NAMES
        assert travel.axis in table
    np.testing.assert_allclose(ranges.as_array()[:, 1],
                               [travel.positive for travel in ranges.axes])


def test_a_ray_that_leaves_and_comes_back_reports_the_connected_range(limited):
    # Along gamma the example limits break only the singularity margin, over a band near
    # 90 degrees: beyond it the platform is allowed again, but out of reach by turning alone.
    gamma = workspace.travel_ranges(limited).axes[5]
    assert gamma.positive_limit == 'max_jacobian_condition'
    offsets = np.linspace(gamma.positive + 1e-4, math.pi, 2000)
    poses = np.repeat(limited.home_pose[None, :], len(offsets), axis=0)
    poses[:, 5] += offsets
    allowed, _ = limits_by_hand(limited, poses)
    assert not allowed[0] and np.any(allowed), 'the gamma ray no longer comes back'
    expected, _ = brute_force_range(limited, limited.home_pose, 5, 1.0, math.pi)
    assert abs(gamma.positive - expected) <= 2.1e-6


def test_travel_ranges_refuse_a_start_that_breaks_a_limit(limited):
    with pytest.raises(ValueError, match='start pose breaks the limits: .*leg_length_max'):
        workspace.travel_ranges(limited, limited.home_pose + [0.0, 0.0, 0.3, 0.0, 0.0, 0.0])


def monte_carlo_volume(geometry, box, count, seed):
    """Return (volume, standard error) of the positions reachable at the home orientation."""
    rng = np.random.default_rng(seed)
    low, high = box
    points = rng.uniform(low, high, (count, 3))
    poses = np.concatenate([points, np.repeat(geometry.home_pose[None, 3:], count, 0)], -1)
    allowed, _ = limits_by_hand(geometry, poses)
    box_volume = float(np.prod(high - low))
    fraction = np.count_nonzero(allowed) / count
    return fraction * box_volume, math.sqrt(fraction * (1 - fraction) / count) * box_volume


def test_volume_agrees_with_monte_carlo_and_converges(limited):
    coarse = workspace.workspace_volume(limited, resolution=0.02)
    fine = workspace.workspace_volume(limited, resolution=0.01)
    assert coarse.bounded and fine.bounded
    box = fine.bounding_box + np.array([[-0.01], [0.01]])
    estimate, error = monte_carlo_volume(limited, box, 100_000, seed=21)
    print(f'\nvolume: grid 20 mm {coarse.volume:.6f} m^3, grid 10 mm {fine.volume:.6f} m^3, '
          f'Monte Carlo {estimate:.6f} +- {error:.6f} m^3 (100000 samples)')
    for result in (coarse, fine):
        assert abs(result.volume - estimate) <= 4.0 * error
    assert abs(fine.volume - coarse.volume) <= 0.005 * fine.volume
    # The bounding box holds every reachable Monte Carlo sample.
    rng = np.random.default_rng(22)
    points = rng.uniform(box[0], box[1], (20_000, 3))
    poses = np.concatenate([points, np.repeat(limited.home_pose[None, 3:], len(points), 0)], -1)
    allowed, _ = limits_by_hand(limited, poses)
    inside = points[allowed]
    assert np.all(inside >= fine.bounding_box[0] - fine.resolution)
    assert np.all(inside <= fine.bounding_box[1] + fine.resolution)


def assert_near_a_limit(geometry, poses, axes, limit, distance=1e-6, sample=1500):
    """Assert each boundary pose is allowed and a step of ``distance`` breaks its limit."""
    rng = np.random.default_rng(5)
    chosen = rng.choice(len(poses), min(sample, len(poses)), replace=False)
    poses, limit = poses[chosen], limit[chosen]
    allowed, _ = limits_by_hand(geometry, poses)
    assert np.all(allowed)
    neighbours = []
    for axis in axes:
        for sign in (-1.0, 1.0):
            moved = poses.copy()
            moved[:, axis] += sign * distance
            neighbours.append(limits_by_hand(geometry, moved)[1])
    broken = np.stack(neighbours)                       # (steps, M, 5)
    assert np.all(np.any(broken, axis=(0, 2))), 'a boundary point far from every limit'
    assert np.all(broken[:, np.arange(len(poses)), limit].any(axis=0)), \
        'a boundary point attributed to the wrong limit'


def test_volume_boundary_points_lie_on_a_limit(limited):
    result = workspace.workspace_volume(limited, resolution=0.02)
    poses = np.concatenate([result.boundary,
                            np.repeat(limited.home_pose[None, 3:], len(result.boundary), 0)],
                           -1)
    assert np.all(np.isin(result.boundary_limit, range(len(LIMIT_NAMES))))
    assert set(result.boundary_limit.tolist()) >= {0, 1, 2}
    assert_near_a_limit(limited, poses, (0, 1, 2), result.boundary_limit)


@pytest.mark.parametrize('plane, pose_change', [
    ('XY', [0.0, 0.0, 0.05, 0.0, 0.0, 0.0]),
    ('XZ', [0.0, 0.0, 0.0, 0.1, 0.0, 0.0]),
    ('YZ', [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
    (('alpha', 'beta'), [0.05, 0.0, 0.0, 0.0, 0.0, 0.2]),
])
def test_slices_classify_their_grid_and_boundary(limited, plane, pose_change):
    pose = limited.home_pose + np.array(pose_change)
    result = workspace.workspace_slice(limited, plane, pose, resolution=(
        (0.004, 0.004) if plane != ('alpha', 'beta') else (0.01, 0.01)))
    u_axis, v_axis = result.axes
    assert result.bounded and result.allowed.shape == (len(result.v), len(result.u))
    # Grid points: the classification equals the independent one.
    grid = np.repeat(pose[None, :], result.allowed.size, axis=0)
    uu, vv = np.meshgrid(result.u, result.v)
    grid[:, u_axis], grid[:, v_axis] = uu.ravel(), vv.ravel()
    allowed, broken = limits_by_hand(limited, grid)
    np.testing.assert_array_equal(result.allowed.ravel(), allowed)
    refused = ~allowed
    assert np.all(broken[refused, result.limit.ravel()[refused]])
    assert np.all(result.limit.ravel()[allowed] == -1)
    # Dexterity: the condition number where allowed, NaN elsewhere.
    assert np.all(np.isnan(result.condition.ravel()[refused]))
    some = np.flatnonzero(allowed)[::97]
    centred = limited.platform_joints - limited.platform_joints.mean(axis=0)
    rho = math.sqrt(np.mean(np.sum(centred ** 2, axis=-1)))
    rotations = reference.rotations_zyx(grid[some, 3:])
    rotated = np.einsum('nij,kj->nki', rotations, limited.platform_joints)
    legs = grid[some, None, :3] + rotated - limited.base_joints
    units = legs / np.linalg.norm(legs, axis=-1, keepdims=True)
    expected = np.linalg.cond(np.concatenate([units, np.cross(rotated, units) / rho], -1))
    np.testing.assert_allclose(result.condition.ravel()[some], expected, rtol=1e-9)
    # Boundary points lie within a micrometre (or microradian) of the limit named.
    boundary = np.repeat(pose[None, :], len(result.boundary), axis=0)
    boundary[:, u_axis], boundary[:, v_axis] = result.boundary[:, 0], result.boundary[:, 1]
    assert len(boundary) > 100
    assert_near_a_limit(limited, boundary, result.axes, result.boundary_limit)
    # The area from the grid agrees with the fraction of allowed points.
    cell = (result.u[1] - result.u[0]) * (result.v[1] - result.v[0])
    assert result.area == pytest.approx(np.count_nonzero(allowed) * cell)


def test_orientation_workspace_at_a_position(limited):
    gammas = (0.0, math.radians(40.0), math.radians(80.0))
    slices = workspace.orientation_workspace(limited, [0.0, 0.0, 0.5], gammas, resolution=0.01)
    assert [s.labels for s in slices] == [('alpha', 'beta')] * 3
    for result, gamma in zip(slices, gammas):
        np.testing.assert_allclose(result.pose, [0.0, 0.0, 0.5, 0.0, 0.0, gamma])
    same = workspace.workspace_slice(limited, 'alpha-beta', slices[1].pose, resolution=0.01)
    np.testing.assert_array_equal(same.allowed, slices[1].allowed)
    # On this platform, 0.5 m up, torsion narrows the reachable tilts.
    assert slices[0].area > slices[1].area > slices[2].area


def test_bad_planes_are_refused(limited):
    for plane in ('XX', 'XQ', ('alpha',), 'alpha-alpha'):
        with pytest.raises(ValueError, match='plane must name two different coordinates'):
            workspace.workspace_slice(limited, plane)
