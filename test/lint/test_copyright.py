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
Every Python file carries the project's Apache-2.0 copyright header.

``ament_copyright`` (the check ``ros2 pkg create`` generates) runs where it is installed; it is
not installable from PyPI, so the header is also checked here, without it.
"""

import os
from pathlib import Path

import pytest

pytestmark = pytest.mark.lint

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
#: Output of colcon when it is run in this folder; folders starting with '.' or '_' are skipped
#: too (.venv, .git, __pycache__), as the ament linters do.
EXCLUDED_DIRECTORIES = {'build', 'install', 'log'}
FIRST_LINE = '# Copyright 2026 stewart_kinematics developers'
LICENSE_NOTICE = 'Licensed under the Apache License, Version 2.0'
#: Number of lines at the top of a file that must hold the license notice.
HEADER_LINES = 15


def python_files():
    """Paths of the package's Python files, relative to the package root, sorted."""
    found = []
    for directory, subdirectories, filenames in os.walk(PACKAGE_ROOT):
        subdirectories[:] = [
            name for name in subdirectories
            if name[0] not in '._' and name not in EXCLUDED_DIRECTORIES]
        found.extend(
            Path(directory, name).relative_to(PACKAGE_ROOT)
            for name in filenames if name.endswith('.py'))
    return sorted(found)


@pytest.mark.copyright
@pytest.mark.linter
def test_copyright(monkeypatch):
    main = pytest.importorskip(
        'ament_copyright.main', reason='ament_copyright is not installed').main
    monkeypatch.chdir(PACKAGE_ROOT)
    rc = main(argv=['.', 'test'])
    assert rc == 0, 'Found errors'


@pytest.mark.copyright
@pytest.mark.linter
def test_copyright_header():
    files = python_files()
    assert Path('setup.py') in files and Path('test', 'lint', 'test_copyright.py') in files
    missing = []
    for path in files:
        lines = (PACKAGE_ROOT / path).read_text(encoding='utf-8').splitlines()
        header = '\n'.join(lines[:HEADER_LINES])
        if not lines or lines[0] != FIRST_LINE or LICENSE_NOTICE not in header:
            missing.append(str(path))
    assert not missing, (
        f'these files lack the header (first line {FIRST_LINE!r}, then the Apache-2.0 notice '
        f'with {LICENSE_NOTICE!r}): ' + ', '.join(missing))
