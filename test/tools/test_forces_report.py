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
``stewart_forces`` as a user runs it, ``main(argv)``.

The Table 3 ramp played in 2 s with the example masses, a pose list, a cueing scenario, and
bad input (one line, exit 2).

The numbers are checked against the leg forces computed here from the package's trajectory
through the ramp's rows (as doc/dynamics.md's worked example builds it), not against the
tool's own code.
"""

import csv
import json
from pathlib import Path

import numpy as np
import pytest
from stewart_kinematics import (
    leg_forces,
    leg_velocities,
    load_geometry,
    matrix_to_euler_zyx,
    PoseTrajectory,
    Ramp,
)
from stewart_kinematics.tools.forces_report import CSV_COLUMNS, main

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / 'config'
PARAMS = ['--params-file', str(CONFIG / 'paper_platform.yaml'),
          '--params-file', str(CONFIG / 'example_limits.yaml'),
          '--params-file', str(CONFIG / 'example_masses.yaml')]
RAMP = ['--trajectory', str(CONFIG / 'table3_ramp.yaml'), '--duration', '2']


def ramp_rows():
    return Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0]).rows


def independent_forces(times):
    """Return forces and speeds along the ramp in 2 s, from the package's trajectory."""
    geometry = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_masses.yaml'])
    samples = PoseTrajectory.from_poses(np.linspace(0.0, 2.0, 11), ramp_rows()).sample(times)
    poses = np.hstack([samples.positions, matrix_to_euler_zyx(samples.rotations)])
    twists = np.hstack([samples.velocities, samples.angular_velocities])
    accelerations = np.hstack([samples.accelerations, samples.angular_accelerations])
    return (leg_forces(geometry, poses, twists, accelerations),
            leg_velocities(geometry, poses, twists))


def run(argv, capsys):
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def test_table3_ramp_in_2_s_with_the_example_masses(tmp_path, capsys):
    paths = {name: tmp_path / f'out.{name}' for name in ('csv', 'json')}
    figure = tmp_path / 'figures' / 'forces.png'
    code, out, err = run(RAMP + PARAMS + ['--csv', str(paths['csv']), '--json',
                                          str(paths['json']), '--figure', str(figure)], capsys)
    assert code == 0, err
    assert err == ''
    results = json.loads(paths['json'].read_text(encoding='utf-8'))
    legs = results['legs']
    assert [leg['leg'] for leg in legs] == [1, 2, 3, 4, 5, 6]
    assert results['duration'] == 2.0
    # At 100 Hz the samples hold 0, 0.01, ..., 2 s: the peaks are among them or the
    # waypoints' other sides, so the largest force on the 10 ms grid is a lower bound that the
    # peak meets within the force's change over a step.
    grid = np.linspace(0.0, 2.0, 201)
    forces, speeds = independent_forces(grid)
    for leg in legs:
        column = leg['leg'] - 1
        assert leg['peak_push'] >= forces[:, column].max() - 1e-9
        assert leg['peak_push'] == pytest.approx(max(forces[:, column].max(), 0.0), abs=2.0)
        assert leg['peak_pull'] == pytest.approx(max(-forces[:, column].min(), 0.0), abs=2.0)
        assert leg['peak_speed'] == pytest.approx(np.abs(speeds[:, column]).max(), rel=1e-3)
    # Legs 1, 2 and 4 push hardest at the end, as the payload stops: exactly the end's forces.
    end, _ = independent_forces([2.0])
    for leg in (1, 2, 4):
        assert legs[leg - 1]['peak_push'] == pytest.approx(end[0, leg - 1], rel=1e-9)
        assert legs[leg - 1]['peak_push_time'] == 2.0
    # The table on stdout says the same, to its decimals.
    rows = [line for line in out.splitlines() if line.strip()[:1].isdigit()
            and '|' in line]
    assert len(rows) == 6
    for row, leg in zip(rows, legs):
        cells = [cell.strip() for cell in row.split('|')]
        assert cells[1] == f'{leg["peak_push"]:.1f} ({leg["peak_push_time"]:.3f})'
        assert cells[3] == f'{leg["rms_force"]:.1f}'
        assert cells[5].endswith('delivered' if leg['peak_power_delivered'] else 'absorbed')
    # The CSV holds the JSON's numbers.
    with open(paths['csv'], encoding='utf-8', newline='') as stream:
        table = list(csv.DictReader(stream))
    assert tuple(table[0]) == CSV_COLUMNS
    for row, leg in zip(table, legs):
        for name in ('peak_push', 'rms_force', 'peak_speed', 'peak_power'):
            assert float(row[name]) == pytest.approx(leg[name], rel=1e-12)
    # example_limits.yaml: 0.05 m/s; played in 2 s the ramp needs more, and says so.
    assert 'speed' in ' '.join(results['beyond_limits'])
    assert 'beyond leg_velocity_max 0.05 m/s' in out
    assert figure.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


