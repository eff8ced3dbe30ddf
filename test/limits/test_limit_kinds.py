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
One home per limit kind: a kind added to LIMIT_KINDS is checked and listed everywhere.

A toy kind, a ceiling on the platform's height (``platform_height_max``), is declared here as a
kind's module would declare it and appended to the list, with no other edit: the limit
settings, the limits model (one pose, a batch, the home pose of a geometry, the workspace),
the parameter specs, the bounds the markers and figures draw, the cue's margins, calibration's
write-out and the safety page's table all pick it up.
"""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from stewart_kinematics import load_geometry, travel_ranges
from stewart_kinematics.cueing.limit_margins import limit_margins, with_margins
from stewart_kinematics.limits import (
    Bound,
    BoundLook,
    kinds,
    LimitKind,
    LimitModel,
    LimitParameter,
    PoseLimits,
)
from stewart_kinematics.limits.base import Limit, PLATFORM
from stewart_kinematics.model.validators import InRange
from stewart_kinematics.parameters.declarations import limit_specs

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: The paper's platform, loaded before the toy kind is listed (its settings class has no field
#: for it until the settings are regenerated).
PAPER = load_geometry(CONFIG / 'paper_platform.yaml')
HOME_Z = float(PAPER.home_pose[2])
CEILING = HOME_Z + 0.02


class PlatformHeight(Limit):
    """Toy evaluator: the height of the platform frame's origin, one value per pose."""

    def __init__(self, geometry, allowed):
        self._base_z = float(geometry.base_joints[0, 2])
        self.bounds = ((Bound('platform_height_max', allowed, True, PLATFORM, 'm'),)
                       if allowed < math.inf else ())

    def values(self, legs):
        """Return z of ``t = L_1 + b_1 - R p_1``, shape (1, n)."""
        lz, az = legs.vectors[2], legs.vectors[5]
        return (lz[:1] + self._base_z - az[:1],)


TOY = LimitKind(
    name='platform_height',
    title='Platform height',
    meaning='The height of the platform frame above the base frame.',
    evaluator='PlatformHeight',
    parameters=(LimitParameter(
        'platform_height_max', 'm', math.inf,
        'Highest position of the platform frame, metres; .inf for no limit',
        (InRange(0.0, math.inf, low_inclusive=False),)),),
    bounds=(BoundLook('platform_height_max', 'platform height', (0.1, 0.2, 0.3)),),
    pose_evaluator=lambda geometry, limits: PlatformHeight(geometry,
                                                           limits.platform_height_max),
)


@pytest.fixture
def toy(monkeypatch):
    """Append the toy kind to the list of kinds: the one line a new kind adds."""
    monkeypatch.setattr(kinds, 'LIMIT_KINDS', kinds.LIMIT_KINDS + [TOY])
    return TOY


def with_ceiling(ceiling=CEILING, **others):
    """Return the paper's platform with the toy ceiling and other limits (SI units)."""
    return dataclasses.replace(PAPER, limits=PoseLimits(platform_height_max=ceiling, **others))


def pose_at(z):
    """Return the home pose with the platform at height ``z``, metres."""
    pose = PAPER.home_pose.copy()
    pose[2] = z
    return pose


def test_every_kind_declares_a_default_that_its_bounds_allow_and_that_sets_no_limit():
    """Each parameter's default passes its own validators and leaves its kind with no bound."""
    for kind in kinds.LIMIT_KINDS:
        for parameter in kind.parameters:
            assert parameter.setting_reason(parameter.setting_default) == '', parameter.name
    assert LimitModel(PAPER, limits=PoseLimits()).pose_limits == ()
    assert {parameter.name for parameter in kinds.limit_parameters()} == {
        'leg_length_min', 'leg_length_max', 'base_joint_max_angle_deg',
        'platform_joint_max_angle_deg', 'max_jacobian_condition', 'leg_radius',
        'leg_velocity_max', 'leg_acceleration_max', 'leg_jerk_max', 'leg_force_min',
        'leg_force_max'}


def test_without_the_line_in_the_list_the_kind_is_unknown():
    """The toy kind is nowhere until listed: the settings refuse its name."""
    assert 'platform_height_max' not in kinds.pose_limit_names()
    with pytest.raises(ValueError, match="'platform_height_max' is not a pose limit"):
        PoseLimits(platform_height_max=1.0)


def test_the_settings_take_its_parameter_with_its_bounds(toy):
    assert PoseLimits().platform_height_max == math.inf     # its default: no limit
    assert not PoseLimits().is_set('platform_height_max')
    assert PoseLimits(platform_height_max=0.5).platform_height_max == 0.5
    for bad in (0.0, -1.0, -math.inf, math.nan, 'high', [0.5], None, [[1.0]]):
        with pytest.raises(ValueError, match='platform_height_max'):
            PoseLimits(platform_height_max=bad)
    # Calibration writes the limits back as parameters: the toy's with them.
    assert PoseLimits(platform_height_max=0.5).parameters()['platform_height_max'] == 0.5


def test_the_limits_model_checks_it_on_one_pose_and_on_a_batch(toy):
    geometry = with_ceiling()
    model = LimitModel(geometry)
    assert model.pose_limit_names == ('platform_height_max',)
    assert model.check_pose(geometry.home_pose[:3], np.eye(3)) == []
    (violation,) = model.check_pose(pose_at(CEILING + 0.01)[:3], np.eye(3))
    assert violation.limit == 'platform_height_max'
    assert violation.value == pytest.approx(CEILING + 0.01, abs=1e-12)
    assert violation.allowed == CEILING
    heights = np.linspace(HOME_Z - 0.05, HOME_Z + 0.05, 41)
    checks = model.check_poses(np.array([pose_at(z) for z in heights]))
    np.testing.assert_array_equal(checks.allowed, heights <= CEILING)


def test_a_geometry_whose_home_breaks_it_is_refused(toy):
    with pytest.raises(ValueError, match='home pose breaks the limits.*platform_height_max'):
        with_ceiling(HOME_Z - 0.01)


def test_the_workspace_reports_it_as_the_limit_met(toy):
    geometry = with_ceiling(leg_length_max=1.0)
    (z_axis,) = [axis for axis in travel_ranges(geometry).axes if axis.axis == 'Z']
    assert z_axis.positive_limit == 'platform_height_max'
    assert z_axis.positive == pytest.approx(CEILING - HOME_Z, abs=1e-5)


def test_everything_that_lists_limits_lists_it(toy):
    assert kinds.pose_limit_names()[-1] == 'platform_height_max'
    # The markers and the workspace figures draw each bound with its kind's label and colour.
    assert kinds.pose_bounds()[-1] == TOY.bounds[0]
    (spec,) = [spec for spec in limit_specs() if spec.name == 'platform_height_max']
    assert spec.default == math.inf and spec.description == TOY.parameters[0].description
    assert spec.check(-1.0) and not spec.check(2.0)
    table = kinds.limits_table()
    assert ('| Platform height | `PlatformHeight` (`platform_height`) | '
            '`platform_height_max` (m) |') in table


def test_the_cue_margins_keep_a_kind_that_declares_none(toy):
    geometry = with_ceiling(leg_length_max=0.9)
    narrowed = with_margins(geometry, 0.01, math.radians(2.0), 0.9)
    assert narrowed.limits.platform_height_max == CEILING
    assert narrowed.limits.leg_length_max == pytest.approx(0.89, abs=1e-15)
    margins = limit_margins(geometry, np.array([pose_at(CEILING + 0.005), PAPER.home_pose]))
    assert margins[0] == pytest.approx(0.005, abs=1e-9) and margins[1] < 0.0
