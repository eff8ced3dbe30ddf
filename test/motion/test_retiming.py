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
Retiming depends on the path and the limits only: property-based tests (hypothesis).

A path is a curve of platform poses: a screw (the position on a straight line, the orientation
turning about one fixed axis, both in proportion: the same curve at any density, from 2
waypoints up) or a smooth wave (three harmonics on each of the six pose coordinates, sampled
densely enough that the waypoints describe the curve: 300 waypoints and more). Each is given
with random timings (any scale from 0.1 s to 10^5 s, uneven), at random densities, unevenly
spaced, with random repeated waypoints (dwells), and retimed under the example limits. The
retimed duration must agree within 1 % with the same curve given densely and evenly, and the
legs must stay within every limit: their lengths from the textbook formula of
test/reference.py at the poses played every millisecond, their velocities and accelerations by
finite differences of those lengths.
"""

from functools import lru_cache
from pathlib import Path

from hypothesis import given, HealthCheck, settings, strategies
import numpy as np
import pytest
import reference

from stewart_kinematics import ActuatorLimits, load_geometry, plan_motion, PoseTrajectory
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, rotation_vector_to_matrix

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
GEOMETRY = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])
LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
HOME = GEOMETRY.home_pose
#: Waypoints of the reference sampling of each curve (evenly spaced, evenly timed).
REFERENCE_DENSITY = 2000
#: Step of the independent check of the played motion, seconds.
STEP = 1e-3
#: Relative tolerance of the durations, and of the limits under finite differences.
DURATION_TOLERANCE = 0.01
SETTINGS = settings(max_examples=12, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow])


def screw(seed):
    """Build a straight line with a rotation about one axis, both in proportion to ``u``."""
    rng = np.random.default_rng(seed)
    offset = rng.uniform(-1.0, 1.0, 6) * [0.03, 0.03, 0.03, 0.1, 0.1, 0.15]
    start = euler_zyx_to_matrix(HOME[3:])

    def poses(u):
        return (HOME[:3] + np.outer(u, offset[:3]),
                start @ rotation_vector_to_matrix(np.outer(u, offset[3:])))
    return poses


def wave(seed):
    """Build three harmonics on each coordinate, from home, within the example limits."""
    rng = np.random.default_rng(seed)
    amplitudes = rng.uniform(-1.0, 1.0, (3, 6)) * [0.015, 0.015, 0.01, 0.05, 0.05, 0.07]
    phases = rng.uniform(0.0, 2.0 * np.pi, (3, 6))
    harmonics = np.arange(1, 4)[:, None]

    def poses(u):
        angles = harmonics[None] * np.pi * np.asarray(u)[:, None, None] + phases
        pose = HOME + (amplitudes * (np.sin(angles) - np.sin(phases))).sum(axis=1)
        return pose[:, :3], euler_zyx_to_matrix(pose[:, 3:])
    return poses


CURVES = {'screw': screw, 'wave': wave}


@lru_cache(maxsize=None)
def reference_duration(kind, seed):
    """Retimed duration of the curve given densely and evenly, timed evenly over 10 s."""
    positions, rotations = CURVES[kind](seed)(np.linspace(0.0, 1.0, REFERENCE_DENSITY))
    plan = plan_motion(PoseTrajectory(np.linspace(0.0, 10.0, REFERENCE_DENSITY), positions,
                                      rotations), GEOMETRY, LIMITS, retime_path=True)
    assert plan.accepted, plan.reason
    return plan.trajectory.duration


def given_path(kind, seed, count, spacing_seed, dwells, scale):
    """Sample the curve at ``count`` uneven waypoints, with repeated ones, timed unevenly."""
    rng = np.random.default_rng(spacing_seed)
    u = np.sort(np.concatenate([[0.0, 1.0], rng.uniform(0.0, 1.0, count - 2)]))
    positions, rotations = CURVES[kind](seed)(u)
    repeated = rng.integers(0, count, dwells)
    positions = np.insert(positions, repeated, positions[repeated], axis=0)
    rotations = np.insert(rotations, repeated, rotations[repeated], axis=0)
    steps = rng.uniform(0.05, 1.0, positions.shape[0] - 1)
    times = np.concatenate([[0.0], np.cumsum(steps)])
    return PoseTrajectory(times * scale / times[-1], positions, rotations)


def assert_within_limits(trajectory):
    """Lengths (reference formula) and their finite differences every STEP seconds."""
    times = np.arange(0.0, trajectory.duration, STEP)
    samples = trajectory.sample(times)
    poses = np.concatenate([samples.positions, np.array(
        [reference_angles(rotation) for rotation in samples.rotations])], axis=1)
    lengths = np.array([reference.leg_lengths(pose) for pose in poses])
    assert lengths.min() >= GEOMETRY.leg_length_min
    assert lengths.max() <= GEOMETRY.leg_length_max
    velocities = np.diff(lengths, axis=0) / STEP
    accelerations = np.diff(lengths, 2, axis=0) / STEP ** 2
    assert np.abs(velocities).max() <= LIMITS.velocity_max * (1.0 + DURATION_TOLERANCE)
    assert np.abs(accelerations).max() <= LIMITS.acceleration_max * (1.0 + DURATION_TOLERANCE)


def reference_angles(rotation):
    """Euler angles (alpha, beta, gamma) of R = Rz Ry Rx, independently of the package."""
    beta = np.arcsin(-rotation[2, 0])
    return (np.arctan2(rotation[2, 1], rotation[2, 2]), beta,
            np.arctan2(rotation[1, 0], rotation[0, 0]))


@SETTINGS
@given(kind=strategies.sampled_from(sorted(CURVES)), seed=strategies.integers(0, 3),
       count=strategies.integers(2, 3000), spacing_seed=strategies.integers(0, 2 ** 16),
       dwells=strategies.integers(0, 3), scale=strategies.floats(0.1, 1e5))
def test_the_same_path_retimes_to_the_same_duration_within_the_limits(
        kind, seed, count, spacing_seed, dwells, scale):
    """Any timing, density (a wave: 300 waypoints up) and dwells: the same duration, 1 %."""
    if kind == 'wave':
        count = max(count, 300)
    plan = plan_motion(given_path(kind, seed, count, spacing_seed, dwells, scale), GEOMETRY,
                       LIMITS, retime_path=True)
    assert plan.accepted, plan.reason
    expected = reference_duration(kind, seed)
    assert abs(plan.trajectory.duration / expected - 1.0) <= DURATION_TOLERANCE, (
        plan.trajectory.duration, expected)
    assert_within_limits(plan.trajectory)


@pytest.mark.parametrize('kind', sorted(CURVES))
def test_a_hundred_thousand_uneven_waypoints_retime_like_a_few(kind):
    """10^5 unevenly spaced waypoints with dwells, over 10^4 s: the same duration, 1 %."""
    plan = plan_motion(given_path(kind, 1, 99_990, 7, 5, 1e4), GEOMETRY, LIMITS,
                       retime_path=True)
    assert plan.accepted, plan.reason
    assert abs(plan.trajectory.duration / reference_duration(kind, 1) - 1.0) <= (
        DURATION_TOLERANCE)
    assert_within_limits(plan.trajectory)
