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
Soak with faults: every node under a steady stream for minutes, while things go wrong.

Starts every node of :data:`stewart_kinematics.ros.interfaces.NODE_INTERFACES` but
telemetry_bridge (its input is a UDP socket, and the soak feeds motion_cueing_node's
``vehicle_imu`` itself; ``--nodes`` adds it) from its console script with the shipped
parameter files (as the fuzzer does: :func:`fuzzing.node_fuzzer.parameter_files`),
trajectory_node looping the
Table 3 ramp into ik_node, whose leg lengths feed fk_node. Then, for ``--minutes`` (10 by
default):

- a steady stream: plausible messages on every topic a node subscribes to and no node
  publishes (``--stream-rate`` a second each; trajectories and paths one every two seconds),
  with issue 27's cases among them (:mod:`fuzzing.scenarios`): every other trajectory bulges
  between its waypoints, beyond the stroke or just inside it, made for the low
  ``validation_rate`` (1 to 5 Hz) that half the parameter requests to trajectory_node set;
  ``vehicle_imu`` turns in windows of ``--imu-window`` seconds between plausible samples,
  noisy ones (30 m/s^2 and 5 rad/s of noise, accepted) and a recording stamped ten times as
  fast as it is sent;
- a flood of bad messages every ``--flood-every`` seconds: ``--flood-seconds`` of mutated and
  hostile messages at ``--flood-rate`` on the same topics, and ``--oversized`` oversized ones
  (the fuzzer's: a million numbers, a string of a million characters, 10^5 names or 10^4
  elements in one field), each field of each topic in turn;
- node kills: every ``--kill-every`` seconds the next node in turn gets SIGKILL or SIGTERM (in
  turn), then starts again;
- parameter changes mid-stream: one request every ``--parameter-every`` seconds to a node, valid
  and invalid changes through its parameter services, each answer checked;
- sim time: ``--sim-time`` nodes (ik_node and trajectory_node by default) run with
  ``use_sim_time:=true`` on a /clock this script publishes at 100 Hz, which jumps back and
  forth every ``--jump-every`` seconds (back 30 s, forward an hour, back an hour, forward
  11.6 days, back to the start), and now and then carries a hostile time (negative seconds,
  nanoseconds beyond a second).

ik_node streams its ``joint_commands`` at ``--command-rate``. Every message the nodes publish is
checked (:mod:`fuzzing.output_invariants`: finite, unit quaternions, strings of at most 4,000
characters, within the limits; ``joint_commands`` for the leg rates between consecutive
commands, by their stamps; a pose beyond a pose limit or a command beyond a rate allowed only
as one of the ``command_braking`` and ``returning_to_limits`` findings the nodes counted), every
node's log checked for lines longer than 4,200 characters, every node's /diagnostics counted,
and each node's resident memory sampled every ``--rss-every`` seconds. The report gives
messages in and out per node, refusals by reason, crashes (a node that exits, or prints a
traceback, when not killed by the soak; or that does not stop cleanly on SIGTERM or at the end
on SIGINT: target 0), non-finite outputs, outputs beyond a limit, long strings and long log
lines (target 0), parameter answers, kills and restarts, clock jumps, and the resident memory
of each node (start and end after a warm-up, and the slope of each run of a node: flat).
``--figure rss.png`` draws it. Exits 1 when a
target is missed. Run from the repository root::

    .venv/bin/python benchmarks/soak.py                 # 10 minutes
    .venv/bin/python benchmarks/soak.py --seconds 30    # as in the test suite
