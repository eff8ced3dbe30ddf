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
The platform model: its geometry, rotations, frames, actuators and kinematics.

Rotations (:mod:`.rotations`: one convention, R = Rz(gamma) Ry(beta) Rx(alpha)), the geometry
(:mod:`.geometry`: joints, home pose, limits), the frames (:mod:`.frames`), the actuator
interface and speed limits (:mod:`.actuators`), the velocity kinematics (:mod:`.velocities`),
and the kinematics, one concern per module: the argument checks (:mod:`.inputs`, on
:mod:`.arrays`), the leg formulas (:mod:`.formulas`), inverse kinematics (:mod:`.inverse`), the
Jacobians and their conditioning (:mod:`.jacobians`), forward kinematics (:mod:`.forward`: the
solver in :mod:`.forward_solver`, its start table in :mod:`.start_table`, its result in
:mod:`.forward_result`, the result's error bound in :mod:`.error_bound`). The rules a value
must keep, as data that checks and describes itself (:mod:`.validators`); each limit kind
declares its parameters' bounds with them (:mod:`stewart_kinematics.limits`).

May import: numpy and the standard library only. Nothing here imports ROS or another folder of
the package.
"""
