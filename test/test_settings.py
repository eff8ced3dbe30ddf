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

"""Typed settings: built from the parameter specs, frozen, checked, and failing on a wrong name."""

import dataclasses
import math

import numpy as np
import pytest
from stewart_kinematics import parameters
from stewart_kinematics.parameters import settings as settings_module
from stewart_kinematics.parameters.settings import (
    FkNodeSettings,
    GeometrySettings,
    IkNodeSettings,
    NodeSettings,
    Settings,
    SolverSettings,
    StreamingSettings,
    TrajectoryNodeSettings,
)

pytestmark = pytest.mark.core

GROUP_CLASSES = [value for value in vars(settings_module).values()
                 if isinstance(value, type) and issubclass(value, Settings)
                 and value is not Settings]
NODE_CLASSES = (IkNodeSettings, FkNodeSettings, TrajectoryNodeSettings)
PYTHON_TYPES = {'bool': bool, 'integer': int, 'double': float, 'string': str,
                'double_array': tuple, 'string_array': tuple}


@pytest.mark.parametrize('group', GROUP_CLASSES, ids=lambda group: group.__name__)
def test_a_settings_class_has_one_typed_field_per_spec_with_its_default(group):
    fields = dataclasses.fields(group)
    assert [field.name for field in fields] == [spec.name for spec in group.SPECS]
    for spec in group.SPECS:
        if spec.default is None:
            continue
        value = getattr(group(**required_values(group)), spec.name)
        assert isinstance(value, PYTHON_TYPES[spec.value_type]), spec.name
        expected = tuple(spec.default) if isinstance(spec.default, list) else spec.default
        assert value == expected, spec.name


def required_values(group):
    """Values for the required fields of ``group`` (the geometry's joints and home)."""
    values = {'base_joints': (0.1, 0.0, 0.0) * 6, 'platform_joints': (0.1, 0.0, 0.0) * 6,
              'home_position': (0.0, 0.0, 0.5)}
    return {spec.name: values[spec.name] for spec in group.SPECS if spec.default is None}


def test_every_parameter_belongs_to_a_settings_group_once():
    grouped = [spec.name for group in GROUP_CLASSES for spec in group.SPECS]
    assert sorted(grouped) == sorted(spec.name for spec in parameters.all_specs())


def test_a_wrong_name_fails_where_it_is_written():
    with pytest.raises(TypeError, match='comand_rate'):
        StreamingSettings(comand_rate=100.0)
    with pytest.raises(AttributeError, match='comand_rate'):
        StreamingSettings().comand_rate  # noqa: B018


def test_a_value_is_checked_by_its_spec_with_the_parameter_named():
    with pytest.raises(ValueError, match=r"parameter 'command_rate' must be in \[0, 10000\]"):
        StreamingSettings(command_rate=-1.0)
    with pytest.raises(ValueError, match=r"parameter 'tolerance' must be of type double"):
        SolverSettings(tolerance=1)
    with pytest.raises(ValueError, match="parameter 'max_iterations'"):
        SolverSettings().replace(max_iterations=0)


def test_settings_are_frozen_and_hashable_with_arrays_as_tuples():
    settings = GeometrySettings(**required_values(GeometrySettings))
    assert settings.base_joints == (0.1, 0.0, 0.0) * 6
    with pytest.raises(dataclasses.FrozenInstanceError):
        settings.leg_length_max = 1.0
    assert hash(settings) == hash(GeometrySettings(**required_values(GeometrySettings)))
    assert settings.as_values()['home_position'] == [0.0, 0.0, 0.5]


def test_from_values_takes_its_names_ignores_others_and_names_a_missing_required_one():
    values = dict(required_values(GeometrySettings), leg_length_max=0.9, command_rate=5.0)
    settings = GeometrySettings.from_values(values)
    assert settings.leg_length_max == 0.9 and settings.leg_length_min == 0.0
    assert settings.max_jacobian_condition == math.inf
    del values['platform_joints']
    with pytest.raises(ValueError, match="parameter 'platform_joints' is required"):
        GeometrySettings.from_values(values)


@pytest.mark.parametrize('node', NODE_CLASSES, ids=lambda node: node.__name__)
def test_a_node_settings_object_groups_its_parameters_and_changes_them_by_name(node):
    assert issubclass(node, NodeSettings)
    values = required_values(GeometrySettings)
    settings = node.from_values(values)
    names = [spec.name for spec in node.specs()]
    assert len(names) == len(set(names))
    assert settings.as_values().keys() == set(names)
    changed = settings.replace(queue_depth=20)
    assert changed.queue.queue_depth == 20 and settings.queue.queue_depth == 10
    with pytest.raises(ValueError, match="unknown parameter 'queue_dept'"):
        settings.replace(queue_dept=20)
    with pytest.raises(ValueError, match="parameter 'queue_depth'"):
        settings.replace(queue_depth=0)


def test_the_builders_give_the_objects_the_settings_describe(config_directory):
    values = parameters.read_parameter_file(config_directory / 'paper_platform.yaml')
    values.update(parameters.read_parameter_file(config_directory / 'example_limits.yaml'))
    settings = IkNodeSettings.from_values(values)
    geometry = parameters.geometry_from_settings(settings.geometry)
    same = parameters.geometry_from_parameters(values)
    assert np.array_equal(geometry.home_leg_lengths, same.home_leg_lengths)
    assert geometry.leg_length_max == 0.9
    assert math.degrees(geometry.base_joint_max_angle) == pytest.approx(30.0)
    limits = parameters.actuator_limits_from_settings(settings.geometry)
    assert (limits.velocity_max, limits.acceleration_max) == (0.05, 0.25)
    actuators = parameters.actuator_interface_from_settings(settings.actuators)
    assert actuators.joint_names == ('leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5', 'leg_6')
    frames = parameters.frames_from_settings(settings.frames)
    assert frames.base_frame == 'stewart_base'
