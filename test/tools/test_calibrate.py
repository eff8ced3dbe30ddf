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
stewart_calibrate as a user runs it, and ik_node started on the calibrated parameter file.

The worked example of doc/calibration.md end to end, as processes: the example's measurements
are written, ``stewart_calibrate`` calibrates from them (finding the two spoilt measurements) and
writes ``calibrated.yaml`` and the residual figure; ``ik_node`` then starts with
``--params-file calibrated.yaml`` alone and publishes, for a commanded pose, the leg lengths of
the calibrated joints, computed here with the leg formula from the file read with PyYAML.
"""

import math
from pathlib import Path
import re
import subprocess
import sys

from geometry_msgs.msg import Pose
from helpers import pose_message
import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference
from std_msgs.msg import Float64MultiArray
from stewart_kinematics.tools.node_processes import find_executable
import yaml

pytestmark = pytest.mark.process

#: Seconds a command-line run may take on a loaded machine.
RUN_TIMEOUT = 120.0
#: A pose inside the example limits: X, Y, Z in metres, alpha, beta, gamma in radians.
POSE = np.array([0.02, -0.03, 0.45, math.radians(5.0), math.radians(-3.0), math.radians(8.0)])


def run(arguments, cwd):
    """Run a command to completion; return (exit code, stdout, stderr)."""
    completed = subprocess.run(arguments, cwd=cwd, capture_output=True, text=True,
                               timeout=RUN_TIMEOUT)
    return completed.returncode, completed.stdout, completed.stderr


def file_lengths(path, pose):
    """Leg lengths of ``pose`` (of the platform frame) for the joints of a parameter file."""
    with open(path, encoding='utf-8') as stream:
        parameters = yaml.safe_load(stream)['/**']['ros__parameters']
    assert 'pivot_point' not in parameters
    return np.array(reference.leg_lengths(
        pose, np.reshape(parameters['base_joints'], (6, 3)),
        np.reshape(parameters['platform_joints'], (6, 3))))


#: The README's worked example, run as a script (it is no part of the installed package).
EXAMPLE_SCRIPT = Path(__file__).resolve().parents[2] / 'scripts' / 'calibration_example.py'


@pytest.fixture(scope='module')
def example(tmp_path_factory):
    """Write the worked example's files and calibrate from them with stewart_calibrate."""
    from pathlib import Path
    config = Path(__file__).resolve().parents[2] / 'config'
    directory = tmp_path_factory.mktemp('calibration_example')
    code, out, err = run([sys.executable, str(EXAMPLE_SCRIPT),
                          str(directory), '--config-dir', str(config)], directory)
    assert code == 0, out + err
    code, out, err = run([
        find_executable('stewart_calibrate'), 'measurements.csv',
        '--params-file', str(config / 'paper_platform.yaml'),
        '--params-file', str(config / 'example_limits.yaml'),
        '--params-file', 'nominal_actuators.yaml',
        '--validate', 'validation.csv', '--output', 'calibrated.yaml'], directory)
    return directory, config, code, out, err


def test_stewart_calibrate_reports_finds_the_outliers_and_writes_its_files(example):
    directory, _, code, out, err = example
    assert code == 0, out + err
    assert 'outliers: [12, 31]' in out
    nominal_rms, calibrated_rms = (float(value) for value in re.search(
        r'nominal: +RMS +([\d.]+).*\n +calibrated: +RMS +([\d.]+)', out).groups())
    assert nominal_rms > 1000.0 and calibrated_rms < 8.0  # micrometres, on held-out poses
    assert (directory / 'calibrated.yaml').is_file()
    assert (directory / 'calibrated_residuals.png').read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
    # The calibrated joints and offsets are those of the built platform, to a fraction of a
    # millimetre (the offsets and the joints' z are the worst determined).
    with open(directory / 'calibrated.yaml', encoding='utf-8') as stream:
        calibrated = yaml.safe_load(stream)['/**']['ros__parameters']
    with open(directory / 'true_platform.yaml', encoding='utf-8') as stream:
        true = yaml.safe_load(stream)['/**']['ros__parameters']
    for name in ('base_joints', 'platform_joints', 'actuator_offsets'):
        assert_allclose(calibrated[name], true[name], rtol=0.0, atol=0.6e-3, err_msg=name)
    assert calibrated['leg_length_max'] == 0.9  # the nominal limits are kept


