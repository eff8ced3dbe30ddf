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
Every command-line tool refuses bad options and outputs up front, and never with a traceback.

The defects (issue 21): ``stewart_workspace --params-file config/paper_platform.yaml
--no-figures`` failed with numpy's "zero-size array to reduction operation minimum"; an
unwritable ``--output`` gave a raw traceback; ``stewart_calibrate`` accepted
``--outlier-threshold -1`` and ``--max-condition 0`` and then failed in ways that blamed the
data. Each tool's main() is called in this process, as its console script calls it.
"""

import argparse
import importlib.util
from pathlib import Path

import pytest

from stewart_kinematics.tools import (calibrate, geometry_report, payload, ramp_demo,
                                      workspace_report)
import yaml

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
PLATFORM = str(ROOT / 'config' / 'paper_platform.yaml')
LIMITS = str(ROOT / 'config' / 'example_limits.yaml')
COARSE = ['--slice-resolution-mm', '20', '--volume-resolution-mm', '50',
          '--angle-resolution-deg', '5']


def load_example_script():
    """Import scripts/calibration_example.py (not a package module)."""
    spec = importlib.util.spec_from_file_location(
        'calibration_example', ROOT / 'scripts' / 'calibration_example.py')
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


EXAMPLE = load_example_script()
#: Every command-line tool: name -> main(argv).
TOOLS = {'stewart_workspace': workspace_report.main, 'stewart_calibrate': calibrate.main,
         'ramp_demo': ramp_demo.main, 'calibration_example': EXAMPLE.main,
         'stewart_geometry': geometry_report.main, 'stewart_payload': payload.main}


class _Parsed(Exception):
    """Raised instead of parsing, carrying the parser."""


def parser_of(main, monkeypatch):
    """Return the argparse parser a tool's main() builds."""
    def capture(self, *args, **kwargs):
        raise _Parsed(self)
    monkeypatch.setattr(argparse.ArgumentParser, 'parse_args', capture)
    with pytest.raises(_Parsed) as parsed:
        main([])
    return parsed.value.args[0]


def run(main, argv, capsys):
    """Run a main(); return (exit code, stderr)."""
    try:
        code = main([str(argument) for argument in argv])
    except SystemExit as exit_:
        code = exit_.code
    captured = capsys.readouterr()
    assert 'Traceback' not in captured.err
    return code, captured.err


@pytest.mark.parametrize('tool', TOOLS)
def test_no_numeric_option_is_a_bare_float_or_int(tool, monkeypatch):
    # argparse's float accepts nan, inf and any sign; each option needs its own range.
    parser = parser_of(TOOLS[tool], monkeypatch)
    bare = [action.option_strings or action.dest for action in parser._actions
            if action.type in (float, int)]
    assert not bare, f'{tool}: options without a range check: {bare}'


@pytest.mark.parametrize('tool, argv, words', [
    ('stewart_calibrate', ['m.csv', '--params-file', PLATFORM, '--outlier-threshold', '-1'],
     'argument --outlier-threshold: must be at least 1'),
    ('stewart_calibrate', ['m.csv', '--params-file', PLATFORM, '--max-condition', '0'],
     'argument --max-condition: must be at least 1'),
    ('stewart_calibrate', ['--params-file', PLATFORM, '--propose', '3'],
     'argument --propose: must be at least 8'),
    ('stewart_calibrate', ['--params-file', PLATFORM, '--propose', '20', '--position-range',
                           'nan'], 'argument --position-range: must be finite'),
    ('stewart_calibrate', ['--params-file', PLATFORM, '--propose', '20', '--angle-range-deg',
                           '0'], 'argument --angle-range-deg: must be in (0, 90]'),
    ('stewart_workspace', ['--params-file', PLATFORM, '--slice-resolution-mm', '-2'],
     'argument --slice-resolution-mm: must be in [0.1, 100]'),
    ('stewart_workspace', ['--params-file', PLATFORM, '--volume-resolution-mm', '1e-9'],
     'argument --volume-resolution-mm'),
    ('stewart_workspace', ['--params-file', PLATFORM, '--angle-resolution-deg', 'inf'],
     'argument --angle-resolution-deg: must be finite'),
    ('stewart_workspace', ['--params-file', PLATFORM, '--pose', '0', '0', 'x', '0', '0', '0'],
     'argument --pose: must be a number'),
    ('stewart_workspace', ['--params-file', PLATFORM, '--pose', '0', '0', '0.4', '0', '0',
                           '400'], 'argument --pose: the angles must be in [-180, 180]'),
    ('stewart_geometry', ['--params-file', PLATFORM, '--volume-resolution-mm', '-1'],
     'argument --volume-resolution-mm: must be in [5, 200]'),
    ('ramp_demo', ['--row-period', '0'], 'argument --row-period: must be in [0.001, 60]'),
    ('ramp_demo', ['--timeout', '-5'], 'argument --timeout'),
    ('ramp_demo', ['--config-dir', '/no/such/folder'], 'argument --config-dir'),
])
def test_a_bad_option_exits_2_naming_it(tool, argv, words, capsys):
    code, error = run(TOOLS[tool], argv, capsys)
    assert code == 2 and words in error, error