def test_a_pose_list_of_the_ramp_rows_gives_the_same_peaks(tmp_path, capsys):
    rows = ramp_rows()
    times = np.linspace(0.0, 2.0, 11)
    poses = tmp_path / 'poses.csv'
    with open(poses, 'w', encoding='utf-8') as stream:
        stream.write('# the Table 3 ramp in 2 s, degrees\ntime,X,Y,Z,alpha_deg,beta_deg,'
                     'gamma_deg\n')
        for time, row in zip(times, rows):
            stream.write(','.join(repr(float(value)) for value in (
                time, *row[:3], *np.degrees(row[3:]))) + '\n')
    radians = tmp_path / 'radians.csv'
    with open(radians, 'w', encoding='utf-8') as stream:
        stream.write('time,X,Y,Z,alpha,beta,gamma\n')
        for time, row in zip(times, rows):
            stream.write(','.join(repr(float(value)) for value in (time, *row)) + '\n')
    outputs = []
    for source in (['--poses', str(poses)], ['--poses', str(radians)], RAMP):
        json_path = tmp_path / f'{len(outputs)}.json'
        code, _, err = run(source + PARAMS + ['--json', str(json_path)], capsys)
        assert code == 0, err
        outputs.append(json.loads(json_path.read_text(encoding='utf-8'))['legs'])
    for legs in outputs[:2]:
        for leg, other in zip(legs, outputs[2]):
            for name in ('peak_push', 'peak_pull', 'rms_force', 'peak_speed', 'peak_power'):
                assert leg[name] == pytest.approx(other[name], rel=1e-9, abs=1e-9)


def test_retimed_the_ramp_keeps_the_leg_speed_limit(tmp_path, capsys):
    """Retimed to example_limits.yaml's 0.05 m/s and 0.25 m/s^2, the ramp takes about 3 s."""
    json_path = tmp_path / 'retimed.json'
    code, out, err = run(['--trajectory', str(CONFIG / 'table3_ramp.yaml'), '--retime']
                         + PARAMS + ['--json', str(json_path)], capsys)
    assert code == 0, err
    results = json.loads(json_path.read_text(encoding='utf-8'))
    assert 2.9 < results['duration'] < 3.1
    assert max(leg['peak_speed'] for leg in results['legs']) == pytest.approx(0.05, rel=1e-3)
    assert all(leg['peak_speed'] <= 0.05 * (1 + 1e-6) for leg in results['legs'])
    assert 'retimed to the leg speed and acceleration limits' in out
    assert 'every peak within the limits given' in out
    for argv in (['--scenario', 'lap', '--retime'] + PARAMS, RAMP + ['--retime'] + PARAMS):
        with pytest.raises(SystemExit) as raised:
            main(argv)
        assert raised.value.code == 2 and 'argument --retime' in capsys.readouterr().err


def test_retiming_without_rate_limits_is_refused_in_one_line(capsys):
    code, _, err = run(['--trajectory', str(CONFIG / 'table3_ramp.yaml'), '--retime',
                        '--params-file', str(CONFIG / 'paper_platform.yaml')], capsys)
    assert code == 2 and err.count('\n') == 1, err


def test_peak_power_is_drawn_and_checked(tmp_path, capsys):
    figure = tmp_path / 'forces.png'
    code, out, err = run(RAMP + PARAMS + ['--peak-power', '2', '--figure', str(figure)],
                         capsys)
    assert code == 0, err
    assert 'beyond --peak-power 2 W' in out
    assert figure.stat().st_size > 10_000


def test_a_cueing_scenario_runs_through_the_motion_cueing(tmp_path, capsys):
    json_path = tmp_path / 'scenario.json'
    code, out, err = run(['--scenario', 'acceleration_braking', '--rate', '50'] + PARAMS
                         + ['--params-file', str(CONFIG / 'motion_cueing.yaml'),
                            '--json', str(json_path)], capsys)
    assert code == 0, err
    results = json.loads(json_path.read_text(encoding='utf-8'))
    assert 'acceleration_braking' in results['motion']
    # The platform mostly holds its weight: every leg pushes about a sixth of the ~50 kg
    # (platform, payload, legs) at rest, more or less while it tilts.
    for leg in results['legs']:
        assert 40.0 < leg['rms_force'] < 150.0
        assert leg['peak_speed'] < 0.05       # the cueing keeps leg_velocity_max
    assert 'every peak within the limits given' in out


