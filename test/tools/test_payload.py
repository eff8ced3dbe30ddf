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
stewart_payload: proposed poses, the report, the parameter file out, and every bad file.

The tool's main() is run as the console script runs it: ``--propose`` writes poses within the
limits; the synthetic measurements of scripts/payload_example.py at them give a report with the
true payload within its target and a parameter file that the package's parameter reader layers
after the platform's files into the payload; level poses give the warning naming z; a bad
measurement file (NaN, inf, a row of the wrong length, no rows, a missing column, 1e308) exits
2 with one line naming the file, its line and the column; too few poses exit 1.
"""

import importlib.util
from pathlib import Path
import re

import numpy as np
from numpy.testing import assert_allclose
import pytest
from stewart_kinematics import load_geometry
from stewart_kinematics.analysis.payload_identification import load_force_measurements
from stewart_kinematics.limits.geometry_checks import check_poses_array
from stewart_kinematics.parameters import IkNodeSettings, load_settings
from stewart_kinematics.tools.payload import main

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
NAMES = ('paper_platform.yaml', 'example_limits.yaml', 'example_masses.yaml')
FILES = [str(ROOT / 'config' / name) for name in NAMES]
PARAMS = [word for path in FILES for word in ('--params-file', path)]


def load_example():
    """Import scripts/payload_example.py (not a package module)."""
    spec = importlib.util.spec_from_file_location(
        'payload_example', ROOT / 'scripts' / 'payload_example.py')
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


EXAMPLE = load_example()


def run(argv, capsys):
    """Run stewart_payload's main(); return (exit code, stdout, stderr)."""
    try:
        code = main([str(argument) for argument in argv])
    except SystemExit as exit_:
        code = exit_.code
    captured = capsys.readouterr()
    assert 'Traceback' not in captured.err
    return code, captured.out, captured.err


@pytest.fixture(scope='module')
def measured(tmp_path_factory):
    """Write the proposed poses and the example's measurements at them; return the folder."""
    folder = tmp_path_factory.mktemp('payload')
    assert main(PARAMS + ['--propose', '20', '--poses-out', str(folder / 'poses.csv')]) == 0
    assert EXAMPLE.main([str(folder / 'poses.csv'), str(folder / 'measurements.csv')]) == 0
    return folder


def test_the_proposed_poses_are_within_the_limits(measured):
    """--propose: 20 rows of poses within every limit, the force columns left to fill in."""
    lines = (measured / 'poses.csv').read_text().splitlines()
    assert lines[1] == 'X,Y,Z,alpha,beta,gamma,' + ','.join(f'force_{i}' for i in range(1, 7))
    assert len(lines) == 22 and all(line.endswith(',' * 6) for line in lines[2:])
    poses = np.array([[float(value) for value in line.split(',')[:6]] for line in lines[2:]])
    assert check_poses_array(load_geometry(FILES), poses).allowed.all()


def test_the_example_payload_is_identified_within_the_target(measured, capsys):
    """The report gives 20 kg at (10, -20, 50) mm within 0.1 kg and 2 mm; the file loads."""
    output = measured / 'payload.yaml'
    code, out, error = run([measured / 'measurements.csv', *PARAMS, '--output', output],
                           capsys)
    assert code == 0, error
    mass = float(re.search(r'mass \(kg\) +([-\d.]+) +([\d.]+)', out).group(1))
    center = [float(re.search(fr'centre {axis} \(mm\) +([-\d.]+) +[\d.]+', out).group(1))
              for axis in 'xyz']
    assert abs(mass - 20.0) < 0.1
    assert_allclose(center, [10.0, -20.0, 50.0], atol=2.0)
    assert 'warnings: none' in out and f'wrote {output}' in out
    settings = load_settings(IkNodeSettings, FILES + [str(output)], 'ik_node')
    assert abs(settings.geometry.payload_mass - 20.0) < 0.1
    assert_allclose(settings.geometry.payload_center_of_mass, [0.01, -0.02, 0.05], atol=2e-3)
    payload = load_geometry(FILES + [str(output)]).mass_properties.payload
    assert_allclose(payload.center_of_mass, settings.geometry.payload_center_of_mass, rtol=0.0,
                    atol=0.0)


def test_level_poses_print_the_warning_naming_z(measured, tmp_path, capsys):
    """The example's measurements with every pose level: the height is kept, and said."""
    lines = (measured / 'poses.csv').read_text().splitlines()
    level = lines[:2] + [','.join(line.split(',')[:3] + ['0.0'] * 3) + ',' * 6
                         for line in lines[2:]]
    (tmp_path / 'level.csv').write_text('\n'.join(level) + '\n')
    EXAMPLE.main([str(tmp_path / 'level.csv'), str(tmp_path / 'measurements.csv')])
    code, out, error = run([tmp_path / 'measurements.csv', *PARAMS, '--output',
                            tmp_path / 'payload.yaml'], capsys)
    assert code == 0, error
    assert "payload_unobservable: the poses cannot determine the centre of mass's z" in out
    assert 'not determined (kept)' in out
    assert '# Warnings: payload_unobservable' in (tmp_path / 'payload.yaml').read_text()


