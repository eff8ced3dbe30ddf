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
Motion: the reference ramp, platform trajectories, their checks, timing and streaming.

:mod:`.ramp` (the paper's Table 3 ramp as a function of time), :mod:`.pose_trajectory`
(waypoints interpolated on SE(3), played on a clock), :mod:`.trajectory_check` (every sample
against every limit), :mod:`.retiming` (time-optimal timing with toppra), :mod:`.planning`
(check, retime, decide), :mod:`.leg_trajectory` (the actuators' trajectory),
:mod:`.streaming` (jerk-limited streamed commands with ruckig) and :mod:`.mock_actuators`
(mock_platform's simulated legs: a first-order lag within the leg limits, faults for tests).

May import: :mod:`stewart_kinematics.model`, :mod:`stewart_kinematics.limits`,
:mod:`stewart_kinematics.findings`, toppra and ruckig. Nothing here imports ROS.
"""
