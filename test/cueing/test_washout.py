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
The classical washout against closed-form filter responses, and its inputs refused.

The closed forms are worked out here by partial fractions, independently of the package: the
translational channel's position after a step of specific force ``a`` is ``k a g(t)`` with
``g`` the impulse response of ``1 / ((s + p)^2 (s + q))`` (damping 1, ``p = omega``,
``q = omega_b``); the rotational channel's angle after a step of angular velocity ``w`` is
``k w t exp(-omega t)``.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics.cueing import ClassicalWashout, CueingSettings
from stewart_kinematics.cueing.filters import expm, FilterBank, high_pass, integrated, low_pass

pytestmark = pytest.mark.core

G = 9.80665
REST = [0.0, 0.0, G]
STILL = [0.0, 0.0, 0.0]


def settings(**changes):
    """Literature defaults with the tilt and rotation off unless changed."""
    values = {'tilt_scale': (0.0, 0.0), 'rotation_scale': (0.0, 0.0, 0.0)}
    values.update(changes)
    return CueingSettings(**values)


def step_position(t, p, q):
    """Impulse response of 1 / ((s + p)^2 (s + q)) and its two derivatives (p != q)."""
    a, c = 1.0 / (p - q) ** 2, -1.0 / (p - q)
    ep, eq = np.exp(-p * t), np.exp(-q * t)
    g = a * (eq - ep) + c * t * ep
    dg = a * (-q * eq + p * ep) + c * (ep - p * t * ep)
    ddg = a * (q * q * eq - p * p * ep) + c * (-2.0 * p * ep + p * p * t * ep)
    return g, dg, ddg


def run(washout, times, force, rate=STILL):
    """Step from a first sample at rest at t = 0, then hold the inputs; return the steps."""
    washout.step(REST, STILL, 0.0)
    steps, previous = [], 0.0
    for time in times:
        steps.append(washout.step(force, rate, time - previous))
        previous = time
    return steps


def test_translational_step_matches_the_closed_form():
    """A step of 3 m/s^2 forward: position, velocity, acceleration as k a g, g', g''."""
    washout = ClassicalWashout(settings(translation_scale=(0.5, 0.5, 0.5)))
    times = np.arange(1, 2001) * 0.01
    steps = run(washout, times, [3.0, 0.0, G])
    g, dg, ddg = step_position(times, 2.5, 0.25)
    assert_allclose([s.displacement[0] for s in steps], 1.5 * g, rtol=0, atol=1e-12)
    assert_allclose([s.velocity[0] for s in steps], 1.5 * dg, rtol=0, atol=1e-12)
    assert_allclose([s.acceleration[0] for s in steps], 1.5 * ddg, rtol=0, atol=1e-12)
    assert_allclose([s.displacement[1:] for s in steps], 0.0, atol=0.0)


def test_step_response_is_exact_at_any_sample_times():
    """Jittered steps give the closed form at their own times: exact discretisation."""
    rng = np.random.default_rng(3)
    times = np.cumsum(rng.uniform(0.0002, 0.03, size=1500))
    washout = ClassicalWashout(settings(translation_scale=(1.0, 0.5, 0.5),
                                        translation_break_frequency=(0.4, 0.25, 0.25)))
    steps = run(washout, times, [-2.0, 0.0, G])
    # The filter's clock is rounded to 1 us, the remainder carried: within 0.5 us of the stamps.
    g, dg, _ = step_position(times, 2.5, 0.4)
    assert_allclose([s.displacement[0] for s in steps], -2.0 * g, rtol=0, atol=1e-6 * 2.0)


def test_washout_returns_to_neutral_and_never_reverses_through_it():
    """With damping >= 1 the displacement keeps one sign, rises once, falls once, ends at 0."""
    for frequency, damping, break_frequency in ((2.5, 1.0, 0.25), (1.0, 1.0, 1.0),
                                                (4.0, 1.5, 0.5), (0.8, 1.0, 2.0)):
        washout = ClassicalWashout(settings(
            translation_frequency=(frequency,) * 3, translation_damping=(damping,) * 3,
            translation_break_frequency=(break_frequency,) * 3))
        times = np.arange(1, 12001) * 0.01
        x = np.array([s.displacement[0] for s in run(washout, times, [2.0, 0.0, G])])
        assert np.all(x >= 0.0), (frequency, damping, break_frequency)
        peak = int(np.argmax(x))
        assert np.all(np.diff(x[:peak + 1]) >= 0.0) and np.all(np.diff(x[peak:]) <= 1e-15)
        assert x[-1] < 1e-6 * x[peak]


