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
``stewart_cueing``'s options, inputs and outputs, through its ``main()``.

Bad options exit 2 naming the option before any work; an input file that cannot be used exits
1 with the file, the line and the column; a good run writes the table, the numbers and the
figures, and ``--strict`` exits 3 when a target is missed.
"""

import math
from pathlib import Path
import warnings

import numpy as np
import pytest
from stewart_kinematics.cueing.scenarios import scenario
from stewart_kinematics.tools import cueing_report
from stewart_kinematics.tools.cueing_report import CSV_COLUMNS, main
import yaml

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
PLATFORM = ['--params-file', str(CONFIG / 'paper_platform.yaml'),
            '--params-file', str(CONFIG / 'example_limits.yaml')]
TUNED = PLATFORM + ['--params-file', str(CONFIG / 'motion_cueing.yaml')]


def write_csv(path, rows, header=','.join(CSV_COLUMNS)):
    """Write a CSV input with a comment, the header and ``rows``."""
    lines = ['# recorded by a test', header] + [','.join(map(str, row)) for row in rows]
    path.write_text('\n'.join(lines) + '\n', encoding='utf-8')
    return path


def scenario_rows(name, rate=50.0):
    """Return the rows of a generated scenario, as a CSV would hold them."""
    generated = scenario(name, rate)
    return np.column_stack([generated.times + 100.0, generated.specific_force,
                            generated.angular_velocity]).tolist()


@pytest.mark.parametrize('arguments, option', [
    (['--rate', '-5'], '--rate'), (['--rate', 'fast'], '--rate'),
    (['--rate', 'nan'], '--rate'), (['--scenario', 'drift'], '--scenario'),
    (['--csv', '/nonexistent/input.csv'], '--csv'),
    (['--false-cue-threshold', '0'], '--false-cue-threshold'),
    (['--settle-time', 'inf'], '--settle-time'),
    (['--csv', __file__, '--scenario', 'lap'], '--scenario'),
])
def test_bad_options_exit_2_naming_the_option(capsys, tmp_path, arguments, option):
    """Refuse the value naming the option (argparse); nothing is written."""
    with pytest.raises(SystemExit) as raised:
        main(TUNED + ['--output', str(tmp_path / 'out')] + arguments)
    assert raised.value.code == 2
    assert option in capsys.readouterr().err
    assert not (tmp_path / 'out').exists()


def test_output_that_is_a_file_exits_2_before_any_work(capsys, tmp_path):
    """--output naming a file: refused before replaying anything."""
    blocker = tmp_path / 'taken'
    blocker.write_text('not a folder', encoding='utf-8')
    with pytest.raises(SystemExit) as raised:
        main(TUNED + ['--output', str(blocker)])
    assert raised.value.code == 2
    err = capsys.readouterr().err
    assert '--output' in err and 'not a folder' in err


def test_a_rate_slower_than_the_input_gap_exits_1_saying_why(capsys, tmp_path):
    """
    A scenario sampled below 1 / max_input_gap (10 Hz) would be replayed on a wrong clock.

    Before, 1e-300 Hz gave "times must have shape (N,)", and 0.1 Hz a run that met targets
    with the platform never moved.
    """
    for rate in ('1e-300', '0.1', '9.99'):
        code = main(TUNED + ['--scenario', 'brake_step', '--rate', rate, '--no-figures',
                             '--quiet', '--output', str(tmp_path / 'out')])
        assert code == 1
        assert 'longer than max_input_gap (0.1 s)' in capsys.readouterr().err
    assert not (tmp_path / 'out' / 'cueing_results.yaml').exists()


@pytest.mark.parametrize('source', ['--csv', '--mcap'])
def test_a_rate_with_a_recorded_input_exits_2_not_ignored(capsys, tmp_path, source):
    """--rate samples the generated scenarios only: with a file it would be dropped unsaid."""
    with pytest.raises(SystemExit) as raised:
        main(TUNED + [source, __file__, '--rate', '50', '--output', str(tmp_path / 'out')])
    assert raised.value.code == 2
    assert 'argument --rate: a --csv or --mcap replay keeps its own times' \
        in capsys.readouterr().err


def test_an_output_folder_that_cannot_be_made_exits_2_naming_the_option(
        capsys, tmp_path, monkeypatch):
    """A folder the check before the run cannot foresee (root in /proc): no traceback."""
    def refuse(*args, **kwargs):
        raise FileNotFoundError(2, 'No such file or directory', str(tmp_path / 'out'))
    monkeypatch.setattr(Path, 'mkdir', refuse)
    with pytest.raises(SystemExit) as raised:
        main(TUNED + ['--scenario', 'brake_step', '--output', str(tmp_path / 'out')])
    assert raised.value.code == 2
    assert capsys.readouterr().err.endswith(
        f'argument --output: cannot write there: {tmp_path / "out"}: '
        'No such file or directory\n')


def test_an_output_that_fails_during_the_run_exits_1_in_one_line(
        capsys, tmp_path, monkeypatch):
    """A write refused after the replay (a full disk): one line naming the file, exit 1."""
    results = tmp_path / 'out' / 'cueing_results.md'

    def full(self, *args, **kwargs):
        raise OSError(28, 'No space left on device', str(self))
    monkeypatch.setattr(Path, 'write_text', full)
    code = main(TUNED + ['--scenario', 'brake_step', '--no-figures', '--quiet',
                         '--output', str(tmp_path / 'out')])
    assert code == 1
    assert capsys.readouterr().err == \
        f'stewart_cueing: cannot write {results}: No space left on device\n'


def test_a_warning_of_the_run_is_printed_not_only_counted(capsys, tmp_path):
    """An MPC whose QP never solves leaves the platform at rest: the summary says so."""
    starved = tmp_path / 'starved.yaml'
    starved.write_text('/**:\n  ros__parameters:\n    cueing_method: mpc\n'
                       '    mpc_max_iterations: 1\n', encoding='utf-8')
    assert main(TUNED + ['--params-file', str(starved), '--scenario', 'brake_step',
                         '--no-figures', '--quiet', '--output', str(tmp_path / 'out')]) == 0
    out = capsys.readouterr().out
    samples = scenario('brake_step', 100.0).times.size
    assert f'  warning mpc_fallback at {samples - 1} of {samples} samples: ' \
        "The model-predictive cueing's QP was not solved (infeasible, out of iterations)\n" \
        in out


def test_params_file_is_required(capsys):
    """Without a parameter file there is no platform: usage error naming the option."""
    with pytest.raises(SystemExit) as raised:
        main(['--scenario', 'lap'])
    assert raised.value.code == 2
    assert '--params-file' in capsys.readouterr().err


def test_csv_input_is_replayed_and_reported(capsys, tmp_path):
    """A CSV of the multi-sine (stamps from 100 s): table, numbers, figure, progress."""
    path = write_csv(tmp_path / 'drive.csv', scenario_rows('multi_sine'))
    output = tmp_path / 'out'
    assert main(TUNED + ['--csv', str(path), '--output', str(output)]) == 0
    captured = capsys.readouterr()
    assert '100% drive.csv' in captured.err
    assert 'drive.csv: 1651 samples' in captured.out
    assert (output / 'drive.png').stat().st_size > 10000
    tables = (output / 'cueing_results.md').read_text(encoding='utf-8').split('\n\n')
    assert len(tables) == 3
    assert tables[2].splitlines()[2].startswith('| drive.csv | 0 |')
    numbers = yaml.safe_load((output / 'cueing_results.yaml').read_text(encoding='utf-8'))
    assert numbers['drive.csv']['specific_force']['x']['correlation'] > 0.8
    assert numbers['drive.csv']['angular_velocity']['yaw']['correlation'] is None
    assert numbers['drive.csv']['targets']['zero limit violations'] is True
    # A CSV is no built-in scenario: its targets are the limits, neutral and the tilt rate.
    assert len(numbers['drive.csv']['targets']) == 3


@pytest.mark.parametrize('rows, header, fragment', [
    ([[0.0, 0, 0, 9.8, 0, 0, 0]] * 3, 'time,ax,ay,az,wx,wy,wz', 'the header must be'),
    ([[0.0, 0, 0, 9.8, 0, 0, 0], [0.01, 0, 'nan', 9.8, 0, 0, 0], [0.02, 0, 0, 9.8, 0, 0, 0]],
     None, 'line 4: specific_force_y must be a finite number'),
    ([[0.0, 0, 0, 9.8, 0, 0, 0], [0.01, 0, 0, 9.8, 0, 0]], None, 'line 4: expected 7 values'),
    ([[0.0, 0, 0, 9.8, 0, 0, 0], [0.0, 0, 0, 9.8, 0, 0, 0], [0.1, 0, 0, 9.8, 0, 0, 0]], None,
     'times must increase'),
    ([[0.0, 0, 0, 9.8, 0, 0, 0], [0.01, 500.0, 0, 9.8, 0, 0, 0],
      [0.02, 0, 0, 9.8, 0, 0, 0]], None, 'beyond 100 m/s^2'),
    ([[0.0, 0, 0, 9.8, 0, 0, 0]], None, 'at least 3 samples'),
    # Counted from -1e308, 0 and 0.01 are both 1e308: the step between them is lost.
    ([[-1e308, 0, 0, 9.8, 0, 0, 0], [0.0, 0, 0, 9.8, 0, 0, 0], [0.01, 0, 0, 9.8, 0, 0, 0]],
     None, 'sample 2 at 0.01 s is too far from the first (-1e+308 s)'),
    ([[-1e308, 0, 0, 9.8, 0, 0, 0], [1e308, 0, 0, 9.8, 0, 0, 0],
      [1.5e308, 0, 0, 9.8, 0, 0, 0]], None, 'sample 1 at 1e+308 s is too far'),
])
def test_unusable_csv_exits_1_saying_where(capsys, tmp_path, rows, header, fragment):
    """A bad header, a bad value, a short row, a repeated time, an absurd force, too short."""
    path = write_csv(tmp_path / 'bad.csv', rows, header or ','.join(CSV_COLUMNS))
    with warnings.catch_warnings():
        warnings.simplefilter('error')   # numpy's overflow words are a defect too
        assert main(TUNED + ['--csv', str(path), '--output', str(tmp_path / 'out'),
                             '--quiet']) == 1
    err = capsys.readouterr().err
    assert fragment in err and 'bad.csv' in err and 'np.float64' not in err


@pytest.mark.parametrize('content, fragment', [
    # A quoted field beyond the csv module's limit was a traceback from _csv.Error.
    (','.join(CSV_COLUMNS).encode() + b'\n"' + b'1' * 200_000 + b'",0,0,9.8,0,0,0\n',
     'not a CSV file of samples: field larger than field limit'),
    (b'\xff\xfe\x00 not text', 'bad.csv: cannot be read'),
    (b'', 'no header and no data'),
])
def test_csv_that_is_no_table_exits_1_naming_it(capsys, tmp_path, content, fragment):
    """A field too large for the csv module, bytes that are not text, an empty file."""
    path = tmp_path / 'bad.csv'
    path.write_bytes(content)
    assert main(TUNED + ['--csv', str(path), '--output', str(tmp_path / 'out'),
                         '--quiet']) == 1
    err = capsys.readouterr().err
    assert fragment in err and 'Traceback' not in err


def test_csv_that_is_a_folder_is_refused_as_an_option(capsys, tmp_path):
    """--csv naming a folder was an IsADirectoryError traceback; now exit 2 naming it."""
    with pytest.raises(SystemExit) as exit_:
        main(TUNED + ['--csv', str(tmp_path), '--output', str(tmp_path / 'out')])
    assert exit_.value.code == 2
    assert f'{tmp_path} is not a file' in capsys.readouterr().err


def test_strict_exits_3_when_a_target_is_missed(capsys, tmp_path):
    """The literature's defaults on this platform return too slowly: --strict says so."""
    code = main(PLATFORM + ['--scenario', 'acceleration_braking', '--output',
                            str(tmp_path / 'out'), '--no-figures', '--quiet', '--strict'])
    assert code == 3
    out = capsys.readouterr().out
    assert 'MISSED within 1 mm and 0.1 deg of neutral' in out
    assert not list((tmp_path / 'out').glob('*.png'))


