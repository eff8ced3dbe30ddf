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
Benchmark the motion core: whole-trajectory checks, toppra retiming, the ruckig filter.

Run with ``.venv/bin/python benchmarks/motion_benchmark.py`` (no ROS needed). Prints one
table of medians with ratios against baselines measured in the same process, the targets of
the motion issue (checking and retiming a 10 s trajectory of 100 waypoints at 1 kHz under
100 ms; the streaming filter under 50 us per command), and the duration of the paper's Table 3
ramp before and after retiming under config/example_limits.yaml.

The 10 s trajectory: 100 waypoints on slow waves around the home pose (up to 3 cm and 14
degrees), within every example limit as timed, so that the check runs over all 10,001
samples. Baselines: the per-pose :func:`stewart_kinematics.limits.check_pose` over the same
samples (what a check without vectorisation costs), and one single-pose inverse kinematics
call (the per-message work of ik_node) for the filter.
"""

import math
from pathlib import Path
import platform
import statistics
import sys
import time

import numpy as np

from stewart_kinematics import (
    check_trajectory,
    CommandFilter,
    inverse_kinematics,
    limits,
    load_geometry,
    plan_motion,
    PoseTrajectory,
    Ramp,
    retime,
    TimedTrajectory,
)
from stewart_kinematics.parameters import (
    actuator_limits_from_settings,
    GeometrySettings,
    load_settings,
)

ROOT = Path(__file__).resolve().parent.parent
CONFIG = [ROOT / 'config' / 'paper_platform.yaml', ROOT / 'config' / 'example_limits.yaml']
VALIDATION_RATE = 1000.0
CHECK_TARGET = 0.100   # seconds: check and retime
FILTER_TARGET = 50e-6  # seconds per command
COMMAND_PERIOD = 0.002


def median_time(function, repeats):
    """Return the median wall time of ``function()`` over ``repeats`` calls, seconds."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def ten_second_trajectory(geometry):
    """Build 100 waypoints over 10 s, within the example limits as timed."""
    times = np.linspace(0.0, 10.0, 100)
    # 1 - cos(k pi t / 10): at rest at both ends, as the interpolation starts and ends.
    amplitudes = np.array([0.015, 0.015, 0.01, math.radians(4.0), math.radians(4.0),
                           math.radians(7.0)])
    harmonics = np.array([2, 3, 1, 2, 3, 1])
    wave = amplitudes * (1.0 - np.cos(np.outer(times, harmonics) * math.pi / 10.0))
    return PoseTrajectory.from_poses(times, geometry.home_pose + wave)


def table_3_path():
    """Build the paper's Table 3, one row a second, as the ramp plays it in 'table' mode."""
    rows = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0]).rows
    return PoseTrajectory.from_poses(np.arange(11.0), rows)


