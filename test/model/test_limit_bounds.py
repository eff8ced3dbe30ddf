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
One rule per limit: Geometry and ActuatorLimits accept exactly the values their parameters do.

Each limit's value is probed at and beyond its bounds (and with NaN and infinities) twice: as
the parameter (its spec's check, in the parameter's units) and as the argument of the core
object (in SI units). Both must refuse the same values, with the same sentence.
"""

import math

import numpy as np
import pytest
import reference

from stewart_kinematics.limits import PoseLimits
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.parameters import GEOMETRY_PARAMETERS

pytestmark = pytest.mark.core

SPECS = {spec.name: spec for spec in GEOMETRY_PARAMETERS}
#: The paper's platform 100 times as large: 70 m legs, 5 m apart at their closest at home, so
#: that a leg radius of up to a metre does not make the legs collide there.
SCALE = 100.0
#: Values at and around every bound of the limits, in the parameters' units.
PROBES = (-math.inf, -1.0, -1e-12, 0.0, 1e-12, 0.5, 0.999, 1.0, 1.001, 45.0, 179.999, 180.0,
          180.001, 1e6, 1e308, math.inf, math.nan)

#: Geometry's argument, its parameter, and the conversion from the parameter's units.
GEOMETRY_LIMITS = [
    ('leg_length_min', 'leg_length_min', float),
    ('leg_length_max', 'leg_length_max', float),
    ('base_joint_max_angle', 'base_joint_max_angle_deg', math.radians),
    ('platform_joint_max_angle', 'platform_joint_max_angle_deg', math.radians),
    ('max_jacobian_condition', 'max_jacobian_condition', float),
    ('leg_radius', 'leg_radius', float),
]


def large_geometry(**limits):
    """Build the paper's platform scaled by SCALE, with the given limits."""
    return Geometry(reference.BASE_JOINTS * SCALE, reference.PLATFORM_JOINTS * SCALE,
                    np.concatenate([np.asarray(reference.HOME[:3]) * SCALE, reference.HOME[3:]]),
                    limits=PoseLimits(**limits))


def rule_refusal(build, argument, value):
    """Return the message of a refusal by ``argument``'s own rule, else None (built, or other)."""
    try:
        build(**{argument: value})
    except ValueError as error:
        if str(error).startswith(f'{argument} must'):
            return str(error)
    return None


@pytest.mark.parametrize('argument, parameter, convert', GEOMETRY_LIMITS,
                         ids=[row[0] for row in GEOMETRY_LIMITS])
def test_the_geometry_refuses_exactly_what_the_parameter_refuses(argument, parameter, convert):
    spec = SPECS[parameter]
    for value in PROBES:
        reason = spec.check(value)
        refusal = rule_refusal(large_geometry, argument, convert(value))
        assert bool(reason) == (refusal is not None), (argument, value, reason, refusal)
        if reason and convert is float:
            assert refusal == reason.replace(f"parameter '{parameter}'", argument)


@pytest.mark.parametrize('argument', ['velocity_max', 'acceleration_max', 'jerk_max'])
def test_the_actuator_limits_refuse_exactly_what_the_parameter_refuses(argument):
    spec = SPECS[f'leg_{argument}']
    for value in PROBES:
        reason = spec.check(value)
        refusal = None
        try:
            ActuatorLimits(**{argument: value})
        except ValueError as error:
            refusal = str(error)
        assert bool(reason) == (refusal is not None), (argument, value, reason, refusal)
        if reason:
            assert refusal.startswith(reason.replace(f"parameter '{spec.name}'", spec.name))


def test_a_leg_radius_beyond_its_parameter_range_is_refused_by_the_geometry_too():
    """The parameter allows [0, 1] m; the geometry accepted any radius (1.5 m: built)."""
    assert large_geometry(leg_radius=1.0).leg_radius == 1.0
    with pytest.raises(ValueError, match=r'^leg_radius must be in \[0, 1\], got 1.5$'):
        large_geometry(leg_radius=1.5)


def test_angles_are_checked_in_radians_with_the_bounds_of_the_degrees():
    """(0, 180] degrees is (0, pi] radians: pi itself allowed, 0 and a hair above pi not."""
    assert large_geometry(base_joint_max_angle=math.pi).base_joint_max_angle == math.pi
    with pytest.raises(ValueError, match=r'^platform_joint_max_angle must be in \(0, 3.14159\]'):
        large_geometry(platform_joint_max_angle=math.nextafter(math.pi, 4.0))
    with pytest.raises(ValueError, match='base_joint_max_angle must be in'):
        large_geometry(base_joint_max_angle=0.0)