def test_an_output_that_cannot_be_written_is_refused_before_the_work(tmp_path, capsys):
    blocker = tmp_path / 'a_file'
    blocker.write_text('not a folder')
    cases = [
        ('stewart_workspace', ['--params-file', PLATFORM, '--output', blocker], '--output'),
        ('stewart_workspace', ['--params-file', PLATFORM, '--output', blocker / 'sub'],
         '--output'),
        ('stewart_calibrate', [tmp_path / 'm.csv', '--params-file', PLATFORM, '--output',
                               blocker / 'calibrated.yaml'], '--output'),
        ('stewart_calibrate', [tmp_path / 'm.csv', '--params-file', PLATFORM, '--output',
                               tmp_path / 'out.yaml', '--figure', blocker / 'f.png'],
         '--figure'),
        ('stewart_calibrate', ['--params-file', PLATFORM, '--propose', '10', '--poses-out',
                               tmp_path], '--poses-out'),
        ('ramp_demo', ['--figures', blocker], '--figures'),
        ('ramp_demo', ['--no-figures', '--bag', blocker / 'bag'], '--bag'),
        ('calibration_example', [blocker], 'output'),
    ]
    for tool, argv, option in cases:
        code, error = run(TOOLS[tool], argv, capsys)
        assert code == 2 and f'argument {option}: cannot write there' in error, (tool, error)
    assert sorted(path.name for path in tmp_path.iterdir()) == ['a_file']


def test_the_workspace_of_a_platform_without_limits_is_reported(tmp_path, capsys):
    # The README promises any geometry and limits: the paper's platform has none.
    code, error = run(workspace_report.main, ['--params-file', PLATFORM, '--no-figures',
                                              '--output', tmp_path, *COARSE], capsys)
    assert code == 0, error
    numbers = yaml.safe_load((tmp_path / 'workspace.yaml').read_text())
    assert numbers['volume']['bounded'] is False and numbers['volume']['volume_m3'] > 1.0
    box = numbers['volume']['bounding_box_m']
    assert box['min'][2] < 0.4325 < box['max'][2]


def test_a_bad_measurement_file_is_refused_with_its_line(tmp_path, capsys):
    bad = tmp_path / 'measurements.csv'
    bad.write_text('X,Y,Z,alpha,beta,gamma,' + ','.join(f'actuator_{i}' for i in range(1, 7))
                   + '\n' + ','.join(['0.0'] * 11) + '\n', encoding='utf-8')
    code, error = run(calibrate.main, [bad, '--params-file', PLATFORM, '--output',
                                       tmp_path / 'out.yaml'], capsys)
    assert code == 1 and 'line 2: 11 fields' in error
    assert not (tmp_path / 'out.yaml').exists()


def test_the_example_script_refuses_a_missing_check_file(tmp_path, capsys):
    code, error = run(EXAMPLE.main, [tmp_path, '--check', tmp_path / 'none.yaml'], capsys)
    assert code == 2 and 'argument --check' in error
    (tmp_path / 'calibrated.yaml').write_text('/**:\n  ros__parameters:\n    a: 1.0\n')
    code, error = run(EXAMPLE.main, [tmp_path, '--check', tmp_path / 'calibrated.yaml'], capsys)
    # The folder holds no true_platform.yaml: a parameter file that cannot be read (exit 2).
    assert code == 2 and 'argument output:' in error and 'true_platform.yaml' in error


def test_a_quoted_number_layered_in_either_order_is_refused_by_the_tools(tmp_path, capsys):
    quoted = tmp_path / 'quoted.yaml'
    quoted.write_text('/**:\n  ros__parameters:\n    leg_length_max: "0.9"\n', encoding='utf-8')
    for files in ([PLATFORM, quoted], [quoted, PLATFORM]):
        arguments = [a for path in files for a in ('--params-file', path)]
        code, error = run(workspace_report.main, arguments + ['--output', tmp_path / 'out'],
                          capsys)
        # A value of the wrong type: the file cannot be read as a parameter file (exit 2),
        # named with its line.
        assert code == 2 and "'leg_length_max' must be of type double" in error, error
        assert 'quoted.yaml:3:' in error and 'a value in quotes' in error
        code, error = run(calibrate.main, arguments + ['--propose', '10', '--poses-out',
                                                       tmp_path / 'poses.csv'], capsys)
        assert code == 2 and "'leg_length_max'" in error and 'quoted.yaml:3:' in error


def test_the_example_script_refuses_a_hostile_check_file_naming_it(tmp_path, capsys):
    # Issue 27: the reader of every tool refuses an alias (rcl does too), in one line.
    (tmp_path / 'true_platform.yaml').write_text(Path(PLATFORM).read_text())
    check = tmp_path / 'calibrated.yaml'
    check.write_text('/**:\n  ros__parameters:\n    a: &a [1.0, 1.0]\n    b: [*a, *a]\n',
                     encoding='utf-8')
    code, error = run(EXAMPLE.main, [tmp_path, '--check', check], capsys)
    assert code == 2 and error.strip() == (
        f'calibration_example: error: argument --check: {check}:4: YAML alias *a refused: a '
        'parameter file cannot use aliases (rcl refuses them too); write the values out')
