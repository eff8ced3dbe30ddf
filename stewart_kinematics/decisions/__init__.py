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
The decisions the nodes take, as pure objects a Python user can call in a loop.

:class:`~.pose_commands.CommandCheck` (ik_node: a commanded pose in, safe leg lengths or every
reason out) and :class:`~.pose_tracker.PoseTracker` (fk_node: measured leg lengths in, a trusted
pose or the reason out). Each returns a result that carries a
:class:`~stewart_kinematics.findings.Finding` when it refuses.

May import: :mod:`stewart_kinematics.model`, :mod:`stewart_kinematics.limits`,
:mod:`stewart_kinematics.findings`, :mod:`stewart_kinematics.analysis.assembly_modes`. Nothing
here imports ROS.
"""
