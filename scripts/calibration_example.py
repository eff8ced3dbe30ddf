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
The calibration example of doc/calibration.md: measurements of a synthetic built hexapod.

The "built" platform is the paper's with every joint coordinate moved by up to 2 mm and every
actuator's zero by up to 5 mm (seeded, so the files are the same every time). It is measured
at the 50 poses that ``measurement_poses`` proposes within the example limits, with a tracker
noise of 5 um and 10 urad and an actuator noise of 1 um; two measurements are spoilt (a
mis-read tracker point, a glitching actuator). Writes to the output folder:

- ``measurements.csv``: the 50 measurements, for ``stewart_calibrate``;
- ``validation.csv``: 200 further random poses, for ``--validate``;
- ``nominal_actuators.yaml``: the drawing's actuator offsets (0.65 m), a parameter file to
  layer on the nominal geometry;
- ``true_platform.yaml``: the built platform's real parameters, to compare with the result.

Run ``python scripts/calibration_example.py OUTPUT_DIR``; after calibrating,
``... OUTPUT_DIR --check calibrated.yaml`` drives the built platform with the nominal and the
calibrated model and prints the pose errors it reaches.
"""

import argparse
from dataclasses import replace
import math
from pathlib import Path
import sys

import numpy as np

from stewart_kinematics.analysis.calibration import measurement_poses, predict_actuator_positions
from stewart_kinematics.analysis.calibration_files import (
    load_measurements,
    write_measurements,
    write_parameter_file,
)
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, rotation_angle_between
from stewart_kinematics.parameters import load_geometry, ParameterFileError, read_parameter_file
from stewart_kinematics.tools.cli_arguments import check_output_paths, refuse_parameter_file
from stewart_kinematics.tools.ramp_demo import default_config_directory

SEED = 2026
NOMINAL_OFFSET = 0.65
JOINT_ERROR = 2e-3
OFFSET_ERROR = 5e-3
POSITION_NOISE = 5e-6
ANGLE_NOISE = 10e-6
READING_NOISE = 1e-6
POSE_COUNT = 50
VALIDATION_COUNT = 200
POSITION_RANGE = 0.06
ANGLE_RANGE = math.radians(12.0)
#: The spoilt measurements: a tracker point mis-read by 1.5 mm in Y, and an actuator reading
#: off by 0.4 mm.
MISREAD_POSE, MISREAD_ERROR = 12, 1.5e-3
GLITCH_POSE, GLITCH_LEG, GLITCH_ERROR = 31, 3, 0.4e-3


def write_example(directory: Path, config_directory: Path) -> dict:
    """Write the example's files into ``directory``; return their paths by name."""
    directory.mkdir(parents=True, exist_ok=True)
    generator = np.random.default_rng(SEED)
    nominal = load_geometry([config_directory / 'paper_platform.yaml',
                             config_directory / 'example_limits.yaml'])
    built = replace(
        nominal,
        base_joints=nominal.base_joints + generator.uniform(-JOINT_ERROR, JOINT_ERROR, (6, 3)),
        platform_joints=nominal.platform_joints
        + generator.uniform(-JOINT_ERROR, JOINT_ERROR, (6, 3)))
    offsets = NOMINAL_OFFSET + generator.uniform(-OFFSET_ERROR, OFFSET_ERROR, 6)

    def measure(poses):
        readings = predict_actuator_positions(built, offsets, poses)
        readings += generator.normal(0.0, READING_NOISE, readings.shape)
        noise = np.concatenate([generator.normal(0.0, POSITION_NOISE, (len(poses), 3)),
                                generator.normal(0.0, ANGLE_NOISE, (len(poses), 3))], axis=1)
        return poses + noise, readings

    selection = measurement_poses(nominal, POSE_COUNT, position_range=POSITION_RANGE,
                                  angle_range=ANGLE_RANGE, seed=SEED)
    poses, readings = measure(selection.poses)
    poses[MISREAD_POSE, 1] += MISREAD_ERROR
    readings[GLITCH_POSE, GLITCH_LEG] += GLITCH_ERROR
    half_width = np.array([POSITION_RANGE] * 3 + [ANGLE_RANGE] * 3)
    validation = nominal.home_pose + generator.uniform(-1.0, 1.0, (VALIDATION_COUNT, 6)) * (
        0.8 * half_width)
    validation_poses, validation_readings = measure(validation)

    paths = {name: directory / name for name in (
        'measurements.csv', 'validation.csv', 'nominal_actuators.yaml', 'true_platform.yaml')}
    units = ('X, Y, Z in metres; alpha, beta, gamma in radians; actuator positions in metres '
             '(leg length minus offset)')
    write_measurements(paths['measurements.csv'], poses, readings,
                       f'Synthetic measurements of a built paper platform (seed {SEED}).\n'
                       + units)
    write_measurements(paths['validation.csv'], validation_poses, validation_readings,
                       'Further measurements of the same platform, for --validate.\n' + units)
    write_parameter_file(paths['nominal_actuators.yaml'],
                         {'actuator_offsets': [NOMINAL_OFFSET] * 6},
                         "The drawing's actuator offsets: an actuator reads 0 at a leg length "
                         'of 0.65 m.')
    write_parameter_file(
        paths['true_platform.yaml'],
        {'base_joints': built.base_joints.ravel().tolist(),
         'platform_joints': built.platform_joints.ravel().tolist(),
         'actuator_offsets': offsets.tolist()},
        'The built platform the synthetic measurements come from (the truth).')
    print(f'measurement poses: smallest singular value {selection.smallest_singular_value:.3g}, '
          f'{selection.improvement:.2f}x the median of random poses; scaled condition number '
          f'{selection.condition_number:.3g} (random: {selection.random_condition_number:.3g})')
    for path in paths.values():
        print(f'wrote {path}')
    return paths


