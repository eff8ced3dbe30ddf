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
The model-predictive cueing (cueing_method mpc): its QP, its model, and the core running it.

Independent values: the leg lengths of the plan by exact inverse kinematics (not the MPC's
linearisation), the prediction against scipy's integration of the continuous model, the
model's specific force against the perception module's finite differences of the cue's poses,
and the limits by the evaluator's own checks. About 10 s in all.
"""

import math
from pathlib import Path

from hypothesis import given, settings, strategies as st
import numpy as np
from numpy.testing import assert_allclose
import pytest
from scipy.integrate import solve_ivp

from stewart_kinematics.cueing import CueingSettings, MotionCueing, replay
from stewart_kinematics.cueing.evaluation import evaluate
from stewart_kinematics.cueing.mpc_cueing import (
    continuous_model,
    DOF,
    MpcCueing,
    output_matrix,
    STATES,
)
from stewart_kinematics.cueing.perception import perceived_motion
from stewart_kinematics.cueing.qp_solver import QpResult, QpSolver
from stewart_kinematics.cueing.scenarios import scenario
from stewart_kinematics.cueing.washout import ClassicalWashout
from stewart_kinematics.findings import MPC_FALLBACK
from stewart_kinematics.limits import limits_of
from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.parameters import read_parameter_file

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml')]
G = 9.80665


def shipped_values(**changes):
    """Return the shipped files' parameters with ``cueing_method: mpc`` and ``changes``."""
    values = {}
    for path in FILES:
        values.update(read_parameter_file(path, 'motion_cueing_node'))
    values['cueing_method'] = 'mpc'
    values.update(changes)
    return values


@pytest.fixture(scope='module')
def core():
    """Return a MotionCueing with the MPC (its state is reset by each test that steps it)."""
    return MotionCueing.from_parameters(shipped_values())


def test_cueing_method_switch_builds_the_right_object(core):
    """Classical stays the default; mpc builds the MPC over the core's own limiter."""
    classical = MotionCueing.from_parameters(shipped_values(cueing_method='classical'))
    assert type(classical.washout) is ClassicalWashout
    assert isinstance(core.washout, MpcCueing)
    assert core.washout.limiter is core.limiter
    assert CueingSettings().cueing_method == 'classical'


def _plan_states(mpc, plan):
    """Simulate the plan with the MPC's step matrices; return the states after each step."""
    states, x = [], mpc.state.copy()
    for u in plan:
        x = mpc._phi @ x + mpc._gamma @ u
        states.append(x.copy())
    return np.array(states)


@settings(max_examples=25, deadline=None)
@given(st.lists(st.floats(-1.0, 1.0), min_size=10, max_size=10),
       st.floats(-4.0, 4.0), st.floats(-4.0, 4.0))
def test_plan_keeps_the_leg_limits_from_random_states(core, shares, force_x, force_y):
    """
    From random states inside the box, the plan keeps the hard rows, and its next step the legs.

    The hard linearised rows over the whole horizon; then the first step (0.2 s) on the exact
    leg lengths of the planned cue poses (inverse kinematics), not on the MPC's linearisation:
    the stroke within its margin less 2 mm, the leg velocities (finite differences of those
    lengths) within the actuators' limit (the plan uses 0.8 of it).
    """
    mpc = core.washout
    mpc.reset()
    state = np.zeros(STATES)
    shares = np.array(shares)
    state[0:3] = 0.3 * shares[0:3] * mpc._box[1, 0:3]
    state[6:8] = 0.3 * shares[3:5] * mpc._box[1, 3:5]
    state[3:6] = 0.01 * shares[5:8]          # m/s
    state[8:10] = 0.02 * shares[8:10]        # rad/s, within the tilt rate limit
    force = [force_x, force_y, G]
    mpc.step_checked(force, [0.0, 0.0, 0.0], 0.0)   # settles the vehicle's perception
    mpc.state = state
    problem = mpc._problem(mpc._vehicle_input(force, [0.0, 0.0, 0.0]), 0.0)
    result = mpc.solver.solve(*problem)
    assert result.solved
    gradient, a, lower, upper, bounds_lower, bounds_upper = problem
    hard = mpc.hard_rows
    assert np.all(a[:hard] @ result.x >= lower[:hard] - 1e-6)
    assert np.all(a[:hard] @ result.x <= upper[:hard] + 1e-6)
    # On the exact legs, the step the plan applies before it is made again (the first; the
    # linearisation is about the current pose, and the far end of the plan moves on).
    states = _plan_states(mpc, result.x.reshape(mpc.horizon, DOF))[:1]
    poses = core.limiter.cue_poses(states[:, 0:3],
                                   np.concatenate([states[:, 6:8], np.zeros((len(states), 1))],
                                                  axis=1))
    lengths = np.array([inverse_kinematics(core.geometry, pose) for pose in poses])
    limits = limits_of(core.geometry)
    margin = core.limiter.leg_length_margin
    assert np.all(lengths >= limits.leg_length_min + margin - 2e-3)
    assert np.all(lengths <= limits.leg_length_max - margin + 2e-3)
    start = inverse_kinematics(core.geometry, core.limiter.cue_poses(state[0:3],
                                                                     [*state[6:8], 0.0]))
    speeds = np.diff(np.vstack([start, lengths]), axis=0) / mpc.step_time
    assert np.all(np.abs(speeds) <= core.actuator_limits.velocity_max)
    mpc.reset()


