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
The measures of a cue, and the issue's numbers on the four first scenarios.

The measures are checked on series whose answer is known (a shifted sine, constructed false
cues of each kind, a perfect cue, leg lengths with one fast step, poses with known rates); the
numbers are those the documentation's table reports, with the shipped motion_cueing.yaml on the
paper's platform and the example limits (test/cueing/test_cueing_scenarios.py checks the
scenarios' shapes).
"""

import math
from pathlib import Path

import numpy as np
import pytest

from stewart_kinematics import ActuatorLimits, travel_ranges
from stewart_kinematics.cueing import evaluate, MotionCueing, replay
from stewart_kinematics.cueing.evaluation import (
    cross_correlation_peak,
    delay,
    false_cues,
    GENERIC_TARGETS,
    judge,
    MAX_DELAY,
    pearson,
    rest_time,
    STRICT_TARGETS,
    time_over,
)
from stewart_kinematics.cueing.limit_margins import leg_speed_violations
from stewart_kinematics.cueing.perception import body_rates
from stewart_kinematics.cueing.scenarios import (
    all_scenarios,
    MULTI_SINE_FREQUENCIES,
    scenario,
    SCENARIO_NAMES,
)
from stewart_kinematics.cueing.vestibular import perceive

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml')]
G = 9.80665
#: The scenarios the session's shipped report runs (conftest): the first four.
REPORTED = ('acceleration_braking', 'slalom', 'multi_sine', 'lap')


def test_pearson_matches_numpy():
    """The correlation is numpy's corrcoef; NaN for a constant series."""
    rng = np.random.default_rng(2)
    a, b = rng.normal(size=500), rng.normal(size=500)
    b += 0.5 * a
    assert pearson(a, b) == pytest.approx(np.corrcoef(a, b)[0, 1], abs=1e-12)
    assert math.isnan(pearson(a, np.ones(500)))


def test_a_series_constant_to_rounding_has_no_correlation_or_delay():
    """
    1e-16 of rounding (what a turn by 180 deg leaves on the other axes) is no motion.

    Before, its correlation with itself, and with any like it, came out near 1: a table showed
    r 1.00 for an axis nothing moved along. A small real signal (1e-6) still correlates.
    """
    rng = np.random.default_rng(3)
    times = np.arange(0.0, 10.0, 0.01)
    signal = np.sin(times)
    noise = 1e-16 * rng.normal(size=times.size)
    assert math.isnan(pearson(noise, noise)) and math.isnan(pearson(signal, noise))
    assert all(math.isnan(value) for value in cross_correlation_peak(times, noise, noise))
    assert math.isnan(pearson(G + 1e-15 * signal, signal))   # gravity and its last bits
    small = 1e-6 * signal
    assert pearson(small, signal) == pytest.approx(1.0, abs=1e-12)
    assert cross_correlation_peak(times, small, signal)[0] == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize('shift', [0.03, -0.02, 0.0, 0.1234])
def test_delay_recovers_a_known_shift(shift):
    """A multi-sine and the same shifted by ``shift`` seconds: the delay is ``shift``."""
    times = np.arange(0.0, 30.0, 0.01)

    def signal(t):
        return sum(np.sin(2.0 * math.pi * f * t + k) for k, f in enumerate((0.5, 1.0, 2.0)))
    assert delay(times, signal(times), signal(times - shift)) == pytest.approx(shift, abs=1e-3)


def aperiodic(t):
    """Return a sum of sines of incommensurate frequencies: no period within 30 s."""
    return sum(np.sin(2.0 * math.pi * f * t + k) for k, f in enumerate((0.13, 0.37, 0.71)))


