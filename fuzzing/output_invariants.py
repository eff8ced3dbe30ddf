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
What every message a node publishes must satisfy, whatever it was sent: the fuzzer's oracle.

:class:`OutputInvariants` checks any published message, of any type, for two things without
knowing its type: every number is finite, and every geometry_msgs/Quaternion is a unit one. A
topic whose name says what it carries gets the limits too, checked with the package's
:class:`~stewart_kinematics.limits.LimitModel` built from the same parameter files as the node:

- ``leg_lengths``, ``leg_extensions`` (plus the home lengths), ``joint_commands`` (positions
  plus ``actuator_offsets``) and ``leg_trajectory`` (each point): within the stroke;
- ``leg_velocities``, and the velocities of ``joint_commands`` and ``leg_trajectory``:
  within ``leg_velocity_max`` (and the trajectory's accelerations within
  ``leg_acceleration_max``); a trajectory's times increase;
- a topic named ``*pose`` or ``*pose_stamped`` (Pose or PoseStamped): the pose of the tool
  frame, whose platform pose keeps every pose limit (stroke, joint cones, singularity margin,
  leg collisions) under one of the frame trees the node had while the message was sent
  (:meth:`OutputInvariants.add_frames` adds one after an accepted tool frame change).

A command stream (``joint_commands`` of an ik_node with ``command_rate``: every message a sample
of a motion, stamped with the time it is sent) is checked across messages too: the leg
velocity, acceleration and jerk between consecutive commands, as divided differences of the
lengths by the stamps, within the limits (:class:`~fuzzing.stream_rates.LegRateStream`, kept by
:class:`OutputLog`). Only a braking command may break a rate or, on a pose topic, a pose limit
(a leg stopped at its stroke's end, a cone passed while braking, and the commands that come
back): :meth:`OutputLog.problems` allows as many such outputs as the node counted
``command_braking`` and ``returning_to_limits`` findings on ``/diagnostics``, and no more.

A topic of another name is still checked for finite numbers and unit quaternions: a node added
later is covered by those without a change here. Limits are checked to a relative
:data:`TOLERANCE`: the rounding of a pose sent as a quaternion, not a margin.

