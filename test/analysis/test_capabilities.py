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
The geometry report (stewart_kinematics.analysis.capabilities), in the core.

Its figures are checked against the drawings and formulas of test/reference.py (leg lengths,
the angle between two legs at a shared joint, the clearance between legs) and against the
analysis functions it gathers; each warning is provoked by the parameter change a user would
make by mistake.
"""

import json
import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics import findings, load_geometry, travel_ranges, workspace_volume
from stewart_kinematics.analysis.capabilities import (
    DEFAULT_VOLUME_RESOLUTION,
    geometry_report,
    parameters_report,
)
from stewart_kinematics.limits import LEG_PAIRS
from stewart_kinematics.parameters import read_parameter_files

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = {'6-6': ['paper_platform.yaml', 'example_limits.yaml'], '6-3': ['platform_6_3.yaml'],
         '3-3': ['platform_3_3.yaml']}


def values_of(design, **changes):
    """Return the parameter values of a design's files, with changes."""
    values = read_parameter_files([CONFIG / name for name in FILES[design]])
    values.update(changes)
    return values


def codes(report):
    """Return the codes of a report's warnings."""
    return [warning.code for warning in report.warnings]


@pytest.fixture(scope='module', params=sorted(FILES))
def design(request):
    """Return ``(name, geometry, report)`` of each example design."""
    geometry = load_geometry([CONFIG / name for name in FILES[request.param]])
    return request.param, geometry, geometry_report(geometry)


def test_report_of_each_design_matches_its_parts(design):
    name, geometry, report = design
    assert report.usable and report.home_refusal == '' and report.warnings == ()
    assert report.design == name and report.shared_joints == geometry.shared_joints
    assert_allclose(report.home_leg_lengths, reference.leg_lengths(
        geometry.home_pose, geometry.base_joints, geometry.platform_joints), rtol=0, atol=1e-12)
    assert report.home_condition == pytest.approx(
        {'6-6': 9.5376, '6-3': 6.5143, '3-3': 5.0883}[name], abs=1e-4)
    ranges = travel_ranges(geometry)
    assert_allclose(report.travel.as_array(), ranges.as_array(), atol=0.0)
    volume = workspace_volume(geometry, resolution=DEFAULT_VOLUME_RESOLUTION)
    assert report.volume.volume == volume.volume > 0.0 and report.volume.bounded
    assert report.modes.complete and report.modes_within_limits == 1
    assert report.nearest_mode is None and report.nearest_mode_distance == math.inf
    assert len(report.modes) + report.modes.complex_solutions == (
        38 if name == '6-6' else 16)


def test_margins_at_home_are_the_distances_to_each_limit(design):
    """Stroke, cones, condition and clearance at home, from the textbook formulas."""
    name, geometry, report = design
    margins = {margin.limit: margin for margin in report.margins}
    assert list(margins) == ['leg_length_min', 'leg_length_max', 'base_joint_max_angle',
                             'platform_joint_max_angle', 'max_jacobian_condition',
                             'leg_collision']
    lengths = np.array(reference.leg_lengths(geometry.home_pose, geometry.base_joints,
                                             geometry.platform_joints))
    assert margins['leg_length_min'].margin == pytest.approx(
        lengths.min() - geometry.leg_length_min, abs=1e-12)
    assert margins['leg_length_max'].margin == pytest.approx(
        geometry.leg_length_max - lengths.max(), abs=1e-12)
    assert margins['base_joint_max_angle'].margin == geometry.base_joint_max_angle
    assert margins['max_jacobian_condition'].margin == pytest.approx(
        geometry.max_jacobian_condition - report.home_condition, abs=1e-12)
    # The clearance: the nearest two legs that share no joint, by the reference distance.
    rotation = reference.rotation_zyx(*geometry.home_pose[3:])
    tops = geometry.home_pose[:3] + geometry.platform_joints @ rotation.T
    shared = {joint.legs for joint in geometry.shared_joints}
    clearances = {(i, j): reference.segment_distance(
        geometry.base_joints[i - 1], tops[i - 1], geometry.base_joints[j - 1], tops[j - 1])
        for i, j in LEG_PAIRS if (i, j) not in shared}
    nearest = min(clearances, key=clearances.get)
    collision = margins['leg_collision']
    assert collision.value == pytest.approx(clearances[nearest], abs=1e-12)
    assert collision.margin == pytest.approx(clearances[nearest] - 2 * geometry.leg_radius,
                                             abs=1e-12)
    assert collision.subject == f'legs {nearest[0]} and {nearest[1]}'
    assert not any(margin.broken for margin in report.margins)


@pytest.mark.parametrize('name', ['6-3', '3-3'])
def test_the_angle_between_two_legs_at_a_shared_joint(name):
    """The angle at home between the legs of each shared joint, from the drawing."""
    report = geometry_report(load_geometry(CONFIG / FILES[name][0]))
    base, platform = reference.design_joints(name)
    home = np.array(reference.DESIGN_HOME)
    legs = home[:3] + platform - base
    for joint, angle in zip(report.shared_joints, report.shared_joint_angles):
        first, second = (legs[leg - 1] for leg in joint.legs)
        expected = math.acos(first @ second / np.linalg.norm(first) / np.linalg.norm(second))
        assert angle == pytest.approx(expected, abs=1e-6)
    text = report.text()
    assert f'Design: {name} (' in text and 'the two legs meet at' in text


