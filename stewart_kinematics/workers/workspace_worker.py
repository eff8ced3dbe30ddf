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
A worker process that runs the workspace analyses of one geometry, for ik_node.

The workspace (:func:`~stewart_kinematics.analysis.workspace.workspace_shell`, seconds) and the
travel ranges (a fraction of one) are computed in a process of their own
(:class:`WorkspaceWorker`): a thread would share the interpreter lock with the node's executor,
and a 1 kHz command path waited up to tens of milliseconds for it on a busy machine. Nothing
here imports ROS: ``ros/workspace_publishing.py`` hands the results to the node.
"""

import multiprocessing
import os
import threading

from stewart_kinematics.workers.owner_watch import exit_with_owner

#: Scheduling priority of the worker process below the node's (nice(2) increment): on a
#: busy machine the operating system runs the command path first.
WORKER_NICENESS = 10


class WorkspaceWorker:
    """
    A process that runs functions of :mod:`stewart_kinematics.analysis.workspace` for one geometry.

    Started with the ``forkserver`` method (a clean interpreter: forking a process that runs
    DDS threads is unsafe), at a lower scheduling priority; jobs run one after the other;
    each result, or the exception as a ``RuntimeError``, goes to ``on_result(tag, value)``,
    called in a reader thread. Closing terminates the process at once, so a node never waits
    for a computation to exit. A node that dies without closing it (SIGKILL) leaves it idle:
    it then exits by itself within ``OWNER_CHECK_PERIOD`` (:mod:`.owner_watch`), and
    multiprocessing's forkserver and resource tracker after it.

    :param geometry: the :class:`stewart_kinematics.Geometry` of every job.
    :param on_result: called with each job's tag and result.
    """

    def __init__(self, geometry, on_result):
        context = multiprocessing.get_context('forkserver')
        self.jobs, self.results = context.Queue(), context.Queue()
        self.on_result = on_result
        self.process = context.Process(
            target=_serve, args=(geometry, self.jobs, self.results, os.getpid()),
            name='workspace', daemon=True)
        self.process.start()
        self.reader = threading.Thread(target=self._read, name='workspace results',
                                       daemon=True)
        self.reader.start()

    def submit(self, tag, function, *args, **kwargs):
        """
        Queue ``function(geometry, *args, **kwargs)``; ``tag`` names the job.

        :param function: a function of :mod:`stewart_kinematics.analysis.workspace` (module-level:
            it reaches the worker process pickled by its qualified name).
        """
        self.jobs.put((tag, function, args, kwargs))

    def _read(self):
        while True:
            try:
                item = self.results.get()
            except (EOFError, OSError, TypeError, ValueError):
                # The queue closed under the reader as the process exits.
                return
            if item is None:
                return
            self.on_result(*item)

    def close(self):
        """Terminate the process and the reader; jobs not finished are dropped."""
        self.process.terminate()
        self.results.put(None)
        for channel in (self.jobs, self.results):
            channel.cancel_join_thread()


def _serve(geometry, jobs, results, node_pid):
    """
    Run jobs until the node terminates the process, or is gone (the worker process's main).

    :param node_pid: the node's process: once it no longer exists, the worker exits.
    """
    # Below the node on a busy machine: the command path comes first.
    os.nice(WORKER_NICENESS)
    exit_with_owner(node_pid)
    while True:
        tag, function, args, kwargs = jobs.get()
        try:
            value = function(geometry, *args, **kwargs)
        except Exception as error:   # sent back as text: any exception pickles as this one
            value = RuntimeError(f'{type(error).__name__}: {error}')
        results.put((tag, value))
