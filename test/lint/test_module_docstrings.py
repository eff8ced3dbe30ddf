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


"""Every module opens with a docstring that says what it is for, under the licence header."""

import ast
from pathlib import Path

import pytest

pytestmark = pytest.mark.lint

ROOT = Path(__file__).resolve().parents[2]
MODULES = sorted(
    path for folder in ('stewart_kinematics', 'benchmarks', 'scripts', 'launch', 'test')
    for path in (ROOT / folder).rglob('*.py'))


@pytest.mark.parametrize('path', MODULES, ids=lambda path: str(path.relative_to(ROOT)))
def test_module_opens_with_a_docstring(path):
    """The first statement is a docstring whose summary line is a sentence."""
    docstring = ast.get_docstring(ast.parse(path.read_text(encoding='utf-8')))
    assert docstring, f'{path.relative_to(ROOT)} has no module docstring'
    summary = docstring.strip().splitlines()[0]
    assert summary.endswith(('.', ':')) and len(summary) > 15, summary


def test_modules_are_found():
    """The check sees the package's modules, nodes and tools included."""
    names = {path.relative_to(ROOT).as_posix() for path in MODULES}
    assert {'stewart_kinematics/model/forward.py', 'stewart_kinematics/ros/ik_node.py',
            'stewart_kinematics/tools/ramp_demo.py'} <= names
