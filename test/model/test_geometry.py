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
Unit tests of stewart_kinematics.model.geometry (pure numpy).

The paper's Tables 1 and 2 are typed here in millimetres, as printed, and converted to metres.
"""

import dataclasses
import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import BASE_JOINTS, HOME, leg_lengths, paper_geometry, PLATFORM_JOINTS

from stewart_kinematics.limits import LimitModel
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.parameters import geometry_from_parameters, load_geometry

pytestmark = pytest.mark.core

PAPER_PLATFORM_YAML = Path(__file__).resolve().parents[2] / 'config' / 'paper_platform.yaml'

BASE_M, PLATFORM_M = BASE_JOINTS, PLATFORM_JOINTS
HOME_Z = HOME[2]


def paper_parameters():
    """Return the paper's geometry as ROS parameter values (flat lists, metres and degrees)."""
    return {
        'base_joints': BASE_M.ravel().tolist(),
        'platform_joints': PLATFORM_M.ravel().tolist(),
        'home_position': [0.0, 0.0, HOME_Z],
        'home_orientation_deg': [0.0, 0.0, 0.0],
        'leg_length_min': 0.0,
        'leg_length_max': math.inf,
    }


def write_file(directory, text):
    """Write ``text`` to params.yaml in ``directory`` and return its path."""
    path = directory / 'params.yaml'
    path.write_text(text, encoding='utf-8')
    return path


def flat(values):
    """Format floats as a YAML flow list."""
    return '[' + ', '.join(repr(float(value)) for value in values) + ']'


def paper_yaml_section():
    """Return the '/**' section of a parameter file with the paper's geometry."""
    return (
        '/**:\n'
        '  ros__parameters:\n'
        f'    base_joints: {flat(BASE_M.ravel())}\n'
        f'    platform_joints: {flat(PLATFORM_M.ravel())}\n'
        f'    home_position: [0.0, 0.0, {HOME_Z}]\n')


def test_load_geometry_gives_table_1_base_joints_in_metres():
    """config/paper_platform.yaml holds Table 1 converted to metres."""
    geometry = load_geometry(PAPER_PLATFORM_YAML)
    assert_allclose(geometry.base_joints, BASE_M, rtol=0.0, atol=1e-12)


def test_load_geometry_gives_table_2_platform_joints_in_metres():
    """config/paper_platform.yaml holds Table 2 converted to metres, with p_3 z = 0.257."""
    geometry = load_geometry(PAPER_PLATFORM_YAML)
    assert_allclose(geometry.platform_joints, PLATFORM_M, rtol=0.0, atol=1e-12)
    assert geometry.platform_joints[2, 2] == pytest.approx(0.257, abs=1e-12)


def test_load_geometry_home_pose_and_limits():
    """The paper's home pose is [0, 0, 0.4325, 0, 0, 0] and the legs have no limits."""
    geometry = load_geometry(str(PAPER_PLATFORM_YAML))
    assert_allclose(geometry.home_pose, [0.0, 0.0, HOME_Z, 0.0, 0.0, 0.0], rtol=0.0, atol=0.0)
    assert geometry.leg_length_min == 0.0
    assert geometry.leg_length_max == math.inf


def test_home_leg_lengths_by_hand():
    """Home leg lengths equal |t + p_i - b_i| at the home pose, leg by leg."""
    geometry = load_geometry(PAPER_PLATFORM_YAML)
    expected = leg_lengths(HOME)
    assert geometry.home_leg_lengths.shape == (6,)
    assert_allclose(geometry.home_leg_lengths, expected, rtol=0.0, atol=1e-12)


def test_home_leg_lengths_follow_home_orientation():
    """A home yaw of 90 degrees rotates the platform joints before measuring the legs."""
    geometry = paper_geometry(home_pose=[0.0, 0.0, HOME_Z, 0.0, 0.0, math.pi / 2])
    expected = [
        math.sqrt((-py - bx) ** 2 + (px - by) ** 2 + (HOME_Z + pz - bz) ** 2)
        for (bx, by, bz), (px, py, pz) in zip(BASE_M, PLATFORM_M)]
    assert_allclose(geometry.home_leg_lengths, expected, rtol=0.0, atol=1e-12)