def test_a_home_pose_beyond_the_stroke_is_reported_not_raised():
    report = parameters_report(values_of('6-3', leg_length_max=0.70))
    assert not report.usable and 'leg_length_max' in report.home_refusal
    assert codes(report) == [findings.LIMIT_BROKEN_AT_HOME]
    margin = next(margin for margin in report.margins if margin.limit == 'leg_length_max')
    assert margin.broken and margin.margin == pytest.approx(0.70 - 0.7164906, abs=1e-7)
    assert report.travel is None and report.volume is None
    # What does not need the limits is still there.
    assert report.design == '6-3' and len(report.modes) == 16
    assert report.modes_within_limits is None
    text = report.text()
    assert 'BROKEN' in text and 'Refused by the nodes:' in text
    assert '[limit_broken_at_home] the home pose breaks leg_length_max 700 mm' in text


def test_legs_that_collide_at_home_are_named():
    """Legs 1 and 2 (no shared joint) 135 mm apart: 70 mm legs collide, pairs that share don't."""
    report = parameters_report(values_of('6-3', leg_radius=0.07))
    assert codes(report) == [findings.LEGS_COLLIDE_AT_HOME] and not report.usable
    message = report.warnings[0].message
    assert 'legs 1 and 2 (135.3 mm)' in message and 'legs 1 and 6' not in message


def test_a_near_singular_home_is_warned():
    """The 3-3 turned 88 degrees from its drawn home: near its quarter-turn singularity."""
    report = parameters_report(values_of('3-3', home_orientation_deg=[0.0, 0.0, 88.0],
                                         max_jacobian_condition=math.inf))
    # Near the singularity two assembly modes come together: another one 11 mm away.
    assert report.usable and codes(report) == [findings.NEAR_SINGULAR_HOME,
                                               findings.OTHER_MODE_WITHIN_LIMITS]
    assert report.home_condition > 100.0 and report.nearest_mode_distance < 0.02
    # With the singularity margin set, it is a limit broken instead.
    report = parameters_report(values_of('3-3', home_orientation_deg=[0.0, 0.0, 88.0]))
    assert codes(report) == [findings.LIMIT_BROKEN_AT_HOME]
    assert 'max_jacobian_condition 50' in report.warnings[0].message


def test_joints_nearly_shared_are_warned():
    """
    Warn of p_3 1 mm from p_2: two joints (a 6-4 platform) whose legs cross at home.

    Without a collision check, a platform turned half a turn keeps the limits too.
    """
    platform = values_of('6-3')['platform_joints']
    platform[7] += 0.001
    report = parameters_report(values_of('6-3', platform_joints=platform, leg_radius=0.0))
    assert report.usable and report.design == '6-4'
    assert codes(report) == [findings.LEGS_COLLIDE_AT_HOME, findings.JOINTS_NEARLY_SHARED,
                             findings.OTHER_MODE_WITHIN_LIMITS]
    assert 'axes of legs 2 and 3' in report.warnings[0].message
    assert 'the platform joints of legs 2 and 3 are 1 mm apart' in report.warnings[1].message
    assert [(near.side, near.legs) for near in report.nearly_shared] == [('platform', (2, 3))]


def test_another_mode_within_the_limits_is_warned():
    """The paper's platform without limits: all 10 real modes are allowed."""
    report = parameters_report(values_of('6-6', leg_length_min=0.0, leg_length_max=math.inf,
                                         base_joint_max_angle_deg=180.0,
                                         platform_joint_max_angle_deg=180.0,
                                         max_jacobian_condition=math.inf, leg_radius=0.0))
    assert report.margins == () and report.modes_within_limits == 10
    assert codes(report) == [findings.OTHER_MODE_WITHIN_LIMITS]
    assert report.nearest_mode_distance == pytest.approx(report.nearest_mode.distance)


def test_joints_that_make_no_platform_raise_one_line():
    base = values_of('3-3')['base_joints']
    base[6:9] = base[0:3]          # b_3 onto b_1 and b_2: three legs on one point
    with pytest.raises(ValueError, match=r'^base_joints: joints 1, 2 and 3 coincide') as raised:
        parameters_report(values_of('3-3', base_joints=base))
    assert '\n' not in str(raised.value)


def test_the_report_as_json_is_strict_json(design):
    name, geometry, report = design
    numbers = json.loads(json.dumps(report.as_dict(), allow_nan=False))
    assert numbers['design'] == name and numbers['usable'] is True
    assert numbers['assembly_modes']['within_limits'] == 1
    assert numbers['assembly_modes']['nearest_other_distance_m'] == 'inf'
    assert numbers['workspace_volume']['volume_m3'] == report.volume.volume
    assert len(numbers['shared_joints']) == len(geometry.shared_joints)


@pytest.mark.parametrize('bad', [0.0, -0.02, math.nan, math.inf, 1.0, True, '0.02', None])
def test_a_bad_volume_resolution_is_refused_naming_it(bad):
    geometry = load_geometry(CONFIG / 'platform_6_3.yaml')
    with pytest.raises(ValueError, match='volume_resolution must be a number in'):
        geometry_report(geometry, volume_resolution=bad)


def test_only_a_geometry_is_reported():
    with pytest.raises(ValueError, match='geometry must be a Geometry, got dict'):
        geometry_report({'base_joints': []})