"""

import argparse
from dataclasses import dataclass, field
import fcntl
import math
import os
from pathlib import Path
import random
import signal
import sys
import threading
import time
from typing import Dict, List, Optional

from builtin_interfaces.msg import Time
import numpy as np
from rcl_interfaces.srv import SetParameters, SetParametersAtomically
import rclpy
from rosgraph_msgs.msg import Clock
from rosidl_parser import definition

from stewart_kinematics.parameters import read_parameter_files
from stewart_kinematics.ros.interfaces import NODE_INTERFACES, PUBLISHER, SUBSCRIPTION
from stewart_kinematics.tools.cli_arguments import number_in, positive_number
from stewart_kinematics.tools.node_processes import (
    find_executable,
    isolated_ros_environment,
    NodeProcess,
)
from stewart_kinematics.workers.owner_watch import process_running

# fuzzing/ is the test suite's harness, not installed: import it from the repository root.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from fuzzing.fuzz_client import (  # noqa: E402, I100 (after the path)
    descendants,
    DiagnosticsLog,
    resident_kb,
    SpinningClient,
)
from fuzzing.fuzz_messages import message_class, MessageFuzzer  # noqa: E402
from fuzzing.fuzz_parameters import (  # noqa: E402
    EITHER,
    parameter_message,
    ParameterChange,
)
from fuzzing.fuzz_targets import parameter_files, plausible_hints  # noqa: E402
from fuzzing.output_invariants import (  # noqa: E402
    allowable,
    log_problems,
    numbers_problems,
    OutputInvariants,
    StreamChecks,
    string_problems,
)
from fuzzing.parameter_requests import (  # noqa: E402
    FRAME_NAMES,
    parameter_clients,
    parameter_fuzzer_of,
    ParameterRequests,
)
from fuzzing.scenarios import (  # noqa: E402
    bulging_trajectory,
    FAST_FACTOR,
    ImuStream,
    LOW_VALIDATION_RATES,
)
from fuzzing.stream_rates import ALLOWED_CODES, braking_allowance  # noqa: E402
from rcl_interfaces.msg import ParameterType  # noqa: E402
from stewart_kinematics.ros.message_accounting import REPORT_PERIOD  # noqa: E402

#: Extra start-up arguments of some nodes: trajectory_node loops the Table 3 ramp, a row
#: every 0.2 s, so that the chain trajectory_node -> ik_node -> fk_node always has work.
NODE_ARGUMENTS = {'trajectory_node': ['-p', 'loop:=true', '-p', 'row_period:=0.2']}
#: Messages a second on a topic whose type carries a sequence of messages (a trajectory).
SEQUENCE_RATE = 0.5
#: Main loop period, seconds (the /clock rate is its inverse).
TICK = 0.01
#: Sim time at the start, seconds; and the jumps of the /clock, in turn, seconds.
SIM_TIME_START = 1000.0
CLOCK_JUMPS = (-30.0, 3600.0, -3600.0, 1e6, None)   # None: back to the start's time line
#: Hostile /clock messages, one per cycle of jumps, in turn: (sec, nanosec); each is the only
#: time on /clock for HOSTILE_CLOCK_SECONDS (rclpy's clock subscription has depth 1).
HOSTILE_CLOCKS = ((-5, 0), (0, 4_294_967_295), (2 ** 31 - 1, 999_999_999))
HOSTILE_CLOCK_SECONDS = 0.1
#: Seconds a node's run is younger than when its memory is not yet counted (imports, caches).
RSS_WARM_UP = 20.0
#: Seconds of samples after the warm-up a memory slope needs.
SLOPE_SPAN = 60.0
#: The nodes soaked by default: telemetry_bridge would publish the vehicle_imu the soak feeds
#: (the soak feeds only topics no node publishes); its UDP input has its own flood tests.
SOAKED_NODES = sorted(name for name in NODE_INTERFACES if name != 'telemetry_bridge')
#: Seconds the nodes get, after the stream, to answer what they have in hand.
SETTLE_TIMEOUT = 30.0
#: Seconds a node gets to stop on SIGTERM or SIGINT.
STOP_TIMEOUT = 10.0
#: Seconds a new run gets to report on /diagnostics before a SIGTERM or SIGINT is sent anyway.
READY_TIMEOUT = 20.0
#: Seconds the processes a stopped run started (workers) have to exit after it.
ORPHAN_GRACE = 5.0
#: Examples kept of each kind of problem.
KEPT_EXAMPLES = 5
#: The kinds of vehicle_imu samples of the steady stream, a window of each in turn.
IMU_KINDS = ('plausible', 'noise', 'recording')
#: Share of the parameter requests to trajectory_node that set a low validation_rate
#: (the first one always does).
LOW_RATE_SHARE = 0.5
#: Fast DDS shared-memory files (see test_load_and_faults.py).
SHM_DIRECTORY = Path('/dev/shm')
SHM_PREFIX = 'fastrtps_'


@dataclass
class Run:
    """One run of a node's process, from start to exit."""

    number: int
    process: NodeProcess
    started: float
    ended: Optional[float] = None
    stopped_with: str = ''
    exit_code: Optional[int] = None
    rss: List[tuple] = field(default_factory=list)

    def slope(self, second_half: bool = False) -> Optional[float]:
        """
        Return the memory growth after the warm-up, kB per minute (least squares), or None.

        :param second_half: over the second half of the run only: a node's memory climbs for a
            minute or two (imports on first use, caches, the allocator's pools), then levels
            off; a leak goes on climbing.
        """
        points = [(t, kb) for t, kb in self.rss if t - self.started >= RSS_WARM_UP]
        if second_half and points:
            middle = (points[0][0] + points[-1][0]) / 2.0
            points = [(t, kb) for t, kb in points if t >= middle]
        if len(points) < 3 or points[-1][0] - points[0][0] < SLOPE_SPAN:
            return None
        times, values = np.array(points, dtype=float).T
        return float(np.polyfit(times / 60.0, values, 1)[0])

    def warm(self):
        """Return the first and last resident memory after the warm-up, kB, or None."""
        points = [kb for t, kb in self.rss if t - self.started >= RSS_WARM_UP]
        return (points[0], points[-1]) if points else None


class Slot:
    """A node of the soak: its arguments and its runs."""

    def __init__(self, name: str, sim_time: bool, extra=(), executables: Optional[Path] = None):
        self.name = name
        self.files = parameter_files(name)
        self.arguments = ['--ros-args']
        for path in self.files:
            self.arguments += ['--params-file', str(path)]
        self.arguments += NODE_ARGUMENTS.get(name, []) + list(extra)
        if sim_time:
            self.arguments += ['-p', 'use_sim_time:=true']
        self.executable = find_executable(str(executables / name) if executables else name)
        self.runs: List[Run] = []

    @property
    def run(self) -> Run:
        """Return the current run."""
        return self.runs[-1]

    def start(self):
        """Start a new run."""
        self.runs.append(Run(len(self.runs) + 1, NodeProcess(self.executable, self.arguments),
                             time.monotonic()))


class CounterTotals:
    """Each diagnostic status's counters summed over the runs of its node."""

    def __init__(self):
        self.previous: Dict[str, Dict[str, object]] = {}
        self.latest: Dict[str, Dict[str, object]] = {}

    def update(self, latest: Dict[str, Dict[str, object]]):
        """Take a node's latest counters; a counter that went down means a new run."""
        for name, counters in latest.items():
            last = self.latest.get(name)
            if last is not None and counters['received'] < last['received']:
                self.previous[name] = _add(self.previous.get(name), last)
            self.latest[name] = counters

    def totals(self) -> Dict[str, Dict[str, object]]:
        """Return the counters of each status over every run."""
        return {name: _add(self.previous.get(name), counters)
                for name, counters in self.latest.items()}


