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
Fixtures of the in-process node tests: the nodes and their probes on one executor.

``node_rig`` spins a node under test and the test's probe nodes on one executor, in the test's
thread, and destroys them when the test ends, pass or fail; each module's ``start`` fixture
builds its node and probe and waits, through the rig, until they are connected.
"""

from helpers import DEADLINE
import pytest

from stewart_kinematics.ros.node_main import create_executor


class NodeRig:
    """Nodes spun by one executor in the test's thread, destroyed by :meth:`close`."""

    def __init__(self, spin_until):
        """Create the executor; ``spin_until`` is conftest's fixture of that name."""
        self.executor = create_executor()
        self._spin_until = spin_until
        self._nodes = []

    def add(self, node):
        """Spin ``node`` on the executor from now on and destroy it at the end; return it."""
        self._nodes.append(node)
        self.executor.add_node(node)
        return node

    def connect(self, condition, what):
        """Spin until ``condition()`` holds (the endpoints matched); fail after DEADLINE s."""
        assert self._spin_until(self.executor, condition, DEADLINE), (
            f'{what}: not connected within {DEADLINE} s')

    def close(self):
        """Stop the executor and destroy every node added."""
        self.executor.shutdown()
        for node in self._nodes:
            node.destroy_node()


@pytest.fixture
def node_rig(ros, spin_until):
    """Provide a :class:`NodeRig`, closed when the test ends."""
    rig = NodeRig(spin_until)
    yield rig
    rig.close()
