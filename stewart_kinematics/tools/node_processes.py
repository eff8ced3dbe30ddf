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
Start the package's nodes as separate processes, as ``ros2 run`` does, on an isolated domain.

Used by the ramp demo, the multi-process tests and the benchmarks, so that each of them keeps
DDS traffic on this machine (``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``) and on a domain that
no concurrent run uses.
"""

import contextlib
import os
from pathlib import Path
import random
import shutil
import signal
import socket
import subprocess
import sys
import tempfile

#: Seconds a node gets to stop after SIGINT before it is killed.
STOP_TIMEOUT = 10.0
#: domain_coordinator's port base: holding port DOMAIN_PORT_BASE + id reserves domain id.
DOMAIN_PORT_BASE = 32768


@contextlib.contextmanager
def isolated_ros_environment():
    """
    Set up ``os.environ`` so that ROS traffic stays on this machine and on a free domain.

    Always sets ``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`` and reserves a free
    ``ROS_DOMAIN_ID`` (holding a local port for it, as ROS's ``domain_coordinator`` does),
    whatever the caller's environment says: the demo, the tests and the benchmarks must neither
    reach the network nor meet another run. Sets ``ROS_LOG_DIR`` unless already set. Child
    processes inherit the environment. Restores ``os.environ`` on exit.

    :yields: the ``ROS_DOMAIN_ID`` in use, as a string.
    """
    saved = dict(os.environ)
    with contextlib.ExitStack() as stack:
        os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
        if 'ROS_LOG_DIR' not in os.environ:
            os.environ['ROS_LOG_DIR'] = stack.enter_context(
                tempfile.TemporaryDirectory(prefix='stewart_ros_log_'))
        os.environ['ROS_DOMAIN_ID'] = str(stack.enter_context(_free_domain_id()))
        try:
            yield os.environ['ROS_DOMAIN_ID']
        finally:
            os.environ.clear()
            os.environ.update(saved)


@contextlib.contextmanager
def _free_domain_id():
    """
    Reserve a ROS domain ID from 1 to 100 that no cooperating process uses.

    The protocol of ROS's ``domain_coordinator``: a domain is taken while a process holds a
    TCP port ``DOMAIN_PORT_BASE + id`` bound. Written out here because that package's context
    manager swallows an ``OSError`` raised inside its ``with`` block.
    """
    for candidate in random.sample(range(1, 101), 100):
        reservation = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        try:
            reservation.bind(('', DOMAIN_PORT_BASE + candidate))
        except OSError:
            reservation.close()
            continue
        try:
            yield candidate
        finally:
            reservation.close()
        return
    raise RuntimeError('no free ROS domain ID between 1 and 100')


def find_executable(name: str) -> str:
    """
    Path of one of the package's console scripts.

    Looks beside the running interpreter (a venv's ``bin/``), on ``PATH``, then in the
    package's ``lib/stewart_kinematics/`` (where colcon installs them for ``ros2 run``). A name
    with a slash is a path, taken as it is (as a shell does).

    :raises FileNotFoundError: naming the places searched.
    """
    if os.sep in name:
        if Path(name).is_file() and os.access(name, os.X_OK):
            return name
        raise FileNotFoundError(f'executable {name!r} not found or not executable')
    candidates = [Path(sys.executable).parent / name]
    on_path = shutil.which(name)
    if on_path:
        candidates.append(Path(on_path))
    candidates.append(_package_prefix() / 'lib' / 'stewart_kinematics' / name)
    for candidate in candidates:
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return str(candidate)
    raise FileNotFoundError(
        f'executable {name!r} not found in {", ".join(str(c.parent) for c in candidates)} '
        'or on PATH: install the package first (scripts/setup_venv.sh or colcon build)')


def _package_prefix() -> Path:
    """Return the install prefix of the package: its colcon install folder, or sys.prefix."""
    try:
        from ament_index_python.packages import get_package_prefix
        return Path(get_package_prefix('stewart_kinematics'))
    except (ImportError, LookupError, OSError, ValueError):
        # Not in an ament index (AMENT_PREFIX_PATH unset, or a plain pip install).
        return Path(sys.prefix)


class NodeProcess:
    """
    A node's console script running as a child process, with its output kept.

    :param executable: console script name, such as ``ik_node``.
    :param arguments: command-line arguments, such as ``['--ros-args', '--params-file', f]``.
    :param env: environment; default the current one.
    """

    def __init__(self, executable, arguments=(), env=None):
        self.name = executable
        self.command = [find_executable(executable), *arguments]
        self._output = tempfile.TemporaryFile()
        self.process = subprocess.Popen(
            self.command, env=env, stdout=self._output, stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL)

    def running(self) -> bool:
        """Whether the process has not exited yet."""
        return self.process.poll() is None

    def send_signal(self, signal_number):
        """Send a signal to the process if it is still running."""
        if self.running():
            self.process.send_signal(signal_number)

    def stop(self, timeout=STOP_TIMEOUT) -> int:
        """
        Stop with SIGINT as Ctrl-C would, then kill after ``timeout`` seconds.

        SIGINT lets Fast DDS remove its shared-memory files, which SIGKILL would leave behind.

        :returns: the exit code (negative: killed by that signal).
        """
        self.send_signal(signal.SIGINT)
        try:
            return self.process.wait(timeout)
        except subprocess.TimeoutExpired:
            self.process.kill()
            return self.process.wait()

    def output(self) -> str:
        """Everything the process wrote to stdout and stderr so far."""
        # pread leaves the file position alone: the child writes through the same position.
        descriptor = self._output.fileno()
        return os.pread(descriptor, os.fstat(descriptor).st_size, 0).decode(errors='replace')

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.stop()
        self._output.close()
