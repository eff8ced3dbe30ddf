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
The newest trajectory wins: planning one message at a time, in a thread of its own.

trajectory_node checks and times a trajectory in a :class:`PlanningWorker`, never in its
executor, so that it answers parameters, services and diagnostics, and takes new messages,
while a long trajectory is checked. The worker's policy:

- The newest job wins. :meth:`PlanningWorker.submit` makes a job the next one: a job still
  waiting is answered ``superseded`` at once (on the caller's thread), and the one running is
  cancelled (its work stops at its next step, about 0.1 s:
  :class:`~stewart_kinematics.motion.retiming.Cancelled`) and answered ``superseded`` too.
- Every job gets exactly one answer, a :class:`PlanningAnswer` (a
  :class:`~stewart_kinematics.findings.Decision`): the plan, accepted or refused with the
  planner's reason; ``invalid_trajectory`` for a message that cannot be converted;
  ``superseded``; or ``planning_error`` for an unexpected error in the work (a bug: the thread
  goes on).
- Answers go back through ``deliver``, the caller's way to have a function called on the thread
  that publishes (trajectory_node: its executor, :func:`stewart_kinematics.ros.node_main.
  hand_to_executor`); that function calls ``on_done(answer)`` for each finished job, in order.
  When ``deliver`` cannot hand it over (it returns False, or raises), the answers wait for
  the next hand-over.
- :meth:`PlanningWorker.close` cancels the work under way and waits at most
  :data:`WORKER_STOP_TIMEOUT` for the thread (a daemon, so it never holds up an exit);
  nothing is answered after it.

The thread runs below the caller's priority (:data:`WORKER_NICENESS`, on Linux, which gives
each thread its own niceness): on a busy machine the node's callbacks come first. Nothing here
imports ROS.
"""

from dataclasses import dataclass, field
import os
import threading
from typing import Any, Callable, Optional, Tuple

from stewart_kinematics.findings import (
    Decision,
    Finding,
    INVALID_TRAJECTORY,
    PLANNING_ERROR,
    SUPERSEDED,
)
from stewart_kinematics.motion.retiming import Cancelled

#: Longest :meth:`PlanningWorker.close` waits for the worker to leave the step it is in,
#: seconds (then it leaves it behind: a daemon thread, whose answer is never delivered).
WORKER_STOP_TIMEOUT = 0.25
#: Scheduling priority of the planning thread below its caller's (nice(2) increment).
WORKER_NICENESS = 10


@dataclass(eq=False)
class PlanningJob:
    """
    One message to plan in the worker.

    :param name: what the job is, for its answers (trajectory_node: the input's name,
        ``pose_trajectory`` or ``pose_path``).
    :param plan: ``plan(cancel) -> MotionPlan``: converts the message and plans it; raises
        ``ValueError`` for a message that cannot be converted, and
        :class:`~stewart_kinematics.motion.retiming.Cancelled` when ``cancel`` is set.
    :param prepare: ``prepare(verdict)``, or ``None``: the message of an accepted plan's
        command (its :class:`~stewart_kinematics.limits.TrajectoryCommand`), built in the
        worker.
    :param context: whatever the caller wants back with the answer (trajectory_node: the
        input's accounting and the settings the message arrived with).
    :param cancel: set to stop the work at its next step.
    """

    name: str
    plan: Callable
    prepare: Optional[Callable] = None
    context: Any = None
    cancel: threading.Event = field(default_factory=threading.Event)

    def run(self) -> 'PlanningAnswer':
        """
        Plan, then prepare the message of an accepted plan (worker thread).

        :returns: the :class:`PlanningAnswer`; ``invalid_trajectory`` for a message that
            cannot be converted.
        :raises Cancelled: when ``cancel`` is set meanwhile.
        """
        try:
            plan = self.plan(self.cancel)
        except ValueError as error:   # the message cannot be converted
            return PlanningAnswer(self, refusal=Finding(INVALID_TRAJECTORY, str(error)))
        if not plan.accepted:
            return PlanningAnswer(self, plan, refusal=plan.refusal, warnings=plan.warnings)
        prepared = None if self.prepare is None else self.prepare(plan.command)
        return PlanningAnswer(self, plan, prepared, warnings=plan.warnings)

    def superseded(self) -> 'PlanningAnswer':
        """Return the answer of this job when a newer one replaced it."""
        return PlanningAnswer(self, refusal=Finding(
            SUPERSEDED, f'{self.name}: replaced by a newer trajectory or path before it was '
            'decided'))


@dataclass(frozen=True, eq=False)
class PlanningAnswer(Decision):
    """
    The answer to one :class:`PlanningJob`: its plan, or why there is none to publish.

    :param job: the job answered.
    :param plan: the :class:`~stewart_kinematics.motion.planning.MotionPlan`, or ``None``
        when none was made (not converted, superseded, an error).
    :param prepared: what ``job.prepare`` made of an accepted plan's command, or ``None``.
    :param refusal: ``None`` when the plan was accepted; else the plan's refusal,
        ``invalid_trajectory``, ``superseded`` or ``planning_error``.
    :param warnings: the plan's warnings.
    """

    job: PlanningJob
    plan: Optional[Any] = None
    prepared: Optional[Any] = None
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()


class PlanningWorker:
    """
    A thread that plans one job at a time; the newest replaces the rest (see the module).

    :param deliver: ``deliver(task) -> bool``: have ``task()`` called on the thread that
        publishes; returns whether it was handed over. Called from the worker thread.
    :param on_done: ``on_done(answer)``, called with each :class:`PlanningAnswer`: by
        ``task()`` for a planned job, on the caller's thread for one superseded while waiting.
    :param warm_up: ``warm_up()``, or ``None``: work to do once, in a thread of its own, beside
        the first plans (trajectory_node: importing the retiming, seconds, now rather than in
        the first plan that needs it). Its errors are ignored: the plan that needs it says why.
    :param name: the thread's name.
    """

    def __init__(self, deliver: Callable[[Callable[[], None]], bool],
                 on_done: Callable[[PlanningAnswer], None], *,
                 warm_up: Optional[Callable[[], Any]] = None, name: str = 'planning'):
        self.deliver = deliver
        self.on_done = on_done
        self._condition = threading.Condition()
        self._next = None
        self._running = None
        self._answers = []
        self._closed = False
        if warm_up is not None:
            threading.Thread(target=_ignoring_errors, args=(warm_up,), name=f'{name} warm-up',
                             daemon=True).start()
        self._thread = threading.Thread(target=self._serve, name=name, daemon=True)
        self._thread.start()

    @property
    def running(self) -> Optional[PlanningJob]:
        """Return the job being planned now, or ``None``."""
        with self._condition:
            return self._running

    def submit(self, job: PlanningJob) -> None:
        """Plan ``job`` next: it replaces a job waiting, and cancels the one running."""
        with self._condition:
            if self._closed:
                replaced = job
            else:
                replaced, self._next = self._next, job
                if self._running is not None:
                    self._running.cancel.set()
                self._condition.notify()
        if replaced is not None:
            self.on_done(replaced.superseded())

    def _serve(self):
        try:
            os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), WORKER_NICENESS)
        except (AttributeError, OSError):  # not Linux: the thread runs at the caller's priority
            pass
        while True:
            with self._condition:
                while self._next is None and not self._closed:
                    self._condition.wait()
                if self._closed:
                    return
                job, self._next = self._next, None
                self._running = job
            answer = _answer(job)
            with self._condition:
                self._running = None
                if self._closed:
                    return
                self._answers.append(answer)
                # Under the lock: close() marks the worker closed only after it.
                _hand_over(self.deliver, self._deliver)

    def _deliver(self):
        """Hand the finished answers to ``on_done`` (the thread that publishes)."""
        with self._condition:
            if self._closed:   # a task handed over before the worker was closed
                return
            answers, self._answers = self._answers, []
        for answer in answers:
            self.on_done(answer)

    def close(self) -> Optional[PlanningJob]:
        """
        Cancel the work under way and stop the thread; nothing is answered after.

        :returns: the job that was being planned (now cancelled), or ``None``.
        """
        with self._condition:
            self._closed = True
            cancelled = self._running
            if cancelled is not None:
                cancelled.cancel.set()
            self._condition.notify()
        self._thread.join(WORKER_STOP_TIMEOUT)
        return cancelled


def _answer(job: PlanningJob) -> PlanningAnswer:
    """Run a job: its answer, whatever happens in the work."""
    try:
        return job.run()
    except Cancelled:
        return job.superseded()
    except Exception as error:  # noqa: B902 - a bug must not leave messages unanswered
        return PlanningAnswer(job, refusal=Finding(
            PLANNING_ERROR, f'planning failed unexpectedly: {type(error).__name__}: {error}'))


def _hand_over(deliver, task) -> bool:
    """Hand ``task`` over; a hand-over that fails (an executor shut down) keeps the answers."""
    try:
        return bool(deliver(task))
    except Exception:  # noqa: B902 - the worker thread must live on to answer the next jobs
        return False


def _ignoring_errors(work):
    """Run ``work()``; an error is left to the work that needs it to report."""
    try:
        work()
    except Exception:  # noqa: B902 - the plan that needs it reports the error
        pass
