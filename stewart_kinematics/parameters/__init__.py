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
The parameters: every ROS parameter declared once, the parameter files, and what they build.

:mod:`.spec` (one parameter's declaration, with the validators of
:mod:`stewart_kinematics.model.validators`), :mod:`.declarations` (every
parameter of the package, by group), :mod:`.settings` (the typed settings of each group and
node, generated from the declarations by scripts/generate_settings.py; their behaviour in
:mod:`.settings_base`), :mod:`.files` (parameter files read as rcl reads them),
:mod:`.rcl_yaml` (the package's one YAML reader, with its limits), :mod:`.builders` (the
geometry and frames from parameter values) and :mod:`.tables` (the documentation's parameter
tables).

May import: :mod:`stewart_kinematics.model`, :mod:`stewart_kinematics.limits`,
:mod:`stewart_kinematics.dynamics` (the mass properties), numpy and PyYAML. Nothing here
imports ROS.
"""

from stewart_kinematics.parameters.builders import (
    actuator_interface_from_settings,
    actuator_limits_from_settings,
    frame_parameters_reason,
    frames_from_parameters,
    frames_from_settings,
    geometry_from_parameters,
    geometry_from_settings,
    geometry_with_payload,
    mass_properties_from_parameters,
    mass_properties_from_settings,
    PAYLOAD_PARAMETERS,
)
from stewart_kinematics.parameters.declarations import (
    ACTION_PARAMETERS,
    ACTUATOR_PARAMETERS,
    all_specs,
    ASSEMBLY_MODE_PARAMETERS,
    check_known_names,
    check_values,
    CUEING_CONTROL_PARAMETERS,
    defaults,
    FK_FRAME_PARAMETERS,
    FRAME_PARAMETERS,
    GEOMETRY_PARAMETERS,
    IK_FRAME_PARAMETERS,
    LIFECYCLE_PARAMETERS,
    MARKER_PARAMETERS,
    MASS_SPECS,
    MOCK_PLATFORM_PARAMETERS,
    MOTION_CUEING_PARAMETERS,
    MOTION_PARAMETERS,
    QUEUE_PARAMETERS,
    RAMP_PARAMETERS,
    REPLACED_PARAMETERS,
    SOLVER_PARAMETERS,
    STREAMING_PARAMETERS,
    WORKSPACE_PARAMETERS,
)
from stewart_kinematics.parameters.files import (
    load_geometry,
    load_settings,
    ParameterFileError,
    read_parameter_file,
    read_parameter_files,
)
from stewart_kinematics.parameters.settings import (
    ActionSettings,
    ActuatorSettings,
    AssemblyModeSettings,
    CueingControlSettings,
    CueingParameterSettings,
    FkFrameSettings,
    FkNodeSettings,
    FrameSettings,
    GeometrySettings,
    IkFrameSettings,
    IkNodeSettings,
    LifecycleSettings,
    MarkerSettings,
    MockPlatformNodeSettings,
    MockPlatformSettings,
    MotionCueingNodeSettings,
    MotionSettings,
    QueueSettings,
    RampSettings,
    SolverSettings,
    StreamingSettings,
    TrajectoryNodeSettings,
    WorkspaceSettings,
)
from stewart_kinematics.parameters.settings_base import NodeSettings, Settings
from stewart_kinematics.parameters.spec import (
    BOOL,
    DistinctNames,
    DOUBLE,
    DOUBLE_ARRAY,
    Finite,
    FixedLength,
    FrameName,
    InRange,
    INTEGER,
    NonEmpty,
    NullString,
    OneOf,
    OutOfRangeNumber,
    ParameterSpec,
    STRING,
    STRING_ARRAY,
    Validator,
    ZeroOrInRange,
)
from stewart_kinematics.parameters.tables import markdown_table

__all__ = [
    'ACTION_PARAMETERS',
    'ActionSettings',
    'actuator_interface_from_settings',
    'actuator_limits_from_settings',
    'ACTUATOR_PARAMETERS',
    'ActuatorSettings',
    'all_specs',
    'ASSEMBLY_MODE_PARAMETERS',
    'AssemblyModeSettings',
    'BOOL',
    'check_known_names',
    'check_values',
    'CUEING_CONTROL_PARAMETERS',
    'CueingControlSettings',
    'CueingParameterSettings',
    'defaults',
    'DistinctNames',
    'DOUBLE',
    'DOUBLE_ARRAY',
    'Finite',
    'FixedLength',
    'FK_FRAME_PARAMETERS',
    'FkFrameSettings',
    'FkNodeSettings',
    'FRAME_PARAMETERS',
    'frame_parameters_reason',
    'FrameName',
    'frames_from_parameters',
    'frames_from_settings',
    'FrameSettings',
    'geometry_from_parameters',
    'geometry_from_settings',
    'geometry_with_payload',
    'GEOMETRY_PARAMETERS',
    'GeometrySettings',
    'IK_FRAME_PARAMETERS',
    'IkFrameSettings',
    'IkNodeSettings',
    'LifecycleSettings',
    'InRange',
    'INTEGER',
    'load_geometry',
    'load_settings',
    'markdown_table',
    'LIFECYCLE_PARAMETERS',
    'MARKER_PARAMETERS',
    'MarkerSettings',
    'mass_properties_from_parameters',
    'mass_properties_from_settings',
    'MASS_SPECS',
    'MOCK_PLATFORM_PARAMETERS',
    'MockPlatformNodeSettings',
    'MockPlatformSettings',
    'MOTION_CUEING_PARAMETERS',
    'MOTION_PARAMETERS',
    'MotionCueingNodeSettings',
    'MotionSettings',
    'NodeSettings',
    'NonEmpty',
    'NullString',
    'OneOf',
    'OutOfRangeNumber',
    'ParameterFileError',
    'ParameterSpec',
    'PAYLOAD_PARAMETERS',
    'QUEUE_PARAMETERS',
    'QueueSettings',
    'RAMP_PARAMETERS',
    'RampSettings',
    'read_parameter_file',
    'read_parameter_files',
    'REPLACED_PARAMETERS',
    'Settings',
    'SOLVER_PARAMETERS',
    'SolverSettings',
    'STREAMING_PARAMETERS',
    'StreamingSettings',
    'STRING',
    'STRING_ARRAY',
    'TrajectoryNodeSettings',
    'Validator',
    'WORKSPACE_PARAMETERS',
    'WorkspaceSettings',
    'ZeroOrInRange',
]
