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

"""The layout's rule: the core (the package root's modules) imports no ROS."""

from pathlib import Path
import subprocess
import sys

import pytest

pytestmark = pytest.mark.core

PACKAGE = Path(__file__).resolve().parent.parent / 'stewart_kinematics'
CORE_MODULES = sorted(path.stem for path in PACKAGE.glob('*.py') if path.stem != '__init__')

#: Run in a fresh interpreter: refuse every ROS module, then import the whole core.
IMPORT_WITHOUT_ROS = """
import importlib
import importlib.abc
import sys

class NoRos(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        top = name.split('.')[0]
        if top in ('rclpy', 'rcl_interfaces', 'builtin_interfaces') or top.endswith('_msgs') \\
                or top.endswith('_srvs'):
            raise ImportError(f'{name} is blocked: the core must not import ROS')
        return None

sys.meta_path.insert(0, NoRos())
import stewart_kinematics
for module in sys.argv[1:]:
    importlib.import_module('stewart_kinematics.' + module)
ros = sorted(name for name in sys.modules if name.split('.')[0] == 'rclpy')
assert not ros, ros
print('imported', len(sys.argv) - 1, 'core modules')
"""


def test_core_modules_exist():
    """The core is where the layout says: geometry, kinematics and rotations at the root."""
    assert {'geometry', 'kinematics', 'rotations', 'limits'} <= set(CORE_MODULES)


def test_core_imports_with_rclpy_unavailable():
    """Every root module, and the package itself, imports with every ROS module refused."""
    run = subprocess.run([sys.executable, '-c', IMPORT_WITHOUT_ROS, *CORE_MODULES],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    assert f'imported {len(CORE_MODULES)} core modules' in run.stdout


def test_ros_modules_are_refused_by_the_check():
    """The blocker works: importing a node under it fails, so the test above can fail."""
    run = subprocess.run(
        [sys.executable, '-c',
         IMPORT_WITHOUT_ROS.replace("'stewart_kinematics.' + module", 'module'), 'rclpy'],
        capture_output=True, text=True, timeout=60)
    assert run.returncode != 0
    assert 'blocked' in run.stderr
