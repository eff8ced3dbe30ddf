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
``colcon build`` of this package, as in a ROS 2 workspace, and the installed layout at work.

colcon and ament_package come from PyPI (requirements.txt). The build reads the repository
(``--base-paths``) and writes only into a temporary workspace (``--build-base``,
``--install-base``, ``--log-base``), so the repository stays clean. The installed layout is
what ``ros2 run`` and ``ros2 launch`` rely on: ``lib/stewart_kinematics/<executable>``, the
ament index marker, ``share/stewart_kinematics/`` with package.xml, config/ and launch/. The
installed ``ik_node`` then runs in the environment that ``source install/setup.bash`` gives.
"""

import filecmp
import os
from pathlib import Path
import shutil
import subprocess
import sys

from geometry_msgs.msg import Pose
from numpy.testing import assert_allclose
import pytest
from std_msgs.msg import Float64MultiArray

pytestmark = pytest.mark.process

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = 'stewart_kinematics'
EXECUTABLES = ('ik_node', 'fk_node', 'trajectory_node')
#: Seconds colcon may take: far more than this small package needs, for a loaded machine.
BUILD_TIMEOUT = 120.0
#: What a colcon build in the repository itself would leave there.
BUILD_LEFTOVERS = ('build', 'install', 'log', f'{PACKAGE}.egg-info')
#: Leg lengths of the paper's platform at its home pose (README), metres.
HOME_LENGTHS = [0.7188548665, 0.7188548766, 0.7011464423,
                0.7188548665, 0.7188548793, 0.7188548793]
HOME_POSITION = (0.0, 0.0, 0.4325)
SETTLE_TIME = 0.5


def colcon_executable():
    """Return colcon's path: beside this interpreter (the venv), else on PATH."""
    beside = Path(sys.executable).parent / 'colcon'
    found = str(beside) if beside.is_file() else shutil.which('colcon')
    assert found, 'colcon is not installed: run scripts/setup_venv.sh (requirements.txt pins it)'
    return found


def leftovers():
    """Return the build leftovers present in the repository."""
    return {name for name in BUILD_LEFTOVERS if (ROOT / name).exists()}


@pytest.fixture(scope='module')
def install_base(tmp_path_factory):
    """Build the package with colcon into a temporary workspace; return its install folder."""
    workspace = tmp_path_factory.mktemp('colcon_workspace')
    before = leftovers()
    env = dict(os.environ, COLCON_HOME=str(workspace / 'colcon_home'))
    command = [colcon_executable(), '--log-base', str(workspace / 'log'), 'build',
               '--base-paths', str(ROOT), '--packages-select', PACKAGE,
               '--build-base', str(workspace / 'build'),
               '--install-base', str(workspace / 'install')]
    result = subprocess.run(command, cwd=workspace, env=env, stdin=subprocess.DEVNULL,
                            capture_output=True, text=True, timeout=BUILD_TIMEOUT)
    assert result.returncode == 0, (
        f'colcon build exited {result.returncode}:\n{result.stdout}\n{result.stderr}')
    assert 'Summary: 1 package finished' in result.stdout, result.stdout
    assert leftovers() == before, 'colcon build wrote into the repository'
    return workspace / 'install'


def test_gitignore_covers_colcon_folders():
    """A colcon build run in the repository itself leaves nothing for git to pick up."""
    ignored = (ROOT / '.gitignore').read_text(encoding='utf-8').split()
    for folder in ('build/', 'install/', 'log/', '*.egg-info/'):
        assert folder in ignored, folder


def test_installed_layout_is_what_ros2_run_needs(install_base):
    """Executables in lib/<pkg>/, the ament index marker, package.xml, config/ and launch/."""
    prefix = install_base / PACKAGE
    for name in EXECUTABLES:
        executable = prefix / 'lib' / PACKAGE / name
        assert executable.is_file() and os.access(executable, os.X_OK), executable
    assert (prefix / 'share' / 'ament_index' / 'resource_index' / 'packages' / PACKAGE).is_file()
    share = prefix / 'share' / PACKAGE
    assert filecmp.cmp(share / 'package.xml', ROOT / 'package.xml', shallow=False)
    config = sorted(str(path.relative_to(ROOT / 'config')) for path in (ROOT / 'config').rglob('*')
                    if path.is_file())
    assert {'paper_platform.yaml', 'stewart_kinematics.rviz',
            'ros2_control/stewart_controllers.yaml'} <= set(config)
    assert sorted(str(path.relative_to(share / 'config'))
                  for path in (share / 'config').rglob('*') if path.is_file()) == config
    for name in config:
        assert filecmp.cmp(share / 'config' / name, ROOT / 'config' / name, shallow=False)
    launch_files = sorted(path.name for path in (ROOT / 'launch').glob('*.launch.py'))
    assert launch_files == ['motion_cueing.launch.py', 'stewart_kinematics.launch.py']
    assert sorted(path.name for path in (share / 'launch').iterdir()) == launch_files


def sourced_environment(install_base):
    """Return the environment after ``source install/setup.bash`` in the current one."""
    output = subprocess.run(
        ['bash', '-c', f'source {install_base / "setup.bash"} && env -0'],
        capture_output=True, check=True, timeout=30, stdin=subprocess.DEVNULL).stdout
    return dict(entry.split('=', 1)
                for entry in output.decode().split('\0') if '=' in entry)


def test_installed_ik_node_runs_after_sourcing_setup_bash(install_base, client, start_node):
    """
    After ``source install/setup.bash``, the installed ik_node with the installed config works.

    The package is found in the install folder (its Python module and its share directory, as
    ros2 launch looks it up), and ik_node answers the home pose with the README's lengths.
    """
    prefix = install_base / PACKAGE
    env = sourced_environment(install_base)
    lookup = subprocess.run(
        [sys.executable, '-c',
         'import stewart_kinematics\n'
         'from ament_index_python.packages import get_package_share_directory\n'
         'print(stewart_kinematics.__file__)\n'
         'print(get_package_share_directory("stewart_kinematics"))'],
        env=env, cwd=install_base, capture_output=True, text=True, timeout=30,
        stdin=subprocess.DEVNULL)   # cwd: python -c puts it first on sys.path, as no node does
    assert lookup.returncode == 0, lookup.stderr
    module_file, share = lookup.stdout.split()
    assert Path(module_file).is_relative_to(prefix), module_file
    assert Path(share) == prefix / 'share' / PACKAGE

    config = prefix / 'share' / PACKAGE / 'config' / 'paper_platform.yaml'
    node = start_node(str(prefix / 'lib' / PACKAGE / 'ik_node'),
                      ['--ros-args', '--params-file', str(config)], env=env)
    lengths = []
    subscription = client.node.create_subscription(
        Float64MultiArray, 'leg_lengths', lengths.append, 10)
    publisher = client.node.create_publisher(Pose, 'target_pose', 10)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and subscription.get_publisher_count() >= 1, 'installed ik_node matched', [node])
    client.spin_for(SETTLE_TIME)
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = HOME_POSITION
    pose.orientation.w = 1.0
    publisher.publish(pose)
    client.wait(lambda: lengths, 'leg_lengths from the installed ik_node', [node])

    assert_allclose(lengths[0].data, HOME_LENGTHS, rtol=0.0, atol=1e-9)
    code = node.stop()
    assert code == 0, f'installed ik_node exited {code}:\n{node.output()}'
