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
Unit tests of stewart_kinematics.parameters (no ROS).

Every spec's check() returns '' for an allowed value, else a sentence that names the parameter
and the value; read_parameter_file applies '/**' and then the node's own section.
"""

import array
import math

import pytest

from stewart_kinematics import parameters
from stewart_kinematics.parameters import (
    GEOMETRY_PARAMETERS,
    QUEUE_PARAMETERS,
    RAMP_PARAMETERS,
    read_parameter_file,
    SOLVER_PARAMETERS,
)

pytestmark = pytest.mark.core

ALL_SPECS = GEOMETRY_PARAMETERS + SOLVER_PARAMETERS + QUEUE_PARAMETERS + RAMP_PARAMETERS
SPECS = {spec.name: spec for spec in ALL_SPECS}
REQUIRED = ['base_joints', 'platform_joints', 'home_position']

GOOD_VALUES = [
    ('base_joints', [0.1] * 18),
    ('platform_joints', [-0.2] * 18),
    ('home_position', [0.0, 0.0, 0.4325]),
    ('home_orientation_deg', [-180.0, 0.0, 180.0]),
    ('leg_length_min', 0.0),
    ('leg_length_max', 1.2),
    ('leg_length_max', math.inf),
    ('tolerance', 1e-12),
    ('tolerance', 0.01),
    ('max_iterations', 1),
    ('max_iterations', 1000),
    ('queue_depth', 1),
    ('queue_depth', 10000),
    ('position_start', (0.0, 0.0, 0.4325)),
    ('position_step', [0.0, 0.0, 1.0]),
    ('orientation_end_deg', [15.0, -15.0, 20.0]),
    ('orientation_step_deg', [-400.0, 0.0, 400.0]),
    ('mode', 'table'),
    ('mode', 'interpolate'),
    ('row_period', 0.001),
    ('publish_rate', 1000.0),
    ('duration', 86400.0),
    ('loop', True),
    ('start_delay', 0.0),
    ('min_subscribers', 0),
]

WRONG_TYPES = [
    ('base_joints', 'abc'),
    ('home_position', 0.4325),
    ('leg_length_min', '0.0'),
    ('leg_length_min', True),
    ('tolerance', [1e-12]),
    ('max_iterations', 50.0),
    ('max_iterations', True),
    ('queue_depth', '10'),
    ('mode', 1),
    ('loop', 1),
    ('loop', 'true'),
]

NON_NUMERIC_ITEMS = [
    ('home_position', [0.0, 'a', 0.0]),
    ('position_start', [0.0, True, 0.4]),
    ('base_joints', [None] * 18),
]

WRONG_LENGTHS = [
    ('base_joints', [0.0] * 17),
    ('platform_joints', [0.0] * 19),
    ('home_position', [0.0, 0.4]),
    ('home_orientation_deg', [0.0, 0.0, 0.0, 0.0]),
    ('orientation_step_deg', []),
    ('position_end', [0.1]),
]

OUT_OF_RANGE = [
    ('home_orientation_deg', [0.0, 181.0, 0.0]),
    ('orientation_start_deg', [-180.5, 0.0, 0.0]),
    ('orientation_end_deg', [0.0, 0.0, 360.0]),
    ('leg_length_min', -0.001),
    ('leg_length_max', 0.0),
    ('leg_length_max', -1.0),
    ('tolerance', 0.0),
    ('tolerance', -1e-12),
    ('tolerance', 0.02),
    ('max_iterations', 0),
    ('max_iterations', 1001),
    ('queue_depth', 0),
    ('mode', 'loop'),
    ('row_period', 0.0),
    ('publish_rate', 1000.5),
    ('duration', 0.0),
    ('start_delay', -0.1),
    ('min_subscribers', -1),
]

NON_FINITE = [
    ('base_joints', [0.0] * 17 + [math.nan]),
    ('home_position', [math.inf, 0.0, 0.0]),
    ('position_step', [0.0, math.nan, 0.0]),
    ('leg_length_min', math.inf),
    ('leg_length_min', math.nan),
    ('leg_length_max', math.nan),
    ('tolerance', math.nan),
    ('row_period', math.inf),
    ('duration', math.nan),
]


def assert_names_parameter_and_value(reason, name, value):
    """Check that a reason is a non-empty sentence quoting the parameter and the value."""
    assert reason
    assert f"'{name}'" in reason
    assert repr(value) in reason


def write_file(directory, text):
    """Write ``text`` to params.yaml in ``directory`` and return its path."""
    path = directory / 'params.yaml'
    path.write_text(text, encoding='utf-8')
    return path


# Specs.

def test_spec_names_are_unique():
    """No two specs declare the same parameter."""
    assert len(SPECS) == len(ALL_SPECS)


@pytest.mark.parametrize('spec', ALL_SPECS, ids=lambda spec: spec.name)
def test_spec_is_fully_described(spec):
    """Each spec has a known type and a description."""
    assert spec.value_type in ('bool', 'integer', 'double', 'string', 'double_array')
    assert spec.description


@pytest.mark.parametrize('spec', [spec for spec in ALL_SPECS if spec.default is not None],
                         ids=lambda spec: spec.name)
def test_default_passes_its_own_check(spec):
    """Every default value is allowed by its own spec."""
    assert spec.check(spec.default) == ''


@pytest.mark.parametrize('name', REQUIRED)
def test_required_parameter_without_value_is_reported(name):
    """A required parameter with no value gives a sentence naming it as required."""
    reason = SPECS[name].check(None)
    assert f"'{name}'" in reason and 'required' in reason


def test_only_the_joints_and_home_position_are_required():
    """Exactly base_joints, platform_joints and home_position have no default."""
    assert sorted(spec.name for spec in ALL_SPECS if spec.default is None) == sorted(REQUIRED)


@pytest.mark.parametrize('name', ['leg_length_max', 'tolerance', 'mode'])
def test_optional_parameter_without_value_is_allowed(name):
    """An optional parameter with no value falls back to its default."""
    assert SPECS[name].check(None) == ''


@pytest.mark.parametrize('name, value', GOOD_VALUES)
def test_allowed_value_gives_empty_reason(name, value):
    """Allowed values, including the range boundaries, give ''."""
    assert SPECS[name].check(value) == ''


@pytest.mark.parametrize('name, value', WRONG_TYPES)
def test_wrong_type_names_parameter_type_and_value(name, value):
    """A value of the wrong type gives a sentence naming the parameter, type and value."""
    reason = SPECS[name].check(value)
    assert_names_parameter_and_value(reason, name, value)
    assert SPECS[name].value_type in reason


@pytest.mark.parametrize('name, value', NON_NUMERIC_ITEMS)
def test_non_numeric_array_item_names_parameter_and_value(name, value):
    """An array holding a string, bool or None gives a sentence naming the parameter."""
    assert_names_parameter_and_value(SPECS[name].check(value), name, value)


@pytest.mark.parametrize('name, value', WRONG_LENGTHS)
def test_wrong_length_names_parameter_length_and_value(name, value):
    """An array of the wrong length gives a sentence naming the parameter and both lengths."""
    reason = SPECS[name].check(value)
    assert_names_parameter_and_value(reason, name, value)
    assert f'got {len(value)}' in reason


@pytest.mark.parametrize('name, value', OUT_OF_RANGE)
def test_out_of_range_names_parameter_and_value(name, value):
    """A value outside the allowed range gives a sentence naming the parameter and value."""
    assert_names_parameter_and_value(SPECS[name].check(value), name, value)


@pytest.mark.parametrize('name, value', NON_FINITE)
def test_non_finite_names_parameter_and_value(name, value):
    """A non-finite value where a finite one is needed gives a sentence naming both."""
    assert_names_parameter_and_value(SPECS[name].check(value), name, value)


@pytest.mark.parametrize('name', ['base_joints', 'home_position', 'home_orientation_deg',
                                  'orientation_start_deg', 'position_step'])
def test_double_array_from_rclpy_is_checked(name):
    """An array.array('d'), as rclpy hands over double arrays, is checked like a list."""
    good = [0.0] * (18 if name == 'base_joints' else 3)
    assert SPECS[name].check(array.array('d', good)) == ''
    bad = array.array('d', [math.nan] + good[1:])
    assert f"'{name}'" in SPECS[name].check(bad)


def test_double_refuses_integer_value_as_rcl_does():
    """An integer for a double parameter is refused with a hint, as rcl refuses YAML's 1."""
    assert SPECS['duration'].check(10.0) == ''
    assert 'write 1.0, not 1' in SPECS['duration'].check(10)
    assert 'write 1.0, not 1' in SPECS['position_step'].check([0, 0, 1])