def write(path, text):
    path.write_text(text, encoding='utf-8')
    return str(path)


BAD_POSE_FILES = {
    'header': ('time,x,y\n0,1,2\n', 'the header must be'),
    'nan': ('time,X,Y,Z,alpha,beta,gamma\n0,0,0,0.4325,0,0,0\n1,0,0,nan,0,0,0\n',
            'line 3: Z must be a finite number'),
    'short': ('time,X,Y,Z,alpha,beta,gamma\n0,0,0,0.4325,0,0,0\n1,0,0\n',
              'line 3: expected 7 values, got 3'),
    'one pose': ('time,X,Y,Z,alpha,beta,gamma\n0,0,0,0.4325,0,0,0\n', 'at least 2 poses'),
    'back': ('time,X,Y,Z,alpha,beta,gamma\n1,0,0,0.4325,0,0,0\n0,0,0,0.44,0,0,0\n',
             'times'),
    'empty': ('', 'no header and no data'),
    'huge field': ('time,X,Y,Z,alpha,beta,gamma\n0,0,0,0.4325,0,0,0\n1,' + '1' * 200_000
                   + ',0,0.44,0,0,0\n', 'not a CSV file of poses: field larger'),
    'nul': ('time,X,Y,Z,alpha,beta,gamma\n0,0,0,0.4325,0,0,0\n1,0\x00,0,0.44,0,0,0\n',
            'line 3: X must be a finite number'),
    'too many': ('time,X,Y,Z,alpha,beta,gamma\n' + '0,0,0,0.4325,0,0,0\n' * 100_001,
                 'at most 100,000 poses'),
    'repeated time': ('time,X,Y,Z,alpha,beta,gamma\n0,0,0,0.4325,0,0,0\n0,0,0,0.44,0,0,0\n',
                      'increase strictly'),
    'huge': ('time,X,Y,Z,alpha,beta,gamma\n0,0,0,0.4325,0,0,0\n1,1e308,0,0.44,0,0,0\n',
             'positions'),
}


@pytest.mark.parametrize('case', sorted(BAD_POSE_FILES))
def test_a_bad_pose_list_is_one_line_and_exit_2(tmp_path, capsys, case):
    text, words = BAD_POSE_FILES[case]
    code, out, err = run(['--poses', write(tmp_path / 'poses.csv', text)] + PARAMS, capsys)
    assert code == 2
    assert err.startswith('stewart_forces: error: ') and err.count('\n') == 1, err
    assert words in err
    assert 'Traceback' not in err


def test_force_limits_and_pose_limits_are_reported(tmp_path, capsys):
    """leg_force_min -50 N and leg_force_max 200 N: leg 3 pulls 121.6 N, leg 4 pushes 223.3 N."""
    limits = write(tmp_path / 'actuator.yaml', '/**:\n  ros__parameters:\n'
                   '    leg_force_min: -50.0\n    leg_force_max: 200.0\n')
    json_path = tmp_path / 'out.json'
    code, out, err = run(RAMP + PARAMS + ['--params-file', limits, '--json', str(json_path)],
                         capsys)
    assert code == 0, err
    legs = json.loads(json_path.read_text(encoding='utf-8'))['legs']
    assert legs[2]['peak_pull'] > 50.0 and legs[3]['peak_push'] > 200.0
    assert f'leg 3: pull {legs[2]["peak_pull"]:.1f} N at 2.000 s beyond leg_force_min -50 N' in out
    assert f'leg 4: push {legs[3]["peak_push"]:.1f} N at 2.000 s beyond leg_force_max 200 N' in out
    assert 'break the pose limits' in out and 'leg 3: leg_force_min -50 N broken' in out
    assert sum(leg['peak_push'] > 200.0 or leg['peak_pull'] > 50.0 for leg in legs) == 2


def test_a_motion_at_rest_has_no_power_sign(tmp_path, capsys):
    poses = write(tmp_path / 'rest.csv', 'time,X,Y,Z,alpha,beta,gamma\n0,0,0,0.4325,0,0,0\n'
                  '1,0,0,0.4325,0,0,0\n')
    json_path = tmp_path / 'rest.json'
    code, out, err = run(['--poses', poses, '--json', str(json_path)] + PARAMS, capsys)
    assert code == 0, err
    for leg in json.loads(json_path.read_text(encoding='utf-8'))['legs']:
        assert leg['peak_power'] == 0.0 and leg['peak_power_delivered'] is None
        assert leg['peak_speed'] == 0.0 and leg['peak_push'] > 0.0
        assert leg['rms_force'] == pytest.approx(leg['peak_push'], rel=1e-12)
    assert 'absorbed' not in out.split('power: ')[0]


