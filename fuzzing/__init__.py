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
The adversary of the test suite: the node fuzzer and what it shares with the soak.

Not part of the installed package (a harness, not something a user runs on a robot): the tests,
``benchmarks/soak.py`` and ``scripts/fuzz_nodes.sh`` import it from the repository root
(``pythonpath = .`` in pytest.ini). ``python -m fuzzing.node_fuzzer --help`` for the long run.
"""
