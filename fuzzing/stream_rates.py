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
The leg rates of a command stream as it goes out on the wire: the oracle of a motion.

A node that streams commands (ik_node's ``joint_commands`` with ``command_rate``,
motion_cueing_node's ``target_pose``) sends each as a sample of a motion, at the time it sends
it by its own clock, and its command gate (:class:`stewart_kinematics.limits.CommandGate`, a
``MOTION`` gate) lets a command out only when the divided differences of the commanded leg
lengths keep the leg limits. With ``h_k`` the time between command ``k - 1`` and ``k``:

- velocity ``w_k = (l_k - l_k-1) / h_k``,
- acceleration ``a_k = (w_k - w_k-1) / ((h_k + h_k-1) / 2)``,
- jerk ``j_k = (a_k - a_k-1) / ((h_k + h_k-1 + h_k-2) / 3)`` (ik_node's stream only).

:class:`LegRateStream` computes the same from what it sees: the send times (a stamped
command's ``header.stamp``, which is the node's clock when it sent it; for an unstamped one the
times the fuzzer made the node's simulated clock read, in lockstep) and the leg lengths of each
message. It forgives only rounding, and never less than the gate does: the gate's own
forgiveness (a few units in the last place of the lengths, divided by the intervals), the
rounding between the gate's numbers and the message's (positions plus offsets, a pose read
back), and the rounding of the gate's times (seconds since its clock's origin, which the wire
does not show: bounded by :attr:`LegRateStream.origin_range`). So a stream the gate passed
raises nothing, and a stream that asks a leg for more than its limit anywhere between two
commands is found, command by command.

Only the gate's braking command (``command_braking``) may break a rate limit (a leg stopped
at the end of its stroke stops within one command); the stream cannot tell one from the wire,
so the callers compare the number of commands found with the node's ``command_braking``
counts on ``/diagnostics`` (:func:`braking_allowance`).

A time that does not come after the last one (a simulated clock moved back) starts a new time
line: the gate goes on from its last command at a time the wire does not show, so the next
command is not checked (its interval is not known), the one after it for its velocity, and so
on: no rate is checked across a jump back. Units: metres, seconds.
"""

import math
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

#: Unit roundoff of a float.
EPSILON = float(np.finfo(float).eps)
#: Relative slack on each rate limit: the gate's (``RATE_SLACK``), doubled.
LIMIT_SLACK = 2e-9
#: The gate forgives about 8 ulps of the lengths per order of difference; this many are
#: forgiven here, so that this check never forgives less.
GATE_ROUNDING = 16.0
#: How far the lengths read from a message may be from the gate's, in ulps of the largest of a
#: length and an actuator offset (positions plus offsets; a pose read back through its frames).
WIRE_ROUNDING = 64.0
#: Codes a node counts for a command that may break a limit: a braking command (a leg stopped
#: at its stroke's end, a cone passed while braking) and the commands that bring the platform
#: back within its limits after one.
ALLOWED_CODES = ('command_braking', 'returning_to_limits')
#: Problems a stream keeps in words, at most (the rest are counted).
KEPT_PROBLEMS = 20


class LegRateStream:
    """
    Check the leg rates between consecutive commands of one stream, as the gate checks them.

    :param actuator_limits: the legs' :class:`~stewart_kinematics.ActuatorLimits`.
    :param jerk: whether the node's gate checks the jerk (ik_node's stream does, the cue does
        not).
    :param origin_range: ``(earliest, latest)`` seconds of the node's clock its origin can have
        (the gate's times are seconds since it): bounds the rounding of the gate's times.
    :param name: what the stream is, for the problems (``joint_commands``).
    """

    def __init__(self, actuator_limits, jerk: bool, origin_range: Tuple[float, float] = (
            0.0, 0.0), name: str = 'commands'):
        self.limits = (('velocity', actuator_limits.velocity_max, 'm/s'),
                       ('acceleration', actuator_limits.acceleration_max, 'm/s^2'),
                       ('jerk', actuator_limits.jerk_max if jerk else math.inf, 'm/s^3'))
        self.origin_range = origin_range
        self.name = name
        #: Commands checked, commands found beyond a rate limit, and the first of them in words.
        self.checked = 0
        self.violations = 0
        self.problems: List[str] = []
        self.reset()

    def reset(self) -> None:
        """Start a new time line: the next command has no known predecessor."""
        self._time_ns: Optional[int] = None
        self._lengths: Optional[np.ndarray] = None
        self._radius = 0.0
        #: The divided differences of the last command, each ``(value (6,), error (6,))``, or
        #: ``None`` when not known; the last intervals and their errors, newest first.
        self._velocity = None
        self._acceleration = None
        self._intervals: Tuple[Tuple[float, float], ...] = ()

    def add(self, time_ns: int, lengths, offsets=None) -> List[str]:
        """
        Take the next command: its send time and leg lengths; say what it breaks.

        :param time_ns: when it was sent, nanoseconds of the node's clock (``header.stamp``, or
            the lockstep's time).
        :param lengths: its leg lengths, metres, shape (6,).
        :param offsets: the actuators' offsets the lengths were read with (their rounding),
            metres, or ``None``.
        :returns: the rates beyond a limit, in words (empty: none); also kept in
            :attr:`problems` (the first :data:`KEPT_PROBLEMS`) and counted in
            :attr:`violations`.
        """
        lengths = np.asarray(lengths, dtype=float)
        time_ns = int(time_ns)
        if lengths.shape != (6,) or not np.all(np.isfinite(lengths)):
            self.reset()
            return []
        radius = self._time_radius(time_ns)
        if self._time_ns is None or time_ns <= self._time_ns:
            self.reset()
            self._time_ns, self._lengths, self._radius = time_ns, lengths, radius
            return []
        interval = (time_ns - self._time_ns) * 1e-9
        # How far the gate's interval may be from this one: its two times' rounding, and this
        # one's (a difference of integers, exact, times 1e-9).
        interval_error = radius + self._radius + EPSILON * interval
        size = max(float(np.max(np.abs(lengths))), 1.0)
        if offsets is not None:
            size = max(size, float(np.max(np.abs(offsets))))
        wire = WIRE_ROUNDING * EPSILON * size
        gate = GATE_ROUNDING * EPSILON * size
        # Each divided difference: its value here, how far the gate's may be from it (the
        # lengths' and the intervals' rounding, twice over for the second-order terms), and
        # the gate's own forgiveness on top.
        velocity = (lengths - self._lengths) / interval
        velocity_error = (2.0 * wire + 2.0 * np.abs(velocity) * interval_error) / interval
        found = self._beyond('velocity', velocity, velocity_error + 2.0 * gate / interval)
        acceleration = None
        if self._velocity is not None:
            (last, last_error), = self._intervals[:1]
            span = 0.5 * (interval + last)
            span_error = 0.5 * (interval_error + last_error)
            previous, previous_error = self._velocity
            value = (velocity - previous) / span
            error = (velocity_error + previous_error + 2.0 * np.abs(value) * span_error) / span
            acceleration = (value, error)
            found += self._beyond('acceleration', value,
                                  error + 4.0 * gate / (min(interval, last) * span))
            if self._acceleration is not None and len(self._intervals) >= 2:
                before, before_error = self._intervals[1]
                third = (interval + last + before) / 3.0
                third_error = (interval_error + last_error + before_error) / 3.0
                previous, previous_error = self._acceleration
                jerk = (value - previous) / third
                jerk_error = (error + previous_error + 2.0 * np.abs(jerk) * third_error) / third
                found += self._beyond('jerk', jerk, jerk_error + 8.0 * gate / (
                    min(interval, last, before) * span * third))
        self.checked += 1
        self._intervals = ((interval, interval_error),) + self._intervals[:1]
        self._velocity = (velocity, velocity_error)
        self._acceleration = acceleration
        self._time_ns, self._lengths, self._radius = time_ns, lengths, radius
        if found:
            self.violations += 1
            text = (f'{self.name} sent at {time_ns * 1e-9:.9f} s ({interval * 1e3:.6g} ms after '
                    f'the last): ' + '; '.join(found))
            if len(self.problems) < KEPT_PROBLEMS:
                self.problems.append(text)
            return [text]
        return []

    def _time_radius(self, time_ns) -> float:
        """
        Return how far the gate's time of a command may be from its exact value, seconds.

        The gate's times are ``(ns - origin) * 1e-9``: an integer made a float, then a product,
        each rounded to half a unit in the last place of the seconds since the origin, which
        lies in :attr:`origin_range`.
        """
        seconds = time_ns * 1e-9
        earliest, latest = self.origin_range
        return 2.0 * EPSILON * max(abs(seconds - earliest), abs(seconds - latest), 1.0)

    def _beyond(self, quantity, values, forgiven) -> List[str]:
        """Say which legs' ``values`` pass the limit of ``quantity`` beyond what is forgiven."""
        limit, unit = next((limit, unit) for name, limit, unit in self.limits
                           if name == quantity)
        if not math.isfinite(limit):
            return []
        excess = np.abs(values) - forgiven - limit * (1.0 + LIMIT_SLACK)
        return [f'leg {leg + 1} {quantity} {values[leg]:.6g} {unit} beyond {limit:g} {unit}'
                for leg in np.flatnonzero(excess > 0.0)]


def braking_allowance(latest: Dict[str, Dict[str, object]]) -> int:
    """
    Return how many commands a node said may break a limit: its :data:`ALLOWED_CODES` counts.

    :param latest: the node's statuses' counters, by status name (as
        :class:`~fuzzing.fuzz_client.NodeReports` ``latest`` or the soak's totals hold them).
    """
    total = 0
    for counters in latest.values():
        for key in ('rejected_by_code', 'warned_by_code'):
            total += sum(counters.get(key, {}).get(code, 0) for code in ALLOWED_CODES)
    return total


def allowance_problems(found: int, allowed: int, examples: Sequence[str], what: str) -> List[str]:
    """
    Say whether more commands broke a limit than the node's findings allow.

    :param found: commands found beyond a limit; ``allowed``: :func:`braking_allowance`.
    :param examples: some of them in words.
    :param what: the stream or the node, in words.
    """
    if found <= allowed:
        return []
    return ([f'{what}: {found} command(s) beyond a limit, more than the {allowed} the node '
             f'counted as {" or ".join(ALLOWED_CODES)} on /diagnostics']
            + [f'  {example}' for example in examples[:5]])
