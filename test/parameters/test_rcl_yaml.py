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
The package's one YAML reader (stewart_kinematics.parameters.rcl_yaml) and its limits.

The defects (issue 27): a 504-byte alias bomb given as ``--params-file`` hung the tools for
minutes (the reader expanded every alias); a list 100,000 deep or a mapping 3,000 deep ended
every tool with a RecursionError (PyYAML's composer and the reader's walk both recursed); a
``null`` value was reported as "a value in quotes is a string"; and a 5,000-digit number made
Python's int() raise outside the reader's errors. The reader now builds the values from the
event stream with its own stack and refuses aliases, nesting past MAX_DEPTH, more than
MAX_VALUES values and files larger than MAX_FILE_BYTES, each with one line ``file:line: what``.
"""

import inspect
import math
import random
import sys
import time

from fuzzing.fuzz_parameter_files import alias_bomb, deep_list, deep_mapping, reader_problems
from hypothesis import given, strategies as st
from properties import budget
import pytest

from stewart_kinematics.parameters import (
    NullString,
    OutOfRangeNumber,
    ParameterFileError,
    read_parameter_file,
    read_parameter_files,
)
from stewart_kinematics.parameters import rcl_yaml
from stewart_kinematics.parameters.rcl_yaml import (
    MAX_DEPTH,
    parse_yaml_value,
    rcl_scalar,
    read_yaml_file,
)

pytestmark = pytest.mark.core

HEADER = '/**:\n  ros__parameters:\n'


def write(tmp_path, text, name='params.yaml'):
    """Write a parameter file (text, or bytes as they are); return its path."""
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text, encoding='utf-8')
    return path


def refusal(path, reader=read_parameter_files):
    """Read ``path`` (a file or a list) and return the ParameterFileError's message."""
    with pytest.raises(ParameterFileError) as raised:
        reader(path)
    message = str(raised.value)
    assert '\n' not in message
    return message


def nesting_depth(value) -> int:
    """How many collections are nested in ``value`` (walked with a stack, not recursion)."""
    deepest, stack = 0, [(value, 1)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, (list, dict)):
            deepest = max(deepest, depth)
            children = item.values() if isinstance(item, dict) else item
            stack += [(child, depth + 1) for child in children]
    return deepest


# Aliases --------------------------------------------------------------------------------------

@pytest.mark.parametrize('text, line', [
    (HEADER + '    leg_length_max: &limit 0.9\n    leg_length_min: *limit\n', 4),
    (HEADER + '    base: &base {a: 1.0}\n    limits:\n      <<: *base\n', 5),
    (HEADER + '    home_position: [0.0, 0.0, *undefined]\n', 3),
])
def test_an_alias_is_refused_naming_the_file_and_its_line(tmp_path, text, line):
    # rcl refuses every alias ("Will not support aliasing at line N"): so does the reader.
    path = write(tmp_path, text)
    message = refusal(path, read_yaml_file)
    assert message.startswith(f'{path}:{line}: YAML alias *')
    assert 'aliases' in message


def test_an_anchor_without_an_alias_is_read_as_rcl_reads_it(tmp_path):
    path = write(tmp_path, HEADER + '    leg_length_max: &limit 0.9\n')
    assert read_parameter_file(path) == {'leg_length_max': 0.9}


@pytest.mark.parametrize('style', ['list', 'mapping'])
def test_an_alias_bomb_is_refused_at_once(tmp_path, style):
    # 9 levels of 9 aliases: 387,420,489 values from about 500 bytes.
    bomb = alias_bomb(random.Random(0), levels=9, width=9, style=style)
    assert len(bomb.data) < 1000 and b'*a7' in bomb.data
    path = bomb.write(tmp_path)
    started = time.monotonic()
    message = refusal([path])
    assert time.monotonic() - started < 1.0
    assert message.startswith(f'{path}:4: YAML alias *a0')
    assert not reader_problems(bomb, tmp_path, deadline=2.0)