def runs_of(output):
    """Return scenario name -> its lines of targets in a report's output."""
    runs, name = {}, None
    for line in output.splitlines():
        if line and not line.startswith((' ', '|')):
            name = line.split(':')[0]
            runs[name] = []
        elif line.startswith('  ') and name is not None:
            runs[name].append(line.strip())
    return runs


def test_strict_fails_the_slalom_felt_in_anti_phase(shipped_cueing_report):
    """
    The shipped tuning keeps every limit, but --strict exits 3: the slalom misses its targets.

    The session's run (conftest: four scenarios with --strict, run once): the slalom is felt
    in anti-phase (perceived correlation about -0.6), which a believable cue is not.
    """
    assert shipped_cueing_report.exit_code == 3
    runs = runs_of(shipped_cueing_report.output)
    assert list(runs) == ['acceleration_braking', 'slalom', 'multi_sine', 'lap']
    assert all('met    zero limit violations: 0' in lines for lines in runs.values())
    slalom = '\n'.join(runs['slalom'])
    assert 'MISSED perceived correlation >= 0.6 (y): -0.' in slalom
    assert 'MISSED wrong-sign cue <= 1 s on every axis' in slalom
    assert sorted(path.name for path in shipped_cueing_report.folder.glob('*.png')) == [
        'acceleration_braking.png', 'lap.png', 'multi_sine.png', 'slalom.png']


