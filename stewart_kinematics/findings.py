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
Findings: why the core refused an input, or what it warns about, in words and in numbers.

The decision objects (:class:`stewart_kinematics.PoseTracker`,
:class:`stewart_kinematics.CommandCheck`) never raise for input they cannot use: they return a
result that carries a :class:`Finding`. Its ``code`` is short and stable, to count by (the nodes
count their refusals by it on ``/diagnostics``); its ``message`` is a sentence a user can act
on; its ``details`` are ``(key, value)`` pairs such as iterations, residual or the violated
limits. Nothing here imports ROS.
"""

from dataclasses import dataclass
from typing import Tuple

#: Codes of the findings, one per kind of refusal or warning.
INVALID_POSE = 'invalid_pose'
INVALID_TWIST = 'invalid_twist'
INVALID_LENGTHS = 'invalid_lengths'
INVALID_VELOCITIES = 'invalid_velocities'
OUT_OF_LIMITS = 'out_of_limits'
UNREACHABLE = 'unreachable'
NO_POSE_YET = 'no_pose_yet'
NO_SOLUTION = 'no_solution'
INACCURATE_POSE = 'inaccurate_pose'
ASSEMBLY_MODE_JUMP = 'assembly_mode_jump'
AMBIGUOUS_ASSEMBLY_MODE = 'ambiguous_assembly_mode'
ASSEMBLY_MODE_MARGIN = 'assembly_mode_margin'
NEAR_SINGULARITY = 'near_singularity'
#: Refusals of a trajectory: only leg velocity or acceleration broken, no timing found, and a
#: trajectory that is malformed (for a caller that converts messages).
TOO_FAST = 'too_fast'
RETIMING_FAILED = 'retiming_failed'
INVALID_TRAJECTORY = 'invalid_trajectory'
#: Motion cueing (stewart_kinematics.cueing): a vehicle motion sample refused (malformed, not
#: finite or absurd), a sample whose time does not come after the previous one's, and warnings:
#: a gap in the input, the cue scaled toward neutral to keep the limits, the actuators' speed
#: limits holding the platform back, and a pose held because it would have left the limits.
INVALID_VEHICLE_MOTION = 'invalid_vehicle_motion'
TIME_NOT_INCREASING = 'time_not_increasing'
INPUT_GAP = 'input_gap'
CUE_SCALED = 'cue_scaled'
ACTUATOR_LIMITED = 'actuator_limited'
LIMITS_HELD = 'limits_held'


@dataclass(frozen=True)
class Finding:
    """
    One reason to refuse an input, or to warn about an accepted one.

    :param code: short and stable, such as ``out_of_limits``: what the refusals are counted by.
    :param message: a sentence a user can act on, with the values concerned.
    :param details: ``(key, value)`` pairs of text, such as ``('iterations', '50')``.
    """

    code: str
    message: str
    details: Tuple[Tuple[str, str], ...] = ()

    def __str__(self):
        return self.message


class Decision:
    """
    What every result of a decision object says: accepted, or refused and why.

    A subclass is a dataclass with a ``refusal`` field (a :class:`Finding`, or ``None`` when
    the input was accepted) and a ``warnings`` field (findings about an accepted input).
    """

    @property
    def accepted(self) -> bool:
        """Whether the input was accepted."""
        return self.refusal is None

    @property
    def reason(self) -> str:
        """Why the input was refused, as a sentence; ``''`` when it was accepted."""
        return '' if self.refusal is None else self.refusal.message


def violation_details(violations) -> Tuple[Tuple[str, str], ...]:
    """
    ``(key, value)`` pairs of :class:`~stewart_kinematics.limits.Violation`, for a Finding.

    The key names the limit and the leg (``leg_length_max leg 3``), the value gives the value
    reached and the limit, with their unit.
    """
    pairs = []
    for violation in violations:
        unit = f' {violation.unit}' if violation.unit else ''
        key = violation.limit + (f' leg {violation.leg}' if violation.leg else '')
        pairs.append((key, f'{violation.value:.6g}{unit} (limit {violation.allowed:.6g}{unit})'))
    return tuple(pairs)


def out_of_limits(subject: str, violations) -> Finding:
    """
    Build the refusal of something that breaks limits, listing every violation.

    :param subject: what breaks them, with its verb, such as ``'the pose is'``.
    :param violations: the :class:`~stewart_kinematics.limits.Violation` list, not empty.
    """
    return Finding(OUT_OF_LIMITS,
                   f'{subject} out of the limits: ' + '; '.join(map(str, violations)),
                   violation_details(violations))
