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
Hostile parameter files, for the package's YAML reader, its command-line tools and its nodes.

What issue 27 found by hand, drawn from a seed: a 504-byte alias bomb hung three tools for
minutes, a list 100,000 deep or a mapping 3,000 deep ended every tool with a RecursionError
traceback, and a null value was reported as a string written in quotes. :func:`hostile_file`
draws one file of a kind of :data:`KINDS`:

- ``alias_bomb``: nested aliases of 2 to 10 values over 2 to 9 levels (lists, mappings, or a
  merge key), up to 10^9 values from a few hundred bytes;
- ``deep_list`` and ``deep_mapping``: nesting just past the reader's limit up to 100,000
  levels, in flow (``[[[``) and block style;
- ``null_value``: a geometry parameter set to ``null``, ``~``, ``Null``, ``NULL`` or nothing,
  alone or in a list;
- ``huge_scalar``: a value or a key of 10^4 to 10^7 characters (letters or digits);
- ``garbled``: the shipped platform file with a few characters changed, inserted or cut.

The invariants: the reader (:func:`reader_problems`, in this process) answers within
:data:`DEADLINE` seconds with values or a :class:`~stewart_kinematics.parameters.
ParameterFileError` of one line naming the file and no longer than :data:`MESSAGE_LIMIT`; a file
of the first three kinds is refused; a refusal of a null calls it null (or empty), never a value
in quotes. A tool (:func:`command_problems`, as a process) exits 0, 1 or 2 within the deadline
without a traceback, and on exit 2 writes one line naming the file; a node refuses to start
(exit 1, a fatal ``cannot start`` line naming the file) or starts.

``python -m fuzzing.fuzz_parameter_files --minutes 5`` draws files until the time is up (the
reader only; ``--processes`` also gives each file to every tool and to ik_node); each failure
prints the seed that replays it.
"""

import argparse
import contextlib
from dataclasses import dataclass
import gc
from pathlib import Path
import random
import signal
import subprocess
import sys
import tempfile
import threading
import time
from typing import Callable, List, Optional

from stewart_kinematics import parameters
from stewart_kinematics.parameters import ParameterFileError, read_parameter_files
from stewart_kinematics.parameters.rcl_yaml import MAX_DEPTH

#: The kinds of hostile file :func:`hostile_file` draws.
KINDS = ('alias_bomb', 'deep_list', 'deep_mapping', 'null_value', 'huge_scalar', 'garbled')
#: Seconds the reader, a tool or a node has to answer one file.
DEADLINE = 5.0
#: Longest error line allowed, in characters (a refusal previews a huge value, never echoes it).
MESSAGE_LIMIT = 2000
#: The first lines of every drawn file but the garbled ones: a layer over the platform file.
HEADER = '/**:\n  ros__parameters:\n'
#: Geometry parameters: every tool and every node reads them, so a null one is refused by all.
NULL_TARGETS = tuple(spec for spec in parameters.GEOMETRY_PARAMETERS
                     if spec.value_type in (parameters.DOUBLE, parameters.DOUBLE_ARRAY))
#: The platform file the drawn files are layered over (and the garbled ones are made from).
CONFIG_DIRECTORY = Path(__file__).resolve().parent.parent / 'config'
PLATFORM_FILE = CONFIG_DIRECTORY / 'paper_platform.yaml'


@dataclass(frozen=True)
class HostileFile:
    """
    One drawn parameter file and what the reader must make of it.

    :param kind: one of :data:`KINDS`.
    :param data: the file's bytes.
    :param note: what it is, in words (``alias bomb 9^9 = 387420489 values``).
    :param refused: the reader must refuse it (``False``: either answer is right).
    :param null: the word of a null value (``null``, ``~``, ``''`` for an empty one), if that
        is the change: a refusal must call it null or empty, not a value in quotes.
    :param reason: a word the refusal must hold (``alias``): refused for the right reason.
    """

    kind: str
    data: bytes
    note: str
    refused: bool
    null: Optional[str] = None
    reason: str = ''

    def write(self, directory: Path, name: str = 'hostile.yaml') -> Path:
        """Write the file into ``directory``; return its path."""
        path = Path(directory) / name
        path.write_bytes(self.data)
        return path


def hostile_file(rng: random.Random, kind: Optional[str] = None,
                 max_bytes: int = 20_000_000) -> HostileFile:
    """
    Draw one hostile parameter file.

    :param kind: one of :data:`KINDS` (default: drawn).
    :param max_bytes: largest file to draw (huge scalars and deep block nesting are smaller
        below it), to keep a quick run quick.
    """
    kind = kind or rng.choice(KINDS)
    return _GENERATORS[kind](rng, max_bytes)


def alias_bomb(rng: random.Random, max_bytes: int = 0, levels: Optional[int] = None,
               width: Optional[int] = None, style: Optional[str] = None) -> HostileFile:
    """Return nested aliases: ``width`` values on each of ``levels`` levels (lists, mappings)."""
    levels = levels or rng.randint(2, 9)
    width = width or rng.randint(2, 10)
    style = style or rng.choice(('list', 'mapping', 'merge'))
    if style == 'merge':
        text = HEADER + ('    base: &base {leg_length_max: 0.9, leg_length_min: 0.6}\n'
                         '    limits:\n      <<: *base\n')
        return HostileFile('alias_bomb', text.encode(), 'one merge key (<<: *base)', True,
                           reason='alias')
    lines = ['lol: &a0 [' + ', '.join(['"lol"'] * width) + ']']
    for level in range(1, levels):
        if style == 'list':
            items = ', '.join([f'*a{level - 1}'] * width)
            lines.append(f'l{level}: &a{level} [{items}]')
        else:
            items = ', '.join(f'k{index}: *a{level - 1}' for index in range(width))
            lines.append(f'm{level}: &a{level} {{{items}}}')
    text = HEADER + ''.join(f'    {line}\n' for line in lines)
    return HostileFile('alias_bomb', text.encode(), (
        f'alias bomb of {style}s, {width}^{levels} = {width ** levels} values from '
        f'{len(text)} bytes'), True, reason='alias')


def deep_list(rng: random.Random, max_bytes: int = 20_000_000,
              depth: Optional[int] = None, style: Optional[str] = None) -> HostileFile:
    """Return a list nested ``depth`` deep below a parameter name: ``[[[1.0]]]`` or ``- - 1.0``."""
    depth = depth or rng.choice((MAX_DEPTH, MAX_DEPTH + 1, 1000, 100_000))
    depth = min(depth, max(MAX_DEPTH + 1, max_bytes // 3))
    style = style or rng.choice(('flow', 'block'))
    body = '[' * depth + '1.0' + ']' * depth if style == 'flow' else '- ' * depth + '1.0'
    text = HEADER + '    deep_list:\n      ' + body + '\n'
    refused = depth + 3 > MAX_DEPTH
    return HostileFile('deep_list', text.encode(), f'a list {depth} deep ({style})', refused,
                       reason='nested' if refused else '')


def deep_mapping(rng: random.Random, max_bytes: int = 20_000_000,
                 depth: Optional[int] = None, style: Optional[str] = None) -> HostileFile:
    """Return a mapping nested ``depth`` deep below ``ros__parameters``, flow or block style."""
    depth = depth or rng.choice((MAX_DEPTH - 2, MAX_DEPTH, 3000, 10_000))
    style = style or rng.choice(('flow', 'block'))
    if style == 'block':   # indentation grows with depth: the text with its square
        depth = min(depth, 3000, max(MAX_DEPTH, int((max_bytes / 2) ** 0.5)))
        body = ''.join(f'{" " * (4 + 2 * level)}k{level}:\n' for level in range(depth - 1))
        body += f'{" " * (4 + 2 * (depth - 1))}k{depth - 1}: 1.0\n'
    else:
        depth = min(depth, max(MAX_DEPTH, max_bytes // 5))
        body = '    deep: ' + '{k: ' * (depth - 1) + '{k: 1.0' + '}' * depth + '\n'
    text = HEADER + body
    refused = depth + 2 > MAX_DEPTH
    return HostileFile('deep_mapping', text.encode(), f'a mapping {depth} deep ({style})',
                       refused, reason='nested' if refused else '')


def null_value(rng: random.Random, max_bytes: int = 0, name: Optional[str] = None,
               word: Optional[str] = None, in_list: Optional[bool] = None) -> HostileFile:
    """Return a geometry parameter set to a null (or nothing), alone or as a list item."""
    spec = rng.choice([spec for spec in NULL_TARGETS if name in (None, spec.name)])
    word = rng.choice(('null', '~', 'Null', 'NULL', '')) if word is None else word
    if in_list is None:
        in_list = rng.random() < 0.5
    if spec.value_type == parameters.DOUBLE_ARRAY and in_list:
        if word:
            line = f'    {spec.name}: [0.0, {word}, 0.0]\n'
        else:
            line = f'    {spec.name}:\n      - 0.0\n      -\n      - 0.0\n'
    else:
        line = f'    {spec.name}: {word}\n'
    return HostileFile('null_value', (HEADER + line).encode(),
                       f'{spec.name} set to {word or "nothing"}', True, null=word)


def huge_scalar(rng: random.Random, max_bytes: int = 20_000_000) -> HostileFile:
    """Return a value or a key of 10^4 to 10^7 characters."""
    size = min(rng.choice((10 ** 4, 10 ** 5, 10 ** 6, 10 ** 7)), max(1000, max_bytes - 100))
    text = (rng.choice(('x', '7', '9.', '1e')) * size)[:size]
    place = rng.choice(('double value', 'quoted value', 'string value', 'key', 'list item'))
    # A key longer than 1024 characters must be explicit (? key) in YAML.
    line = {'double value': f'    leg_length_max: {text}\n',
            'quoted value': f"    leg_length_max: '{text}'\n",
            'string value': f"    base_frame: '{text}'\n",
            'key': f'    ? {text}\n    : 1.0\n',
            'list item': f'    home_position: [0.0, 0.0, {text}]\n'}[place]
    return HostileFile('huge_scalar', (HEADER + line).encode(),
                       f'a {place} of {len(text)} characters', False)


def garbled(rng: random.Random, max_bytes: int = 0) -> HostileFile:
    """Return the shipped platform file with one to eight characters changed, inserted or cut."""
    data = bytearray(PLATFORM_FILE.read_bytes())
    changes = []
    for _ in range(rng.randint(1, 8)):
        at = rng.randrange(len(data))
        byte = rng.choice(b'[]{}:-&*!|>\'"#,\t\n ~0.\x00\xff\xc3')
        action = rng.choice(('change', 'insert', 'cut'))
        if action == 'change':
            data[at] = byte
        elif action == 'insert':
            data.insert(at, byte)
        else:
            del data[at]
        changes.append(f'{action} {bytes([byte])!r} at {at}')
    return HostileFile('garbled', bytes(data), 'platform file: ' + ', '.join(changes), False)


_GENERATORS = {'alias_bomb': alias_bomb, 'deep_list': deep_list, 'deep_mapping': deep_mapping,
               'null_value': null_value, 'huge_scalar': huge_scalar, 'garbled': garbled}


class _Late(BaseException):
    """Raised in the main thread when the reader runs past its deadline."""


@contextlib.contextmanager
def _deadline(seconds: float):
    """
    Interrupt the block after ``seconds`` (main thread only; elsewhere, time it after).

    The collector is off meanwhile (an exception raised in one of its callbacks is lost), and
    the alarm repeats every 50 ms until the block ends, in case one is lost anyway.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    state = {'active': True}
    collecting = gc.isenabled()
    gc.disable()

    def interrupt(number, frame):
        if state['active']:
            raise _Late()
    previous = signal.signal(signal.SIGALRM, interrupt)
    signal.setitimer(signal.ITIMER_REAL, seconds, 0.05)
    try:
        yield
    finally:
        while True:   # an alarm may land here too: stop it, whatever it raises
            try:
                state['active'] = False
                signal.setitimer(signal.ITIMER_REAL, 0.0)
                signal.signal(signal.SIGALRM, previous)
                break
            except _Late:
                continue
        if collecting:
            gc.enable()


def reader_problems(hostile: HostileFile, directory: Path,
                    reader: Callable = None, deadline: float = DEADLINE) -> List[str]:
    """
    Read a hostile file (layered over the platform file) and check the reader's answer.

    :param reader: ``reader(paths)``; default :func:`~stewart_kinematics.parameters.
        read_parameter_files`, the reader of every tool.
    :returns: the invariants broken, in words (empty when all hold).
    """
    reader = reader or read_parameter_files
    path = hostile.write(directory)
    started = time.monotonic()
    error = None
    try:
        with _deadline(deadline):
            reader([PLATFORM_FILE, path])
    except _Late:
        return [f'{hostile.note}: no answer within {deadline:g} s']
    except ParameterFileError as refusal:
        error = refusal
    except RecursionError:
        return [f'{hostile.note}: RecursionError']
    except Exception as other:   # noqa: B902  (any other exception is the finding)
        return [f'{hostile.note}: {type(other).__name__}: {str(other)[:200]}']
    seconds = time.monotonic() - started
    problems = []
    if seconds > deadline:
        problems.append(f'{hostile.note}: answered after {seconds:.1f} s')
    if error is None:
        if hostile.refused:
            problems.append(f'{hostile.note}: read without a refusal')
        return problems
    return problems + message_problems(hostile, str(error), str(path))


def message_problems(hostile: HostileFile, message: str, path: str) -> List[str]:
    """Check a refusal's message: one line, naming the file, short, a null called null."""
    problems = []
    if '\n' in message.strip():
        problems.append(f'{hostile.note}: a refusal of several lines: {message[:200]!r}')
    if path not in message:
        problems.append(f'{hostile.note}: a refusal not naming the file: {message[:200]!r}')
    if len(message) > MESSAGE_LIMIT:
        problems.append(f'{hostile.note}: a refusal of {len(message)} characters')
    if hostile.reason and hostile.reason not in message:
        problems.append(f'{hostile.note}: refused, but not for its {hostile.reason}: '
                        f'{message[:200]!r}')
    if hostile.null is not None:
        if 'in quotes' in message:
            problems.append(f'{hostile.note}: a null reported as a value in quotes: '
                            f'{message[:300]!r}')
        if 'empty' not in message or (hostile.null and hostile.null not in message):
            problems.append(f'{hostile.note}: a null not reported as one: {message[:300]!r}')
    return problems


def tool_commands(path: Path, directory: Path) -> dict:
    """Return each command-line tool's arguments on a hostile file: a short run when read."""
    samples = directory / 'samples.csv'
    if not samples.exists():
        samples.write_text(
            'time,specific_force_x,specific_force_y,specific_force_z,angular_velocity_x,'
            'angular_velocity_y,angular_velocity_z\n' + ''.join(
                f'{0.01 * row:.2f},0.0,0.0,9.80665,0.0,0.0,0.0\n' for row in range(21)))
    layered = ['--params-file', str(PLATFORM_FILE), '--params-file', str(path)]
    return {
        'stewart_workspace': layered + [
            '--no-figures', '--output', str(directory / 'workspace'), '--slice-resolution-mm',
            '20', '--volume-resolution-mm', '50', '--angle-resolution-deg', '5'],
        'stewart_calibrate': layered + ['--propose', '10', '--poses-out',
                                        str(directory / 'poses.csv')],
        'stewart_cueing': layered + ['--csv', str(samples), '--no-figures', '--quiet',
                                     '--output', str(directory / 'cueing')],
        'stewart_geometry': layered + ['--volume-resolution-mm', '100'],
        'stewart_forces': layered + ['--trajectory', str(CONFIG_DIRECTORY / 'table3_ramp.yaml'),
                                     '--duration', '2', '--rate', '10'],
        'stewart_payload': layered + ['--propose', '4', '--poses-out',
                                      str(directory / 'payload_poses.csv')],
    }


def command_problems(command: List[str], hostile: HostileFile, path: Path,
                     node: bool = False, deadline: float = DEADLINE) -> List[str]:
    """
    Run a tool or a node on a hostile file and check how it ends.

    :param command: the executable and its arguments (the file among them).
    :param node: a node: it must refuse with exit 1 and a fatal line, or start (then it is
        stopped after ``deadline``); a tool must exit 0, 1 or 2.
    """
    name = Path(command[0]).name
    try:
        completed = subprocess.run(command, capture_output=True, text=True, timeout=deadline,
                                   errors='replace')
    except subprocess.TimeoutExpired as expired:
        if node and not hostile.refused:
            return []   # started, as it may
        output = (expired.stderr or b'')[-300:]
        return [f'{name} on {hostile.note}: no answer within {deadline:g} s {output!r}']
    output = completed.stdout + completed.stderr
    problems = []
    if 'Traceback' in output:
        problems.append(f'{name} on {hostile.note}: a traceback: {output[-500:]!r}')
    if node:
        refusals = [line for line in output.splitlines() if 'cannot start:' in line]
        if completed.returncode != 1 or not refusals:
            problems.append(f'{name} on {hostile.note}: exit {completed.returncode} without a '
                            f'refusal: {output[-300:]!r}')
        elif str(path) in refusals[0]:
            problems += message_problems(hostile, refusals[0].split('cannot start:', 1)[1],
                                         str(path))
        elif hostile.refused:
            problems.append(f'{name} on {hostile.note}: a refusal not naming the file: '
                            f'{refusals[0][:300]!r}')
        return problems
    if completed.returncode not in (0, 1, 2):
        problems.append(f'{name} on {hostile.note}: exit code {completed.returncode}')
    if hostile.refused and completed.returncode != 2:
        problems.append(f'{name} on {hostile.note}: exit {completed.returncode}, not 2: '
                        f'{completed.stderr[-300:]!r}')
    if completed.returncode == 2:
        lines = completed.stderr.strip().splitlines()
        if len(lines) != 1:
            problems.append(f'{name} on {hostile.note}: {len(lines)} lines on stderr: '
                            f'{completed.stderr[:300]!r}')
        problems += message_problems(hostile, completed.stderr, str(path))
    return problems


def fuzz_round(seed: int, directory: Path, processes: bool = False,
               max_bytes: int = 20_000_000) -> List[str]:
    """Draw one file from ``seed``; check the reader (and, with ``processes``, every tool)."""
    from stewart_kinematics.tools.node_processes import find_executable
    hostile = hostile_file(random.Random(seed), max_bytes=max_bytes)
    problems = reader_problems(hostile, directory)
    if processes:
        path = hostile.write(directory)
        for tool, arguments in tool_commands(path, directory).items():
            problems += command_problems([find_executable(tool)] + arguments, hostile, path)
        problems += command_problems(
            [find_executable('ik_node'), '--ros-args', '--params-file', str(PLATFORM_FILE),
             '--params-file', str(path)], hostile, path, node=True)
    return [f'seed {seed}: {problem}' for problem in problems]


def main(argv=None) -> int:
    """Draw hostile files until the time is up; exit 1 if an invariant broke."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--minutes', type=float, default=1.0,
                        help='draw files for this long (default 1)')
    parser.add_argument('--seed', type=int, default=None,
                        help='seed of the first file (default random); file k uses seed + k')
    parser.add_argument('--processes', action='store_true',
                        help='also give every file to each tool and to ik_node, as processes')
    arguments = parser.parse_args(argv)
    seed = arguments.seed if arguments.seed is not None else random.randrange(2 ** 32)
    end = time.monotonic() + 60.0 * arguments.minutes
    failures, count = [], 0
    from stewart_kinematics.tools.node_processes import isolated_ros_environment
    with isolated_ros_environment(), tempfile.TemporaryDirectory() as directory:
        while True:
            problems = fuzz_round(seed + count, Path(directory), arguments.processes)
            for problem in problems:
                print(problem, flush=True)
            failures += problems
            count += 1
            if time.monotonic() >= end:
                break
    print(f'{count} files from seed {seed}, {len(failures)} problem(s)')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
