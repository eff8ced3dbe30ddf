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
The measurement CSV as spreadsheets and hands write it: accepted, or refused with its line.

A byte-order mark, Windows line ends, spaces around fields and comments are accepted; a row
with too few or too many fields, a missing or repeated column, a value that is not a finite
number are refused with the file's own line number (comments and blank lines counted).
"""

import numpy as np
from numpy.testing import assert_array_equal
import pytest

from stewart_kinematics.analysis import calibration
from stewart_kinematics.analysis.calibration_files import (
    load_measurements,
    MEASUREMENT_COLUMNS,
    write_measurements,
)

pytestmark = pytest.mark.core

HEADER = ','.join(MEASUREMENT_COLUMNS)
ROW = ','.join(['0.01', '0.02', '0.45', '0.001', '0.002', '0.003'] + ['0.1'] * 6)


def write(tmp_path, text, encoding='utf-8'):
    """Write a CSV file; return its path."""
    path = tmp_path / 'measurements.csv'
    path.write_bytes(text.encode(encoding))
    return path


def test_byte_order_mark_crlf_spaces_and_comments_are_accepted(tmp_path):
    spaced = ' , '.join(MEASUREMENT_COLUMNS)
    text = ('# measured 2026-11-25\r\n\r\n' + spaced + ' \r\n'
            + ' , '.join(ROW.split(',')) + '\r\n# a comment\r\n' + ROW + '\r\n')
    poses, readings = load_measurements(write(tmp_path, text, 'utf-8-sig'))
    assert poses.shape == readings.shape == (2, 6)
    assert_array_equal(poses[0], [0.01, 0.02, 0.45, 0.001, 0.002, 0.003])
    assert_array_equal(readings, np.full((2, 6), 0.1))


def test_columns_in_any_order_with_others_ignored(tmp_path):
    columns = ['note'] + list(reversed(MEASUREMENT_COLUMNS))
    values = ['first'] + list(reversed(ROW.split(',')))
    poses, readings = load_measurements(write(tmp_path, ','.join(columns) + '\n'
                                              + ','.join(values) + '\n'))
    assert_array_equal(poses[0], [0.01, 0.02, 0.45, 0.001, 0.002, 0.003])


@pytest.mark.parametrize('text, words', [
    ('# c\n' + HEADER + '\n' + ROW + '\n' + ROW + ',0.5\n', 'line 4: 13 fields, but the header '
     '(line 2) names 12 columns'),
    (HEADER + '\n' + ROW.rsplit(',', 1)[0] + '\n', 'line 2: 11 fields'),
    (HEADER + '\n\n# gap\n' + ROW.replace('0.45', 'nan') + '\n', 'line 4: Z must be finite'),
    (HEADER + '\n' + ROW.replace('0.45', '') + '\n', "line 2: Z must be a number, got ''"),
    (HEADER + '\n' + ROW.replace('0.45', '0,45') + '\n', 'line 2: 13 fields'),
    (HEADER.replace('gamma', 'Gamma') + '\n' + ROW + '\n', 'line 1: missing column(s) gamma'),
    (HEADER + ',X\n' + ROW + ',0\n', 'line 1: column(s) X named more than once'),
    ('# only a comment\n', 'no header row'),
    # A quoted field beyond the csv module's limit (131072 characters): a refusal, no traceback.
    (HEADER + '\n"' + '1' * 200000 + '",' + ROW.split(',', 1)[1] + '\n',
     'not a CSV file of measurements: field larger than field limit'),
    (HEADER + '\n', 'no measurements after the header (line 1)'),
])
def test_a_bad_file_is_refused_with_its_line(tmp_path, text, words):
    with pytest.raises(ValueError) as raised:
        load_measurements(write(tmp_path, text))
    assert 'measurements.csv' in str(raised.value) and words in str(raised.value)


def test_a_file_that_is_not_text_or_not_there_is_refused(tmp_path):
    with pytest.raises(ValueError, match='not UTF-8 text'):
        load_measurements(write(tmp_path, HEADER + '\n', 'utf-16'))
    with pytest.raises(ValueError, match='cannot read measurement file'):
        load_measurements(tmp_path / 'absent.csv')


def test_written_files_read_back_exactly(tmp_path):
    generator = np.random.default_rng(3)
    poses, readings = generator.normal(size=(4, 6)), generator.normal(size=(4, 6))
    path = tmp_path / 'written.csv'
    write_measurements(path, poses, readings, 'two lines\nof comment')
    read = load_measurements(path)
    assert_array_equal(read[0], poses)
    assert_array_equal(read[1], readings)


def test_the_file_functions_are_still_importable_from_calibration():
    for name in ('load_measurements', 'write_measurements', 'write_parameter_file',
                 'MEASUREMENT_COLUMNS'):
        assert getattr(calibration, name) is not None