def test_strict_exits_3_on_the_slalom_alone(capsys, tmp_path):
    """
    The slalom alone, with the shipped tuning, at 50 Hz (about 1,450 samples): --strict exits 3.

    The classical washout keeps every limit and returns to neutral, but the slalom is felt in
    anti-phase: its perceived correlation misses 0.6.
    """
    code = main(TUNED + ['--scenario', 'slalom', '--rate', '50', '--output',
                         str(tmp_path / 'out'), '--no-figures', '--quiet', '--strict'])
    out = capsys.readouterr().out
    assert code == 3
    assert 'met    zero limit violations: 0' in out
    assert 'MISSED perceived correlation >= 0.6 (y)' in out


def test_a_file_named_as_a_scenario_is_judged_as_a_file(tmp_path):
    """A CSV called ``slalom`` is not the slalom: its targets are the limits, neutral, tilt."""
    rows = [[k / 50.0, 1.0 if 1.0 <= k / 50.0 < 2.0 else 0.0, 0.0, 9.80665, 0.0, 0.0, 0.0]
            for k in range(300)]
    path = write_csv(tmp_path / 'slalom', rows)
    output = tmp_path / 'out'
    assert main(TUNED + ['--csv', str(path), '--output', str(output), '--no-figures',
                         '--quiet']) == 0
    numbers = yaml.safe_load((output / 'cueing_results.yaml').read_text(encoding='utf-8'))
    assert len(numbers['slalom']['targets']) == 2  # ends 6 s in: no return to neutral judged