def test_calibration_cuts_the_pose_error_of_the_built_platform(example):
    directory, config, code, out, err = example
    assert code == 0, out + err
    code, out, err = run([sys.executable, str(EXAMPLE_SCRIPT),
                          str(directory), '--config-dir', str(config),
                          '--check', str(directory / 'calibrated.yaml')], directory)
    assert code == 0, out + err
    (nominal_position, nominal_angle), (position, angle) = (
        (float(match[0]), float(match[1])) for match in re.findall(
            r'position +([\d.]+) um, worst .*orientation +([\d.]+) urad', out))
    assert nominal_position > 1000.0 and nominal_angle > 1000.0
    assert position < 10.0 and angle < 20.0


def test_docs_worked_example_is_this_output(example):
    # The calibration page's excerpt of the worked example is the output of its commands.
    from pathlib import Path
    page = (Path(__file__).resolve().parents[2] / 'doc' / 'calibration.md').read_text(
        encoding='utf-8')
    excerpt = re.search(r'```text\n(poses: 50 measured.*?)```', page, re.DOTALL)
    assert excerpt, 'worked example excerpt not found in doc/calibration.md'
    _, _, code, out, err = example
    assert code == 0, out + err
    for line in excerpt.group(1).splitlines():
        if line != '...':
            assert line in out, f'doc/calibration.md line not in the output: {line!r}'


def test_ik_node_runs_on_the_calibrated_file_and_publishes_its_lengths(
        example, client, start_node):
    directory, config, code, out, err = example
    assert code == 0, out + err
    node = start_node('ik_node', ['--ros-args', '--params-file',
                                  str(directory / 'calibrated.yaml')])
    received = []
    subscription = client.node.create_subscription(
        Float64MultiArray, 'leg_lengths', received.append, 10)
    publisher = client.node.create_publisher(Pose, 'target_pose', 10)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and subscription.get_publisher_count() >= 1,
                'ik_node matched on target_pose and leg_lengths', [node])
    client.spin_for(0.5)
    publisher.publish(pose_message(POSE))
    client.wait(lambda: received, 'leg_lengths from ik_node', [node])

    expected = file_lengths(directory / 'calibrated.yaml', POSE)
    assert_allclose(received[0].data, expected, rtol=0.0, atol=1e-12)
    nominal = file_lengths(config / 'paper_platform.yaml', POSE)
    assert np.max(np.abs(np.array(received[0].data) - nominal)) > 1e-3
    assert node.running()


def test_stewart_calibrate_refuses_too_few_poses_with_the_reason(example, tmp_path):
    directory, config, _, _, _ = example
    lines = (directory / 'measurements.csv').read_text().splitlines()
    rows = [line for line in lines if not line.startswith('#')]
    (tmp_path / 'few.csv').write_text('\n'.join(rows[:6]) + '\n')
    code, out, err = run([find_executable('stewart_calibrate'), 'few.csv', '--params-file',
                          str(config / 'paper_platform.yaml')], tmp_path)
    assert code == 1
    assert 'cannot calibrate: too few poses: 5 given, at least 8 needed' in err
    assert not (tmp_path / 'calibrated.yaml').exists()


def test_stewart_calibrate_proposes_measurement_poses(example, tmp_path):
    _, config, _, _, _ = example
    code, out, err = run([find_executable('stewart_calibrate'), '--propose', '12',
                          '--params-file', str(config / 'paper_platform.yaml'),
                          '--params-file', str(config / 'example_limits.yaml'),
                          '--poses-out', 'poses.csv'], tmp_path)
    assert code == 0, out + err
    assert re.search(r'proposed 12 poses: smallest singular value \S+ \([\d.]+x the median',
                     out)
    rows = [line.split(',') for line in (tmp_path / 'poses.csv').read_text().splitlines()
            if not line.startswith('#')]
    assert rows[0][:7] == ['X', 'Y', 'Z', 'alpha', 'beta', 'gamma', 'actuator_1']
    assert len(rows) == 13 and all(len(row) == 12 for row in rows)
    assert all(abs(float(row[2]) - 0.4325) <= 0.05 for row in rows[1:])


def test_stewart_calibrate_help_documents_the_columns_and_units(tmp_path):
    code, out, err = run([find_executable('stewart_calibrate'), '--help'], tmp_path)
    assert code == 0, err
    for text in ('X, Y, Z', 'alpha, beta, gamma', 'actuator_1..6', ', m', 'rad',
                 '--params-file', 'exit codes'):
        assert text in out, text
