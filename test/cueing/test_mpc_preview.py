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
The MPC told the vehicle's motion to come (``MotionCueing.set_preview``, ``--preview``).

Independent values: the interval means against integrals done by hand, the reference over the
horizon against scipy's integration of the vestibular model, and what a preview is for: the
tilt built before a brake step begins, which no causal cueing can do.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
from scipy.integrate import solve_ivp

from stewart_kinematics.cueing import MotionCueing, replay
from stewart_kinematics.cueing.evaluation import evaluate
from stewart_kinematics.cueing.scenarios import scenario
from stewart_kinematics.cueing.vehicle_preview import input_preview, interval_means
from stewart_kinematics.parameters import read_parameter_file

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml', 'motion_cueing_preview.yaml')]
G = 9.80665
REST = np.array([0.0, 0.0, G, 0.0, 0.0, 0.0])


def preview_values(**changes):
    """Return the shipped files' parameters, the preview preset last, and ``changes``."""
    values = {}
    for path in FILES:
        values.update(read_parameter_file(path, 'motion_cueing_node'))
    values.update(changes)
    return values


def test_interval_means_are_the_means_over_each_step():
    """A ramp's mean is its midpoint value; past the end the last sample fades (by hand)."""
    times = np.array([0.0, 1.0, 2.0])
    force = np.array([[0.0, 0.0, G], [1.0, -2.0, G], [2.0, -4.0, G]])
    rates = np.zeros((3, 3))
    preview = input_preview(times, force, rates, 100.0, 20.0)
    means = interval_means(preview, 0.0, REST, 0.25, 8, REST, 0.5)
    # Steps 0..7 cover 0..2 s: the ramp x = t, y = -2 t; its mean is the midpoint's value.
    middles = (np.arange(8) + 0.5) * 0.25
    assert_allclose(means[:, 0], middles, atol=1e-12)
    assert_allclose(means[:, 1], -2.0 * middles, atol=1e-12)
    assert_allclose(means[:, 2], G, atol=1e-12)
    # Past the end (2 s): x = 2 exp(-(t - 2) / 0.5); its mean over [2 + a, 2 + b].
    tail = interval_means(preview, 1.5, force[1].tolist() + [0.0] * 3, 0.5, 4, REST, 0.5)
    for k, (a, b) in enumerate([(-0.5, 0.0), (0.0, 0.5), (0.5, 1.0), (1.0, 1.5)]):
        if a < 0.0:
            continue   # still on the ramp (from the present sample, 1.5 s, x = 1 given)
        exact = 2.0 * 0.5 * (math.exp(-a / 0.5) - math.exp(-b / 0.5)) / (b - a)
        # The 16-point midpoint rule: (0.5 / 16 / 0.5)^2 / 24 = 1.6e-4 of the mean.
        assert tail[k, 0] == pytest.approx(exact, rel=2e-4)
    # The present sample is where the series starts; samples at or before it are not used.
    assert tail[0, 0] == pytest.approx(np.mean(np.interp(
        1.5 + (np.arange(16) + 0.5) / 32.0, [1.5, 2.0], [1.0, 2.0])), abs=1e-12)
    # Held (inf) and at rest at once (0).
    held = interval_means(preview, 2.0, force[2].tolist() + [0.0] * 3, 0.5, 3, REST, math.inf)
    assert_allclose(held[:, 0], 2.0)
    gone = interval_means(preview, 2.0, force[2].tolist() + [0.0] * 3, 0.5, 3, REST, 0.0)
    assert_allclose(gone, np.tile(REST, (3, 1)))