@pytest.mark.parametrize('shift', [1.5, -1.5])
def test_delay_is_searched_within_two_seconds(shift):
    """
    Shifted by 1.5 s either way: found (beyond the old 0.5 s window), peak close to 1.

    Within half a sample (5 ms): over a finite window the overlap shrinks with the lag, which
    tilts the peak of a slow signal by a few milliseconds.
    """
    times = np.arange(0.0, 40.0, 0.01)
    found, peak = cross_correlation_peak(times, aperiodic(times), aperiodic(times - shift))
    assert MAX_DELAY == 2.0
    assert found == pytest.approx(shift, abs=5e-3)
    assert 0.8 < peak <= 1.0 + 1e-9
    assert delay(times, aperiodic(times), 0.3 * aperiodic(times - shift)) == pytest.approx(
        shift, abs=5e-3)
    # The old window (0.5 s) could not see it: it finds a side lobe, or none.
    old = delay(times, aperiodic(times), aperiodic(times - shift), max_delay=0.5)
    assert not abs(old - shift) < 0.5


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


def test_false_cues_of_each_kind_are_counted_on_constructed_signals():
    """
    Wrong sign, felt at rest, and nothing for a perfect cue, on signals built to have them.

    The vehicle is perceived at 1 m/s^2 from 1 to 3 s; the platform at -0.5 from 2 to 3 s
    (1 s of wrong sign), at 0.5 from 4 to 5 s with the vehicle at rest (1 s felt at rest), and
    at -0.1 from 6 to 7 s (below the 0.17 threshold: not felt, no false cue).
    """
    times = np.arange(0.0, 8.0, 0.01)
    vehicle = np.where((times >= 1.0) & (times < 3.0), 1.0, 0.0)
    platform = np.zeros_like(times)
    platform[(times >= 2.0) & (times < 3.0)] = -0.5
    platform[(times >= 4.0) & (times < 5.0)] = 0.5
    platform[(times >= 6.0) & (times < 7.0)] = -0.1
    wrong, at_rest = false_cues(times, vehicle, platform, 0.17)
    assert wrong == pytest.approx(1.0, abs=0.011)
    assert at_rest == pytest.approx(1.0, abs=0.011)
    # A perfect cue (the vehicle's, scaled): none of either.
    assert false_cues(times, vehicle, 0.4 * vehicle, 0.17) == (0.0, 0.0)
    # The vehicle below its threshold counts as rest even with a sign.
    assert false_cues(times, np.full(times.size, 0.1), np.full(times.size, -0.5),
                      0.17) == (0.0, pytest.approx(times[-1]))


def test_a_perfect_cue_has_no_false_cue_and_full_correlation():
    """A replay whose felt motion is the input: correlation 1, delay 0, no false cue."""
    from stewart_kinematics import load_geometry
    geometry = load_geometry(FILES[:2])
    times = np.arange(0.0, 6.0, 0.01)
    force = np.tile([0.0, 0.0, G], (times.size, 1))
    force[:, 0] += 1.5 * np.sin(2.0 * math.pi * 0.4 * times) * (times < 5.0)
    rates = np.zeros((times.size, 3))
    rates[:, 2] = 0.2 * np.sin(2.0 * math.pi * 0.3 * times) * (times < 5.0)
    played = replay(MotionCueing(geometry), times, force, rates)
    perfect = type(played.perceived)(times, force, rates)
    measured = evaluate(played.__class__(**{**played.__dict__, 'perceived': perfect}),
                        geometry, ActuatorLimits(0.05, 0.25), math.radians(3.0))
    for axis in ('x', 'yaw'):
        measures = measured.measures(axis)
        assert measures.correlation == pytest.approx(1.0, abs=1e-12)
        assert measures.raw_correlation == pytest.approx(1.0, abs=1e-12)
        assert measures.delay == pytest.approx(0.0, abs=1e-6)
        assert measures.rmse == pytest.approx(0.0, abs=1e-12)
        assert measures.peak == pytest.approx(measures.vehicle_peak)
    for measures in measured.axes + measured.rotations:
        assert measures.false_cue_time == 0.0
    # The felt yaw rate reaches 11.5 deg/s: beyond 3 deg/s about a third of the time.
    assert measured.platform_rate_peak[2] == pytest.approx(0.2, abs=1e-3)
    assert measured.platform_rate_time_over[2] == pytest.approx(
        time_over(times, rates[:, 2], math.radians(3.0)))
    with pytest.raises(ValueError, match='unknown axis'):
        measured.measures('w')


