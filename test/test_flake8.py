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

"""flake8 with the ament configuration, as ``ros2 pkg create`` generates it."""

import gc
from pathlib import Path

from ament_flake8.main import main_with_errors
import pytest

pytestmark = pytest.mark.lint

PACKAGE_ROOT = Path(__file__).resolve().parent.parent


@pytest.mark.flake8
@pytest.mark.linter
def test_flake8(monkeypatch):
    # ament_flake8 checks the working directory and skips folders whose names start with '.'
    # or '_' (.venv, .git); a colcon build run in this folder leaves build/, install/, log/.
    monkeypatch.chdir(PACKAGE_ROOT)
    # flake8 forks its workers from this process: free here the garbage that earlier
    # in-process node tests left (rclpy objects), which crashed a forked worker that freed it.
    gc.collect()
    rc, errors = main_with_errors(argv=['--exclude', 'build', 'install', 'log'])
    assert rc == 0, \
        'Found %d code style errors / warnings:\n' % len(errors) + \
        '\n'.join(errors)
