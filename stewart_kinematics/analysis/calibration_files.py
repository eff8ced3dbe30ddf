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
Calibration's files: the measurement CSV and the calibrated parameter file.

:func:`load_measurements` reads what a tracker and the actuators measured (a header row naming
:data:`MEASUREMENT_COLUMNS`, one row per pose) and refuses a file it cannot use with the file
name and line number: a missing column, a row with too few or too many fields, a value that
is not a finite number. A byte-order mark (as spreadsheet programs write), Windows line ends
and spaces around the fields are accepted; :func:`load_columns`, its reader, reads other
columns the same way (``stewart_payload``'s forces). :func:`write_parameter_file` writes a ROS 2
parameter file the nodes load as it is. Nothing here needs scipy (the fit is in
:mod:`stewart_kinematics.analysis.calibration`).
"""

import csv
import io
import math
import sys
from typing import Sequence, Tuple

import numpy as np

from stewart_kinematics.model.arrays import preview
import yaml

#: The columns of a measurement CSV file, in this order (a header row names them).
MEASUREMENT_COLUMNS = ('X', 'Y', 'Z', 'alpha', 'beta', 'gamma') + tuple(
    f'actuator_{leg}' for leg in range(1, 7))


def load_measurements(path) -> Tuple[np.ndarray, np.ndarray]:
    """
    Read measured poses and actuator positions from a CSV file.

    The file has a header row naming at least the columns of :data:`MEASUREMENT_COLUMNS`
    (``X, Y, Z`` in metres, ``alpha, beta, gamma`` in radians, ``actuator_1`` .. ``actuator_6``
    in metres), in any order, other columns ignored; lines starting with ``#`` and blank lines
    are skipped. Every data row has as many fields as the header.

    :returns: ``(poses, actuator_positions)``, each shape (N, 6).
    :raises ValueError: naming the file and its line, for a missing or repeated column, a row
        with the wrong number of fields, or a value that is not a finite number.
    """
    data = load_columns(path, MEASUREMENT_COLUMNS)[1]
    return data[:, :6], data[:, 6:]


def load_columns(path, *layouts: Sequence[str]) -> Tuple[int, np.ndarray]:
    """
    Read the named columns of a measurement CSV file, as :func:`load_measurements` reads them.

    :param path: the CSV file: a header row naming the columns, then one row per measurement.
    :param layouts: one or more tuples of column names; the first whose columns the header
        names is read (a file of poses, or one of leg lengths, say).
    :returns: ``(layout, values)``: the index of the layout read, and its columns in its order,
        shape (N, len(layout)), every value a finite float.
    :raises ValueError: naming the file and its line (and the column), for missing or repeated
        columns, a row with the wrong number of fields, or a value that is not a finite number.
    """
    try:
        with open(path, newline='', encoding='utf-8-sig') as stream:
            text = stream.read()
    except OSError as error:
        raise ValueError(f'cannot read measurement file {path}: {error.strerror}') from error
    except UnicodeDecodeError as error:
        raise ValueError(f'measurement file {path} is not UTF-8 text: {error}') from error
    rows = []
    try:
        for number, fields in enumerate(csv.reader(io.StringIO(text)), start=1):
            fields = [field.strip() for field in fields]
            if not any(fields) or fields[0].startswith('#'):
                continue
            rows.append((number, fields))
    except csv.Error as error:   # a field beyond the csv module's limit, say
        raise ValueError(f'{path}: not a CSV file of measurements: {error}') from None
    wanted = ' or '.join(', '.join(layout) for layout in layouts)
    if not rows:
        raise ValueError(f'{path}: no header row; the header must name {wanted}')
    header_line, header = rows[0]
    chosen = next((index for index, layout in enumerate(layouts)
                   if all(name in header for name in layout)), None)
    if chosen is None:
        missing = [name for name in layouts[0] if name not in header]
        raise ValueError(f'{path}: line {header_line}: missing column(s) {", ".join(missing)}; '
                         f'the header must name {wanted}')
    names = layouts[chosen]
    repeated = sorted({name for name in names if header.count(name) > 1})
    if repeated:
        raise ValueError(f'{path}: line {header_line}: column(s) {", ".join(repeated)} named '
                         'more than once')
    columns = [header.index(name) for name in names]
    data = []
    for number, fields in rows[1:]:
        if len(fields) != len(header):
            raise ValueError(f'{path}: line {number}: {len(fields)} fields, but the header '
                             f'(line {header_line}) names {len(header)} columns')
        values = []
        for name, column in zip(names, columns):
            try:
                value = float(fields[column])
            except ValueError:
                raise ValueError(f'{path}: line {number}: {name} must be a number, got '
                                 f'{preview(fields[column])}') from None
            if not math.isfinite(value):
                raise ValueError(f'{path}: line {number}: {name} must be finite, got '
                                 f'{preview(fields[column])}')
            values.append(value)
        data.append(values)
    if not data:
        raise ValueError(f'{path}: no measurements after the header (line {header_line})')
    return chosen, np.array(data)


def write_measurements(path, poses, actuator_positions, comment: str = '') -> None:
    """Write poses and actuator positions as :func:`load_measurements` reads them."""
    lines = [f'# {line}'.rstrip() for line in comment.splitlines()]
    lines.append(','.join(MEASUREMENT_COLUMNS))
    for pose, reading in zip(np.atleast_2d(poses), np.atleast_2d(actuator_positions)):
        lines.append(','.join(repr(float(value)) for value in np.concatenate([pose, reading])))
    with open(path, 'w', encoding='utf-8') as stream:
        stream.write('\n'.join(lines) + '\n')


def write_parameter_file(path, values: dict, comment: str = '') -> None:
    """
    Write parameters as a ROS 2 parameter file with one ``/**`` section every node matches.

    :param path: the YAML file to write.
    :param values: parameter name -> value (lists of floats, floats, strings, ...).
    :param comment: text written first, each line as a YAML comment.
    """
    lines = [f'# {line}'.rstrip() for line in comment.splitlines()]
    lines += ['/**:', '  ros__parameters:']
    for name, value in values.items():
        if isinstance(value, (list, tuple)) and len(value) % 3 == 0 and len(value) > 3:
            lines.append(f'    {name}: [')
            for start in range(0, len(value), 3):
                lines.append('      ' + ', '.join(_yaml_scalar(item)
                                                  for item in value[start:start + 3]) + ',')
            lines.append('    ]')
        elif isinstance(value, (list, tuple)):
            lines.append(f'    {name}: [' + ', '.join(map(_yaml_scalar, value)) + ']')
        else:
            lines.append(f'    {name}: {_yaml_scalar(value)}')
    with open(path, 'w', encoding='utf-8') as stream:
        stream.write('\n'.join(lines) + '\n')


def _yaml_scalar(value) -> str:
    if isinstance(value, (float, np.floating)):
        value = float(value)
        if math.isinf(value):
            return '.inf' if value > 0 else '-.inf'
        if value != 0.0 and abs(value) < sys.float_info.min:
            # rcl's strtod refuses a subnormal (ERANGE): the node would read a string. Below
            # 2.2e-308 (metres, degrees), the value is 0.
            value = 0.0
        text = repr(value)
        # YAML 1.1 (PyYAML) reads 1e-05 as a string: a float needs its dot, 1.0e-05.
        mantissa, exponent = text.split('e') if 'e' in text else (text, None)
        if '.' not in mantissa:
            mantissa += '.0'
        return mantissa if exponent is None else f'{mantissa}e{exponent}'
    return yaml.safe_dump(value, default_flow_style=True).strip().removesuffix('...').strip()
