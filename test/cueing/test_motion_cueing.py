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
MotionCueing as a decision: what it refuses and why, the time it keeps, reset and rest.

The node calls :meth:`MotionCueing.cue` for every message and :meth:`MotionCueing.reset` for
the reset service; these tests are the node's behaviour without rclpy.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import ActuatorLimits, load_geometry
from stewart_kinematics.cueing import CueingSettings, MotionCueing
from stewart_kinematics.findings import INPUT_GAP, INVALID_VEHICLE_MOTION, TIME_NOT_INCREASING
from stewart_kinematics.parameters import read_parameter_file

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml')]
G = 9.80665
REST = [0.0, 0.0, G]
STILL = [0.0, 0.0, 0.0]
LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)


@pytest.fixture
def cueing():
    """Build the node's core as motion_cueing_node builds it from the shipped files."""
    values = {}
    for path in FILES:
        values.update(read_parameter_file(path, 'motion_cueing_node'))
    return MotionCueing.from_parameters(values)


def off_home(cueing, pose):
    """Distance of a pose from home: metres, and the largest angle in degrees."""
    home = cueing.geometry.home_pose
    return (float(np.linalg.norm(pose[:3] - home[:3])),
            float(np.degrees(np.max(np.abs(pose[3:] - home[3:])))))


def lean(cueing, seconds=6.0, rate=100.0):
    """Drive a sustained left turn (4 m/s^2) until the platform has moved; return the time."""
    time = 0.0
    for _ in range(int(seconds * rate)):
        time += 1.0 / rate
        cueing.cue(time, [1.0, 4.0, G], [0.0, 0.0, 0.2])
    assert off_home(cueing, cueing.pose)[1] > 1.0
    return time


@pytest.mark.parametrize('force, rate, fragment', [
    ([math.nan, 0.0, G], STILL, 'specific_force must be finite'),
    ([0.0, math.inf, G], STILL, 'specific_force must be finite'),
    ([200.0, 0.0, G], STILL, 'beyond 100 m/s^2'),
    ([1e308, 1e308, 1e308], STILL, 'of magnitude 1.73205e+308 m/s^2 is beyond'),
    ([0.0, G], STILL, 'specific_force must have shape'),
    ('down', STILL, 'specific_force'),
    (REST, [0.0, 0.0, 25.0], 'angular_velocity of magnitude 25'),
    (REST, [0.0, -math.inf, 0.0], 'angular_velocity must be finite'),
    (REST, [[0.0], [0.0], [0.0]], 'angular_velocity must have shape'),
])
def test_bad_samples_are_refused_with_the_reason(cueing, force, rate, fragment):
    """cue() refuses and says why; step() raises ValueError with the same words."""
    cueing.cue(0.0, REST, STILL)
    result = cueing.cue(0.01, force, rate)
    assert not result.accepted
    assert result.refusal.code == INVALID_VEHICLE_MOTION
    assert fragment in result.reason
    assert result.pose is not None and np.all(np.isfinite(result.pose))
    with pytest.raises(ValueError, match=fragment.split(' ')[0]):
        cueing.step(0.02, force, rate)


@pytest.mark.parametrize('time', [0.5, 0.49, math.nan, math.inf, 'soon'])
def test_times_that_do_not_move_forward_are_refused_and_nothing_moves(cueing, time):
    """A repeated, backward or non-finite time: refused, pose None, the state unchanged."""
    cueing.cue(0.0, REST, STILL)
    cueing.cue(0.5, [2.0, 0.0, G], STILL)
    before = cueing.pose
    result = cueing.cue(time, [2.0, 0.0, G], STILL)
    assert result.refusal.code == TIME_NOT_INCREASING and result.pose is None
    assert_allclose(cueing.pose, before, atol=0.0)
    assert cueing.time == 0.5
    assert cueing.cue(0.51, [2.0, 0.0, G], STILL).accepted


def test_a_backward_stamp_of_minus_1e308_is_refused_in_one_short_line(cueing):
    """The refusal writes the times readably: 1e308 in nine digits, a stamp to the nanosecond."""
    cueing.cue(1732000000.5, REST, STILL)
    result = cueing.cue(-1e308, REST, STILL)
    assert result.refusal.code == TIME_NOT_INCREASING
    assert 'time -1e+308 s does not come after the previous sample (1732000000.500000000 s)' \
        in result.reason
    assert len(result.reason) < 200


def test_bad_input_eases_the_platform_back_to_neutral(cueing):
    """A stream of NaN after a sustained turn: every sample refused, the platform glides home."""
    time = lean(cueing)
    poses, lengths = [], []
    for _ in range(1500):
        time += 0.01
        result = cueing.cue(time, [math.nan, 0.0, G], STILL)
        assert result.refusal.code == INVALID_VEHICLE_MOTION
        poses.append(result.pose)
        lengths.append(result.lengths)
    distance, angle = off_home(cueing, poses[-1])
    assert distance < 1e-3 and angle < 0.1
    velocities = np.diff(np.array(lengths), axis=0) / 0.01
    assert np.max(np.abs(velocities)) <= 0.05 * (1.0 + 1e-9)
    assert np.max(np.abs(np.diff(velocities, axis=0))) / 0.01 <= 0.25 * (1.0 + 1e-9)


