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
The command gate's leg forces (issue 29): every command sent, with its motion, within the limit.

A motion's forces are judged here independently: the poses of the sent lengths by forward
kinematics, their twists and accelerations by finite differences at the send times (the
rotation's by scipy's rotation vector), and the forces of those by
:func:`stewart_kinematics.leg_forces`. A stream accelerating a heavy payload stays within
``leg_force_max`` and says so (``force_limited``, naming the legs); a braking command brakes
more gently when braking at the acceleration limit would break the forces; a setpoint carries
its static forces; with every mass 0 nothing is computed.
"""

from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference
from scipy.spatial.transform import Rotation

from stewart_kinematics import (
    ActuatorLimits,
    CommandFilter,
    forward_kinematics,
    leg_forces,
    load_geometry,
    MassProperties,
    RigidBody,
)
from stewart_kinematics.limits import command_gate, CommandGate, MOTION, PoseLimits, SETPOINT
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
PAPER = load_geometry(CONFIG / 'paper_platform.yaml')
HOME_LENGTHS = PAPER.home_leg_lengths
#: A heavy payload: 200 kg, 0.1 m above the platform frame's origin (about 337 N a leg at home).
MASSES = MassProperties(payload=RigidBody(200.0, [0.0, 0.0, 0.1], [2.0, 2.0, 2.0, 0.0, 0.0, 0.0],
                                          name='payload'))
FORCE_MAX = 350.0
LIMITS = ActuatorLimits(0.3, 3.0, 60.0)
PERIOD = 0.001


def geometry(masses=MASSES, **limits):
    """Return the paper's platform with a stroke of +-0.1 m around home, masses and limits."""
    return PAPER.__class__(
        PAPER.base_joints, PAPER.platform_joints, PAPER.home_pose,
        limits=PoseLimits(leg_length_min=HOME_LENGTHS.min() - 0.1,
                          leg_length_max=HOME_LENGTHS.max() + 0.1, **limits),
        mass_properties=masses)


def independent_forces(plant, times, lengths, masses=MASSES):
    """
    Leg forces of sent lengths at their send times, from rest at home before the first.

    Poses by forward kinematics; twist ``V_k = [dp / h, rotvec(R_k R_k-1^T) / h]`` and
    acceleration ``(V_k - V_k-1) / ((h_k + h_k-1) / 2)``, the first after rest over ``h_1``.
    """
    poses, guess = [], PAPER.home_pose
    for row in lengths:
        solution = forward_kinematics(PAPER, row, guess, tolerance=1e-13)
        assert solution.converged
        poses.append(solution.pose)
        guess = solution.pose
    poses = np.array(poses)
    times = np.asarray(times)
    rotations = Rotation.from_matrix(reference.rotations_zyx(poses[:, 3:]))
    steps = np.diff(times)
    twists = np.zeros(poses.shape)
    twists[1:, :3] = np.diff(poses[:, :3], axis=0) / steps[:, None]
    twists[1:, 3:] = (rotations[1:] * rotations[:-1].inv()).as_rotvec() / steps[:, None]
    spans = 0.5 * (steps + np.concatenate([[steps[0]], steps[:-1]]))
    accelerations = np.zeros(poses.shape)
    accelerations[1:] = np.diff(twists, axis=0) / spans[:, None]
    return leg_forces(plant.__class__(plant.base_joints, plant.platform_joints, plant.home_pose),
                      poses, twists, accelerations, mass_properties=masses)


