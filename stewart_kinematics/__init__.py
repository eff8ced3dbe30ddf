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
Kinematics of Gough-Stewart platforms (6-6, 6-3, 3-3), with ROS 2 nodes around them.

The core (this package's root modules) imports only numpy and PyYAML (toppra and ruckig
for timed motion, imported where used); the ROS nodes live in
:mod:`stewart_kinematics.ros` and the demo and helpers in :mod:`stewart_kinematics.tools`::

    from stewart_kinematics import forward_kinematics, inverse_kinematics, load_geometry

    geometry = load_geometry('config/paper_platform.yaml')
    lengths = inverse_kinematics(geometry, [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0])
    result = forward_kinematics(geometry, lengths)
    result.pose, result.converged, result.iterations, result.residual

The decisions the nodes take, for a Python user's own loop: :class:`CommandCheck` (ik_node: a
commanded pose in, safe leg lengths or every reason out), :class:`PoseTracker` (fk_node:
measured leg lengths in, a trusted pose or the reason out), :class:`MotionPlanner`
(trajectory_node: a trajectory in, timed and checked whole, or the reason out),
:class:`CommandFilter` (streamed commands) and :class:`stewart_kinematics.cueing.MotionCueing`
(motion_cueing_node). Each answers with the shared
:class:`~stewart_kinematics.findings.Decision` result.

Poses are ``[X, Y, Z, alpha, beta, gamma]`` in metres and radians, with
``R = Rz(gamma) Ry(beta) Rx(alpha)``; leg lengths are in metres, leg 1..6.
"""

from stewart_kinematics.analysis.assembly_modes import (
    assembly_mode_margin,
    assembly_modes,
    AssemblyMode,
    AssemblyModeMargin,
    AssemblyModes,
)
from stewart_kinematics.analysis.payload_identification import identify_payload, PayloadEstimate
from stewart_kinematics.analysis.workspace import (
    orientation_workspace,
    travel_ranges,
    workspace_slice,
    workspace_volume,
)
from stewart_kinematics.dynamics import (
    external_wrench,
    leg_forces,
    LegBody,
    MassProperties,
    platform_wrench,
    RigidBody,
)
from stewart_kinematics.findings import Finding
from stewart_kinematics.limits import LimitModel, PoseLimits
from stewart_kinematics.model.actuators import ActuatorInterface, ActuatorLimits
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.forward_result import ForwardKinematicsResult
from stewart_kinematics.model.frames import FrameTree, Transform
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.model.inverse import inverse_kinematics, leg_lengths, leg_vectors
from stewart_kinematics.model.jacobians import jacobian, twist_jacobian
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    euler_zyx_to_quaternion,
    matrix_to_euler_zyx,
    matrix_to_quaternion,
    quaternion_to_euler_zyx,
    quaternion_to_matrix,
)
from stewart_kinematics.model.velocities import leg_velocities, platform_twist, SingularPoseError
from stewart_kinematics.motion.leg_trajectory import leg_trajectory, LegTrajectory
from stewart_kinematics.motion.planning import MotionPlan, MotionPlanner, plan_motion
from stewart_kinematics.motion.pose_trajectory import PoseTrajectory, TimedTrajectory
from stewart_kinematics.motion.ramp import Ramp
from stewart_kinematics.motion.retiming import retime
from stewart_kinematics.motion.streaming import CommandFilter, FilteredCommand, StreamTarget
from stewart_kinematics.motion.trajectory_check import check_trajectory, TrajectoryCheck
from stewart_kinematics.parameters import (
    frames_from_parameters,
    geometry_from_parameters,
    load_geometry,
    load_settings,
    SolverSettings,
)
from stewart_kinematics.pose_decisions.pose_commands import (
    CommandCheck,
    LegCommand,
    LegVelocityCommand,
)
from stewart_kinematics.pose_decisions.pose_tracker import (
    PoseAnchor,
    PoseEstimate,
    PoseTracker,
    TwistEstimate,
)

__all__ = [
    'ActuatorInterface',
    'ActuatorLimits',
    'assembly_mode_margin',
    'assembly_modes',
    'AssemblyMode',
    'AssemblyModeMargin',
    'AssemblyModes',
    'calibrate',
    'CalibrationError',
    'CalibrationResult',
    'check_trajectory',
    'CommandCheck',
    'CommandFilter',
    'euler_zyx_to_matrix',
    'euler_zyx_to_quaternion',
    'external_wrench',
    'FilteredCommand',
    'Finding',
    'forward_kinematics',
    'ForwardKinematicsResult',
    'frames_from_parameters',
    'FrameTree',
    'Geometry',
    'geometry_from_parameters',
    'identify_payload',
    'inverse_kinematics',
    'jacobian',
    'leg_forces',
    'leg_lengths',
    'leg_trajectory',
    'leg_vectors',
    'leg_velocities',
    'LegBody',
    'LegCommand',
    'LegTrajectory',
    'LegVelocityCommand',
    'LimitModel',
    'load_geometry',
    'load_settings',
    'MassProperties',
    'matrix_to_euler_zyx',
    'matrix_to_quaternion',
    'measurement_poses',
    'MotionPlan',
    'MotionPlanner',
    'plan_motion',
    'orientation_workspace',
    'PayloadEstimate',
    'platform_twist',
    'platform_wrench',
    'PoseAnchor',
    'PoseEstimate',
    'PoseTracker',
    'PoseLimits',
    'PoseTrajectory',
    'quaternion_to_euler_zyx',
    'quaternion_to_matrix',
    'Ramp',
    'retime',
    'RigidBody',
    'SingularPoseError',
    'SolverSettings',
    'StreamTarget',
    'TimedTrajectory',
    'TrajectoryCheck',
    'Transform',
    'travel_ranges',
    'twist_jacobian',
    'TwistEstimate',
    'workspace_slice',
    'workspace_volume',
]

#: Calibration needs scipy: imported on first use, so that the nodes start without loading it.
_CALIBRATION_NAMES = ('calibrate', 'CalibrationError', 'CalibrationResult', 'measurement_poses')


def __getattr__(name):
    """Import the calibration names on first use (PEP 562)."""
    if name in _CALIBRATION_NAMES:
        from stewart_kinematics.analysis import calibration
        return getattr(calibration, name)
    raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
