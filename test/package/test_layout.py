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
The architecture page's layout table names every module of the package and every top-level folder.

So it cannot go stale: a new module or folder fails here with its path until it has a row,
and a row for a path that no longer exists fails too.
"""

from pathlib import Path
import re
import subprocess
import sys

import pytest

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
#: The documentation page with the layout table.
PAGE_NAME = 'doc/architecture.md'
PAGE = (ROOT / PAGE_NAME).read_text(encoding='utf-8')
PACKAGE = 'stewart_kinematics'
#: Top-level folders that are no part of the repository (made by tools, ignored by git).
UNTRACKED = {'.git', '.venv', '.ros_log', '.pytest_cache', '.hypothesis', 'build', 'install',
             'log', 'demo_output', 'stewart_kinematics.egg-info', '__pycache__'}


def layout_paths():
    """Paths named in backquotes in the first column of the architecture page's Layout table."""
    section = re.search(r'\n## Layout\n(.*?)(?:\n## |\Z)', PAGE, re.DOTALL)
    assert section, f'{PAGE_NAME} has no "## Layout" section'
    first_cells = re.findall(r'^\| ([^|]+) \|', section.group(1), re.MULTILINE)
    paths = set()
    for cell in first_cells:
        paths.update(re.findall(r'`([^`]+)`', cell))
    assert paths, 'the Layout section has no table of paths'
    return paths


def top_level_folders():
    """Return the repository's top-level folders (tracked by git when git knows them)."""
    try:
        tracked = subprocess.run(['git', 'ls-files'], cwd=ROOT, capture_output=True,
                                 text=True, check=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        tracked = []
    if tracked:
        return {path.split('/')[0] + '/' for path in tracked if '/' in path}
    return {path.name + '/' for path in ROOT.iterdir()
            if path.is_dir() and path.name not in UNTRACKED}


def package_paths():
    """Every module (``__init__.py`` aside) and every folder of the package, repo-relative."""
    paths = set()
    for path in (ROOT / PACKAGE).rglob('*.py'):
        if '__pycache__' in path.parts:
            continue
        relative = path.relative_to(ROOT)
        paths.add(relative.parent.as_posix() + '/')
        if path.name != '__init__.py' or relative.parent == Path(PACKAGE):
            paths.add(relative.as_posix())
    return paths


def test_every_module_and_package_folder_has_a_layout_row():
    """Each .py under stewart_kinematics/ and each of its folders is named in the table."""
    named = layout_paths()
    missing = sorted(package_paths() - named)
    assert not missing, (f'{PAGE_NAME} Layout table: add a row for ' + ', '.join(missing))


def test_every_top_level_folder_has_a_layout_row():
    """Each top-level folder of the repository is named in the table (as `folder/`)."""
    named = layout_paths()
    missing = sorted(top_level_folders() - named)
    assert not missing, (f'{PAGE_NAME} Layout table: add a row for ' + ', '.join(missing))


def test_every_layout_row_exists():
    """No row names a file or folder that is not there."""
    gone = sorted(path for path in layout_paths() if not (ROOT / path).exists())
    assert not gone, f'{PAGE_NAME} Layout table names paths that do not exist: ' + ', '.join(gone)


def test_import_rules_table_is_the_checked_rule():
    """The architecture page's table of import rules says what test_core_imports enforces."""
    sys.path.insert(0, str(ROOT / 'test' / 'package'))
    try:
        from test_core_imports import MAY_IMPORT
    finally:
        sys.path.remove(str(ROOT / 'test' / 'package'))
    heading = '## The rules: what each folder may import'
    section = re.search(rf'\n{heading}\n(.*?)\n## ', PAGE, re.DOTALL)
    assert section, f'{PAGE_NAME} has no "{heading}" section'
    rows = re.findall(r'^\| `([\w.]+)/?` \| ([^|]+) \|', section.group(1), re.MULTILINE)
    stated = {}
    for folder, cell in rows:
        part = folder.removesuffix('.py')
        # What a parenthesis adds is a one-module exception (test_core_imports.EXCEPTIONS).
        names = re.findall(r'`([\w/.]+)`', cell.split('(')[0])
        stated[part] = {name.removesuffix('/').removesuffix('.py').replace('/', '.')
                        for name in names} | ({part} if 'itself' in cell or names else set())
    for part, allowed in MAY_IMPORT.items():
        assert part in stated, f'{PAGE_NAME}: no row for {part} in the import rules'
        assert stated[part] == allowed | ({part} if part != 'findings' else set()), part
