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
The motion felt at the head against the definition, and what is perceived of it, by hand.

A smooth analytic motion of the platform (sines in every pose coordinate); the reference is
``f = R^T (h'' + [0, 0, g])`` with ``h = p + R head`` and ``w = (R^T R')^v``, the derivatives
taken by central differences with a step of 1e-4 s on the analytic motion, the rotation from
the elementary matrices of test/reference.py. The package samples the motion every millisecond
and differences the samples: the two agree to the order of the sampling step squared.

What is perceived (the vestibular model, vehicle and platform alike) is checked against the
closed forms of the otoliths' and the canals' step responses, written out here.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import rotation_zyx

from stewart_kinematics.cueing.perception import (
    perceived_motion,
    perception,
    PerceptionEstimator,
    specific_force,
)

pytestmark = pytest.mark.core

G = 9.80665
HEAD = np.array([0.05, -0.02, 0.6])
HOME = np.array([0.0, 0.0, 0.4325, 0.0, 0.0, 0.0])
AMPLITUDES = np.array([0.08, 0.05, 0.02, math.radians(6.0), math.radians(4.0),
                       math.radians(10.0)])
FREQUENCIES = np.array([0.7, 1.1, 1.9, 0.5, 0.9, 0.3]) * 2.0 * math.pi


def pose(t):
    """Return the analytic motion: home plus a sine per coordinate."""
    return HOME + AMPLITUDES * np.sin(FREQUENCIES * t + np.arange(6))


def head(t):
    """Return the head's position in the base frame."""
    p = pose(t)
    return p[:3] + rotation_zyx(*p[3:]) @ HEAD


def reference(t, h=1e-4):
    """Specific force and body angular velocity by central differences of the analytic motion."""
    rotation = rotation_zyx(*pose(t)[3:])
    acceleration = (head(t + h) - 2.0 * head(t) + head(t - h)) / (h * h)
    force = rotation.T @ (acceleration + [0.0, 0.0, G])
    derivative = (rotation_zyx(*pose(t + h)[3:]) - rotation_zyx(*pose(t - h)[3:])) / (2.0 * h)
    skew = rotation.T @ derivative
    return force, np.array([skew[2, 1], skew[0, 2], skew[1, 0]])


def test_batch_perception_matches_the_definition():
    """perceived_motion over 4 s at 1 kHz against the reference at every inner sample."""
    times = np.arange(0.0, 4.0, 0.001)
    perceived = perceived_motion(times, np.array([pose(t) for t in times]), HEAD, G)
    for index in range(5, times.size - 5, 97):
        force, rate = reference(times[index])
        assert_allclose(perceived.specific_force[index], force, atol=2e-4)
        assert_allclose(perceived.angular_velocity[index], rate, atol=1e-5)


def test_uneven_steps_keep_second_order_accuracy():
    """Jittered steps (0.5 to 1.5 ms): the error grows with the steps' difference, still small."""
    rng = np.random.default_rng(5)
    times = np.cumsum(rng.uniform(0.0005, 0.0015, size=3000))
    perceived = perceived_motion(times, np.array([pose(t) for t in times]), HEAD, G)
    for index in range(5, times.size - 5, 101):
        force, rate = reference(times[index])
        assert_allclose(perceived.specific_force[index], force, atol=2e-2)
        assert_allclose(perceived.angular_velocity[index], rate, atol=1e-3)


def test_streaming_estimate_equals_the_batch():
    """Stream: the estimator returns the batch value of the previous sample, with its label."""
    times = np.arange(0.0, 0.5, 0.002)
    poses = np.array([pose(t) for t in times])
    batch = perceived_motion(times, poses, HEAD, G)
    estimator = PerceptionEstimator(HEAD, G)
    for index, (time, sample) in enumerate(zip(times, poses)):
        result = estimator.update(time, sample, label=f'sample {index}')
        if index < 2:
            assert result is None
            continue
        label, force = result
        assert label == f'sample {index - 1}'
        assert_allclose(force, batch.specific_force[index - 1], atol=1e-9)


def test_tilt_at_rest_is_felt_as_gravity():
    """A platform pitched nose-up by beta at rest feels f_x = -g sin(beta): tilt coordination."""
    beta = math.radians(-5.0)
    rotation = rotation_zyx(0.0, beta, 0.0)
    assert_allclose(specific_force(rotation, np.zeros(3), G),
                    [-G * math.sin(beta), 0.0, G * math.cos(beta)], atol=1e-15)
    times = np.arange(0.0, 0.1, 0.01)
    still = np.tile(np.r_[HOME[:3], 0.3, beta, -0.2], (times.size, 1))
    perceived = perceived_motion(times, still, HEAD, G)
    expected = rotation_zyx(0.3, beta, -0.2).T @ [0.0, 0.0, G]
    assert_allclose(perceived.specific_force, np.tile(expected, (times.size, 1)), atol=1e-9)
    assert_allclose(perceived.angular_velocity, 0.0, atol=1e-12)


@pytest.mark.parametrize('times, poses', [
    (np.arange(2.0), np.zeros((2, 6))), (np.arange(5.0), np.zeros((5, 5))),
    (np.array([0.0, 1.0, 1.0, 2.0]), np.zeros((4, 6)))])
def test_malformed_motion_is_refused(times, poses):
    """Too few samples, wrong shapes, repeated times: ValueError."""
    with pytest.raises(ValueError, match='times'):
        perceived_motion(times, poses, HEAD, G)


def otolith_step(t, size, gain=0.4, lead=13.2, long=5.33, short=0.66):
    """
    Return the otolith's response to a step of specific force of ``size`` at t = 0 (closed form).

    ``K (tau_a s + 1) / ((tau_L s + 1)(tau_S s + 1))`` times ``size / s``, by partial
    fractions: ``K size (1 + (tau_a - tau_L) / (tau_L - tau_S) e^(-t / tau_L) - (tau_a -
    tau_S) / (tau_L - tau_S) e^(-t / tau_S))`` for t >= 0.
    """
    t = np.asarray(t, dtype=float)
    value = gain * size * (1.0 + (lead - long) / (long - short) * np.exp(-t / long)
                           - (lead - short) / (long - short) * np.exp(-t / short))
    return np.where(t >= 0.0, value, 0.0)


def canal_step(t, size, long, short=0.1, adaptation=30.0):
    """
    Return the canals' response to a step of rate of ``size`` at t = 0 (closed form).

    ``tau_a tau_L s^2 / ((tau_a s + 1)(tau_L s + 1)(tau_S s + 1))`` times ``size / s`` is
    ``size / tau_S * s / ((s - p1)(s - p2)(s - p3))`` with ``p = -1 / tau``: the sum over the
    poles of ``p_i e^(p_i t) / prod_(j != i) (p_i - p_j)``.
    """
    t = np.asarray(t, dtype=float)
    poles = [-1.0 / adaptation, -1.0 / long, -1.0 / short]
    value = np.zeros_like(t)
    for i, pole in enumerate(poles):
        others = np.prod([pole - other for j, other in enumerate(poles) if j != i])
        value += pole * np.exp(pole * np.maximum(t, 0.0)) / others
    return np.where(t >= 0.0, size / short * value, 0.0)


def test_otolith_closed_form_is_the_models():
    """The closed form's start, slope and end: 0, K tau_a / (tau_L tau_S) per second, K."""
    assert otolith_step(0.0, 1.0) == pytest.approx(0.0, abs=1e-15)
    slope = 0.4 * 13.2 / (5.33 * 0.66)
    assert otolith_step(1e-7, 1.0) / 1e-7 == pytest.approx(slope, rel=1e-5)
    assert otolith_step(1e4, 1.0) == pytest.approx(0.4)
    # The peak, by hand: the derivative vanishes where e^(t (1/tau_S - 1/tau_L)) =
    # (tau_a - tau_S) tau_L / ((tau_a - tau_L) tau_S) = 12.868, at t = 1.9245 s, where the
    # response is 0.4 (1 + 1.68522 * 0.69693 - 2.68522 * 0.05416) = 0.8116.
    times = np.linspace(0.0, 30.0, 300001)
    assert np.max(otolith_step(times, 1.0)) == pytest.approx(0.8116, abs=1e-4)
    assert times[np.argmax(otolith_step(times, 1.0))] == pytest.approx(1.9245, abs=1e-3)


def test_perception_of_a_vehicle_step_is_the_otoliths_step_response():
    """
    The vehicle steps to 2 m/s^2 forward and 1 m/s^2 up at 2 s, and to 0.2 rad/s of yaw.

    Each sample is held over the interval that ends with it, so the continuous step starts one
    step before the sample that carries it; the discretisation is exact: the perceived force
    follows the closed form to 1e-9, and the raw series (gravity removed) stay beside it.
    """
    step = 0.01
    times = np.arange(0.0, 30.0, step)
    force = np.tile([0.0, 0.0, G], (times.size, 1))
    rates = np.zeros((times.size, 3))
    on = times >= 2.0
    force[on, 0] += 2.0
    force[on, 2] += 1.0
    rates[on, 2] = 0.2
    seen = perception(times, force, rates, G)
    since = times - (times[np.argmax(on)] - step)
    assert_allclose(seen.perceived_force[:, 0], otolith_step(since, 2.0), atol=1e-9)
    assert_allclose(seen.perceived_force[:, 1], 0.0, atol=1e-15)
    assert_allclose(seen.perceived_force[:, 2], otolith_step(since, 1.0), atol=1e-9)
    assert_allclose(seen.perceived_rate[:, 2], canal_step(since, 0.2, long=10.2), atol=1e-9)
    assert_allclose(seen.perceived_rate[:, :2], 0.0, atol=1e-15)
    # Hand values: 0.8116 of the step at its peak (1.92 s on), 0.4 of it at the end.
    assert np.max(seen.perceived_force[:, 0]) == pytest.approx(2.0 * 0.8116, abs=2e-4)
    assert seen.perceived_force[-1, 0] == pytest.approx(0.8, abs=0.05)
    assert_allclose(seen.raw[:, :3], force - [0.0, 0.0, G], atol=0)
    assert_allclose(seen.raw[:, 3:], rates, atol=0)
    assert_allclose(seen.perceived[:, 3:], seen.perceived_rate, atol=0)
    assert_allclose(seen.thresholds, [0.17, 0.17, 0.28, math.radians(3.0), math.radians(3.6),
                                      math.radians(2.6)], rtol=1e-12)


def test_perception_at_rest_is_nothing():
    """A vehicle at rest (gravity only): nothing perceived, below every threshold."""
    times = np.arange(0.0, 5.0, 0.01)
    seen = perception(times, np.tile([0.0, 0.0, G], (times.size, 1)),
                      np.zeros((times.size, 3)), G)
    assert_allclose(seen.perceived, 0.0, atol=0)


@pytest.mark.parametrize('value', [math.nan, math.inf, 1e308 * 10])
def test_perception_refuses_non_finite_motion(value):
    """A non-finite sample: ValueError naming what must be finite."""
    times = np.arange(0.0, 1.0, 0.1)
    force = np.tile([0.0, 0.0, G], (times.size, 1))
    force[4, 1] = value
    with pytest.raises(ValueError, match='finite'):
        perception(times, force, np.zeros((times.size, 3)), G)
