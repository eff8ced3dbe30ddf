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
CueingSettings takes its defaults and its allowed values from the motion cueing's parameter specs.

Each setting is probed at and beyond the bounds of its parameter (in the parameter's units: the
settings hold radians where the parameter is in degrees): the settings refuse exactly what the
parameter refuses, and every default is the parameter's default.
"""

from dataclasses import fields
import math

import pytest

from stewart_kinematics.cueing import CueingSettings
from stewart_kinematics.cueing.settings import DEGREE_FIELDS
from stewart_kinematics.parameters import MOTION_CUEING_PARAMETERS

pytestmark = pytest.mark.core

SPECS = {spec.name: spec for spec in MOTION_CUEING_PARAMETERS}
#: Numbers at and around the bounds of the cueing parameters (0, 1, 10, 45, 90, 100, 360, 1000,
#: 3600, 10000), and beyond any.
NUMBERS = (-math.inf, -361.0, -10.001, -10.0, -1.0, 0.0, 1e-9, 0.5, 1.0, 1.001, 2.0, 3.0, 4.0,
           9.999, 10.0, 10.001, 45.0, 45.001, 90.0, 90.001, 100.0, 100.001, 360.0, 360.001,
           1000.0, 1000.001, 3600.0, 3600.001, 1e4, 1e4 + 0.01, 1e308, math.inf, math.nan)
NAMES = ('base_link', '', 'imu link', '/imu', 'imu_link')


def parameter_of(field):
    """Return the parameter spec of a settings field (``<field>_deg`` for one in radians)."""
    return SPECS[field + '_deg' if field in DEGREE_FIELDS else field]


def as_setting(field, value):
    """Return a parameter value as the settings field holds it (radians, tuples)."""
    if field in DEGREE_FIELDS:
        value = [math.radians(item) for item in value] if isinstance(value, list) else (
            math.radians(value))
    return tuple(value) if isinstance(value, list) else value


def probes(spec):
    """Values of the parameter's type at and beyond its bounds."""
    if spec.value_type == 'double':
        return NUMBERS
    if spec.value_type == 'integer':
        return (-1, 0, 1, 2, 3, 4)
    if spec.value_type == 'string':
        return NAMES
    if spec.value_type == 'bool':
        return (True, False)
    # An array: each number in one place of the default, and a wrong length.
    default = spec.default
    return [default[:-1], default + [default[0]]] + [[number] + default[1:] for number in NUMBERS]


SETTING_FIELDS = [item.name for item in fields(CueingSettings) if item.name != 'gravity']


def test_every_setting_but_gravity_is_a_parameter():
    assert sorted(parameter_of(field).name for field in SETTING_FIELDS) == sorted(SPECS)


@pytest.mark.parametrize('field', SETTING_FIELDS)
def test_a_default_is_the_parameter_default(field):
    assert getattr(CueingSettings(), field) == as_setting(field, parameter_of(field).default)


@pytest.mark.parametrize('field', SETTING_FIELDS)
def test_a_setting_refuses_exactly_what_its_parameter_refuses(field):
    spec = parameter_of(field)
    for value in probes(spec):
        reason = spec.check(value)
        try:
            CueingSettings(**{field: as_setting(field, value)})
            refusal = ''
        except ValueError as error:
            refusal = str(error)
        assert bool(reason) == bool(refusal), (field, value, reason, refusal)
        if reason:
            assert refusal.startswith(f'{field} must'), refusal


@pytest.mark.parametrize('changes, message', [
    ({'follower_frequency': 5000.0}, r'follower_frequency must be in \(0, 1000\], got 5000.0'),
    ({'vehicle_frame': ''}, 'vehicle_frame must not be empty'),
    ({'imu_frame': 'imu link'}, 'imu_frame must be a frame name without spaces'),
    ({'tilt_max': math.radians(46.0)}, r'tilt_max must be in \(0, 0.785398\]'),
])
def test_values_the_parameters_refuse_are_refused_by_the_settings(changes, message):
    """The settings had looser rules of their own (any positive frequency, any string)."""
    with pytest.raises(ValueError, match=message):
        CueingSettings(**changes)


@pytest.mark.parametrize('changes', [
    {'translation_frequency': (1e-300, 1.0, 1.0)},
    {'translation_break_frequency': (1.0, 1e-300, 1.0)},
    {'tilt_frequency': 1e-300}, {'rotation_frequency': (1.0, 1.0, 1e-300)},
])
def test_a_filter_frequency_too_low_to_build_is_refused_naming_it(changes):
    """
    1e-300 rad/s was allowed and cubed to 0 in the filter: an internal "monic" message.

    A filter frequency is at least 1e-3 rad/s (a period of 1.7 hours); the refusal names it.
    """
    (name, _), = changes.items()
    with pytest.raises(ValueError, match=rf'^{name} must be in \[0.001, 100\], got '):
        CueingSettings(**changes)
    settings = CueingSettings(**{name: 1e-3 if name == 'tilt_frequency' else (1e-3,) * 3})
    assert getattr(settings, name) in (1e-3, (1e-3,) * 3)


def test_from_parameters_names_the_parameter_in_degrees():
    with pytest.raises(ValueError, match='^tilt_max_deg must be in degrees within the allowed '
                                         r'range; tilt_max must be in \(0, 0.785398\]'):
        CueingSettings.from_parameters({'tilt_max_deg': 50.0})