def _add(a, b):
    if a is None:
        return b
    result = {key: a[key] + b[key] for key in ('received', 'published', 'rejected')}
    for key in ('rejected_by_code', 'warned_by_code'):
        result[key] = dict(a[key])
        for code, count in b[key].items():
            result[key][code] = result[key].get(code, 0) + count
    return result


class Soak:
    """The soak: nodes, streams, faults and what was seen."""

    def __init__(self, arguments):
        self.arguments = arguments
        self.rng = random.Random(arguments.seed)
        streaming = {'command_rate': arguments.command_rate} if arguments.command_rate else {}
        self.slots = {name: Slot(name, name in arguments.sim_time,
                                 ['-p', f'command_rate:={arguments.command_rate!r}']
                                 if name == 'ik_node' and streaming else (),
                                 arguments.executables)
                      for name in arguments.nodes}
        any_files = next(iter(self.slots.values())).files
        self.invariants = OutputInvariants.from_parameter_files(
            any_files, None, streaming if 'ik_node' in self.slots else {})
        self.hints = plausible_hints(any_files, None)
        #: The command streams among the outputs, and the outputs that may be braking
        #: commands (a pose beyond a pose limit), with examples.
        self.streams = StreamChecks(self.invariants)
        self.allowable = 0
        self.allowable_by_topic: Dict[str, int] = {}
        self.allowable_examples: List[str] = []
        self.long_strings: List[str] = []
        self.log_problems: List[str] = []
        #: The steady stream's generators: bulging trajectories (the validation rate last
        #: asked for, beyond the stroke or not in turn) and the IMU's kinds and time line.
        self.low_validation_rate = LOW_VALIDATION_RATES[0]
        self.bulges = {'beyond': 0, 'inside': 0, 'not placed': 0}
        self.imu_counts = dict.fromkeys(IMU_KINDS, 0)
        self.oversized: Dict[str, int] = {}
        self.max_clock = 0.0
        self.trajectories = 0
        self.low_rate_requests = 0
        self.imu_ns = self.imu_wall_ns = None
        cueing = read_parameter_files(parameter_files('motion_cueing_node'),
                                      'motion_cueing_node')
        self.imu_streams = {kind: ImuStream(self.rng, kind,
                                            cueing.get('max_specific_force', 100.0),
                                            cueing.get('max_angular_velocity', 20.0))
                            for kind in IMU_KINDS if kind != 'plausible'}
        #: The frames a vehicle_imu sample is cued in: the vehicle's (or none given).
        self.vehicle_frames = ['', cueing.get('vehicle_frame', 'base_link')]
        self.diagnostics = DiagnosticsLog()
        self.totals = {name: CounterTotals() for name in self.slots}
        self.outputs: Dict[str, int] = {}
        self.non_finite: List[str] = []
        self.beyond_limits: List[str] = []
        self.counts = {'non-finite': 0, 'beyond a limit': 0, 'long strings': 0}
        self.crashes: List[str] = []
        self.kills: Dict[str, int] = {'SIGKILL': 0, 'SIGTERM': 0}
        self.jumps = {'back': 0, 'forward': 0, 'hostile clock messages': 0}
        self.sent: Dict[str, int] = {}
        self.bad: Dict[str, int] = {}
        self.parameter_counts: Dict[str, int] = {}
        self.parameter_problems: List[str] = []
        self.accounting_problems: List[str] = []
        #: (when to look, node, run, pids) of the processes of stopped runs; those left behind.
        self.orphan_checks: List[tuple] = []
        self.orphans: List[str] = []
        self.requests: List[ParameterRequests] = []
        self.client = None
        self._lock = threading.Lock()
        self._stop = threading.Event()

    # Outputs ------------------------------------------------------------------------------------

    def output_callback(self, topic):
        """Return the callback that checks and counts one output topic (with message info)."""
        def on_message(message, info):
            problems = self.invariants.problems(topic, message)
            with self._lock:
                self.outputs[topic] = self.outputs.get(topic, 0) + 1
                if problems:
                    text = f'{topic}: {"; ".join(problems)}'
                    if numbers_problems(message):
                        kind, examples = 'non-finite', self.non_finite
                    elif string_problems(message):
                        kind, examples = 'long strings', self.long_strings
                    elif allowable(topic, message):
                        # A braking command may break a pose limit: counted at the end, by
                        # topic (one command goes out on each pose topic of its node).
                        kind, examples = None, self.allowable_examples
                        self.allowable_by_topic[topic] = (
                            self.allowable_by_topic.get(topic, 0) + 1)
                        self.allowable = max(self.allowable_by_topic.values())
                    else:
                        kind, examples = 'beyond a limit', self.beyond_limits
                    if kind is not None:
                        self.counts[kind] += 1
                    if len(examples) < KEPT_EXAMPLES:
                        examples.append(text)
                self.streams.check(topic, message, info)
            if topic == '/diagnostics':
                self.diagnostics(message)
        return on_message

    # The run -----------------------------------------------------------------------------------

    def run(self, client) -> int:
        """Run the soak for its duration; print the report; return the exit code."""
        self.client = client
        node = client.node
        published = {endpoint.name: endpoint for interface in NODE_INTERFACES.values()
                     if interface.node in self.slots for endpoint in interface.of_kind(PUBLISHER)}
        subscribed = {endpoint.name: endpoint for interface in NODE_INTERFACES.values()
                      if interface.node in self.slots
                      for endpoint in interface.of_kind(SUBSCRIPTION)}
        for name, endpoint in published.items():
            try:
                message_type = endpoint.message_type
            except ImportError:
                continue
            node.create_subscription(message_type, name, self.output_callback(name), 100)
        # The soak feeds only topics no node publishes: what a node publishes is an output,
        # checked, and the soak's own messages must not be taken for one.
        streams = []
        for name, endpoint in sorted(subscribed.items()):
            if name in published:
                continue
            rate = (SEQUENCE_RATE if _has_message_sequence(endpoint.message_type)
                    else self.arguments.stream_rate)
            streams.append([name, node.create_publisher(endpoint.message_type, name, 100),
                            MessageFuzzer(endpoint.message_type, self.rng, self.hints, name),
                            rate, 0.0])
        # The oversized messages of the floods: every field of every topic, in a drawn order.
        oversized = [(stream, place) for stream in streams
                     for place in stream[2].oversized_places()]
        self.rng.shuffle(oversized)
        oversized_index = 0
        pending = []
        clock = node.create_publisher(Clock, '/clock', 10)
        sim_nodes = bool(self.arguments.sim_time)
        wall_start = time.time()
        for slot in self.slots.values():
            slot.start()
        parameter_thread = threading.Thread(target=self.parameter_loop, args=(client,),
                                            name='soak_parameters', daemon=True)
        parameter_thread.start()
        arguments = self.arguments
        start = time.monotonic()
        end = start + arguments.seconds
        next_kill = start + arguments.kill_every
        next_flood = start + arguments.flood_every
        next_jump = start + arguments.jump_every
        next_rss = start
        offset = 0.0
        jump_index = 0
        kill_index = 0
        flood_until = hostile_until = 0.0
        hostile = HOSTILE_CLOCKS[0]
        flood_credit = 0.0
        last = start
        while True:
            now = time.monotonic()
            if now >= end:
                break
            elapsed, last = now - last, now
            # The steady stream, and the flood when one is on.
            for stream in streams:
                stream[4] += elapsed * stream[3]
                while stream[4] >= 1.0:
                    stream[4] -= 1.0
                    self.steady(stream, now - start)
            if now < flood_until:
                flood_credit += elapsed * arguments.flood_rate
                while flood_credit >= 1.0:
                    flood_credit -= 1.0
                    self.publish(self.rng.choice(streams),
                                 self.rng.choice(('mutated', 'mutated', 'hostile')), self.bad)
                if pending:   # one oversized message a tick: each is megabytes
                    stream, place = pending.pop()
                    message, _ = stream[2].oversized(place)
                    stream[1].publish(message)
                    key = f'{stream[0]} {place}'
                    self.oversized[key] = self.oversized.get(key, 0) + 1
            elif now >= next_flood:
                flood_until = now + arguments.flood_seconds
                next_flood += arguments.flood_every
                for _ in range(arguments.oversized if oversized else 0):
                    pending.append(oversized[oversized_index % len(oversized)])
                    oversized_index += 1
            # The clock: jumps, and a hostile message once per cycle of jumps.
            if now >= next_jump:
                next_jump += arguments.jump_every
                jump = CLOCK_JUMPS[jump_index % len(CLOCK_JUMPS)]
                new_offset = 0.0 if jump is None else offset + jump
                self.jumps['back' if new_offset < offset else 'forward'] += 1
                offset = new_offset
                if jump is None:
                    hostile = HOSTILE_CLOCKS[(jump_index // len(CLOCK_JUMPS))
                                             % len(HOSTILE_CLOCKS)]
                    hostile_until = now + HOSTILE_CLOCK_SECONDS
                    self.jumps['hostile clock messages'] += 1
                jump_index += 1
            if now < hostile_until:
                # Alone on /clock for a while: rclpy's clock subscription keeps one message.
                clock.publish(Clock(clock=Time(sec=hostile[0], nanosec=hostile[1])))
                self.max_clock = max(self.max_clock, hostile[0] + hostile[1] * 1e-9)
            else:
                sim = SIM_TIME_START + (now - start) + offset
                clock.publish(Clock(clock=Time(sec=int(sim),
                                               nanosec=int((sim % 1.0) * 1e9))))
                self.max_clock = max(self.max_clock, sim)
            # Where a command stream's clock origin can be: a run's start, on either clock.
            with self._lock:
                self.streams.set_origin_range(
                    (0.0, self.max_clock + 1.0) if sim_nodes else (wall_start - 1.0,
                                                                   time.time() + 1.0))
            # Faults: a kill in turn; a node that exited by itself is a crash, and restarts.
            if now >= next_kill:
                next_kill += arguments.kill_every
                names = sorted(self.slots)
                slot = self.slots[names[kill_index % len(names)]]
                # SIGKILL and SIGTERM in turn, shifted by one each round: each node gets both.
                kill_signal = (signal.SIGKILL, signal.SIGTERM)[
                    (kill_index + kill_index // len(names)) % 2]
                kill_index += 1
                self.kill(slot, kill_signal)
            for slot in self.slots.values():
                if not slot.run.process.running():
                    self.crashed(slot, 'exited by itself')
            if now >= next_rss:
                next_rss += arguments.rss_every
                for slot in self.slots.values():
                    kb = resident_kb(slot.run.process.process.pid)
                    if kb is not None:
                        slot.run.rss.append((now, kb))
            for name, slot in self.slots.items():
                self.totals[name].update(self.diagnostics.reports('/' + name).latest)
            self.check_orphans(now)
            time.sleep(max(0.0, TICK - (time.monotonic() - now)))
        faults = time.monotonic() - start
        self._stop.set()
        parameter_thread.join(timeout=30.0)
        client.wait(lambda: all(requests.done() for requests in self.requests), 5.0)
        # The last work in hand (a large trajectory being planned) answered and reported, so
        # that the counts add up, while the clock still runs.
        settled_at = time.monotonic()
        while time.monotonic() - settled_at < SETTLE_TIMEOUT and (
                time.monotonic() - settled_at < 2.0 * REPORT_PERIOD or not self.accounted()):
            sim = SIM_TIME_START + (time.monotonic() - start) + offset
            clock.publish(Clock(clock=Time(sec=int(sim), nanosec=int((sim % 1.0) * 1e9))))
            time.sleep(TICK)
        for slot in self.slots.values():
            self.stop(slot, signal.SIGINT)
        client.wait(lambda: not any(process_running(pid) for check in self.orphan_checks
                                    for pid in check[3]), ORPHAN_GRACE)
        self.check_orphans(math.inf)
        for name in self.slots:
            self.totals[name].update(self.diagnostics.reports('/' + name).latest)
        for requests in self.requests:
            requests.forget_unanswered()
            self.parameter_problems += requests.problems
            for key, count in requests.counts.items():
                self.parameter_counts[key] = self.parameter_counts.get(key, 0) + count
        return self.report(faults, time.monotonic() - start)

    def accounted(self) -> bool:
        """Whether every node's latest counts add up: no message in hand when it reported."""
        for name in self.slots:
            reports = self.diagnostics.reports('/' + name)
            if any(counters['received'] != counters['published'] + counters['rejected']
                   for counters in reports.latest.values()):
                return False
        return True

    def steady(self, stream, elapsed: float):
        """
        Publish one message of the steady stream: plausible, or one of issue 27's cases.

        ``vehicle_imu``: a window of each of :data:`IMU_KINDS` in turn, in the vehicle frame,
        every sample stamped on one time line that runs :data:`FAST_FACTOR` times fast in a
        recording's window; every
        other ``pose_trajectory``: a bulging trajectory, beyond the stroke and inside it in
        turn, made for the validation rate last asked of trajectory_node.

        :param elapsed: seconds since the soak started.
        """
        name, publisher, generator = stream[:3]
        if name.split('/')[-1] == 'vehicle_imu':
            kind = IMU_KINDS[int(elapsed / self.arguments.imu_window) % len(IMU_KINDS)]
            now = time.time_ns()
            if self.imu_ns is None:
                self.imu_ns = now
            else:
                speed_up = FAST_FACTOR if kind == 'recording' else 1.0
                self.imu_ns += max(1, int((now - self.imu_wall_ns) * speed_up))
            self.imu_wall_ns = now
            frame_id = self.rng.choice(self.vehicle_frames)
            if kind == 'plausible':
                message, _ = generator.message('plausible')
                message.header.stamp.sec, message.header.stamp.nanosec = divmod(
                    self.imu_ns, 1_000_000_000)
                message.header.frame_id = frame_id
            else:
                message = self.imu_streams[kind].message(self.imu_ns, frame_id)
            self.imu_counts[kind] += 1
            publisher.publish(message)
            self.sent[name] = self.sent.get(name, 0) + 1
            return
        if name.split('/')[-1] == 'pose_trajectory':
            self.trajectories += 1
            if self.trajectories % 2 == 0:
                beyond = self.trajectories % 4 == 0
                invariants = self.invariants
                try:
                    message, _ = bulging_trajectory(
                        self.rng, invariants.geometry, invariants.actuator_limits,
                        invariants.frames[0], self.low_validation_rate, beyond,
                        self.hints.frames[0])
                except ValueError:
                    self.bulges['not placed'] += 1
                else:
                    self.bulges['beyond' if beyond else 'inside'] += 1
                    publisher.publish(message)
                    self.sent[name] = self.sent.get(name, 0) + 1
                    return
        self.publish(stream, 'plausible', self.sent)

    def publish(self, stream, kind, counts):
        """Publish one message of a stream, of a kind (plausible, mutated, hostile)."""
        name, publisher, generator = stream[:3]
        message, _ = generator.message(kind)
        publisher.publish(message)
        counts[name] = counts.get(name, 0) + 1

    # Faults -------------------------------------------------------------------------------------

    def kill(self, slot: Slot, kill_signal):
        """Kill a node's run with a signal; a SIGTERM must end it cleanly; then start again."""
        self.kills[kill_signal.name] += 1
        self.stop(slot, kill_signal)
        slot.start()

    def stop(self, slot: Slot, stop_signal):
        """
        Stop the current run with a signal and check how it ended.

        A SIGTERM or SIGINT waits until the run has reported on /diagnostics (it is built and
        spinning): in the first few tenths of a second Python is still importing, and a signal
        then ends it as Python's defaults do (a KeyboardInterrupt traceback, or killed by
        SIGTERM), before the node can handle it.
        """
        run = slot.run
        process = run.process
        self.watch_children(slot, run)
        if stop_signal != signal.SIGKILL:
            self.client.wait(lambda: any(arrival > run.started for arrival in
                                         self.diagnostics.reports('/' + slot.name).arrivals),
                             READY_TIMEOUT, [process])
        locks = _shm_lock_files(process.process.pid) if stop_signal == signal.SIGKILL else []
        if process.running():
            process.send_signal(stop_signal)
        try:
            code = process.process.wait(STOP_TIMEOUT)
        except Exception:   # subprocess.TimeoutExpired: a node that ignores the signal
            process.process.kill()
            code = process.process.wait()
            self.crash(slot, f'still running {STOP_TIMEOUT} s after {stop_signal.name}')
        run.ended, run.stopped_with, run.exit_code = time.monotonic(), stop_signal.name, code
        output = process.output()
        process.__exit__(None, None, None)
        self.check_log(slot, run, output)
        if stop_signal != signal.SIGKILL and code != 0:
            self.crash(slot, f'exit code {code} after {stop_signal.name}', output)
        elif 'Traceback' in output:
            self.crash(slot, f'a traceback (stopped with {stop_signal.name})', output)
        _remove_dead_segments(locks)

    def check_log(self, slot: Slot, run: Run, output: str):
        """Keep the lines of a run's log longer than the bound (a refusal that echoed a flood)."""
        self.log_problems += [f'{slot.name} run {run.number}: {problem}'
                              for problem in log_problems(output)]

    def watch_children(self, slot: Slot, run: Run):
        """Look, ORPHAN_GRACE seconds after this, for processes of the run still alive."""
        children = descendants(run.process.process.pid)
        if children:
            self.orphan_checks.append((time.monotonic() + ORPHAN_GRACE, slot.name, run.number,
                                       children))

    def check_orphans(self, now: float):
        """Count (and kill) the processes of stopped runs still alive after the grace."""
        due = [check for check in self.orphan_checks if check[0] <= now]
        self.orphan_checks = [check for check in self.orphan_checks if check[0] > now]
        for _, name, number, children in due:
            for pid in children:
                if process_running(pid):
                    try:
                        command = Path(f'/proc/{pid}/cmdline').read_bytes().replace(
                            b'\0', b' ').decode(errors='replace')[:100]
                        os.kill(pid, signal.SIGKILL)
                    except OSError:
                        continue
                    self.orphans.append(f'{name} run {number}: pid {pid} {command}')

    def crashed(self, slot: Slot, what: str):
        """Record a run that ended without being stopped, and start a new one."""
        run = slot.run
        run.ended, run.exit_code = time.monotonic(), run.process.process.poll()
        output = run.process.output()
        run.process.__exit__(None, None, None)
        self.check_log(slot, run, output)
        self.crash(slot, f'{what} with exit code {run.exit_code}', output)
        slot.start()

    def crash(self, slot: Slot, what: str, output: str = ''):
        """Count a crash, with the end of the run's output."""
        tail = '\n'.join(output.splitlines()[-25:])
        self.crashes.append(f'{slot.name} run {slot.run.number}: {what}\n{tail}')

    # Parameters ---------------------------------------------------------------------------------

    def parameter_loop(self, client):
        """Every --parameter-every seconds, one request of one to three changes to a node."""
        rng = random.Random(self.arguments.seed + 1)
        fuzzers = {}
        clients = {}
        while not self._stop.wait(self.arguments.parameter_every):
            slot = self.slots[rng.choice(sorted(self.slots))]
            run = slot.run
            if not run.process.running() or time.monotonic() - run.started < 3.0:
                continue
            key = (slot.name, run.number)
            if slot.name not in clients:
                clients[slot.name] = parameter_clients(client.node, '/' + slot.name)
            services = clients[slot.name]
            if key not in fuzzers:
                fuzzer = parameter_fuzzer_of(client, services, rng, timeout=5.0)
                if fuzzer is None:
                    continue
                fuzzers[key] = fuzzer
                self.requests.append(ParameterRequests(fuzzer, self.invariants))
                fuzzers[key + ('requests',)] = self.requests[-1]
            requests = fuzzers[key + ('requests',)]
            if slot.name == 'trajectory_node' and (not self.low_rate_requests
                                                   or rng.random() < LOW_RATE_SHARE):
                # Issue 27: a low validation_rate, for the bulging trajectories.
                rate = rng.uniform(*LOW_VALIDATION_RATES)
                self.low_validation_rate = rate
                self.low_rate_requests += 1
                changes = [_valid_change('validation_rate', ParameterType.PARAMETER_DOUBLE, rate),
                           _valid_change('retime', ParameterType.PARAMETER_BOOL, False)]
                requests.send(services[SetParameters], changes, False)
                continue
            changes = fuzzers[key].changes(rng.randint(1, 3))
            # A valid change of the frames moves every pose: let the checks know beforehand.
            for change in changes:
                if change.expect == EITHER and change.name in FRAME_NAMES:
                    self.invariants.add_frames({**fuzzers[key].values,
                                                change.name: change.value})
            atomic = rng.random() < 0.1
            requests.send(services[SetParametersAtomically if atomic else SetParameters],
                          changes, atomic)

    # The report ---------------------------------------------------------------------------------

    def report(self, duration: float, total: float) -> int:
        """
        Print the report; return 0 when every target is met, else 1.

        :param duration: seconds of the stream and the faults; ``total``: with the start and
            the final stop.
        """
        arguments = self.arguments
        lines = [f'SOAK {duration:.0f} s ({total:.0f} s with the start and the stop), seed '
                 f'{arguments.seed}: nodes '
                 f'{", ".join(self.slots)}; sim time on {", ".join(arguments.sim_time) or "none"}']
        lines.append(f'SOAK stream sent {sum(self.sent.values())} {_sorted(self.sent)}')
        lines.append(f'SOAK bad messages sent {sum(self.bad.values())} {_sorted(self.bad)}')
        lines.append(f'SOAK issue 27 cases: bulging trajectories {_sorted(self.bulges)}, '
                     f'{self.low_rate_requests} requests of a low validation_rate; vehicle_imu '
                     f'by kind {_sorted(self.imu_counts)}; oversized messages '
                     f'{sum(self.oversized.values())} {_sorted(self.oversized)}')
        for name in self.slots:
            totals = self.totals[name].totals()
            received = sum(counters['received'] for counters in totals.values())
            published = sum(counters['published'] for counters in totals.values())
            refused, warned = {}, {}
            for counters in totals.values():
                for code, count in counters['rejected_by_code'].items():
                    refused[code] = refused.get(code, 0) + count
                for code, count in counters['warned_by_code'].items():
                    warned[code] = warned.get(code, 0) + count
            reports = self.diagnostics.reports('/' + name)
            lines.append(f'SOAK {name}: in {received}, out {published}, refused by reason '
                         f'{_sorted(refused)}, warnings {_sorted(warned)}; '
                         f'{len(reports.stamps)} DiagnosticArrays in {duration:.0f} s, at most '
                         f'{_most_in_a_second(reports.arrivals)} in one second; '
                         f'{len(self.slots[name].runs)} runs')
            # The counts of the last run add up (the rate is not checked: sim time jumps).
            self.accounting_problems += [
                problem for problem in self.diagnostics.problems('/' + name)
                if 'DiagnosticArrays over' not in problem]
        lines.append(f'SOAK outputs seen {sum(self.outputs.values())} {_sorted(self.outputs)}')
        lines.append(f'SOAK accounting problems {len(self.accounting_problems)} (target 0)')
        lines += [f'  {problem}' for problem in self.accounting_problems]
        lines.append(f'SOAK crashes {len(self.crashes)} (target 0)')
        lines += [f'  {crash}' for crash in self.crashes]
        lines.append(f'SOAK processes left behind by stopped runs {len(self.orphans)} '
                     '(target 0)')
        lines += [f'  {orphan}' for orphan in self.orphans[:KEPT_EXAMPLES]]
        lines.append(f'SOAK non-finite outputs {self.counts["non-finite"]} (target 0)')
        lines += [f'  {example}' for example in self.non_finite]
        allowance = sum(braking_allowance(self.totals[name].totals()) for name in self.slots)
        streamed = self.streams.violations
        excess = max(0, self.allowable + streamed - allowance)
        beyond = self.counts['beyond a limit'] + excess
        lines.append(f'SOAK outputs beyond a limit {beyond} (target 0)')
        lines.append(f'SOAK   of which braking beyond what the nodes counted {excess}: '
                     f'{self.allowable} poses beyond a pose limit and {streamed} of '
                     f'{self.streams.checked} stream commands beyond a rate (between consecutive '
                     f'joint_commands), against {allowance} {" and ".join(ALLOWED_CODES)} '
                     'findings counted')
        lines += [f'  {example}' for example in self.beyond_limits]
        if excess:
            lines += [f'  {example}' for example in (
                self.allowable_examples + self.streams.problems())[:KEPT_EXAMPLES]]
        lines.append(f'SOAK long strings in outputs {self.counts["long strings"]} (target 0)')
        lines += [f'  {example[:300]}' for example in self.long_strings]
        lines.append(f'SOAK long log lines {len(self.log_problems)} (target 0)')
        lines += [f'  {problem[:300]}' for problem in self.log_problems[:KEPT_EXAMPLES]]
        lines.append(f'SOAK kills {_sorted(self.kills)}; clock {_sorted(self.jumps)}')
        lines.append(f'SOAK parameter answers {_sorted(self.parameter_counts)}; problems '
                     f'{len(self.parameter_problems)} (target 0)')
        lines += [f'  {problem}' for problem in self.parameter_problems[:KEPT_EXAMPLES]]
        lines.append('SOAK resident memory (kB) per run of each node, after a '
                     f'{RSS_WARM_UP:.0f} s warm-up: node run: lived s, start -> end, slope '
                     'kB/min over the run and over its second half')
        for name, slot in self.slots.items():
            for run in slot.runs:
                warm = run.warm()
                slope = run.slope()
                late = run.slope(second_half=True)
                lived = (run.ended or time.monotonic()) - run.started
                lines.append(
                    f'SOAK rss {name} run {run.number}: {lived:.0f} s, '
                    + (f'{warm[0]} -> {warm[1]}' if warm else 'too short')
                    + (f', slope {slope:+.1f}' if slope is not None else '')
                    + (f', second half {late:+.1f}' if late is not None else '')
                    + (f' ({run.stopped_with})' if run.stopped_with else ''))
        print('\n'.join(lines), flush=True)
        if arguments.figure:
            self.figure(arguments.figure)
        missed = (self.crashes or self.counts['non-finite'] or beyond
                  or self.counts['long strings'] or self.log_problems
                  or self.parameter_problems or self.accounting_problems or self.orphans)
        return 1 if missed else 0

    def figure(self, path):
        """Draw the resident memory of every run of every node over time, as a PNG."""
        import matplotlib
        matplotlib.use('Agg')
        from matplotlib import pyplot
        figure, axes = pyplot.subplots(figsize=(7.0, 3.2), dpi=100)
        origin = min(run.started for slot in self.slots.values() for run in slot.runs)
        for index, (name, slot) in enumerate(self.slots.items()):
            colour = f'C{index}'
            for number, run in enumerate(slot.runs):
                if run.rss:
                    times, values = zip(*run.rss)
                    axes.plot((np.array(times) - origin) / 60.0, np.array(values) / 1024.0,
                              color=colour, label=name if number == 0 else None)
        axes.set_xlabel('time (min); a gap: the node was killed and started again')
        axes.set_ylabel('resident memory (MiB)')
        axes.set_title('Soak: resident memory of each node')
        axes.legend(loc='lower right', fontsize='small')
        figure.tight_layout()
        figure.savefig(path)
        print(f'SOAK figure {path}')


def _valid_change(name: str, type_code: int, value) -> ParameterChange:
    """Return a valid parameter change (either answer allowed; the value held is tracked)."""
    return ParameterChange(parameter_message(name, type_code, value), EITHER, 'issue 27 case',
                           value=value)


def _sorted(counts) -> str:
    return str(dict(sorted(counts.items())))


def _most_in_a_second(arrivals) -> int:
    """Return the most arrivals (monotonic seconds, in order) within any one second."""
    most, first = 0, 0
    for last, arrival in enumerate(arrivals):
        while arrival - arrivals[first] > 1.0:
            first += 1
        most = max(most, last - first + 1)
    return most


def _has_message_sequence(message_type) -> bool:
    """Whether a message type has a sequence of messages (trajectory points, path poses)."""
    for slot in message_type.SLOT_TYPES:
        if isinstance(slot, definition.NamespacedType):
            if _has_message_sequence(message_class(slot)):
                return True
        elif isinstance(slot, definition.AbstractNestedType) and isinstance(
                slot.value_type, definition.NamespacedType):
            return True
    return False


def _shm_lock_files(pid):
    """Return the lock files of the Fast DDS shared-memory segments a process owns."""
    locks = []
    try:
        descriptors = list(Path(f'/proc/{pid}/fd').iterdir())
    except OSError:
        return locks
    for descriptor in descriptors:
        try:
            target = Path(os.readlink(descriptor))
        except OSError:
            continue
        if (target.parent == SHM_DIRECTORY and target.name.startswith(SHM_PREFIX)
                and target.name.endswith('_el') and 'port' not in target.name):
            locks.append(target)
    return locks


def _remove_dead_segments(locks):
    """Remove the segments of a killed node whose lock no living process holds (SIGKILL)."""
    for lock_file in locks:
        segment = lock_file.with_name(lock_file.name[:-len('_el')])
        try:
            descriptor = os.open(lock_file, os.O_RDONLY)
        except FileNotFoundError:
            continue
        try:
            fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            continue
        finally:
            os.close(descriptor)
        for path in (segment, lock_file):
            try:
                path.unlink()
            except FileNotFoundError:
                pass


def parse_arguments(argv):
    """Command-line options of the soak."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    duration = parser.add_mutually_exclusive_group()
    duration.add_argument('--minutes', type=positive_number, default=10.0,
                          help='how long, minutes (default: 10)')
    duration.add_argument('--seconds', type=positive_number, default=None,
                          help='how long, seconds (instead of --minutes)')
    parser.add_argument('--seed', type=int, default=None, help='seed (default: random)')
    parser.add_argument('--nodes', nargs='+', choices=sorted(NODE_INTERFACES),
                        default=SOAKED_NODES, help='nodes (default: every one but '
                        'telemetry_bridge)')
    parser.add_argument('--sim-time', nargs='*', default=None,
                        help='nodes on sim time (default: ik_node trajectory_node)')
    parser.add_argument('--stream-rate', type=number_in(0.1, 1000.0), default=50.0,
                        help='steady messages a second on each input topic (default: 50)')
    parser.add_argument('--kill-every', type=positive_number, default=60.0,
                        help='seconds between two kills (default: 60)')
    parser.add_argument('--flood-every', type=positive_number, default=30.0,
                        help='seconds between two floods of bad messages (default: 30)')
    parser.add_argument('--flood-seconds', type=positive_number, default=3.0,
                        help='seconds of each flood (default: 3)')
    parser.add_argument('--flood-rate', type=number_in(1.0, 5000.0), default=1000.0,
                        help='bad messages a second during a flood (default: 1000)')
    parser.add_argument('--oversized', type=int, default=3,
                        help='oversized messages in each flood (a million numbers, a string of '
                             'a million characters...: each field of each topic in turn; '
                             'default: 3)')
    parser.add_argument('--imu-window', type=positive_number, default=5.0,
                        help='seconds of each kind of vehicle_imu samples in turn: plausible, '
                             'noisy, a recording ten times fast (default: 5)')
    parser.add_argument('--command-rate', type=number_in(0.0, 1000.0), default=100.0,
                        help="ik_node's command_rate: joint_commands streamed and checked for "
                             'their leg rates (default: 100; 0: not streamed)')
    parser.add_argument('--executables', type=Path, default=None,
                        help='a folder to take the console scripts from (another build, such '
                             'as an older revision), instead of the installed ones')
    parser.add_argument('--jump-every', type=positive_number, default=20.0,
                        help='seconds between two /clock jumps (default: 20)')
    parser.add_argument('--parameter-every', type=positive_number, default=2.0,
                        help='seconds between two parameter requests (default: 2)')
    parser.add_argument('--rss-every', type=positive_number, default=5.0,
                        help='seconds between two memory samples (default: 5)')
    parser.add_argument('--figure', type=Path, default=None,
                        help='write a PNG of the resident memory over time here')
    arguments = parser.parse_args(argv)
    arguments.seconds = arguments.seconds or 60.0 * arguments.minutes
    if arguments.oversized < 0:
        parser.error('--oversized must be at least 0')
    if arguments.seed is None:
        arguments.seed = random.SystemRandom().randrange(2 ** 32)
    if arguments.sim_time is None:
        arguments.sim_time = [name for name in ('ik_node', 'trajectory_node')
                              if name in arguments.nodes]
    unknown = sorted(set(arguments.sim_time) - set(arguments.nodes))
    if unknown:
        parser.error(f'--sim-time names nodes that do not run: {unknown}')
    return arguments


def main(argv=None) -> int:
    """Run the soak on an isolated ROS domain; return 0 when every target is met."""
    arguments = parse_arguments(argv)
    with isolated_ros_environment():
        rclpy.init(args=[])
        client = SpinningClient(rclpy.create_node('stewart_soak'))
        soak = Soak(arguments)
        try:
            return soak.run(client)
        finally:
            for slot in soak.slots.values():
                if slot.runs and slot.run.process.running():
                    slot.run.process.stop()
            client.close()
            rclpy.try_shutdown()


if __name__ == '__main__':
    sys.exit(main())