def test_constructor_defaults():
    """Without a home pose or limits, the home pose is zero and no limit is set."""
    geometry = Geometry(base_joints=BASE_M, platform_joints=PLATFORM_M)
    assert_allclose(geometry.home_pose, np.zeros(6), rtol=0.0, atol=0.0)
    assert geometry.limits is None
    assert LimitModel(geometry).pose_limits == () and LimitModel(geometry).leg_state_limits == ()
    with pytest.raises(AttributeError, match='leg_length_max'):
        geometry.leg_length_max


@pytest.mark.parametrize('name, value', [
    ('base_joints', BASE_M[:5]),
    ('base_joints', BASE_M.ravel()),
    ('platform_joints', PLATFORM_M[:, :2]),
    ('home_pose', [0.0, 0.0, HOME_Z]),
])
def test_wrong_shape_raises_naming_the_array(name, value):
    """An array of the wrong shape raises ValueError naming it and the expected shape."""
    with pytest.raises(ValueError, match=rf'{name} must have shape'):
        paper_geometry(**{name: value})


def test_non_numeric_array_raises_naming_the_array():
    """A non-numeric joint array raises ValueError naming it."""
    with pytest.raises(ValueError, match='base_joints must be numbers'):
        paper_geometry(base_joints=[['a', 'b', 'c']] * 6)


@pytest.mark.parametrize('name, bad', [
    ('base_joints', math.nan),
    ('platform_joints', math.inf),
    ('home_pose', math.nan),
])
def test_non_finite_value_raises_naming_the_array(name, bad):
    """A NaN or infinite entry raises ValueError naming the array."""
    value = np.array(getattr(paper_geometry(), name))
    value.flat[1] = bad
    with pytest.raises(ValueError, match=rf'{name} must be finite'):
        paper_geometry(**{name: value})


def test_two_coincident_joints_are_one_joint_shared_by_two_legs():
    """Two base joints at the same place are one joint that legs 2 and 5 share."""
    base = BASE_M.copy()
    base[4] = base[1]
    geometry = paper_geometry(base_joints=base)
    assert [(joint.side, joint.legs) for joint in geometry.shared_joints] == [('base', (2, 5))]
    assert geometry.design == '5-6'


def test_three_coincident_joints_raise_naming_the_joints():
    """Three base joints at the same place raise ValueError naming them: two legs at most."""
    base = BASE_M.copy()
    base[[0, 4]] = base[1]
    with pytest.raises(ValueError, match=r'base_joints: joints 1, 2 and 5 coincide \(3 legs on '
                                         r'one point\); a joint may be shared by 2 legs at most'):
        paper_geometry(base_joints=base)


def test_collinear_joints_raise():
    """Six platform joints on one line raise ValueError saying they are collinear."""
    platform = np.array([[0.01 * k, 0.02 * k, 0.275] for k in range(6)])
    with pytest.raises(ValueError, match=r'platform_joints: the six joints are collinear'):
        paper_geometry(platform_joints=platform)


@pytest.mark.parametrize('low, high, message', [
    (1.0, 1.0, r'leg_length_min < leg_length_max, got leg_length_min=1.0, leg_length_max=1.0'),
    (1.0, 0.5, r'leg_length_min < leg_length_max, got leg_length_min=1.0, leg_length_max=0.5'),
    (-0.1, 1.0, r'leg_length_min must be in \[0, inf\], got -0.1'),
    (math.nan, 1.0, 'leg_length_min must be finite, got nan'),
    (0.0, math.nan, r'leg_length_max must be in \(0, inf\], got nan'),
    (math.inf, math.inf, 'leg_length_min must be finite, got inf'),
])
def test_bad_leg_length_limits_raise(low, high, message):
    """Limits that do not satisfy 0 <= min < max raise ValueError naming what is wrong."""
    with pytest.raises(ValueError, match=message):
        paper_geometry(leg_length_min=low, leg_length_max=high)