@pytest.mark.parametrize('argument, fragment', [
    ('times', 'times'), ('specific_force', 'specific_force'),
    ('angular_velocity', 'angular_velocity')])
def test_a_replay_of_words_is_refused_naming_the_argument(argument, fragment):
    """Strings where numbers belong: ValueError naming the argument, no numpy message."""
    from stewart_kinematics import load_geometry
    times = np.arange(0.0, 0.05, 0.01)
    inputs = {'times': times, 'specific_force': np.tile([0.0, 0.0, G], (times.size, 1)),
              'angular_velocity': np.zeros((times.size, 3))}
    inputs[argument] = np.array(inputs[argument]).astype(str).tolist()
    with pytest.raises(ValueError, match=fragment) as raised:
        replay(MotionCueing(load_geometry(FILES[:2])), **inputs)
    assert 'could not convert' not in str(raised.value)


def test_false_cues_and_travel_are_measured_on_a_replay():
    """
    A replay whose felt force opposes the input for 1 s, then is felt sideways at rest for 1 s.

    evaluate() perceives the input and the felt force alike through the otoliths and counts
    the false cues on the perceived series.
    """
    from stewart_kinematics import load_geometry
    geometry = load_geometry(FILES[:2])
    times = np.arange(0.0, 8.0, 0.01)
    force = np.tile([0.0, 0.0, G], (times.size, 1))
    force[(times >= 1.0) & (times < 3.0), 0] = 1.0
    cueing = MotionCueing(geometry)
    played = replay(cueing, times, force, np.zeros((times.size, 3)))
    felt = played.perceived.specific_force.copy()
    felt[:, 0] = np.where((times >= 2.0) & (times < 3.0), -2.0, 0.0)
    felt[(times >= 6.0) & (times < 7.0), 1] = 2.0
    fake = type(played.perceived)(times, felt, played.perceived.angular_velocity)
    doctored = played.__class__(**{**played.__dict__, 'perceived': fake})
    measured = evaluate(doctored, geometry, ActuatorLimits(0.05, 0.25), math.radians(3.0),
                        travel=travel_ranges(geometry).as_array())
    x, y = measured.axes[:2]
    # Both through the otoliths (vestibular.perceive, called here on its own), then counted.
    wanted, _ = perceive(times, force, np.zeros((times.size, 3)))
    given, _ = perceive(times, felt, np.zeros((times.size, 3)))
    counted = false_cues(times, wanted[:, 0], given[:, 0], 0.17)
    assert (x.wrong_sign_time, x.felt_at_rest_time) == counted
    assert x.wrong_sign_time > 0.7 and y.wrong_sign_time == 0.0
    assert y.felt_at_rest_time > 0.7
    assert x.raw_correlation < 0.0 and x.correlation < 0.0
    assert x.threshold == 0.17 and measured.axes[2].threshold == 0.28
    assert measured.rotations[0].threshold == pytest.approx(math.radians(3.0))
    assert len(measured.travel_used) == 6 and max(measured.travel_used) > 0.0


def test_platform_rates_from_poses_with_known_rates():
    """
    Poses turning with sines in roll, pitch and yaw: the body rates of ZYX angles, closed form.

    ``w = [a' - g' sin b, b' cos a + g' cos b sin a, -b' sin a + g' cos b cos a]`` for
    ``R = Rz(g) Ry(b) Rx(a)``; the centred differences agree to the step squared.
    """
    times = np.arange(0.0, 4.0, 0.001)
    amplitude, omega = np.radians([6.0, 4.0, 10.0]), 2.0 * math.pi * np.array([0.5, 0.9, 0.3])
    angles = amplitude * np.sin(np.outer(times, omega))
    rates = amplitude * omega * np.cos(np.outer(times, omega))
    poses = np.column_stack([np.zeros((times.size, 2)), np.full(times.size, 0.43), angles])
    a, b = angles[:, 0], angles[:, 1]
    da, db, dg = rates.T
    expected = np.column_stack([da - dg * np.sin(b), db * np.cos(a) + dg * np.cos(b) * np.sin(a),
                                -db * np.sin(a) + dg * np.cos(b) * np.cos(a)])
    measured = body_rates(times, poses)
    np.testing.assert_allclose(measured[1:-1], expected[1:-1], atol=2e-5)
    # A constant roll rate of 6 deg/s for 2 s: over 3 deg/s for those 2 s.
    steady = np.zeros((3001, 6))
    clock = np.arange(3001) * 0.001
    steady[:, 3] = np.radians(6.0) * np.clip(clock - 0.5, 0.0, 2.0)
    rolled = body_rates(clock, steady)
    assert time_over(clock, rolled[:, 0], math.radians(3.0)) == pytest.approx(2.0, abs=2e-3)
    with pytest.raises(ValueError, match='times'):
        body_rates(clock[:2], steady[:2])


