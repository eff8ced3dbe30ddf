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

"""pydocstyle with the ament convention, as ``ros2 pkg create`` generates it."""

from pathlib import Path

from ament_pep257.main import main
import pytest

pytestmark = pytest.mark.lint

PACKAGE_ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.linter
@pytest.mark.pep257
def test_pep257(monkeypatch):
    # ament_pep257 skips folders whose names start with '.' or '_' (.venv, .git); a colcon
    # build run in this folder leaves build/, install/, log/. The generated test passes
    # ['.', 'test'], which reports every error in test/ twice.
    monkeypatch.chdir(PACKAGE_ROOT)
    rc = main(argv=['.', '--exclude', 'build', 'install', 'log'])
    assert rc == 0, 'Found code style errors / warnings'
