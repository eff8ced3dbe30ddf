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
The cue's commands as they are sent (issue 27): within the leg rates whatever the input.

Each test runs :class:`~stewart_kinematics.cueing.MotionCueing` and judges the commands it gives
(the ``target_pose`` numbers, turned into leg lengths by the reference formula, at the times
they are sent) by finite differences computed here: never a stop in one step, never faster
than the limits in the time of the commands, even for a recording played fast.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics.cueing import cue_limiter, MotionCueing
from stewart_kinematics.model.rotations import quaternion_to_matrix
from stewart_kinematics.parameters import read_parameter_files

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
G = 9.80665
VELOCITY_MAX, ACCELERATION_MAX = 0.05, 0.25   # config/example_limits.yaml


def cueing(**overrides):
    """Return the MotionCueing of the shipped files (paper platform, example limits, cueing)."""
    values = read_parameter_files([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml',
                                   CONFIG / 'motion_cueing.yaml'], 'motion_cueing_node')
    values.update(overrides)
    return MotionCueing.from_parameters(values)


def sent_lengths(step):
    """Return the leg lengths of a step's target_pose message, by the reference formula."""
    position, quaternion = step.command.tool_pose
    rotation = quaternion_to_matrix(quaternion / np.linalg.norm(quaternion))
    return reference.leg_lengths_of_matrix(position, rotation)


def rates(times, lengths):
    """Leg velocities and accelerations between consecutive commands (midpoint differences)."""
    times, lengths = np.asarray(times), np.asarray(lengths)
    steps = np.diff(times)
    velocities = np.diff(lengths, axis=0) / steps[:, None]
    spans = 0.5 * (steps[1:] + steps[:-1])
    return velocities, np.diff(velocities, axis=0) / spans[:, None]


def test_noisy_input_never_stops_a_leg_in_one_step():
    """
    Noisy input keeps both rate limits at every command.

    The adversarial pass's input (issue 27): specific force noise of 30 m/s^2 around gravity,
    rotation noise of 5 rad/s, at 100 Hz, for 20 s (the limiter acts in nearly every step). It
    stopped legs at 0.0245 m/s within one 10 ms step (2.45 m/s^2).
    """
    motion = cueing()
    rng = np.random.default_rng(1)
    times, lengths, codes = [], [], set()
    for k in range(2000):
        step = motion.cue(k * 0.01, [0.0, 0.0, G] + rng.normal(0.0, 30.0, 3),
                          rng.normal(0.0, 5.0, 3))
        assert step.command.accepted
        codes |= {finding.code for finding in step.warnings}
        times.append(k * 0.01)
        lengths.append(sent_lengths(step))
    velocities, accelerations = rates(times, lengths)
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-9)
    assert 'limits_held' not in codes


def test_a_follower_whose_forward_kinematics_fails_brakes_instead_of_holding(monkeypatch):
    """
    A follower whose forward kinematics fails brakes; it never holds the pose.

    Forward kinematics failing inside the follower while the actuators limit the cue (the
    noisy input above): braking, never the pose held (a stop in one step); the rates are kept
    throughout (issue 27: the pose was held, warned only as actuator_limited).
    """
    motion = cueing()
    real = cue_limiter.forward_kinematics
    failing = {'now': False, 'count': 0}

    def solve(*arguments, **keywords):
        result = real(*arguments, **keywords)
        if failing['now']:
            failing['count'] += 1
            return type(result)(result.pose, False, 50, 1.0, 'made to fail')
        return result
    monkeypatch.setattr(cue_limiter, 'forward_kinematics', solve)
    times, lengths, codes = [], [], []
    rng = np.random.default_rng(2)
    for k in range(600):
        failing['now'] = 100 <= k < 300
        step = motion.cue(k * 0.01, [0.0, 0.0, G] + rng.normal(0.0, 30.0, 3),
                          rng.normal(0.0, 5.0, 3))
        assert step.command.accepted
        codes += [finding.code for finding in step.warnings]
        times.append(k * 0.01)
        lengths.append(sent_lengths(step))
    assert failing['count'] > 50   # the follower needed forward kinematics, and it failed
    assert 'command_braking' in codes
    velocities, accelerations = rates(times, lengths)
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-9)


@pytest.mark.parametrize('speed_up', [1.0, 10.0])
def test_the_platform_is_paced_by_the_commands_times_not_the_stamps(speed_up):
    """
    The platform is paced by the times its commands are sent, not by the input's stamps.

    A recording (stamps 10 ms apart) played ``speed_up`` times fast: the commands sent every
    10 / speed_up ms keep the leg rates in the time they are sent (issue 27: played ten times
    fast, the legs moved ten times faster than the limits allow).
    """
    motion = cueing()
    times, lengths = [], []
    for k in range(1500):
        stamp = k * 0.01
        force = [6.0 * math.sin(2.0 * stamp), 4.0 * math.cos(3.0 * stamp), G]
        step = motion.cue(stamp, force, [0.0, 0.0, 0.5 * math.sin(stamp)],
                          command_time=stamp / speed_up)
        assert step.command.accepted
        times.append(stamp / speed_up)
        lengths.append(sent_lengths(step))
    velocities, accelerations = rates(times, lengths)
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-9)
    assert np.ptp(np.asarray(lengths), axis=0).max() > 1e-3   # it did move


def test_an_imu_turned_or_in_ned_is_cued_in_the_vehicle_frame():
    """imu_frame in NED axes (roll 180 deg): its vectors, turned, cue exactly as the vehicle's."""
    reference_cue = cueing()
    ned = cueing(imu_frame='imu_ned', imu_orientation_rpy_deg=[180.0, 0.0, 0.0])
    for k in range(200):
        force = np.array([3.0, 1.0, G])
        rate = np.array([0.1, -0.2, 0.3])
        expected = reference_cue.cue(k * 0.01, force, rate, frame_id='base_link')
        flip = np.array([1.0, -1.0, -1.0])   # vehicle (x forward, y left, z up) -> NED
        turned = ned.cue(k * 0.01, force * flip, rate * flip, frame_id='imu_ned')
        assert turned.refusal is None
        assert_allclose(turned.pose, expected.pose, atol=1e-12)
    assert np.abs(expected.pose[:3] - reference_cue.geometry.home_pose[:3]).max() > 1e-3


def test_a_frame_that_cannot_be_placed_is_refused_with_the_reason():
    """An IMU in 'imu_link' with no imu_frame set: refused (wrong_frame), eased toward neutral."""
    motion = cueing()
    step = motion.cue(0.0, [3.0, 0.0, G], [0.0, 0.0, 0.0], frame_id='imu_link')
    assert step.refusal.code == 'wrong_frame'
    assert "'imu_link'" in step.reason and 'base_link' in step.reason
    assert step.command.accepted   # the step at rest is still sent
    assert motion.cue(0.01, [3.0, 0.0, G], [0.0, 0.0, 0.0], frame_id='').refusal is None
