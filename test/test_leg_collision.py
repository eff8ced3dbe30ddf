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
Tests of the leg collision limit against an independent segment distance (test/reference.py).

The evaluator (stewart_kinematics.limits.leg_collision) computes the distance between the axes
of all 15 pairs of legs, vectorised over poses, by Ericson's clamped closest points; the
reference enumerates the textbook candidates (the critical point of the two lines, and the four
edges: an end point to the other segment), and is itself checked against a ternary search.
"""

import dataclasses
import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics import Geometry, load_geometry, Ramp
from stewart_kinematics.limits import LEG_PAIRS, LimitModel, segment_distances
from stewart_kinematics.limits.leg_collision import FIRST, SECOND
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parent.parent / 'config'
#: How far the decision may be off, metres: no miss and no false alarm beyond this.
DECISION_TOLERANCE = 1e-9


@pytest.fixture(scope='module')
def limited():
    """Return the paper's platform under the example limits (legs of 40 mm diameter)."""
    return load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])


def collisions_only(geometry, leg_radius):
    """Return the geometry with no limit but leg collisions of ``leg_radius``."""
    return dataclasses.replace(geometry, leg_length_min=0.0, leg_length_max=math.inf,
                               base_joint_max_angle=math.pi, platform_joint_max_angle=math.pi,
                               max_jacobian_condition=math.inf, leg_radius=leg_radius)


def reference_distances(geometry, poses):
    """Distances between the legs' axes of each pose, (N, 15), from test/reference.py."""
    rotations = np.array([reference.rotation_zyx(*pose[3:]) for pose in poses])
    tops = poses[:, None, :3] + np.einsum('nij,kj->nki', rotations, geometry.platform_joints)
    return reference.segment_distance(geometry.base_joints[FIRST], tops[:, FIRST],
                                      geometry.base_joints[SECOND], tops[:, SECOND])


def test_the_reference_agrees_with_a_ternary_search():
    """The enumeration of test/reference.py equals a search over the segment (1e-12 m)."""
    rng = np.random.default_rng(1)
    points = rng.normal(size=(4, 3000, 3))
    points[:, :300] = points[:, :1]               # both segments points, then one
    points[1, 300:600] = points[0, 300:600]
    assert_allclose(reference.segment_distance(*points),
                    reference.segment_distance_by_search(*points), rtol=0.0, atol=1e-12)


def test_every_pair_on_thousands_of_random_poses_no_miss_no_false_alarm(limited):
    """
    The 15 distances of 5000 poses equal the reference's; the decision is never wrong by 1e-9 m.

    Half the poses stay near home, where only the neighbouring legs come close; the others
    move and turn the platform far (up to 0.3 m, 1 rad of tilt, 3 rad of yaw), so that legs
    cross and every pair collides somewhere.
    """
    geometry = collisions_only(limited, 0.025)
    rng = np.random.default_rng(2)
    near = rng.uniform(-1.0, 1.0, (2500, 6)) * [0.15, 0.15, 0.1, 0.5, 0.5, 1.2]
    far = rng.uniform(-1.0, 1.0, (2500, 6)) * [0.3, 0.3, 0.3, 1.0, 1.0, 3.0]
    poses = geometry.home_pose + np.concatenate([near, far])
    checks = LimitModel(geometry).check_poses(poses)
    expected = reference_distances(geometry, poses)
    assert_allclose(checks.leg_distances, expected, rtol=0.0, atol=1e-12)
    allowed_distance = 2.0 * geometry.leg_radius
    broken = checks.broken['leg_collision']
    missed = broken != (expected < allowed_distance)
    assert not np.any(missed & (np.abs(expected - allowed_distance) > DECISION_TOLERANCE))
    # The sample exercises the limit: each of the 15 pairs collides at 100 poses or more.
    assert np.all(broken.sum(axis=0) >= 100), broken.sum(axis=0)
    assert np.array_equal(checks.allowed, ~broken.any(axis=1))


