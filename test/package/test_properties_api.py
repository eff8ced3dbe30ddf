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
No public name escapes the adversary: each one of the package root has a property test.

The names are ``stewart_kinematics.__all__`` (the lazily imported calibration names among
them); a property test is a hypothesis test in a test/*/test_properties_*.py module that names
what it exercises with ``@covers(...)`` (test/properties.py). A new public name fails here
until a property test covers it.
"""

import importlib
from pathlib import Path
import sys

import pytest

import stewart_kinematics

pytestmark = pytest.mark.core

#: The test folder: the property tests live in the folders of the code they test.
TEST_DIRECTORY = Path(__file__).resolve().parents[1]


def property_module(path):
    """Import a test module by its file, as pytest does (its basename is unique in test/)."""
    if path.stem in sys.modules:
        return sys.modules[path.stem]
    sys.path.insert(0, str(path.parent))
    try:
        return importlib.import_module(path.stem)
    finally:
        sys.path.remove(str(path.parent))


def covered_names():
    """Return public name -> the property tests that cover it."""
    covered = {}
    for path in sorted(TEST_DIRECTORY.rglob('test_properties_*.py')):
        if path.stem == Path(__file__).stem:
            continue
        module = property_module(path)
        for test_name, test in vars(module).items():
            if test_name.startswith('test_') and hasattr(test, 'hypothesis'):
                for name in getattr(test, 'covers', ()):
                    covered.setdefault(name, []).append(f'{path.stem}.{test_name}')
    return covered


def test_every_public_name_has_a_property_test():
    covered = covered_names()
    missing = sorted(set(stewart_kinematics.__all__) - set(covered))
    assert not missing, f'public names without a property test (@covers): {missing}'


def test_property_tests_cover_only_public_names():
    unknown = sorted(set(covered_names()) - set(stewart_kinematics.__all__))
    assert not unknown, f'@covers names that are not public (misspelt?): {unknown}'


def test_the_lazy_calibration_names_are_public_and_importable():
    lazy = stewart_kinematics._CALIBRATION_NAMES
    assert set(lazy) <= set(stewart_kinematics.__all__)
    for name in stewart_kinematics.__all__:
        assert getattr(stewart_kinematics, name) is not None, name
