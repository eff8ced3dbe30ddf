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
The tolerances of a FollowJointTrajectory goal, as ros2_controllers' joint_trajectory_controller.

What a goal's ``path_tolerance``, ``goal_tolerance`` and ``goal_time_tolerance`` mean
(control_msgs/msg/JointTolerance), resolved against the defaults from the parameters exactly
as ``joint_trajectory_controller/tolerances.hpp`` (Jazzy) resolves them
(:func:`resolve_tolerance`): a value > 0 is the tolerance; 0 keeps the default; -1 erases it
(no tolerance: the joint may move without restriction); a resolved tolerance of 0 is not
enforced. Then the checks of one sample (:func:`state_violation`), the path check while the
trajectory runs and the goal check after its end (:class:`ToleranceMonitor`), with the
result codes of control_msgs/action/FollowJointTrajectory.

Where this differs from joint_trajectory_controller, and why:

- A tolerance that is negative but not -1, or not finite, refuses the goal (``invalid_goal``,
  naming the joint and the value); a tolerance naming a joint the goal does not move refuses it
  (``invalid_joints``). The controller logs an error and silently uses its defaults for the
  whole goal: a client's mistake would go unnoticed.
- A resolved ``goal_time_tolerance`` of 0 checks the goal once, at the end time; the
  controller then waits without limit for the goal tolerance, and a client without a timeout
  hangs.
- Acceleration tolerances are resolved but never violated: joint_states carries no
  accelerations (the controller likewise compares accelerations only when it has them).

Units: those of the joints (metres for the legs and x, y, z; radians for roll, pitch, yaw),
their rates per second. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Sequence, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.findings import Decision, Finding

#: control_msgs/action/FollowJointTrajectory result codes.
SUCCESSFUL = 0
INVALID_GOAL = -1
INVALID_JOINTS = -2
OLD_HEADER_TIMESTAMP = -3
PATH_TOLERANCE_VIOLATED = -4
GOAL_TOLERANCE_VIOLATED = -5

#: The value of a JointTolerance field that erases a default tolerance (control_msgs).
ERASE = -1.0
#: How near -1 counts as -1: joint_trajectory_controller's ``numeric_limits<float>::epsilon``.
ERASE_TOLERANCE = float(np.finfo(np.float32).eps)
#: The largest tolerance taken, in the joints' units (or seconds): beyond, a mistake.
TOLERANCE_MAX = 1e6

#: The state variables a tolerance bounds, in JointTolerance's order.
VARIABLES = ('position', 'velocity', 'acceleration')


@dataclass(frozen=True)
class JointToleranceValues:
    """
    One control_msgs/msg/JointTolerance: a joint's tolerances as a goal gives them.

    :param name: the joint.
    :param position: joint units; ``velocity`` per second; ``acceleration`` per second^2; each
        > 0 (the tolerance), 0 (the default) or -1 (none).
    """

    name: str
    position: float = 0.0
    velocity: float = 0.0
    acceleration: float = 0.0


@dataclass(frozen=True)
class StateTolerances:
    """
    Per joint tolerances on the error of a state, arrays of shape (n,), 0 = not enforced.

    :param position: joint units.
    :param velocity: joint units per second.
    :param acceleration: joint units per second^2 (resolved, never violated: see the module).
    """

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray

    @classmethod
    def uniform(cls, count: int, position: float = 0.0, velocity: float = 0.0,
                acceleration: float = 0.0) -> 'StateTolerances':
        """Return the same tolerances for ``count`` joints."""
        return cls(np.full(count, float(position)), np.full(count, float(velocity)),
                   np.full(count, float(acceleration)))


@dataclass(frozen=True)
class SegmentTolerances:
    """
    A goal's tolerances, resolved: while it runs (``path``), at its end (``goal``), and when.

    :param path: the state tolerances checked at every sample before the end.
    :param goal: the state tolerances the measured state must meet after the end.
    :param goal_time: seconds after the end time allowed to meet ``goal``; 0: checked once, at
        the end time.
    """

    path: StateTolerances
    goal: StateTolerances
    goal_time: float


@dataclass(frozen=True)
class ToleranceResolution(Decision):
    """
    :func:`resolve_tolerances`' answer: the tolerances, or why the goal's are refused.

    :param refusal: ``None``, or ``invalid_joints`` / ``invalid_goal``.
    :param tolerances: the resolved :class:`SegmentTolerances`, ``None`` when refused.
    """

    refusal: Optional[Finding]
    tolerances: Optional[SegmentTolerances] = None
    warnings: Tuple[Finding, ...] = ()


