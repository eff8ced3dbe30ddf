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
Offline analysis: the workspace, every assembly mode, and calibration.

:mod:`.workspace` (travel ranges, volumes, slices), :mod:`.assembly_modes` (every real pose of a
set of leg lengths), :mod:`.calibration` (the geometry identified from measurements, with
scipy) and :mod:`.payload_identification` (the payload's mass and centre of mass from leg
forces measured at rest). The worker threads and processes in which the nodes run them live in
:mod:`stewart_kinematics.workers`.

May import: :mod:`stewart_kinematics.model`, :mod:`stewart_kinematics.limits`,
:mod:`stewart_kinematics.parameters`, :mod:`stewart_kinematics.dynamics` (payload
identification), numpy, scipy (calibration only). Nothing here imports
ROS.
"""
