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
PoseTracker's refuse_ambiguous_start: a first solution in an unknown assembly mode is refused.

At the end of the paper's Table 3 the leg lengths allow four real modes (two above the base);
from the home pose, 0.21 m and 26 deg away, none is within the assembly guard's 0.05 m and
10 deg, so a tracker that was just started cannot tell which one the platform is in.
"""

import math
from pathlib import Path

import numpy as np
import pytest
from stewart_kinematics import findings, inverse_kinematics, load_geometry, PoseTracker
from stewart_kinematics.parameters import SolverSettings
from stewart_kinematics.pose_decisions import pose_tracker

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
TABLE_3_END = np.array([0.1, 0.15, 0.5325, math.radians(15.0), math.radians(-15.0),
                        math.radians(20.0)])


@pytest.fixture(scope='module')
def paper():
    return load_geometry(CONFIG / 'paper_platform.yaml')


def test_off_by_default_the_first_solution_is_accepted(paper):
    tracker = PoseTracker(paper)
    assert tracker.settings.refuse_ambiguous_start is False
    estimate = tracker.update(inverse_kinematics(paper, TABLE_3_END))
    assert estimate.accepted


def test_an_ambiguous_start_is_refused_with_the_reason_then_a_known_pose_resolves_it(paper):
    tracker = PoseTracker(paper, SolverSettings(refuse_ambiguous_start=True))
    lengths = inverse_kinematics(paper, TABLE_3_END)
    estimate = tracker.update(lengths)
    assert not estimate.accepted
    assert estimate.refusal.code == findings.AMBIGUOUS_ASSEMBLY_MODE
    assert '4 assembly modes lie within the limits' in estimate.reason
    assert ('modes_within_limits', '4') in estimate.refusal.details
    assert tracker.last_lengths is None
    # A reset to a pose known to be near the platform's: that mode is the one.
    tracker.reset(TABLE_3_END + np.array([0.01, -0.01, 0.0, 0.0, math.radians(2.0), 0.0]))
    estimate = tracker.update(lengths)
    assert estimate.accepted
    np.testing.assert_allclose(estimate.pose, TABLE_3_END, atol=1e-9)
    # Then tracking goes on as usual, without searching again.
    assert tracker.update(lengths + 1e-4).accepted


def test_one_reachable_mode_is_not_ambiguous(paper):
    limited = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])
    tracker = PoseTracker(limited, SolverSettings(refuse_ambiguous_start=True))
    assert tracker.update(inverse_kinematics(limited, TABLE_3_END)).accepted


def test_the_search_runs_once_while_the_lengths_stay(paper, monkeypatch):
    calls = []
    original = pose_tracker.start_ambiguity

    def counting(*args, **kwargs):
        calls.append(args)
        return original(*args, **kwargs)

    monkeypatch.setattr(pose_tracker, 'start_ambiguity', counting)
    tracker = PoseTracker(paper, SolverSettings(refuse_ambiguous_start=True))
    lengths = inverse_kinematics(paper, TABLE_3_END)
    for step in range(3):
        assert not tracker.update(lengths + 1e-4 * step).accepted
    assert len(calls) == 1
    assert not tracker.update(lengths + 0.01).accepted     # moved: searched again
    assert len(calls) == 2
