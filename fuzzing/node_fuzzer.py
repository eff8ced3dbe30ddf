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
Fuzz a node as a process: hostile messages on every input, parameter changes, then checks.

:func:`fuzz_node` starts a node's console script with the shipped parameter files, subscribes
to every topic it publishes, and floods every topic it subscribes to (all read from its
declaration in :data:`stewart_kinematics.ros.interfaces.NODE_INTERFACES`) with messages from
:mod:`~fuzzing.fuzz_messages`, up to 1 kHz, mixing in run-time parameter
changes from :mod:`~fuzzing.fuzz_parameters` through the node's parameter
services. It then checks the invariants:

- the node keeps running, answers a parameter request and each declared service within a
  deadline after the flood, and stops cleanly on SIGINT (exit 0, no traceback);
- every message it published is finite, with unit quaternions, and within the limits
  (:mod:`~fuzzing.output_invariants`);
- no string it published (``/diagnostics`` included) and no line it logged is longer than the
  bound of :mod:`~fuzzing.output_invariants`, also after oversized messages (a million numbers,
  a frame id of a million characters: :meth:`~fuzzing.fuzz_messages.MessageFuzzer.oversized`);
- every parameter change that must be refused is, with a reason (naming the parameter when
  the spec refuses the value), and the node then holds exactly the values it accepted;
- its /diagnostics reports come about once a second and add up: received = published +
  rejected per input, rejections by code summing to the rejections, every code registered,
  never more received than sent;
- a command stream (ik_node's ``joint_commands`` with ``command_rate``) keeps the leg rates
  between consecutive commands (:mod:`~fuzzing.stream_rates`), and only as many outputs break
  a limit as the node counted braking commands.

With ``scenarios`` (``--scenarios N``), the node's scenario of :mod:`~fuzzing.node_scenarios`
follows the flood, N rounds of it: issue 27's cases drawn on purpose (trajectory_node: low
``validation_rate`` and bulging trajectories; motion_cueing_node, on simulated time in
lockstep with the fuzzer's ``/clock``: noisy IMU bursts and a recording played ten times fast,
every ``target_pose`` checked for its leg rates at its exact send time).