Text is bounded too, whatever the input was (issue 27: one refusal echoed a million values):
no string of any output, ``/diagnostics`` included, is longer than :data:`MAX_OUTPUT_STRING`
(:func:`string_problems`), and no line of a node's log longer than :data:`MAX_LOG_LINE`
(:func:`log_problems`).
"""

import functools
import math
import threading
from typing import Dict, List, Sequence

from fuzzing.fuzz_messages import fields_of, message_class, type_name
from fuzzing.stream_rates import allowance_problems, LegRateStream
import numpy as np
from rosidl_parser import definition

from stewart_kinematics.limits import LimitModel
from stewart_kinematics.model.frames import Transform
from stewart_kinematics.model.rotations import quaternion_to_matrix
from stewart_kinematics.parameters import (
    actuator_interface_from_settings,
    actuator_limits_from_settings,
    ActuatorSettings,
    frames_from_parameters,
    geometry_from_parameters,
    GeometrySettings,
    read_parameter_files,
)
from stewart_kinematics.ros.message_accounting import MAX_TEXT_LENGTH

#: Relative slack on every limit (and absolute, in the limit's unit, near zero).
TOLERANCE = 1e-9
#: Largest distance of a published quaternion's norm from 1.
QUATERNION_TOLERANCE = 1e-6
#: Problems reported per message, at most.
MAX_PROBLEMS = 3
#: Failing output messages an :class:`OutputLog` keeps for its final check.
KEPT_FAILURES = 100
#: Longest string an output may carry, characters: the bound of the nodes' /diagnostics
#: strings; frame and joint names are far shorter.
MAX_OUTPUT_STRING = MAX_TEXT_LENGTH
#: Characters of a log line before its message: severity, time and logger name, as rclpy
#: writes them (``[WARN] [1715683432.123456789] [ns.fk_node]: ``), with room for a namespace.
LOG_PREFIX_ROOM = 200
#: Longest line of a node's output.
MAX_LOG_LINE = MAX_TEXT_LENGTH + LOG_PREFIX_ROOM


@functools.lru_cache(maxsize=None)
def _fields(message_type):
    return tuple(fields_of(message_type))


def numbers_problems(message, path: str = '') -> List[str]:
    """
    Every non-finite number and non-unit quaternion of a message, in words (empty: none).

    Walks the message through its rosidl fields, so any type is checked.
    """
    problems = []
    if type_name(type(message)) == 'geometry_msgs/Quaternion':
        norm = math.sqrt(message.x ** 2 + message.y ** 2 + message.z ** 2 + message.w ** 2)
        if not abs(norm - 1.0) <= QUATERNION_TOLERANCE:
            problems.append(f'{path or "quaternion"}: norm {norm!r}, not 1')
    for name, slot_type in _fields(type(message)):
        value = getattr(message, name)
        where = f'{path}.{name}' if path else name
        if isinstance(slot_type, definition.NamespacedType):
            problems += numbers_problems(value, where)
        elif isinstance(slot_type, definition.AbstractNestedType):
            element = slot_type.value_type
            if isinstance(element, definition.NamespacedType):
                for index, item in enumerate(value):
                    problems += numbers_problems(item, f'{where}[{index}]')
                    if len(problems) >= MAX_PROBLEMS:
                        break
            elif isinstance(element, definition.BasicType) and element.typename in (
                    'double', 'float', 'long double') and len(value):
                array = np.asarray(value, dtype=float)
                bad = np.flatnonzero(~np.isfinite(array))
                if bad.size:
                    problems.append(f'{where}[{bad[0]}] = {array[bad[0]]!r} '
                                    f'({bad.size} non-finite)')
        elif isinstance(slot_type, definition.BasicType) and slot_type.typename in (
                'double', 'float', 'long double') and not math.isfinite(value):
            problems.append(f'{where} = {value!r}')
        if len(problems) >= MAX_PROBLEMS:
            break
    return problems[:MAX_PROBLEMS]


@functools.lru_cache(maxsize=None)
def _text_fields(message_type):
    """Return the fields of a message type that are or hold strings, at any depth."""
    found = []
    for name, slot_type in _fields(message_type):
        element = getattr(slot_type, 'value_type', slot_type)
        if isinstance(element, definition.AbstractGenericString) or (
                isinstance(element, definition.NamespacedType)
                and _text_fields(message_class(element))):
            found.append((name, slot_type, element))
    return tuple(found)


def string_problems(message, path: str = '') -> List[str]:
    """
    Every string of a message longer than :data:`MAX_OUTPUT_STRING`, in words (empty: none).

    Walks only the fields that hold strings (a marker's thousands of points are skipped).
    """
    problems = []
    for name, slot_type, element in _text_fields(type(message)):
        value = getattr(message, name)
        where = f'{path}.{name}' if path else name
        items = value if isinstance(slot_type, definition.AbstractNestedType) else [value]
        for index, item in enumerate(items):
            at = f'{where}[{index}]' if items is value else where
            if isinstance(element, definition.NamespacedType):
                problems += string_problems(item, at)
            elif len(item) > MAX_OUTPUT_STRING:
                problems.append(f'{at}: a string of {len(item):,} characters (at most '
                                f'{MAX_OUTPUT_STRING:,}), starting {item[:60]!r}')
            if len(problems) >= MAX_PROBLEMS:
                return problems[:MAX_PROBLEMS]
    return problems


def log_problems(output: str) -> List[str]:
    """Every line of a node's output longer than :data:`MAX_LOG_LINE`, in words (empty: none)."""
    problems = []
    for number, line in enumerate(output.splitlines(), 1):
        if len(line) > MAX_LOG_LINE:
            problems.append(f'log line {number} has {len(line):,} characters (at most '
                            f'{MAX_LOG_LINE:,}): {line[:160]!r}...')
            if len(problems) >= MAX_PROBLEMS:
                break
    return problems


def _beyond(values, low, high) -> np.ndarray:
    """Return the indices of values outside [low, high], with the relative :data:`TOLERANCE`."""
    values = np.asarray(values, dtype=float)
    slack_low = TOLERANCE * max(1.0, abs(low)) if math.isfinite(low) else 0.0
    slack_high = TOLERANCE * max(1.0, abs(high)) if math.isfinite(high) else 0.0
    return np.flatnonzero(~((values >= low - slack_low) & (values <= high + slack_high)))


class OutputInvariants:
    """
    Check published messages against the platform's limits and the numbers' sanity.

    :param geometry: the platform (its stroke and pose limits).
    :param actuator_limits: leg velocity and acceleration limits.
    :param actuators: joint names and offsets (actuator positions = lengths - offsets).
    :param frames: the frame tree the node starts with.
    """

    def __init__(self, geometry, actuator_limits, actuators, frames, streams=()):
        self.geometry = geometry
        self.model = LimitModel(geometry)
        self.actuator_limits = actuator_limits
        self.actuators = actuators
        #: Every frame tree the node may have had while publishing (a change is asynchronous).
        self.frames = [frames]
        self.stroke = (geometry.limits.leg_length_min, geometry.limits.leg_length_max)
        #: The topics (last name part) whose messages are a stamped command stream, checked
        #: across messages for their leg rates (jerk included: ik_node's stream limits it).
        self.streams = frozenset(streams)
        #: Where the publishers' clock origins lie, seconds (:class:`LegRateStream`): a wall
        #: clock's origin is after 0 and before now.
        self.origin_range = (0.0, 2.0 ** 31)

    @classmethod
    def from_parameter_files(cls, paths: Sequence, node_name: str,
                             overrides=None) -> 'OutputInvariants':
        """
        Build the invariants of a node started with these parameter files.

        :param overrides: parameter values given besides the files (``-p name:=value``), by
            name: ``command_rate`` makes ``joint_commands`` a command stream.
        """
        values = dict(read_parameter_files(paths, node_name))
        values.update(overrides or {})
        geometry = geometry_from_parameters(values)
        streams = ['joint_commands'] if (values.get('command_rate') or 0.0) > 0.0 else []
        return cls(geometry, actuator_limits_from_settings(GeometrySettings.from_values(values)),
                   actuator_interface_from_settings(ActuatorSettings.from_values(values)),
                   frames_from_parameters(values), streams)

    def stream(self, topic: str):
        """
        Return a new :class:`LegRateStream` for a topic that is a command stream, or ``None``.

        :param topic: the topic's name; its last part says whether it is one.
        """
        role = topic.rstrip('/').split('/')[-1]
        if role not in self.streams:
            return None
        return LegRateStream(self.actuator_limits, True, self.origin_range, role)

    def stream_command(self, message):
        """
        Return ``(send time, ns; leg lengths (6,))`` of a ``joint_commands`` message, or ``None``.

        ``None`` for a message that names other joints (its own check says so).
        """
        try:
            order = self.actuators.order(list(message.name))
            lengths = self.actuators.lengths(np.asarray(message.position, dtype=float)[order])
        except (ValueError, IndexError):
            return None
        stamp = message.header.stamp
        return stamp.sec * 1_000_000_000 + stamp.nanosec, lengths

    def add_frames(self, values) -> None:
        """
        Add the frame tree of parameter values (a frame change the node may have accepted).

        Values that make no frame tree (names that repeat: a node refuses those) add nothing.
        """
        try:
            frames = frames_from_parameters(values)
        except ValueError:
            return
        if frames not in self.frames:
            self.frames.append(frames)

    def problems(self, topic: str, message) -> List[str]:
        """
        Say what is wrong with a message published on ``topic`` (empty: nothing).

        :param topic: the topic's name; its last part chooses the limit checks.
        """
        problems = (numbers_problems(message) + string_problems(message))[:MAX_PROBLEMS]
        if problems:
            return problems
        role = topic.rstrip('/').split('/')[-1]
        kind = type_name(type(message))
        check = _ROLE_CHECKS.get((role, kind))
        if check is None and (role.endswith('pose') or role.endswith('pose_stamped')) and kind in (
                'geometry_msgs/Pose', 'geometry_msgs/PoseStamped'):
            check = OutputInvariants.pose_problems
        return check(self, message)[:MAX_PROBLEMS] if check is not None else []

    # The checks by role ------------------------------------------------------------------------

    def length_problems(self, lengths, what: str) -> List[str]:
        """Leg lengths outside the stroke, or not six of them."""
        lengths = np.asarray(lengths, dtype=float)
        if lengths.shape != (6,):
            return [f'{what}: {lengths.size} values, not 6']
        low, high = self.stroke
        return [f'{what}: leg {index + 1} length {float(lengths[index])!r} m outside the stroke '
                f'[{low}, {high}]' for index in _beyond(lengths, max(low, 0.0), high)]

    def rate_problems(self, values, limit: float, what: str, unit: str) -> List[str]:
        """Rates beyond ``limit`` in magnitude."""
        values = np.asarray(values, dtype=float)
        return [f'{what}: leg {index + 1} {float(values[index])!r} {unit} beyond {limit} {unit}'
                for index in _beyond(values, -limit, limit)]

    def leg_lengths_problems(self, message) -> List[str]:
        """``leg_lengths``: six lengths within the stroke."""
        return self.length_problems(message.data[message.layout.data_offset:], 'leg_lengths')

    def leg_extensions_problems(self, message) -> List[str]:
        """``leg_extensions``: home lengths plus extensions within the stroke."""
        data = np.asarray(message.data[message.layout.data_offset:], dtype=float)
        if data.shape != (6,):
            return [f'leg_extensions: {data.size} values, not 6']
        return self.length_problems(data + self.geometry.home_leg_lengths, 'leg_extensions')

    def leg_velocities_problems(self, message) -> List[str]:
        """``leg_velocities``: six rates within leg_velocity_max."""
        data = message.data[message.layout.data_offset:]
        if len(data) != 6:
            return [f'leg_velocities: {len(data)} values, not 6']
        return self.rate_problems(data, self.actuator_limits.velocity_max, 'leg_velocities',
                                  'm/s')

    def joint_commands_problems(self, message) -> List[str]:
        """``joint_commands``: the legs' joints, positions within the stroke, rates within."""
        names = tuple(message.name)
        if sorted(names) != sorted(self.actuators.joint_names) or len(message.position) != 6:
            return [f'joint_commands: joints {names} with {len(message.position)} positions, '
                    f'not {self.actuators.joint_names}']
        order = self.actuators.order(list(names))
        lengths = self.actuators.lengths(np.asarray(message.position, dtype=float)[order])
        problems = self.length_problems(lengths, 'joint_commands')
        if len(message.velocity):
            problems += self.rate_problems(message.velocity, self.actuator_limits.velocity_max,
                                           'joint_commands velocity', 'm/s')
        return problems

    def leg_trajectory_problems(self, message) -> List[str]:
        """``leg_trajectory``: every point within the stroke and the rate limits, in time."""
        problems = []
        limits = self.actuator_limits
        previous = -math.inf
        names = list(message.joint_names)
        if sorted(names) != sorted(self.actuators.joint_names):
            return [f'leg_trajectory: joints {names}, not {self.actuators.joint_names}']
        order = self.actuators.order(names)
        for index, point in enumerate(message.points):
            what = f'leg_trajectory point {index}'
            time = point.time_from_start.sec + point.time_from_start.nanosec * 1e-9
            if not time >= previous:
                problems.append(f'{what}: time_from_start {time} s before {previous} s')
            previous = time
            positions = np.asarray(point.positions, dtype=float)
            if positions.shape != (6,):
                problems.append(f'{what}: {positions.size} positions')
                continue
            problems += self.length_problems(self.actuators.lengths(positions[order]), what)
            if len(point.velocities):
                problems += self.rate_problems(point.velocities, limits.velocity_max,
                                               f'{what} velocity', 'm/s')
            if len(point.accelerations):
                problems += self.rate_problems(point.accelerations, limits.acceleration_max,
                                               f'{what} acceleration', 'm/s^2')
            if len(problems) >= MAX_PROBLEMS:
                break
        return problems

    def pose_problems(self, message) -> List[str]:
        """Say why a tool pose breaks a pose limit under every frame tree in force, if it does."""
        frame_id = ''
        if hasattr(message, 'header'):
            frame_id = message.header.frame_id
            message = message.pose
        point, orientation = message.position, message.orientation
        tool = Transform(np.array([point.x, point.y, point.z]), quaternion_to_matrix(
            [orientation.x, orientation.y, orientation.z, orientation.w]))
        reasons = []
        for frames in self.frames:
            try:
                platform = frames.platform_from_tool(tool, frame_id)
            except ValueError as error:
                reasons.append(str(error))
                continue
            try:
                violations = [violation for violation in self.model.check_pose(
                    platform.position, platform.rotation)
                    if violation.excess > TOLERANCE * max(1.0, abs(violation.allowed))]
            except ValueError as error:
                violations = [error]
            if not violations:
                return []
            reasons.append('; '.join(map(str, violations[:MAX_PROBLEMS])))
        return [f'pose ({point.x!r}, {point.y!r}, {point.z!r}) in {frame_id!r} breaks the '
                f'limits under each of the {len(self.frames)} frame tree(s): '
                + ' | '.join(reasons)]


#: The limit checks of the topics whose name says what they carry, by (name, type).
_ROLE_CHECKS = {
    ('leg_lengths', 'std_msgs/Float64MultiArray'): OutputInvariants.leg_lengths_problems,
    ('leg_extensions', 'std_msgs/Float64MultiArray'): OutputInvariants.leg_extensions_problems,
    ('leg_velocities', 'std_msgs/Float64MultiArray'): OutputInvariants.leg_velocities_problems,
    ('joint_commands', 'sensor_msgs/JointState'): OutputInvariants.joint_commands_problems,
    ('leg_trajectory', 'trajectory_msgs/JointTrajectory'):
        OutputInvariants.leg_trajectory_problems,
}


def checked_roles() -> List[str]:
    """Return the topic names that get limit checks besides the numbers (for the docs)."""
    return sorted({role for role, _ in _ROLE_CHECKS} | {'*pose', '*pose_stamped'})


class StreamChecks:
    """
    The command streams among a node's outputs, each checked across its messages.

    One :class:`~fuzzing.stream_rates.LegRateStream` per topic that
    :attr:`OutputInvariants.streams` names. A new publisher on a topic (its sequence numbers
    start again: a node started again) starts a new time line. Not thread-safe: the caller
    holds its lock.

    :param invariants: the :class:`OutputInvariants` that say which topics are streams.
    """

    def __init__(self, invariants: OutputInvariants):
        self.invariants = invariants
        self.streams: Dict[str, LegRateStream] = {}
        self._sequence: Dict[str, int] = {}

    def check(self, topic: str, message, info=None) -> None:
        """Check one output message (of a stream topic; others are ignored) against the last."""
        if topic not in self.streams:
            stream = self.invariants.stream(topic)
            if stream is None:
                return
            self.streams[topic] = stream
        stream = self.streams[topic]
        sequence = info.get('publication_sequence_number') if isinstance(info, dict) else None
        last = self._sequence.get(topic)
        if sequence is not None:
            if last is not None and sequence <= last:
                stream.reset()   # a new publisher: a node started again
            self._sequence[topic] = sequence
        command = self.invariants.stream_command(message)
        if command is None:
            stream.reset()
            return
        stream.add(*command, self.invariants.actuators.offsets)

    def set_origin_range(self, origin_range) -> None:
        """Say where the publishers' clock origins lie, seconds (see :class:`LegRateStream`)."""
        self.invariants.origin_range = origin_range
        for stream in self.streams.values():
            stream.origin_range = origin_range

    @property
    def violations(self) -> int:
        """Return how many stream commands broke a rate limit."""
        return sum(stream.violations for stream in self.streams.values())

    @property
    def checked(self) -> int:
        """Return how many stream commands were checked for their rates."""
        return sum(stream.checked for stream in self.streams.values())

    def problems(self) -> List[str]:
        """Return the first of the commands that broke a rate limit, in words."""
        return [problem for stream in self.streams.values() for problem in stream.problems]


class OutputLog:
    """
    Subscription callbacks that check every output of a node: counts, and the failures kept.

    A failing message is kept (:data:`KEPT_FAILURES` at most) and checked again at the end by
    :meth:`problems`, against every frame tree seen by then: a frame change is asynchronous,
    and an output may arrive before the answer that says its frames changed. A command stream
    (:attr:`OutputInvariants.streams`) is checked across its messages as they arrive
    (:class:`StreamChecks`).

    :param invariants: the :class:`OutputInvariants` to check with.
    """

    def __init__(self, invariants: OutputInvariants):
        self.invariants = invariants
        self.counts: Dict[str, int] = {}
        self.failures = []
        self.failure_count = 0
        #: The command streams' checks.
        self.streams = StreamChecks(invariants)
        self._lock = threading.Lock()

    def callback(self, topic):
        """Return the subscription callback of one output topic (it takes the message info)."""
        def on_message(message, info):
            problems = self.invariants.problems(topic, message)
            with self._lock:
                self.counts[topic] = self.counts.get(topic, 0) + 1
                if problems:
                    self.failure_count += 1
                    if len(self.failures) < KEPT_FAILURES:
                        self.failures.append((topic, message))
                self.streams.check(topic, message, info)
        return on_message

    def problems(self, allowance: int = 0) -> List[str]:
        """
        Check the failing messages again, against every frame tree seen: what still fails.

        :param allowance: how many outputs may break a limit because the node said so: its
            ``command_braking`` and ``returning_to_limits`` counts on /diagnostics
            (:func:`~fuzzing.stream_rates.braking_allowance`). Only a pose beyond a pose limit
            and a command stream's rates are allowed; nothing non-finite, no long string, no
            leg length or trajectory point beyond the stroke.
        """
        problems, allowed, by_topic = [], [], {}
        with self._lock:
            failures = list(self.failures)
            streamed, examples = self.streams.violations, self.streams.problems()
        for topic, message in failures:
            found = [f'published on {topic}: {problem}'
                     for problem in self.invariants.problems(topic, message)]
            if found and allowable(topic, message):
                allowed += found[:1]
                by_topic[topic] = by_topic.get(topic, 0) + 1
            else:
                problems += found
        if problems and self.failure_count > len(failures):
            problems.append(f'... {self.failure_count} failing output messages in all')
        # One braking command goes out on each pose topic of the node (motion_cueing_node:
        # target_pose and its platform pose on cue_pose): counted once, by its busiest topic.
        problems += allowance_problems(max(by_topic.values(), default=0) + streamed, allowance,
                                       allowed + examples,
                                       'poses beyond a pose limit and streams beyond a rate')
        return problems


def allowable(topic: str, message) -> bool:
    """Whether a failing output may be a braking command: a pose, finite, with short strings."""
    role = topic.rstrip('/').split('/')[-1]
    return ((role.endswith('pose') or role.endswith('pose_stamped'))
            and not numbers_problems(message) and not string_problems(message))
