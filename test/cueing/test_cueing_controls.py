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
MotionCueing's run-time controls: intensity and gains, soft start and stop, pause and resume.

The gains ramped or refused, park, the soft motions, the pause held. Leg lengths are
recomputed from the poses sent with the leg formula of ``reference``; the limits are
example_limits.yaml's (0.05 m/s, 0.25 m/s^2 per leg). About 15 s for the module.
"""

import dataclasses
import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics.cueing import MotionCueing
from stewart_kinematics.cueing.controls import GainRamp, smoothstep
from stewart_kinematics.cueing.limit_margins import pose_violations
from stewart_kinematics.cueing.motion_cueing import (
    CUEING,
    PARKED,
    PAUSED,
    STARTING,
    STOPPING,
)
from stewart_kinematics.cueing.washout import ClassicalWashout
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import read_parameter_file

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml')]
G = 9.80665
PERIOD = 0.01
VELOCITY_MAX, ACCELERATION_MAX = 0.05, 0.25


def make_cueing(**controls):
    """Build the node's core from the shipped files, with some control parameters."""
    values = {}
    for path in FILES:
        values.update(read_parameter_file(path, 'motion_cueing_node'))
    values.update(controls)
    return MotionCueing.from_parameters(values)


def drive(time):
    """Return a vehicle's specific force and angular velocity at ``time`` (seconds)."""
    force = [1.5 * math.sin(2.0 * time) + 0.8 * math.sin(5.1 * time),
             1.2 * math.sin(1.3 * time + 0.4), G + 0.6 * math.sin(3.7 * time)]
    rate = [0.2 * math.sin(1.1 * time), 0.15 * math.sin(0.7 * time), 0.3 * math.sin(0.9 * time)]
    return force, rate


def legs(pose):
    """Leg lengths of a platform pose (metres, radians), written out in reference."""
    return np.array(reference.leg_lengths(pose))


def assert_leg_limits(poses, times):
    """Check the leg velocities and accelerations of consecutive commands; return lengths."""
    lengths = np.array([legs(pose) for pose in poses])
    intervals = np.diff(np.asarray(times))[:, None]
    velocities = np.diff(lengths, axis=0) / intervals
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-6)
    accelerations = np.diff(velocities, axis=0) / intervals[1:]
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-6)
    return lengths


def stream(cueing, start, count, change=None):
    """Cue ``count`` samples of :func:`drive` from ``start``; ``change(k)`` before sample k."""
    steps = []
    for k in range(count):
        if change is not None:
            change(k)
        time = start + k * PERIOD
        steps.append(cueing.cue(time, *drive(time), command_time=time))
    return steps


# Gains ---------------------------------------------------------------------------------------

def test_smoothstep_runs_from_zero_to_one_flat_at_both_ends():
    assert smoothstep(-1.0) == 0.0 and smoothstep(0.0) == 0.0 and smoothstep(2.0) == 1.0
    assert smoothstep(0.5) == 0.5
    assert_allclose((smoothstep(1e-6) - smoothstep(0.0)) / 1e-6, 0.0, atol=1e-5)
    assert_allclose((smoothstep(1.0) - smoothstep(1.0 - 1e-6)) / 1e-6, 0.0, atol=1e-5)


def test_a_gain_ramp_is_the_smoothstep_and_a_new_target_starts_where_it_is():
    ramp = GainRamp(np.ones(8))
    ramp.set_target(np.zeros(8), 2.0)
    ramp.advance(0.5)
    assert_allclose(ramp.value, 1.0 - smoothstep(0.25), rtol=0, atol=1e-15)
    middle = ramp.value.copy()
    ramp.set_target(np.full(8, 2.0), 1.0)
    ramp.advance(0.25)
    assert_allclose(ramp.value, middle + (2.0 - middle) * smoothstep(0.25), atol=1e-15)
    ramp.advance(10.0)
    assert not ramp.ramping
    assert_allclose(ramp.value, 2.0, rtol=0, atol=0)