def main() -> int:
    """Print the table; return 0."""
    geometry = load_geometry(CONFIG)
    actuator_limits = actuator_limits_from_settings(load_settings(GeometrySettings, CONFIG))
    path = ten_second_trajectory(geometry)
    given = TimedTrajectory.as_given(path)
    retime(path, geometry, actuator_limits)  # import toppra and scipy before timing

    rows = []
    check = check_trajectory(given, geometry, actuator_limits, validation_rate=VALIDATION_RATE)
    assert check.accepted, check.reason
    check_time = median_time(lambda: check_trajectory(
        given, geometry, actuator_limits, validation_rate=VALIDATION_RATE), 7)
    samples = given.sample_times(VALIDATION_RATE)
    poses = given.sample(samples)
    baseline_samples = samples[::10]
    baseline_poses = given.sample(baseline_samples)

    def per_pose_check():
        for position, rotation in zip(baseline_poses.positions, baseline_poses.rotations):
            limits.check_pose(geometry, position, rotation)
    baseline_time = median_time(per_pose_check, 3) * samples.shape[0] / baseline_samples.shape[0]
    retime_time = median_time(lambda: retime(path, geometry, actuator_limits), 7)
    plan = plan_motion(path, geometry, actuator_limits, retime_path=True,
                       validation_rate=VALIDATION_RATE)
    assert plan.accepted, plan.reason
    plan_time = median_time(lambda: plan_motion(path, geometry, actuator_limits,
                                                retime_path=True,
                                                validation_rate=VALIDATION_RATE), 7)
    rows.append(('check 10 s as timed, 10,001 samples, every limit', check_time,
                 f'{baseline_time / check_time:.0f}x faster than check_pose per sample '
                 f'({baseline_time * 1e3:.0f} ms)'))
    rows.append(('retime (toppra) 100 waypoints', retime_time,
                 f'{plan.trajectory.duration:.2f} s retimed'))
    rows.append(('check as timed + retime', check_time + retime_time,
                 f'target < {CHECK_TARGET * 1e3:.0f} ms'))
    rows.append(('plan_motion(retime): retime, stretch, check '
                 f'{plan.check.samples:,} samples', plan_time, ''))
    del poses

    command_filter = CommandFilter(actuator_limits, COMMAND_PERIOD, geometry.home_leg_lengths)
    rng = np.random.default_rng(0)
    targets = geometry.home_leg_lengths + rng.uniform(-0.02, 0.02, size=(200, 6))

    def stream():
        for index in range(10000):
            if index % 50 == 0:
                command_filter.set_target(targets[index // 50])
            command_filter.step()
    filter_time = median_time(stream, 3) / 10000
    home = geometry.home_pose
    ik_time = median_time(lambda: [inverse_kinematics(geometry, home) for _ in range(10000)],
                          3) / 10000
    rows.append(('streaming filter, per command (ruckig, 6 legs)', filter_time,
                 f'{filter_time / ik_time:.2f}x one single-pose IK ({ik_time * 1e6:.1f} us); '
                 f'target < {FILTER_TARGET * 1e6:.0f} us'))

    print(f'Motion benchmark: Python {platform.python_version()}, numpy {np.__version__}, '
          f'{platform.machine()}')
    print(f'{"What":<62} {"Median":>10}  Compared')
    for what, seconds, compared in rows:
        shown = f'{seconds * 1e3:.1f} ms' if seconds >= 1e-3 else f'{seconds * 1e6:.1f} us'
        print(f'{what:<62} {shown:>10}  {compared}')

    print()
    print(f'{"Target":<62} {"Met":>10}  This run')
    met = check_time + retime_time < CHECK_TARGET
    print(f'{"check + retime of 10 s, 100 waypoints, 1 kHz < 100 ms":<62} '
          f'{"yes" if met else "no":>10}  {(check_time + retime_time) * 1e3:.1f} ms')
    met = filter_time < FILTER_TARGET
    print(f'{"streaming filter < 50 us per command":<62} {"yes" if met else "no":>10}  '
          f'{filter_time * 1e6:.1f} us')

    print()
    ramp = table_3_path()
    ramp_given = plan_motion(ramp, geometry, actuator_limits)
    ramp_retimed = plan_motion(ramp, geometry, actuator_limits, retime_path=True)
    print('Table 3 ramp under config/example_limits.yaml '
          f'(leg_velocity_max {actuator_limits.velocity_max:g} m/s, leg_acceleration_max '
          f'{actuator_limits.acceleration_max:g} m/s^2)')
    for name, plan in (('rows 1 s apart, interpolated', ramp_given),
                       ('retimed (toppra)', ramp_retimed)):
        print(f'  {name:<34} {plan.trajectory.duration:6.2f} s, peak leg velocity '
              f'{plan.check.peak_velocity_ratio * 100:5.1f} % and acceleration '
              f'{plan.check.peak_acceleration_ratio * 100:5.1f} % of the limits')
    return 0


if __name__ == '__main__':
    sys.exit(main())
