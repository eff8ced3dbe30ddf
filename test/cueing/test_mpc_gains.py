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
Run-time gains with the MPC (cueing_method mpc): intensity and channel gains scale its aim.

Before, every gain change with the MPC was refused ("this washout takes no gain change at run
time"). Independent values: a run at intensity 0.5 against a run at intensity 1 with the aim
halved in the settings (``mpc_force_scale`` and ``rotation_scale``), the leg lengths of the
commands by the leg formula of ``reference``, the QP's constraints before and after a change.
About 10 s for the module.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose, assert_array_equal
import pytest
import reference

from stewart_kinematics.cueing import MotionCueing
from stewart_kinematics.cueing.controls import smoothstep
from stewart_kinematics.cueing.mpc_cueing import MpcCueing
from stewart_kinematics.parameters import read_parameter_file

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml')]
G = 9.80665
PERIOD = 0.01
VELOCITY_MAX, ACCELERATION_MAX = 0.05, 0.25   # example_limits.yaml, per leg


def values(**changes):
    """Return the shipped files' parameters with ``cueing_method: mpc`` and ``changes``."""
    found = {}
    for path in FILES:
        found.update(read_parameter_file(path, 'motion_cueing_node'))
    found['cueing_method'] = 'mpc'
    found.update(changes)
    return found


def drive(time):
    """Return a vehicle's specific force and angular velocity at ``time`` (seconds)."""
    force = [1.5 * math.sin(2.0 * time) + 0.8 * math.sin(5.1 * time),
             1.2 * math.sin(1.3 * time + 0.4), G + 0.6 * math.sin(3.7 * time)]
    rate = [0.2 * math.sin(1.1 * time), 0.15 * math.sin(0.7 * time), 0.3 * math.sin(0.9 * time)]
    return force, rate


def stream(cueing, count, change=None):
    """Cue ``count`` samples of :func:`drive`; ``change(k)`` before sample k."""
    steps = []
    for k in range(count):
        if change is not None:
            change(k)
        time = k * PERIOD
        steps.append(cueing.cue(time, *drive(time), command_time=time))
    return steps


def assert_leg_limits(steps):
    """Every command accepted; leg velocities and accelerations of the poses within limits."""
    assert all(step.command.accepted for step in steps)
    lengths = np.array([reference.leg_lengths(step.pose) for step in steps])
    intervals = np.diff([step.command.time for step in steps])[:, None]
    velocities = np.diff(lengths, axis=0) / intervals
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-6)
    accelerations = np.diff(velocities, axis=0) / intervals[1:]
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-6)


def test_intensity_half_is_the_mpc_run_with_its_aim_halved():
    """cueing_intensity 0.5: the commands at 1 with mpc_force_scale and rotation_scale halved."""
    shipped = values()
    halved = MotionCueing.from_parameters(values(cueing_intensity=0.5))
    aimed = MotionCueing.from_parameters(values(
        mpc_force_scale=[0.5 * x for x in shipped['mpc_force_scale']],
        rotation_scale=[0.5 * x for x in shipped['rotation_scale']]))
    plain = MotionCueing.from_parameters(values())
    assert isinstance(halved.washout, MpcCueing)
    assert_allclose(halved.washout.reference_scale, 0.5 * plain.washout.reference_scale,
                    rtol=1e-15, atol=0.0)
    one, other, full = stream(halved, 150), stream(aimed, 150), stream(plain, 150)
    poses = np.array([step.pose for step in one])
    assert_allclose(poses, np.array([step.pose for step in other]), rtol=0.0, atol=1e-9)
    # Not the run at intensity 1: the gain acted.
    assert np.abs(poses - np.array([step.pose for step in full])).max() > 1e-3


