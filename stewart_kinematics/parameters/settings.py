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
Typed settings: frozen objects whose fields are the parameters of a group of specs.

A settings class is built from the specs of :mod:`stewart_kinematics.parameters.declarations`
(the one declaration of each parameter), so its fields have the parameters' names, types and
defaults, and every value is checked by the specs' validators when an object is made. A wrong
name fails where it is written (``TypeError`` when building, ``AttributeError`` when reading),
not later as a silent default::

    >>> from stewart_kinematics.parameters import StreamingSettings
    >>> StreamingSettings(command_rate=100.0).command_rate
    100.0
    >>> StreamingSettings(command_rate=-1.0)
    Traceback (most recent call last):
        ...
    ValueError: parameter 'command_rate' must be in [0, 10000], got -1.0

A node's settings (:class:`NodeSettings`) group those of the parameter groups it declares:
``settings.streaming.command_rate``. Arrays are stored as tuples, so settings are immutable and
hashable. Nothing here imports ROS.
"""

import array
import dataclasses
from typing import Any, Dict, Mapping, Tuple

from stewart_kinematics.parameters.declarations import (
    ACTUATOR_PARAMETERS,
    ASSEMBLY_MODE_PARAMETERS,
    FK_FRAME_PARAMETERS,
    FRAME_PARAMETERS,
    GEOMETRY_PARAMETERS,
    IK_FRAME_PARAMETERS,
    MARKER_PARAMETERS,
    MOTION_CUEING_PARAMETERS,
    MOTION_PARAMETERS,
    QUEUE_PARAMETERS,
    RAMP_PARAMETERS,
    SOLVER_PARAMETERS,
    STREAMING_PARAMETERS,
    WORKSPACE_PARAMETERS,
)
from stewart_kinematics.parameters.spec import (
    BOOL,
    DOUBLE,
    DOUBLE_ARRAY,
    INTEGER,
    ParameterSpec,
    STRING,
    STRING_ARRAY,
)

#: The Python type of each parameter type, for the settings' field annotations.
_FIELD_TYPES = {
    BOOL: bool,
    INTEGER: int,
    DOUBLE: float,
    STRING: str,
    DOUBLE_ARRAY: Tuple[float, ...],
    STRING_ARRAY: Tuple[str, ...],
}


class Settings:
    """
    Base of the settings classes that :func:`settings_class` builds from parameter specs.

    Build one with keyword arguments (``SolverSettings(tolerance=1e-10)``: the others take
    their defaults) or from a mapping of parameter values that may hold other names too
    (:meth:`from_values`). Every value is checked by its spec: ``ValueError`` names the
    parameter, the value and what is allowed.
    """

    #: The specs of the fields, in order.
    SPECS: Tuple[ParameterSpec, ...] = ()

    def __post_init__(self):
        for spec in self.SPECS:
            value = getattr(self, spec.name)
            if value is None and spec.default is not None:
                value = spec.default   # None is a value nobody set: the default, as in a file
                object.__setattr__(self, spec.name, value)
            if isinstance(value, (list, array.array)):
                value = tuple(value)
                object.__setattr__(self, spec.name, value)
            reason = spec.check(value)
            if reason:
                raise ValueError(reason)

    @classmethod
    def names(cls) -> Tuple[str, ...]:
        """Return the parameter names of the fields, in order."""
        return tuple(spec.name for spec in cls.SPECS)

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> 'Settings':
        """
        Build the settings from parameter values: the names of this class, others ignored.

        :param values: parameter name -> value, as a parameter file or a node gives them; a
            missing optional parameter takes its default.
        :raises ValueError: naming the parameter, if a value is not allowed or a required one
            is missing.
        """
        for spec in cls.SPECS:
            if spec.default is None and values.get(spec.name) is None:
                raise ValueError(spec.check(None))
        return cls(**{name: values[name] for name in cls.names() if name in values})

    def replace(self, **changes) -> 'Settings':
        """Return a copy with some fields changed, checked like a new object."""
        return dataclasses.replace(self, **changes)

    def as_values(self) -> Dict[str, Any]:
        """Return parameter name -> value (arrays as lists, as a parameter file holds them)."""
        return {name: list(value) if isinstance(value, tuple) else value
                for name, value in ((name, getattr(self, name)) for name in self.names())}


def settings_class(name: str, specs, doc: str) -> type:
    """
    Build a frozen settings class with one field per spec (name, type and default).

    :param name: the class name, such as ``'SolverSettings'``.
    :param specs: the :class:`~stewart_kinematics.parameters.spec.ParameterSpec` of the fields.
    :param doc: the class docstring: what the group configures.
    """
    fields = []
    for spec in specs:
        default = spec.default
        if isinstance(default, list):
            default = tuple(default)
        options = {} if default is None else {'default': default}
        fields.append((spec.name, _FIELD_TYPES[spec.value_type], dataclasses.field(**options)))
    cls = dataclasses.make_dataclass(name, fields, bases=(Settings,), frozen=True, kw_only=True,
                                     namespace={'SPECS': tuple(specs), '__doc__': doc})
    cls.__module__ = __name__
    return cls


class NodeSettings:
    """
    Base of a node's settings: one :class:`Settings` object per parameter group it declares.

    The groups are the fields of a subclass (a frozen dataclass), such as ``geometry`` and
    ``streaming``; :data:`GROUPS` names the group classes in declaration order.
    """

    #: Field name -> settings class, in the order the node declares them.
    GROUPS: Dict[str, type] = {}

    @classmethod
    def specs(cls) -> Tuple[ParameterSpec, ...]:
        """Return the specs of every parameter of the node, group by group."""
        return tuple(spec for group in cls.GROUPS.values() for spec in group.SPECS)

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> 'NodeSettings':
        """Build every group from parameter values (see :meth:`Settings.from_values`)."""
        return cls(**{field: group.from_values(values) for field, group in cls.GROUPS.items()})

    def replace(self, **changes) -> 'NodeSettings':
        """
        Return a copy with some parameters changed, by parameter name, checked.

        :raises ValueError: for a name that none of the node's groups has.
        """
        groups = {field: getattr(self, field) for field in self.GROUPS}
        for name, value in changes.items():
            field = next((field for field, group in self.GROUPS.items()
                          if name in group.names()), None)
            if field is None:
                raise ValueError(f"unknown parameter '{name}' for {type(self).__name__}")
            groups[field] = groups[field].replace(**{name: value})
        return type(self)(**groups)

    def as_values(self) -> Dict[str, Any]:
        """Return parameter name -> value for every parameter of the node."""
        values = {}
        for field in self.GROUPS:
            values.update(getattr(self, field).as_values())
        return values


def node_settings_class(name: str, doc: str, **groups) -> type:
    """
    Build a node's settings class: one field per parameter group.

    :param name: the class name, such as ``'IkNodeSettings'``.
    :param doc: the class docstring.
    :param groups: field name -> settings class, in declaration order.
    """
    cls = dataclasses.make_dataclass(
        name, [(field, group) for field, group in groups.items()], bases=(NodeSettings,),
        frozen=True, kw_only=True, namespace={'GROUPS': dict(groups), '__doc__': doc})
    cls.__module__ = __name__
    return cls


# The parameter groups, one settings class each (see declarations.py for every field's
# meaning, unit and allowed values).
GeometrySettings = settings_class(
    'GeometrySettings', GEOMETRY_PARAMETERS,
    'The platform: joints, home pose, and every limit (stroke, joint cones, singularity '
    'margin, leg speed); :func:`~stewart_kinematics.parameters.builders.geometry_from_settings` '
    'builds the Geometry.')
ActuatorSettings = settings_class(
    'ActuatorSettings', ACTUATOR_PARAMETERS,
    'The actuators as a driver names them: joint names and zeros.')
SolverSettings = settings_class(
    'SolverSettings', SOLVER_PARAMETERS,
    "The forward kinematics solver and the pose tracker's checks (fk_node).")
AssemblyModeSettings = settings_class(
    'AssemblyModeSettings', ASSEMBLY_MODE_PARAMETERS,
    'The assembly-mode margin that fk_node reports.')
FrameSettings = settings_class(
    'FrameSettings', FRAME_PARAMETERS,
    'The base, platform, user and tool frames; '
    ':func:`~stewart_kinematics.parameters.builders.frames_from_settings` builds the FrameTree.')
FkFrameSettings = settings_class(
    'FkFrameSettings', FK_FRAME_PARAMETERS, "fk_node's broadcast of the estimated pose.")
IkFrameSettings = settings_class(
    'IkFrameSettings', IK_FRAME_PARAMETERS, "ik_node's broadcast of the commanded pose.")
MarkerSettings = settings_class('MarkerSettings', MARKER_PARAMETERS, 'The RViz markers.')
WorkspaceSettings = settings_class(
    'WorkspaceSettings', WORKSPACE_PARAMETERS, "ik_node's workspace outputs.")
QueueSettings = settings_class(
    'QueueSettings', QUEUE_PARAMETERS, 'The queues of every subscription and publisher.')
RampSettings = settings_class(
    'RampSettings', RAMP_PARAMETERS, 'The Table 3 ramp and how trajectory_node plays it.')
MotionSettings = settings_class(
    'MotionSettings', MOTION_PARAMETERS,
    'Trajectories and paths received by trajectory_node: checking, retiming, playing.')
StreamingSettings = settings_class(
    'StreamingSettings', STREAMING_PARAMETERS, "ik_node's streamed, jerk-limited commands.")
CueingParameterSettings = settings_class(
    'CueingParameterSettings', MOTION_CUEING_PARAMETERS,
    "motion_cueing_node's washout, limit margins and input checks, as the node declares its "
    "parameters (degrees where named); not the motion cueing's own settings, "
    ':class:`stewart_kinematics.cueing.CueingSettings` (SI units), which '
    ':meth:`~stewart_kinematics.cueing.CueingSettings.from_parameters` builds from these.')

# The nodes' settings: the groups each node declares, in order.
IkNodeSettings = node_settings_class(
    'IkNodeSettings', "ik_node's settings.", geometry=GeometrySettings,
    actuators=ActuatorSettings, frames=FrameSettings, ik_frames=IkFrameSettings,
    markers=MarkerSettings, workspace=WorkspaceSettings, streaming=StreamingSettings,
    queue=QueueSettings)
FkNodeSettings = node_settings_class(
    'FkNodeSettings', "fk_node's settings.", geometry=GeometrySettings,
    actuators=ActuatorSettings, solver=SolverSettings, assembly_modes=AssemblyModeSettings,
    frames=FrameSettings, fk_frames=FkFrameSettings, markers=MarkerSettings,
    queue=QueueSettings)
MotionCueingNodeSettings = node_settings_class(
    'MotionCueingNodeSettings', "motion_cueing_node's settings.", geometry=GeometrySettings,
    frames=FrameSettings, cueing=CueingParameterSettings, queue=QueueSettings)
TrajectoryNodeSettings = node_settings_class(
    'TrajectoryNodeSettings', "trajectory_node's settings.", geometry=GeometrySettings,
    actuators=ActuatorSettings, frames=FrameSettings, ramp=RampSettings, motion=MotionSettings,
    queue=QueueSettings)
