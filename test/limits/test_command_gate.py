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
Unit tests of stewart_kinematics.limits.command_gate: every command checked as it is sent.

The rates of a motion are checked against divided differences computed here independently
(numpy's polynomial fit through the commands); braking is checked step by step against the
limits; the trajectories' refusals reproduce the adversarial pass's defect (issue 27).
"""

import math

from hypothesis import example, given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import budget
import pytest
import reference

from stewart_kinematics import ActuatorLimits, MotionPlanner
from stewart_kinematics.limits import CommandGate, LIMIT_NAMES, MOTION, SETPOINT
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, euler_zyx_to_quaternion

pytestmark = pytest.mark.core

LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
GEOMETRY = reference.paper_geometry(leg_length_min=0.65, leg_length_max=0.90,
                                    base_joint_max_angle=math.radians(30.0),
                                    platform_joint_max_angle=math.radians(35.0),
                                    max_jacobian_condition=50.0, leg_radius=0.02)
HOME = np.array(GEOMETRY.home_pose)


def lengths_of(pose):
    """Leg lengths of a pose by the reference formula (independent of the package)."""
    return reference.leg_lengths(pose)


def divided_derivatives(times, lengths):
    """
    Velocity, acceleration and jerk of the last command: derivatives of the interpolating cubic.

    The k-th divided difference times k! is the k-th derivative of the polynomial through the
    last k + 1 commands: computed here with numpy's exact polynomial through them.
    """
    result = []
    for order in (1, 2, 3):
        t, values = np.asarray(times[-order - 1:]), np.asarray(lengths[-order - 1:])
        coefficients = np.polyfit(t - t[-1], values, order)
        result.append(coefficients[0] * math.factorial(order))
    return result


# Setpoints ------------------------------------------------------------------------------------

def test_a_setpoint_is_the_legs_of_its_pose_or_refused_with_every_violation():
    """Setpoints: lengths of the pose (reference formula), no rate between them; far: refused."""
    gate = CommandGate(GEOMETRY, LIMITS, timing=SETPOINT)
    near = HOME + [0.01, 0.0, 0.0, 0.0, 0.0, 0.0]
    far = HOME + [0.05, 0.0, 0.02, 0.0, 0.0, 0.0]
    for pose in (near, far, near):   # jumps: a setpoint's motion is the drive's
        command = gate.pose(pose[:3], euler_zyx_to_matrix(pose[3:]))
        assert command.accepted
        assert_allclose(command.lengths, lengths_of(pose), atol=1e-14)
    beyond = HOME + [0.0, 0.0, 0.3, 0.0, 0.0, 0.0]
    command = gate.pose(beyond[:3], euler_zyx_to_matrix(beyond[3:]))
    assert command.refusal.code == 'out_of_limits' and command.lengths is None
    assert {violation.limit for violation in command.violations} == {'leg_length_max'}


def test_a_pose_message_is_checked_as_ik_node_reads_it():
    """tool_pose: the quaternion as sent (not unit here) gives the lengths of its rotation."""
    gate = CommandGate(GEOMETRY, LIMITS, timing=SETPOINT)
    quaternion = 2.0 * euler_zyx_to_quaternion([0.05, -0.02, 0.1])
    command = gate.tool_pose(HOME[:3], quaternion)
    assert command.accepted
    assert_allclose(command.lengths, lengths_of(np.r_[HOME[:3], 0.05, -0.02, 0.1]), atol=1e-14)
    position, sent = command.tool_pose
    assert_allclose(sent, quaternion)


# Motion: the rates between consecutive commands ---------------------------------------------

def test_the_rates_of_a_motion_are_its_divided_differences():
    """
    A command's velocity and acceleration are those of the polynomial through the commands.

    The last commands at jittered times; and a jerk a hair above the limit is refused, a hair
    below passes.
    """
    gate = CommandGate(GEOMETRY, LIMITS, timing=MOTION, jerk=True)
    gate.reset(time=0.0)
    times, lengths = [0.0], [GEOMETRY.home_leg_lengths]
    rng = np.random.default_rng(5)
    time = 0.0
    for k in range(1, 40):
        time += rng.uniform(0.008, 0.012)
        pose = HOME + [0.002 * (1.0 - math.cos(3.0 * time)), 0.0, 0.0, 0.0, 0.0, 0.0]
        command = gate.pose(pose[:3], euler_zyx_to_matrix(pose[3:]), time)
        assert command.accepted, command.reason
        times.append(time)
        lengths.append(command.lengths)
        if k >= 3:
            velocity, acceleration, _ = divided_derivatives(times, lengths)
            assert_allclose(command.velocities, velocity, rtol=1e-9, atol=1e-12)
            assert_allclose(command.accelerations, acceleration, rtol=1e-6, atol=1e-9)
    # A cubic motion of jerk j from rest, on a uniform clock: j is the third divided difference.
    for jerk, allowed in ((LIMITS.jerk_max * 0.999, True), (LIMITS.jerk_max * 1.001, False)):
        gate.reset(time=0.0)
        home = GEOMETRY.home_leg_lengths
        for k in range(1, 6):
            t = k * 0.01
            command = gate.legs(home + [jerk * t ** 3 / 6.0, 0, 0, 0, 0, 0], t)
            if k >= 3:
                assert command.accepted == allowed, command.reason
                if not allowed:
                    assert 'leg_jerk_max' in command.reason
                    break


@given(st.floats(0.2, 0.95), st.floats(2.5, 8.0), st.integers(0, 2 ** 31),
       st.floats(0.0, 0.45))
@example(0.9375, 2.5, 788, 0.0)   # its legs lead to a pose beyond max_jacobian_condition
@budget(25)
def test_a_motion_within_the_limits_passes_whatever_the_send_times(share, frequency, seed,
                                                                   jitter):
    """
    A smooth motion within the limits passes every command, whatever its send times.

    Peak velocity and acceleration at ``share`` of the limits, sent at jittered times (each
    interval off by up to 45 %): the divided differences never exceed the derivatives they
    stand for.
    """
    amplitude = share * min(LIMITS.velocity_max / frequency,
                            LIMITS.acceleration_max / frequency ** 2)
    gate = CommandGate(GEOMETRY, LIMITS, timing=MOTION)
    home = GEOMETRY.home_leg_lengths
    gate.reset(time=0.0)
    rng = np.random.default_rng(seed)
    direction = rng.uniform(-1.0, 1.0, 6)
    direction /= np.max(np.abs(direction))
    time = 0.0
    for _ in range(150):
        time += 0.01 * (1.0 + jitter * rng.uniform(-1.0, 1.0))
        # Leg lengths on a smooth path: |l'| <= share v_max, |l''| <= share a_max per leg.
        lengths = home + direction * amplitude * (1.0 - math.cos(frequency * time))
        command = gate.legs(lengths, time)
        broken = {violation.limit for violation in command.violations}
        if broken and broken <= set(LIMIT_NAMES):
            # A random direction may lead the legs to a pose beyond a pose limit (near a
            # singularity, say): the rates are what this test is about, so it ends there.
            break
        assert command.accepted, command.reason


def test_a_stop_in_one_step_is_refused_and_braking_keeps_the_limits():
    """
    A stop in one step is refused; the gate brakes within every rate limit instead.

    The defect of the cue's last resort (issue 27): legs at 0.0245 m/s held in one 10 ms step
    ask 2.45 m/s^2. The gate refuses the hold; its braking slows each leg at 0.25 m/s^2 to rest
    within every rate limit, in about v / a, never in one step.
    """
    gate = CommandGate(GEOMETRY, LIMITS, timing=MOTION)
    home = GEOMETRY.home_leg_lengths
    velocity = np.array([0.0245, -0.0245, 0.01, 0.0, 0.02, -0.005])
    gate.reset(time=0.0)
    ramp = 0.2   # from rest to `velocity` in 0.2 s: at most 0.1225 m/s^2
    times, sent = [0.0], [home]
    for k in range(1, 40):
        t = k * 0.01
        travel = t * t / (2.0 * ramp) if t < ramp else t - ramp / 2.0
        command = gate.legs(home + velocity * travel, t)
        assert command.accepted, command.reason
        times.append(t)
        sent.append(command.lengths)
    held = gate.legs(sent[-1], 0.40)
    assert held.refusal.code == 'too_fast'
    assert 'leg_acceleration_max' in held.reason and '2.45' in held.reason
    time, braking = 0.40, 0
    while True:
        command = gate.brake(time, replaced=held.refusal)
        assert command.accepted and command.braking
        assert command.warnings[0].code == 'command_braking'
        times.append(time)
        sent.append(command.lengths)
        braking += 1
        if not np.any(command.velocities):
            break
        time += 0.01
        assert time < 1.0
    velocities = np.diff(sent, axis=0) / np.diff(times)[:, None]
    accelerations = np.diff(velocities, axis=0) / 0.01
    assert np.abs(velocities).max() <= LIMITS.velocity_max
    assert np.abs(accelerations).max() <= LIMITS.acceleration_max * (1 + 1e-9)
    assert 9 <= braking <= 12   # 0.0245 / 0.25 = 0.098 s


def test_braking_stops_a_leg_at_the_end_of_its_stroke_and_says_so():
    """A leg too fast to stop before leg_length_max stops there; the finding says so."""
    geometry = GEOMETRY.with_limits(leg_length_max=GEOMETRY.home_leg_lengths[0] + 0.0062)
    gate = CommandGate(geometry, LIMITS, timing=MOTION)
    home = geometry.home_leg_lengths
    gate.reset(time=0.0)
    leg_1 = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    for k in range(1, 21):   # 0.2 s at 0.2 m/s^2: 0.04 m/s after 4 mm; 3.2 mm to stop, 2.2 left
        t = k * 0.01
        assert gate.legs(home + leg_1 * 0.1 * t * t, t).accepted
    time, messages = 0.2, []
    while True:
        time += 0.01
        command = gate.brake(time)
        assert command.lengths[0] <= geometry.leg_length_max
        messages += [finding.message for finding in command.warnings]
        if not np.any(command.velocities):
            break
    assert command.lengths[0] == geometry.leg_length_max
    assert any('legs [1] stopped at the end of the stroke' in message for message in messages)


def test_a_motion_outside_its_limits_may_only_come_back():
    """After a braking command beyond a limit, commands no further out pass, further out not."""
    geometry = GEOMETRY.with_limits(leg_length_max=GEOMETRY.home_leg_lengths[0] + 0.001)
    gate = CommandGate(geometry, LIMITS, timing=MOTION)
    home = geometry.home_leg_lengths
    # The platform rests 0.5 mm beyond the stroke on leg 1 (after braking that could not stop).
    gate.reset(home + [0.0015, 0.0, 0.0, 0.0, 0.0, 0.0], time=0.0)
    back = gate.legs(home + [0.00148, 0.0, 0.0, 0.0, 0.0, 0.0], 0.02)
    assert back.accepted and back.warnings[0].code == 'returning_to_limits'
    further = gate.legs(home + [0.00149, 0.0, 0.0, 0.0, 0.0, 0.0], 0.04)
    assert further.refusal.code == 'out_of_limits'
    assert gate.legs(home + [0.00146, 0.0, 0.0, 0.0, 0.0, 0.0], 0.04).accepted


def test_the_clock_a_motion_is_sent_on():
    """
    A motion's commands need time to pass between them.

    No time passed: a new command is refused, the same one again passes; a clock moved back
    starts a new time line.
    """
    gate = CommandGate(GEOMETRY, LIMITS, timing=MOTION)
    gate.reset(time=1.0)
    home = GEOMETRY.home_leg_lengths
    moved = home + 1e-5
    assert gate.legs(moved, 1.01).accepted
    assert gate.legs(moved + 1e-6, 1.01).refusal.code == 'clock_not_advancing'
    far_back = gate.legs(moved + 1e-6, -1e308).refusal   # its time in 9 digits, not 300
    assert 'the command at -1e+308 s does not come after the last one (1.010000000 s)' \
        in far_back.message and len(far_back.message) < 200
    assert gate.legs(moved, 1.01).accepted
    assert gate.elapsed(0.5) is None and gate.last_time == 0.5
    assert gate.elapsed(0.51) == pytest.approx(0.01)
    assert gate.legs(moved, math.nan).refusal.code == 'clock_not_advancing'


def test_leg_velocities_that_cannot_stop_inside_the_stroke_are_refused():
    """A leg 1 mm from its end commanded outward at 0.04 m/s needs 3.2 mm to stop: refused."""
    gate = CommandGate(GEOMETRY, LIMITS)
    lengths = GEOMETRY.home_leg_lengths.copy()
    lengths[2] = GEOMETRY.leg_length_max - 0.001
    outward = np.array([0.0, 0.0, 0.04, 0.0, 0.0, 0.0])
    command = gate.leg_velocities(outward, lengths)
    assert command.refusal.code == 'out_of_limits' and 'legs [3]' in command.reason
    assert gate.leg_velocities(-outward, lengths).accepted
    assert gate.leg_velocities(outward * 0.5, lengths).accepted   # 0.8 mm to stop


# Trajectories ---------------------------------------------------------------------------------

def bulging_plan(validation_rate, publish_rate):
    """Issue 27's trajectory: two waypoints, a start velocity that bulges the path ~67 mm up."""
    geometry = GEOMETRY.with_limits(leg_length_max=0.75)
    planner = MotionPlanner(geometry, ActuatorLimits(10.0, 100.0),
                            validation_rate=validation_rate, publish_rate=publish_rate)
    quaternion = euler_zyx_to_quaternion([0.0, 0.0, 0.0])
    positions = np.array([[0.0, 0.0, 0.4325], [0.0, 0.0, 0.4325]])
    return planner.plan_trajectory([0.0, 1.0], positions, [quaternion, quaternion],
                                   np.array([[0.0, 0.0, 0.35], [0.0, 0.0, 0.0]]),
                                   np.zeros((2, 3)))


def test_a_trajectory_is_checked_at_every_point_it_is_published_with():
    """Validation at 1 Hz missed the bulge; the gate checks the 100 Hz points and refuses."""
    plan = bulging_plan(1.0, 100.0)
    assert plan.refusal.code == 'out_of_limits'
    assert 'published point' in plan.reason and 'leg_length_max' in plan.reason
    assert 'validation_rate' in plan.reason


def test_the_controllers_interpolation_between_sparse_points_is_checked():
    """1 point a second: both points are within the stroke, the quintic between is not."""
    plan = bulging_plan(1.0, 1.0)
    assert plan.refusal.code == 'out_of_limits'
    assert "controller's interpolation" in plan.reason


def test_every_published_point_of_an_accepted_trajectory_keeps_every_limit():
    """A retimed 5-waypoint path: each point's lengths, velocities, accelerations, pose."""
    planner = MotionPlanner(GEOMETRY, LIMITS, retime=True, validation_rate=50.0,
                            publish_rate=200.0)
    poses = HOME + np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.03, 0.0, 0.01, 0.0, 0.05, 0.0],
                             [0.0, 0.03, 0.02, 0.05, 0.0, 0.1], [-0.02, 0.0, 0.0, 0.0, 0.0, 0.0],
                             [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    quaternions = [euler_zyx_to_quaternion(pose[3:]) for pose in poses]
    plan = planner.plan_trajectory(np.arange(5.0), poses[:, :3], quaternions)
    assert plan.accepted, plan.reason
    points = plan.command.trajectory
    assert np.all(points.lengths >= GEOMETRY.leg_length_min)
    assert np.all(points.lengths <= GEOMETRY.leg_length_max)
    assert np.abs(points.velocities).max() <= LIMITS.velocity_max * (1 + 1e-9)
    assert np.abs(points.accelerations).max() <= LIMITS.acceleration_max * (1 + 1e-9)
    samples = plan.trajectory.sample(points.times)
    expected = reference.leg_lengths_batch(samples.positions, samples.rotations)
    assert_allclose(points.lengths, expected, atol=1e-12)
