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
Tables of numbers from CSV files, as the command-line tools read them.

One reader for every tool that takes a CSV of samples (``stewart_cueing --csv``,
``stewart_forces --poses``): a header from a fixed set, then rows of finite numbers; blank
lines and lines starting with ``#`` are skipped. Whatever is wrong with the file (it cannot be
read, is too large, is not text, has a field beyond the csv module's limit, a bad header, a row
of the wrong length, a value that is not a finite number) raises one ``ValueError`` naming the
file, the line and the column, never a traceback from the csv module.
"""

import csv
import math
from pathlib import Path

from stewart_kinematics.model.arrays import preview


def read_number_table(path: Path, headers, *, what: str, max_rows: int, max_bytes: int):
    """
    Read a CSV table of finite numbers whose header is one of ``headers``.

    :param path: the file.
    :param headers: the allowed headers, each a tuple of column names; the first is the one
        named in the error of a bad header.
    :param what: what a row is, plural, for the messages (``'poses'``).
    :param max_rows: the most data rows the file may hold.
    :param max_bytes: the largest file read.
    :returns: ``(header, rows)``: the file's header (one of ``headers``) and its rows, a list
        of lists of floats, each as long as the header.
    :raises ValueError: naming the file, and the line and the column where there is one.
    """
    try:
        size = path.stat().st_size
        if not path.is_file():
            raise ValueError(f'{path}: not a file')
        if size > max_bytes:
            raise ValueError(f'{path}: {size:,} bytes, more than a list of {max_rows:,} '
                             f'{what} may take ({max_bytes:,})')
        with open(path, encoding='utf-8', newline='') as stream:
            lines = [(number, line) for number, line in enumerate(stream, start=1)
                     if line.strip() and not line.lstrip().startswith('#')]
    except (OSError, UnicodeDecodeError) as error:
        raise ValueError(f'{path}: cannot be read: {error}') from None
    if not lines:
        raise ValueError(f'{path}: no header and no data')
    if len(lines) > max_rows + 1:
        raise ValueError(f'{path}: at most {max_rows:,} {what}, got {len(lines) - 1:,}')
    try:
        return _rows(path, lines, tuple(headers))
    except csv.Error as error:   # a field beyond the csv module's limit, say
        raise ValueError(f'{path}: not a CSV file of {what}: {error}') from None


def _rows(path, lines, headers):
    reader = csv.reader(line for _, line in lines)
    header = tuple(cell.strip() for cell in next(reader))
    if header not in headers:
        allowed = ' or '.join(','.join(names) for names in headers)
        raise ValueError(f'{path} line {lines[0][0]}: the header must be {allowed}, got '
                         f'{preview(",".join(header))}')
    rows = []
    for (number, _), cells in zip(lines[1:], reader):
        if len(cells) != len(header):
            raise ValueError(f'{path} line {number}: expected {len(header)} values, got '
                             f'{len(cells)}')
        row = []
        for column, cell in zip(header, cells):
            try:
                value = float(cell)
            except ValueError:
                value = math.nan
            if not math.isfinite(value):
                raise ValueError(f'{path} line {number}: {column} must be a finite number, '
                                 f'got {preview(cell.strip())}')
            row.append(value)
        rows.append(row)
    return header, rows
