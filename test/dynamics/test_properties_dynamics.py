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
Property tests of the dynamics: one pose and a batch agree to the bit, hostile input is refused.

Random poses near home, twists, accelerations and masses (hypothesis): each pose of a batch
gives the forces of the same pose alone, bit for bit, and the legs' wrench balances what the
forces were computed for; a non-finite, huge or misshapen argument is refused in the package's
words, never with a numpy warning (pytest.ini makes one an error).
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from properties import (
    assert_refused,
    budget,
    covers,
    floats,
    HUGE,
    NON_FINITE,
    NOT_NUMBERS,
    PAPER,
    pose_batches,
    poses_near_home,
)
import pytest

from stewart_kinematics import (
    leg_forces,
    LegBody,
    MassProperties,
    platform_wrench,
    RigidBody,
)

pytestmark = pytest.mark.core

TWISTS = st.tuples(*[floats(-0.5, 0.5)] * 6).map(np.array)
ACCELERATIONS = st.tuples(*[floats(-5.0, 5.0)] * 6).map(np.array)
INERTIAS = st.tuples(floats(0.0, 1.0), floats(0.0, 1.0), floats(0.0, 1.0)).map(
    lambda moments: [max(moments), max(moments), min(moments), 0.0, 0.0, 0.0])


@st.composite
def mass_properties(draw):
    """Platform, payload and legs with random masses (legs massless half the time)."""
    platform = RigidBody(draw(floats(0.1, 50.0)), draw(st.tuples(*[floats(-0.1, 0.1)] * 3)),
                         draw(INERTIAS))
    payload = RigidBody(draw(floats(0.1, 100.0)), draw(st.tuples(*[floats(-0.2, 0.2)] * 3)),
                        draw(INERTIAS))
    if draw(st.booleans()):
        lower = LegBody(draw(floats(0.1, 5.0)), draw(floats(0.0, 0.4)), draw(floats(0.0, 0.1)))
        upper = LegBody(draw(floats(0.1, 5.0)), draw(floats(0.0, 0.4)), draw(floats(0.0, 0.1)))
    else:
        lower = upper = LegBody()
    return MassProperties(platform=platform, payload=payload, leg_lower=lower, leg_upper=upper)


@covers('leg_forces', 'MassProperties', 'RigidBody', 'LegBody')
@budget(40)
@given(poses=pose_batches(max_size=6), twist=TWISTS, acceleration=ACCELERATIONS,
       masses=mass_properties())
def test_each_pose_of_a_batch_gives_its_own_forces_to_the_bit(poses, twist, acceleration,
                                                              masses):
    count = len(poses)
    twists = twist * np.linspace(0.0, 1.0, count)[:, None]
    accelerations = acceleration * np.linspace(1.0, -1.0, count)[:, None]
    batch = leg_forces(PAPER, poses, twists, accelerations, mass_properties=masses)
    assert batch.shape == (count, 6)
    for pose, pose_twist, pose_acceleration, row in zip(poses, twists, accelerations, batch):
        single = leg_forces(PAPER, pose, pose_twist, pose_acceleration, mass_properties=masses)
        assert single.shape == (6,)
        assert single.tobytes() == row.tobytes()
    # One twist for every pose broadcasts, and is the same as the twist repeated.
    if count:
        same = leg_forces(PAPER, poses, twist, mass_properties=masses)
        repeated = leg_forces(PAPER, poses, np.tile(twist, (count, 1)), mass_properties=masses)
        assert same.tobytes() == repeated.tobytes()


@covers('platform_wrench', 'leg_forces')
@budget(30)
@given(pose=poses_near_home(), masses=mass_properties())
def test_the_static_forces_hold_the_weight(pose, masses):
    """At rest with massless legs, the legs' wrench is the weight's, to rounding."""
    masses = MassProperties(platform=masses.platform, payload=masses.payload)
    forces = leg_forces(PAPER, pose, mass_properties=masses)
    wrench = platform_wrench(PAPER, pose, forces)
    weight = masses.moving_mass * 9.80665
    assert wrench[:3] == pytest.approx([0.0, 0.0, weight], abs=1e-9 * weight)
    batch = platform_wrench(PAPER, pose[None], forces[None])
    assert batch[0].tobytes() == wrench.tobytes()


@covers('leg_forces')
@budget(30)
@given(pose=poses_near_home(), which=st.sampled_from(['poses', 'twists', 'accelerations']),
       entry=st.integers(0, 5), bad=st.one_of(NON_FINITE, HUGE), masses=mass_properties(),
       batch=st.booleans())
def test_non_finite_values_are_refused_and_huge_ones_never_give_a_non_finite_force(
        pose, which, entry, bad, masses, batch):
    """Refuse NaN and inf naming the argument; 1e308 gives finite forces or a refusal."""
    arguments = {'poses': pose, 'twists': np.full(6, 0.1), 'accelerations': np.full(6, 1.0)}
    arguments[which] = np.where(np.arange(6) == entry, bad, arguments[which])
    if batch:
        arguments = {name: np.stack([value, value]) for name, value in arguments.items()}

    def call():
        return leg_forces(PAPER, arguments['poses'], arguments['twists'],
                          arguments['accelerations'], mass_properties=masses)
    if not math.isfinite(bad):
        assert_refused(call, [which])
        return
    try:
        forces = call()
    except ValueError:
        assert_refused(call, ['too large', 'singular'])
    else:   # a huge speed that no mass feels (a linear velocity) changes nothing
        assert np.all(np.isfinite(forces))


@covers('leg_forces', 'platform_wrench')
@budget(30)
@given(value=NOT_NUMBERS, which=st.sampled_from(['poses', 'twists', 'accelerations', 'forces']))
def test_arguments_that_are_not_numbers_are_refused_naming_them(value, which):
    masses = MassProperties(payload=RigidBody(10.0))
    if which == 'forces':
        assert_refused(lambda: platform_wrench(PAPER, PAPER.home_pose, value), ['forces'])
        return
    if value is None and which != 'poses':
        return   # no twist or acceleration: at rest
    arguments = {'poses': PAPER.home_pose, 'twists': None, 'accelerations': None}
    arguments[which] = value
    assert_refused(lambda: leg_forces(PAPER, arguments['poses'], arguments['twists'],
                                      arguments['accelerations'], mass_properties=masses),
                   [which])


@covers('leg_forces', 'platform_wrench')
@budget(30)
@given(shape=st.lists(st.integers(0, 7), min_size=0, max_size=3).map(tuple).filter(
    lambda shape: not (len(shape) in (1, 2) and shape[-1] == 6)))
def test_wrong_shapes_are_refused_with_the_shape(shape):
    masses = MassProperties(payload=RigidBody(10.0))
    assert_refused(lambda: leg_forces(PAPER, np.full(shape, 0.1), mass_properties=masses),
                   ['poses', 'shape'])
    assert_refused(lambda: platform_wrench(PAPER, PAPER.home_pose, np.full(shape, 0.1)),
                   ['forces'])