def stream(plant, count=1500, rise=0.05):
    """Stream every leg ``rise`` metres longer from home at 1 kHz: times, lengths, commands."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME_LENGTHS, plant)
    assert command_filter.set_target(HOME_LENGTHS + rise, 0.0).accepted
    times, lengths, commands = [0.0], [HOME_LENGTHS], []
    for k in range(1, count):
        command = command_filter.send(k * PERIOD)
        assert command.accepted, command.refusal
        times.append(k * PERIOD)
        lengths.append(command.lengths)
        commands.append(command)
    return np.array(times), np.array(lengths), commands


def test_the_stream_without_a_force_limit_asks_more_than_it():
    """The motion of the test below, unlimited, breaks leg_force_max: the limit has work."""
    times, lengths, commands = stream(geometry(), count=400)
    forces = independent_forces(PAPER, times, lengths)[1:]
    assert forces.max() > FORCE_MAX + 5.0
    # The command's forces are those of its pose sent, with the motion's twist and acceleration.
    assert_allclose(np.array([command.forces for command in commands]), forces, atol=0.02)


def test_a_stream_accelerating_a_heavy_payload_is_held_within_leg_force_max():
    times, lengths, commands = stream(geometry(leg_force_max=FORCE_MAX))
    forces = independent_forces(PAPER, times, lengths)[1:]
    assert forces.max() <= FORCE_MAX + 0.02
    assert_allclose(np.array([command.forces for command in commands]), forces, atol=0.02)
    assert np.all(np.array([command.forces for command in commands]) <= FORCE_MAX)
    # It got there, slower, and said why: the limit and the legs.
    assert_allclose(lengths[-1], HOME_LENGTHS + 0.05, atol=1e-9)
    # Planned again more slowly (force_limited) or braked (command_braking): never silently.
    named = [finding for command in commands for finding in command.warnings
             if finding.code in ('force_limited', 'command_braking')]
    # The first names the force limit and the legs (one after a braking command may name
    # the jerk: braking may exceed it).
    assert named
    assert 'leg_force_max' in named[0].message
    assert any(key.startswith('leg_force_max leg') for key, _ in named[0].details)


def test_a_braking_command_brakes_gently_enough_to_keep_the_forces():
    """
    Moving down, then braking: braking at leg_acceleration_max would push too hard.

    It brakes more gently, within leg_force_max.
    """
    plant = geometry(leg_force_max=FORCE_MAX)
    static = leg_forces(plant, plant.home_pose)
    gate = CommandGate(plant, LIMITS, timing=MOTION)
    gate.reset(time=0.0)
    speed = 0.02   # m/s down: the legs' lengths fall at about that
    times, sent = [0.0], [HOME_LENGTHS]
    for k in range(1, 6):
        command = gate.pose(np.array([0.0, 0.0, PAPER.home_pose[2] - speed * k * 0.01]),
                            np.eye(3), time=k * 0.01)
        assert command.accepted, command.refusal
        times.append(k * 0.01)
        sent.append(command.lengths)
    # Ramping up to the speed asked 0.2 m/s^2 of 200 kg; braking at 3 m/s^2 would ask 600 N.
    assert static.max() + 200.0 * 3.0 * 0.999 / 6.0 > FORCE_MAX
    braking = gate.brake(0.06)
    assert braking.accepted and braking.braking
    assert 'harder would break the leg force limits' in braking.warnings[0].message
    assert np.all(braking.forces <= FORCE_MAX)
    forces = independent_forces(PAPER, times + [0.06], sent + [braking.lengths])
    assert_allclose(braking.forces, forces[-1], atol=0.02)
    assert np.all(braking.velocities < 0.0)   # still moving: it brakes, never a stop at once


def test_a_motion_command_beyond_the_forces_is_refused_naming_the_legs():
    plant = geometry(leg_force_max=FORCE_MAX)
    gate = CommandGate(plant, LIMITS, timing=MOTION)
    gate.reset(time=0.0)
    # 0.2 mm up in 10 ms from rest: 2 m/s^2 up asked of 200 kg, 67 N more a leg (the leg
    # rates within their limits).
    command = gate.pose(np.array([0.0, 0.0, PAPER.home_pose[2] + 0.0002]), np.eye(3),
                        time=0.01)
    assert not command.accepted
    assert command.refusal.code == 'too_fast'
    assert 'leg_force_max' in command.refusal.message
    assert {violation.limit for violation in command.violations} == {'leg_force_max'}
    assert set(command.legs_at_fault) == set(range(1, 7))


def test_a_setpoint_carries_its_static_forces():
    plant = geometry()
    gate = CommandGate(plant, LIMITS, timing=SETPOINT)
    pose = np.array([0.01, -0.02, 0.44, 0.05, -0.03, 0.08])
    command = gate.pose(pose[:3], euler_zyx_to_matrix(pose[3:]))
    assert command.accepted
    assert_allclose(command.forces, leg_forces(plant, pose), rtol=1e-12, atol=1e-9)


def test_without_masses_nothing_is_computed(monkeypatch):
    """Every mass 0: no forces on any command, and leg_forces is never called."""
    def forbidden(*arguments, **keywords):
        raise AssertionError('leg_forces called without masses')
    monkeypatch.setattr(command_gate, 'leg_forces', forbidden)
    plant = geometry(masses=MassProperties(), leg_force_max=1.0)
    times, lengths, commands = stream(plant, count=200)
    assert all(command.forces is None for command in commands)
    gate = CommandGate(plant, LIMITS, timing=SETPOINT)
    assert gate.pose(PAPER.home_pose[:3], np.eye(3)).forces is None


@pytest.mark.parametrize('before', [
    MassProperties(payload=RigidBody(100.0, [0.0, 0.0, 0.1], [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
                                     name='payload')),
    MassProperties()], ids=['lighter payload', 'no masses'])
def test_a_payload_set_mid_stream_is_checked_from_the_next_step(before):
    """
    The payload grows to 200 kg while the stream accelerates: its next steps keep leg_force_max.

    A stream that kept checking its steps with the masses it started with would push the
    200 kg beyond the limit (the unlimited motion asks more of it: the first test above).
    """
    command_filter = CommandFilter(LIMITS, PERIOD, HOME_LENGTHS,
                                   geometry(masses=before, leg_force_max=FORCE_MAX))
    assert command_filter.set_target(HOME_LENGTHS + 0.05, 0.0).accepted
    times, lengths, commands = [0.0], [HOME_LENGTHS], []
    switch = 20
    for k in range(1, 1500):
        if k == switch:
            command_filter.set_mass_properties(
                geometry(masses=before, leg_force_max=FORCE_MAX).with_mass_properties(MASSES))
        command = command_filter.send(k * PERIOD)
        assert command.accepted, command.refusal
        times.append(k * PERIOD)
        lengths.append(command.lengths)
        commands.append(command)
    forces = independent_forces(PAPER, times, lengths)
    # From the step after the switch (its acceleration is judged against the step before).
    assert forces[switch + 1:].max() <= FORCE_MAX + 0.02
    assert all(command.forces is not None and np.all(command.forces <= FORCE_MAX)
               for command in commands[switch:])
    assert_allclose(lengths[-1], HOME_LENGTHS + 0.05, atol=1e-9)
