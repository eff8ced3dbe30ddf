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
What fk_node reports of its tracker on ``/diagnostics``: the assembly-mode margin, the ambiguity.

:func:`margin_status` decides what to report of the latest assembly-mode margin of a
:class:`~stewart_kinematics.workers.margin_monitor.AssemblyModeMarginMonitor` (a warning when
another mode lies closer than the warning distance, or the search was incomplete), and
:func:`ambiguity_status` what to report of a :class:`~.pose_tracker.PoseTracker`'s ambiguity
(a warning from the first sign of a fold crossing until the tracker is re-anchored). The node
turns each into a DiagnosticStatus. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

from stewart_kinematics import findings
from stewart_kinematics.findings import Finding
from stewart_kinematics.pose_decisions.pose_tracker import PoseTracker


@dataclass(frozen=True)
class MarginStatus:
    """
    What fk_node reports of the assembly-mode margin: a warning or not, a sentence, the values.

    :param warning: an ``assembly_mode_margin`` finding when the margin deserves a warning
        (another mode closer than the warning distance, or a search that was incomplete),
        else ``None``.
    :param message: the status sentence.
    :param values: ``(key, value)`` pairs: the margin, its parts, the modes, the cost.
    """

    warning: Optional[Finding]
    message: str
    values: Tuple[Tuple[str, str], ...] = ()


def margin_status(monitor) -> MarginStatus:
    """
    Decide what to report of the latest assembly-mode margin of a monitor.

    :param monitor: an
        :class:`stewart_kinematics.workers.margin_monitor.AssemblyModeMarginMonitor`.
    :returns: a :class:`MarginStatus`; its warning, if any, is what the node counts and logs.
    """
    too_close = monitor.warning()
    margin = monitor.latest
    if margin is None:
        return MarginStatus(None, 'no solution yet, or not computed yet')
    if too_close:
        message = too_close
    elif margin.nearest is None:
        message = 'no other assembly mode within the limits'
    else:
        message = (f'nearest other assembly mode within the limits: {margin.position:.4g} m and '
                   f'{math.degrees(margin.angle):.4g} deg away')
    if not margin.complete:
        message += f'; the search was incomplete: {margin.reason}'
    values = (('margin_position_m', f'{margin.position:.6g}'),
              ('margin_angle_deg', f'{math.degrees(margin.angle):.6g}'),
              ('margin_distance_m', f'{margin.distance:.6g}'),
              ('modes_within_limits', str(margin.modes_within_limits)),
              ('search_complete', str(margin.complete)),
              ('computed_in_ms', f'{monitor.latest_seconds * 1e3:.1f}'))
    warning = (Finding(findings.ASSEMBLY_MODE_MARGIN, message, values)
               if too_close or not margin.complete else None)
    return MarginStatus(warning, message, values)


@dataclass(frozen=True)
class AmbiguityStatus:
    """
    What fk_node reports of the tracker's ambiguity: a warning or not, a sentence, the values.

    :param warning: the tracker's ``ambiguous_estimate`` finding while it holds, else ``None``.
    :param message: the status sentence.
    :param values: ``(key, value)`` pairs: whether ambiguous, how and when last anchored, the
        cause.
    """

    warning: Optional[Finding]
    message: str
    values: Tuple[Tuple[str, str], ...] = ()


def ambiguity_status(tracker: PoseTracker) -> AmbiguityStatus:
    """
    Decide what to report of a tracker's ambiguity: WARN with its finding while it holds.

    :param tracker: a :class:`PoseTracker`.
    """
    values = (('ambiguous', str(tracker.ambiguous)), ('anchored_by', tracker.anchored_by),
              ('poses_since_anchor', str(tracker.poses_since_anchor)))
    ambiguity = tracker.ambiguity
    if ambiguity is None:
        return AmbiguityStatus(None, 'the estimate follows one assembly mode since the last '
                               f'anchor ({tracker.anchored_by})', values)
    return AmbiguityStatus(ambiguity, ambiguity.message, values + tuple(
        pair for pair in ambiguity.details if pair[0] != 'anchored_by'))