def test_an_intensity_change_scales_the_cue_by_the_ramp_exactly():
    """Mid-stream to 0.3 over 1 s: displacement and rotation are the unchanged cue times r(t)."""
    changed, unchanged = make_cueing(gain_ramp_time=1.0), make_cueing()
    begin = 150

    def change(k):
        if k == begin:
            assert changed.set_gains(intensity=0.3) is None

    ramped = stream(changed, 0.0, 400, change)
    plain = stream(unchanged, 0.0, 400)
    for k, (one, other) in enumerate(zip(ramped, plain)):
        # The ramp advances by each sample's step, from the sample after the change on.
        share = 1.0 - 0.7 * smoothstep((k - begin + 1) * PERIOD / 1.0) if k >= begin else 1.0
        assert_allclose(one.displacement, share * other.displacement, rtol=1e-9, atol=1e-12)
        assert_allclose(one.angles - np.r_[one.tilt, 0.0],
                        share * (other.angles - np.r_[other.tilt, 0.0]), rtol=1e-9, atol=1e-12)
        # The tilt's gain acts before its rate limiter: the rate limit holds throughout.
        assert np.abs(one.tilt_rate).max() <= math.radians(3.0) * (1 + 1e-9)


def test_an_intensity_raised_mid_stream_never_jumps_the_cue_and_a_step_would():
    """From 0.3 to 1: the cue's change per sample stays within the ramp's bound."""
    def largest_change(ramp_time):
        cueing = make_cueing(cueing_intensity=0.3, gain_ramp_time=ramp_time)
        steps = stream(cueing, 0.0, 300, lambda k: k == 100 and cueing.set_gains(intensity=1.0))
        targets = np.array([step.target for step in steps[1:]])
        return np.abs(np.diff(targets, axis=0)).max(), steps

    baseline = make_cueing()
    plain = np.array([step.target for step in stream(baseline, 0.0, 300)[1:]])
    cue_size = np.abs(plain - baseline.geometry.home_pose).max()
    natural = np.abs(np.diff(plain, axis=0)).max()
    # The gain moves by at most 1.5 * 0.7 * dt / T per sample (the smoothstep's steepest).
    bound = natural + 1.5 * 0.7 * PERIOD / 2.0 * cue_size * 1.2
    ramped, steps = largest_change(2.0)
    assert ramped <= bound
    stepped, _ = largest_change(0.01)
    assert stepped > bound   # the check would see a jump
    poses = [step.pose for step in steps]
    assert_leg_limits(poses, [step.command.time for step in steps])


def test_a_flood_of_changes_keeps_every_command_within_the_limits():
    """A new intensity every sample (a slider dragged): the commands keep the leg limits."""
    cueing = make_cueing(gain_ramp_time=0.5)
    rng = np.random.default_rng(7)
    steps = stream(cueing, 0.0, 300, lambda k: cueing.set_gains(
        intensity=float(rng.uniform(0.0, 1.0)),
        translation_scale=[float(rng.uniform(0.0, 0.3))] * 3))
    assert all(step.command.accepted for step in steps)
    assert_leg_limits([step.pose for step in steps], [step.command.time for step in steps])


@pytest.mark.parametrize('intensity', [math.nan, math.inf, -math.inf, -0.1, 1.0000001, 1e308,
                                       'high', None])
def test_an_intensity_that_is_no_number_in_0_1_is_refused_naming_it(intensity):
    cueing = make_cueing()
    before = cueing.gains.target
    if intensity is None:
        assert cueing.set_gains(intensity=intensity) is None   # None: as now
    else:
        refusal = cueing.set_gains(intensity=intensity)
        assert refusal.code == 'gain_refused'
        assert 'cueing_intensity' in refusal.message
    assert_allclose(cueing.gains.target, before, rtol=0, atol=0)


@pytest.mark.parametrize('gains', [[0.2, 0.2], [0.2, math.nan, 0.2], [-0.1, 0.2, 0.2],
                                   [0.2, 0.2, 11.0], 'abc'])