def test_underdamped_washout_does_reverse():
    """The check above can fail: damping 0.3 overshoots through neutral."""
    washout = ClassicalWashout(settings(translation_damping=(0.3, 0.3, 0.3),
                                        translation_break_frequency=(1.0, 1.0, 1.0)))
    steps = run(washout, np.arange(1, 3001) * 0.01, [2.0, 0.0, G])
    x = np.array([s.displacement[0] for s in steps])
    assert x.min() < -1e-3


def test_second_order_translation_keeps_a_displacement():
    """Order 2: a sustained acceleration a holds the head at k a / omega^2."""
    washout = ClassicalWashout(settings(translation_order=2))
    steps = run(washout, np.arange(1, 3001) * 0.01, [2.0, 0.0, G])
    assert steps[-1].displacement[0] == pytest.approx(0.5 * 2.0 / 2.5 ** 2, rel=1e-9)


def test_rotational_step_matches_the_closed_form():
    """A yaw rate step w: angle k w t exp(-omega t), rate its derivative."""
    washout = ClassicalWashout(settings(rotation_scale=(0.5, 0.5, 0.5)))
    times = np.arange(1, 1001) * 0.01
    steps = run(washout, times, REST, [0.0, 0.0, 0.3])
    assert_allclose([s.rotation[2] for s in steps], 0.15 * times * np.exp(-times), atol=1e-12)
    assert_allclose([s.angles[2] for s in steps], 0.15 * times * np.exp(-times), atol=1e-12)


def test_tilt_reaches_asin_of_the_scaled_force_at_the_rate_limit():
    """A constant 3 m/s^2: pitch -asin(k a / g), approached at exactly 3 deg/s, never faster."""
    washout = ClassicalWashout(settings(tilt_scale=(0.5, 0.5)))
    dt = 0.001
    times = np.arange(1, 10001) * dt
    steps = run(washout, times, [3.0, 0.0, G])
    pitch = np.array([s.tilt[1] for s in steps])
    rate = np.array([s.tilt_rate[1] for s in steps])
    limit = math.radians(3.0)
    assert np.all(np.abs(rate) <= limit * (1.0 + 1e-12))
    assert np.all(np.abs(np.diff(pitch)) <= limit * dt * (1.0 + 1e-12))
    target = -math.asin(0.5 * 3.0 / G)
    assert pitch[-1] == pytest.approx(target, abs=1e-12)
    assert_allclose([s.tilt[0] for s in steps], 0.0, atol=0.0)
    # On the way the tilt runs at the rate limit, the acceleration limit only at both ends:
    # reaching 8.8 deg at 3 deg/s takes 2.9 s, plus under 0.3 s for the onset.
    at_limit = np.abs(rate) >= limit * (1.0 - 1e-12)
    assert at_limit.sum() * dt > 0.8 * abs(target) / limit
    reached = times[np.argmax(np.abs(pitch - target) < 1e-4)]
    assert abs(target) / limit < reached < abs(target) / limit + 0.8


def test_sustained_input_from_the_start_gives_no_onset_cue():
    """The first sample settles the filters: a car already in a turn does not jolt the seat."""
    washout = ClassicalWashout(CueingSettings())
    first = washout.step([0.0, 4.0, G], [0.0, 0.0, 0.3], 0.0)
    later = [washout.step([0.0, 4.0, G], [0.0, 0.0, 0.3], 0.01) for _ in range(100)]
    for step in [first] + later:
        assert_allclose(step.displacement, 0.0, atol=1e-12)
        assert_allclose(step.rotation, 0.0, atol=1e-12)
    assert later[-1].tilt[0] > 0.0  # the tilt ramps toward the sustained force


