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
The node fuzzer's scenarios of issue 27 (fuzzing/node_scenarios.py), each against its node.

Each would have found its defect on the wire, from outside the node (doc/testing_adversarial.md
shows each failing against the revision before issue 27, d137fe8):

- trajectory_node, a low ``validation_rate`` and bulging trajectories: ``leg_trajectory``
  carried leg lengths beyond the stroke;
- motion_cueing_node in lockstep with the fuzzer's simulated clock, noisy IMU bursts: the cue
  follower held a pose, stopping legs within one 10 ms step; a recording played ten times
  fast: the legs moved ten times faster than their limits;
- ik_node streaming at ``command_rate``: its commands, stepped by the period whatever the
  clock said, broke the leg rates between their stamps.

A flood of a few hundred messages comes first (the scenario must hold after it too; not before
the lockstep, which then starts from a fresh node and replays exactly), then the scenario,
then every invariant of the fuzzer. The seeds are fixed (``STEWART_FUZZ_SEED`` overrides them):
the noisy seed is one whose bursts made the old follower hold a pose (the hold is rare: about
one burst of 250 samples in five). ``STEWART_FUZZ_EXECUTABLES`` names a folder of console
scripts to fuzz instead of the installed ones (another build, such as an older revision's
``.venv/bin``). Run with ``-s`` to see the figures (lines starting ``FUZZ``).
"""

import os

from fuzzing.node_fuzzer import fuzz_node, FuzzSettings
import pytest

pytestmark = pytest.mark.process

#: A folder of console scripts to fuzz instead of the installed ones.
EXECUTABLES = os.environ.get('STEWART_FUZZ_EXECUTABLES')
#: Messages of the flood before each scenario.
MESSAGES = 300


def settings(node, seed, messages=MESSAGES, **changes):
    """Return the fuzz settings of a scenario run (the session's seed, if one is given)."""
    seed = int(os.environ.get('STEWART_FUZZ_SEED', seed))
    executable = os.path.join(EXECUTABLES, node) if EXECUTABLES else None
    return FuzzSettings(node, seed, messages, huge=0, oversized=0, variant=False,
                        executable=executable, **changes)


def run(fuzz_settings):
    """Fuzz, print the figures, and fail with the problems."""
    report = fuzz_node(fuzz_settings)
    print(report.summary())
    assert not report.problems, report.failure()
    return report


def test_low_validation_rates_and_bulging_trajectories_put_no_leg_beyond_the_stroke(ros):
    """Two rounds: two bulges beyond the stroke refused, two inside it published, all checked."""
    report = run(settings('trajectory_node', 7, scenarios=2))
    assert any('2 beyond the stroke' in line and '2 inside it' in line
               for line in report.scenario), report.scenario
    assert report.rejections.get('out_of_limits', 0) >= 2
    assert report.outputs.get('leg_trajectory', 0) >= 2


def test_noisy_imu_in_lockstep_never_stops_a_leg_in_one_step(ros):
    """Six bursts of 250 noisy samples from rest: every target_pose within the leg rates."""
    report = run(settings('motion_cueing_node', 1, 0, scenarios=6, only=('noisy_imu',)))
    assert any('1494 target_pose checked' in line for line in report.scenario), report.scenario


def test_a_recording_played_ten_times_fast_keeps_the_leg_rates_in_real_time(ros):
    """200 samples stamped 100 ms apart, sent 10 ms apart: the rates kept as sent."""
    report = run(settings('motion_cueing_node', 5, 0, scenarios=1, only=('fast_recording',)))
    assert any('199 target_pose checked' in line for line in report.scenario), report.scenario


def test_streamed_joint_commands_keep_the_leg_rates_between_their_stamps(ros):
    """ik_node at command_rate 100 Hz under a flood: every step within the rates, or braking."""
    report = run(settings('ik_node', 3, parameters={'command_rate': 100.0}))
    assert report.outputs.get('joint_commands', 0) > 100
