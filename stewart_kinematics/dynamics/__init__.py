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
Dynamics: what the actuators must push to hold or move the platform, its payload and the legs.

The masses and gravity (:mod:`.mass_properties`: :class:`RigidBody` for the platform and the
payload, :class:`LegBody` for the two bodies of each leg, :class:`MassProperties` for all of
them), the terms of the equations of motion, for one pose in floats and a batch in arrays
(:mod:`.wrenches`), and the inverse dynamics (:mod:`.inverse_dynamics`: :func:`leg_forces`,
:func:`platform_wrench`), the wrench on the platform that measured leg forces reveal
(:mod:`.external_wrench`: :func:`external_wrench`), and actuator sizing along a timed motion
(:mod:`.sizing`: :func:`actuator_demands`, :func:`trajectory_demands`: per leg peak push,
pull, RMS force, speed and power). The model and its conventions: doc/dynamics.md.

May import: ``model/``, numpy and the standard library. Nothing here imports ROS.
"""

from stewart_kinematics.dynamics.external_wrench import external_wrench
from stewart_kinematics.dynamics.inverse_dynamics import leg_forces, platform_wrench
from stewart_kinematics.dynamics.mass_properties import LegBody, MassProperties, RigidBody
from stewart_kinematics.dynamics.sizing import (
    actuator_demands,
    ActuatorDemands,
    LegDemand,
    trajectory_demands,
)

__all__ = ['actuator_demands', 'ActuatorDemands', 'external_wrench', 'leg_forces', 'LegBody',
           'LegDemand', 'MassProperties', 'platform_wrench', 'RigidBody',
           'trajectory_demands']