def test_a_gain_of_the_wrong_size_or_range_is_refused_naming_it(gains):
    refusal = make_cueing().set_gains(translation_scale=gains)
    assert refusal.code == 'gain_refused' and 'translation_scale' in refusal.message


def test_a_gain_whose_cue_leaves_the_travel_is_refused_with_the_largest_allowed():
    """The refusal names the value and the travel; just below the largest, it is taken."""
    cueing = make_cueing()
    refusal = cueing.set_gains(translation_scale=[2.0, 0.2, 0.2])
    assert refusal.code == 'gain_refused'
    message = refusal.message
    assert 'translation_scale x = 2 times cueing_intensity 1' in message, message
    assert '0.804 m, beyond the 0.352 m of travel' in message, message
    largest = float(message.split('at most ')[1].split(' ')[0])
    assert 0.2 < largest < 2.0
    assert cueing.set_gains(translation_scale=[largest * 1.01, 0.2, 0.2]) is not None
    assert cueing.set_gains(translation_scale=[largest * 0.99, 0.2, 0.2]) is None

    # Independently: a sustained reference force (4 m/s^2, soft-limited) at the largest gain
    # peaks at the travel, and the pose of the travel is the edge of the narrowed limits.
    settings = cueing.settings
    washout = ClassicalWashout(dataclasses.replace(settings,
                                                   translation_scale=(largest, 0.2, 0.2)))
    washout.step([0.0, 0.0, G], [0.0, 0.0, 0.0], 0.0)
    peak = max(washout.step([4.0, 0.0, G], [0.0, 0.0, 0.0], 0.01).displacement[0]
               for _ in range(4000))
    limiter = cueing.limiter
    travel = cueing._gain_check.travel()[0]
    assert_allclose(peak, travel, rtol=0.01)
    for distance, inside in ((travel, True), (travel + 0.02, False)):
        allowed = []
        for sign in (1.0, -1.0):
            pose = limiter.cue_poses([sign * distance, 0.0, 0.0], [0.0, 0.0, 0.0])
            allowed.append(not pose_violations(limiter.cue_geometry, pose[:3],
                                               euler_zyx_to_matrix(pose[3:])))
        assert all(allowed) if inside else not all(allowed)


def test_lowering_a_gain_beyond_the_travel_is_always_taken():
    """Started beyond the travel (a parameter file): a lower gain, still beyond, is taken."""
    cueing = make_cueing(translation_scale=[3.0, 0.2, 0.2])
    assert cueing.set_gains(translation_scale=[2.5, 0.2, 0.2]) is None
    assert cueing.set_gains(translation_scale=[2.8, 0.2, 0.2]) is not None   # raised again


def test_intensity_zero_eases_the_cue_to_neutral():
    cueing = make_cueing(gain_ramp_time=0.5)
    steps = stream(cueing, 0.0, 600, lambda k: k == 100 and cueing.set_gains(intensity=0.0))
    assert_allclose(steps[-1].displacement, 0.0, atol=1e-12)
    assert np.abs(steps[-1].angles).max() < math.radians(0.5)   # the tilt at its rate limit


# Park, soft start and stop --------------------------------------------------------------------

def operate_until(cueing, mode, time, limit=2000):
    """Call operate every PERIOD until ``mode``; return (time, the steps sent)."""
    steps = []
    for _ in range(limit):
        time += PERIOD
        step = cueing.operate(time)
        if step is not None:
            assert step.command.accepted
            steps.append(step)
        if cueing.mode == mode:
            return time, steps
    pytest.fail(f'never {mode}: {cueing.mode}')


