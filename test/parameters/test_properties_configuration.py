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
Property tests of frames, actuators and the parameter builders: round trips and refusals.

Transforms compose and invert; a frame tree turns tool poses into platform poses and back;
an actuator interface turns lengths into positions and back in any joint order; parameter
values and files build the geometry they describe, and a bad one is refused naming the
parameter.
"""

import math
import sys

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose, assert_array_equal
from properties import (
    any_angles,
    assert_refused,
    budget,
    covers,
    floats,
    NON_FINITE,
    NOT_NUMBERS,
    PAPER,
    poses_near_home,
    ROOT,
    with_bad_entry,
    wrong_shapes,
)
import pytest
from reference import BASE_JOINTS, PLATFORM_JOINTS, rotation_zyx

from stewart_kinematics import (
    ActuatorInterface,
    ActuatorLimits,
    frames_from_parameters,
    FrameTree,
    geometry_from_parameters,
    load_geometry,
    load_settings,
    Transform,
)
from stewart_kinematics.parameters import defaults, FRAME_PARAMETERS, GEOMETRY_PARAMETERS

pytestmark = pytest.mark.core


def transforms():
    """Rigid transforms within a metre, any rotation."""
    return st.tuples(st.tuples(*[floats(-1.0, 1.0)] * 3), any_angles()).map(
        lambda value: Transform(np.array(value[0]), rotation_zyx(*value[1])))


def geometry_values(**changes):
    """Return parameter values of the paper's platform, as a node reads them."""
    values = defaults(GEOMETRY_PARAMETERS)
    values.update(base_joints=BASE_JOINTS.ravel().tolist(),
                  platform_joints=PLATFORM_JOINTS.ravel().tolist(),
                  home_position=[0.0, 0.0, 0.4325])
    values.update(changes)
    return values


@covers('Transform')
@budget(40)
@given(transforms(), transforms(), st.lists(st.tuples(*[floats(-1.0, 1.0)] * 3), max_size=5))
def test_transforms_compose_invert_and_apply(first, second, points):
    points = np.array(points, dtype=float).reshape(-1, 3)
    both = first @ second
    assert_allclose(both.apply(points), first.apply(second.apply(points)), rtol=0, atol=1e-12)
    identity = first @ first.inverse()
    assert_allclose(identity.rotation, np.eye(3), rtol=0, atol=1e-15)
    assert_allclose(identity.position, np.zeros(3), rtol=0, atol=1e-15)
    assert Transform().is_identity() and Transform.from_pose(np.zeros(6)).is_identity()
    assert_allclose(first.inverse().apply(first.apply(points)), points, rtol=0, atol=1e-12)
    again = Transform.from_pose(first.as_pose())
    assert_allclose(again.position, first.position, atol=1e-15)
    assert_allclose(again.rotation, first.rotation, atol=1e-14)


@covers('Transform')
@budget(40)
@given(st.sampled_from(['position', 'rotation']), st.data())
def test_a_transform_of_bad_arrays_is_refused(name, data):
    good = {'position': np.zeros(3), 'rotation': np.eye(3)}
    bad = data.draw(st.one_of(NOT_NUMBERS, wrong_shapes(good[name].shape),
                              NON_FINITE.flatmap(lambda v: with_bad_entry(good[name], v))))
    arguments = dict(good, **{name: bad})
    assert_refused(lambda: Transform(**arguments), ('position', 'rotation', 'transform'))
    if not (isinstance(bad, np.ndarray) and bad.shape == (6,) and np.all(np.isfinite(bad))):
        assert_refused(lambda: Transform.from_pose(bad), ('pose', 'Euler angles'))


