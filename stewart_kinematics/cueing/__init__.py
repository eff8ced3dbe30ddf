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
Motion cueing: a vehicle's motion in, platform motion a person feels out, within every limit.

The classical washout (:mod:`.washout`, filters in :mod:`.filters`), scaled into the limits
model and followed within the actuators' speed (:mod:`.cue_limiter`, its limit calls in
:mod:`.limit_margins`), the motion felt at the head (:mod:`.perception`), all behind one decision
object (:class:`MotionCueing`, :mod:`.motion_cueing`); :func:`replay` (:mod:`.replay`) runs a
whole input through it, :mod:`.scenarios` generates nine test drives and :mod:`.evaluation`
measures the result as a person perceives it (:mod:`.vestibular`). Settings:
:class:`CueingSettings` (:mod:`.settings`).

May import: :mod:`stewart_kinematics.model`, :mod:`~stewart_kinematics.limits`,
:mod:`~stewart_kinematics.findings`, :mod:`~stewart_kinematics.parameters`,
:mod:`~stewart_kinematics.motion` and numpy. Nothing here imports ROS.
"""

from stewart_kinematics.cueing.evaluation import CueEvaluation, evaluate
from stewart_kinematics.cueing.motion_cueing import CueStep, MotionCueing
from stewart_kinematics.cueing.perception import perceived_motion, PerceivedMotion
from stewart_kinematics.cueing.replay import CueReplay, replay
from stewart_kinematics.cueing.scenarios import all_scenarios, Scenario, scenario
from stewart_kinematics.cueing.settings import CueingSettings
from stewart_kinematics.cueing.washout import ClassicalWashout

__all__ = [
    'all_scenarios',
    'ClassicalWashout',
    'CueEvaluation',
    'CueingSettings',
    'CueReplay',
    'CueStep',
    'evaluate',
    'MotionCueing',
    'perceived_motion',
    'PerceivedMotion',
    'replay',
    'Scenario',
    'scenario',
]