def test_scenarios_start_and_end_at_rest():
    """Nine scenarios, sampled at the rate asked, at rest at the start and after rest_time."""
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
    Return the evaluations of the first four scenarios on the shipped configuration.

    The replay of the four is the core tier's longest computation: conftest's
    ``shipped_cueing_report`` runs it once a session, as ``stewart_cueing`` does (the core's
    ``replay`` and ``evaluate`` on the shipped files), and its evaluations are judged here.
    """
    assert list(shipped_cueing_report.evaluations) == list(REPORTED)
    return shipped_cueing_report.evaluations


@pytest.mark.parametrize('name', REPORTED)
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
    """
    Correlation >= 0.8 perceived and raw, delay within 50 ms raw, longitudinal and lateral.

    Perceived, the felt force leads by 67 and 59 ms (the high-pass's phase lead, weighted by
    the otoliths): the strict target of 50 ms is missed, and judge() says so.
    """
    measured = results['multi_sine']
    for axis in measured.axes[:2]:
        assert axis.correlation >= 0.8, axis
        assert axis.raw_correlation >= 0.8, axis
        assert abs(axis.raw_delay) <= 0.05, axis
        assert -0.08 < axis.delay < -0.05, axis
    missed = [target for target, ok, _ in judge('multi_sine', measured) if not ok]
    assert missed == ['perceived delay <= 50 ms (x)', 'perceived delay <= 50 ms (y)']


def test_slalom_in_anti_phase_misses_its_targets(results):
    """
    The slalom is felt in anti-phase: perceived correlation about -0.6, seconds of wrong sign.

    The strict targets say so (correlation, false cues, perceived tilt rate), so
    ``stewart_cueing --strict`` fails on it (test/tools/test_cueing_report.py).
    """
    measured = results['slalom']
    y = measured.measures('y')
    assert y.correlation < -0.5 and y.raw_correlation < -0.5
    assert y.wrong_sign_time > 3.0
    verdict = {target: ok for target, ok, _ in judge('slalom', measured)}
    assert verdict['perceived correlation >= 0.6 (y)'] is False
    assert verdict['wrong-sign cue <= 1 s on every axis'] is False
    assert verdict['zero limit violations'] is True


def test_the_lap_reports_the_platform_rates_not_the_tilt_channel(results):
    """The tilt channel keeps 3 deg/s; the platform's roll and pitch reach about 6 deg/s."""
    measured = results['lap']
    assert measured.tilt_rate_peak <= math.radians(3.0) * (1.0 + 1e-9)
    assert measured.platform_tilt_rate_peak > math.radians(5.0)
    assert measured.platform_rate_time_over[0] > 1.0
    assert measured.perceived_tilt_rate_peak > math.radians(3.0)


def test_every_scenario_has_strict_targets():
    """Every built-in scenario has its targets; their axes exist; other inputs get the limits."""
    assert set(STRICT_TARGETS) == set(SCENARIO_NAMES)
    for targets in STRICT_TARGETS.values():
        assert targets.correlation
        assert set(targets.correlation) <= {'x', 'y', 'z', 'roll', 'pitch', 'yaw'}
        assert targets.wrong_sign_time <= 3.0 and targets.felt_at_rest_time <= 3.0
    assert not GENERIC_TARGETS.correlation
