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
Calibration on synthetic hexapods: a true platform, measured with noise, identified back.

The true platform is the paper's with every joint coordinate moved by up to 2 mm and every
actuator offset by up to 5 mm; its "measurements" (poses with 5 um / 10 urad noise, actuator
readings with 1 um noise) come from the leg formula written out below in numpy, not from the
package. A calibration must predict the actuator readings of held-out poses as well as the true
platform does (the noise floor), where the nominal platform is off by millimetres; outliers must
be found by index; degenerate pose sets must be refused with the reason.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics import load_geometry
from stewart_kinematics.analysis.calibration import (
    calibrate,
    calibrated_parameters,
    CalibrationError,
    identifiability,
    load_measurements,
    measurement_poses,
    MIN_POSES,
    PARAMETER_NAMES,
    predict_actuator_positions,
    write_measurements,
    write_parameter_file,
)
from stewart_kinematics.parameters import ACTUATOR_PARAMETERS, check_values, read_parameter_file

pytestmark = pytest.mark.core

NOMINAL_OFFSETS = np.full(6, 0.6)
POSITION_NOISE = 5e-6
ANGLE_NOISE = 10e-6
READING_NOISE = 1e-6
#: Half-widths of the measured poses around home: metres, radians.
POSITION_RANGE = 0.05
ANGLE_RANGE = math.radians(10.0)


def readings(base, platform, offsets, poses):
    """Actuator positions ``|t + R p_i - b_i| - o_i`` in metres, (N, 6)."""
    rotations = reference.rotations_zyx(poses[:, 3:])
    legs = np.einsum('kab,ib->kia', rotations, platform) + poses[:, None, :3] - base
    return np.linalg.norm(legs, axis=-1) - offsets


class Hexapod:
    """A built platform: the nominal one with its joints and offsets a little off."""

    def __init__(self, nominal, seed):
        generator = np.random.default_rng(seed)
        self.generator = generator
        self.base = nominal.base_joints + generator.uniform(-2e-3, 2e-3, (6, 3))
        self.platform = nominal.platform_joints + generator.uniform(-2e-3, 2e-3, (6, 3))
        self.offsets = NOMINAL_OFFSETS + generator.uniform(-5e-3, 5e-3, 6)
        self.parameters = np.concatenate([self.base.ravel(), self.platform.ravel(),
                                          self.offsets])

    def random_poses(self, home, count, position_range=POSITION_RANGE, angle_range=ANGLE_RANGE,
                     mask=(1.0,) * 6):
        """Poses uniform within home +- the ranges (an axis with mask 0 stays at home)."""
        half_width = np.array([position_range] * 3 + [angle_range] * 3) * np.array(mask)
        return home + self.generator.uniform(-1.0, 1.0, (count, 6)) * half_width

    def measure(self, poses):
        """Return the measured poses and the actuator readings at the true poses, with noise."""
        noise = np.concatenate([
            self.generator.normal(0.0, POSITION_NOISE, (len(poses), 3)),
            self.generator.normal(0.0, ANGLE_NOISE, (len(poses), 3))], axis=1)
        exact = readings(self.base, self.platform, self.offsets, poses)
        return poses + noise, exact + self.generator.normal(0.0, READING_NOISE, exact.shape)


def rms(values):
    """Root mean square of every element."""
    return float(np.sqrt(np.mean(np.square(values))))


@pytest.fixture(scope='module')
def nominal(config_directory_path):
    """Return the paper's platform as drawn."""
    return load_geometry(config_directory_path / 'paper_platform.yaml')


@pytest.fixture(scope='module')
def config_directory_path():
    """Return the package's config/ folder (module scope)."""
    from pathlib import Path
    return Path(__file__).resolve().parents[2] / 'config'


def held_out_errors(nominal, hexapod, result, count=300):
    """RMS prediction error on fresh poses: nominal, calibrated, and the true platform's."""
    poses, measured = hexapod.measure(hexapod.random_poses(nominal.home_pose, count))
    nominal_error = predict_actuator_positions(nominal, NOMINAL_OFFSETS, poses) - measured
    calibrated_error = predict_actuator_positions(
        result.geometry, result.actuator_offsets, poses) - measured
    true_error = readings(hexapod.base, hexapod.platform, hexapod.offsets, poses) - measured
    return rms(nominal_error), rms(calibrated_error), rms(true_error)