def resolve_tolerance(default: float, value: float, what: str) -> float:
    """
    Resolve one tolerance a goal gives against its default (tolerances.hpp's rule).

    :param default: the default tolerance (0 = none).
    :param value: the goal's: > 0 taken, 0 the default, -1 (within float32 epsilon) none.
    :param what: what the value is, for the error (``'path_tolerance of leg_1: position'``).
    :returns: the tolerance; 0 when none is enforced.
    :raises ValueError: for a value that is not finite, beyond :data:`TOLERANCE_MAX`, or
        negative but not -1.

    >>> resolve_tolerance(0.01, 0.0, 'x'), resolve_tolerance(0.01, 0.002, 'x')
    (0.01, 0.002)
    >>> resolve_tolerance(0.01, -1.0, 'x')
    0.0
    """
    value = float(value)
    if not math.isfinite(value) or value > TOLERANCE_MAX:
        raise ValueError(f'{what} is {value!r}: a tolerance must be finite and at most '
                         f'{TOLERANCE_MAX:g}')
    if value > 0.0:
        return value
    if abs(value - ERASE) < ERASE_TOLERANCE:
        return 0.0
    if value < 0.0:
        raise ValueError(f'{what} is {value!r}: give a tolerance > 0, 0 for the default, or -1 '
                         'for none')
    return float(default)


def resolve_tolerances(joint_names: Sequence[str], defaults: SegmentTolerances,
                       path_tolerance: Sequence[JointToleranceValues] = (),
                       goal_tolerance: Sequence[JointToleranceValues] = (),
                       goal_time_tolerance: float = 0.0) -> ToleranceResolution:
    """
    Resolve a goal's tolerances against the defaults, joint by joint, as the controller does.

    :param joint_names: the joints of the goal's joint set, in the order of ``defaults``.
    :param defaults: the tolerances from the parameters.
    :param path_tolerance: the goal's ``path_tolerance`` entries (any joints of the set, in any
        order; a joint not named keeps its defaults).
    :param goal_tolerance: likewise for ``goal_tolerance``.
    :param goal_time_tolerance: seconds: > 0 taken, 0 the default, -1 none (checked at the end
        time only).
    :returns: a :class:`ToleranceResolution`: refused ``invalid_joints`` for a name outside the
        set, ``invalid_goal`` for an illegal value, each naming the entry.
    """
    names = list(joint_names)
    try:
        goal_time = resolve_tolerance(defaults.goal_time, goal_time_tolerance,
                                      'goal_time_tolerance')
    except ValueError as error:
        return ToleranceResolution(Finding(findings.INVALID_GOAL, str(error)))
    resolved = {}
    for field_name, entries, default in (('path_tolerance', path_tolerance, defaults.path),
                                         ('goal_tolerance', goal_tolerance, defaults.goal)):
        arrays = {variable: np.array(getattr(default, variable), dtype=float)
                  for variable in VARIABLES}
        for entry in entries:
            if entry.name not in names:
                return ToleranceResolution(Finding(
                    findings.INVALID_JOINTS,
                    f'{field_name} names joint {entry.name!r}, which the goal does not move '
                    f'(its joints: {", ".join(names)})'))
            index = names.index(entry.name)
            for variable in VARIABLES:
                try:
                    arrays[variable][index] = resolve_tolerance(
                        arrays[variable][index], getattr(entry, variable),
                        f'{field_name} of {entry.name}: {variable}')
                except (TypeError, ValueError) as error:
                    return ToleranceResolution(Finding(findings.INVALID_GOAL, str(error)))
        resolved[field_name] = StateTolerances(**arrays)
    return ToleranceResolution(None, SegmentTolerances(
        resolved['path_tolerance'], resolved['goal_tolerance'], goal_time))


@dataclass(frozen=True)
class ToleranceViolation:
    """
    The worst violated tolerance of one state: which joint, what, and by how much.

    :param joint: the joint's name.
    :param variable: ``'position'`` or ``'velocity'``.
    :param error: desired minus actual, joint units (per second for a velocity).
    :param tolerance: the tolerance broken.
    """

    joint: str
    variable: str
    error: float
    tolerance: float

    @property
    def excess(self) -> float:
        """Return by how much the error exceeds the tolerance, joint units."""
        return abs(self.error) - self.tolerance

    def __str__(self) -> str:
        """Name the joint, the variable, the error, the tolerance and the excess."""
        unit = '/s' if self.variable == 'velocity' else ''
        return (f'{self.joint} {self.variable} error {self.error:.6g}{unit} beyond its tolerance '
                f'{self.tolerance:.6g}{unit} by {self.excess:.3g}{unit}')


