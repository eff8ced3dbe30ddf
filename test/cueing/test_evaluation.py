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
The scenarios, the measures of a cue, and the issue's numbers on the four scenarios.

The measures are checked on series whose answer is known (a shifted sine, a constructed false
cue, leg lengths with one fast step); the numbers are those the documentation's table reports,
with the shipped motion_cueing.yaml on the paper's platform and the example limits.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from stewart_kinematics import ActuatorLimits, travel_ranges
from stewart_kinematics.cueing import evaluate, MotionCueing, replay
from stewart_kinematics.cueing.evaluation import delay, pearson, rest_time
from stewart_kinematics.cueing.limit_margins import leg_speed_violations
from stewart_kinematics.cueing.scenarios import (
    all_scenarios,
    MULTI_SINE_FREQUENCIES,
    scenario,
    SCENARIO_NAMES,
)

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml')]
G = 9.80665


def test_pearson_matches_numpy():
    """The correlation is numpy's corrcoef; NaN for a constant series."""
    rng = np.random.default_rng(2)
    a, b = rng.normal(size=500), rng.normal(size=500)
    b += 0.5 * a
    assert pearson(a, b) == pytest.approx(np.corrcoef(a, b)[0, 1], abs=1e-12)
    assert math.isnan(pearson(a, np.ones(500)))


@pytest.mark.parametrize('shift', [0.03, -0.02, 0.0, 0.1234])
def test_delay_recovers_a_known_shift(shift):
    """A multi-sine and the same shifted by ``shift`` seconds: the delay is ``shift``."""
    times = np.arange(0.0, 30.0, 0.01)

    def signal(t):
        return sum(np.sin(2.0 * math.pi * f * t + k) for k, f in enumerate((0.5, 1.0, 2.0)))
    assert delay(times, signal(times), signal(times - shift)) == pytest.approx(shift, abs=1e-3)


def test_delay_beyond_the_window_is_infinite():
    """Shifted by more than the window: no delay within it explains them."""
    times = np.arange(0.0, 30.0, 0.01)
    ramp = np.sin(2.0 * math.pi * 0.05 * times)
    assert delay(times, ramp, np.sin(2.0 * math.pi * 0.05 * (times - 2.0)),
                 max_delay=0.5) == math.inf


def test_rest_time_finds_the_last_motion():
    """The input rests from the sample after its last one away from rest."""
    times = np.arange(10) * 0.1
    force = np.tile([0.0, 0.0, G], (10, 1))
    rates = np.zeros((10, 3))
    force[3, 0] = 1.0
    rates[6, 2] = 0.1
    assert rest_time(times, force, rates) == pytest.approx(0.7)
    rates[9, 2] = 0.1
    assert rest_time(times, force, rates) is None


def test_leg_speed_violations_count_constructed_steps():
    """One leg jumps 1 mm in 10 ms: 0.1 m/s, over 0.05; its acceleration over 0.25 twice."""
    times = np.arange(6) * 0.01
    lengths = np.full((6, 6), 0.7)
    lengths[3:, 2] += 0.001
    counts = leg_speed_violations(times, lengths, ActuatorLimits(0.05, 0.25))
    assert counts['velocity'] == 1 and counts['acceleration'] == 2
    assert counts['velocity_peak'] == pytest.approx(0.1)


