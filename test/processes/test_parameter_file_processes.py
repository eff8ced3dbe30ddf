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
Every console script that reads parameter files, run as a user runs it, on hostile files.

The defects (issue 27): a 504-byte alias bomb given as ``--params-file`` hung stewart_workspace,
stewart_cueing and stewart_calibrate for minutes; a list 100,000 deep or a mapping 3,000 deep
ended each with a RecursionError traceback; a null value was reported as a string in quotes.
Now each exits 2 within seconds with one line on stderr naming the file and its line, and no
traceback; ramp_demo does the same for a hostile file in its ``--config-dir``, before any node
starts; a node refuses the file at start (exit 1), also within seconds.
"""

from concurrent.futures import ThreadPoolExecutor
import random
import shutil
import subprocess
import time

from fuzzing.fuzz_parameter_files import (
    alias_bomb,
    command_problems,
    deep_list,
    deep_mapping,
    fuzz_round,
    null_value,
    PLATFORM_FILE,
    tool_commands,
)
import pytest

from stewart_kinematics.tools.node_processes import find_executable

pytestmark = pytest.mark.process

#: Seconds each run may take: far more than a refusal needs (it reads no further than the
#: fault), far less than the hang it replaced (the reader expanded every alias).
DEADLINE = 10.0
#: Processes run at once (the machine's cores are shared).
WORKERS = 3


def hostile_files():
    """Return the four hostile files of the issue, by name: (file, line at fault, words)."""
    rng = random.Random(27)
    return {
        'alias bomb': (alias_bomb(rng, levels=9, width=9, style='list'), 4, 'YAML alias'),
        'list 100000 deep': (deep_list(rng, depth=100_000, style='flow'), 4, 'nested more'),
        'mapping 3000 deep': (deep_mapping(rng, depth=3000, style='flow'), 3, 'nested more'),
        'null value': (null_value(rng, name='leg_length_max', word='null'), 3, 'got null'),
    }


def run(command):
    """Run a command; return (exit code, stdout, stderr, seconds)."""
    started = time.monotonic()
    completed = subprocess.run(command, capture_output=True, text=True, timeout=DEADLINE)
    return (completed.returncode, completed.stdout, completed.stderr,
            time.monotonic() - started)


def test_every_tool_refuses_every_hostile_file_in_one_line(tmp_path):
    files = hostile_files()
    jobs = []
    for name, (hostile, line, words) in files.items():
        folder = tmp_path / name.replace(' ', '_')
        folder.mkdir()
        path = hostile.write(folder)
        for tool, arguments in tool_commands(path, folder).items():
            jobs.append((tool, name, path, line, words, [find_executable(tool)] + arguments))
    with ThreadPoolExecutor(WORKERS) as pool:
        results = list(pool.map(lambda job: run(job[-1]), jobs))
    assert len(results) == len(files) * len(tool_commands(tmp_path, tmp_path)) >= 20
    for (tool, name, path, line, words, _), (code, out, err, seconds) in zip(jobs, results):
        where = f'{tool} on the {name}'
        assert code == 2, f'{where}: exit {code}: {err[-500:]}'
        assert 'Traceback' not in out + err, where
        assert seconds < DEADLINE, where
        lines = err.strip().splitlines()
        assert len(lines) == 1, f'{where}: {err[:500]}'
        assert lines[0].startswith(f'{tool}: error: argument --params-file: {path}:{line}: ')
        assert words in lines[0] and 'in quotes' not in lines[0], lines[0]


def test_ramp_demo_refuses_a_hostile_file_in_its_config_folder_before_any_node(tmp_path):
    config = PLATFORM_FILE.parent
    for name, (hostile, line, words) in hostile_files().items():
        folder = tmp_path / name.replace(' ', '_')
        shutil.copytree(config, folder)
        # The ramp file (trajectory_node's), or the platform (every node's) for the null.
        target = 'paper_platform.yaml' if hostile.null else 'table3_ramp.yaml'
        (folder / target).unlink()
        path = hostile.write(folder, target)
        if hostile.null:   # a layer over the platform: make it a whole platform file again
            path.write_text(PLATFORM_FILE.read_text() + hostile.data.decode().split(
                'ros__parameters:\n', 1)[1])
            line = len(PLATFORM_FILE.read_text().splitlines()) + 1
        code, out, err, seconds = run([find_executable('ramp_demo'), '--config-dir',
                                       str(folder), '--no-figures', '--no-bag'])
        assert code == 2 and 'Traceback' not in out + err, (name, err[-500:])
        assert seconds < DEADLINE and 'ROS_DOMAIN_ID' not in out, name
        assert err.strip() == err.strip().splitlines()[0], err
        assert err.startswith(f'ramp_demo: error: argument --config-dir: {path}:{line}: '), err
        assert words in err, err


def test_a_node_refuses_the_hostile_files_at_start(tmp_path):
    jobs = []
    for name, (hostile, _, _) in hostile_files().items():
        folder = tmp_path / name.replace(' ', '_')
        folder.mkdir()
        path = hostile.write(folder)
        jobs.append((hostile, path, [find_executable('ik_node'), '--ros-args', '--params-file',
                                     str(PLATFORM_FILE), '--params-file', str(path)]))
    with ThreadPoolExecutor(WORKERS) as pool:
        problems = pool.map(lambda job: command_problems(job[2], job[0], job[1], node=True,
                                                         deadline=DEADLINE), jobs)
    assert not [problem for found in problems for problem in found]


def test_a_drawn_hostile_file_keeps_every_invariant(tmp_path):
    # The fuzzer's round (python -m fuzzing.fuzz_parameter_files --processes): the reader,
    # every tool and ik_node on drawn files; kept small (the long run is the script's).
    seed = random.SystemRandom().randrange(2 ** 32)
    problems = fuzz_round(seed, tmp_path, processes=True, max_bytes=1_000_000)
    assert not problems, '\n'.join(problems)