def test_one_pose_equals_the_batch_to_the_bit(limited):
    """check_pose (one pose, the float leg path) reports the batch's collisions exactly."""
    geometry = collisions_only(limited, 0.025)
    rng = np.random.default_rng(3)
    spread = [0.1, 0.1, 0.1, 0.5, 0.5, 1.2]
    poses = geometry.home_pose + rng.uniform(-1.0, 1.0, (300, 6)) * spread
    model = LimitModel(geometry)
    checks = model.check_poses(poses)
    refused = 0
    for index, pose in enumerate(poses):
        single = model.check_pose(pose[:3], euler_zyx_to_matrix(pose[3:]))
        assert single == checks.violations(index)
        refused += bool(single)
    assert refused > 30


def test_a_collision_names_the_two_legs_and_the_clearance(limited):
    """A refusal says which two legs, how far apart their axes are, and the clearance."""
    geometry = collisions_only(limited, 0.02)
    pose = np.array([0.0, 0.0, 0.4325, 0.45, 0.0, 1.3])
    violations = LimitModel(geometry).check_pose(pose[:3], euler_zyx_to_matrix(pose[3:]))
    assert violations
    for violation in violations:
        assert violation.limit == 'leg_collision' and violation.unit == 'm'
        assert (violation.leg, violation.other_leg) in LEG_PAIRS
        assert violation.legs == (violation.leg, violation.other_leg)
        assert violation.allowed == pytest.approx(0.04, abs=1e-15)
        distance = reference_distances(geometry, pose[None])[0][
            LEG_PAIRS.index((violation.leg, violation.other_leg))]
        assert violation.value == pytest.approx(distance, abs=1e-12)
        assert violation.excess == pytest.approx(0.04 - distance, abs=1e-12)
        text = str(violation)
        assert text.startswith(f'legs {violation.leg} and {violation.other_leg}: leg_collision')
        assert f'clearance {violation.value - 0.04:.6g} m' in text


def test_a_home_pose_where_legs_collide_is_refused_naming_the_pairs():
    """Legs of 53 mm: at home the axes of legs 1 and 6, and 4 and 5, are 52.1 mm apart."""
    with pytest.raises(ValueError, match='home pose breaks the limits') as raised:
        reference.paper_geometry(leg_radius=0.0265)
    message = str(raised.value)
    assert 'legs 1 and 6: leg_collision' in message and 'legs 4 and 5: leg_collision' in message
    assert 'legs 2 and 3' not in message          # 54.4 mm apart: clear of 53 mm
    assert reference.paper_geometry(leg_radius=0.025).leg_radius == 0.025


@pytest.mark.parametrize('radius', [-0.01, math.nan, math.inf, 1e308 * 10.0])
def test_a_leg_radius_that_is_no_radius_is_refused(radius):
    """Negative, NaN or infinite radii are refused, naming the parameter."""
    with pytest.raises(ValueError, match='leg_radius must be finite and >= 0'):
        reference.paper_geometry(leg_radius=radius)


def test_the_table_3_ramp_keeps_the_example_leg_radius(limited):
    """config/example_limits.yaml says so: legs 2 and 3 come closest, 47.3 mm, at its end."""
    ramp = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])
    poses = ramp.sample(np.linspace(0.0, 10.0, 2001), 10.0)
    distances = reference_distances(limited, poses)
    assert limited.leg_radius == 0.02
    assert distances.min() == pytest.approx(0.0473, abs=5e-5)
    assert LEG_PAIRS[int(np.argmin(distances.min(axis=0)))] == (2, 3)
    assert np.argmin(distances.min(axis=1)) == len(poses) - 1
    assert LimitModel(limited).check_poses(poses).allowed.all()


# Segments an adversary would choose --------------------------------------------------------

def evaluator_distance(p0, p1, q0, q1):
    """Return the evaluator's distance of segments p0 p1 and q0 q1 (as legs 1 and 2)."""
    legs = np.zeros((6, 3))
    legs[0], legs[1] = np.subtract(p1, p0), np.subtract(q1, q0)
    offsets = np.zeros((15, 3))
    offsets[0] = np.subtract(p0, q0)             # pair (1, 2)
    lengths = np.linalg.norm(legs, axis=-1)
    distances = segment_distances(legs[:, :1], legs[:, 1:2], legs[:, 2:], lengths[:, None],
                                  tuple(offsets[:, axis:axis + 1] for axis in range(3)))
    return float(distances[0, 0])