def test_a_ramp_moves_the_aim_smoothly_and_never_jumps_the_commanded_pose():
    """Intensity 1 -> 0.3 over 1 s mid-stream: the aim follows the smoothstep, the pose no jump."""
    cueing = MotionCueing.from_parameters(values(gain_ramp_time=1.0))
    begin, scales = 60, []

    def change(k):
        if k == begin:
            assert cueing.set_gains(intensity=0.3) is None
        scales.append(cueing.washout.reference_scale.copy())

    steps = stream(cueing, 200, change)
    plain = stream(MotionCueing.from_parameters(values()), 200)
    scales = np.array(scales)
    configured = scales[0]
    # The ramp advances with each sample; the aim at sample k is the gain of sample k - 1.
    share = np.array([1.0 - 0.7 * smoothstep((k - begin) / 100.0) for k in range(200)])
    assert_allclose(scales, share[:, None] * configured, rtol=1e-12, atol=1e-15)
    assert_allclose(scales[-1], 0.3 * configured, rtol=1e-12)
    # The aim moves at most 1.5 * 0.7 * dt / T of itself per sample: no step.
    assert np.abs(np.diff(scales, axis=0)).max() <= 1.5 * 0.7 * PERIOD * configured.max() * 1.01
    targets = np.array([step.target for step in steps[1:]])
    natural = np.abs(np.diff(np.array([step.target for step in plain[1:]]), axis=0)).max()
    assert np.abs(np.diff(targets, axis=0)).max() <= 1.05 * natural
    assert_leg_limits(steps)


def test_gains_change_no_limit_and_every_command_keeps_the_limits():
    """The QP's constraints are the same at any gains; a flood of changes keeps the leg limits."""
    cueing = MotionCueing.from_parameters(values(gain_ramp_time=0.3))
    mpc = cueing.washout
    stream(cueing, 20)
    vehicle = mpc._vehicle_input(*drive(0.2))
    before = mpc._problem(vehicle, 0.0)
    mpc.set_gains(np.array([0.1, 2.0, 0.0, 3.0, 0.0, 4.0, 0.0, 1.0]))
    after = mpc._problem(vehicle, 0.0)
    assert np.abs(after[0] - before[0]).max() > 1e-6   # the aim changed ...
    for one, other in zip(before[1:], after[1:]):       # ... no constraint did
        assert_array_equal(one, other)
    rng = np.random.default_rng(11)
    cueing = MotionCueing.from_parameters(values(gain_ramp_time=0.3))
    steps = stream(cueing, 200, lambda k: cueing.set_gains(
        intensity=float(rng.uniform(0.0, 1.0)),
        translation_scale=[float(rng.uniform(0.0, 2.0))] * 3,
        tilt_scale=[float(rng.uniform(0.0, 2.0))] * 2,
        rotation_scale=[float(rng.uniform(0.0, 2.0))] * 3) if k % 7 == 0 else None)
    assert all(np.all(np.isfinite(step.pose)) for step in steps)
    assert_leg_limits(steps)


def test_tilt_gains_fold_into_the_force_aim_weighted_by_the_configured_gains():
    """Force aim x: (translation x + tilt x) over their configured sum; z translation alone."""
    cueing = MotionCueing.from_parameters(values(translation_scale=[0.2, 0.2, 0.4],
                                                 tilt_scale=[0.6, 0.2]))
    mpc = cueing.washout
    force = np.array(values()['mpc_force_scale'])
    mpc.set_gains([0.2, 0.1, 0.1, 0.2, 0.2, 0.5, 0.25, 0.5])
    assert_allclose(mpc.reference_scale,
                    [force[0] * 0.4 / 0.8, force[1] * 0.3 / 0.4, force[2] * 0.25, 0.5, 0.25],
                    rtol=1e-14)
    # A gain configured 0 leaves that axis's aim as configured (no ratio to take).
    zero = MotionCueing.from_parameters(values(translation_scale=[0.2, 0.2, 0.0])).washout
    zero.set_gains([0.1, 0.1, 0.3, 0.1, 0.1, 0.5, 0.5, 0.5])
    assert_allclose(zero.reference_scale[2], force[2], rtol=1e-15)


def test_the_travel_check_skips_what_the_mpc_plans_within_and_checks_its_yaw():
    """Classical refuses translation 2 and roll 5 for the travel; the MPC takes them, not yaw 9."""
    classical = MotionCueing.from_parameters(values(cueing_method='classical'))
    mpc = MotionCueing.from_parameters(values())
    for change in ({'translation_scale': [2.0, 0.2, 0.2]}, {'rotation_scale': [5.0, 5.0, 0.3]}):
        assert 'travel' in classical.gain_refusal(**change).message
        assert mpc.gain_refusal(**change) is None
    yaw = mpc.gain_refusal(rotation_scale=[0.3, 0.3, 9.0])
    assert yaw is not None and 'yaw' in yaw.message and 'travel' in yaw.message
    refused = mpc.gain_refusal(intensity=math.nan)
    assert refused is not None and 'cueing_intensity' in refused.message
