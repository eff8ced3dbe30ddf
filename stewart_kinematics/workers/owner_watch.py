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
The lifetime of a worker process: it ends when the process it works for is gone.

A node computes the slow analyses (workspace, assembly-mode margin) in a worker process started
by ``forkserver``. A node stopped with SIGKILL cannot stop its worker, which would then wait for
jobs forever, and keep multiprocessing's forkserver and resource tracker alive with it. So each
worker watches its owner and exits once the owner no longer runs. Standard library only.
"""

import os
import threading
import time

#: Seconds between two looks of a worker at whether its owner still runs.
OWNER_CHECK_PERIOD = 1.0


def process_running(pid: int) -> bool:
    """Whether the process ``pid`` exists (a zombie counts as gone where /proc tells)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        with open(f'/proc/{pid}/stat') as stat:
            return stat.read().rsplit(')', 1)[1].split()[0] != 'Z'
    except OSError:
        return True


def exit_with_owner(owner_pid: int, period: float = OWNER_CHECK_PERIOD) -> threading.Thread:
    """
    In a worker process: end this process within ``period`` seconds of its owner's end.

    A daemon thread looks at the owner every ``period`` seconds and ends the process with
    ``os._exit`` (no clean-up to wait for: the results have nobody to go to).

    :param owner_pid: the process the worker works for (not its parent: under ``forkserver``
        the parent is the fork server).
    :returns: the watching thread.
    """
    def watch():
        while process_running(owner_pid):
            time.sleep(period)
        os._exit(0)

    watcher = threading.Thread(target=watch, name='owner watch', daemon=True)
    watcher.start()
    return watcher
