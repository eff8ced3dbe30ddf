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
The allowed values of each limit of the platform, declared once.

The limits' parameter specs (:data:`stewart_kinematics.parameters.GEOMETRY_PARAMETERS`) take
these validators, and :class:`~stewart_kinematics.model.geometry.Geometry` and
:class:`~stewart_kinematics.model.actuators.ActuatorLimits` check their values with the same
objects, so a parameter file and a Python caller meet one rule, and the documentation prints it.
They live here, in model/, because model/ may import only model/.

Angles are declared in degrees, as the parameters give them; the geometry checks its radians
with the same rule converted (:meth:`~stewart_kinematics.model.validators.Validator.converted`).
"""

import math

from stewart_kinematics.model.validators import Finite, InRange

#: Shortest leg length, metres: 0 for no limit (and below leg_length_max: the geometry checks).
LEG_LENGTH_MIN = (Finite(), InRange(0.0, math.inf))
#: Longest leg length, metres: ``inf`` for no limit (and above leg_length_min).
LEG_LENGTH_MAX = (InRange(0.0, math.inf, low_inclusive=False),)
#: Largest angle of a leg from its home direction at a joint (joint cone), degrees.
JOINT_MAX_ANGLE_DEG = (Finite(), InRange(0.0, 180.0, low_inclusive=False))
#: Largest condition number of the dimensionless Jacobian: ``inf`` for no limit.
MAX_JACOBIAN_CONDITION = (InRange(1.0, math.inf),)
#: Radius of a leg's capsule, metres: 0 for no collision check; a metre is beyond any leg.
LEG_RADIUS = (Finite(), InRange(0.0, 1.0))
#: Largest leg velocity, acceleration or jerk (m/s, m/s^2, m/s^3): ``inf`` for no limit.
LEG_RATE_MAX = (InRange(0.0, math.inf, low_inclusive=False),)