def test_markdown_table_shows_unknowns_as_dashes():
    """Show NaN correlations (a constant axis) and delays beyond the window as such."""
    assert cueing_report._number(math.nan) == '-'
    assert cueing_report._number(math.inf, '.0f') == '> 2000'
    assert cueing_report._number(-math.inf, '.0f') == '< -2000'


def test_preview_with_the_classical_washout_exits_1_saying_why(capsys, tmp_path):
    """--preview needs the MPC: with the classical washout it is refused, naming the setting."""
    code = main(TUNED + ['--scenario', 'lane_change', '--preview', '--output',
                         str(tmp_path / 'out'), '--no-figures', '--quiet'])
    assert code == 1
    assert 'a preview needs cueing_method mpc' in capsys.readouterr().err


def test_preview_tells_the_mpc_the_drive(capsys, tmp_path):
    """With the preview preset, --preview cues the lane change closer than without it."""
    preset = TUNED + ['--params-file', str(CONFIG / 'motion_cueing_preview.yaml')]
    rmse = {}
    for told in (False, True):
        output = tmp_path / f'out{told}'
        code = main(preset + ['--scenario', 'lane_change', '--output', str(output),
                              '--no-figures', '--quiet'] + (['--preview'] if told else []))
        assert code == 0
        numbers = yaml.safe_load((output / 'cueing_results.yaml').read_text(encoding='utf-8'))
        rmse[told] = numbers['lane_change']['specific_force']['y']['rmse']
    assert rmse[True] < 0.9 * rmse[False]