def test_reference_over_the_horizon_integrates_the_vestibular_model():
    """The reference from a preview is the vehicle's bank integrated by scipy, step by step."""
    core = MotionCueing.from_parameters(preview_values())
    mpc = core.washout
    rng = np.random.default_rng(5)
    n, h = mpc.horizon, mpc.step_time
    to_come = rng.normal(0.0, 1.0, (n, 6))
    to_come[:, 2] += G
    bank = mpc._vehicle
    state = rng.normal(0.0, 0.1, bank.a.shape[0])
    reference = (mpc._psi_unit @ state
                 + mpc._upsilon_preview_unit @ (to_come - REST).ravel()).reshape(n, 5)
    x = state.copy()
    for k in range(n):
        u = to_come[k] - REST
        solution = solve_ivp(lambda _t, y: bank.a @ y + bank.b @ u, (0.0, h), x, rtol=1e-10,
                             atol=1e-12)
        x = solution.y[:, -1]
        assert_allclose(reference[k], (bank.c @ x)[:5], atol=1e-7)


@pytest.mark.parametrize('arguments, words', [
    (([0.0, 0.1], [[0, 0, G]] * 3, [[0, 0, 0]] * 2), 'shape (2, 3)'),
    (([0.0, 0.1], [[0, 0, G], [math.nan, 0, G]], [[0, 0, 0]] * 2), 'finite: sample 1'),
    (([0.0, 0.1], [[0, 0, G]] * 2, [[0, 0, 0], [math.inf, 0, 0]]), 'finite: sample 1'),
    (([0.0, 0.1], [[0, 0, G], [1e308, 0, G]], [[0, 0, 0]] * 2), 'absurd'),
    (([0.0, 0.0], [[0, 0, G]] * 2, [[0, 0, 0]] * 2), 'must increase'),
    (([0.0, math.nan], [[0, 0, G]] * 2, [[0, 0, 0]] * 2), 'finite'),
    (([], [], []), 'M >= 1'),
    (('soon', [[0, 0, G]], [[0, 0, 0]]), 'preview times'),
    (([0.0], [['a', 0, G]], [[0, 0, 0]]), 'preview specific_force'),
])
def test_bad_previews_are_refused_naming_what_is_wrong(arguments, words):
    """A malformed preview is refused with a ValueError; the cueing goes on as before."""
    core = MotionCueing.from_parameters(preview_values())
    core.set_preview([0.0, 10.0], [[1.0, 0.0, G]] * 2, [[0.0, 0.0, 0.0]] * 2)
    kept = core.input_preview
    with pytest.raises(ValueError, match=None) as raised:
        core.set_preview(*arguments)
    assert words in str(raised.value)
    assert core.input_preview is kept
    step = core.step(0.0, [0.0, 0.0, G], [0.0, 0.0, 0.0])
    assert step.accepted


def test_a_preview_needs_the_mpc():
    """The classical washout has no horizon: a preview is refused, saying so."""
    core = MotionCueing.from_parameters(preview_values(cueing_method='classical'))
    with pytest.raises(ValueError, match='needs cueing_method mpc'):
        core.set_preview([0.0], [[0.0, 0.0, G]], [[0.0, 0.0, 0.0]])


@pytest.mark.parametrize('force, rate, column, words', [
    ([1e308, 0.0, G], [0.0, 0.0, 0.0], None, 'specific_force: row 0 of magnitude at least 1e+308'),
    ([0.0, 0.0, G], [0.0, 30.0, 0.0], None, 'angular_velocity: row 0 of magnitude at least 30'),
    ([0.0, 0.0, G], [0.0, 0.0, 0.0], 0, 'preview specific_force: row 3 of magnitude at least 1e'),
    ([0.0, 0.0, G], [0.0, 0.0, 0.0], 4, 'preview angular_velocity: row 3 of magnitude'),
])
def test_mpc_step_refuses_absurd_inputs_and_previews(force, rate, column, words):
    """
    MpcCueing.step bounds its inputs and preview as MotionCueing does (100 m/s^2, 20 rad/s).

    1e308 gave numpy's 'overflow encountered in matmul' (an error under pytest.ini) and 1e10
    a fallback finding instead of a refusal naming the value.
    """
    mpc = MotionCueing.from_parameters(preview_values()).washout
    preview = None
    if column is not None:
        preview = np.tile(REST, (mpc.horizon, 1))
        preview[3, column] = 1e308
    with pytest.raises(ValueError) as raised:
        mpc.step(force, rate, 0.01, preview=preview)
    assert words in str(raised.value)
    assert 'absurd for a vehicle' in str(raised.value)


