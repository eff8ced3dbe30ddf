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
The ``stewart_geometry`` console script, run as a process as a user runs it.

Its exit codes (0 taken, 1 refused, 2 a bad option or file, 3 warnings under --strict), its
text and its JSON, against the core's report computed here and the numbers the example files'
comments promise.
"""

import json
from pathlib import Path
import subprocess

import pytest

from stewart_kinematics import load_geometry
from stewart_kinematics.analysis.capabilities import geometry_report
from stewart_kinematics.tools.node_processes import find_executable

pytestmark = pytest.mark.process

CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: Generous: the report is short work, but a loaded machine may be many times slower.
DEADLINE = 120.0


def run_tool(*arguments):
    """Run stewart_geometry; return the completed process."""
    return subprocess.run([find_executable('stewart_geometry'), *map(str, arguments)],
                          capture_output=True, text=True, timeout=DEADLINE, check=False)


def test_the_6_3_platform_is_reported(tmp_path):
    done = run_tool('--params-file', CONFIG / 'platform_6_3.yaml')
    assert done.returncode == 0, done.stderr
    assert done.stderr == ''
    text = done.stdout
    assert 'Design: 6-3 (legs 1 and 6, 2 and 3, 4 and 5 share their platform joints)' in text
    assert 'Home leg lengths: 0.716491, 0.716491, 0.716491, 0.716491, 0.716491, 0.716491 m' in text
    assert 'Condition number at home: 6.514' in text
    assert 'leg_collision 40 mm: at home 135.318 mm (legs 5 and 6), margin 95.32 mm' in text
    assert ("Assembly modes of home's leg lengths: 16 real (1 within the limits), 0 complex, "
            '24 at infinity') in text
    assert 'Workspace at the home orientation: ' in text and 'Warnings: none' in text
    for axis in ('X', 'Y', 'Z', 'alpha', 'beta', 'gamma'):
        assert any(line.startswith(axis + ' ') for line in text.splitlines()), axis


def test_json_holds_the_cores_numbers():
    path = CONFIG / 'platform_3_3.yaml'
    done = run_tool('--params-file', path, '--json', '--volume-resolution-mm', '40')
    assert done.returncode == 0, done.stderr
    numbers = json.loads(done.stdout)
    report = geometry_report(load_geometry(path), volume_resolution=0.04)
    assert numbers['parameter_files'] == [str(path)]
    assert numbers['design'] == '3-3' and len(numbers['shared_joints']) == 6
    assert numbers['home_condition'] == report.home_condition
    assert numbers['workspace_volume']['volume_m3'] == report.volume.volume
    assert numbers['workspace_volume']['resolution_m'] == 0.04
    assert numbers['assembly_modes'] == {
        'real': 16, 'within_limits': 1, 'complex': 0, 'at_infinity': 24, 'paths': 16,
        'complete': True, 'nearest_other_distance_m': 'inf', 'nearest_other_pose': None}
    assert numbers['travel_ranges']['gamma']['positive_limit'] == 'max_jacobian_condition'
    assert numbers['warnings'] == []


def test_a_home_pose_beyond_a_limit_exits_1_with_the_report(tmp_path):
    shorter = tmp_path / 'short_actuators.yaml'
    shorter.write_text('/**:\n  ros__parameters:\n    leg_length_max: 0.70\n',
                       encoding='utf-8')
    done = run_tool('--params-file', CONFIG / 'platform_6_3.yaml', '--params-file', shorter)
    assert done.returncode == 1, done.stdout + done.stderr
    assert 'leg_length_max 700 mm: at home 716.491 mm (leg 2), margin -16.49 mm BROKEN' in (
        done.stdout)
    assert 'Refused by the nodes: the home pose breaks the limits' in done.stdout
    assert '[limit_broken_at_home]' in done.stdout and 'Traceback' not in done.stderr


def test_warnings_exit_3_only_under_strict():
    arguments = ['--params-file', CONFIG / 'paper_platform.yaml', '--volume-resolution-mm', '100']
    relaxed, strict = run_tool(*arguments), run_tool(*arguments, '--strict')
    assert relaxed.returncode == 0 and strict.returncode == 3, strict.stderr
    assert '[other_mode_within_limits] 10 assembly modes' in strict.stdout


def test_joints_that_make_no_platform_exit_1_in_one_line(tmp_path):
    three = tmp_path / 'three_on_one.yaml'
    three.write_text('/**:\n  ros__parameters:\n    base_joints: [' + ', '.join(
        ['0.1125, 0.1948557, 0.0'] * 3 + ['0.1125, -0.1948557, 0.0', '-0.225, 0.0, 0.0',
                                          '-0.225, 0.0, 0.0']) + ']\n', encoding='utf-8')
    done = run_tool('--params-file', CONFIG / 'platform_3_3.yaml', '--params-file', three)
    assert done.returncode == 1 and done.stdout == ''
    assert done.stderr.count('\n') == 1 and 'Traceback' not in done.stderr
    assert done.stderr.startswith('stewart_geometry: ')
    assert 'base_joints: joints 1, 2 and 3 coincide (3 legs on one point)' in done.stderr


@pytest.mark.parametrize('arguments, words', [
    (['--params-file', 'config/platform_6_3.yaml', '--volume-resolution-mm', '0'],
     'argument --volume-resolution-mm: must be in [5, 200], got'),
    (['--params-file', 'config/platform_6_3.yaml', '--volume-resolution-mm', 'nan'],
     'argument --volume-resolution-mm: must be finite'),
    ([], 'the following arguments are required: --params-file'),
    (['--params-file', 'no/such/file.yaml'], 'argument --params-file: no/such/file.yaml'),
])
def test_a_bad_option_or_file_exits_2_in_one_line(arguments, words):
    done = subprocess.run([find_executable('stewart_geometry'), *arguments],
                          capture_output=True, text=True, timeout=DEADLINE, check=False,
                          cwd=CONFIG.parent)
    assert done.returncode == 2 and words in done.stderr, done.stderr
    assert 'Traceback' not in done.stderr and done.stdout == ''
    assert done.stderr.strip().splitlines()[-1].startswith('stewart_geometry: error: ')


def test_the_how_to_shows_what_the_tool_prints():
    """Each line of the own-platform how-to's excerpt is a line the tool prints for the 6-3."""
    page = (CONFIG.parent / 'doc' / 'how-to' / 'own_platform.md').read_text(encoding='utf-8')
    excerpt = page.split('checks the geometry and prints the report; for the example:', 1)[1]
    excerpt = excerpt.split('```text\n', 1)[1].split('```', 1)[0]
    done = run_tool('--params-file', CONFIG / 'platform_6_3.yaml')
    printed = done.stdout.splitlines()
    for line in excerpt.splitlines():
        assert line in printed, line
