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
Unit tests of PlanningWorker (motion/planning_worker.py): the newest trajectory wins.

The jobs' plans are stand-ins that wait on events, so that the test decides what runs when;
they stop as real plans do (:func:`~stewart_kinematics.motion.retiming.raise_if_cancelled`).
``deliver`` is a queue that the test's thread empties, as trajectory_node's executor does.
"""

import queue
import threading

import pytest

from stewart_kinematics.findings import Decision, Finding
from stewart_kinematics.motion.planning_worker import PlanningJob, PlanningWorker
from stewart_kinematics.motion.retiming import raise_if_cancelled

pytestmark = pytest.mark.core

#: Seconds any wait of these tests may take on a loaded machine before it counts as a failure.
TIMEOUT = 10.0


class Plan(Decision):
    """A stand-in MotionPlan: accepted or refused, with a command to prepare."""

    def __init__(self, refusal=None, command='command'):
        self.refusal, self.warnings, self.command = refusal, (), command


class Harness:
    """A worker whose answers the test collects, running the handed-over tasks itself."""

    def __init__(self, deliverable=True, **options):
        self.tasks = queue.Queue()
        self.answers = []
        self.deliverable = deliverable
        self.threads = []
        self.worker = PlanningWorker(self.deliver, self.on_done, **options)

    def deliver(self, task):
        self.threads.append(threading.current_thread().name)
        if not self.deliverable:
            return False
        self.tasks.put(task)
        return True

    def on_done(self, answer):
        self.answers.append(answer)

    def run_tasks(self, count=1):
        """Run ``count`` handed-over tasks, as the executor does, waiting for each."""
        for _ in range(count):
            self.tasks.get(timeout=TIMEOUT)()

    def codes(self):
        """Return the answers so far: each job's name and its refusal's code (or 'accepted')."""
        return [(answer.job.name, answer.refusal.code if answer.refusal else 'accepted')
                for answer in self.answers]


def blocked_job(name, started=None, release=None, result=None):
    """Return a job whose plan signals ``started``, then waits for ``release`` or a cancel."""
    def plan(cancel):
        if started is not None:
            started.set()
        while not (release is not None and release.is_set()):
            raise_if_cancelled(cancel)
            cancel.wait(0.01)
        return result if result is not None else Plan()
    return PlanningJob(name, plan, prepare=lambda command: f'message of {command}')


def test_an_accepted_plan_comes_back_with_its_message_prepared_in_the_worker():
    """The answer is accepted, carries the plan, and the message prepare() made off the caller."""
    harness = Harness()
    prepared_in = []

    def prepare(command):
        prepared_in.append(threading.current_thread().name)
        return f'message of {command}'
    harness.worker.submit(PlanningJob('pose_trajectory', lambda cancel: Plan(), prepare,
                                      context='mine'))
    harness.run_tasks()
    [answer] = harness.answers
    assert answer.accepted and answer.reason == ''
    assert answer.prepared == 'message of command' and answer.job.context == 'mine'
    assert prepared_in == ['planning'] and harness.threads == ['planning']
    harness.worker.close()


def test_a_refused_plan_and_a_message_that_cannot_be_converted_are_answered_with_the_reason():
    """The plan's own refusal; a ValueError while converting: invalid_trajectory, its text."""
    harness = Harness()
    refused = Finding('out_of_limits', 'leg 3 too long')
    harness.worker.submit(PlanningJob('pose_path', lambda cancel: Plan(refused)))
    harness.run_tasks()

    def broken(cancel):
        raise ValueError('points must be in time order')
    harness.worker.submit(PlanningJob('pose_trajectory', broken))
    harness.run_tasks()
    assert harness.codes() == [('pose_path', 'out_of_limits'),
                               ('pose_trajectory', 'invalid_trajectory')]
    assert harness.answers[0].refusal is refused and harness.answers[0].prepared is None
    assert harness.answers[1].reason == 'points must be in time order'
    harness.worker.close()