def test_soft_input_limit_compresses_large_forces_only():
    """translation_input_limit L: a = L tanh(a_in / L) enters the high-pass."""
    for force in (0.01, 6.0):
        a = run(ClassicalWashout(settings()), [0.01], [force, 0.0, G])[0].acceleration[0]
        b = run(ClassicalWashout(settings(translation_input_limit=1.5)), [0.01],
                [force, 0.0, G])[0].acceleration[0]
        assert b / a == pytest.approx(1.5 * math.tanh(force / 1.5) / force, rel=1e-12)


@pytest.mark.parametrize('name, value', [
    ('specific_force', [math.nan, 0.0, G]), ('specific_force', [0.0, math.inf, G]),
    ('specific_force', [0.0, 0.0]), ('specific_force', 'up'), ('specific_force', None),
    ('angular_velocity', [0.0, -math.inf, 0.0]), ('angular_velocity', [[0.0, 0.0, 0.0]]),
    ('angular_velocity', [1e308, 1e308, 1e308 * 10]),
])
def test_malformed_inputs_raise_naming_the_argument(name, value):
    """NaN, inf, overflow, wrong shapes and types: ValueError that names the argument."""
    washout = ClassicalWashout()
    arguments = {'specific_force': REST, 'angular_velocity': STILL}
    arguments[name] = value
    with pytest.raises(ValueError, match=name):
        washout.step(arguments['specific_force'], arguments['angular_velocity'], 0.01)


@pytest.mark.parametrize('dt', [-0.01, math.nan, math.inf])
def test_bad_steps_raise(dt):
    """A negative or non-finite step is refused."""
    with pytest.raises(ValueError, match='dt'):
        ClassicalWashout().step(REST, STILL, dt)


@pytest.mark.parametrize('changes, name', [
    ({'translation_order': 1}, 'translation_order'), ({'tilt_order': 3}, 'tilt_order'),
    ({'translation_frequency': (1.0, -1.0, 1.0)}, 'translation_frequency'),
    ({'translation_scale': (0.5, 0.5)}, 'translation_scale'),
    ({'tilt_rate_max': 0.0}, 'tilt_rate_max'), ({'gravity': math.nan}, 'gravity'),
    ({'head_position': (0.0, 0.0, math.inf)}, 'head_position'),
    ({'tilt_complementary': 'yes'}, 'tilt_complementary'),
    ({'condition_margin': 0.0}, 'condition_margin'),
])
def test_settings_refuse_values_out_of_range(changes, name):
    """Each setting is checked when built; the message names it."""
    with pytest.raises(ValueError, match=name):
        CueingSettings(**changes)


def test_expm_matches_closed_forms():
    """A rotation generator, a nilpotent matrix and a diagonal: exact exponentials."""
    angle = 2.7
    assert_allclose(expm(np.array([[0.0, -angle], [angle, 0.0]])),
                    [[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]],
                    atol=1e-14)
    assert_allclose(expm(np.array([[0.0, 3.0], [0.0, 0.0]])), [[1.0, 3.0], [0.0, 1.0]],
                    atol=1e-15)
    assert_allclose(expm(np.diag([-40.0, 0.5])), np.diag([math.exp(-40.0), math.exp(0.5)]),
                    rtol=1e-13, atol=1e-30)


def test_filter_bank_low_pass_and_complement():
    """A settled low-pass outputs its input; a high-pass integrated too often is refused."""
    numerator, denominator = low_pass(2, 3.0, 1.0)
    bank = FilterBank(1, [(numerator, denominator, 0, (0,))])
    assert bank.settle([2.5]) == pytest.approx([2.5], rel=1e-15)
    with pytest.raises(ValueError, match='drift'):
        integrated(high_pass(2, 1.0, 1.0), 3)
    with pytest.raises(ValueError, match='improper'):
        FilterBank(1, [(np.array([1.0, 0.0, 0.0]), np.array([1.0, 1.0]), 0, (0,))])


# Attitude-aware specific force (Reid and Nahon's L_IS).