def test_park_is_the_lowest_pose_below_home_within_the_margins():
    cueing = make_cueing()
    park = cueing.park_pose
    home = cueing.geometry.home_pose
    assert_allclose(park[[0, 1, 3, 4, 5]], np.asarray(home)[[0, 1, 3, 4, 5]], atol=0)
    assert park[2] < home[2] - 0.02
    geometry = cueing.limiter.cue_geometry
    assert not pose_violations(geometry, park[:3], np.eye(3))
    lower = park[:3] - [0.0, 0.0, 1e-4]
    assert pose_violations(geometry, lower, np.eye(3))
    # The shortest leg is leg_length_margin (10 mm) inside the stroke's 0.65 m.
    assert_allclose(legs(park).min(), 0.66, atol=1e-5)


def test_soft_stop_brakes_then_parks_within_the_leg_limits_in_the_time_asked():
    cueing = make_cueing(soft_stop_time=2.0)
    steps = stream(cueing, 0.0, 200)
    time = steps[-1].command.time   # one command each PERIOD, on
    assert cueing.stop().success and cueing.mode == STOPPING
    _, stopping = operate_until(cueing, PARKED, time)
    poses = [steps[-1].pose] + [step.pose for step in stopping]
    times = [steps[-1].command.time] + [step.command.time for step in stopping]
    lengths = assert_leg_limits(poses, times)
    assert_allclose(lengths[-1], legs(cueing.park_pose), atol=1e-9)
    assert times[-1] - times[0] >= 2.0
    # Parked: samples are held, nothing moves, the watchdog rests.
    held = cueing.cue(20.0, *drive(20.0), command_time=20.0)
    assert held.pose is None and held.warnings[0].code == 'cueing_held'
    assert cueing.operate(20.1) is None and cueing.watch(25.0) is None


@pytest.mark.parametrize('position', [[0.0, 0.0, 0.0], [0.005, 0.0, 0.41]])
def test_a_tilted_park_is_where_stop_takes_the_platform_within_the_limits(position):
    # park_orientation_deg: a platform that parks tilted (before: always home's orientation).
    cueing = make_cueing(park_orientation_deg=[0.0, 2.0, 0.0], park_position=position,
                         soft_stop_time=1.0)
    park = cueing.park_pose
    assert_allclose(park[3:], [0.0, math.radians(2.0), 0.0], rtol=0.0, atol=1e-15)
    if any(position):
        assert_allclose(park[:3], position, rtol=0.0, atol=0.0)
    else:   # the lowest pose below home so tilted: its shortest leg at the 10 mm margin
        assert_allclose(park[:2], cueing.geometry.home_pose[:2], rtol=0.0, atol=0.0)
        assert_allclose(legs(park).min(), 0.66, atol=1e-5)
    steps = stream(cueing, 0.0, 100)
    assert cueing.stop().success
    _, stopping = operate_until(cueing, PARKED, steps[-1].command.time)
    poses = [steps[-1].pose] + [step.pose for step in stopping]
    times = [steps[-1].command.time] + [step.command.time for step in stopping]
    lengths = assert_leg_limits(poses, times)
    assert_allclose(lengths[-1], legs(park), rtol=0.0, atol=1e-9)
    assert_allclose(stopping[-1].pose, park, rtol=0.0, atol=1e-7)
    started = make_cueing(park_orientation_deg=[0.0, 2.0, 0.0], park_position=position,
                          start_parked=True)
    assert_allclose(started.pose, park, rtol=0.0, atol=1e-12)


@pytest.mark.parametrize('orientation, words', [
    ([0.0, 60.0, 0.0], 'beyond its limits'),
    ([0.0, math.nan, 0.0], 'park_orientation_deg'),
    ([math.inf, 0.0, 0.0], 'park_orientation_deg'),
    ([1e308, 0.0, 0.0], 'park_orientation_deg'),
    ([0.0, 2.0], 'park_orientation_deg'),
    ([], 'park_orientation_deg'),
    ('tilted', 'park_orientation_deg'),
    ([0.0, [2.0], 0.0], 'park_orientation_deg'),
])
def test_a_park_orientation_beyond_the_limits_or_no_angles_is_refused_naming_it(
        orientation, words):
    with pytest.raises(ValueError) as raised:
        make_cueing(park_orientation_deg=orientation)
    message = str(raised.value)
    assert words in message and '\n' not in message, message
    if words == 'beyond its limits':
        assert 'park_orientation_deg [0.0, 60.0, 0.0]' in message