def test_a_newer_job_supersedes_the_one_waiting_at_once_and_cancels_the_one_running():
    """A runs; B waits; C comes: B is answered superseded at once, A is cancelled, C is planned."""
    harness = Harness()
    started = threading.Event()
    harness.worker.submit(blocked_job('A', started))
    assert started.wait(TIMEOUT)
    harness.worker.submit(blocked_job('B'))
    assert harness.codes() == []   # B waits; A runs on
    harness.worker.submit(PlanningJob('C', lambda cancel: Plan()))
    # B is answered by submit itself, on the caller's thread: no task needed.
    assert harness.codes() == [('B', 'superseded')]
    assert 'replaced by a newer trajectory or path' in harness.answers[0].reason
    harness.run_tasks()
    if len(harness.answers) < 3:
        harness.run_tasks()   # A's answer and C's may come in one task or two
    assert harness.codes() == [('B', 'superseded'), ('A', 'superseded'), ('C', 'accepted')]
    harness.worker.close()


def test_an_unexpected_error_is_answered_and_the_worker_goes_on():
    """A bug in the work (not a ValueError): planning_error with its type; the next job runs."""
    harness = Harness()

    def buggy(cancel):
        raise KeyError('oops')
    harness.worker.submit(PlanningJob('pose_trajectory', buggy))
    harness.run_tasks()
    harness.worker.submit(PlanningJob('pose_path', lambda cancel: Plan()))
    harness.run_tasks()
    assert harness.codes() == [('pose_trajectory', 'planning_error'), ('pose_path', 'accepted')]
    assert "KeyError: 'oops'" in harness.answers[0].reason
    harness.worker.close()


def test_answers_wait_while_they_cannot_be_handed_over():
    """A hand-over that fails (no executor yet) keeps the answer: it comes with the next."""
    harness = Harness(deliverable=False)
    harness.worker.submit(PlanningJob('first', lambda cancel: Plan()))
    for _ in range(int(TIMEOUT / 0.01)):
        if harness.threads:
            break
        threading.Event().wait(0.01)
    assert harness.threads and harness.tasks.empty()
    harness.deliverable = True
    harness.worker.submit(PlanningJob('second', lambda cancel: Plan()))
    harness.run_tasks()
    assert harness.codes() == [('first', 'accepted'), ('second', 'accepted')]
    harness.worker.close()


def test_close_cancels_the_job_running_returns_it_and_answers_nothing_more():
    """The running job stops at its next step; no answer is handed over after close."""
    harness = Harness()
    started = threading.Event()
    job = blocked_job('pose_trajectory', started)
    harness.worker.submit(job)
    assert started.wait(TIMEOUT)
    assert harness.worker.running is job
    assert harness.worker.close() is job
    assert job.cancel.is_set()
    assert harness.tasks.empty() and harness.answers == []
    assert harness.worker.close() is None   # closing twice changes nothing
    # A job given after close gets its one answer at once: nothing will plan it.
    harness.worker.submit(PlanningJob('late', lambda cancel: Plan()))
    assert harness.codes() == [('late', 'superseded')]


def test_a_task_handed_over_before_close_delivers_nothing_after_it():
    """The executor may run a task queued before the node was destroyed: it is a no-op."""
    harness = Harness()
    harness.worker.submit(PlanningJob('pose_path', lambda cancel: Plan()))
    task = harness.tasks.get(timeout=TIMEOUT)
    harness.worker.close()
    task()
    assert harness.answers == []


def test_the_warm_up_runs_beside_the_plans_and_its_error_is_ignored():
    """warm_up runs in a thread of its own; it raising neither stops nor delays the worker."""
    warmed = threading.Event()
    release = threading.Event()

    def warm_up():
        warmed.set()
        release.wait(TIMEOUT)
        raise ImportError('toppra is not installed')
    harness = Harness(warm_up=warm_up)
    assert warmed.wait(TIMEOUT)
    harness.worker.submit(PlanningJob('pose_trajectory', lambda cancel: Plan()))
    harness.run_tasks()   # planned while the warm-up still waits
    release.set()
    assert harness.codes() == [('pose_trajectory', 'accepted')]
    harness.worker.close()


def test_a_hand_over_that_raises_keeps_the_answers_and_the_worker_alive():
    """An executor shut down may raise in create_task: the next job is still planned."""
    harness = Harness()
    failed = threading.Event()

    def deliver(task):
        if not failed.is_set():
            failed.set()
            raise RuntimeError('the executor is shut down')
        return harness.deliver(task)
    harness.worker.deliver = deliver
    harness.worker.submit(PlanningJob('first', lambda cancel: Plan()))
    assert failed.wait(TIMEOUT)
    harness.worker.submit(PlanningJob('second', lambda cancel: Plan()))
    harness.run_tasks()
    assert harness.codes() == [('first', 'accepted'), ('second', 'accepted')]
    harness.worker.close()
