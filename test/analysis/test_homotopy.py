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
Tests of stewart_kinematics.analysis.homotopy: the path tracker's parts, against plain numpy.

The assembly modes it finds are tested in test_assembly_modes.py (against Dietmaier's published
solutions and an independent multi-start search); here the pieces: the equations against their
definition, the Taylor series of a path against points on the path found by Newton's method,
and the distinctness count against its pairwise definition.
"""

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import leg_lengths, paper_geometry, TABLE_3

from stewart_kinematics.analysis import homotopy

pytestmark = pytest.mark.core


@pytest.fixture(scope='module')
def system():
    """Return the paper platform's start system, a Table 3 row's quadrics, the homotopy."""
    geometry = paper_geometry()
    frame = homotopy.NormalisedFrame(geometry)
    start, _ = homotopy.geometry_start_system(geometry)
    lengths = np.asarray(leg_lengths(TABLE_3[6]))
    target = homotopy._normalised_quadrics(start.basis, frame.platform_joints,
                                           frame.base_joints, lengths / frame.scale)
    return start, target, homotopy.Homotopy(start, start.quadrics, target)


def definition(start, target, z, s):
    """H(z, s) typed out: (gamma (1 - s) Q_start + s Q_target) forms, Study quadric, chart."""
    legs = [z @ (start.gamma * (1 - s) * source + s * goal) @ z
            for source, goal in zip(start.quadrics, target)]
    return np.array(legs + [z @ start.basis.study @ z, start.chart @ z - 1.0])


def test_equations_and_jacobians_match_their_definition(system):
    start, target, equations = system
    rng = np.random.default_rng(3)
    z = rng.normal(size=(5, 8)) + 1j * rng.normal(size=(5, 8))
    s = rng.uniform(size=5)
    values, jacobians = equations.evaluate(z, s)
    for k in range(5):
        assert_allclose(values[k], definition(start, target, z[k], s[k]), rtol=1e-12)
        step = 1e-7 * (rng.normal(size=8) + 1j * rng.normal(size=8))
        difference = (definition(start, target, z[k] + step, s[k])
                      - definition(start, target, z[k] - step, s[k])) / 2.0
        assert_allclose(jacobians[k] @ step, difference, rtol=1e-6, atol=1e-12)


def test_the_series_is_the_taylor_series_of_the_path(system):
    """The predictor's series, summed, lands on the path within its truncation error."""
    start, _, equations = system
    z = start.solutions[:8].copy()   # solutions of the start system: points of the paths at s=0
    s = np.zeros(8)
    assert np.max(np.abs(equations.evaluate(z, s)[0])) < 1e-12
    inverse = np.linalg.inv(equations.evaluate(z, s)[1])
    series = equations.series(z, s, inverse, 5)
    for h in (0.01, 0.02):
        on_path = z + h * series[1]
        for _ in range(8):
            values, jacobians = equations.evaluate(on_path, s + h)
            on_path -= np.linalg.solve(jacobians, values[..., None])[..., 0]
        errors = [np.max(np.abs(sum(series[j] * h ** j for j in range(order + 1)) - on_path))
                  for order in range(1, 6)]
        # Each order more cuts the error, by about the step over the series' radius.
        assert all(later < earlier for earlier, later in zip(errors, errors[1:]))
        assert errors[-1] < 1e-3 * errors[0]


def test_tracked_ends_solve_the_target_and_the_end_game_polishes_them(system):
    start, target, equations = system
    ends, reached = homotopy.track(start, target, start.solutions)
    assert np.all(reached == 1.0)
    polished, residuals, conditions = homotopy.polish(start, target, ends)
    values, _ = equations.evaluate(polished, np.ones(len(polished)))
    finite = np.all(np.isfinite(polished), axis=-1)
    assert np.max(np.abs(values[finite])) < 1e-10
    assert np.all(residuals[finite] < homotopy.END_RESIDUAL)
    assert np.all(conditions[finite] >= 1.0)


def test_count_distinct_matches_its_pairwise_definition():
    rng = np.random.default_rng(4)
    points = rng.normal(size=(12, 8)) + 1j * rng.normal(size=(12, 8))
    points[5] = points[2] * (1.0 + 1e-9)          # the same point, within 1e-6 relative
    points[7] = points[2] + 1e-3 * points[2]       # a different one
    points[9] = points[0]
    expected = sum(
        1 for k in range(12)
        if not any(np.linalg.norm(points[k] - points[j]) <= 1e-6 * np.linalg.norm(points[j])
                   for j in range(k)))
    assert homotopy.count_distinct(points) == expected == 10
    assert homotopy.count_distinct(points[:0]) == 0