@pytest.mark.parametrize('seed, count', [(1, 30), (2, 45), (3, 60)])
def test_calibrated_model_predicts_held_out_poses_at_the_noise_floor(nominal, seed, count):
    hexapod = Hexapod(nominal, seed)
    poses, measured = hexapod.measure(hexapod.random_poses(nominal.home_pose, count))
    result = calibrate(nominal, poses, measured, NOMINAL_OFFSETS)

    nominal_rms, calibrated_rms, floor = held_out_errors(nominal, hexapod, result)
    assert nominal_rms > 1e-3  # the drawing is off by millimetres
    # The noise floor (pose noise seen through the legs, plus reading noise) is about 5 um;
    # the calibrated model comes within 25 % of it on poses it never saw.
    assert 3e-6 < floor < 8e-6
    assert calibrated_rms < 1.25 * floor
    assert result.outliers == ()
    assert np.all(result.rms_before > 5 * result.rms_after)
    assert np.all(result.rms_after < 8e-6)
    # The fit's own noise estimate and standard deviations are honest.
    assert 0.7 * floor < result.noise < 1.3 * floor
    errors = (result.parameters - hexapod.parameters) / result.standard_deviations
    assert np.max(np.abs(errors)) < 4.5
    assert result.condition_number < 1e4


def test_noise_free_measurements_give_back_all_42_parameters(nominal):
    # With full poses measured and frames fixed by the measurement, every parameter is
    # identifiable: exact data give the true platform back exactly.
    hexapod = Hexapod(nominal, 4)
    poses = hexapod.random_poses(nominal.home_pose, 30)
    exact = readings(hexapod.base, hexapod.platform, hexapod.offsets, poses)
    result = calibrate(nominal, poses, exact, NOMINAL_OFFSETS)
    assert_allclose(result.parameters, hexapod.parameters, rtol=0.0, atol=1e-9)
    assert_allclose(result.geometry.base_joints, hexapod.base, rtol=0.0, atol=1e-9)
    assert_allclose(result.actuator_offsets, hexapod.offsets, rtol=0.0, atol=1e-9)
    assert result.identifiability.identifiable
    assert len(PARAMETER_NAMES) == 42
    # The calibrated geometry keeps the nominal home pose and limits.
    assert_allclose(result.geometry.home_pose, nominal.home_pose)
    assert result.geometry.leg_length_max == nominal.leg_length_max


def test_unknown_nominal_offsets_are_estimated_from_the_readings(nominal):
    hexapod = Hexapod(nominal, 5)
    poses, measured = hexapod.measure(hexapod.random_poses(nominal.home_pose, 40))
    result = calibrate(nominal, poses, measured)
    assert_allclose(result.actuator_offsets, hexapod.offsets, rtol=0.0, atol=1e-3)
    assert held_out_errors(nominal, hexapod, result)[1] < 8e-6


def test_outliers_are_found_by_index_and_do_not_spoil_the_fit(nominal):
    hexapod = Hexapod(nominal, 6)
    poses, measured = hexapod.measure(hexapod.random_poses(nominal.home_pose, 50))
    # Mis-read tracker points (one grossly, by 50 mm) and glitching actuator readings.
    poses[3, 0] += 0.05
    poses[7, 0] += 2e-3
    poses[19, 4] += 1e-3
    poses[33, 2] -= 0.5e-3
    measured[41, 3] += 0.3e-3
    measured[45, 0] -= 0.02
    result = calibrate(nominal, poses, measured, NOMINAL_OFFSETS)
    assert result.outliers == (3, 7, 19, 33, 41, 45)
    assert not result.inliers[[3, 7, 19, 33, 41, 45]].any() and result.inliers.sum() == 44
    nominal_rms, calibrated_rms, floor = held_out_errors(nominal, hexapod, result)
    assert calibrated_rms < 1.25 * floor
    assert 'outliers: [3, 7, 19, 33, 41, 45]' in result.report()

    # Plain least squares is pulled off by the small ones, and refuses the gross ones.
    small = np.ones(len(poses), dtype=bool)
    small[[3, 45]] = False
    plain = calibrate(nominal, poses[small], measured[small], NOMINAL_OFFSETS, loss='linear')
    assert plain.outliers == ()
    assert held_out_errors(nominal, hexapod, plain)[1] > 3 * floor
    with pytest.raises(CalibrationError, match='does not fit.*set the outliers aside'):
        calibrate(nominal, poses, measured, NOMINAL_OFFSETS, loss='linear')