def test_sustained_force_tilts_within_the_rate_limit(core):
    """A step of forward force: the cue pitches nose-up (gravity plays it), within 3 deg/s."""
    mpc = core.washout
    mpc.reset()
    dt, rate_max = 0.01, core.settings.tilt_rate_max
    pitches, rates = [], []
    for index in range(800):
        force = [2.0 if index >= 10 else 0.0, 0.0, G]
        step = mpc.step_checked(force, [0.0, 0.0, 0.0], 0.0 if index == 0 else dt)
        pitches.append(step.tilt[1])
        rates.append(step.tilt_rate)
        assert step.solved
    pitches, rates = np.array(pitches), np.array(rates)
    # f_x = -g sin(pitch): a forward force is played by a negative pitch.
    assert pitches[-1] < -math.radians(0.5)
    assert np.all(np.abs(rates) <= rate_max * (1.0 + 1e-9))
    assert np.all(np.abs(np.diff(pitches)) / dt <= rate_max * (1.0 + 1e-6))
    mpc.reset()


def test_prediction_matches_an_integration_of_the_continuous_model(core):
    """Phi_z x0 + Gamma_z U equals scipy's integration of x' = A x + B u with u held."""
    mpc = core.washout
    rng = np.random.default_rng(7)
    x0 = rng.normal(scale=0.05, size=STATES)
    inputs = rng.normal(scale=0.3, size=(mpc.horizon, DOF))
    predicted = (mpc._phi_z @ x0 + mpc._gamma_z @ inputs.ravel()).reshape(mpc.horizon, -1)
    a, b = continuous_model(G)
    c = output_matrix()
    x = x0.copy()
    for k in range(mpc.horizon):
        solution = solve_ivp(lambda _, state, u=inputs[k]: a @ state + b @ u,
                             (0.0, mpc.step_time), x, rtol=1e-11, atol=1e-13)
        x = solution.y[:, -1]
        assert_allclose(predicted[k], c @ x, rtol=1e-7, atol=1e-9)


def test_model_force_is_the_force_felt_on_the_cue_poses(core):
    """
    The model's specific force ``a + g [-pitch, roll, 0]`` is what the head feels.

    On the cue's poses of an MPC run (a force step), the perception module's finite
    differences give the specific force in the platform frame; the small-angle model agrees
    to 1 % of the largest force plus the second-order terms it drops.
    """
    mpc = core.washout
    mpc.reset()
    dt = 0.01
    times, poses, accelerations, gravity = [], [], [], []
    for index in range(300):
        force = [1.5 if index >= 10 else 0.0, -1.0 if index >= 50 else 0.0, G]
        step = mpc.step_checked(force, [0.0, 0.0, 0.0], 0.0 if index == 0 else dt)
        times.append(index * dt)
        poses.append(core.limiter.cue_poses(step.displacement, step.angles))
        accelerations.append(mpc._input[:3].copy())   # held over the next interval
        gravity.append(G * np.array([-step.tilt[1], step.tilt[0], 0.0]))
    mpc.reset()
    felt = perceived_motion(np.array(times), np.array(poses), core.settings.head_position)
    felt_force = felt.specific_force - [0.0, 0.0, G]
    accelerations, gravity = np.array(accelerations), np.array(gravity)
    # The centred difference at sample k sees the mean of the accelerations held over the
    # intervals before and after it; gravity is the tilt's at k.
    model = 0.5 * (accelerations[:-2] + accelerations[1:-1]) + gravity[1:-1]
    scale = np.max(np.abs(model))
    assert scale > 0.05
    # Dropped by the small-angle model: g (1 - cos) on z and the accelerations turned by the
    # tilt, second order in the angle.
    angle = float(np.max(np.abs(gravity))) / G
    dropped = G * angle ** 2 / 2.0 + float(np.max(np.abs(accelerations))) * angle
    assert_allclose(felt_force[1:-1], model, atol=0.01 * scale + dropped)


def test_core_replay_with_mpc_keeps_every_limit(core):
    """A 5 s lane change through MotionCueing with the MPC: no limit broken, tilt <= 3 deg/s."""
    lane = scenario('lane_change')
    keep = lane.times <= 5.0
    cueing = MotionCueing.from_parameters(shipped_values())
    played = replay(cueing, lane.times[keep], lane.specific_force[keep],
                    lane.angular_velocity[keep])
    assert np.all(np.isfinite(played.poses))
    measured = evaluate(played, cueing.geometry, cueing.actuator_limits,
                        cueing.settings.tilt_rate_max)
    assert measured.limit_violations == 0
    assert measured.platform_tilt_rate_peak <= math.radians(3.0) * (1.0 + 1e-6)
    assert 'mpc_fallback' not in played.warnings
    # The cue is felt in phase with the lane change (classical: 0.05 over the whole run).
    assert measured.measures('y').correlation > 0.6


