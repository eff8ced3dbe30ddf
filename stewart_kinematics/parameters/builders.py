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
The core objects that parameter settings describe: the geometry, frames and actuators.

Each builder takes the typed settings of :mod:`stewart_kinematics.parameters.settings` (a node
has them as ``settings.geometry``, ``settings.frames``, ...). The ``*_from_parameters``
functions take a mapping of parameter values instead, as a parameter file gives them. Nothing
here imports ROS.
"""

import dataclasses
from typing import Any, Mapping

import numpy as np

from stewart_kinematics.dynamics.mass_properties import LegBody, MassProperties, RigidBody
from stewart_kinematics.limits.kinds import actuator_settings, pose_settings
from stewart_kinematics.limits.settings import PoseLimits
from stewart_kinematics.model.actuators import ActuatorInterface, ActuatorLimits
from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.frames import FrameTree, Transform
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.parameters.settings import (
    ActuatorSettings,
    FrameSettings,
    GeometrySettings,
)


def geometry_from_settings(settings: GeometrySettings) -> Geometry:
    """
    Build the geometry that parameter settings describe.

    :param settings: joints (flat lists, metres), home pose (metres, degrees) and limits (the
        parameters of every pose limit kind, as their kinds declare them).
    :raises ValueError: if the geometry is not allowed (a joint shared by three legs or more,
        two legs sharing both joints, collinear joints, a home pose that breaks its own limits).
    """
    home_pose = np.concatenate([np.asarray(settings.home_position, dtype=float),
                                np.radians(np.asarray(settings.home_orientation_deg))])
    return Geometry(
        base_joints=np.reshape(np.asarray(settings.base_joints, dtype=float), (6, 3)),
        platform_joints=np.reshape(np.asarray(settings.platform_joints, dtype=float), (6, 3)),
        home_pose=home_pose,
        limits=pose_limits_from_settings(settings),
        mass_properties=mass_properties_from_settings(settings))


def pose_limits_from_settings(settings: GeometrySettings) -> PoseLimits:
    """Return the pose limits of the geometry settings: every pose limit kind's parameters."""
    return PoseLimits.from_parameters({parameter.name: getattr(settings, parameter.name)
                                       for parameter in pose_settings().values()})


def actuator_limits_from_settings(settings: GeometrySettings) -> ActuatorLimits:
    """Return the legs' speed limits (``leg_velocity_max``, ...) of the geometry settings."""
    return ActuatorLimits(**{name: parameter.setting_value(getattr(settings, parameter.name))
                             for name, parameter in actuator_settings().items()})


def mass_properties_from_settings(settings: GeometrySettings) -> MassProperties:
    """
    Return the masses and gravity of the geometry settings (kg, metres, kg m^2, m/s^2).

    The platform's and the payload's centres of mass and inertias are in the platform frame;
    each leg body's centre is a distance from its own joint along the leg axis.

    :raises ValueError: naming the parameter, for a body given an inertia without a mass (each
        value alone is checked by its parameter's rules).
    """
    bodies = {}
    for body in ('platform', 'payload'):
        bodies[body] = _body(RigidBody, body, settings, f'{body}_')
    for body in ('lower', 'upper'):
        bodies[f'leg_{body}'] = _body(LegBody, f'leg_{body}', settings, f'leg_{body}_')
    return MassProperties(gravity=list(settings.gravity), **bodies)


def mass_properties_from_parameters(values: Mapping[str, Any]) -> MassProperties:
    """
    Return the masses and gravity of ROS parameter values, as a parameter file gives them.

    :param values: parameter name -> value (``payload_mass``, ``gravity``, ...; the
        :data:`~stewart_kinematics.parameters.MASS_SPECS`); a missing one takes its
        default (every mass 0), and the geometry's own are needed as for
        :func:`geometry_from_parameters`.
    :raises ValueError: naming the parameter, if a value is missing or not allowed.
    """
    return mass_properties_from_settings(GeometrySettings.from_values(values))


#: The payload's parameters: the masses that may change at run time (payloads change).
PAYLOAD_PARAMETERS = ('payload_mass', 'payload_center_of_mass', 'payload_inertia')