def test_false_cues_and_travel_are_measured():
    """A replay whose felt force opposes the input for 1 s: 1 s of false cue on x."""
    from stewart_kinematics import load_geometry
    geometry = load_geometry(FILES[:2])
    times = np.arange(0.0, 5.0, 0.01)
    force = np.tile([0.0, 0.0, G], (times.size, 1))
    force[(times >= 1.0) & (times < 3.0), 0] = 1.0
    cueing = MotionCueing(geometry)
    played = replay(cueing, times, force, np.zeros((times.size, 3)))
    felt = played.perceived.specific_force.copy()
    felt[:, 0] = np.where((times >= 2.0) & (times < 3.0), -0.5, 0.0)
    fake = type(played.perceived)(times, felt, played.perceived.angular_velocity)
    doctored = played.__class__(**{**played.__dict__, 'perceived': fake})
    measured = evaluate(doctored, geometry, ActuatorLimits(0.05, 0.25), math.radians(3.0),
                        travel=travel_ranges(geometry).as_array())
    assert measured.axes[0].false_cues == 100
    assert measured.axes[0].false_cue_time == pytest.approx(1.0, abs=0.011)
    assert len(measured.travel_used) == 6 and max(measured.travel_used) > 0.0


def test_scenarios_start_and_end_at_rest():
    """Four scenarios, sampled at the rate asked, at rest at the start and after rest_time."""
    for generated in all_scenarios(rate=50.0):
        times = generated.times
        assert generated.name in SCENARIO_NAMES
        assert np.allclose(np.diff(times), 0.02)
        assert generated.specific_force.shape == generated.angular_velocity.shape == (
            times.size, 3)
        resting = times >= generated.rest_time
        assert times[-1] >= generated.rest_time + 10.0
        assert np.all(generated.specific_force[resting] == [0.0, 0.0, G])
        np.testing.assert_allclose(generated.angular_velocity[resting], 0.0, atol=0)
        np.testing.assert_allclose(generated.specific_force[0], [0.0, 0.0, G], atol=1e-12)


def test_multi_sine_holds_its_three_frequencies():
    """The multi-sine's spectrum peaks at 0.5, 1 and 2 Hz, on both axes."""
    generated = scenario('multi_sine', rate=100.0)
    for axis in (0, 1):
        spectrum = np.abs(np.fft.rfft(generated.specific_force[:, axis]))
        frequencies = np.fft.rfftfreq(generated.times.size, 0.01)
        peaks = frequencies[np.argsort(spectrum)[-3:]]
        assert sorted(np.round(peaks, 1)) == list(MULTI_SINE_FREQUENCIES)


@pytest.mark.parametrize('name, rate', [('drift', 100.0), ('slalom', 0.0),
                                        ('lap', math.nan)])
def test_unknown_scenarios_and_bad_rates_are_refused(name, rate):
    """An unknown name or a rate that is not positive: ValueError."""
    with pytest.raises(ValueError, match='scenario|rate'):
        scenario(name, rate)


@pytest.fixture(scope='module')
def results(shipped_cueing_report):
    """
    Return the evaluations of the four scenarios on the shipped configuration.

    The replay of the four is the core tier's longest computation: conftest's
    ``shipped_cueing_report`` runs it once a session, as ``stewart_cueing`` does (the core's
    ``replay`` and ``evaluate`` on the shipped files), and its evaluations are judged here.
    """
    assert list(shipped_cueing_report.evaluations) == list(SCENARIO_NAMES)
    return shipped_cueing_report.evaluations


@pytest.mark.parametrize('name', SCENARIO_NAMES)
def test_every_scenario_keeps_the_limits_and_returns_to_neutral(results, name):
    """Zero limit violations, tilt rate within 3 deg/s, 1 mm and 0.1 deg 10 s after rest."""
    measured = results[name]
    assert measured.limit_violations == 0
    assert measured.tilt_rate_violations == 0
    assert measured.tilt_rate_peak <= math.radians(3.0) * (1.0 + 1e-9)
    assert measured.residual_position <= 1e-3
    assert measured.residual_angle <= math.radians(0.1)
    assert 'limits_held' not in measured.warnings


def test_multi_sine_is_felt_as_given(results):
    """Correlation >= 0.8 and delay within 50 ms, longitudinal and lateral."""
    for axis in results['multi_sine'].axes[:2]:
        assert axis.correlation >= 0.8, axis
        assert abs(axis.delay) <= 0.05, axis
