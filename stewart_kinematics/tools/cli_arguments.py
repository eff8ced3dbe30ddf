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
What the command-line tools share: checked numeric options and output paths checked up front.

Each ``type=`` function here refuses a bad value with ``argparse.ArgumentTypeError``, so that
argparse exits with code 2 and a message naming the option (``argument --max-condition: must
be at least 1, got 0``) before any work starts; :func:`check_output_paths` refuses an output
that cannot be written, also before the work, instead of a traceback at its end.
:func:`refuse_parameter_file` does the same for a parameter file that cannot be read
(:class:`~stewart_kinematics.parameters.ParameterFileError`): exit code 2 and one line naming
the option, the file and the line.
"""

import argparse
import math
import os
from pathlib import Path
import sys

#: Exit code of a bad option or a parameter file that cannot be read (argparse's own).
EXIT_USAGE = 2


def number(text: str) -> float:
    """Parse a finite float (``nan`` and ``inf`` refused)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f'must be a number, got {text!r}') from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f'must be finite, got {text!r}')
    return value


def positive_number(text: str) -> float:
    """Parse a finite float above 0."""
    value = number(text)
    if not value > 0.0:
        raise argparse.ArgumentTypeError(f'must be positive, got {text!r}')
    return value


def number_at_least(low: float):
    """Return a parser of a finite float of at least ``low``."""
    def parse(text: str) -> float:
        value = number(text)
        if not value >= low:
            raise argparse.ArgumentTypeError(f'must be at least {low:g}, got {text!r}')
        return value
    parse.__name__ = f'number >= {low:g}'
    return parse


def number_in(low: float, high: float, *, low_inclusive: bool = True):
    """Return a parser of a finite float in ``[low, high]`` (``(low, high]`` if not inclusive)."""
    def parse(text: str) -> float:
        value = number(text)
        above = value >= low if low_inclusive else value > low
        if not (above and value <= high):
            interval = f'{"[" if low_inclusive else "("}{low:g}, {high:g}]'
            raise argparse.ArgumentTypeError(f'must be in {interval}, got {text!r}')
        return value
    parse.__name__ = f'number in ({low:g}, {high:g}]'
    return parse


def integer_at_least(low: int):
    """Return a parser of an integer of at least ``low``."""
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f'must be an integer, got {text!r}') from None
        if value < low:
            raise argparse.ArgumentTypeError(f'must be at least {low}, got {text!r}')
        return value
    parse.__name__ = f'integer >= {low}'
    return parse


def existing_file(text: str) -> Path:
    """``type=`` of an input file: the path, when it names a file."""
    path = Path(text)
    if not path.is_file():
        raise argparse.ArgumentTypeError(f'{text} is not a file')
    return path


def existing_path(text: str) -> Path:
    """``type=`` of an input that may be a file or a folder (a rosbag2 folder, say)."""
    path = Path(text)
    if not path.exists():
        raise argparse.ArgumentTypeError(f'{text} does not exist')
    return path


def output_problem(path: Path, directory: bool = False) -> str:
    """
    Say why ``path`` cannot be written, or return ``''``.

    :param path: a file to write (its folder is made if missing), or a folder to write into.
    :param directory: whether ``path`` is a folder.
    """
    path = Path(path)
    if directory and path.exists() and not path.is_dir():
        return f'{path} exists and is not a folder'
    if not directory and path.is_dir():
        return f'{path} is a folder, not a file'
    # The nearest existing ancestor must be a folder we may write into.
    existing = path if directory else path.parent
    while not existing.exists():
        if existing.parent == existing:
            break
        existing = existing.parent
    if not existing.is_dir():
        return f'{existing} is not a folder, so {path} cannot be made'
    if not os.access(existing, os.W_OK | os.X_OK):
        return f'{existing} is not writable, so {path} cannot be written'
    if not directory and path.exists() and not os.access(path, os.W_OK):
        return f'{path} is not writable'
    return ''


def check_output_paths(parser: argparse.ArgumentParser, outputs) -> None:
    """
    Refuse unwritable outputs before any work: ``parser.error`` (exit 2) naming the option.

    :param outputs: ``(option, path, is_directory)`` triples; a ``None`` path is skipped.
    """
    for option, path, directory in outputs:
        if path is None:
            continue
        problem = output_problem(path, directory)
        if problem:
            parser.error(f'argument {option}: cannot write there: {problem}')


def refuse_parameter_file(prog: str, error, option: str = '--params-file') -> int:
    """
    Report a parameter file that cannot be read as a bad option is reported; return 2.

    One line on stderr, ``prog: error: argument --params-file: file:line: what is wrong``,
    and no usage: the option is right, the file is not.

    :param prog: the tool's name.
    :param error: the :class:`~stewart_kinematics.parameters.ParameterFileError`.
    :param option: the option that named the file.
    """
    print(f'{prog}: error: argument {option}: {error}', file=sys.stderr)
    return EXIT_USAGE
