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
The perception model against closed forms and scipy.signal's simulation of the published forms.

The oracle builds each transfer function from the published time constants in their own form
(``K (tau_a s + 1) / ((tau_L s + 1)(tau_S s + 1))``, not the monic one the package uses) and
simulates it with scipy.signal; the otolith's step response is also checked against its partial
fractions worked by hand.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
from scipy import signal

from stewart_kinematics.cueing.vestibular import (
    CANALS,
    OTOLITHS,
    perceive,
    perception_thresholds,
    vestibular_bank,
)

pytestmark = pytest.mark.core

G = 9.80665
TIMES = np.arange(0.0, 30.0, 0.01)


def test_the_published_parameters():
    assert (OTOLITHS.gain, OTOLITHS.lead_time_constant, OTOLITHS.long_time_constant,
            OTOLITHS.short_time_constant) == (0.4, 13.2, 5.33, 0.66)
    assert CANALS.long_time_constants == (6.1, 5.3, 10.2)
    assert (CANALS.short_time_constant, CANALS.adaptation_time_constant) == (0.1, 30.0)
    assert_allclose(perception_thresholds(),
                    [0.17, 0.17, 0.28, *np.radians([3.0, 3.6, 2.6])], rtol=0, atol=1e-15)


def test_an_otolith_step_is_its_partial_fractions():
    k, ta, tl, ts = 0.4, 13.2, 5.33, 0.66
    force = np.zeros((TIMES.size, 3))
    force[:, 0] = 2.0  # a 2 m/s^2 forward step from t = 0
    force[:, 2] = G
    perceived, rates = perceive(TIMES, force, np.zeros((TIMES.size, 3)))
    expected = 2.0 * k * (1.0 + (ta - tl) / (tl - ts) * np.exp(-TIMES / tl)
                          + (ta - ts) / (ts - tl) * np.exp(-TIMES / ts))
    assert_allclose(perceived[:, 0], expected, rtol=0, atol=1e-12)
    assert_allclose(perceived[:, 1:], 0.0, atol=1e-15)
    assert_allclose(rates, 0.0, atol=1e-15)
    # The tilt-translation ambiguity: a sustained force is felt at 0.4 of it.
    assert perceived[-1, 0] == pytest.approx(0.8, abs=0.01)


@pytest.mark.parametrize('axis', [0, 1, 2])
def test_canals_against_scipy(axis):
    ta, tl, ts = 30.0, CANALS.long_time_constants[axis], 0.1
    rate = np.zeros((TIMES.size, 3))
    rate[:, axis] = 0.2 * np.sin(1.3 * TIMES) + 0.1 * (TIMES > 2.0)
    rest = np.tile([0.0, 0.0, G], (TIMES.size, 1))
    _, perceived = perceive(TIMES, rest, rate)
    published = signal.lti([ta * tl, 0.0, 0.0],
                           np.polymul(np.polymul([ta, 1.0], [tl, 1.0]), [ts, 1.0]))
    # The package holds each sample over the interval ending with it: feed scipy that signal.
    held = np.r_[rate[1:, axis], rate[-1, axis]]
    _, oracle, _ = signal.lsim(published, held, TIMES, interp=False)
    assert_allclose(perceived[:, axis], oracle, rtol=0, atol=1e-9)
    others = [index for index in range(3) if index != axis]
    assert_allclose(perceived[:, others], 0.0, atol=1e-15)


def test_otoliths_against_scipy_on_a_sine():
    force = np.tile([0.0, 0.0, G], (TIMES.size, 1))
    force[:, 1] += 0.5 * np.sin(2.0 * TIMES)
    force[:, 2] += 0.3 * np.sin(0.7 * TIMES)
    perceived, _ = perceive(TIMES, force, np.zeros((TIMES.size, 3)))
    published = signal.lti([0.4 * 13.2, 0.4], np.polymul([5.33, 1.0], [0.66, 1.0]))
    for axis in (1, 2):
        held = np.r_[force[1:, axis], force[-1, axis]] - (G if axis == 2 else 0.0)
        _, oracle, _ = signal.lsim(published, held, TIMES, interp=False)
        assert_allclose(perceived[:, axis], oracle, rtol=0, atol=1e-9)


def test_frequency_responses_against_hand_values():
    bank = vestibular_bank()
    # Frequency response c (jw - a)^-1 b + d of each channel.
    # Hand values: |K (1 + j w tau_a) / ((1 + j w tau_L)(1 + j w tau_S))| at 0.5 and 0.1 rad/s;
    # the canal's about roll at 1 rad/s.
    for channel, frequency, gain in ((0, 0.5, 0.4 * math.hypot(1, 6.6) / math.hypot(1, 2.665)
                                      / math.hypot(1, 0.33)),
                                     (2, 0.1, 0.4 * math.hypot(1, 1.32) / math.hypot(1, 0.533)
                                      / math.hypot(1, 0.066)),
                                     (3, 1.0, 30 * 6.1 / math.hypot(1, 30) / math.hypot(1, 6.1)
                                      / math.hypot(1, 0.1))):
        response = bank.c[channel] @ np.linalg.solve(
            1j * frequency * np.eye(bank.order) - bank.a, bank.b[:, channel]) \
            + bank.d[channel, channel]
        assert abs(response) == pytest.approx(gain, rel=1e-12)
    assert bank.order == 15


@pytest.mark.parametrize('times, force, rate', [
    (np.arange(3.0), np.zeros((3, 3)), np.zeros((2, 3))),
    (np.arange(3.0), np.zeros(3), np.zeros((3, 3))),
    (np.array([0.0, 1.0, 1.0]), np.zeros((3, 3)), np.zeros((3, 3))),
    (np.array([0.0, math.nan, 2.0]), np.zeros((3, 3)), np.zeros((3, 3))),
    (np.arange(3.0), np.full((3, 3), math.inf), np.zeros((3, 3))),
    (np.arange(3.0), np.zeros((3, 3)), np.full((3, 3), math.nan)),
])
def test_bad_series_are_refused_clearly(times, force, rate):
    with pytest.raises(ValueError, match='times|finite'):
        perceive(times, force, rate)