def corrupt(measured, tmp_path, line, column, value):
    """Write the example's measurements with one field replaced; return the file."""
    lines = (measured / 'measurements.csv').read_text().splitlines()
    fields = lines[line - 1].split(',')
    fields[column] = value
    lines[line - 1] = ','.join(fields)
    path = tmp_path / 'bad.csv'
    path.write_text('\n'.join(lines) + '\n')
    return path


@pytest.mark.parametrize('line, column, value, words', [
    (3, 7, 'nan', 'line 3: force_2 must be finite'),
    (5, 11, '-inf', 'line 5: force_6 must be finite'),
    (4, 0, 'abc', 'line 4: X must be a number'),
    (4, 11, '1.0,2.0', 'line 4: 13 fields, but the header (line 2) names 12 columns'),
    (2, 6, 'force_one', 'line 2: missing column(s) force_1'),
])
def test_a_bad_measurement_file_exits_2_naming_its_line_and_column(
        measured, tmp_path, capsys, line, column, value, words):
    """One line on stderr with the file, the line and the column; nothing written."""
    path = corrupt(measured, tmp_path, line, column, value)
    code, out, error = run([path, *PARAMS, '--output', tmp_path / 'payload.yaml'], capsys)
    assert code == 2 and str(path) in error and words in error, error
    assert len(error.strip().splitlines()) == 1
    assert not (tmp_path / 'payload.yaml').exists()


def test_empty_huge_and_short_files(measured, tmp_path, capsys):
    """An empty file, no rows, forces of 1e308 (exit 2); three poses (exit 1)."""
    lines = (measured / 'measurements.csv').read_text().splitlines()
    huge = lines[:2] + [','.join(line.split(',')[:6] + ['1e308'] * 6) for line in lines[2:]]
    for text, code_wanted, words in (
            ('', 2, 'no header row'), ('\n'.join(lines[:2]), 2, 'no measurements after the '
                                       'header'),
            ('\n'.join(huge), 2, 'the forces are too large'),
            ('\n'.join(lines[:5]), 1, 'cannot identify the payload: 3 pose(s): at least 4')):
        path = tmp_path / 'file.csv'
        path.write_text(text + '\n')
        code, out, error = run([path, *PARAMS, '--output', tmp_path / 'payload.yaml'], capsys)
        assert code == code_wanted and words in error, error
        assert len(error.strip().splitlines()) == 1
    code, out, error = run([tmp_path / 'missing.csv', *PARAMS], capsys)
    assert code == 2 and 'cannot read measurement file' in error


def test_bad_options_and_parameter_files_exit_2(tmp_path, capsys):
    """No measurements and no --propose, a bad --max-condition, a parameter file in error."""
    for argv, words in (
            (PARAMS, 'give the measurement CSV, or --propose N'),
            (['m.csv', *PARAMS, '--max-condition', '1'], 'argument --max-condition'),
            (['m.csv', *PARAMS, '--max-condition', 'nan'], 'argument --max-condition'),
            ([*PARAMS, '--propose', '3'], 'argument --propose: must be at least 4'),
            ([*PARAMS, '--propose', '20', '--margin', '0'], 'argument --margin')):
        code, out, error = run(argv, capsys)
        assert code == 2 and words in error, error
    bad = tmp_path / 'bad.yaml'
    bad.write_text('/**:\n  ros__parameters:\n    payload_mass: -1.0\n')
    code, out, error = run(['m.csv', *PARAMS, '--params-file', bad], capsys)
    assert code == 2 and 'payload_mass' in error and len(error.strip().splitlines()) == 1


def test_a_yaml_file_gives_the_report_of_the_csv_file(measured, tmp_path, capsys):
    """The example's measurements as YAML: the same report; the how-to's YAML block reads."""
    lines = (measured / 'measurements.csv').read_text().splitlines()[2:]
    rows = [[float(value) for value in line.split(',')] for line in lines]
    (tmp_path / 'measurements.yaml').write_text('measurements:\n' + ''.join(
        f'  - pose: {row[:6]}\n    forces: {row[6:]}\n' for row in rows))
    reports = []
    for path in (measured / 'measurements.csv', tmp_path / 'measurements.yaml'):
        code, out, error = run([path, *PARAMS, '--output', tmp_path / 'payload.yaml'], capsys)
        assert code == 0, error
        reports.append(out.split('\nwrote')[0])
    assert reports[0] == reports[1]
    page = (ROOT / 'doc' / 'how-to' / 'identify_payload.md').read_text(encoding='utf-8')
    block = re.search(r'```yaml\n(.*?)```', page, re.DOTALL).group(1)
    (tmp_path / 'block.yaml').write_text(block)
    poses, forces = load_force_measurements(tmp_path / 'block.yaml', load_geometry(FILES))
    assert poses.shape == forces.shape == (2, 6) and forces[0, 0] == 95.2