``python -m fuzzing.node_fuzzer --minutes 10`` (``scripts/fuzz_nodes.sh``)
runs rounds over every declared node for longer; each round prints its seed, and ``--node
NAME --seed S --messages N`` replays one.
"""

import argparse
from dataclasses import dataclass, field
from pathlib import Path
import random
import signal
import socket
import sys
import time
from typing import Dict, List, Optional, Sequence

from fuzzing.fuzz_client import DiagnosticsLog, paced, SpinningClient
from fuzzing.fuzz_messages import choose_kind, MessageFuzzer, summarize
from fuzzing.fuzz_parameters import argument, start_variant
from fuzzing.fuzz_targets import parameter_files, plausible_hints
from fuzzing.node_scenarios import Scenario, scenario_names, ScenarioRun, SCENARIOS, SimClock
from fuzzing.output_invariants import log_problems, OutputInvariants, OutputLog
from fuzzing.parameter_requests import (
    held_value_problems,
    parameter_clients,
    parameter_fuzzer_of,
    ParameterRequests,
)
from fuzzing.stream_rates import braking_allowance
from rcl_interfaces.srv import GetParameters, SetParameters, SetParametersAtomically
import rclpy
from rosidl_parser import definition

from stewart_kinematics.cueing.telemetry_packet import encode
from stewart_kinematics.ros.interfaces import (
    MOCK_PLATFORM,
    NODE_INTERFACES,
    PUBLISHER,
    SERVICE,
    SUBSCRIPTION,
)
from stewart_kinematics.ros.mock_platform import inputs_taken
from stewart_kinematics.ros.node_main import EXIT_START_FAILED
from stewart_kinematics.tools.cli_arguments import number_in, positive_number
from stewart_kinematics.tools.node_processes import (
    find_executable,
    isolated_ros_environment,
    NodeProcess,
)

#: Seconds to wait for discovery, an answer, or the node's first report.
DEADLINE = 20.0
#: Seconds the node may take to work through its queues after the flood.
SETTLE_DEADLINE = 60.0
#: Queue depth of the fuzzer's publishers and subscriptions (reliable, keep last).
QUEUE_DEPTH = 100
#: Messages of each input whose mutations a failure report shows.
KEPT_DESCRIPTIONS = 5


@dataclass
class FuzzSettings:
    """
    One fuzz run of one node.

    :param node: a node of :data:`NODE_INTERFACES` (its console script has its name).
    :param seed: the seed of every random draw: the same seed sends the same messages.
    :param messages: messages to send in all, over every input.
    :param rate: messages a second at most.
    :param parameter_every: one parameter request (one to three changes) per this many
        messages (0: none).
    :param huge: messages with a sequence of 10^5 elements among them.
    :param oversized: rounds of oversized messages: in each, every input gets one message per
        field that a sender can grow (a million numbers, a string of a million characters, 10^5
        names or elements; :meth:`~fuzzing.fuzz_messages.MessageFuzzer.oversized_places`).
    :param files: parameter files (default: :func:`parameter_files`).
    :param arguments: more ``--ros-args`` arguments for the node.
    :param parameters: parameter values to start the node with (``-p``), over the files and
        the variant, by name (the output checks see them: ``command_rate`` makes
        ``joint_commands`` a command stream).
    :param variant: start the node with a :func:`~fuzzing.fuzz_parameters.
        start_variant` of its read-only parameters, drawn from the seed (a variant the node
        refuses to start with, saying why, is reported and the run made without it).
    :param scenarios: rounds of the node's scenario after the flood
        (:data:`~fuzzing.node_scenarios.SCENARIOS`; 0: none; a node without one: none). One
        that needs simulated time starts the node with ``use_sim_time`` and a ``/clock``
        from the fuzzer for the whole run.
    :param only: the names of the scenarios to play (default: every one of the node's).
    :param executable: the node's console script to start (a path), instead of the installed
        one: to fuzz another build (an older revision, say).
    """

    node: str
    seed: int
    messages: int = 2000
    rate: float = 1000.0
    parameter_every: int = 50
    huge: int = 1
    oversized: int = 1
    files: Optional[Sequence[Path]] = None
    arguments: Sequence[str] = ()
    parameters: Dict[str, object] = field(default_factory=dict)
    variant: bool = True
    scenarios: int = 0
    only: Sequence[str] = ()
    executable: Optional[str] = None

    def replay_options(self) -> str:
        """Return the command-line options that replay this run."""
        return (f'--node {self.node} --seed {self.seed} --messages {self.messages} '
                f'--rate {self.rate:g} --huge {self.huge} --oversized {self.oversized}'
                + ('' if self.variant else ' --no-variant')
                + (f' --scenarios {self.scenarios}' if self.scenarios else '')
                + ''.join(f' --scenario {name}' for name in self.only)
                + (f' --executable {self.executable}' if self.executable else ''))

    @property
    def to_play(self) -> List[Scenario]:
        """Return the node's scenarios to play (none without ``scenarios``)."""
        if self.scenarios <= 0:
            return []
        return [scenario for scenario in SCENARIOS.get(self.node, ())
                if not self.only or scenario.name in self.only]


@dataclass
class FuzzReport:
    """What a fuzz run sent, saw and found."""

    settings: FuzzSettings
    sent: Dict[str, int] = field(default_factory=dict)
    kinds: Dict[str, int] = field(default_factory=dict)
    outputs: Dict[str, int] = field(default_factory=dict)
    parameter_changes: Dict[str, int] = field(default_factory=dict)
    rejections: Dict[str, int] = field(default_factory=dict)
    published: int = 0
    reports: int = 0
    duration: float = 0.0
    #: Seconds of each phase: start and discovery, flood, answers and settling.
    phases: Dict[str, float] = field(default_factory=dict)
    problems: List[str] = field(default_factory=list)
    #: The last messages sent to each input, in words (their mutations).
    recent: Dict[str, List[str]] = field(default_factory=dict)
    output: str = ''
    #: The start-up variant the node ran with (``-p`` arguments), and why one was dropped.
    variant: List[str] = field(default_factory=list)
    variant_refused: str = ''
    #: What the node's scenario sent and saw, in words.
    scenario: List[str] = field(default_factory=list)

    def summary(self) -> str:
        """Return the run's figures in a few lines."""
        settings = self.settings
        kinds = ', '.join(f'{kind} {count}' for kind, count in sorted(self.kinds.items()))
        lines = [
            f'FUZZ {settings.node} seed {settings.seed}, started with '
            f'{" ".join(self.variant) or "the files alone"}'
            + (f' (a variant refused: {self.variant_refused})' if self.variant_refused else ''),
            f'FUZZ {settings.node} seed {settings.seed}: {sum(self.sent.values())} messages in '
            f'{self.duration:.1f} s ({kinds}); sent by topic {dict(sorted(self.sent.items()))}',
            f'FUZZ {settings.node} outputs seen {dict(sorted(self.outputs.items()))}; counted '
            f'published {self.published}, rejected by code '
            f'{dict(sorted(self.rejections.items()))}; {self.reports} DiagnosticArrays',
            f'FUZZ {settings.node} parameter changes '
            f'{dict(sorted(self.parameter_changes.items()))}; phases (s) '
            + ', '.join(f'{name} {seconds:.1f}' for name, seconds in self.phases.items()),
        ]
        lines += [f'FUZZ {settings.node} scenario: {line}' for line in self.scenario]
        return '\n'.join(lines)

    def failure(self) -> str:
        """Return the problems, how to replay them and what was sent last, for a failure."""
        lines = [f'{len(self.problems)} problem(s) fuzzing {self.settings.node}:']
        lines += [f'  - {problem}' for problem in self.problems]
        lines.append('Replay: python -m fuzzing.node_fuzzer '
                     + self.settings.replay_options()
                     + f' (or STEWART_FUZZ_SEED={self.settings.seed} for the test)')
        for topic, recent in sorted(self.recent.items()):
            lines.append(f'Last messages on {topic}: ' + ' | '.join(recent))
        lines.append(self.summary())
        lines.append(f'--- {self.settings.node} output ---\n{self.output[-20000:]}')
        return '\n'.join(lines)


def fuzz_node(settings: FuzzSettings, context=None) -> FuzzReport:
    """
    Run one fuzz run of a node as a process and check the invariants.

    Needs rclpy initialised on an isolated domain (:func:`isolated_ros_environment`; the
    tests' fixtures do both). Starts and stops the node itself.

    :param context: the rclpy context of the fuzzer's node (default: the global one).
    :returns: the :class:`FuzzReport`; its ``problems`` are empty when every invariant holds.
    """
    drawn = start_variant(random.Random(f'{settings.seed} variant')) if settings.variant else {}
    report = _fuzz_once(settings, drawn, context)
    if drawn and report.variant_refused:
        refused = report.variant_refused
        report = _fuzz_once(settings, {}, context)
        report.variant_refused = refused
    return report


def _fuzz_once(settings: FuzzSettings, drawn: dict, context) -> FuzzReport:
    """Fuzz a node started with the variant ``drawn`` (name -> value); see :func:`fuzz_node`."""
    interface = NODE_INTERFACES[settings.node]
    files = list(settings.files or parameter_files(settings.node))
    variant = [word for name, value in sorted(drawn.items())
               for word in ('-p', argument(name, value))]
    report = FuzzReport(settings, variant=variant[1::2])
    given = [word for name, value in sorted(settings.parameters.items())
             for word in ('-p', argument(name, value))]
    rng = random.Random(settings.seed)
    invariants = OutputInvariants.from_parameter_files(files, settings.node,
                                                       {**drawn, **settings.parameters})
    hints = plausible_hints(files, settings.node)
    arguments = ['--ros-args']
    for path in files:
        arguments += ['--params-file', str(path)]
    arguments += variant + given + list(settings.arguments)
    sim_time = any(scenario.sim_time for scenario in settings.to_play)
    if sim_time:
        arguments += ['-p', 'use_sim_time:=true']
    # A command stream's times are seconds since the node's clock origin: when it was built.
    launched = time.time()
    invariants.origin_range = (launched - 1.0, launched + DEADLINE + 60.0)
    process = NodeProcess(find_executable(settings.executable or settings.node), arguments)
    client = SpinningClient(rclpy.create_node(f'stewart_fuzzer_{settings.node}',
                                              context=context))
    clock = SimClock(client.node) if sim_time else None
    try:
        _run(settings, interface, process, client, rng, invariants, hints, report, clock, files,
             {**drawn, **settings.parameters})
    finally:
        if clock is not None:
            clock.close()
        client.close()
        code = process.stop()
        report.output = process.output()
        process.__exit__(None, None, None)
    refusal = _start_refusal(report.output) if variant and not report.sent else ''
    if refusal and code == EXIT_START_FAILED and 'Traceback' not in report.output:
        # A variant the node cannot start with, and says why: allowed, not a problem.
        report.variant_refused = refusal
        report.problems = []
        return report
    if code != 0:
        report.problems.append(f'{settings.node} exited with code {code} on SIGINT')
    if 'Traceback' in report.output:
        report.problems.append(f'{settings.node} printed a traceback')
    report.problems += log_problems(report.output)
    return report


def _datagram_input(client, services, node):
    """
    Return ``(status name, send)`` for a node fed by UDP: ``send(rng)`` sends one datagram.

    The datagrams: well-formed telemetry packets with plausible or hostile values (NaN, inf,
    1e308, a sequence going back), truncated or padded ones, and random bytes of any length up
    to the largest datagram, to the node's ``telemetry_address`` and ``telemetry_port``.
    """
    answer = client.call(services[GetParameters], GetParameters.Request(
        names=['telemetry_address', 'telemetry_port']), DEADLINE)
    address, port = answer.values[0].string_value, answer.values[1].integer_value
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sequence = [0]

    def send(rng):
        sequence[0] = (sequence[0] + rng.choice((1, 1, 1, 0, -1))) % 2 ** 32
        values = [rng.choice((rng.uniform(-20.0, 20.0), float('nan'), float('inf'), 1e308,
                              -1e308)) if rng.random() < 0.2 else rng.uniform(-20.0, 20.0)
                  for _ in range(6)]
        packet = encode(sequence[0], time.time_ns() + rng.randint(-10 ** 9, 10 ** 9),
                        values[:3], values[3:])
        kind = rng.choice(('packet', 'packet', 'truncated', 'padded', 'bytes', 'huge'))
        if kind == 'truncated':
            packet = packet[:rng.randrange(len(packet))]
        elif kind == 'padded':
            packet += bytes(rng.randrange(1, 64))
        elif kind == 'bytes':
            packet = rng.randbytes(rng.randrange(0, 256))
        elif kind == 'huge':
            packet = rng.randbytes(rng.randrange(1024, 65507))
        udp.sendto(packet, (address, port))
        return f'datagram {kind}'
    return f'udp {address}:{port}', send


def _inputs_taken(interface, started):
    """
    Return the subscriptions the node makes when started with the parameters ``started``.

    Every declared one, but mock_platform's: its ``command_input`` names the one command input
    it takes (or ``all``), as the node reads it (:func:`~stewart_kinematics.ros.mock_platform.
    inputs_taken`). Waiting for the others to match would wait for ever, and a message sent to
    them would reach nobody.
    """
    if interface is MOCK_PLATFORM:
        return [MOCK_PLATFORM[name]
                for name in inputs_taken(started.get('command_input', 'all'))]
    return list(interface.of_kind(SUBSCRIPTION))


def _start_refusal(output: str) -> str:
    """Return the reason of a node's fatal 'cannot start' log line, or ''."""
    for line in output.splitlines():
        if 'cannot start:' in line:
            return line.split('cannot start:', 1)[1].strip()
    return ''


def _run(settings, interface, process, client, rng, invariants, hints, report, clock, files,
         started):
    """
    Run the body of :func:`fuzz_node`: discovery, flood, answers, scenario, checks.

    :param started: the parameters given on the command line (the variant's and the
        settings'), name -> value.
    """
    node = client.node
    fqn = '/' + settings.node
    diagnostics = DiagnosticsLog()
    outputs = OutputLog(invariants)
    phase_start = time.monotonic()

    def phase(name):
        nonlocal phase_start
        now = time.monotonic()
        report.phases[name] = now - phase_start
        phase_start = now

    for endpoint in interface.of_kind(PUBLISHER):
        try:
            message_type = endpoint.message_type
        except ImportError:
            continue   # an optional message package (tf2_msgs) that is not installed
        callback = outputs.callback(endpoint.name)
        if endpoint.name == '/diagnostics':
            def callback(array, info, check=callback):
                check(array, info)
                diagnostics(array)
        node.create_subscription(message_type, endpoint.name, callback, QUEUE_DEPTH)
    inputs = []
    for endpoint in _inputs_taken(interface, started):
        publisher = node.create_publisher(endpoint.message_type, endpoint.name, QUEUE_DEPTH)
        inputs.append((endpoint.name, publisher, MessageFuzzer(
            endpoint.message_type, rng, hints, endpoint.name)))
    services = parameter_clients(node, fqn)

    def fail(problem):
        report.problems.append(problem)
        return report

    if not client.wait(lambda: all(publisher.get_subscription_count() >= 1
                                   for _, publisher, _ in inputs)
                       and diagnostics.count(fqn) >= 1, DEADLINE, [process]):
        return fail(f'{settings.node} not matched on its inputs and /diagnostics within '
                    f'{DEADLINE} s (running: {process.running()})')
    if clock is None:
        # Built by now (it answers): its clock's origin is behind us.
        outputs.streams.set_origin_range((invariants.origin_range[0], time.time() + 1.0))
    fuzzer = parameter_fuzzer_of(client, services, rng)
    if fuzzer is None:
        return fail(f'{settings.node} did not list or describe its parameters')
    requests = ParameterRequests(fuzzer, invariants)
    phase('start')

    # The flood: inputs in random order, parameter requests mixed in, huge and oversized
    # messages spread over it.
    huge_inputs = [entry for entry in inputs if has_sequence(entry[2].message_type)]
    special = [('huge', huge_inputs[number % len(huge_inputs)], None)
               for number in range(settings.huge if huge_inputs else 0)]
    special += [('oversized', entry, place) for _ in range(settings.oversized)
                for entry in inputs for place in entry[2].oversized_places()]
    huge_at = {}
    for number, (kind, (topic, publisher, generator), place) in enumerate(
            special if settings.messages else ()):
        index = (number + 1) * settings.messages // (len(special) + 1)
        huge_at[index] = (topic, publisher, kind) + (
            generator.message(kind) if place is None else generator.oversized(place))
    datagrams = None if inputs else _datagram_input(client, services, settings.node)
    start = time.monotonic()
    recent = {topic: [] for topic, _, _ in inputs}
    for index in paced(settings.rate, settings.messages):
        if datagrams is not None:
            # A node whose input is a UDP socket (telemetry_bridge): hostile datagrams.
            topic, send = datagrams
            kind = send(rng)
            report.sent[topic] = report.sent.get(topic, 0) + 1
            report.kinds[kind] = report.kinds.get(kind, 0) + 1
        elif index in huge_at:
            topic, publisher, kind, message, done = huge_at[index]
        else:
            topic, publisher, generator = inputs[rng.randrange(len(inputs))]
            kind = choose_kind(rng)
            message, done = generator.message(kind)
        if datagrams is None:
            publisher.publish(message)
            report.sent[topic] = report.sent.get(topic, 0) + 1
            report.kinds[kind] = report.kinds.get(kind, 0) + 1
            recent[topic] = (recent[topic] + [
                f'#{index} {kind}: {summarize(done) or "as drawn"}'])[-KEPT_DESCRIPTIONS:]
        if settings.parameter_every and index % settings.parameter_every == 0:
            atomic = rng.random() < 0.1
            changes = fuzzer.changes(rng.randint(1, 3))
            requests.send(services[SetParametersAtomically if atomic else SetParameters],
                          changes, atomic)
        if index % 100 == 0 and not process.running():
            report.recent = recent
            return fail(f'{settings.node} exited during the flood, after message {index}')
    report.duration = time.monotonic() - start
    report.recent = recent
    phase('flood')

    # Alive and answering: a parameter request, then every declared service.
    flood_end = diagnostics.count(fqn)
    answer = client.call(services[GetParameters], GetParameters.Request(
        names=sorted(fuzzer.descriptors)), DEADLINE)
    if answer is None:
        return fail(f'{settings.node} did not answer get_parameters within {DEADLINE} s after '
                    f'the flood (running: {process.running()})')
    for endpoint in interface.of_kind(SERVICE):
        # A relative service name resolves in the namespace, as the node's does.
        service = node.create_client(endpoint.message_type, endpoint.name)
        if client.call(service, endpoint.message_type.Request(), DEADLINE) is None:
            report.problems.append(f'{settings.node} did not answer {endpoint.name} within '
                                   f'{DEADLINE} s')
    # A request can be lost: the service's queue (depth 10) overflows while the node is busy,
    # as a topic's does. The node may have applied a lost request's changes, or not.
    client.wait(requests.done, DEADLINE, [process])
    requests.forget_unanswered()
    if not client.wait(lambda: diagnostics.settled(fqn, flood_end, report.sent), SETTLE_DEADLINE,
                       [process]):
        report.problems.append(f'{settings.node} still receiving {SETTLE_DEADLINE} s after the '
                               f'flood (running: {process.running()})')
    phase('settle')
    finish = []
    if settings.to_play and process.running():
        run = ScenarioRun(fqn, client, process, {topic: publisher for topic, publisher, _
                                                 in inputs}, services, requests, invariants,
                          diagnostics, report, rng, files, clock)
        for scenario in settings.to_play:
            if process.running():
                scenario.play(run, settings.scenarios)
        finish = run.finish
        scenario_end = diagnostics.count(fqn)
        client.wait(requests.done, DEADLINE, [process])
        if not client.wait(lambda: diagnostics.settled(fqn, scenario_end, report.sent),
                           SETTLE_DEADLINE, [process]):
            report.problems.append(f'{settings.node} still receiving {SETTLE_DEADLINE} s after '
                                   f'the scenario (running: {process.running()})')
        phase('scenario')
    report.problems += requests.problems
    report.problems += held_value_problems(client, services, fuzzer, DEADLINE)
    latest = diagnostics.reports(fqn).latest
    report.problems += outputs.problems(braking_allowance(latest))
    for check in finish:
        report.problems += check()
    report.problems += diagnostics.problems(fqn, report.sent)
    reports = diagnostics.reports(fqn)
    report.reports = len(reports.stamps)
    report.outputs = dict(outputs.counts)
    report.parameter_changes = dict(requests.counts)
    for counters in reports.latest.values():
        report.published += counters['published']
        for code, count in counters['rejected_by_code'].items():
            report.rejections[code] = report.rejections.get(code, 0) + count
    if not process.running():
        report.problems.append(f'{settings.node} exited after the flood')
    return report


def has_sequence(message_type) -> bool:
    """Whether a message type has a sequence field (one that can be made huge)."""
    return any(isinstance(slot, definition.UnboundedSequence) for slot in message_type.SLOT_TYPES)


# The command line --------------------------------------------------------------------------


def parse_arguments(argv):
    """Command-line options of the long fuzz run."""
    parser = argparse.ArgumentParser(
        description='Fuzz every node of the package (or those named) as processes: rounds of '
                    'hostile messages and parameter changes, each round with its own seed.')
    parser.add_argument('--minutes', type=positive_number, default=None,
                        help='run rounds until this many minutes have passed (default: one '
                             'round)')
    parser.add_argument('--node', action='append', choices=sorted(NODE_INTERFACES),
                        help='fuzz this node (repeatable; default: every declared node)')
    parser.add_argument('--seed', type=int, default=None,
                        help='seed of the first round (default: random); round k uses seed + k')
    parser.add_argument('--messages', type=int, default=20000,
                        help='messages per node and round (default: 20000)')
    parser.add_argument('--rate', type=number_in(1.0, 10000.0), default=1000.0,
                        help='messages a second at most (default: 1000)')
    parser.add_argument('--huge', type=int, default=3,
                        help='messages with 10^5 elements per node and round (default: 3)')
    parser.add_argument('--oversized', type=int, default=1,
                        help='rounds of oversized messages per node and round: one message '
                             'per input and per field it can grow (10^6 numbers, 10^6 '
                             'characters, 10^5 names or elements; default: 1)')
    parser.add_argument('--scenarios', type=int, default=1,
                        help="rounds of each node's scenario after the flood (issue 27's "
                             'cases: low validation_rate and bulging trajectories; noisy and '
                             'fast IMU input in lockstep with a simulated clock; default: 1; '
                             '0: none)')
    parser.add_argument('--scenario', dest='only', action='append', default=[],
                        choices=scenario_names(),
                        help='play this scenario only (repeatable; default: every scenario of '
                             'each node)')
    parser.add_argument('--executable', default=None,
                        help='the console script to start (a path), instead of the installed '
                             'one: to fuzz another build; with one --node')
    parser.add_argument('--no-variant', dest='variant', action='store_false',
                        help='start the nodes with the parameter files alone (default: with a '
                             'start-up variant of their read-only parameters drawn from the '
                             'seed)')
    arguments = parser.parse_args(argv)
    if (arguments.messages < 0 or arguments.huge < 0 or arguments.oversized < 0
            or arguments.scenarios < 0):
        parser.error('--messages, --huge, --oversized and --scenarios must be at least 0')
    if arguments.executable and len(arguments.node or []) != 1:
        parser.error('--executable needs exactly one --node')
    return arguments


def main(argv=None) -> int:
    """Fuzz the nodes in rounds; exit 1 with the replay options of every failed round."""
    arguments = parse_arguments(argv)
    nodes = arguments.node or sorted(NODE_INTERFACES)
    seed = arguments.seed if arguments.seed is not None else random.randrange(2 ** 32)
    end = time.monotonic() + 60.0 * (arguments.minutes or 0.0)
    failures = []
    with isolated_ros_environment():
        rclpy.init(args=[])
        try:
            for round_number in range(10 ** 9):
                for node in nodes:
                    settings = FuzzSettings(node, seed + round_number, arguments.messages,
                                            arguments.rate, huge=arguments.huge,
                                            oversized=arguments.oversized,
                                            variant=arguments.variant,
                                            scenarios=arguments.scenarios,
                                            only=tuple(arguments.only),
                                            executable=arguments.executable)
                    report = fuzz_node(settings)
                    print(report.summary(), flush=True)
                    if report.problems:
                        print(report.failure(), flush=True)
                        failures.append(settings.replay_options())
                if time.monotonic() >= end:
                    break
        except KeyboardInterrupt:
            print('interrupted', file=sys.stderr)
        finally:
            rclpy.try_shutdown()
    for options in failures:
        print(f'FAILED: replay with python -m fuzzing.node_fuzzer {options}')
    print(f'{len(failures)} failed round(s)')
    return 1 if failures else 0


if __name__ == '__main__':
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    raise SystemExit(main())
