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
Wrong-way heave of the limited cue against the unlimited one, per follower weights.

Run from the repository root with ``.venv/bin/python benchmarks/follower_weights_benchmark.py``
(``--scenario NAME``, default the 60 s mixed drive; ``--weights x,y,z,roll,pitch,yaw``
repeated for other sets besides the defaults). At the literature's gains (motion_cueing_node's
defaults, not ``config/motion_cueing.yaml``) on the paper's platform with
``example_limits.yaml``, a scenario is replayed once without actuator limits (the unlimited
cue: the follower follows the cue exactly; the workspace scale still applies) and once with
them per set of ``follower_weights``. For each it prints the wrong-way heave as issue 31
measured it: the seconds during which the specific force felt at the head along z is beyond
0.1 m/s^2 with the opposite sign to the input's (raw, ``[0, 0, g]`` removed from both; the
same for x and y), with its ratio to the unlimited cue's and the target of issue 31 (within
10 %); beside it the evaluator's perceived wrong-sign seconds per axis (through the
vestibular model, :func:`stewart_kinematics.cueing.evaluate`), the RMSE of the felt force and
the limit violations against the actuator limits (the unlimited cue breaks them, by design).
"""

import argparse
import dataclasses
import sys
import time

import numpy as np

from stewart_kinematics.cueing import evaluate, MotionCueing, replay
from stewart_kinematics.cueing.scenarios import scenario, SCENARIO_NAMES
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.parameters import read_parameter_files

FILES = ['config/paper_platform.yaml', 'config/example_limits.yaml']
#: The target of issue 31: limited wrong-way heave within this share of the unlimited cue's.
HEAVE_TARGET = 1.10
#: A felt force of the opposite sign beyond this is a wrong-way cue, m/s^2.
THRESHOLD = 0.1


def wrong_way_time(replay_, threshold=THRESHOLD, gravity=9.80665):
    """
    Seconds per axis during which the felt force opposes the input's beyond ``threshold``.

    Raw specific force, ``[0, 0, g]`` removed from both; each sample stands for the half
    steps on either side of it.

    :returns: x, y, z seconds, shape (3,).
    """
    times = replay_.times
    wanted = replay_.specific_force - [0.0, 0.0, gravity]
    felt = replay_.perceived.specific_force - [0.0, 0.0, gravity]
    wrong = (wanted * felt < 0.0) & (np.abs(felt) > threshold)
    steps = np.diff(times)
    weights = 0.5 * (np.concatenate([[0.0], steps]) + np.concatenate([steps, [0.0]]))
    return weights @ wrong


def measure(name, weights=None, unlimited=False):
    """Return ``(wrong-way seconds x y z, evaluation, seconds)`` of scenario ``name``."""
    template = MotionCueing.from_parameters(read_parameter_files(FILES, 'motion_cueing_node'))
    settings = template.settings
    if weights is not None:
        settings = dataclasses.replace(settings, follower_weights=weights)
    limits = ActuatorLimits() if unlimited else template.actuator_limits
    run = scenario(name)
    started = time.perf_counter()
    played = replay(MotionCueing(template.geometry, settings, limits), run.times,
                    run.specific_force, run.angular_velocity)
    seconds = time.perf_counter() - started
    return wrong_way_time(played), evaluate(
        played, template.geometry, template.actuator_limits, rest=run.rest_time), seconds


def _row(label, measured, reference=None):
    wrong, evaluation, seconds = measured
    perceived = [axis.wrong_sign_time for axis in evaluation.axes]
    rmse = [axis.raw_rmse for axis in evaluation.axes]
    ratio = '' if reference is None else f' ({wrong[2] / reference:.2f}x unlimited)'
    return (f'{label}: wrong-way heave {wrong[2]:.2f} s{ratio}; wrong-way x/y {wrong[0]:.2f}/'
            f'{wrong[1]:.2f} s; perceived wrong-sign x/y/z {perceived[0]:.2f}/{perceived[1]:.2f}/'
            f'{perceived[2]:.2f} s; RMSE x/y/z {rmse[0]:.3f}/{rmse[1]:.3f}/{rmse[2]:.3f} m/s^2; '
            f'violations {evaluation.limit_violations} ({seconds:.0f} s)')


def main(argv=None) -> int:
    """Print the table; exit 1 when the default weights miss the heave target."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[1])
    parser.add_argument('--scenario', default='mixed_drive', choices=SCENARIO_NAMES)
    parser.add_argument('--weights', action='append', type=lambda text: tuple(
        float(value) for value in text.split(',')),
        help='x,y,z,roll,pitch,yaw follower weights to try besides the defaults')
    options = parser.parse_args(argv)
    unlimited = measure(options.scenario, unlimited=True)
    reference = unlimited[0][2]
    print(_row('unlimited cue', unlimited))
    default = measure(options.scenario)
    print(_row('limited, default weights', default, reference))
    for weights in options.weights or ():
        print(_row('limited, weights ' + ','.join(f'{w:g}' for w in weights),
                   measure(options.scenario, weights), reference))
    met = default[0][2] <= HEAVE_TARGET * reference
    print(f'target (issue 31): limited wrong-way heave within {HEAVE_TARGET - 1:.0%} of the '
          f'unlimited cue\'s: {"met" if met else "MISSED"}')
    return 0 if met else 1


if __name__ == '__main__':
    sys.exit(main())
