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
The assembly-mode margin computed beside a node: in a worker thread or a worker process.

:class:`AssemblyModeMarginMonitor` runs :func:`~stewart_kinematics.assembly_mode_margin` (the
distance to the nearest other real assembly mode within the limits, milliseconds to tens of
them) off the message path: fk_node asks for the margin of its latest solution at its status
rate and reads the latest result when it reports. A worker process ends with its owner
(:mod:`.owner_watch`). Nothing here imports ROS.
"""

from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from concurrent.futures.process import BrokenProcessPool
import math
import multiprocessing
import os
import signal
import time
from typing import Optional

import numpy as np

from stewart_kinematics.analysis.assembly_modes import assembly_mode_margin, AssemblyModeMargin
from stewart_kinematics.analysis.homotopy import geometry_start_system
from stewart_kinematics.workers.owner_watch import exit_with_owner


class AssemblyModeMarginMonitor:
    """
    The assembly-mode margin of a tracker's latest solution, computed in the background.

    Finding every mode takes milliseconds to tens of them, too long for a message callback:
    fk_node calls :meth:`request` at its status rate with the last solution, which starts one
    computation in the worker unless one is running or the lengths have not changed, and reads
    :attr:`latest` when it reports. The solutions keep flowing meanwhile.

    The worker is a thread, or with ``worker='process'`` a process of its own (started by
    ``forkserver``, at a lower priority, ignoring SIGINT: its owner stops it). fk_node takes the
    process: a computing thread holds the interpreter lock, and the thread that runs the
    message callbacks then waits for it at each hand-over, up to the interpreter's switch
    interval (5 ms): with a computing thread, the callbacks' wake-ups are late by about that
    interval at the 99th percentile, instead of a small fraction of it without the thread.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param warning_distance: a margin (the combined distance of :func:`pose_distance`)
        below this, metres, is worth a warning; 0 for none.
    :param worker: ``'thread'`` or ``'process'`` (:data:`MARGIN_WORKERS`).
    :raises ValueError: for another ``worker``.
    """

    def __init__(self, geometry, warning_distance=0.0, worker='thread'):
        if worker not in MARGIN_WORKERS:
            raise ValueError(f'worker must be one of {MARGIN_WORKERS}, got {worker!r}')
        self.geometry = geometry
        self.warning_distance = float(warning_distance)
        self.worker = worker
        #: The last margin computed, or None; with the lengths it is for, its cost, seconds,
        #: and the tag its request carried.
        self.latest: Optional[AssemblyModeMargin] = None
        self.latest_lengths = None
        self.latest_seconds = None
        self.latest_tag = None
        self._running = None
        self._running_tag = None
        self._start_worker()

    def _start_worker(self):
        """Start the worker; it builds the geometry's start systems at once (under a second)."""
        if self.worker == 'thread':
            self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix='assembly_modes')
            self._warm_up = self._pool.submit(geometry_start_system, self.geometry)
        else:
            # The process keeps the geometry (its start systems are cached by the object):
            # each request sends only a pose and lengths.
            self._pool = ProcessPoolExecutor(
                max_workers=1, mp_context=multiprocessing.get_context('forkserver'),
                initializer=_start_margin_worker, initargs=(self.geometry, os.getpid()))
            self._warm_up = self._pool.submit(int)

    def request(self, pose, lengths, tag=None) -> bool:
        """
        Start computing the margin of ``pose`` (with its ``lengths``) unless one is running.

        :param tag: anything that says which pose this is, given back with the result as
            :attr:`latest_tag` (fk_node: the tracker's ``accepted_count``, for
            :meth:`stewart_kinematics.PoseTracker.note_margin`).
        :returns: whether a computation started; none does for lengths already done.
        """
        self._collect()
        if self._running is not None or lengths is None:
            return False
        lengths = np.array(lengths, dtype=float)
        if self.latest_lengths is not None and np.array_equal(lengths, self.latest_lengths):
            return False
        geometry = self.geometry if self.worker == 'thread' else None
        try:
            self._running = self._pool.submit(
                _timed_margin, geometry, np.array(pose, dtype=float), lengths)
            self._running_tag = tag
        except BrokenProcessPool:   # the worker process died: a new one for the next request
            self._start_worker()
            return False
        return True

    def warning(self) -> str:
        """Say why the latest margin deserves a warning, or return ``''``."""
        self._collect()
        margin = self.latest
        if margin is None or not margin.distance < self.warning_distance:
            return ''
        return (f'another assembly mode within the limits lies {margin.position:.4g} m and '
                f'{math.degrees(margin.angle):.4g} deg from the estimated pose '
                f'(combined distance {margin.distance:.4g} m < {self.warning_distance:g} m): a '
                'solver thrown that far would land in it')

    def wait(self, timeout=None):
        """Wait for the running computation, if any (for tests and shutdown)."""
        if self._running is not None:
            try:
                self._running.result(timeout)
            except BrokenProcessPool:
                pass
        self._collect()

    def close(self):
        """Stop the worker (a running computation finishes first)."""
        self._pool.shutdown(wait=True, cancel_futures=True)

    def _collect(self):
        if self._running is not None and self._running.done():
            future, self._running = self._running, None
            try:
                self.latest, self.latest_lengths, self.latest_seconds = future.result()
                self.latest_tag = self._running_tag
            except BrokenProcessPool:   # the worker process died: a new one for the next
                self._start_worker()


#: Where :class:`AssemblyModeMarginMonitor` computes.
MARGIN_WORKERS = ('thread', 'process')
#: Scheduling priority of a margin worker process below its owner's (a nice(2) increment):
#: on a busy machine the owner's message callbacks run first.
MARGIN_WORKER_NICENESS = 10
#: In a margin worker process, the geometry it computes for (see _start_margin_worker).
_worker_geometry = None


def _start_margin_worker(geometry, owner_pid):
    """
    Set up a margin worker process: lower priority, no Ctrl-C, its geometry's start systems.

    :param owner_pid: the monitor's process: once it is gone (SIGKILL), the worker exits.
    """
    global _worker_geometry
    exit_with_owner(owner_pid)
    os.nice(MARGIN_WORKER_NICENESS)
    # A Ctrl-C in a terminal reaches the whole process group: the owner stops the worker.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _worker_geometry = geometry
    geometry_start_system(geometry)


def _timed_margin(geometry, pose, lengths):
    """
    Return :func:`assembly_mode_margin`, ``lengths`` and the seconds it took.

    :param geometry: the geometry, or None in a margin worker process: the process's own.
    """
    geometry = _worker_geometry if geometry is None else geometry
    start = time.perf_counter()
    margin = assembly_mode_margin(geometry, pose, lengths)
    return margin, lengths, time.perf_counter() - start