def test_unknown_names_are_refused_with_a_suggestion():
    """A misspelt parameter name is refused, naming the closest known one."""
    parameters.check_known_names(['tolerance', 'base_joints'], 'test')
    with pytest.raises(ValueError, match="'tolerence' \\(did you mean 'tolerance'\\?\\)"):
        parameters.check_known_names(['tolerence', 'base_joints'], 'test')


def test_defaults_maps_names_to_defaults():
    """defaults() gives each name its default, None for the required ones."""
    result = parameters.defaults(GEOMETRY_PARAMETERS)
    assert result['base_joints'] is None
    assert result['home_orientation_deg'] == [0.0, 0.0, 0.0]
    assert result['leg_length_max'] == math.inf
    assert list(result) == [spec.name for spec in GEOMETRY_PARAMETERS]


def test_check_values_accepts_allowed_values():
    """check_values() returns quietly when every value is allowed."""
    parameters.check_values(SOLVER_PARAMETERS, {'tolerance': 1e-9, 'max_iterations': 20})


def test_check_values_raises_with_the_reason():
    """check_values() raises ValueError with the first bad value's reason."""
    with pytest.raises(ValueError, match=r"'max_iterations'.*0"):
        parameters.check_values(SOLVER_PARAMETERS, {'tolerance': 1e-9, 'max_iterations': 0})


