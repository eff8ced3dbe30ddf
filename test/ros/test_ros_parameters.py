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
Tests of stewart_kinematics.ros.ros_parameters.declare_parameters on a plain rclpy Node.

Values come from parameter files written to ``tmp_path`` (``--params-file``) or from
``parameter_overrides``, as rclpy's own tests do; nothing is mocked.
"""

import math

import pytest
from rcl_interfaces.msg import ParameterType
from rclpy.exceptions import (
    InvalidParameterTypeException,
    InvalidParameterValueException,
    ParameterException,
)
from rclpy.node import Node
from rclpy.parameter import Parameter

from stewart_kinematics import parameters
from stewart_kinematics.ros.ros_parameters import declare_parameters
import yaml

pytestmark = pytest.mark.node

NODE_NAME = 'parameter_test_node'
SPECS = (parameters.GEOMETRY_PARAMETERS + parameters.SOLVER_PARAMETERS
         + parameters.QUEUE_PARAMETERS)
RAMP_SPECS = parameters.RAMP_PARAMETERS

BASE_JOINTS = [
    0.0486989, 0.2196666, 0.0, 0.1658874, 0.1520078, 0.0, 0.1658874, -0.1520078, 0.0,
    0.0486989, -0.2196666, 0.0, -0.2145863, -0.0676588, 0.0, -0.2145863, 0.0676588, 0.0]
PLATFORM_JOINTS = [
    -0.0513030, 0.1409539, 0.275, 0.1477212, 0.0260472, 0.275, 0.1477212, -0.0260472, 0.257,
    -0.0513030, -0.1409539, 0.275, -0.0964181, -0.1149067, 0.275, -0.0964181, 0.1149067, 0.275]
GOOD_VALUES = {
    'base_joints': BASE_JOINTS,
    'platform_joints': PLATFORM_JOINTS,
    'home_position': [0.0, 0.0, 0.4325],
    'home_orientation_deg': [1.0, -2.0, 3.0],
    'leg_length_min': 0.5,
    'leg_length_max': math.inf,
    'tolerance': 1e-9,
    'max_iterations': 20,
    'queue_depth': 7,
}

#: The unit word each parameter's description must contain, typed from the README's intent.
UNITS = {
    'base_joints': 'metres',
    'platform_joints': 'metres',
    'home_position': 'metres',
    'home_orientation_deg': 'degrees',
    'leg_length_min': 'metres',
    'leg_length_max': 'metres',
    'tolerance': 'metres',
    'max_iterations': 'iterations',
    'queue_depth': 'messages',
    'position_start': 'metres',
    'position_step': 'metres',
    'position_end': 'metres',
    'orientation_start_deg': 'degrees',
    'orientation_step_deg': 'degrees',
    'orientation_end_deg': 'degrees',
    'row_period': 'seconds',
    'publish_rate': 'hertz',
    'duration': 'seconds',
    'start_delay': 'seconds',
    'min_subscribers': 'subscri',
}


@pytest.fixture
def make_node(ros):
    """Return a factory of Nodes taking Node keyword arguments; destroys them afterwards."""
    nodes = []

    def make(**kwargs):
        node = Node(NODE_NAME, **kwargs)
        nodes.append(node)
        return node
    yield make
    for node in nodes:
        node.destroy_node()


@pytest.fixture
def write_params(tmp_path):
    """Return a writer of parameter files: values, section and extra sections in, path out."""
    counter = iter(range(1000))

    def write(values, section='/**', extra=None):
        document = {section: {'ros__parameters': dict(values)}}
        document.update(extra or {})
        path = tmp_path / f'params_{next(counter)}.yaml'
        path.write_text(yaml.safe_dump(document), encoding='utf-8')
        return str(path)
    return write


def file_args(*paths):
    """Build the ``cli_args`` of a node that reads the given parameter files."""
    arguments = ['--ros-args']
    for path in paths:
        arguments += ['--params-file', path]
    return arguments


def with_value(name, value):
    """Return GOOD_VALUES with one value replaced."""
    values = dict(GOOD_VALUES)
    values[name] = value
    return values


def test_good_file_gives_its_values(make_node, write_params):
    """A valid file (a /** section and the node's own section) sets every value declared."""
    geometry = {k: v for k, v in GOOD_VALUES.items() if k not in ('tolerance', 'max_iterations')}
    path = write_params(geometry, extra={NODE_NAME: {'ros__parameters': {
        'tolerance': 1e-9, 'max_iterations': 20}}})
    node = make_node(cli_args=file_args(path))
    values = declare_parameters(node, SPECS)
    assert {name: values[name] for name in GOOD_VALUES} == GOOD_VALUES
    for name, value in GOOD_VALUES.items():
        assert node.get_parameter(name).value == value


def test_defaults_fill_what_the_file_leaves_out(make_node, write_params):
    """Optional parameters absent from the file take their spec defaults."""
    required = {name: GOOD_VALUES[name]
                for name in ('base_joints', 'platform_joints', 'home_position')}
    node = make_node(cli_args=file_args(write_params(required)))
    values = declare_parameters(node, SPECS)
    assert values['home_orientation_deg'] == [0.0, 0.0, 0.0]
    assert values['leg_length_min'] == 0.0
    assert values['leg_length_max'] == math.inf
    assert values['tolerance'] == 1e-12
    assert values['max_iterations'] == 50
    assert values['queue_depth'] == 10


def test_parameter_overrides_give_their_values(make_node):
    """Values given as parameter_overrides instead of a file are used too."""
    overrides = [Parameter(name, value=value) for name, value in GOOD_VALUES.items()]
    node = make_node(parameter_overrides=overrides)
    values = declare_parameters(node, SPECS)
    assert {name: values[name] for name in GOOD_VALUES} == GOOD_VALUES


@pytest.mark.parametrize('name, value, reason', [
    ('base_joints', BASE_JOINTS[:17], "'base_joints' must have exactly 18 elements, got 17"),
    ('platform_joints', PLATFORM_JOINTS + [0.0],
     "'platform_joints' must have exactly 18 elements, got 19"),
    ('home_position', [0.0, 0.4325], "'home_position' must have exactly 3 elements, got 2"),
])
def test_wrong_length_array_in_file_is_refused(make_node, write_params, name, value, reason):
    """An array of the wrong length fails the declaration with the spec's reason."""
    node = make_node(cli_args=file_args(write_params(with_value(name, value))))
    with pytest.raises(InvalidParameterValueException) as raised:
        declare_parameters(node, SPECS)
    assert reason in str(raised.value)


@pytest.mark.parametrize('name, value, reason', [
    ('home_orientation_deg', [0.0, 0.0, 200.0], "'home_orientation_deg' must be in [-180, 180]"),
    ('tolerance', 0.5, "'tolerance' must be in (0, 0.01]"),
    ('tolerance', 0.0, "'tolerance' must be in (0, 0.01]"),
    ('max_iterations', 0, "'max_iterations' must be in [1, 1000]"),
    ('leg_length_min', -0.1, "'leg_length_min' must be in [0, inf]"),
    ('leg_length_max', 0.0, "'leg_length_max' must be in (0, inf]"),
    ('queue_depth', 0, "'queue_depth' must be in [1, 10000]"),
    ('home_position', [0.0, math.nan, 0.4], "'home_position' must be finite"),
])
def test_out_of_range_value_in_file_is_refused(make_node, write_params, name, value, reason):
    """A value outside its allowed range fails the declaration, naming parameter and range."""
    node = make_node(cli_args=file_args(write_params(with_value(name, value))))
    with pytest.raises(InvalidParameterValueException) as raised:
        declare_parameters(node, SPECS)
    assert reason in str(raised.value)


@pytest.mark.parametrize('name, value, expected_type', [
    ('base_joints', 'b1 b2 b3', 'DOUBLE_ARRAY'),
    ('tolerance', 'small', 'DOUBLE'),
    ('max_iterations', 2.5, 'INTEGER'),
])
def test_wrong_type_in_file_is_refused(make_node, write_params, name, value, expected_type):
    """A value of the wrong type fails with a message naming the parameter and the type."""
    node = make_node(cli_args=file_args(write_params(with_value(name, value))))
    with pytest.raises(InvalidParameterTypeException) as raised:
        declare_parameters(node, SPECS)
    message = str(raised.value)
    assert name in message
    assert expected_type in message


def test_wrong_type_is_a_parameter_exception(make_node, write_params):
    """Both failure kinds derive from ParameterException, which node_main catches."""
    assert issubclass(InvalidParameterTypeException, ParameterException)
    assert issubclass(InvalidParameterValueException, ParameterException)
    node = make_node(cli_args=file_args(write_params(with_value('base_joints', 'x'))))
    with pytest.raises(ParameterException):
        declare_parameters(node, SPECS)


@pytest.mark.parametrize('missing', ['base_joints', 'platform_joints', 'home_position'])
def test_missing_required_parameter_raises_value_error(make_node, write_params, missing):
    """A required parameter that no file sets raises ValueError naming it (as documented)."""
    values = {k: v for k, v in GOOD_VALUES.items() if k != missing}
    node = make_node(cli_args=file_args(write_params(values)))
    with pytest.raises(ValueError) as raised:
        declare_parameters(node, SPECS)
    assert f"'{missing}' is required" in str(raised.value)


def test_missing_required_parameter_is_refused_with_its_name(make_node, write_params):
    """Whatever the exception class, a missing required parameter stops the declaration."""
    values = {k: v for k, v in GOOD_VALUES.items() if k != 'home_position'}
    node = make_node(cli_args=file_args(write_params(values)))
    with pytest.raises((ValueError, ParameterException)) as raised:
        declare_parameters(node, SPECS)
    assert "'home_position' is required" in str(raised.value)
    assert 'parameter file' in str(raised.value)


@pytest.mark.parametrize('name, value, reason', [
    ('tolerance', -1.0, "'tolerance' must be in (0, 0.01], got -1.0"),
    ('tolerance', math.nan, "'tolerance' must be finite"),
    ('max_iterations', 5000, "'max_iterations' must be in [1, 1000], got 5000"),
])
def test_invalid_run_time_change_is_refused(make_node, name, value, reason):
    """An invalid set_parameters is unsuccessful with the reason; old value and settings stay."""
    changes = []
    node = make_node(parameter_overrides=[
        Parameter(key, value=val) for key, val in GOOD_VALUES.items()])
    declare_parameters(node, SPECS, on_change=lambda *change: changes.append(change))
    [result] = node.set_parameters([Parameter(name, value=value)])
    assert not result.successful
    assert reason in result.reason
    assert node.get_parameter(name).value == GOOD_VALUES[name]
    assert changes == []


def test_wrong_type_at_run_time_is_refused(make_node):
    """A string for a double at run time is refused and the old value kept."""
    node = make_node(parameter_overrides=[
        Parameter(key, value=val) for key, val in GOOD_VALUES.items()])
    declare_parameters(node, SPECS)
    [result] = node.set_parameters([Parameter('tolerance', value='small')])
    assert not result.successful
    assert result.reason
    assert node.get_parameter('tolerance').value == 1e-9


def test_valid_run_time_change_calls_on_change(make_node):
    """A valid run-time change is applied and reported to on_change once, with its value."""
    changes = []
    node = make_node(parameter_overrides=[
        Parameter(key, value=val) for key, val in GOOD_VALUES.items()])
    declare_parameters(node, SPECS, on_change=lambda *change: changes.append(change))
    assert changes == []
    [result] = node.set_parameters([Parameter('tolerance', value=1e-6)])
    assert result.successful, result.reason
    assert node.get_parameter('tolerance').value == 1e-6
    assert changes == [('tolerance', 1e-6)]
    [result] = node.set_parameters([Parameter('max_iterations', value=7)])
    assert result.successful, result.reason
    assert changes == [('tolerance', 1e-6), ('max_iterations', 7)]


def test_atomic_change_with_one_bad_value_changes_nothing(make_node):
    """set_parameters_atomically with one invalid value applies none of them."""
    changes = []
    node = make_node(parameter_overrides=[
        Parameter(key, value=val) for key, val in GOOD_VALUES.items()])
    declare_parameters(node, SPECS, on_change=lambda *change: changes.append(change))
    result = node.set_parameters_atomically([
        Parameter('tolerance', value=1e-6), Parameter('max_iterations', value=-3)])
    assert not result.successful
    assert "'max_iterations'" in result.reason
    assert node.get_parameter('tolerance').value == 1e-9
    assert node.get_parameter('max_iterations').value == 20
    assert changes == []


@pytest.mark.parametrize('name, value', [
    ('base_joints', list(reversed(BASE_JOINTS))),
    ('home_position', [0.0, 0.0, 0.5]),
    ('leg_length_max', 2.0),
    ('queue_depth', 3),
])
def test_read_only_parameters_refuse_changes(make_node, name, value):
    """The geometry and the queue depth cannot change at run time, even to valid values."""
    changes = []
    node = make_node(parameter_overrides=[
        Parameter(key, value=val) for key, val in GOOD_VALUES.items()])
    declare_parameters(node, SPECS, on_change=lambda *change: changes.append(change))
    [result] = node.set_parameters([Parameter(name, value=value)])
    assert not result.successful
    assert 'read-only' in result.reason
    assert node.get_parameter(name).value == GOOD_VALUES[name]
    assert changes == []


@pytest.mark.parametrize('specs', [SPECS, RAMP_SPECS], ids=['kinematics', 'ramp'])
def test_descriptors_carry_description_unit_type_and_read_only(make_node, specs):
    """Every declared parameter has a descriptor with description, unit, type and read-only."""
    required = {spec.name: GOOD_VALUES[spec.name] for spec in specs if spec.default is None}
    node = make_node(parameter_overrides=[
        Parameter(key, value=val) for key, val in required.items()])
    declare_parameters(node, specs)
    types = {
        'bool': ParameterType.PARAMETER_BOOL,
        'integer': ParameterType.PARAMETER_INTEGER,
        'double': ParameterType.PARAMETER_DOUBLE,
        'string': ParameterType.PARAMETER_STRING,
        'double_array': ParameterType.PARAMETER_DOUBLE_ARRAY,
    }
    for spec in specs:
        described = node.describe_parameter(spec.name)
        assert described.name == spec.name
        assert described.description.startswith(spec.description)
        if spec.name in UNITS:
            assert UNITS[spec.name] in described.description, spec.name
        if spec.constraints:
            assert f'(allowed: {spec.constraints})' in described.description
        assert described.type == types[spec.value_type], spec.name
        assert described.read_only == spec.read_only, spec.name
    geometry_names = {spec.name for spec in parameters.GEOMETRY_PARAMETERS}
    for spec in specs:
        if spec.name in geometry_names:
            # The payload's change at run time (test_payload_parameters.py); nothing else does.
            assert node.describe_parameter(spec.name).read_only == (
                spec.name not in parameters.PAYLOAD_PARAMETERS), spec.name
    if specs is SPECS:
        assert not node.describe_parameter('tolerance').read_only
        assert not node.describe_parameter('max_iterations').read_only


def test_ramp_mode_must_be_known(make_node, write_params):
    """A ramp mode other than table or interpolate is refused, listing the allowed ones."""
    node = make_node(cli_args=file_args(write_params({'mode': 'circle'})))
    with pytest.raises(InvalidParameterValueException) as raised:
        declare_parameters(node, RAMP_SPECS)
    assert "'mode' must be one of table, interpolate, off; got 'circle'" in str(raised.value)