# Nesting -------------------------------------------------------------------------------------

@pytest.mark.parametrize('kind', ['list', 'mapping'])
def test_nesting_up_to_the_limit_is_read_and_one_level_more_is_refused(kind):
    def text(depth):
        if kind == 'list':
            return '[' * depth + '1.0' + ']' * depth
        return '{k: ' * (depth - 1) + '{k: 1.0' + '}' * depth
    value = parse_yaml_value(text(MAX_DEPTH))
    assert nesting_depth(value) == MAX_DEPTH
    with pytest.raises(ParameterFileError, match=f'nested more than {MAX_DEPTH} levels deep'):
        parse_yaml_value(text(MAX_DEPTH + 1))


def test_the_reader_does_not_recurse_per_level():
    # With room for 30 more frames than the test itself uses, a value nested 64 deep (past
    # that room) is still read: the reader keeps its own stack.
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(len(inspect.stack()) + 30)
    try:
        value = parse_yaml_value('[' * MAX_DEPTH + ']' * MAX_DEPTH)
    finally:
        sys.setrecursionlimit(limit)
    assert nesting_depth(value) == MAX_DEPTH


@pytest.mark.parametrize('generator, depth, style, line', [
    # Line 4 holds the whole list, line 3 the whole flow mapping; in block style, the mapping
    # nested 65 deep (the file's, '/**', ros__parameters, then k0 to k61) starts at k62's line.
    (deep_list, 100_000, 'flow', 4), (deep_list, 100_000, 'block', 4),
    (deep_mapping, 3000, 'flow', 3), (deep_mapping, 3000, 'block', 3 + MAX_DEPTH - 2)])
def test_a_file_nested_thousands_deep_is_refused_at_once(tmp_path, generator, depth, style,
                                                         line):
    hostile = generator(random.Random(0), depth=depth, style=style)
    path = hostile.write(tmp_path)
    started = time.monotonic()
    message = refusal([path])
    assert time.monotonic() - started < 1.0
    assert message.startswith(f'{path}:{line}: nested more than {MAX_DEPTH} levels deep')


def test_a_deep_p_value_is_refused_as_a_value_error():
    # The nodes parse -p values with the same reader (ros_parameters._parameter_assignment).
    with pytest.raises(ValueError, match='nested more than'):
        parse_yaml_value('[' * 100_000 + ']' * 100_000)


# Size ----------------------------------------------------------------------------------------

def test_more_values_than_the_budget_are_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(rcl_yaml, 'MAX_VALUES', 22)
    # Keys count: the file's mapping, '/**', its mapping, 'ros__parameters', its mapping, 'a'
    # and the list are 7 values, then 15 items.
    path = write(tmp_path, HEADER + '    a: [' + ', '.join(['1.0'] * 15) + ']\n')
    assert len(read_yaml_file(path).value['/**']['ros__parameters']['a']) == 15
    path = write(tmp_path, HEADER + '    a: [' + ', '.join(['1.0'] * 16) + ']\n')
    assert refusal(path, read_yaml_file) == f'{path}:3: more than 22 values: not a parameter file'


def test_a_file_larger_than_the_limit_is_refused_unread(tmp_path, monkeypatch):
    monkeypatch.setattr(rcl_yaml, 'MAX_FILE_BYTES', 1000)
    path = write(tmp_path, HEADER + f"    base_frame: '{'x' * 2000}'\n")
    assert refusal(path, read_yaml_file) == (
        f'{path}: larger than 1000 bytes: not a parameter file')


def test_a_huge_value_is_read_and_its_refusal_is_short(tmp_path):
    huge = 'x' * 10 ** 6
    path = write(tmp_path, HEADER + f"    base_frame: '{huge}'\n")
    assert read_parameter_file(path)['base_frame'] == huge
    # A key longer than 1024 characters must be explicit (?) in YAML.
    path = write(tmp_path, HEADER + f'    ? {huge}y\n    : 1.0\n')
    message = refusal([path])
    assert len(message) < 2000 and '(1000001 characters)' in message
    path = write(tmp_path, HEADER + f'    leg_length_max: {huge}\n')
    message = refusal([path])
    assert len(message) < 1000 and '(1,000,000 characters)' in message