def test_too_few_poses_are_refused(nominal):
    hexapod = Hexapod(nominal, 7)
    poses, measured = hexapod.measure(hexapod.random_poses(nominal.home_pose, MIN_POSES - 1))
    with pytest.raises(CalibrationError, match='too few poses: 7 given, at least 8'):
        calibrate(nominal, poses, measured, NOMINAL_OFFSETS)


@pytest.mark.parametrize('case, mask, position_range, angle_range, expected', [
    ('no rotation', (1, 1, 1, 0, 0, 0), POSITION_RANGE, ANGLE_RANGE,
     ['cannot determine 18 parameter combination', 'never rotate the platform',
      '+0.71 b2.y +0.71 p2.y']),
    ('yaw only', (1, 1, 1, 0, 0, 1), POSITION_RANGE, ANGLE_RANGE,
     ['cannot determine 6 parameter combination', 'never turn alpha, beta',
      'b1.z', 'p1.z']),
    ('all nearly one pose', (1,) * 6, 2e-4, 1e-3,
     ['cannot determine', 'poses span 0.', 'in X, Y, Z']),
])
def test_degenerate_pose_sets_are_named(nominal, case, mask, position_range, angle_range,
                                        expected):
    hexapod = Hexapod(nominal, 8)
    poses, measured = hexapod.measure(
        hexapod.random_poses(nominal.home_pose, 40, position_range, angle_range, mask))
    exact = poses.copy()
    exact[:, 3:] = np.where(np.array(mask[3:]) == 0, nominal.home_pose[3:], poses[:, 3:])
    with pytest.raises(CalibrationError) as raised:
        calibrate(nominal, exact, measured, NOMINAL_OFFSETS)
    for text in expected:
        assert text in str(raised.value), case
    assert not identifiability(nominal, exact).identifiable


def test_data_the_model_cannot_fit_are_refused(nominal):
    # Readings in millimetres instead of metres.
    hexapod = Hexapod(nominal, 9)
    poses, measured = hexapod.measure(hexapod.random_poses(nominal.home_pose, 40))
    with pytest.raises(CalibrationError, match='check the units'):
        calibrate(nominal, poses, measured * 1e3)
    # A third of the poses spoilt is not a few outliers.
    spoilt = measured.copy()
    spoilt[::3, 0] += 5e-4
    with pytest.raises(CalibrationError, match='14 of 40 poses do not fit the model'):
        calibrate(nominal, poses, spoilt, NOMINAL_OFFSETS)


def test_measurement_poses_beat_random_ones_and_stay_within_limits(config_directory_path):
    limited = load_geometry([config_directory_path / 'paper_platform.yaml',
                             config_directory_path / 'example_limits.yaml'])
    selection = measurement_poses(limited, 30, position_range=0.08,
                                  angle_range=math.radians(15.0), candidates=600, seed=1)
    assert selection.poses.shape == (30, 6)
    assert len({tuple(pose) for pose in selection.poses}) == 30
    from stewart_kinematics.limits import check_poses
    assert not any(check_poses(limited, selection.poses))
    assert selection.improvement > 1.5
    assert selection.condition_number < selection.random_condition_number
    again = measurement_poses(limited, 30, position_range=0.08,
                              angle_range=math.radians(15.0), candidates=600, seed=1)
    assert_allclose(again.poses, selection.poses)
    # The proposed poses calibrate the platform.
    hexapod = Hexapod(limited, 10)
    poses, measured = hexapod.measure(selection.poses)
    result = calibrate(limited, poses, measured, NOMINAL_OFFSETS)
    assert held_out_errors(limited, hexapod, result)[1] < 8e-6
    with pytest.raises(ValueError, match='at least 8'):
        measurement_poses(limited, 5)


