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

"""PoseLimits: the home of the pose limits' values, and the geometry that is given them."""

import dataclasses
import math
from pathlib import Path
import pickle

import numpy as np
import pytest

from stewart_kinematics import Geometry, load_geometry, PoseLimits
from stewart_kinematics.parameters import geometry_from_parameters, GEOMETRY_PARAMETERS

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
LIMITED = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])


@pytest.mark.parametrize('changes, words', [
    ({'leg_radius': True}, 'leg_radius'),
    ({'leg_radius': '0.1'}, 'leg_radius'),
    ({'leg_radius': [[[0.1]]]}, 'leg_radius must be one number'),
    ({'leg_radius': None}, 'leg_radius'),
    ({'leg_radius': 1.5}, r'leg_radius must be in \[0, 1\]'),
    ({'max_jacobian_condition': math.nan}, 'max_jacobian_condition'),
    ({'base_joint_max_angle': 4.0}, 'base_joint_max_angle'),
    ({'leg_length_min': -math.inf}, 'leg_length_min'),
    ({'leg_length_min': 0.9, 'leg_length_max': 0.5}, 'leg_length_min < leg_length_max'),
    ({'': 1.0}, "'' is not a pose limit"),
    ({'leg_radius_m': 0.01}, "'leg_radius_m' is not a pose limit.*leg_radius"),
])
def test_bad_values_are_refused_naming_the_setting(changes, words):
    with pytest.raises(ValueError, match=words):
        PoseLimits(**changes)


def test_the_settings_refuse_what_their_parameters_refuse():
    """One rule: a parameter file and a Python caller meet the same bounds (SI for the cones)."""
    specs = {spec.name: spec for spec in GEOMETRY_PARAMETERS}
    for name, probes in (('leg_radius', (-0.01, 0.0, 0.5, 1.0, 1.0001, 2.0)),
                         ('leg_length_min', (-1e-9, 0.0, 0.3)),
                         ('max_jacobian_condition', (0.99, 1.0, 1e308, math.inf))):
        for value in probes:
            refused_by_spec = bool(specs[name].check(value))
            try:
                PoseLimits(**{name: value})
                refused = False
            except ValueError:
                refused = True
            assert refused == refused_by_spec, (name, value)
    for degrees in (-1.0, 0.0, 1e-9, 90.0, 180.0, 180.0001):
        refused_by_spec = bool(specs['base_joint_max_angle_deg'].check(degrees))
        try:
            PoseLimits(base_joint_max_angle=math.radians(degrees))
            refused = False
        except ValueError:
            refused = True
        assert refused == refused_by_spec, degrees


def test_the_values_are_immutable_comparable_and_survive_pickling():
    limits = LIMITED.limits
    assert limits == PoseLimits(**limits.values())
    assert pickle.loads(pickle.dumps(limits)) == limits
    assert hash(pickle.loads(pickle.dumps(limits))) == hash(limits)
    with pytest.raises(AttributeError, match='immutable'):
        limits.leg_radius = 1.0
    with pytest.raises(AttributeError, match='no setting'):
        limits.leg_radiuss
    assert limits.replace(leg_radius=0.03).leg_radius == 0.03 and limits.leg_radius == 0.02


def test_parameters_round_trip_through_the_settings():
    """What calibration writes back (parameters, degrees) builds the same limits again."""
    parameters = LIMITED.limits.parameters()
    assert parameters['base_joint_max_angle_deg'] == pytest.approx(30.0, abs=1e-12)
    assert PoseLimits.from_parameters(parameters) == LIMITED.limits


def test_a_geometry_is_given_its_limits_and_checks_its_home_with_them():
    bare = dataclasses.replace(LIMITED, limits=None)
    assert bare.limits is None
    with pytest.raises(ValueError, match='limits must be a stewart_kinematics.PoseLimits'):
        Geometry(bare.base_joints, bare.platform_joints, bare.home_pose, limits='abc')
    with pytest.raises(ValueError, match='home pose breaks the limits.*leg_length_max'):
        Geometry(bare.base_joints, bare.platform_joints, bare.home_pose,
                 limits=PoseLimits(leg_length_max=float(np.min(bare.home_leg_lengths))))
    # The thin path for callers of the old Geometry: reads and changes go to the limits.
    assert LIMITED.leg_length_max == LIMITED.limits.leg_length_max == 0.9
    assert LIMITED.with_limits(leg_radius=0.0).limits.leg_radius == 0.0
    with pytest.raises(ValueError, match='no limits to change'):
        bare.with_limits(leg_radius=0.01)
    with pytest.raises(AttributeError):
        bare.leg_length_max


def test_a_parameter_file_builds_the_geometry_with_its_limit_settings():
    values = {'base_joints': LIMITED.base_joints.ravel().tolist(),
              'platform_joints': LIMITED.platform_joints.ravel().tolist(),
              'home_position': LIMITED.home_pose[:3].tolist(), 'leg_radius': 0.01,
              'platform_joint_max_angle_deg': 45.0}
    geometry = geometry_from_parameters(values)
    assert geometry.limits == PoseLimits(leg_radius=0.01,
                                         platform_joint_max_angle=math.radians(45.0))
