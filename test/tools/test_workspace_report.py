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
The ``stewart_workspace`` console script, run as a process as a user runs it.

Coarse grids keep it quick; the numbers it prints and writes are compared with the core's
own results computed here.
"""

import math
from pathlib import Path
import subprocess

import numpy as np
import pytest
from stewart_kinematics import load_geometry, travel_ranges
from stewart_kinematics.tools.node_processes import find_executable
import yaml

pytestmark = pytest.mark.process

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml']
COARSE = ['--slice-resolution-mm', '8', '--volume-resolution-mm', '20',
          '--angle-resolution-deg', '1.0']
#: Generous: coarse grids keep the report short, but a loaded machine may be many times slower.
DEADLINE = 300.0


def run_report(*arguments):
    """Run stewart_workspace; return the completed process."""
    return subprocess.run([find_executable('stewart_workspace'), *map(str, arguments)],
                          capture_output=True, text=True, timeout=DEADLINE, check=False)


def test_report_prints_writes_numbers_and_figures(tmp_path):
    output = tmp_path / 'report'
    done = run_report('--params-file', FILES[0], '--params-file', FILES[1],
                      '--output', output, *COARSE)
    assert done.returncode == 0, done.stderr
    expected = travel_ranges(load_geometry(FILES))
    for axis in expected.axes:
        scale = 1e3 if axis.unit == 'm' else math.degrees(1.0)
        line = next(line for line in done.stdout.splitlines() if line.startswith(axis.axis + ' '))
        assert f'{axis.negative * scale:.3f}' in line and f'{axis.positive * scale:.3f}' in line
        assert axis.positive_limit in line
    assert 'm^3' in done.stdout and 'bounding box' in done.stdout
    # The progress bar, on stderr.
    assert '[' + '#' * 30 + '] 8/8 done' in done.stderr

    numbers = yaml.safe_load((output / 'workspace.yaml').read_text())
    for axis in expected.axes:
        written = numbers['travel_ranges'][axis.axis]
        assert written['negative'] == pytest.approx(axis.negative, abs=1e-12)
        assert written['positive'] == pytest.approx(axis.positive, abs=1e-12)
        assert (written['negative_limit'], written['negative_leg']) == \
            (axis.negative_limit, axis.negative_leg)
    volume = numbers['volume']
    assert volume['bounded'] and 0.07 < volume['volume_m3'] < 0.09
    assert f'{volume["volume_m3"]:.6f} m^3' in done.stdout
    assert [entry['plane'] for entry in numbers['slices']] == ['X-Y', 'X-Z', 'Y-Z']
    assert len(numbers['orientation_workspace']) == 3
    assert numbers['parameter_files'] == [str(path) for path in FILES]
    for name in ('workspace_slices.png', 'orientation_workspace.png', 'dexterity.png'):
        data = (output / name).read_bytes()
        assert data[:8] == b'\x89PNG\r\n\x1a\n' and len(data) > 10_000, name


def test_start_pose_and_yaml_only(tmp_path):
    done = run_report('--params-file', FILES[0], '--params-file', FILES[1],
                      '--output', tmp_path, '--no-figures', '--pose', '0.02', '0', '0.45',
                      '2', '0', '5', *COARSE)
    assert done.returncode == 0, done.stderr
    numbers = yaml.safe_load((tmp_path / 'workspace.yaml').read_text())
    np.testing.assert_allclose(numbers['start_pose'],
                               [0.02, 0.0, 0.45, math.radians(2.0), 0.0, math.radians(5.0)])
    assert not list(tmp_path.glob('*.png'))


def test_bad_input_is_refused_with_a_message(tmp_path):
    done = run_report('--params-file', FILES[0], '--params-file', FILES[1],
                      '--output', tmp_path, '--pose', '0', '0', '0.8', '0', '0', '0', *COARSE)
    assert done.returncode == 1
    assert 'start pose breaks the limits' in done.stderr and 'leg_length_max' in done.stderr
    missing = run_report('--params-file', tmp_path / 'missing.yaml')
    # A parameter file that cannot be read is refused as a bad option is (issue 27).
    assert missing.returncode == 2 and 'cannot read parameter file' in missing.stderr
    usage = run_report('--output', tmp_path)
    assert usage.returncode == 2 and '--params-file' in usage.stderr


def test_a_payload_and_a_force_limit_shrink_the_ranges_and_are_shown(tmp_path):
    payload = tmp_path / 'payload.yaml'
    payload.write_text('/**:\n  ros__parameters:\n    payload_mass: 20.0\n'
                       '    payload_center_of_mass: [0.0, 0.0, 0.1]\n'
                       '    leg_force_max: 60.0\n')
    loaded = run_report('--params-file', FILES[0], '--params-file', FILES[1],
                        '--params-file', payload, '--output', tmp_path / 'loaded',
                        '--no-figures', *COARSE)
    assert loaded.returncode == 0, loaded.stderr
    lines = loaded.stdout.splitlines()
    assert lines[0].startswith('Payload: 20 kg, centre of mass [0, 0, 0.1] m (platform frame)')
    assert lines[1] == ('Force limits: leg_force_max 60 N (each pose judged with its static '
                        'leg forces)')
    expected = travel_ranges(load_geometry(FILES + [payload]))
    free = travel_ranges(load_geometry(FILES))
    beta = next(line for line in lines if line.startswith('beta '))
    assert f'{math.degrees(expected.axes[4].positive):.3f}' in beta
    assert beta.rstrip().endswith('leg_force_max, leg 4')
    assert expected.axes[4].positive < free.axes[4].positive - math.radians(5.0)
    numbers = yaml.safe_load((tmp_path / 'loaded' / 'workspace.yaml').read_text())
    masses = numbers['masses']
    assert masses['masses_set'] and masses['force_limits_checked']
    assert masses['payload'] == {'mass_kg': 20.0, 'center_of_mass_m': [0.0, 0.0, 0.1]}
    assert masses['force_limits_n'] == {'leg_force_min': None, 'leg_force_max': 60.0}
    assert numbers['travel_ranges']['beta']['positive_limit'] == 'leg_force_max'
    assert numbers['travel_ranges']['beta']['positive'] == pytest.approx(
        expected.axes[4].positive, abs=1e-12)

    # Every mass 0: the force limit is set but changes nothing, and the report says so.
    massless = tmp_path / 'massless.yaml'
    massless.write_text('/**:\n  ros__parameters:\n    leg_force_max: 60.0\n')
    done = run_report('--params-file', FILES[0], '--params-file', FILES[1],
                      '--params-file', massless, '--output', tmp_path / 'massless',
                      '--no-figures', *COARSE)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[0] == (
        'Masses: none set (every mass 0): the leg forces are 0, the force limits '
        '(leg_force_max 60 N) are not checked and change nothing')
    numbers = yaml.safe_load((tmp_path / 'massless' / 'workspace.yaml').read_text())
    assert not numbers['masses']['masses_set'] and not numbers['masses']['force_limits_checked']
    for axis in free.axes:
        written = numbers['travel_ranges'][axis.axis]
        assert (written['negative'], written['positive']) == (axis.negative, axis.positive)
        assert 'leg_force' not in f'{written["negative_limit"]} {written["positive_limit"]}'