@covers('FrameTree', 'frames_from_parameters')
@budget(40)
@given(transforms(), transforms(), poses_near_home())
def test_tool_poses_and_platform_poses_round_trip(tool, user, pose):
    tree = FrameTree(user_frame='work', user_pose=user).with_tool('tcp', tool)
    assert {name for name, _, _ in [(t[1], t[0], t[2]) for t in tree.static_transforms()]}
    for frame in ('', tree.base_frame, 'work'):
        tool_pose = tree.tool_pose_vector(pose, frame)
        assert np.all(np.isfinite(tool_pose))
        if frame != 'work':
            back = tree.platform_pose_vectors(tool_pose[None])[0]
            assert_allclose(back[:3], pose[:3], rtol=0, atol=1e-12)
            assert_allclose(rotation_zyx(*back[3:]), rotation_zyx(*pose[3:]), atol=1e-12)
    with pytest.raises(ValueError, match="frame 'elsewhere'"):
        tree.reference('elsewhere')
    values = defaults(FRAME_PARAMETERS)
    assert frames_from_parameters(values).tool_pose_vector(pose).tolist() == pytest.approx(
        pose.tolist(), abs=1e-15)


@covers('FrameTree', 'frames_from_parameters')
@budget(30)
@given(st.sampled_from(['base_frame', 'platform_frame', 'user_frame', 'tool_frame']),
       st.sampled_from(['', '/slash', 'with space', 'stewart_base', None, 3]))
def test_bad_frame_names_are_refused_naming_them(name, value):
    values = defaults(FRAME_PARAMETERS)
    values[name] = value
    valid = value is None or isinstance(value, str) and value not in ('/slash', 'with space') and (
        value != '' or name in ('user_frame', 'tool_frame')) and (
        value == '' or value not in {defaults(FRAME_PARAMETERS)[other] for other in (
            'base_frame', 'platform_frame') if other != name})
    try:
        tree = frames_from_parameters(values)
    except ValueError as error:
        assert not valid, error
        assert name in str(error) or 'frame' in str(error), error
    else:   # an empty user or tool frame name means none
        assert valid, (name, value)
        assert tree.base_frame and tree.platform_frame


@covers('ActuatorInterface')
@budget(40)
@given(st.permutations(range(6)), st.tuples(*[floats(-1.0, 1.0)] * 6),
       st.tuples(*[floats(0.3, 1.2)] * 6))
def test_actuator_positions_and_lengths_round_trip_in_any_joint_order(order, offsets, lengths):
    actuators = ActuatorInterface(offsets=np.array(offsets))
    lengths = np.array(lengths)
    positions = actuators.positions(lengths)
    assert_allclose(actuators.lengths(positions), lengths, rtol=0, atol=1e-15)
    names = [actuators.joint_names[k] for k in order] + ['gripper']
    assert_array_equal(np.array(names)[actuators.order(names)], actuators.joint_names)


@covers('ActuatorInterface', 'ActuatorLimits')
@budget(40)
@given(st.one_of(NOT_NUMBERS, NON_FINITE, st.sampled_from([0.0, -1.0, [1.0, 2.0]])),
       st.sampled_from(['velocity_max', 'acceleration_max', 'jerk_max']))
def test_bad_actuator_settings_are_refused_naming_them(value, name):
    if value != math.inf:   # inf: no limit
        assert_refused(lambda: ActuatorLimits(**{name: value}), (name, 'leg_' + name))
    limits = ActuatorLimits(0.05, 0.25, 2.5)
    assert_refused(lambda: limits.scaled(value), ('speed_scale',))
    assert_refused(lambda: ActuatorInterface(offsets=value), ('offsets',))
    assert_refused(lambda: ActuatorInterface(joint_names=('a', 'a', 'b', 'c', 'd', 'e')),
                   ('joint_names',))
    assert_refused(lambda: ActuatorInterface().order(['leg_1', 'leg_2']), ('leg_3',))


def flushed(joints):
    """Return the joints as a parameter file holds them: subnormal numbers written as 0.0."""
    return np.where(np.abs(joints) < sys.float_info.min, 0.0, joints)


