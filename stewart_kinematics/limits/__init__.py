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
The limits model: every reason a pose, or a motion, is not allowed, decided in one place.

One module per kind of limit, each declaring everything about it (a
:class:`~.kind.LimitKind`: its parameters with their units, bounds and defaults, its evaluator,
its label and colour) and holding its evaluator, which checks one pose or arrays of poses
through the core's single formulas (the leg vectors of :mod:`stewart_kinematics.model.formulas`,
the rotation entries of :mod:`stewart_kinematics.model.rotations`):

- :mod:`.stroke`: ``leg_length_min``, ``leg_length_max`` (poses and leg lengths);
- :mod:`.joint_cones`: ``base_joint_max_angle``, ``platform_joint_max_angle``;
- :mod:`.singularity`: ``max_jacobian_condition``, the singularity margin;
- :mod:`.leg_collision`: ``leg_collision``, legs as capsules of ``leg_radius``;
- :mod:`.leg_rates`: ``leg_velocity_max``, ``leg_acceleration_max``, ``leg_jerk_max``.

:data:`~.kinds.LIMIT_KINDS` lists them, and everything that lists limits derives from it.
:class:`~.settings.PoseLimits` holds the values of the pose limits (a geometry is given its
own), :class:`stewart_kinematics.ActuatorLimits` those of the leg rates.
:class:`~.limit_model.LimitModel` composes the evaluators of the limits that are set and gives
every check: one pose, a batch, leg states (trajectories, streams, twists).
:class:`~.command_gate.CommandGate` applies it to every command as it is sent to the actuators, and
gives the verdict a node publishes. :mod:`.geometry_checks` has the same as functions of a
geometry. :mod:`.base` holds what the evaluators share, :mod:`.violation` what they report.

May import: :mod:`stewart_kinematics.model`, :mod:`stewart_kinematics.dynamics` (the leg
forces), :mod:`stewart_kinematics.findings` and numpy.
Nothing here imports ROS.
"""

from stewart_kinematics.limits.base import Bound, LEG_PAIRS, LegSamples, Limit, PoseLegs
from stewart_kinematics.limits.command_gate import (
    CommandGate,
    LegCommand,
    LegVelocityCommand,
    MOTION,
    SETPOINT,
    TrajectoryCommand,
    Verdict,
)
from stewart_kinematics.limits.geometry_checks import (
    check_pose,
    check_poses,
    check_poses_array,
    check_samples,
    joint_angles,
    leg_length_violations,
)
from stewart_kinematics.limits.joint_cones import JointCones
from stewart_kinematics.limits.kind import BoundLook, CueMargins, LimitKind, LimitParameter
from stewart_kinematics.limits.kinds import LEG_STATE_LIMIT_NAMES, LIMIT_KINDS, LIMIT_NAMES
from stewart_kinematics.limits.leg_collision import LegCollision, segment_distances
from stewart_kinematics.limits.leg_rates import LegRate
from stewart_kinematics.limits.limit_model import LimitChecks, LimitModel
from stewart_kinematics.limits.settings import limits_of, PoseLimits
from stewart_kinematics.limits.singularity import SingularityMargin
from stewart_kinematics.limits.stroke import Stroke
from stewart_kinematics.limits.violation import Violation

__all__ = [
    'Bound',
    'BoundLook',
    'check_pose',
    'check_poses',
    'check_poses_array',
    'check_samples',
    'CommandGate',
    'CueMargins',
    'joint_angles',
    'JointCones',
    'LEG_PAIRS',
    'LEG_STATE_LIMIT_NAMES',
    'LegCollision',
    'LegCommand',
    'LegRate',
    'LegSamples',
    'LegVelocityCommand',
    'leg_length_violations',
    'Limit',
    'LIMIT_KINDS',
    'LIMIT_NAMES',
    'LimitChecks',
    'LimitKind',
    'LimitParameter',
    'limits_of',
    'LimitModel',
    'MOTION',
    'PoseLegs',
    'PoseLimits',
    'segment_distances',
    'SETPOINT',
    'SingularityMargin',
    'Stroke',
    'TrajectoryCommand',
    'Verdict',
    'Violation',
]