def test_reset_washes_out_to_neutral_within_the_limits(cueing):
    """reset() mid-turn: the platform glides home while the vehicle is at rest, no jump."""
    time = lean(cueing)
    cueing.reset()
    poses, lengths = [], []
    for _ in range(1000):
        time += 0.01
        result = cueing.cue(time, REST, STILL)
        poses.append(result.pose)
        lengths.append(result.lengths)
    assert off_home(cueing, poses[-1])[0] < 1e-3 and off_home(cueing, poses[-1])[1] < 0.1
    velocities = np.diff(np.array(lengths), axis=0) / 0.01
    assert np.max(np.abs(velocities)) <= 0.05 * (1.0 + 1e-9)
    assert np.max(np.abs(np.diff(velocities, axis=0))) / 0.01 <= 0.25 * (1.0 + 1e-9)


def test_reset_settles_on_the_next_sample(cueing):
    """After reset the washout starts from the next sample's steady state: no onset cue."""
    time = lean(cueing)
    cueing.reset()
    result = cueing.cue(time + 0.01, [1.0, 4.0, G], [0.0, 0.0, 0.2])
    assert_allclose(result.displacement, 0.0, atol=1e-12)
    # The tilt starts again from neutral: one step at the acceleration limit.
    limit = cueing.settings.tilt_acceleration_max * 0.01 * 0.01
    assert np.all(np.abs(result.tilt) <= limit * (1.0 + 1e-12))


def test_a_gap_counts_as_max_input_gap(cueing):
    """Five seconds without samples: one input_gap warning, the washout advances 0.1 s only."""
    twin = MotionCueing(cueing.geometry, cueing.settings, cueing.actuator_limits)
    for machine in (cueing, twin):
        machine.cue(0.0, REST, STILL)
        machine.cue(0.01, [2.0, 0.0, G], STILL)
    gapped = cueing.cue(5.01, [2.0, 0.0, G], STILL)
    plain = twin.cue(0.11, [2.0, 0.0, G], STILL)
    assert [w.code for w in gapped.warnings].count(INPUT_GAP) == 1
    assert 'max_input_gap' in gapped.warnings[0].message
    assert_allclose(gapped.displacement, plain.displacement, atol=1e-15)
    assert_allclose(gapped.pose, plain.pose, atol=1e-15)


def test_rest_eases_home_when_no_input_comes(cueing):
    """rest(dt), as the node's input watchdog calls it, brings the platform home."""
    lean(cueing)
    for _ in range(1500):
        result = cueing.rest(0.01)
    distance, angle = off_home(cueing, result.pose)
    assert distance < 1e-3 and angle < 0.1
    for dt in (0.0, -0.01, math.nan, math.inf):
        with pytest.raises(ValueError, match='dt'):
            cueing.rest(dt)


def test_first_sample_is_home_and_perception_follows_three_samples_later(cueing):
    """The platform starts at home; the felt force comes one sample behind, from the third."""
    first = cueing.cue(10.0, REST, STILL)
    assert_allclose(first.pose, cueing.geometry.home_pose, atol=0.0)
    assert first.perceived is None
    assert cueing.cue(10.01, REST, STILL).perceived is None
    label, force = cueing.cue(10.02, REST, STILL).perceived
    assert label == 10.01
    assert_allclose(force, REST, atol=1e-9)


def test_from_parameters_names_a_bad_value():
    """A cueing parameter out of range is refused with its name, as the node would."""
    values = read_parameter_file(FILES[0])
    with pytest.raises(ValueError, match='tilt_rate_max_deg'):
        MotionCueing.from_parameters({**values, 'tilt_rate_max_deg': -3.0})
    with pytest.raises(ValueError, match='translation_frequency'):
        MotionCueing.from_parameters({**values, 'translation_frequency': [1.0, 1.0]})


def test_defaults_of_the_parameters_are_the_settings_defaults():
    """The declared defaults build exactly CueingSettings() (one set of literature values)."""
    from stewart_kinematics.parameters import defaults, MOTION_CUEING_PARAMETERS
    assert CueingSettings.from_parameters(defaults(MOTION_CUEING_PARAMETERS)) == CueingSettings()


def test_without_limits_files_the_cueing_still_runs():
    """The paper's platform alone (no limits at all) with the literature defaults."""
    cueing = MotionCueing(load_geometry(FILES[0]), CueingSettings(), LIMITS)
    for k in range(100):
        assert cueing.cue(k * 0.01, [3.0, -2.0, G], [0.1, 0.0, 0.3]).accepted


@pytest.mark.parametrize('huge', [1e308, 1e200])
def test_rest_with_a_huge_dt_still_eases_home(cueing, huge):
    """
    A rest of 1e308 s (finite: allowed) must not freeze the command clock or overflow.

    Before, the command clock moved by dt: 1e308 left it where later steps of 0.01 s no longer
    moved it, and the platform stayed off home for ever.
    """
    cueing.start()
    for k in range(100):
        step = cueing.cue(k * 0.01, [1.0, 0.0, G], STILL)
    off_before = off_home(cueing, step.pose)[0]
    assert off_before > 1e-3
    cueing.rest(huge)
    for _ in range(3000):
        step = cueing.rest(0.01)
        assert np.all(np.isfinite(step.pose))
    assert off_home(cueing, step.pose)[0] < 0.1 * off_before
