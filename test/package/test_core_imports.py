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
The layout's rules: the core imports no ROS, and each folder imports only what it may.

The core is every module outside ``ros/`` and ``tools/``. Each folder's ``__init__.py`` states
what it may import; :data:`MAY_IMPORT` is the same rule, checked on every module's imports.
"""

import ast
from pathlib import Path
import subprocess
import sys

import pytest

pytestmark = pytest.mark.core

PACKAGE = Path(__file__).resolve().parents[2] / 'stewart_kinematics'
#: The package's folders outside the core.
NOT_CORE = ('ros', 'tools')
CORE_MODULES = sorted(
    '.'.join(path.relative_to(PACKAGE).with_suffix('').parts)
    for path in PACKAGE.rglob('*.py')
    if path.name != '__init__.py' and path.relative_to(PACKAGE).parts[0] not in NOT_CORE)
#: What each part of the package may import from the package (``''``: the root's modules,
#: such as findings). ros/ and tools/ may import all of it.
MAY_IMPORT = {
    'findings': set(),
    'model': {'model'},
    'limits': {'model', 'dynamics', 'limits', 'findings'},
    'dynamics': {'model', 'dynamics'},
    'parameters': {'model', 'dynamics', 'limits', 'parameters'},
    'pose_decisions': {'model', 'limits', 'findings', 'parameters', 'pose_decisions',
                       'analysis.assembly_modes'},
    'motion': {'model', 'dynamics', 'limits', 'findings', 'parameters', 'motion'},
    'analysis': {'model', 'limits', 'findings', 'parameters', 'analysis', 'dynamics'},
    'cueing': {'model', 'limits', 'findings', 'parameters', 'motion', 'cueing', 'dynamics'},
    'workers': {'analysis', 'workers'},
}
#: Single modules allowed one import more than their folder, and why: none (a geometry asks
#: the limits it is given whether its home pose is allowed, without importing limits/).
EXCEPTIONS = {}

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
    """The core is where the layout says: the model, the limits, the pose decisions, motion."""
    assert {'model.geometry', 'model.inverse', 'model.forward', 'model.rotations',
            'limits.geometry_checks', 'pose_decisions.pose_commands', 'motion.retiming',
            'findings'} <= set(CORE_MODULES)


def package_imports(path):
    """Every ``stewart_kinematics...`` module that the module at ``path`` imports."""
    imported = set()
    for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            if node.module == 'stewart_kinematics':
                imported.update(f'stewart_kinematics.{alias.name}' for alias in node.names)
            elif node.module.startswith('stewart_kinematics.'):
                imported.add(node.module)
        elif isinstance(node, ast.Import):
            imported.update(alias.name for alias in node.names
                            if alias.name.startswith('stewart_kinematics.'))
    return imported


def allowed(part, module, importer=''):
    """Whether ``part`` (a folder or root module) may import ``stewart_kinematics.<module>``."""
    rules = MAY_IMPORT[part] | EXCEPTIONS.get(importer, set())
    return any(module == rule or module.startswith(rule + '.') for rule in rules)


def test_each_folder_imports_only_what_its_rule_allows():
    """A module of model/ importing motion/, say, fails here with the module and the import."""
    broken = []
    for module in CORE_MODULES:
        part = module.split('.')[0]
        assert part in MAY_IMPORT, f'{module}: add its folder to MAY_IMPORT (and a rule)'
        path = PACKAGE.joinpath(*module.split('.')).with_suffix('.py')
        for imported in sorted(package_imports(path)):
            target = imported[len('stewart_kinematics.'):]
            if not allowed(part, target, module):
                broken.append(f'{module} imports {imported}')
    assert not broken, 'imports against the layout rules:\n' + '\n'.join(broken)


def test_the_rules_have_no_cycle_and_no_exception():
    """No folder reaches itself through another: the rules order the folders, none excepted."""
    assert not EXCEPTIONS

    def reaches(start, goal, seen=()):
        return any(rule.split('.')[0] == goal or (
            rule.split('.')[0] not in seen and rule.split('.')[0] in MAY_IMPORT
            and reaches(rule.split('.')[0], goal, seen + (rule.split('.')[0],)))
            for rule in MAY_IMPORT[start] if rule.split('.')[0] != start)

    assert [part for part in MAY_IMPORT if reaches(part, part)] == []


def test_the_rule_check_catches_a_forbidden_import():
    """The check above can fail: model/ may not import motion/ nor limits/."""
    assert not allowed('model', 'motion.ramp') and not allowed('model', 'limits')
    assert allowed('motion', 'model.inverse') and allowed('pose_decisions', 'findings')


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