def test_home_pose_outside_limits_raises_naming_the_legs():
    """A maximum between leg 3 (0.701 m) and the others (0.719 m) names legs 1, 2, 4, 5, 6."""
    with pytest.raises(ValueError, match='home pose breaks the limits') as raised:
        paper_geometry(leg_length_max=0.71)
    message = str(raised.value)
    for leg in (1, 2, 4, 5, 6):
        assert f'leg {leg}: leg_length_max 0.71 m' in message
    assert 'leg 3' not in message


def test_home_pose_below_minimum_raises_naming_the_leg():
    """A minimum above leg 3's home length (0.701 m) names leg 3 only."""
    with pytest.raises(ValueError, match='home pose breaks the limits') as raised:
        paper_geometry(leg_length_min=0.71, leg_length_max=1.0)
    message = str(raised.value)
    assert 'leg 3: leg_length_min 0.71 m broken by 0.00885' in message
    assert 'leg 1' not in message


def test_limits_around_home_are_accepted():
    """Limits that contain every home leg length are stored as floats."""
    geometry = paper_geometry(leg_length_min=0.5, leg_length_max=1)
    assert geometry.leg_length_min == 0.5
    assert isinstance(geometry.leg_length_max, float) and geometry.leg_length_max == 1.0


def test_arrays_are_read_only():
    """The stored arrays cannot be written to."""
    geometry = paper_geometry()
    for name in ('base_joints', 'platform_joints', 'home_pose'):
        with pytest.raises(ValueError, match='read-only'):
            getattr(geometry, name)[0] = 1.0


def test_arrays_are_copied_from_the_caller():
    """Changing the caller's array afterwards does not change the geometry."""
    base = BASE_M.copy()
    geometry = paper_geometry(base_joints=base)
    base[0, 0] = 99.0
    assert_allclose(geometry.base_joints, BASE_M, rtol=0.0, atol=0.0)


def test_fields_cannot_be_reassigned():
    """The geometry is frozen."""
    geometry = paper_geometry()
    with pytest.raises(dataclasses.FrozenInstanceError):
        geometry.leg_length_max = 2.0


def test_joint_angle_and_condition_limits_are_validated():
    """Cone angles must be in (0, pi] and the condition limit at least 1."""
    with pytest.raises(ValueError, match='base_joint_max_angle'):
        paper_geometry(base_joint_max_angle=0.0)
    with pytest.raises(ValueError, match='platform_joint_max_angle'):
        paper_geometry(platform_joint_max_angle=4.0)
    with pytest.raises(ValueError, match='max_jacobian_condition'):
        paper_geometry(max_jacobian_condition=0.5)


def test_home_pose_must_be_away_from_the_singularity_margin():
    """A condition limit below the home pose's (about 9.5) refuses the geometry."""
    with pytest.raises(ValueError, match='platform: max_jacobian_condition 5'):
        paper_geometry(max_jacobian_condition=5.0)


def test_from_parameters_builds_the_paper_geometry():
    """Flat joint lists in metres and the home orientation in degrees are converted."""
    values = paper_parameters()
    values['home_orientation_deg'] = [0.0, 0.0, 90.0]
    geometry = geometry_from_parameters(values)
    assert_allclose(geometry.base_joints, BASE_M, rtol=0.0, atol=0.0)
    assert_allclose(geometry.platform_joints, PLATFORM_M, rtol=0.0, atol=0.0)
    assert_allclose(geometry.home_pose, [0.0, 0.0, HOME_Z, 0.0, 0.0, math.pi / 2],
                    rtol=0.0, atol=1e-15)


def test_from_parameters_uses_defaults_for_optional_values():
    """Missing optional parameters take their defaults: no rotation and no limits."""
    values = paper_parameters()
    for name in ('home_orientation_deg', 'leg_length_min', 'leg_length_max'):
        del values[name]
    geometry = geometry_from_parameters(values)
    assert_allclose(geometry.home_pose[3:], [0.0, 0.0, 0.0], rtol=0.0, atol=0.0)
    assert geometry.leg_length_min == 0.0
    assert geometry.leg_length_max == math.inf


