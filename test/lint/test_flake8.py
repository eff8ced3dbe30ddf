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

from pathlib import Path
import subprocess
import sys

import pytest

pytestmark = pytest.mark.lint

PACKAGE_ROOT = Path(__file__).resolve().parents[2]

#: ament_flake8 checks the working directory and skips folders whose names start with '.' or
#: '_' (.venv, .git); a colcon build run in this folder leaves build/, install/, log/.
RUN_FLAKE8 = """
import sys
from ament_flake8.main import main_with_errors
rc, errors = main_with_errors(argv=['--exclude', 'build', 'install', 'log'])
print('\\n'.join(errors))
sys.exit(rc)
"""


@pytest.mark.flake8
@pytest.mark.linter
def test_flake8():
    # In a fresh interpreter: flake8 forks worker processes, and a fork of this one, where
    # earlier tests left rclpy and numpy threads running, can deadlock.
    run = subprocess.run([sys.executable, '-c', RUN_FLAKE8], cwd=PACKAGE_ROOT,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, f'Found code style errors / warnings:\n{run.stdout}{run.stderr}'