def test_check_values_reports_missing_required_value():
    """check_values() raises ValueError naming a missing required parameter."""
    with pytest.raises(ValueError, match=r"'base_joints' is required"):
        parameters.check_values(GEOMETRY_PARAMETERS, {})


def test_markdown_table_lists_every_parameter():
    """The README table has a header, a separator and one row per spec."""
    lines = parameters.markdown_table(RAMP_PARAMETERS).splitlines()
    assert len(lines) == 2 + len(RAMP_PARAMETERS)
    for spec, line in zip(RAMP_PARAMETERS, lines[2:]):
        assert line.startswith(f'| `{spec.name}` | {spec.value_type} |')


def test_markdown_table_shows_a_default_of_minus_infinity_as_minus_inf():
    """leg_force_min's default (no pull limit) is -.inf, as a parameter file writes it."""
    specs = [spec for spec in GEOMETRY_PARAMETERS
             if spec.name in ('leg_force_min', 'leg_force_max')]
    lines = parameters.markdown_table(specs).splitlines()
    assert lines[2].startswith('| `leg_force_min` | double | `-.inf` |')
    assert lines[3].startswith('| `leg_force_max` | double | `.inf` |')


# Parameter files.

def test_read_wildcard_section(tmp_path):
    """Without a node name, the '/**' section is read, with YAML types kept."""
    path = write_file(tmp_path, (
        '/**:\n  ros__parameters:\n    a: 1\n    b: .inf\n    c: [0.1, 0.2]\n'
        'my_node:\n  ros__parameters:\n    a: 2\n'))
    assert read_parameter_file(path) == {'a': 1, 'b': math.inf, 'c': [0.1, 0.2]}


def test_node_section_overrides_wildcard_whatever_the_file_order(tmp_path):
    """The node's section overrides '/**' even when written before it."""
    path = write_file(tmp_path, (
        'my_node:\n  ros__parameters:\n    a: 2\n    d: true\n'
        '/**:\n  ros__parameters:\n    a: 1\n    b: 3.0\n'))
    assert read_parameter_file(path, 'my_node') == {'a': 2, 'b': 3.0, 'd': True}


def test_other_node_sections_are_ignored(tmp_path):
    """Another node's section does not apply."""
    path = write_file(tmp_path, (
        '/**:\n  ros__parameters:\n    a: 1\n'
        'other_node:\n  ros__parameters:\n    a: 5\n    e: 6\n'))
    assert read_parameter_file(path, 'my_node') == {'a': 1}


@pytest.mark.parametrize('key', ['my_node', '/my_node', '/ns/my_node'])
def test_node_section_key_forms(tmp_path, key):
    """A section keyed 'name', '/name' or '/namespace/name' applies to that node."""
    path = write_file(tmp_path, (
        '/**:\n  ros__parameters:\n    a: 1\n'
        f'{key}:\n  ros__parameters:\n    a: 7\n'))
    assert read_parameter_file(path, 'my_node') == {'a': 7}


def test_file_without_wildcard_section(tmp_path):
    """A file with only the node's section gives that section's values."""
    path = write_file(tmp_path, 'my_node:\n  ros__parameters:\n    a: 1\n')
    assert read_parameter_file(path, 'my_node') == {'a': 1}
    assert read_parameter_file(path) == {}


def test_missing_file_raises_naming_it(tmp_path):
    """A missing file raises ValueError naming the path."""
    with pytest.raises(ValueError, match=r'absent\.yaml: cannot read parameter file'):
        read_parameter_file(tmp_path / 'absent.yaml')


def test_invalid_yaml_raises(tmp_path):
    """A file that is not YAML raises ValueError naming the file."""
    path = write_file(tmp_path, '/**:\n  ros__parameters: {a: [1, 2\n')
    with pytest.raises(ValueError, match=r'params\.yaml:3: not valid YAML'):
        read_parameter_file(path)


@pytest.mark.parametrize('text', ['', '- a\n- b\n', 'just text\n'])
def test_document_that_is_not_a_map_raises(tmp_path, text):
    """An empty file, a list or a scalar raises ValueError explaining the layout."""
    with pytest.raises(ValueError, match='must map node names to ros__parameters'):
        read_parameter_file(write_file(tmp_path, text))


def test_wildcard_without_ros_parameters_raises(tmp_path):
    """A '/**' section without ros__parameters raises ValueError naming the section."""
    path = write_file(tmp_path, '/**:\n  a: 1\n')
    with pytest.raises(ValueError, match=r"section '/\*\*' .*no ros__parameters"):
        read_parameter_file(path)


def test_node_section_with_bad_ros_parameters_raises(tmp_path):
    """A node section whose ros__parameters is not a map raises ValueError naming it."""
    path = write_file(tmp_path, (
        '/**:\n  ros__parameters:\n    a: 1\n'
        'my_node:\n  ros__parameters: [1, 2]\n'))
    with pytest.raises(ValueError, match=r"section 'my_node' .*no ros__parameters"):
        read_parameter_file(path, 'my_node')
