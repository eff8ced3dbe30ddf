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
Background workers: where the nodes' slow analyses run, off their message paths.

:mod:`.margin_monitor` computes the assembly-mode margin in a worker thread or process
(fk_node's), :mod:`.workspace_worker` the workspace and travel ranges in a worker process
(ik_node's), and :mod:`.owner_watch` ends a worker process once the process it works for is
gone.

May import: :mod:`stewart_kinematics.analysis`, numpy and the standard library. Nothing here
imports ROS.
"""
