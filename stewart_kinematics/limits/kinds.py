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
Every kind of limit, in the order every check reports them: the one list the rest derives from.

Adding a kind of limit is adding its module (its evaluator and its
:class:`~stewart_kinematics.limits.kind.LimitKind`, ``KIND``) and one line here. The functions
below read the list when they are called, so what derives from it (the limits model, the limit
settings, the parameter specs, the markers, the figures, the documentation's tables) sees a
kind added to it. Nothing here imports ROS.
"""

from typing import Dict, Tuple

from stewart_kinematics.limits import (
    joint_cones,
    leg_collision,
    leg_forces,
    leg_rates,
    singularity,
    stroke,
)
from stewart_kinematics.limits.kind import ACTUATOR, BoundLook, LimitParameter, POSE

#: Every kind of limit, in report order.
LIMIT_KINDS = [
    stroke.KIND,
    joint_cones.KIND,
    singularity.KIND,
    leg_collision.KIND,
    leg_forces.KIND,
    leg_rates.KIND,
]


def pose_bounds() -> Tuple[BoundLook, ...]:
    """Return the bounds of every pose limit, in report order (what a workspace boundary meets)."""
    return tuple(bound for kind in LIMIT_KINDS if kind.pose_evaluator for bound in kind.bounds)


def pose_limit_names() -> Tuple[str, ...]:
    """Return the names of the pose limits, in report order: :data:`LIMIT_NAMES` as it is now."""
    return tuple(bound.name for bound in pose_bounds())


def limit_parameters(keeps: str = '') -> Tuple[LimitParameter, ...]:
    """
    Return the parameters of every kind, in list order.

    :param keeps: :data:`~.kind.POSE` or :data:`~.kind.ACTUATOR` for those kept there; all
        when empty.
    """
    return tuple(parameter for kind in LIMIT_KINDS for parameter in kind.parameters
                 if not keeps or parameter.keeps == keeps)


def pose_settings() -> Dict[str, LimitParameter]:
    """Return setting name -> parameter, of every parameter the pose limits' settings keep."""
    return {parameter.setting_name: parameter for parameter in limit_parameters(POSE)}


def actuator_settings() -> Dict[str, LimitParameter]:
    """Return setting name -> parameter, of every parameter ActuatorLimits keeps."""
    return {parameter.setting_name: parameter for parameter in limit_parameters(ACTUATOR)}


def limits_table() -> str:
    """
    Return the Markdown table of every kind of limit: its evaluator, parameters and meaning.

    The safety page's table of limits (``{limit-table}`` of the documentation's extension).
    """
    rows = ['| Limit | Evaluator | Parameters | Meaning |', '| --- | --- | --- | --- |']
    for kind in LIMIT_KINDS:
        parameters = ', '.join(
            f'`{parameter.name}`' + (f' ({parameter.unit})' if parameter.unit else '')
            for parameter in kind.parameters)
        rows.append(f'| {kind.title} | `{kind.evaluator}` (`{kind.name}`) | {parameters} | '
                    f'{kind.meaning} |')
    return '\n'.join(rows)


#: The pose limits, in the order every check reports them (the kinds' bounds, as listed now).
LIMIT_NAMES = pose_limit_names()
#: The limits of leg states (lengths and their derivatives), in the order they are reported.
LEG_STATE_LIMIT_NAMES = tuple(name for kind in LIMIT_KINDS for name in kind.leg_state_names)