def state_violation(joint_names: Sequence[str], tolerances: StateTolerances,
                    position_error, velocity_error=None) -> Optional[ToleranceViolation]:
    """
    Check one state's errors against tolerances (``check_state_tolerance_per_joint``).

    A tolerance of 0 is not enforced; a velocity error that is not known (``None``: the
    measured state carries no velocities) is 0, as the controller takes a missing one.

    :param position_error: desired minus actual positions, shape (n,).
    :param velocity_error: desired minus actual velocities, shape (n,), or ``None``.
    :returns: the violation that exceeds its tolerance most (relative to it), or ``None``.
    """
    worst, worst_ratio = None, 1.0
    for variable, errors in (('position', position_error), ('velocity', velocity_error)):
        if errors is None:
            continue
        errors = np.asarray(errors, dtype=float)
        allowed = getattr(tolerances, variable)
        # A non-finite error (a lost measurement) breaks any tolerance that is enforced.
        with np.errstate(invalid='ignore', divide='ignore'):
            ratios = np.where(allowed > 0.0, np.abs(errors) / np.where(allowed > 0.0, allowed,
                                                                       1.0), 0.0)
        ratios = np.where(np.isnan(ratios), math.inf, ratios)
        index = int(np.argmax(ratios))
        if ratios[index] > worst_ratio:
            worst_ratio = float(ratios[index])
            worst = ToleranceViolation(joint_names[index], variable, float(errors[index]),
                                       float(allowed[index]))
    return worst


@dataclass(frozen=True)
class GoalOutcome:
    """
    How a goal ended, as its FollowJointTrajectory result says it.

    :param error_code: :data:`SUCCESSFUL`, :data:`PATH_TOLERANCE_VIOLATED` or
        :data:`GOAL_TOLERANCE_VIOLATED` (or another code of the action).
    :param error_string: the reason, one line.
    :param finding: the :class:`~stewart_kinematics.findings.Finding`, ``None`` for success.
    """

    error_code: int
    error_string: str
    finding: Optional[Finding] = None

    @property
    def succeeded(self) -> bool:
        """Whether the goal succeeded."""
        return self.error_code == SUCCESSFUL


class ToleranceMonitor:
    """
    The path and goal checks of one running goal, sample by sample (the controller's update).

    Before the end time every measured sample is checked against the path tolerances
    (``PATH_TOLERANCE_VIOLATED``); from the end time on, a sample measured then and within the
    goal tolerances succeeds; at ``end + goal_time`` without one, ``GOAL_TOLERANCE_VIOLATED``
    (with the last sample's worst joint, or saying none was measured).

    :param joint_names: the goal's joints, the order of every array given.
    :param tolerances: the resolved :class:`SegmentTolerances`.
    :param end_time: the trajectory's end, seconds from its start.
    """

    def __init__(self, joint_names: Sequence[str], tolerances: SegmentTolerances,
                 end_time: float):
        self.joint_names = tuple(joint_names)
        self.tolerances = tolerances
        self.end_time = float(end_time)
        self._last_violation = None

    def update(self, time: float, position_error=None, velocity_error=None,
               measured_after_end: bool = False) -> Optional[GoalOutcome]:
        """
        Check the latest measured state at ``time`` (seconds from the trajectory's start).

        :param position_error: desired minus actual positions, shape (n,); ``None`` when no
            state has been measured.
        :param velocity_error: likewise for velocities, or ``None`` (not measured).
        :param measured_after_end: whether that state was measured at or after the end time
            (only such a state can meet the goal).
        :returns: the :class:`GoalOutcome` once the goal is decided, else ``None``.
        """
        if position_error is not None and time < self.end_time:
            violation = state_violation(self.joint_names, self.tolerances.path,
                                        position_error, velocity_error)
            if violation is not None:
                return GoalOutcome(PATH_TOLERANCE_VIOLATED, f'path tolerance violated at '
                                   f'{time:.3f} s: {violation}', Finding(
                                       findings.PATH_TOLERANCE_VIOLATED, str(violation)))
            return None
        if time < self.end_time:
            return None
        if position_error is not None and measured_after_end:
            violation = state_violation(self.joint_names, self.tolerances.goal, position_error,
                                        velocity_error)
            if violation is None:
                return GoalOutcome(SUCCESSFUL, 'Goal successfully reached!')
            self._last_violation = violation
        late = time - self.end_time
        if late < self.tolerances.goal_time:
            return None
        if self._last_violation is None:
            reason = ('no joint_states measured since the end time of the trajectory: the goal '
                      'cannot be checked')
        else:
            reason = f'goal tolerance violated: {self._last_violation}'
        message = (f'{reason} ({late:.3f} s after the end, goal_time_tolerance '
                   f'{self.tolerances.goal_time:g} s)')
        return GoalOutcome(GOAL_TOLERANCE_VIOLATED, message,
                           Finding(findings.GOAL_TOLERANCE_VIOLATED, message))