def geometry_with_payload(geometry: Geometry, values: Mapping[str, Any]) -> Geometry:
    """
    Return a geometry carrying the payload of parameter values, its other masses unchanged.

    A run-time change of the payload (``ros2 param set``) goes through here: the new payload
    is checked whole, then with the geometry's limits at its home pose (a payload too heavy
    for ``leg_force_max`` at home is refused).

    :param geometry: the geometry the node uses now (its platform, legs and gravity are kept).
    :param values: parameter name -> value; the :data:`PAYLOAD_PARAMETERS` are read (kg,
        metres in the platform frame, kg m^2 about the centre of mass, platform axes), each
        one's own rules already checked.
    :raises ValueError: naming the payload parameters, for an inertia without a mass or a
        home pose whose leg forces break the limits with the new payload.
    """
    try:
        payload = RigidBody(values['payload_mass'], list(values['payload_center_of_mass']),
                            list(values['payload_inertia']), name='payload')
    except ValueError as error:
        raise ValueError(f"parameters 'payload_mass' and 'payload_inertia': {error}") from None
    masses = geometry.mass_properties or MassProperties()
    try:
        return geometry.with_mass_properties(dataclasses.replace(masses, payload=payload))
    except ValueError as error:
        given = ', '.join(f'{name} {preview(_plain(values[name]))}'
                          for name in PAYLOAD_PARAMETERS)
        raise ValueError(f'payload refused ({given}): {error}') from None


def _plain(value):
    """Return a parameter's value as a number or a list (rclpy gives ``array.array``)."""
    return value if isinstance(value, (int, float, str)) else list(value)


def _body(kind, name, settings, prefix):
    """Build one body of the mass properties, refusing a bad one naming its parameters."""
    mass, center, inertia = (getattr(settings, prefix + field)
                             for field in ('mass', 'center_of_mass', 'inertia'))
    if isinstance(center, (list, tuple)):
        center, inertia = list(center), list(inertia)
    try:
        return kind(mass, center, inertia, name=name)
    except ValueError as error:
        raise ValueError(f"parameters '{prefix}mass' and '{prefix}inertia': {error}") from None


def actuator_interface_from_settings(settings: ActuatorSettings) -> ActuatorInterface:
    """Return the actuators' joint names and zeros."""
    return ActuatorInterface(joint_names=settings.joint_names, offsets=settings.actuator_offsets)


def frames_from_settings(settings: FrameSettings) -> FrameTree:
    """
    Build the frame tree that frame settings describe (positions in metres, angles in degrees).

    :raises ValueError: for frame names that repeat.
    """
    return FrameTree(
        base_frame=settings.base_frame, platform_frame=settings.platform_frame,
        user_frame=settings.user_frame,
        user_pose=_frame_pose(settings.user_frame_position, settings.user_frame_orientation_deg),
        tool_frame=settings.tool_frame,
        tool_pose=_frame_pose(settings.tool_frame_position, settings.tool_frame_orientation_deg))


def geometry_from_parameters(values: Mapping[str, Any]) -> Geometry:
    """
    Build a geometry from ROS parameter values, as a parameter file gives them.

    :param values: parameter name -> value, with the names and units of
        :data:`~stewart_kinematics.parameters.GEOMETRY_PARAMETERS` (flat joint lists in
        metres, home orientation in degrees); others are ignored, and a missing optional one
        takes its default. A pivot point is the tool frame's origin
        (:func:`frames_from_parameters`), not part of the geometry.
    :raises ValueError: naming the parameter, if a value is missing or not allowed.
    """
    return geometry_from_settings(GeometrySettings.from_values(values))


def frames_from_parameters(values: Mapping[str, Any]) -> FrameTree:
    """
    Build the frame tree from ROS parameter values, as a parameter file gives them.

    :param values: parameter name -> value, with the names and units of
        :data:`~stewart_kinematics.parameters.FRAME_PARAMETERS`; a missing one takes its
        default.
    :raises ValueError: naming the parameter, if a value is not allowed, or for frame names
        that repeat.
    """
    return frames_from_settings(FrameSettings.from_values(values))


def frame_parameters_reason(values: Mapping[str, Any]) -> str:
    """
    Say why frame parameter values cannot make a frame tree, or return ``''``.

    For a run-time change, where a rule between parameters (frame names must differ) decides.
    """
    try:
        frames_from_parameters(values)
    except ValueError as error:
        return str(error)
    return ''


def _frame_pose(position, orientation_deg) -> Transform:
    """Return the transform of a position (metres) and Euler angles (degrees)."""
    return Transform.from_pose(np.concatenate([
        np.asarray(position, dtype=float), np.radians(np.asarray(orientation_deg, dtype=float))]))