def test_start_parked_then_soft_start_to_neutral_then_cueing():
    cueing = make_cueing(start_parked=True, soft_start_time=2.5)
    assert cueing.mode == PARKED
    assert_allclose(cueing.pose, cueing.park_pose, atol=1e-12)
    assert cueing.cue(0.0, *drive(0.0), command_time=0.0).pose is None
    assert cueing.start().success and cueing.mode == STARTING
    time, starting = operate_until(cueing, CUEING, 0.0)
    poses = [cueing.park_pose] + [step.pose for step in starting]
    times = [starting[0].command.time - PERIOD] + [step.command.time for step in starting]
    lengths = assert_leg_limits(poses, times)
    assert_allclose(lengths[-1], cueing.geometry.home_leg_lengths, atol=1e-9)
    assert times[-1] - times[0] >= 2.5
    steps = stream(cueing, 10.0, 100)
    assert all(step.command.accepted for step in steps)
    assert_leg_limits([poses[-1]] + [step.pose for step in steps],
                      [times[-1]] + [step.command.time for step in steps])


def test_stop_during_start_turns_back_to_park_within_the_limits():
    cueing = make_cueing(start_parked=True, soft_start_time=2.0)
    cueing.start()
    time, steps = 0.0, []
    for _ in range(100):   # half way up, moving
        time += PERIOD
        step = cueing.operate(time)
        if step is not None:
            steps.append(step)
    assert cueing.mode == STARTING
    assert cueing.stop().success and cueing.mode == STOPPING
    assert not cueing.pause().success   # pause during stop: refused, it parks
    assert not cueing.start().success   # start during stop: refused, once parked
    _, stopping = operate_until(cueing, PARKED, time)
    steps += stopping
    lengths = assert_leg_limits([step.pose for step in steps],
                                [step.command.time for step in steps])
    assert_allclose(lengths[-1], legs(cueing.park_pose), atol=1e-9)


# Pause and resume ----------------------------------------------------------------------------

def test_pause_holds_and_resume_goes_on_without_a_jump():
    cueing = make_cueing()
    before = stream(cueing, 0.0, 200)
    assert cueing.pause().success
    time, braking = operate_until(cueing, PAUSED, before[-1].command.time)
    held = cueing.pose
    frozen = cueing.washout.filters.state.copy()
    # Paused: samples held, the watchdog and operate send nothing, the pose stays.
    for k in range(50):
        answer = cueing.cue(3.0 + k * PERIOD, *drive(3.0), command_time=time + k * PERIOD)
        assert answer.pose is None and answer.warnings[0].code == 'cueing_held'
    assert cueing.operate(time + 1.0) is None and cueing.watch(time + 1.0) is None
    assert_allclose(cueing.pose, held, rtol=0, atol=0)
    assert_allclose(cueing.washout.filters.state, frozen, rtol=0, atol=0)
    assert cueing.resume().success and cueing.mode == CUEING
    after = stream(cueing, 5.0, 100)
    # The washout goes on from its frozen state: the first cue is the held one, stepped once
    # over no time (a new time line).
    assert_allclose(after[0].displacement, before[-1].displacement, atol=1e-3)
    steps = before[-1:] + braking + after
    assert all(step.command.accepted for step in steps)
    # Across the resume too: the leg limits hold on the commands' own times.
    poses = [step.pose for step in steps]
    command_times = [step.command.time for step in steps]
    assert_leg_limits(poses, command_times)


def test_the_controls_refuse_what_does_not_follow():
    cueing = make_cueing()
    assert cueing.resume().success   # not paused: nothing to do
    assert cueing.start().success    # cueing already
    assert cueing.stop().success
    assert not cueing.resume().success
    assert not cueing.pause().success
    for moment in (math.nan, math.inf, 'soon', None):
        assert cueing.operate(moment) is None