def test_calibrated_parameter_file_loads_as_the_calibrated_geometry(tmp_path,
                                                                    config_directory_path):
    # A tool frame (pivot point) off the platform frame's origin: kept as it is, while the
    # joints, in the platform frame, are the calibrated ones.
    values = read_parameter_file(config_directory_path / 'paper_platform.yaml')
    values.update(read_parameter_file(config_directory_path / 'example_limits.yaml'))
    values['tool_frame_position'] = [0.01, -0.02, 0.25]
    nominal_file = tmp_path / 'nominal.yaml'
    write_parameter_file(nominal_file, values)
    nominal = load_geometry(nominal_file)
    hexapod = Hexapod(nominal, 11)
    poses, measured = hexapod.measure(hexapod.random_poses(nominal.home_pose, 40))
    result = calibrate(nominal, poses, measured, NOMINAL_OFFSETS)

    path = tmp_path / 'calibrated.yaml'
    write_parameter_file(path, calibrated_parameters(result, values), 'calibrated\nby a test')
    text = path.read_text()
    assert text.startswith('# calibrated\n# by a test\n/**:\n  ros__parameters:\n')
    loaded = load_geometry(path)
    assert_allclose(loaded.base_joints, result.geometry.base_joints, rtol=0.0, atol=1e-15)
    assert_allclose(loaded.platform_joints, result.geometry.platform_joints, rtol=0.0,
                    atol=1e-15)
    assert_allclose(loaded.home_pose, nominal.home_pose, rtol=0.0, atol=1e-15)
    assert loaded.leg_length_max == 0.9 and loaded.max_jacobian_condition == 50.0
    written = read_parameter_file(path)
    assert written['tool_frame_position'] == [0.01, -0.02, 0.25]
    assert written['base_frame'] == 'stewart_base'
    check_values(ACTUATOR_PARAMETERS, written)  # floats written as floats
    assert_allclose(written['actuator_offsets'], result.actuator_offsets, rtol=0.0, atol=0.0)

    # Floats without a dot in Python's repr (1e-05) still load as floats, not strings.
    tiny = tmp_path / 'tiny.yaml'
    write_parameter_file(tiny, {'leg_length_min': 1e-05, 'actuator_offsets': [1e-05] * 6})
    check_values(ACTUATOR_PARAMETERS, read_parameter_file(tiny))
    assert read_parameter_file(tiny)['leg_length_min'] == 1e-05
    # A subnormal number is written 0.0: rcl (strtod, ERANGE) would read it as a string.
    write_parameter_file(tiny, {'leg_length_min': 5e-324, 'actuator_offsets': [-1e-310] * 6})
    assert read_parameter_file(tiny) == {'leg_length_min': 0.0, 'actuator_offsets': [0.0] * 6}


def test_measurement_files_round_trip_and_bad_ones_are_named(tmp_path):
    generator = np.random.default_rng(12)
    poses, positions = generator.normal(size=(5, 6)), generator.normal(size=(5, 6))
    path = tmp_path / 'measurements.csv'
    write_measurements(path, poses, positions, 'five poses')
    read_poses, read_positions = load_measurements(path)
    assert_allclose(read_poses, poses, rtol=0.0, atol=0.0)
    assert_allclose(read_positions, positions, rtol=0.0, atol=0.0)

    path.write_text('X,Y,Z,alpha,beta,gamma,actuator_1\n0,0,0,0,0,0,0\n')
    with pytest.raises(ValueError, match='missing column.*actuator_2'):
        load_measurements(path)
    header = 'index, X, Y, Z, alpha, beta, gamma, ' + ', '.join(
        f'actuator_{leg}' for leg in range(1, 7))
    path.write_text(header + '\n1' + ', 0.0' * 12 + '\n2, 0.0, zero' + ', 0.0' * 10 + '\n')
    with pytest.raises(ValueError, match="line 3: Y must be a number, got 'zero'"):
        load_measurements(path)


def test_calibration_is_exported_but_scipy_loads_only_when_used():
    import subprocess
    import sys
    code = ('import sys, stewart_kinematics\n'
            "assert 'scipy' not in sys.modules, 'importing the package loaded scipy'\n"
            'from stewart_kinematics import calibrate, CalibrationError, measurement_poses\n'
            "assert 'scipy' in sys.modules and calibrate.__module__.endswith('calibration')\n")
    completed = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                               timeout=60)
    assert completed.returncode == 0, completed.stderr
