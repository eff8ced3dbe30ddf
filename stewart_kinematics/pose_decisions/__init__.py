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
The pose decisions of the kinematics nodes: a pose to command (ik_node), a pose to trust (fk_node).

:class:`~.pose_commands.CommandCheck` (ik_node: a commanded pose or twist of the tool frame in,
safe leg lengths or velocities or every reason out) and :class:`~.pose_tracker.PoseTracker`
(fk_node: measured leg lengths in, a trusted pose of the tool frame or the reason out). Each
returns the shared :class:`~stewart_kinematics.findings.Decision` result, which carries a
:class:`~stewart_kinematics.findings.Finding` when it refuses. :mod:`.tracker_status` decides
what fk_node reports of its tracker on ``/diagnostics``.

Every node's decision object lives with the concept it decides on, and a node converts
messages, calls it, publishes and counts:

- ik_node: :class:`~.pose_commands.CommandCheck` here; with ``command_rate``,
  :class:`~stewart_kinematics.motion.streaming.CommandFilter` (motion/).
- fk_node: :class:`~.pose_tracker.PoseTracker` here, with the assembly-mode margin's monitor
  (:mod:`stewart_kinematics.workers.margin_monitor`).
- trajectory_node: :class:`~stewart_kinematics.motion.planning.MotionPlanner`,
  :class:`~stewart_kinematics.motion.playback.RampPlayback` and
  :class:`~stewart_kinematics.motion.playback.TrajectoryPlayback`, and
  :class:`~stewart_kinematics.motion.planning_worker.PlanningWorker` (motion/).
- motion_cueing_node: :class:`~stewart_kinematics.cueing.MotionCueing` (cueing/), its input
  watchdog included.

They are not gathered in one folder: :class:`~stewart_kinematics.cueing.MotionCueing` is the
front of the cueing pipeline that cueing/ runs offline too (``replay``), and the planner and the
players are the motion's; gathered here, this folder and those would import each other.

May import: :mod:`stewart_kinematics.model`, :mod:`stewart_kinematics.limits`,
:mod:`stewart_kinematics.findings`, :mod:`stewart_kinematics.parameters`,
:mod:`stewart_kinematics.analysis.assembly_modes`. Nothing here imports ROS.
"""
