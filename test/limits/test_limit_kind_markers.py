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

"""The workspace markers colour each boundary point with its limit kind's declared colour."""

import math

import pytest
from std_msgs.msg import Header

from stewart_kinematics.limits import BoundLook, kinds, LimitKind, LimitParameter
from stewart_kinematics.model.validators import InRange
from stewart_kinematics.ros.markers import LIMIT_ALPHA, workspace_markers

pytestmark = pytest.mark.node

#: A kind added to the list, with one bound and its colour (no evaluator: only drawn here).
TOY = LimitKind(
    name='toy', title='Toy', meaning='A toy limit.', evaluator='Toy',
    parameters=(LimitParameter('toy_max', 'm', math.inf, 'A toy limit, metres',
                               (InRange(0.0, math.inf, low_inclusive=False),)),),
    bounds=(BoundLook('toy_max', 'toy', (0.25, 0.5, 0.75)),),
    pose_evaluator=lambda geometry, limits: None)


def colours(array):
    """Return {marker id: (r, g, b, a)} of the POINTS markers."""
    return {marker.id: (marker.color.r, marker.color.g, marker.color.b, marker.color.a)
            for marker in array.markers if marker.type == marker.POINTS}


def test_each_limit_has_its_kinds_colour(monkeypatch):
    bounds = kinds.pose_bounds()
    points = [[0.0, 0.0, 0.1 * index] for index in range(len(bounds))]
    shown = colours(workspace_markers(Header(frame_id='base'), points, range(len(bounds))))
    assert shown == {index: pytest.approx(bound.colour + (LIMIT_ALPHA,), abs=1e-6)
                     for index, bound in enumerate(bounds)}
    monkeypatch.setattr(kinds, 'LIMIT_KINDS', kinds.LIMIT_KINDS + [TOY])
    toy = len(bounds)
    shown = colours(workspace_markers(Header(frame_id='base'), [[0.0, 0.0, 1.0]], [toy]))
    assert shown == {toy: pytest.approx((0.25, 0.5, 0.75, LIMIT_ALPHA), abs=1e-6)}