@pytest.mark.parametrize('p0, p1, q0, q1, expected', [
    # Parallel, overlapping: the distance between the lines.
    ((0, 0, 0), (1, 0, 0), (0.5, 0.3, 0), (1.5, 0.3, 0), 0.3),
    # Parallel, apart along their direction: end to end.
    ((0, 0, 0), (1, 0, 0), (2, 0.3, 0), (3, 0.3, 0), math.hypot(1.0, 0.3)),
    # Anti-parallel, overlapping.
    ((0, 0, 0), (1, 0, 0), (1.5, 0, 0.4), (0.2, 0, 0.4), 0.4),
    # Collinear and overlapping: they touch.
    ((0, 0, 0), (1, 0, 0), (0.5, 0, 0), (2, 0, 0), 0.0),
    # Crossing: distance 0.
    ((0, 0, 0), (1, 1, 0), (1, 0, 0), (0, 1, 0), 0.0),
    # Skew, closest points inside both.
    ((0, 0, 0), (1, 0, 0), (0.5, -1, 0.25), (0.5, 1, 0.25), 0.25),
    # A point (a leg of zero length) and a segment; two points.
    ((0.5, 0.2, 0), (0.5, 0.2, 0), (0, 0, 0), (1, 0, 0), 0.2),
    ((0, 0, 0), (1, 0, 0), (2, 0, 0), (2, 0, 0), 1.0),
    ((0, 0, 0), (0, 0, 0), (0, 3, 4), (0, 3, 4), 5.0),
    # Nearly parallel (1e-9 rad) and offset.
    ((0, 0, 0), (1, 0, 0), (0, 0.1, 0), (1, 0.1 + 1e-9, 0), 0.1),
], ids=['parallel', 'parallel apart', 'anti-parallel', 'collinear', 'crossing', 'skew',
        'point and segment', 'segment and point', 'two points', 'nearly parallel'])
def test_degenerate_segments(p0, p1, q0, q1, expected):
    """Parallel, collinear, crossing and zero-length segments: the exact distance, no NaN."""
    with np.errstate(all='raise'):                 # no warning escapes the evaluator either
        distance = evaluator_distance(p0, p1, q0, q1)
    assert distance == pytest.approx(expected, abs=1e-12)
    assert distance == pytest.approx(float(reference.segment_distance(
        *(np.array(point, dtype=float) for point in (p0, p1, q0, q1)))), abs=1e-12)


def test_a_platform_joint_on_its_base_joint_is_a_point_not_a_failure():
    """A leg of zero length (exact, dyadic joints) is a point: its distances are finite."""
    scale = 2.0 ** 20
    base = np.round(reference.BASE_JOINTS * scale) / scale
    platform = np.round(reference.PLATFORM_JOINTS * scale) / scale
    geometry = Geometry(base_joints=base, platform_joints=platform, home_pose=reference.HOME,
                        leg_radius=0.001)
    position = base[0] - platform[0]                      # platform joint 1 on base joint 1
    model = LimitModel(geometry)
    legs = model.pose_legs(position, np.eye(3))
    assert legs.lengths[0, 0] == 0.0
    (distances,) = model.evaluator(type(model.pose_limits[0])).values(legs)
    assert np.all(np.isfinite(distances))
    expected = reference_distances(geometry, np.concatenate([position, np.zeros(3)])[None])
    assert_allclose(distances[:, 0], expected[0], rtol=0.0, atol=1e-12)


@pytest.mark.parametrize('value, words', [
    (-0.01, "parameter 'leg_radius' must be in [0, 1]"), (math.nan, "'leg_radius' must be finite"),
    (math.inf, "'leg_radius' must be finite"), (2.0, "'leg_radius' must be in [0, 1]")])
def test_the_leg_radius_parameter_refuses_what_is_no_radius(value, words):
    """A parameter file's leg_radius is checked by its spec: the node stops with this reason."""
    from stewart_kinematics.parameters import GeometrySettings
    values = {'base_joints': reference.BASE_JOINTS.ravel().tolist(),
              'platform_joints': reference.PLATFORM_JOINTS.ravel().tolist(),
              'home_position': list(reference.HOME[:3]), 'leg_radius': value}
    with pytest.raises(ValueError, match=words.replace('[', r'\[').replace(']', r'\]')):
        GeometrySettings.from_values(values)
    values['leg_radius'] = 0.02
    assert GeometrySettings.from_values(values).leg_radius == 0.02
