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
Benchmark calibration: the time to calibrate from 50 poses, against baselines in the same run.

The documentation's worked example platform (the paper's, joints moved by up to 2 mm, offsets by
up to 5 mm), measured at 50 poses with 5 um / 10 urad tracker noise, 1 um actuator noise and two
spoilt measurements. Timed, medians of repeated runs:

- ``calibrate`` as shipped (robust loss, outlier rejection, final fit, standard deviations);
- ``calibrate`` with ``loss='linear'`` (one plain fit, no outlier rejection);
- the baseline: the same plain fit with scipy's ``least_squares`` differentiating the model
  by finite differences (its default), instead of the analytic identification Jacobian;
- ``measurement_poses`` choosing the 50 poses from 2000 candidates.

Each row gives the held-out RMS error of the result on 200 further poses (the noise floor is
about 5.5 um). Run: ``.venv/bin/python benchmarks/calibration_benchmark.py``.
"""

import argparse
import math
from pathlib import Path
import platform
import statistics
import sys
import tempfile
import time

import numpy as np
from scipy.optimize import least_squares

from stewart_kinematics.analysis.calibration import (
    calibrate,
    load_measurements,
    measurement_poses,
    predict_actuator_positions,
)
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import load_geometry

ROOT = Path(__file__).resolve().parent.parent
# The documentation's worked example lives in scripts/, outside the installed package.
sys.path.insert(0, str(ROOT / 'scripts'))
import calibration_example  # noqa: E402,I100


def median_time(function, repeats):
    """Return the median wall time of ``function()`` over ``repeats`` calls, and its result."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def finite_difference_fit(nominal, poses, readings, offsets):
    """Plain least squares on the same model, with scipy's finite-difference Jacobian."""
    rotations = euler_zyx_to_matrix(poses[:, 3:])

    def residuals(x):
        base, platform_joints = x[:18].reshape(6, 3), x[18:36].reshape(6, 3)
        legs = np.einsum('kab,ib->kia', rotations, platform_joints) + poses[:, None, :3] - base
        return (np.linalg.norm(legs, axis=-1) - x[36:] - readings).ravel()

    x0 = np.concatenate([nominal.base_joints.ravel(), nominal.platform_joints.ravel(), offsets])
    x = least_squares(residuals, x0, x_scale='jac').x
    return Geometry(x[:18].reshape(6, 3), x[18:36].reshape(6, 3), nominal.home_pose), x[36:]


def main(argv=None) -> int:
    """Run the benchmark and print its table; return the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.strip().split('\n\n')[0])
    parser.add_argument('--repeats', type=int, default=20, help='runs per timing')
    arguments = parser.parse_args(argv)
    config = ROOT / 'config'
    with tempfile.TemporaryDirectory() as folder:
        paths = calibration_example.write_example(Path(folder), config)
        poses, readings = load_measurements(paths['measurements.csv'])
        held_out = load_measurements(paths['validation.csv'])
    nominal = load_geometry([config / 'paper_platform.yaml', config / 'example_limits.yaml'])
    offsets = np.full(6, calibration_example.NOMINAL_OFFSET)

    def held_out_rms(geometry, calibrated_offsets):
        error = predict_actuator_positions(geometry, calibrated_offsets, held_out[0]) \
            - held_out[1]
        return math.sqrt(float(np.mean(np.square(error))))

    rows = []
    baseline_time, (geometry, fitted) = median_time(
        lambda: finite_difference_fit(nominal, poses, readings, offsets), arguments.repeats)
    rows.append(('least_squares, finite-difference Jacobian (baseline)', baseline_time,
                 held_out_rms(geometry, fitted)))
    for label, loss in (('calibrate, plain (loss=linear)', 'linear'),
                        ('calibrate as shipped (soft_l1, outliers, final fit)', 'soft_l1')):
        elapsed, result = median_time(
            lambda loss=loss: calibrate(nominal, poses, readings, offsets, loss=loss),
            arguments.repeats)
        rows.append((label, elapsed, held_out_rms(result.geometry, result.actuator_offsets)))
    selection_time, _ = median_time(
        lambda: measurement_poses(nominal, 50, position_range=calibration_example.POSITION_RANGE,
                                  angle_range=calibration_example.ANGLE_RANGE, seed=1),
        max(1, arguments.repeats // 10))

    print(f'Calibration from {poses.shape[0]} poses; {platform.python_implementation()} '
          f'{platform.python_version()}, numpy {np.__version__}, '
          f'scipy {sys.modules["scipy"].__version__}; median of {arguments.repeats} runs')
    print(f'{"Solver":55s} {"median":>10s} {"vs baseline":>12s} {"held-out RMS":>13s}')
    for label, elapsed, error in rows:
        print(f'{label:55s} {elapsed * 1e3:8.1f} ms {baseline_time / elapsed:10.2f}x '
              f'{error * 1e6:10.2f} um')
    print(f'{"measurement_poses: 50 of 2000 candidates":55s} {selection_time * 1e3:8.1f} ms')
    return 0


if __name__ == '__main__':
    sys.exit(main())