@covers('geometry_from_parameters', 'load_geometry')
@budget(25)
@given(st.tuples(*[floats(-0.01, 0.01)] * 36), st.sampled_from([0.85, 0.9, math.inf]))
def test_parameters_and_files_build_the_geometry_they_describe(tmp_path_factory, offsets,
                                                               leg_length_max):
    offsets = np.array(offsets).reshape(2, 6, 3)
    values = geometry_values(base_joints=(BASE_JOINTS + offsets[0]).ravel().tolist(),
                             platform_joints=(PLATFORM_JOINTS + offsets[1]).ravel().tolist(),
                             leg_length_max=leg_length_max)
    geometry = geometry_from_parameters(values)
    assert_allclose(geometry.base_joints, BASE_JOINTS + offsets[0], rtol=0, atol=0)
    assert geometry.leg_length_max == leg_length_max
    path = tmp_path_factory.mktemp('files') / 'platform.yaml'
    from stewart_kinematics.analysis.calibration_files import write_parameter_file
    write_parameter_file(path, values)
    loaded = load_geometry(path)
    # rcl reads a subnormal number as a string (strtod's ERANGE): the file holds 0.0 instead.
    assert_array_equal(loaded.base_joints, flushed(geometry.base_joints))
    assert_array_equal(loaded.platform_joints, flushed(geometry.platform_joints))
    assert loaded.leg_length_max == leg_length_max


@covers('geometry_from_parameters', 'load_geometry')
@budget(40)
@given(st.sampled_from(['base_joints', 'platform_joints', 'home_position',
                        'home_orientation_deg', 'leg_length_min', 'leg_length_max',
                        'base_joint_max_angle_deg', 'max_jacobian_condition']),
       st.one_of(NOT_NUMBERS, NON_FINITE, st.sampled_from([-1.0, 0.0, 1, [0.0], 400.0])))
def test_bad_parameter_values_are_refused_naming_the_parameter(tmp_path_factory, name, value):
    values = geometry_values(**{name: value})
    try:
        geometry = geometry_from_parameters(values)
    except ValueError as error:
        assert name in str(error) or 'home pose' in str(error), error
    else:   # a value that happens to be allowed: the geometry holds it
        assert geometry is not None
    path = tmp_path_factory.mktemp('bad') / 'platform.yaml'
    path.write_text('/**:\n  ros__parameters:\n    leg_length_max: "0.9"\n', encoding='utf-8')
    platform = ROOT / 'config' / 'paper_platform.yaml'
    for files in ([platform, path], [path, platform]):
        assert_refused(lambda: load_geometry(files), ('leg_length_max',))
    assert_refused(lambda: load_geometry(path.parent / 'absent.yaml'), ('absent.yaml',))
    assert PAPER.limits is None


@covers('load_settings')
@budget(20)
@given(floats(0.8, 1.2), floats(0.3, 0.6), st.sampled_from(['fk_node', None]))
def test_settings_load_as_the_files_say_or_are_refused(tmp_path_factory, leg_length_max,
                                                       leg_length_min, node_name):
    from stewart_kinematics.parameters import FkNodeSettings, GeometrySettings
    folder = tmp_path_factory.mktemp('settings')
    platform = ROOT / 'config' / 'paper_platform.yaml'
    limits = folder / 'limits.yaml'
    limits.write_text(f'/**:\n  ros__parameters:\n    leg_length_max: {leg_length_max!r}\n'
                      f'    leg_length_min: {leg_length_min!r}\n'
                      'fk_node:\n  ros__parameters:\n    tolerance: 1e-10\n', encoding='utf-8')
    settings = load_settings(GeometrySettings, [platform, limits], node_name)
    assert settings.leg_length_max == leg_length_max
    assert settings.leg_length_min == leg_length_min
    fk = load_settings(FkNodeSettings, [platform, limits], node_name)
    assert fk.solver.tolerance == (1e-10 if node_name else 1e-12)
    quoted = folder / 'quoted.yaml'
    quoted.write_text('/**:\n  ros__parameters:\n    leg_length_max: "0.9"\n', encoding='utf-8')
    for files in ([platform, quoted], [quoted, platform]):
        assert_refused(lambda: load_settings(GeometrySettings, files), ('leg_length_max',))
    typo = folder / 'typo.yaml'
    typo.write_text('/**:\n  ros__parameters:\n    leg_lenght_max: 0.9\n', encoding='utf-8')
    assert_refused(lambda: load_settings(GeometrySettings, [platform, typo]),
                   ("did you mean 'leg_length_max'",))