def test_at_zero_attitude_the_attitude_aware_washout_changes_nothing():
    """L_IS is the identity at neutral: every output equal to 1e-12 on a random input."""
    rng = np.random.default_rng(31)
    forces = REST + rng.normal(0.0, 3.0, size=(400, 3))
    rates = rng.normal(0.0, 0.5, size=(400, 3))
    steps = rng.uniform(0.001, 0.03, size=400)
    aware, plain = (ClassicalWashout(settings(attitude_aware_specific_force=flag,
                                              translation_input_limit=2.0))
                    for flag in (True, False))
    for force, rate, dt in zip(forces, rates, steps):
        a, b = aware.step(force, rate, dt), plain.step(force, rate, dt)
        assert_allclose(aware.attitude, 0.0, atol=0.0)
        for name in ('displacement', 'velocity', 'acceleration', 'tilt', 'rotation', 'angles'):
            assert_allclose(getattr(a, name), getattr(b, name), rtol=0.0, atol=1e-12)
    assert_allclose(aware.simulator_force(forces[0]), forces[0], rtol=0.0, atol=0.0)


def test_a_tilted_simulator_takes_the_force_in_its_own_frame():
    """Rolled 10 deg (left side up): f = [0, 0, F] is [0, -F sin, F cos] in the simulator."""
    washout = ClassicalWashout(settings(attitude_aware_specific_force=True))
    roll, pitch, force = math.radians(10.0), math.radians(-4.0), G / math.cos(math.radians(30))
    washout.attitude = np.array([roll, 0.0, 0.0])
    assert_allclose(washout.simulator_force([0.0, 0.0, force]),
                    [0.0, -force * math.sin(roll), force * math.cos(roll)], atol=1e-12)
    # Pitched (nose up for a negative pitch), then yawed 90 deg: forward becomes left.
    washout.attitude = np.array([0.0, pitch, math.pi / 2])
    assert_allclose(washout.simulator_force([2.0, 0.0, G]),
                    [0.0, 2.0 * math.cos(pitch) + G * math.sin(pitch),
                     -2.0 * math.sin(pitch) + G * math.cos(pitch)], atol=1e-12)
    # Off: the force as it comes.
    plain = ClassicalWashout(settings(attitude_aware_specific_force=False))
    plain.attitude = np.array([roll, 0.0, 0.0])
    assert_allclose(plain.simulator_force([0.0, 0.0, force]), [0.0, 0.0, force], atol=0.0)


def test_the_translational_channel_high_passes_the_rotated_force():
    """At a roll held by hand, the channel moves as for the hand-rotated force as it comes."""
    roll, force = math.radians(10.0), G / math.cos(math.radians(30))
    aware = ClassicalWashout(settings(attitude_aware_specific_force=True))
    plain = ClassicalWashout(settings(attitude_aware_specific_force=False))
    aware.step(REST, STILL, 0.0)
    plain.step(REST, STILL, 0.0)
    rotated = [0.0, -force * math.sin(roll), force * math.cos(roll)]
    for _ in range(50):
        aware.attitude = np.array([roll, 0.0, 0.0])   # as if the rotational channel held it
        a = aware.step([0.0, 0.0, force], STILL, 0.01)
        b = plain.step(rotated, STILL, 0.01)
        assert_allclose(a.displacement, b.displacement, rtol=0.0, atol=1e-12)
        assert_allclose(a.acceleration, b.acceleration, rtol=0.0, atol=1e-12)
    # The simulator is pushed to the right (-y), away from the gravity its roll shows.
    assert a.displacement[1] < -1e-3


def coordinated_turn(bank=math.radians(30.0), speed=60.0, roll_time=3.0, hold=10.0):
    """
    Return an aircraft's coordinated turn at 100 Hz: level 1 s, roll in, hold, out, level.

    Roll rate ``p = bank / roll_time`` in and out; in the turn the heading turns at
    ``g tan(phi) / V`` (body pitch and yaw rates its components ``sin(phi)`` and
    ``cos(phi)``), and the specific force is ``[0, 0, g / cos(phi)]``: no lateral component.
    """
    times = np.arange(-100, int(100 * (2 * roll_time + hold + 10))) * 0.01
    rate = bank / roll_time
    phi = (np.clip(times / roll_time, 0.0, 1.0)
           - np.clip((times - roll_time - hold) / roll_time, 0.0, 1.0)) * bank
    roll_rate = rate * (((times >= 0.0) & (times < roll_time)).astype(float)
                        - ((times >= roll_time + hold) & (times < 2 * roll_time + hold)))
    heading_rate = G * np.tan(phi) / speed
    rates = np.stack([roll_rate, heading_rate * np.sin(phi), heading_rate * np.cos(phi)], 1)
    force = np.stack([0.0 * times, 0.0 * times, G / np.cos(phi)], 1)
    return times, force, rates


