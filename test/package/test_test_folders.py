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
The tests are shaped like the package: one folder per sub-package, and unique module names.

A test module lives in the folder of the code it tests (test/model/ for stewart_kinematics/model/,
...), or in one of the folders for what is no sub-package: processes/ (the nodes as processes),
fuzzing/ (the node fuzzer), package/ (package-wide checks) and lint/. pytest imports each test
module by its basename (pytest.ini), so two modules of one name in two folders would not both
load: the names are unique across test/.
"""

from collections import Counter
from pathlib import Path

import pytest

pytestmark = pytest.mark.core

TEST = Path(__file__).resolve().parents[1]
PACKAGE = TEST.parent / 'stewart_kinematics'
#: Test folders that are no sub-package of stewart_kinematics.
OTHER_FOLDERS = {'processes', 'fuzzing', 'package', 'lint'}


def modules():
    """Return every test module under test/ (resources/ aside)."""
    return sorted(path for path in TEST.rglob('test_*.py')
                  if 'resources' not in path.relative_to(TEST).parts)


def sub_packages():
    """Return the names of the package's sub-packages."""
    return {path.parent.name for path in PACKAGE.glob('*/__init__.py')}


def test_every_test_module_is_in_the_folder_of_a_sub_package_or_a_named_other():
    folders = sub_packages() | OTHER_FOLDERS
    misplaced = [path.relative_to(TEST).as_posix() for path in modules()
                 if len(path.relative_to(TEST).parts) != 2
                 or path.relative_to(TEST).parts[0] not in folders]
    assert not misplaced, (
        f'test modules belong in test/<folder>/ with <folder> one of {sorted(folders)}: '
        + ', '.join(misplaced))


def test_the_known_folders_exist_and_hold_tests():
    """The folders for what is no sub-package are there (a rename here must update the list)."""
    used = {path.relative_to(TEST).parts[0] for path in modules()}
    assert OTHER_FOLDERS <= used
    assert {'model', 'limits', 'motion', 'ros'} <= used


def test_test_module_names_are_unique():
    counts = Counter(path.name for path in modules())
    twice = sorted(name for name, count in counts.items() if count > 1)
    assert not twice, f'test module names used in two folders (pytest.ini): {twice}'


def test_test_folders_are_no_packages():
    """No __init__.py: the folders are not importable packages, as pytest.ini's mode assumes."""
    packages = sorted(path.relative_to(TEST).as_posix() for path in TEST.rglob('__init__.py')
                      if 'resources' not in path.relative_to(TEST).parts)
    assert not packages, f'test folders with an __init__.py: {packages}'