@pytest.mark.parametrize('name', ['base_joints', 'platform_joints', 'home_position'])
def test_from_parameters_missing_required_parameter_names_it(name):
    """A missing required parameter raises ValueError naming it."""
    values = paper_parameters()
    del values[name]
    with pytest.raises(ValueError, match=rf"parameter '{name}' is required"):
        geometry_from_parameters(values)


def test_from_parameters_bad_value_names_parameter_and_value():
    """A list of the wrong length raises ValueError naming the parameter and the value."""
    values = paper_parameters()
    values['home_position'] = [0.0, 0.5]
    with pytest.raises(ValueError, match=r"'home_position'.*3 elements.*\[0\.0, 0\.5\]"):
        geometry_from_parameters(values)


def test_load_geometry_missing_file_raises_naming_the_path(tmp_path):
    """A missing file raises ValueError naming it."""
    path = tmp_path / 'absent.yaml'
    with pytest.raises(ValueError, match=r'absent\.yaml: cannot read parameter file'):
        load_geometry(path)


def test_load_geometry_invalid_yaml_raises(tmp_path):
    """A file that is not YAML raises ValueError saying so."""
    path = write_file(tmp_path, '/**:\n  ros__parameters: [unclosed\n')
    with pytest.raises(ValueError, match='not valid YAML'):
        load_geometry(path)


def test_load_geometry_bad_value_names_parameter_and_value(tmp_path):
    """A negative leg_length_min raises ValueError naming the file, parameter and value."""
    path = write_file(tmp_path, paper_yaml_section() + '    leg_length_min: -0.25\n')
    with pytest.raises(ValueError, match=r"params\.yaml: parameter 'leg_length_min'.*-0\.25"):
        load_geometry(path)


def test_load_geometry_bad_geometry_names_file_and_problem(tmp_path):
    """Limits that exclude the home pose raise ValueError naming the file and the legs."""
    path = write_file(tmp_path, paper_yaml_section() + '    leg_length_max: 0.5\n')
    with pytest.raises(ValueError, match=r'params\.yaml: the home pose breaks the limits: leg'):
        load_geometry(path)


def test_load_geometry_node_section_overrides_wildcard(tmp_path):
    """A node's own section overrides '/**' for that node only."""
    text = (paper_yaml_section()
            + 'fk_node:\n  ros__parameters:\n    leg_length_max: 2.0\n'
            + '    home_position: [0.0, 0.0, 0.5]\n')
    path = write_file(tmp_path, text)
    for_node = load_geometry(path, node_name='fk_node')
    assert for_node.leg_length_max == 2.0
    assert_allclose(for_node.home_pose[:3], [0.0, 0.0, 0.5], rtol=0.0, atol=0.0)
    assert_allclose(for_node.base_joints, BASE_M, rtol=0.0, atol=1e-15)
    shared = load_geometry(path)
    assert shared.leg_length_max == math.inf
    assert_allclose(shared.home_pose[:3], [0.0, 0.0, HOME_Z], rtol=0.0, atol=0.0)


def test_load_geometry_refuses_a_misspelt_parameter_name(tmp_path):
    """A typo in a parameter name is refused with the closest known name."""
    text = PAPER_PLATFORM_YAML.read_text(encoding='utf-8')
    path = tmp_path / 'typo.yaml'
    path.write_text(text.replace('leg_length_max:', 'leg_length_mx:'), encoding='utf-8')
    with pytest.raises(ValueError, match="did you mean 'leg_length_max'"):
        load_geometry(path)


def test_load_geometry_names_what_replaced_pivot_point(tmp_path):
    """A file that still sets pivot_point is refused, naming the tool frame that replaced it."""
    path = tmp_path / 'old.yaml'
    path.write_text(PAPER_PLATFORM_YAML.read_text(encoding='utf-8').replace(
        'home_position:', 'pivot_point: [0.0, 0.0, 0.0]\n    home_position:'), encoding='utf-8')
    with pytest.raises(ValueError, match="'pivot_point' .replaced by 'tool_frame_position'"):
        load_geometry(path)