def pose_errors(directory: Path, calibrated_file: Path, config_directory: Path) -> str:
    """
    Compare the pose errors of the built platform driven by the nominal and calibrated models.

    For each pose of ``validation.csv`` (as commanded), each model gives the actuator positions
    to command (its leg lengths minus its offsets); the built platform (``true_platform.yaml``)
    then has those positions plus its real offsets as leg lengths, and reaches the pose that
    its forward kinematics gives for them. Returns the report as text.
    """
    nominal = load_geometry([config_directory / 'paper_platform.yaml',
                             config_directory / 'example_limits.yaml'])
    truth = read_parameter_file(directory / 'true_platform.yaml')
    built = replace(nominal, base_joints=np.reshape(truth['base_joints'], (6, 3)),
                    platform_joints=np.reshape(truth['platform_joints'], (6, 3)))
    calibrated = load_geometry(calibrated_file)
    calibrated_offsets = np.array(read_parameter_file(calibrated_file)['actuator_offsets'])
    commanded, _ = load_measurements(directory / 'validation.csv')
    lines = [f'pose error of the built platform over {commanded.shape[0]} commanded poses '
             '(RMS, worst)']
    for name, model, offsets in (('nominal', nominal, np.full(6, NOMINAL_OFFSET)),
                                 ('calibrated', calibrated, calibrated_offsets)):
        # The model commands actuator positions; the built legs are those plus its offsets.
        positions = predict_actuator_positions(model, offsets, commanded)
        lengths = positions + np.asarray(truth['actuator_offsets'])
        reached = forward_kinematics(built, lengths, commanded)
        if not np.all(reached.converged):
            raise RuntimeError(f'forward kinematics failed for the {name} model')
        position = np.linalg.norm(reached.pose[:, :3] - commanded[:, :3], axis=1)
        angle = rotation_angle_between(euler_zyx_to_matrix(reached.pose[:, 3:]),
                                       euler_zyx_to_matrix(commanded[:, 3:]))
        lines.append(f'  {name:10s}  position {_rms(position) * 1e6:9.2f} um, worst '
                     f'{np.max(position) * 1e6:9.2f} um;  orientation '
                     f'{_rms(angle) * 1e6:8.2f} urad, worst {np.max(angle) * 1e6:8.2f} urad')
    return '\n'.join(lines)


def _rms(values) -> float:
    return float(np.sqrt(np.mean(np.square(values))))


def main(argv=None) -> int:
    """Write the example files (or compare a calibration with the truth); return 0."""
    parser = argparse.ArgumentParser(description=__doc__.strip().split('\n\n')[0])
    parser.add_argument('output', type=Path, help='folder to write the files to')
    parser.add_argument('--config-dir', type=Path, default=None,
                        help='folder with paper_platform.yaml and example_limits.yaml')
    parser.add_argument('--check', type=Path, metavar='CALIBRATED_YAML', default=None,
                        help='instead, print the pose errors of the built platform driven by '
                             'the nominal model and by this calibrated parameter file')
    arguments = parser.parse_args(argv)
    config_directory = arguments.config_dir or default_config_directory()
    if not config_directory.is_dir():
        parser.error(f'argument --config-dir: {config_directory} is not a folder')
    if arguments.check is None:
        check_output_paths(parser, [('output', arguments.output, True)])
    elif not arguments.check.is_file():
        parser.error(f'argument --check: {arguments.check} is not a file')
    try:
        if arguments.check is not None:
            print(pose_errors(arguments.output, arguments.check, config_directory))
        else:
            write_example(arguments.output, config_directory)
    except ParameterFileError as error:
        source = Path(error.source)
        option = ('--check' if source == arguments.check else
                  '--config-dir' if source.parent == config_directory else 'output')
        return refuse_parameter_file('calibration_example', error, option)
    except (ValueError, RuntimeError) as error:
        print(f'calibration_example: {error}', file=sys.stderr)
        return 1
    except KeyError as error:
        print(f'calibration_example: parameter {error} is missing from the parameter files',
              file=sys.stderr)
        return 1
    except OSError as error:
        print(f'calibration_example: {error.filename}: {error.strerror}', file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
