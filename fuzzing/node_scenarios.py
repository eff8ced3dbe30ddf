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
The node fuzzer's scenarios: the generators of :mod:`fuzzing.scenarios` played against a node.

After its flood, :func:`fuzzing.node_fuzzer.fuzz_node` plays a node's scenario
(:data:`SCENARIOS`) when asked (``FuzzSettings.scenarios``, ``--scenarios``):

- **trajectory_node**: a parameter request for a low ``validation_rate`` (1 to 5 Hz, with
  ``retime`` off), then a bulging ``pose_trajectory`` (:func:`~fuzzing.scenarios.
  bulging_trajectory`), alternately beyond the stroke and just inside it, each waited for. Every
  ``leg_trajectory`` the node publishes is checked point by point by the output invariants.
- **motion_cueing_node**, on simulated time in **lockstep** with the fuzzer: for each
  ``vehicle_imu`` sample the fuzzer publishes ``/clock`` ``t``, waits until the node's clock
  reads ``t`` (the stamp of the ``/parameter_events`` message a parameter request makes the node
  publish: the node's own clock, read in its own executor; retried until it is ``t``), sends the
  sample, and waits for its ``target_pose``. So every command's send time is known exactly,
  and the leg rates between consecutive ``target_pose`` messages are checked as the command
  gate promises them (:class:`~fuzzing.stream_rates.LegRateStream`, without jerk). Bursts of
  noisy samples (:class:`~fuzzing.scenarios.ImuStream`) from rest, and a recording played ten
  times fast; between bursts the clock runs ten times fast until the node's watchdog has
  eased the platform home. A command found beyond a rate is allowed only as one of the
  node's ``command_braking`` findings on ``/diagnostics`` during the lockstep.

Why the lockstep: ``target_pose`` carries no stamp, and the node's clock is what its gate
times the commands by. A message's arrival tells nothing exact about when it was sent, and
``/clock`` and ``vehicle_imu`` are two topics that DDS does not order between them: without
the proof that the node's clock reads ``t``, a sample could be handled at the clock before,
and a correct node would look as if it had stopped its legs in one step.
"""

from dataclasses import dataclass, field
import threading
import time
from typing import Callable, Dict, List, Optional

from fuzzing.fuzz_parameters import EITHER, parameter_message, ParameterChange, python_value
from fuzzing.scenarios import bulging_trajectory, FAST_FACTOR, ImuStream
from fuzzing.stream_rates import allowance_problems, braking_allowance, LegRateStream
from geometry_msgs.msg import Pose
import numpy as np
from rcl_interfaces.msg import ParameterEvent, ParameterType
from rcl_interfaces.srv import GetParameters, SetParameters
from rclpy.parameter import Parameter
from rclpy.qos import qos_profile_parameter_events
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Trigger

from stewart_kinematics.model.frames import Transform
from stewart_kinematics.model.inverse import leg_vectors
from stewart_kinematics.model.rotations import normalize_quaternion, quaternion_to_matrix
from stewart_kinematics.parameters import (
    FRAME_PARAMETERS,
    frames_from_parameters,
    read_parameter_files,
)
from trajectory_msgs.msg import JointTrajectory

#: Where the fuzzer's simulated clock starts, nanoseconds.
SIM_TIME_START_NS = 1000 * 1_000_000_000
#: Period of the free-running simulated clock, seconds of wall time.
CLOCK_PERIOD = 0.01
#: Steps of the lockstep, nanoseconds (100 Hz, as the adversarial pass sent its samples).
LOCKSTEP_STEP_NS = 10_000_000
#: Seconds to wait for the node's clock to read a time, for an output, or for an answer.
STEP_DEADLINE = 5.0
#: Seconds between two tries to see the node's clock read a time (a /clock message may be
#: lost: its subscription is best effort).
PROBE_RETRY = 0.2
#: How much faster than wall time the clock runs while the node eases home between bursts.
EASING_SPEED_UP = 10.0
#: Seconds of wall time without a target_pose after which the node is taken to rest; the
#: longest wait for it.
QUIET_SECONDS = 0.3
QUIET_DEADLINE = 30.0
#: Samples of each noisy burst, and of each fast recording.
BURST_STEPS = 250
RECORDING_STEPS = 200
#: Seconds between two looks at a condition nothing notifies.
POLL_PERIOD = 0.02
#: Seconds to wait for trajectory_node to answer one trajectory.
TRAJECTORY_DEADLINE = 10.0


class SimClock:
    """
    The fuzzer's ``/clock`` for a node on simulated time: free-running, or set step by step.

    Free-running, it publishes every :data:`CLOCK_PERIOD` of wall time, ``speed_up`` times as
    fast as wall time; paused, only :meth:`publish` moves it. It never goes back.

    :param node: the fuzzer's rclpy node.
    :param start_ns: the first time, nanoseconds.
    """

    def __init__(self, node, start_ns: int = SIM_TIME_START_NS):
        self.publisher = node.create_publisher(Clock, '/clock', 10)
        self.now_ns = start_ns
        self.speed_up = 1.0
        self._running = threading.Event()
        self._stop = threading.Event()
        self._lock = threading.Lock()
        self._thread = threading.Thread(target=self._run, name='fuzz_sim_clock', daemon=True)
        self.resume()
        self._thread.start()

    def _run(self):
        last = time.monotonic()
        while not self._stop.wait(CLOCK_PERIOD):
            now = time.monotonic()
            if self._running.is_set():
                with self._lock:
                    self.now_ns += max(1, int((now - last) * self.speed_up * 1e9))
                    self._send(self.now_ns)
            last = now

    def _send(self, ns: int):
        message = Clock()
        message.clock.sec, message.clock.nanosec = divmod(ns, 1_000_000_000)
        self.publisher.publish(message)

    def pause(self) -> int:
        """Stop running free; return the last time published, nanoseconds."""
        self._running.clear()
        with self._lock:
            return self.now_ns

    def resume(self, speed_up: float = 1.0):
        """Run free again from the last time, ``speed_up`` times as fast as wall time."""
        with self._lock:
            self.speed_up = speed_up
        self._running.set()

    def publish(self, ns: int):
        """Publish the time ``ns`` (paused: the lockstep's step), never one before the last."""
        with self._lock:
            self.now_ns = max(self.now_ns, ns)
            self._send(self.now_ns)

    def close(self):
        """Stop the thread."""
        self._stop.set()
        self._thread.join()


class Waiter:
    """A condition the fuzzer's callbacks notify, to wait for outputs without polling."""

    def __init__(self):
        self.condition = threading.Condition()

    def notify(self):
        """Wake the waiting thread."""
        with self.condition:
            self.condition.notify_all()

    def wait(self, predicate: Callable[[], bool], timeout: float) -> bool:
        """
        Wait until ``predicate()`` holds, ``timeout`` seconds at most; return whether it does.

        Woken by :meth:`notify`, and every :data:`POLL_PERIOD` for what notifies nobody (the
        diagnostics log).
        """
        end = time.monotonic() + timeout
        with self.condition:
            while not predicate():
                remaining = end - time.monotonic()
                if remaining <= 0.0:
                    return bool(predicate())
                self.condition.wait(min(remaining, POLL_PERIOD))
            return True


class NodeClock:
    """
    What a node's clock reads, seen through the stamps of its ``/parameter_events``.

    rclpy stamps a parameter event with the node's clock when it handles a parameter request,
    in the node's executor; setting ``use_sim_time`` to ``true`` on a node already on simulated
    time changes nothing else.

    :param client: the fuzzer's :class:`~fuzzing.fuzz_client.SpinningClient`.
    :param node_name: the node's full name (``/motion_cueing_node``).
    :param waiter: the :class:`Waiter` to notify.
    """

    def __init__(self, client, node_name: str, waiter: Waiter):
        self.node_name = node_name
        self.waiter = waiter
        self.stamp_ns: Optional[int] = None
        self.events = 0
        self.service = client.node.create_client(SetParameters, f'{node_name}/set_parameters')
        self.request = SetParameters.Request(parameters=[
            Parameter('use_sim_time', value=True).to_parameter_msg()])
        client.node.create_subscription(ParameterEvent, '/parameter_events', self._on_event,
                                        qos_profile_parameter_events)

    def _on_event(self, event):
        if event.node == self.node_name:
            self.stamp_ns = event.stamp.sec * 1_000_000_000 + event.stamp.nanosec
            self.events += 1
            self.waiter.notify()

    def reach(self, clock: SimClock, ns: int, deadline: float = STEP_DEADLINE) -> bool:
        """
        Publish ``ns`` on /clock until the node's clock is seen to read it exactly.

        :returns: whether it did within ``deadline`` seconds.
        """
        end = time.monotonic() + deadline
        while time.monotonic() < end:
            clock.publish(ns)
            seen = self.events
            self.service.call_async(self.request)
            self.waiter.wait(lambda: self.events > seen, PROBE_RETRY)
            if self.stamp_ns == ns:
                return True
        return False


@dataclass
class ScenarioRun:
    """
    What the fuzzer gives a scenario: the node, its inputs, the checks, and the report.

    :param node_name: the node's full name.
    :param client: the fuzzer's spinning client.
    :param process: the node's :class:`~stewart_kinematics.tools.node_processes.NodeProcess`.
    :param inputs: the fuzzer's publisher of each input topic, by topic.
    :param services: the node's parameter services (:func:`~fuzzing.parameter_requests.
        parameter_clients`).
    :param requests: the run's :class:`~fuzzing.parameter_requests.ParameterRequests`.
    :param invariants: the output checks.
    :param diagnostics: the run's :class:`~fuzzing.fuzz_client.DiagnosticsLog`.
    :param report: the :class:`~fuzzing.node_fuzzer.FuzzReport`: ``sent``, ``problems`` and
        ``scenario`` (lines in words) grow.
    :param rng: the run's random generator.
    :param files: the node's parameter files.
    :param clock: the simulated clock, for a node on simulated time.
    """

    node_name: str
    client: object
    process: object
    inputs: Dict[str, object]
    services: dict
    requests: object
    invariants: object
    diagnostics: object
    report: object
    rng: object
    files: list
    clock: Optional[SimClock] = None
    #: Set by a scenario: problems found only once the node's counters are final.
    finish: List[Callable[[], List[str]]] = field(default_factory=list)

    def sent(self, topic: str) -> None:
        """Count one message sent to ``topic``."""
        self.report.sent[topic] = self.report.sent.get(topic, 0) + 1

    def values(self, names) -> dict:
        """Return the node's values of ``names`` now (get_parameters), over its files' values."""
        values = dict(read_parameter_files(self.files, self.node_name.strip('/')))
        answer = self.client.call(self.services[GetParameters],
                                  GetParameters.Request(names=list(names)), STEP_DEADLINE)
        if answer is not None:
            for name, value in zip(names, answer.values):
                if value.type != ParameterType.PARAMETER_NOT_SET:
                    values[name] = python_value(value)
        return values


def _change(name: str, type_code: int, value) -> ParameterChange:
    """Return a valid parameter change (either answer allowed, the held value tracked)."""
    return ParameterChange(parameter_message(name, type_code, value), EITHER, 'scenario',
                           value=value)


def trajectory_scenario(run: ScenarioRun, rounds: int) -> None:
    """
    Low validation rates and bulging trajectories, beyond the stroke and inside it, in turn.

    Each round: for each of a trajectory beyond the stroke and one inside it (in a drawn
    order), a request for a drawn validation_rate (with ``retime`` off and ``speed_scale`` 1),
    then the trajectory, waited for until the node counts it or publishes it.
    """
    names = [spec.name for spec in FRAME_PARAMETERS]
    values = run.values(names)
    frames = frames_from_parameters(values)
    base_frame = values.get('base_frame') or 'stewart_base'
    invariants = run.invariants
    publisher = run.inputs['pose_trajectory']
    status = f'{run.node_name}: pose_trajectory'
    waiter = Waiter()
    outputs = []
    run.client.node.create_subscription(
        JointTrajectory, 'leg_trajectory',
        lambda message: (outputs.append(message), waiter.notify()), 10)
    cases = []
    for _ in range(rounds):
        order = [True, False]
        run.rng.shuffle(order)
        for beyond in order:
            message, case = bulging_trajectory(run.rng, invariants.geometry,
                                               invariants.actuator_limits, frames,
                                               beyond=beyond, frame_id=base_frame)
            run.requests.send(run.services[SetParameters], [
                _change('validation_rate', ParameterType.PARAMETER_DOUBLE, case.validation_rate),
                _change('retime', ParameterType.PARAMETER_BOOL, False),
                _change('speed_scale', ParameterType.PARAMETER_DOUBLE, 1.0)], False)
            run.client.wait(run.requests.done, STEP_DEADLINE, [run.process])
            before = _received(run.diagnostics, run.node_name, status)
            published = len(outputs)
            publisher.publish(message)
            run.sent('pose_trajectory')
            cases.append(case)
            # Answered: published, or counted by the next report (once a second).
            waiter.wait(lambda: len(outputs) > published or _received(
                run.diagnostics, run.node_name, status) > before, TRAJECTORY_DEADLINE)
    beyond = [case for case in cases if case.beyond]
    inside = [case for case in cases if not case.beyond]
    run.report.scenario.append(
        f'bulging trajectories at validation_rate {min(c.validation_rate for c in cases):.2f} '
        f'to {max(c.validation_rate for c in cases):.2f} Hz: {len(beyond)} beyond the stroke '
        f'(by {_range_mm(c.peak_excess for c in beyond)} mm), {len(inside)} inside it (by '
        f'{_range_mm(-c.peak_excess for c in inside)} mm); {len(outputs)} leg_trajectory '
        'published')
    run.report.scenario += [f'  {case.describe()}' for case in cases]


def _received(diagnostics, node_name: str, status: str) -> int:
    """Return the ``received`` counter of a node's status in its latest report (0: none)."""
    return diagnostics.reports(node_name).latest.get(status, {}).get('received', 0)


def _range_mm(values) -> str:
    values = [value * 1e3 for value in values]
    return f'{min(values):.3f} to {max(values):.3f}' if values else '-'


def noisy_imu_scenario(run: ScenarioRun, rounds: int) -> None:
    """Play ``rounds`` bursts of :data:`BURST_STEPS` noisy samples, each from rest, in lockstep."""
    cueing_scenario(run, [('noise', BURST_STEPS, 1.0)] * rounds)


def fast_recording_scenario(run: ScenarioRun, rounds: int) -> None:
    """Play ``rounds`` recordings of :data:`RECORDING_STEPS` samples stamped ten times fast."""
    cueing_scenario(run, [('recording', RECORDING_STEPS, FAST_FACTOR)] * rounds)


def cueing_scenario(run: ScenarioRun, bursts) -> None:
    """
    Bursts of IMU samples, each from rest, in lockstep with the node's simulated clock.

    :param bursts: ``(kind, samples, speed_up)`` each: an :class:`ImuStream` kind, how many
        samples, 10 ms of the clock apart, and how much faster their stamps run.

    Before each burst the washout is reset (the ``reset`` service), the clock runs fast until
    the node has eased the platform home, and the washout is reset again: each burst starts as
    on a fresh node. Each ``target_pose`` goes to a
    :class:`LegRateStream` with its exact send time.
    """
    clock = run.clock
    if clock is None:
        raise ValueError('the cueing scenario needs the node on simulated time')
    names = [spec.name for spec in FRAME_PARAMETERS] + [
        'max_specific_force', 'max_angular_velocity', 'vehicle_frame']
    values = run.values(names)
    frames = frames_from_parameters(values)
    invariants = run.invariants
    waiter = Waiter()
    poses = []
    run.client.node.create_subscription(
        Pose, 'target_pose', lambda message: (poses.append(message), waiter.notify()), 100)
    probe = NodeClock(run.client, run.node_name, waiter)
    if not probe.service.wait_for_service(timeout_sec=STEP_DEADLINE):
        run.report.problems.append(f'{run.node_name} did not offer set_parameters')
        return
    publisher = run.inputs['vehicle_imu']
    stream = LegRateStream(invariants.actuator_limits, False,
                           (0.0, SIM_TIME_START_NS * 1e-9), 'target_pose')
    before = None
    lost = []
    stamp = 0
    reset = run.client.node.create_client(Trigger, 'reset')
    # The flood called every service, stop among them: let a stop reach park, then start
    # (a start runs from park to neutral as the bursts' easing lets the clock run).
    _ease_home(run, clock, poses, waiter)
    run.client.call(run.client.node.create_client(Trigger, 'start'), Trigger.Request(),
                    STEP_DEADLINE)
    for kind, steps, speed_up in bursts:
        # From rest, the washout reset to take the first sample as it is: what a fresh node
        # starts from (reset before easing too: the platform goes home sooner).
        run.client.call(reset, Trigger.Request(), STEP_DEADLINE)
        _ease_home(run, clock, poses, waiter)
        run.client.call(reset, Trigger.Request(), STEP_DEADLINE)
        if before is None:
            before = braking_allowance(run.diagnostics.reports(run.node_name).latest)
        start = clock.pause()
        stream.reset()   # the watchdog's last commands were sent at times not known here
        samples = ImuStream(run.rng, kind, values.get('max_specific_force', 100.0),
                            values.get('max_angular_velocity', 20.0))
        frame_id = run.rng.choice(['', values.get('vehicle_frame') or ''])
        # The samples' stamps: from now, and after every stamp sent before (a time line).
        stamp = max(_wall_ns(), stamp + 1_000_000_000)
        for step in range(1, steps + 1):
            ns = start + step * LOCKSTEP_STEP_NS
            if not probe.reach(clock, ns):
                lost.append(f"{kind}: the node's clock did not read {ns * 1e-9:.3f} s within "
                            f'{STEP_DEADLINE} s')
                break
            count = len(poses)
            publisher.publish(samples.message(
                stamp + int(step * LOCKSTEP_STEP_NS * speed_up), frame_id))
            run.sent('vehicle_imu')
            if not waiter.wait(lambda: len(poses) > count, STEP_DEADLINE):
                lost.append(f'{kind}: no target_pose for the sample at {ns * 1e-9:.3f} s')
                break
            if len(poses) != count + 1:
                lost.append(f'{kind}: {len(poses) - count} target_pose for one sample')
                break
            stream.add(ns, pose_lengths(invariants.geometry, frames, poses[-1]))
        stamp += int(steps * LOCKSTEP_STEP_NS * speed_up)
        clock.resume()
    # A sample without a target_pose is not a problem in itself (a braking command whose pose
    # cannot be found is not sent: the last command stands), but the lockstep of its burst ends
    # there: a late output would be taken for the next sample's.
    played = ', '.join(f'{kind} x{speed_up:g} {steps}' for kind, steps, speed_up in bursts)
    run.report.scenario.append(
        f'lockstep {played}: {stream.checked} target_pose checked for their leg rates, '
        f'{stream.violations} beyond' + (f'; lockstep ended early ({"; ".join(lost)})'
                                         if lost else ''))

    def finish():
        allowed = braking_allowance(run.diagnostics.reports(run.node_name).latest) - (before or 0)
        return allowance_problems(stream.violations, allowed, stream.problems,
                                  f'{run.node_name} target_pose in lockstep')
    run.finish.append(finish)


def pose_lengths(geometry, frames, message: Pose) -> np.ndarray:
    """
    Return the leg lengths a ``target_pose`` message commands, metres, shape (6,).

    As ik_node reads it: the quaternion normalised, the tool frame's pose (base frame) moved
    to the platform frame's through ``frames``.
    """
    point, orientation = message.position, message.orientation
    rotation = quaternion_to_matrix(normalize_quaternion(
        [orientation.x, orientation.y, orientation.z, orientation.w]))
    platform = frames.platform_from_tool(Transform(np.array([point.x, point.y, point.z]),
                                                   rotation))
    return np.linalg.norm(leg_vectors(geometry, platform.position, platform.rotation), axis=-1)


def _ease_home(run: ScenarioRun, clock: SimClock, poses, waiter: Waiter) -> None:
    """Let the clock run fast until the node has sent no target_pose for a while (at rest)."""
    clock.resume(EASING_SPEED_UP)
    end = time.monotonic() + QUIET_DEADLINE
    while time.monotonic() < end:
        count = len(poses)
        if not waiter.wait(lambda: len(poses) > count, QUIET_SECONDS):
            break


def _wall_ns() -> int:
    """Return the wall time, nanoseconds (the samples' stamps start there)."""
    return time.time_ns()


@dataclass(frozen=True)
class Scenario:
    """
    One scenario of a node.

    :param name: its name (``--scenario``).
    :param play: ``play(run, rounds)``.
    :param sim_time: whether the node must run on the fuzzer's simulated clock.
    :param what: what it plays, in words (the docs).
    """

    name: str
    play: Callable[[ScenarioRun, int], None]
    sim_time: bool
    what: str


#: Each node's scenarios, in the order they are played.
SCENARIOS = {
    'trajectory_node': (
        Scenario('bulging_trajectories', trajectory_scenario, False,
                 'a low validation_rate, then a bulging pose_trajectory, beyond the stroke '
                 'and inside it in turn'),),
    'motion_cueing_node': (
        Scenario('noisy_imu', noisy_imu_scenario, True,
                 f'{BURST_STEPS} noisy vehicle_imu samples from rest at 100 Hz, in lockstep'),
        Scenario('fast_recording', fast_recording_scenario, True,
                 f'{RECORDING_STEPS} samples of a recording stamped ten times as fast as they '
                 'are sent, in lockstep')),
}


def scenario_names() -> List[str]:
    """Return the name of every scenario of every node."""
    return [scenario.name for scenarios in SCENARIOS.values() for scenario in scenarios]