def felt_lateral(washout, times, force, rates):
    """Return the lateral force felt at the head, ``(R^T (d'' + [0, 0, g]))_y``, m/s^2."""
    from stewart_kinematics.model.rotations import euler_zyx_to_matrix
    felt, previous = [], times[0]
    for time, f, w in zip(times, force, rates):
        step = washout.step(f, w, time - previous)
        previous = time
        felt.append((euler_zyx_to_matrix(step.angles).T @ (step.acceleration + REST))[1])
    return np.array(felt)


def test_a_coordinated_turn_with_and_without_the_simulator_attitude():
    """
    The turn's roll shows gravity sideways; L_IS offsets it only where the high-pass passes.

    Hand values: the rotational channel rolls ``k p t exp(-t)`` during the roll-in (omega 1
    rad/s), so without L_IS the head feels ``g sin(k p / e)`` sideways at t = 1 s, 0.315
    m/s^2 at the literature's gains (k 0.5, p 10 deg/s). With L_IS the translational
    channel is asked for ``-k_t F sin(roll)``: at the literature's gains its high-pass (2.5
    rad/s, third order) passes about |HP(j 1)| = 0.13 of the roll's content (about 1 rad/s),
    times ``k_t F / g`` (0.58), so the felt force changes by under 15 % of its peak. With a
    channel that passes it (scale 1, second order at 0.1 rad/s, a simulator with metres of
    travel) the roll-in's felt force falls below 40 %; the high-pass must give back the net
    lateral velocity ``k_r bank F`` the offsetting asks for (2.9 m/s here), so a tail of the
    other sign, under 0.13 m/s^2, stays.
    """
    times, force, rates = coordinated_turn()
    hand = G * math.sin(0.5 * math.radians(10.0) / math.e)
    in_turn = {}
    for label, changes in (('literature', {}), ('wide', {
            'translation_scale': (1.0, 1.0, 1.0), 'translation_order': 2,
            'translation_frequency': (0.1, 0.1, 0.1)})):
        for aware in (False, True):
            washout = ClassicalWashout(CueingSettings(
                tilt_scale=(0.0, 0.0), attitude_aware_specific_force=aware, **changes))
            in_turn[label, aware] = felt_lateral(washout, times, force, rates)
    plain = in_turn['literature', False]
    assert plain[times.searchsorted(1.0)] == pytest.approx(hand, rel=0.01)
    assert np.max(np.abs(plain)) == pytest.approx(hand, rel=0.01)

    def false_time(felt):
        return 0.01 * np.count_nonzero(np.abs(felt) > 0.1)

    # Without L_IS, both channel settings feel the same roll (and a little of the heave
    # channel's sin(roll) d''_z): about 11.6 s beyond 0.1 m/s^2.
    assert false_time(plain) == pytest.approx(11.6, abs=0.2)
    assert_allclose(in_turn['wide', False], plain, atol=0.04)
    # At the literature's gains L_IS changes little (measured: peak +7 %, time -0.3 s).
    literature = in_turn['literature', True]
    assert np.max(np.abs(literature - plain)) < 0.15 * hand
    assert np.max(np.abs(literature)) == pytest.approx(hand, rel=0.1)
    assert false_time(literature) == pytest.approx(false_time(plain), rel=0.1)
    # Where the translational channel passes the roll, L_IS takes most of it away.
    wide = in_turn['wide', True]
    roll_in = (times >= 0.0) & (times <= 3.0)
    assert np.max(np.abs(wide[roll_in])) < 0.4 * hand
    assert np.max(np.abs(wide)) < 0.45 * hand
    assert false_time(wide) < 0.3 * false_time(plain)