def test_mpc_step_refuses_a_preview_of_the_wrong_shape():
    """MpcCueing.step checks its preview (shape, finite) as it checks its inputs."""
    mpc = MotionCueing.from_parameters(preview_values()).washout
    for bad in (np.zeros((mpc.horizon - 1, 6)), np.full((mpc.horizon, 6), math.nan), 'x'):
        with pytest.raises(ValueError, match='preview'):
            mpc.step([0.0, 0.0, G], [0.0, 0.0, 0.0], 0.01, preview=bad)


def _pitch_before_braking(preview):
    """Return the cue's pitch (rad) at the brake step's onset, and the braking's mean pitch."""
    drive = scenario('brake_step')
    core = MotionCueing.from_parameters(preview_values())
    played = replay(core, drive.times, drive.specific_force, drive.angular_velocity,
                    preview=preview)
    braking = np.flatnonzero(np.abs(drive.specific_force[:, 0]) > 0.05)
    onset = braking[0]
    return played.angles[onset, 1], np.mean(played.angles[braking, 1]), played


def test_a_preview_builds_the_tilt_before_the_brake_step():
    """
    Knowing the braking to come, the MPC has tilted toward it when it begins; without, not.

    The tilt at the onset has the sign the braking's tilt has, and is more than half a degree
    (3 deg/s is the rate limit: the preview's 4 s horizon gives it time); without a preview
    the platform is level at the onset (nothing to aim at). Every command keeps the limits
    either way (the replay's limiter and gate).
    """
    ahead, braking_mean, played = _pitch_before_braking(True)
    assert np.sign(ahead) == np.sign(braking_mean)
    assert abs(ahead) > math.radians(0.5)
    level, _, _ = _pitch_before_braking(False)
    assert abs(level) < math.radians(0.01)
    assert 'command_refused' not in played.warnings


def test_a_new_time_line_drops_the_preview():
    """restart_time: the preview's clock is the old time line's, so it is forgotten."""
    core = MotionCueing.from_parameters(preview_values())
    core.set_preview([0.0, 1.0], [[0.0, 0.0, G]] * 2, [[0.0, 0.0, 0.0]] * 2)
    core.restart_time()
    assert core.input_preview is None


def _operate_until(core, mode, time):
    """Call operate every 20 ms until the core is in ``mode``; return the time reached."""
    for _ in range(5000):
        time += 0.02
        core.operate(time)
        if core.mode == mode:
            return time
    raise AssertionError(f'never {mode}: {core.mode}')


def test_the_preview_stays_through_a_start_and_a_pause_and_goes_when_the_input_is_lost():
    """
    Start and resume go on on the same clock: the preview given before them stays in use.

    Before, the end of a start dropped a preview sent while the platform rose from park (as a
    simulator sends its scripted drive once, at the start): silently, the MPC cued without it.
    The watchdog's loss of input starts a new clock: that one drops it.
    """
    core = MotionCueing.from_parameters(preview_values(start_parked=True, soft_start_time=1.0))
    told = ([0.0, 100.0], [[1.0, 0.0, G]] * 2, [[0.0, 0.0, 0.0]] * 2)
    core.set_preview(*told)
    preview = core.input_preview
    assert core.start().success
    time = _operate_until(core, 'cueing', 0.0)
    assert core.input_preview is preview
    core.cue(time, [1.0, 0.0, G], [0.0, 0.0, 0.0], command_time=time)
    assert core.pause().success
    time = _operate_until(core, 'paused', time)
    assert core.resume().success
    assert core.input_preview is preview
    time += 0.01
    assert core.cue(time, [1.0, 0.0, G], [0.0, 0.0, 0.0], command_time=time).accepted
    # No input for input_timeout: the stream is lost, and its preview with it.
    core.watch(time + 10.0)
    assert core.input_preview is None