def test_a_parameter_file_without_a_ramp_is_refused(capsys):
    code, _, err = run(['--trajectory', str(CONFIG / 'paper_platform.yaml')] + PARAMS, capsys)
    assert code == 2 and err.count('\n') == 1 and 'no ramp in it' in err, err


def test_a_huge_pose_file_is_refused_before_it_is_read(tmp_path, capsys):
    huge = tmp_path / 'huge.csv'
    with open(huge, 'wb') as stream:
        stream.truncate(33 * 1024 * 1024)     # sparse: 33 MB of NUL bytes, nothing written
    code, _, err = run(['--poses', str(huge)] + PARAMS, capsys)
    assert code == 2 and err.count('\n') == 1 and 'more than a list of 100,000 poses' in err, err


def test_a_bad_ramp_file_is_one_line_and_exit_2(tmp_path, capsys):
    ramp = write(tmp_path / 'ramp.yaml', 'trajectory_node:\n  ros__parameters:\n'
                 '    position_step: [0.01, 0.015, 0.0123]\n')
    code, _, err = run(['--trajectory', ramp, '--duration', '2'] + PARAMS, capsys)
    assert code == 2 and err.count('\n') == 1 and 'ramp axis Z' in err, err
    not_yaml = write(tmp_path / 'garbled.yaml', 'trajectory_node: [\n')
    code, _, err = run(['--trajectory', not_yaml] + PARAMS, capsys)
    assert code == 2 and err.count('\n') == 1 and 'argument --trajectory' in err, err


def test_bad_parameters_are_one_line_and_exit_2(tmp_path, capsys):
    masses = write(tmp_path / 'masses.yaml', '/**:\n  ros__parameters:\n'
                   '    payload_mass: -1.0\n')
    code, _, err = run(RAMP + PARAMS + ['--params-file', masses], capsys)
    assert code == 2 and err.count('\n') == 1 and 'payload_mass' in err, err
    unknown = write(tmp_path / 'unknown.yaml', '/**:\n  ros__parameters:\n    payload: 1.0\n')
    code, _, err = run(RAMP + PARAMS + ['--params-file', unknown], capsys)
    assert code == 2 and err.count('\n') == 1 and 'argument --params-file' in err, err


@pytest.mark.parametrize('options, words', [
    (['--rate', 'nan'], 'argument --rate'),
    (['--rate', '0'], 'argument --rate'),
    (['--duration', '-1'], 'argument --duration'),
    (['--duration', 'inf'], 'argument --duration'),
    (['--peak-power', '0'], 'argument --peak-power'),
])
def test_bad_options_exit_2_naming_them(capsys, options, words):
    with pytest.raises(SystemExit) as raised:
        main(RAMP[:2] + PARAMS + options)
    assert raised.value.code == 2
    assert words in capsys.readouterr().err


def test_options_that_do_not_fit_exit_2(tmp_path, capsys):
    poses = write(tmp_path / 'poses.csv', 'time,X,Y,Z,alpha,beta,gamma\n')
    for argv, words in (
            (['--poses', poses, '--duration', '2'] + PARAMS, 'only with --trajectory'),
            (PARAMS, 'one of the arguments'),
            (RAMP + ['--poses', poses] + PARAMS, 'not allowed with'),
            (['--poses', str(tmp_path / 'missing.csv')] + PARAMS, 'is not a file'),
            (RAMP + PARAMS + ['--json', str(tmp_path)], 'argument --json'),
            (['--scenario', 'rally'] + PARAMS, 'argument --scenario')):
        with pytest.raises(SystemExit) as raised:
            main(argv)
        assert raised.value.code == 2
        assert words in capsys.readouterr().err


def test_a_scenario_at_a_rate_beyond_a_trajectory_is_refused_before_the_replay(capsys):
    code, _, err = run(['--scenario', 'lap', '--rate', '5000'] + PARAMS, capsys)
    assert code == 2 and err.count('\n') == 1 and 'lower --rate' in err, err


def test_too_many_samples_are_refused(capsys):
    code, _, err = run(['--trajectory', str(CONFIG / 'table3_ramp.yaml'), '--duration',
                        '100000', '--rate', '10000'] + PARAMS, capsys)
    assert code == 2 and 'samples' in err and err.count('\n') == 1, err