# Empty values, keys, documents, encodings -------------------------------------------------------

@pytest.mark.parametrize('text, expected', [
    (HEADER + '    leg_length_max:\n', ":3: the value of 'leg_length_max' is empty"),
    (HEADER + '    home_position:\n      - 0.0\n      -\n      - 0.4\n',
     ':5: the value of a list item is empty'),
    (HEADER + '    "": 1.0\n', ':3: a key is empty'),
    (HEADER + '    ? [a, b]\n    : 1.0\n', ':3: a key must be a name, not a list'),
    (HEADER + '    a: 1.0\n---\n/**:\n  ros__parameters:\n    b: 2.0\n',
     ':4: a second YAML document'),
    (HEADER + '    a: [1.0, 2.0\n    b: 3.0\n', ':4: not valid YAML'),
    ('/**:\n\tros__parameters:\n', ':2: not valid YAML'),
    (HEADER + '    a: 1.0\n    b: "\x00"\n', ':4: not valid YAML: control characters'),
])
def test_a_file_rcl_refuses_is_refused_in_one_line_with_its_line(tmp_path, text, expected):
    path = write(tmp_path, text)
    message = refusal(path, read_parameter_file)
    assert message.startswith(f'{path}{expected}'), message


def test_a_file_that_is_not_utf8_is_refused_with_the_line_of_the_byte(tmp_path):
    path = write(tmp_path, (HEADER + "    base_frame: 'b\xe4se'\n").encode('latin-1'))
    assert refusal(path, read_yaml_file).startswith(
        f'{path}:3: not UTF-8 text: byte 0xe4')


def test_a_missing_file_is_refused_naming_it(tmp_path):
    path = tmp_path / 'absent.yaml'
    assert refusal(path, read_yaml_file) == (
        f'{path}: cannot read parameter file: No such file or directory')


# Nulls and the type messages -------------------------------------------------------------------

@pytest.mark.parametrize('word', ['null', 'Null', 'NULL', '~'])
def test_a_null_is_the_string_rcl_makes_of_it_and_is_reported_as_null(tmp_path, word):
    path = write(tmp_path, HEADER + f'    leg_length_max: {word}\n')
    value = read_parameter_file(path)['leg_length_max']
    assert value == word and isinstance(value, NullString)
    message = refusal([path])
    assert message.startswith(
        f"{path}:3: parameter 'leg_length_max' must be of type double, got {word} (an empty "
        f"value in YAML, which ROS reads as the string '{word}')")
    assert 'in quotes' not in message


def test_a_null_in_a_list_is_reported_as_null(tmp_path):
    path = write(tmp_path, HEADER + '    home_position: [0.0, ~, 0.4]\n')
    message = refusal([path])
    assert "'home_position' must be of type double_array, got ~ in the list" in message
    assert 'in quotes' not in message


def test_a_null_for_a_string_parameter_is_the_string_null_as_for_rcl(tmp_path):
    path = write(tmp_path, HEADER + '    base_frame: null\n    platform_frame: "null"\n')
    values = read_parameter_files([path])
    assert values == {'base_frame': 'null', 'platform_frame': 'null'}
    assert isinstance(values['base_frame'], NullString)
    assert not isinstance(values['platform_frame'], NullString)


@pytest.mark.parametrize('written, hint', [
    ('"0.9"', True), ("'1e-3'", True), ('"true"', True), ('abc', False), ('"abc"', False)])
def test_the_quotes_hint_is_given_only_for_a_quoted_number(tmp_path, written, hint):
    path = write(tmp_path, HEADER + f'    leg_length_max: {written}\n')
    assert ('a value in quotes is a string' in refusal([path])) is hint