def test_preview_times_spanning_the_float_range_are_taken_without_overflow():
    """
    Times from -1e308 to 1e308 increase: taken, without numpy's 'overflow encountered'.

    Their difference is beyond the float range (pytest.ini makes a RuntimeWarning an error).
    """
    core = MotionCueing.from_parameters(preview_values())
    core.set_preview([-1e308, 1e308], [[0.0, 0.0, G]] * 2, [[0.0, 0.0, 0.0]] * 2)
    assert_allclose(core.input_preview.times, [-1e308, 1e308], rtol=0.0)
    assert core.step(0.0, [0.0, 0.0, G], [0.0, 0.0, 0.0]).accepted


def test_times_that_do_not_increase_are_shown_as_plain_numbers():
    """The refusal shows the times as a user wrote them, not numpy's np.float64(...)."""
    core = MotionCueing.from_parameters(preview_values())
    with pytest.raises(ValueError) as raised:
        core.set_preview(np.array([0.0, -0.0]), [[0.0, 0.0, G]] * 2, [[0.0, 0.0, 0.0]] * 2)
    assert str(raised.value) == ('preview times must increase: sample 1 (-0.0 s) does not '
                                 'come after the one before (0.0 s)')
    assert 'np.' not in str(raised.value)


def _brake_ahead(start):
    """Return a preview from ``start`` (s): 1 s at rest, then braking at 5 m/s^2 for 3 s."""
    times = start + np.arange(401) * 0.01
    force = np.tile([0.0, 0.0, G], (401, 1))
    force[times > start + 1.0, 0] = -5.0
    return times, force, np.zeros((401, 3))


def _pitch_after(core, start, samples=50):
    """Cue ``samples`` samples at rest from ``start`` (s); return the last cue's pitch, rad."""
    for index in range(samples):
        step = core.step(start + index * 0.01, [0.0, 0.0, G], [0.0, 0.0, 0.0])
    return step.pose[4]


def test_a_preview_given_while_paused_is_used_after_resume():
    """
    Resume goes on on the simulator's clock: the preview given during the pause stays.

    The cue then tilts toward the braking to come (against a twin told nothing); the preview
    was dropped on resume before.
    """
    pitches = []
    for told in (True, False):
        core = MotionCueing.from_parameters(preview_values())
        _pitch_after(core, 0.0, 10)
        assert core.pause().success
        if told:
            core.set_preview(*_brake_ahead(1.0))
        assert core.resume().success
        assert (core.input_preview is not None) == told
        pitches.append(_pitch_after(core, 1.0))
    assert abs(pitches[0]) > math.radians(0.1)
    assert abs(pitches[1]) < math.radians(0.01)


def test_a_preview_given_while_parked_is_used_once_started():
    """The end of a start from park keeps the preview given while parked (it was dropped)."""
    core = MotionCueing.from_parameters(preview_values())
    assert core.stop().success
    now = 0.0
    while core.mode != 'parked' and now < 60.0:
        now += 0.01
        core.operate(now)
    assert core.mode == 'parked'
    core.set_preview(*_brake_ahead(0.0))
    assert core.start().success
    while core.mode != 'cueing' and now < 120.0:
        now += 0.01
        core.operate(now)
    assert core.mode == 'cueing'
    assert core.input_preview is not None
    assert abs(_pitch_after(core, 0.0)) > math.radians(0.1)


def _evaluated(values, name, preview):
    """Replay scenario ``name`` with the parameters ``values``; return its evaluation."""
    drive = scenario(name)
    template = MotionCueing.from_parameters(values)
    cueing = MotionCueing(template.geometry, template.settings, template.actuator_limits)
    played = replay(cueing, drive.times, drive.specific_force, drive.angular_velocity,
                    preview=preview)
    return evaluate(played, template.geometry, template.actuator_limits,
                    template.settings.tilt_rate_max, rest=drive.rest_time,
                    gravity=template.settings.gravity)


