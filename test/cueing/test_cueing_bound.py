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
The clairvoyant bound's machinery on cases with a known answer (about 2 s in all).

The references are the evaluator's own perception (:func:`.vestibular.perceive`) of forces
built here; the answers are worked independently: a force the platform can give exactly is
rendered with no error, a platform that may not move leaves the whole reference as error, a
sustained force beyond the tilt limit leaves at least the clipped part (and no more than the
clipped constant's error), and relaxing a limit never raises the bound.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics.cueing.cueing_bound import axis_bound, AxisLimits, otolith_matrix
from stewart_kinematics.cueing.vestibular import perceive

pytestmark = pytest.mark.core

G = 9.80665
RATE = 10.0
STEP = 0.1


def perceived_x(times, force_x):
    """Return the evaluator's perceived force along x of a force along x, (N,)."""
    forces = np.zeros((times.size, 3))
    forces[:, 0] = force_x
    forces[:, 2] = G
    return perceive(times, forces, np.zeros((times.size, 3)))[0][:, 0]


def ramped_step(times, level, start=2.0, ramp=2.0):
    """Return a force rising linearly from 0 at ``start`` to ``level`` over ``ramp`` s."""
    return level * np.clip((times - start) / ramp, 0.0, 1.0)


TIMES = np.arange(0.0, 20.0, 1.0 / RATE)
WIDE = AxisLimits(tilt=math.radians(10.0), tilt_rate=math.radians(3.0), position=0.4,
                  velocity=0.4, acceleration=3.0)


def test_otolith_matrix_is_the_evaluators_filter():
    force = np.sin(0.7 * TIMES[1:]) + (TIMES[1:] > 5.0)
    matrix = otolith_matrix(STEP, TIMES.size - 1)
    assert_allclose(matrix @ force, perceived_x(TIMES, np.r_[0.0, force])[1:], atol=1e-9)


def test_a_force_within_the_limits_is_rendered_without_error():
    # 1 m/s^2 sustained: 5.9 deg of tilt, reached at 3 deg/s in 2 s; the ramp takes 2 s.
    reference = perceived_x(TIMES, ramped_step(TIMES, 1.0))
    bound = axis_bound(TIMES, reference, WIDE, STEP)
    assert bound.status == 1
    assert bound.rmse < 1e-3
    assert bound.fine_rmse < 2e-2
    assert_allclose(bound.gravity_term[-1], 1.0, atol=1e-2)   # held by tilt, not translation


def test_a_platform_that_may_not_move_leaves_the_whole_reference():
    reference = perceived_x(TIMES, ramped_step(TIMES, 3.0))
    still = AxisLimits(tilt=0.0, tilt_rate=0.0, position=0.0, velocity=0.0, acceleration=0.0)
    bound = axis_bound(TIMES, reference, still, STEP)
    expected = math.sqrt(np.mean(reference[1:] ** 2))
    assert_allclose(bound.rmse, expected, rtol=1e-6)
    assert_allclose(bound.force, 0.0, atol=1e-9)


def test_a_force_beyond_the_tilt_limit_leaves_the_clipped_part():
    # 5 m/s^2 sustained, tilt alone (no travel), tilt as fast as wanted: g sin(10 deg) = 1.70.
    reference = perceived_x(TIMES, ramped_step(TIMES, 5.0, ramp=0.1))
    tilt_only = AxisLimits(tilt=math.radians(10.0), tilt_rate=math.inf, position=0.0,
                           velocity=0.0, acceleration=0.0)
    bound = axis_bound(TIMES, reference, tilt_only, STEP)
    cap = G * math.sin(math.radians(10.0))
    clipped = perceived_x(TIMES, np.minimum(ramped_step(TIMES, 5.0, ramp=0.1), cap))
    clipped_rmse = math.sqrt(np.mean((clipped - reference)[1:] ** 2))
    assert np.max(np.abs(bound.gravity_term)) <= cap * (1.0 + 1e-9)
    # No better than the clipped constant by more than the otolith's slow undershoot allows,
    # and never worse than it (it is feasible).
    assert bound.rmse <= clipped_rmse * (1.0 + 1e-6)
    assert bound.rmse >= 0.9 * clipped_rmse


def test_relaxing_a_limit_never_raises_the_bound():
    reference = perceived_x(TIMES, ramped_step(TIMES, 4.0, ramp=0.5)
                            - ramped_step(TIMES, 4.0, start=8.0, ramp=0.5))
    tight = axis_bound(TIMES, reference, AxisLimits(math.radians(5.0), math.radians(2.0), 0.05,
                                                    0.05, 0.5), STEP).rmse
    looser = axis_bound(TIMES, reference, AxisLimits(math.radians(10.0), math.radians(3.0),
                                                     0.05, 0.05, 0.5), STEP).rmse
    loosest = axis_bound(TIMES, reference, WIDE, STEP).rmse
    assert tight > looser > loosest > 0.0


@pytest.mark.parametrize('step, reference, limits, message', [
    (0.15, None, WIDE, 'whole multiple'),
    (math.nan, None, WIDE, 'whole multiple'),
    (0.0, None, WIDE, 'whole multiple'),
    (STEP, 'nan', WIDE, 'finite'),
    (STEP, 'short', WIDE, 'N >= 3'),
    (STEP, None, AxisLimits(math.nan, 0.1, 0.1), 'limits must be'),
    (STEP, None, AxisLimits(0.1, -1.0, 0.1), 'limits must be'),
])
def test_bad_input_is_refused_with_the_value(step, reference, limits, message):
    times, values = TIMES, np.zeros(TIMES.size)
    if reference == 'nan':
        values = values.copy()
        values[3] = math.nan
    elif reference == 'short':
        times, values = TIMES[:2], values[:2]
    with pytest.raises(ValueError, match=message):
        axis_bound(times, values, limits, step)