@pytest.mark.parametrize('name, value, words', [
    ('cueing_method', 'predictive', ('cueing_method', 'classical, mpc')),
    ('mpc_horizon', 1, ('mpc_horizon',)),
    ('mpc_horizon', 2.5, ('mpc_horizon', 'integer')),
    ('mpc_step', math.nan, ('mpc_step',)),
    ('mpc_step', 0.0, ('mpc_step',)),
    ('mpc_input_weight', [0.0, 0.01], ('mpc_input_weight',)),
    ('mpc_force_weight', [1.0, 1.0], ('mpc_force_weight', '3')),
    ('mpc_limit_share', 1.5, ('mpc_limit_share',)),
    ('mpc_reference_time_constant', -1.0, ('mpc_reference_time_constant',)),
    ('mpc_workspace_share', math.inf, ('mpc_workspace_share',)),
])
def test_bad_parameters_are_refused_with_the_reason(name, value, words):
    """Each bad mpc parameter gets one line naming it and what is allowed."""
    with pytest.raises(ValueError) as raised:
        MotionCueing.from_parameters(shipped_values(**{name: value}))
    message = str(raised.value)
    assert '\n' not in message
    for word in words:
        assert word in message


def test_settings_refuse_a_method_that_is_not_a_word():
    """The settings check the kind of the new fields too."""
    with pytest.raises(ValueError, match='cueing_method'):
        CueingSettings(cueing_method=3)
    with pytest.raises(ValueError, match='mpc_horizon'):
        CueingSettings(mpc_horizon=2.5)


class FailingSolver:
    """A solver that never solves (infeasible, out of iterations): the fallback's test."""

    def __init__(self):
        self.calls = 0
        self.fail = False
        self.inner = None

    def solve(self, *problem):
        self.calls += 1
        if self.fail:
            return QpResult(None, False, 1000, -4)
        return self.inner.solve(*problem)

    def reset(self):
        if self.inner is not None:
            self.inner.reset()


def test_solver_failure_falls_back_and_every_command_keeps_the_limits():
    """
    The QP fails from 1.5 s on: the last plan runs out, then the cue brakes to rest.

    Every command stays finite and within the limits; each failed step warns mpc_fallback.
    """
    cueing = MotionCueing.from_parameters(shipped_values())
    failing = FailingSolver()
    failing.inner = cueing.washout.solver
    cueing.washout.solver = failing
    lane = scenario('lane_change')
    keep = lane.times <= 4.5
    times = lane.times[keep]
    poses, lengths, fallbacks = [], [], 0
    for index, t in enumerate(times):
        failing.fail = t >= 1.5
        step = cueing.step(t, lane.specific_force[index], lane.angular_velocity[index])
        poses.append(step.pose)
        lengths.append(step.lengths)
        fallbacks += any(finding.code == MPC_FALLBACK for finding in step.warnings)
        assert step.command.accepted
    assert fallbacks == np.count_nonzero(times >= 1.5)
    poses = np.array(poses)
    assert np.all(np.isfinite(poses))
    # After the plan ran out the cue brakes: its rates come to rest.
    mpc = cueing.washout
    assert_allclose(mpc.state[3:6], 0.0, atol=1e-6)
    assert_allclose(mpc.state[8:10], 0.0, atol=1e-6)
    steps = np.diff(times)
    velocities = np.diff(np.array(lengths), axis=0) / steps[:, None]
    assert np.all(np.abs(velocities) <= cueing.actuator_limits.velocity_max * (1 + 1e-9))
    accelerations = np.diff(velocities, axis=0) / steps[1:, None]
    assert np.all(np.abs(accelerations) <= cueing.actuator_limits.acceleration_max * (1 + 1e-6))


def test_qp_solver_reports_failures_instead_of_raising():
    """Infeasible bounds, an iteration limit hit, non-finite data: not solved, no exception."""
    hessian = np.eye(2)
    solver = QpSolver(hessian)
    a = np.array([[1.0, 1.0]])
    infeasible = solver.solve(np.zeros(2), a, np.array([3.0]), np.array([4.0]),
                              np.array([-1.0, -1.0]), np.array([1.0, 1.0]))
    assert not infeasible.solved and infeasible.x is None
    limited = QpSolver(hessian, max_iterations=1)
    result = limited.solve(np.array([-5.0, -5.0]), np.array([[1.0, 0.0], [0.0, 1.0]]),
                           np.array([-1.0, -1.0]), np.array([1.0, 1.0]),
                           np.array([-0.5, -0.5]), np.array([0.5, 0.5]))
    assert not result.solved
    nan = solver.solve(np.array([math.nan, 0.0]), a, np.array([0.0]), np.array([1.0]),
                       np.array([-1.0, -1.0]), np.array([1.0, 1.0]))
    assert not nan.solved
    solved = solver.solve(np.array([-1.0, 0.0]), a, np.array([-10.0]), np.array([10.0]),
                          np.array([-0.5, -1.0]), np.array([0.5, 1.0]))
    assert solved.solved
    assert_allclose(solved.x, [0.5, 0.0], atol=1e-9)