def test_told_the_mixed_drive_the_mpc_errs_20_percent_less_than_classical():
    """
    Issue 31's target on the 60 s mixed drive, along x and y: RMSE at least 20 % lower.

    Classical washout with the shipped tuning against the MPC with the preview preset, told
    the drive; equal limits and perception model. Every command within the limits, the
    perceived tilt rate within 3 deg/s. (Heave, z, is not met: doc/motion_cueing_mpc.md.)
    About 20 s.
    """
    classical = _evaluated(preview_values(cueing_method='classical'), 'mixed_drive', False)
    told = _evaluated(preview_values(), 'mixed_drive', True)
    for axis in ('x', 'y'):
        assert told.measures(axis).rmse <= 0.8 * classical.measures(axis).rmse, axis
    assert told.limit_violations == 0
    assert told.perceived_tilt_rate_peak <= math.radians(3.0)


def test_a_preview_in_the_imu_frame_is_turned_into_the_vehicle_frame():
    """
    As for a sample: values in imu_frame are turned by imu_orientation_rpy_deg.

    An IMU mounted upside down about x (NED-like: roll 180 deg) reports x, -y, -z of the
    vehicle frame; the preview taken is the vehicle frame's, by hand.
    """
    core = MotionCueing.from_parameters(preview_values(
        imu_frame='imu_ned', imu_orientation_rpy_deg=[180.0, 0.0, 0.0]))
    core.set_preview([0.0, 1.0], [[1.0, 2.0, -G], [3.0, -4.0, -G]],
                     [[0.1, 0.2, 0.3], [0.0, 0.0, -0.5]], frame_id='imu_ned')
    assert_allclose(core.input_preview.inputs,
                    [[1.0, -2.0, G, 0.1, -0.2, -0.3], [3.0, 4.0, G, 0.0, 0.0, 0.5]],
                    rtol=0.0, atol=1e-12)
    core.set_preview([0.0], [[1.0, 2.0, G]], [[0.0, 0.0, 0.0]], frame_id='')
    assert_allclose(core.input_preview.inputs, [[1.0, 2.0, G, 0.0, 0.0, 0.0]], atol=0.0)


def test_rest_without_input_eases_home_whatever_the_preview_says():
    """
    rest() (no input came): the platform glides to neutral, as told nothing.

    The input's clock stands still there, so a braking told to come 0.5 s after the last
    sample stayed 0.5 s ahead for ever: 10 s of rest held the platform 9.5 deg tilted.
    """
    core = MotionCueing.from_parameters(preview_values())
    core.set_preview(*_brake_ahead(0.0))
    _pitch_after(core, 0.0)
    for _ in range(1000):
        step = core.rest(0.01)
    # Near neutral (the geometry's home pose, level): within 1 mm and 0.05 deg after 10 s
    # (the tilt built toward the braking washes out slowly: 0.02 deg left), not 62 mm and
    # 9.5 deg as before.
    assert_allclose(step.pose[:3], core.geometry.home_pose[:3], atol=1e-3)
    assert_allclose(step.pose[3:], core.geometry.home_pose[3:], atol=math.radians(0.05))
    assert core.input_preview is not None


@pytest.mark.parametrize('times', [[0.0, 0.2], [-3.0], [0.1, 0.49]])
def test_a_preview_wholly_past_is_refused_naming_the_clock(times):
    """
    A preview ending at or before the last sample (0.49 s) has nothing to come: refused.

    It was taken without a word (a message stamped 0, or on another clock, did nothing);
    the preview before stays in use.
    """
    core = MotionCueing.from_parameters(preview_values())
    core.set_preview(*_brake_ahead(0.0))
    kept = core.input_preview
    _pitch_after(core, 0.0)
    with pytest.raises(ValueError) as raised:
        core.set_preview(times, [[0.0, 0.0, G]] * len(times), [[0.0, 0.0, 0.0]] * len(times))
    assert str(raised.value).startswith(f'the preview ends at {times[-1]!r} s, not after the '
                                        'last sample (0.49 s)')
    assert core.input_preview is kept
    core.set_preview([0.5], [[0.0, 0.0, G]], [[0.0, 0.0, 0.0]])   # one point to come: taken
    assert core.input_preview is not kept
