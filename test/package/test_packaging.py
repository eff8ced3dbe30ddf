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
package.xml and setup.py declare what the code imports.

rosdep installs a ROS package's dependencies from package.xml alone, so every ROS package that
the package's modules or its launch file import must be declared there, and every Python
library by its rosdep key. matplotlib serves only the demo's figures: setup.py declares it as
the ``demo`` extra.
"""

import ast
from pathlib import Path
import re
import sys
import xml.etree.ElementTree as ElementTree

import pytest

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = 'stewart_kinematics'
#: rosdep keys of the Python libraries the code may import (import name -> key). Every other
#: import that is neither the standard library nor this package is taken for a ROS package
#: of the same name.
PYTHON_ROSDEP_KEYS = {
    'matplotlib': 'python3-matplotlib',
    # mpl_toolkits (mplot3d) ships inside matplotlib.
    'mpl_toolkits': 'python3-matplotlib',
    'numpy': 'python3-numpy',
    'scipy': 'python3-scipy',
    'yaml': 'python3-yaml',
}
#: Python libraries with no rosdep key, installed from PyPI only (import name -> distribution):
#: package.xml cannot declare them, so setup.py and requirements.txt must.
PYPI_ONLY = {
    'daqp': 'daqp',
    'mcap': 'mcap',
    'mcap_ros2': 'mcap-ros2-support',
    'rosbags': 'rosbags',
    'ruckig': 'ruckig',
    'toppra': 'toppra',
}
#: Dependency tags that make a package available at run time.
RUN_DEPENDS = ('exec_depend', 'depend')


def declared_run_dependencies():
    """Names in package.xml's exec_depend and depend tags."""
    root = ElementTree.parse(ROOT / 'package.xml').getroot()
    return {element.text.strip() for tag in RUN_DEPENDS for element in root.iter(tag)}


def imported_modules():
    """``{top-level module: [files importing it]}`` over the package and launch/."""
    files = sorted((ROOT / PACKAGE).rglob('*.py')) + sorted((ROOT / 'launch').glob('*.py'))
    imports = {}
    for path in files:
        for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                names = [node.module]
            else:
                continue
            for name in names:
                imports.setdefault(name.split('.')[0], []).append(
                    path.relative_to(ROOT).as_posix())
    return imports


def required_keys():
    """``{rosdep key: files}`` that the imports require package.xml to declare."""
    required = {}
    for module, files in imported_modules().items():
        if module in sys.stdlib_module_names or module == PACKAGE or module in PYPI_ONLY:
            continue
        key = PYTHON_ROSDEP_KEYS.get(module, module)
        required.setdefault(key, set()).update(files)
    return required


def test_package_xml_declares_every_imported_package():
    """Each ROS package and Python library imported at run time is an exec_depend."""
    declared = declared_run_dependencies()
    missing = {key: sorted(files) for key, files in required_keys().items()
               if key not in declared}
    assert not missing, '\n'.join(
        f'package.xml: add <exec_depend>{key}</exec_depend> (imported by {", ".join(files)}; '
        f'a Python library needs its rosdep key in PYTHON_ROSDEP_KEYS of {Path(__file__).name})'
        for key, files in missing.items())


def test_pypi_only_libraries_are_declared_in_setup_and_requirements():
    """A library without a rosdep key is in setup.py (the core's or the demo's) and pinned."""
    setup = (ROOT / 'setup.py').read_text(encoding='utf-8')
    install = ast.literal_eval(re.search(r'install_requires=(\[.*?\]),', setup).group(1))
    extras = ast.literal_eval(
        re.search(r'extras_require=(\{.*?\}),\n', setup, re.DOTALL).group(1))
    pinned = {line.split('==')[0].split('[')[0].strip().lower()
              for line in (ROOT / 'requirements.txt').read_text(encoding='utf-8').splitlines()
              if '==' in line and not line.startswith('#')}
    imports = imported_modules()
    for module, distribution in PYPI_ONLY.items():
        users = imports.get(module)
        if not users:
            continue
        tools_only = all(path.startswith(f'{PACKAGE}/tools/') for path in users)
        declared = extras.get('demo', []) if tools_only else install
        assert distribution in declared, (
            f"setup.py: add '{distribution}' to "
            f"{'extras_require demo' if tools_only else 'install_requires'} (imported by "
            f'{", ".join(sorted(set(users)))})')
        assert distribution.lower() in pinned, f'requirements.txt: pin {distribution}'


def test_launch_file_dependencies_are_declared():
    """The launch file's imports, launch and launch_ros, are exec_depends."""
    assert {'launch', 'launch_ros', 'ament_index_python'} <= declared_run_dependencies()


def test_package_xml_declares_nothing_unused():
    """Every run dependency of package.xml is imported somewhere (or is a message package)."""
    declared = declared_run_dependencies()
    used = set(required_keys())
    assert declared - used == set(), (
        f'package.xml declares run dependencies nothing imports: {sorted(declared - used)}')


def test_matplotlib_is_the_demo_extra():
    """setup.py puts matplotlib in the demo extra; the core and the nodes never import it."""
    setup = (ROOT / 'setup.py').read_text(encoding='utf-8')
    extras = re.search(r'extras_require=(\{.*?\}),\n', setup, re.DOTALL)
    assert extras, 'setup.py has no extras_require'
    assert 'matplotlib' in ast.literal_eval(extras.group(1)).get('demo', [])
    users = set(imported_modules()['matplotlib'])
    assert users and all(path.startswith(f'{PACKAGE}/tools/') for path in users), users