def test_an_unknown_name_is_refused_with_its_line_and_a_bounded_list(tmp_path):
    names = ''.join(f'    unknown_{index}: 1.0\n' for index in range(50))
    path = write(tmp_path, HEADER + '    leg_length_max: 0.9\n' + names)
    message = refusal([path])
    assert message.startswith(f"{path}:4: unknown parameter(s) 'unknown_0'")
    assert 'and 45 more' in message and 'unknown_49' not in message


# rcl's typing ----------------------------------------------------------------------------------

@pytest.mark.parametrize('text, expected', [
    # What rcl_yaml_param_parser (ROS 2 Jazzy) gives for each, read back from an rclpy node.
    ('1', 1), ('-9223372036854775808', -2 ** 63), ('0777', 511), ('0x1F', 31),
    ('99999999999999999999', 1e20),                 # beyond 64 bits: strtod
    ('0x7fffffffffffffff1', 1.4757395258967641e+20),
    ('1e-3', 0.001), ('.inf', math.inf), ('-.Inf', -math.inf), ('08', 8.0),
    # strtod's ERANGE: rcl keeps the text, marked as a number out of range.
    ('1e999', OutOfRangeNumber('1e999')), ('1e-400', OutOfRangeNumber('1e-400')),
    ('5e-324', OutOfRangeNumber('5e-324')), ('0x1p-1080', OutOfRangeNumber('0x1p-1080')),
    ('0.0e-999', 0.0), ('2.2250738585072014e-308', 2.2250738585072014e-308),
    ('1_000', '1_000'), ('yes', True), ('Off', False), ('abc', 'abc'),
])
def test_a_scalar_is_typed_as_rcl_types_it(text, expected):
    value = rcl_scalar(text)
    assert type(value) is type(expected) and value == expected


def test_a_number_of_thousands_of_digits_is_a_string_not_an_error():
    # Python's int() refuses more than 4300 digits; strtol and strtod overflow (ERANGE).
    assert rcl_scalar('1' * 5000) == OutOfRangeNumber('1' * 5000)
    assert rcl_scalar('9.' + '9' * 10 ** 6) == 10.0


def test_a_number_out_of_range_is_reported_as_one(tmp_path):
    path = write(tmp_path, HEADER + '    leg_length_max: 1e999\n    base_joints: [0.1, 5e-324]\n')
    message = refusal([path])
    assert message.startswith(f"{path}:3: parameter 'leg_length_max' must be of type double, "
                              'got 1e999 (beyond the range of a double')
    assert 'in quotes' not in message


def test_keys_are_the_text_written_as_for_rcl(tmp_path):
    path = write(tmp_path, 'node:\n  ros__parameters:\n    on: 1\n    1e-3: 2\n    null: 3\n')
    assert read_parameter_file(path, 'node') == {'on': 1, '1e-3': 2, 'null': 3}


def test_a_tag_other_than_str_is_ignored_as_by_rcl(tmp_path):
    path = write(tmp_path, HEADER + '    a: !!str 1.0\n    b: !!float 3\n    c: !custom 2.5\n')
    assert read_parameter_file(path) == {'a': '1.0', 'b': 3, 'c': 2.5}


# Any text --------------------------------------------------------------------------------------

YAML_ALPHABET = st.sampled_from(list('ab01.-:[]{},&*!|>\'"#~ \t\n\x00') + ['\u00e9', '\ufeff'])


@budget(200)
@given(st.text(YAML_ALPHABET, max_size=80))
def test_any_text_is_read_or_refused_in_one_line_naming_the_file(tmp_path_factory, text):
    path = tmp_path_factory.mktemp('any') / 'any.yaml'
    path.write_text(HEADER + '    ' + text + '\n', encoding='utf-8')
    try:
        read_parameter_file(path)
    except ParameterFileError as error:
        message = str(error)
        assert message.startswith(f'{path}:') and '\n' not in message
