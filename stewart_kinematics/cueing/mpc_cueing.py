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
Model-predictive motion cueing: translation and tilt traded over a horizon, within the legs.

A linear MPC over the perception model (``cueing_method: mpc``; doc/motion_cueing_mpc.md gives
the formulation with its equations, the solver's measurement and the tuning). Each sample it
solves one quadratic programme (QP) and applies the first input for the sample's ``dt``:

- **state** (25): the head's displacement ``p`` and velocity ``v`` (x, y, z, base frame,
  metres), the tilt ``phi`` (roll, pitch, radians) and its rate, and the 15 states of the
  vestibular model (:func:`~.vestibular.vestibular_bank`: otoliths on the specific force, canals
  on the angular velocity) driven by the platform's motion;
- **input** (5): the head's acceleration ``a`` (m/s^2) and the tilt's acceleration (rad/s^2),
  held over each step of ``mpc_step`` seconds;
- **specific force at the head** (platform frame, relative to ``[0, 0, g]``), small angles:
  ``f = a + g [-pitch, roll, 0]`` (tilting by ``theta`` gives ``g theta`` of specific force:
  gravity tilt coordination is part of the model; the products of angles and accelerations
  are dropped, below 1 % for the 10 degrees of tilt allowed);
- **cost**: over ``mpc_horizon`` steps, the perceived specific force and roll and pitch rate
  against the vehicle's perceived ones (scaled by ``mpc_force_scale`` and ``rotation_scale``,
  and at run time by the intensity and gains: :meth:`MpcCueing.set_gains`),
  the reference being the vehicle's current input held over the horizon and fading with
  ``mpc_reference_time_constant`` (``inf``: held), plus small weights on the displacement,
  velocity, tilt and tilt rate (the washout to neutral) and on the inputs;
- **constraints**: every leg's length within its stroke less the cue's margin, its velocity
  and acceleration within ``mpc_limit_share`` of the actuator limits (the leg Jacobian rows of
  :func:`~stewart_kinematics.model.jacobians.jacobian`, linearised about the current cue's
  pose), the tilt rate and the perceived (canals') roll and pitch rate within
  ``tilt_rate_max`` (below the threshold of perceived rotation),
  the tilt within ``tilt_max``, and the platform at rest at the horizon's end (so that the
  plan can always stop inside the stroke).

Yaw is not in the MPC (it changes no specific force at the head): the classical washout's
rotational channel cues it, as in the classical method. The output replaces the classical
washout's (:class:`~.washout.WashoutStep`), and :class:`~.cue_limiter.CueLimiter` keeps every
command within every limit whatever the MPC says. When the QP fails (infeasible, or out of
iterations), the rest of the last plan is applied, and once that runs out the cue brakes to
rest (an ``mpc_fallback`` warning), never a non-finite cue. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.cueing.controls import WashoutGains
from stewart_kinematics.cueing.filters import expm, TIME_QUANTUM
from stewart_kinematics.cueing.limit_margins import poses_allowed
from stewart_kinematics.cueing.qp_solver import QpSolver
from stewart_kinematics.cueing.settings import CueingSettings
from stewart_kinematics.cueing.vehicle_preview import refuse_absurd_rows
from stewart_kinematics.cueing.vestibular import vestibular_bank
from stewart_kinematics.cueing.washout import ClassicalWashout, WashoutStep
from stewart_kinematics.findings import Finding, MPC_FALLBACK
from stewart_kinematics.limits import limits_of
from stewart_kinematics.model.arrays import as_float_array
from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.model.jacobians import jacobian

#: Degrees of freedom the MPC moves: x, y, z of the head, roll and pitch of the tilt.
DOF = 5
#: States: p (3), v (3), tilt (2), tilt rate (2), the vestibular bank's (15).
POSITION, VELOCITY, TILT, TILT_RATE, VESTIBULAR = (
    slice(0, 3), slice(3, 6), slice(6, 8), slice(8, 10), slice(10, 25))
STATES = 25
#: Outputs weighed per step: perceived force (3) and roll, pitch rate (2), q (5), q' (5).
OUTPUTS = 15
#: Step of the finite differences of the cue's pose in the cue's coordinates (m, rad).
_DIFFERENCE_STEP = 1e-6
#: Keep this many step lengths' discretisation.
_CACHE_SIZE = 64
#: The reach of each cue coordinate is searched up to this (metres, radians), in this many
#: samples.
_REACH_SEARCH = (0.5, 0.5, 0.5, 0.5, 0.5)
_REACH_SAMPLES = 500


def cue_reach(limiter) -> np.ndarray:
    """
    Return how far each cue coordinate alone goes inside the cue's limits, shape (2, 5).

    Rows: toward negative (as a negative number) and toward positive values; columns: the
    head's x, y, z (metres), roll and pitch (radians). Each coordinate is moved alone from
    neutral, in :data:`_REACH_SAMPLES` steps up to :data:`_REACH_SEARCH`, until its pose
    leaves the limits narrowed by the cue's margins (``limiter.cue_geometry``: the stroke, the
    joint cones, the singularity margin, every limit of the limits model).
    """
    reach = np.zeros((2, DOF))
    shares = np.linspace(0.0, 1.0, _REACH_SAMPLES + 1)[1:]
    for axis in range(DOF):
        for row, sign in enumerate((-1.0, 1.0)):
            q = np.zeros((shares.size, 6))
            q[:, axis] = sign * _REACH_SEARCH[axis] * shares
            poses = limiter.cue_poses(q[:, :3], q[:, 3:])
            allowed = poses_allowed(limiter.cue_geometry, poses)
            first_out = int(np.argmin(allowed)) if not np.all(allowed) else shares.size
            reach[row, axis] = sign * _REACH_SEARCH[axis] * (shares[first_out - 1]
                                                             if first_out > 0 else 0.0)
    return reach


@dataclass(frozen=True)
class MpcStep(WashoutStep):
    """
    A :class:`~.washout.WashoutStep` of the MPC, with how its QP went.

    :param findings: ``mpc_fallback`` when the QP failed and the last plan or braking was
        applied instead.
    :param solved: whether this step's QP was solved.
    :param iterations: the solver's iterations (0 when no QP was solved).
    """

    findings: Tuple[Finding, ...] = ()
    solved: bool = True
    iterations: int = 0


def continuous_model(gravity: float):
    """
    Return ``(A, B)`` of the platform and its perception, continuous time (25 and 5 columns).

    ``x' = A x + B u``; see the module for the state and input. The specific force is
    ``f = a + g [-pitch, roll, 0]`` and the canals see the tilt rate, yaw rate 0.
    """
    bank = vestibular_bank()
    a = np.zeros((STATES, STATES))
    b = np.zeros((STATES, DOF))
    a[POSITION, VELOCITY] = np.eye(3)
    b[VELOCITY, 0:3] = np.eye(3)
    a[TILT, TILT_RATE] = np.eye(2)
    b[TILT_RATE, 3:5] = np.eye(2)
    # The bank's input [f, w] as a function of the state and input.
    force_of_state = np.zeros((6, STATES))
    force_of_state[0, 7] = -gravity   # f_x = a_x - g pitch
    force_of_state[1, 6] = gravity    # f_y = a_y + g roll
    force_of_state[3, 8] = force_of_state[4, 9] = 1.0   # w_roll, w_pitch
    force_of_input = np.zeros((6, DOF))
    force_of_input[0:3, 0:3] = np.eye(3)
    a[VESTIBULAR, VESTIBULAR] = bank.a
    a[VESTIBULAR, :] += bank.b @ force_of_state
    b[VESTIBULAR, :] += bank.b @ force_of_input
    return a, b


def discretised(a, b, dt: float):
    """Return the exact zero-order-hold ``(Phi, Gamma)`` of ``(a, b)`` over ``dt`` seconds."""
    states, inputs = b.shape
    augmented = np.zeros((states + inputs, states + inputs))
    augmented[:states, :states] = a
    augmented[:states, states:] = b
    exponential = expm(augmented * dt)
    return exponential[:states, :states].copy(), exponential[:states, states:].copy()


def output_matrix() -> np.ndarray:
    """Return ``C`` (15 x 25): perceived force and roll, pitch rate; q; q'."""
    c = np.zeros((OUTPUTS, STATES))
    c[0:5, VESTIBULAR] = vestibular_bank().c[0:5]
    c[5:8, POSITION] = np.eye(3)
    c[8:10, TILT] = np.eye(2)
    c[10:13, VELOCITY] = np.eye(3)
    c[13:15, TILT_RATE] = np.eye(2)
    return c


def prediction_matrices(phi, gamma, c, horizon: int):
    """
    Return ``(Phi_z, Gamma_z)``: ``z_k = C x_k`` for ``k = 1..N`` from ``x_0`` and the inputs.

    ``Z = Phi_z x_0 + Gamma_z U``, ``Z`` stacked ``(N * outputs,)``, ``U`` ``(N * inputs,)``.
    """
    outputs, inputs = c.shape[0], gamma.shape[1]
    phi_z = np.zeros((horizon * outputs, phi.shape[0]))
    gamma_z = np.zeros((horizon * outputs, horizon * inputs))
    power = np.eye(phi.shape[0])
    responses = []   # C Phi^j Gamma
    for k in range(horizon):
        responses.append(c @ power @ gamma)
        power = phi @ power
        phi_z[k * outputs:(k + 1) * outputs] = c @ power
    for k in range(horizon):
        for j in range(k + 1):
            gamma_z[k * outputs:(k + 1) * outputs, j * inputs:(j + 1) * inputs] = \
                responses[k - j]
    return phi_z, gamma_z


class MpcCueing:
    """
    The model-predictive cueing as one stateful object, stepped like the classical washout.

    :param settings: a :class:`~stewart_kinematics.cueing.CueingSettings` (its ``mpc_*``
        fields, ``tilt_rate_max``, ``tilt_max``, ``tilt_acceleration_max``, ``rotation_*``).
    :param limiter: the :class:`~.cue_limiter.CueLimiter` that follows the cue: its geometry,
        actuator limits, stroke margin and the cue's pose (:meth:`~.cue_limiter.CueLimiter.
        cue_poses`) are what the constraints are linearised from.
    :param solver: a :class:`~.qp_solver.QpSolver` (default: one built from the settings).
    """

    #: The plan keeps the cue within its box (each coordinate's reach times
    #: ``mpc_workspace_share``) and the legs' stroke whatever the gains, so the travel check
    #: of a gain change (:class:`~.controls.GainCheck`, which measures the classical filters'
    #: response) does not apply: a larger aim is met as far as the limits allow.
    keeps_travel = True

    def __init__(self, settings: CueingSettings, limiter, solver: Optional[QpSolver] = None):
        self.settings = s = settings
        self.limiter = limiter
        self.gravity = s.gravity
        self.horizon = n = s.mpc_horizon
        self.step_time = s.mpc_step
        self._a, self._b = continuous_model(s.gravity)
        self._phi, self._gamma = discretised(self._a, self._b, s.mpc_step)
        self._c = output_matrix()
        self._phi_z, self._gamma_z = prediction_matrices(self._phi, self._gamma, self._c, n)
        # Weights of z = [perceived f (3), perceived w (2), q (5), q' (5)] and of u.
        weights = np.concatenate([
            s.mpc_force_weight, [s.mpc_rate_weight] * 2, s.mpc_position_weight,
            [s.mpc_tilt_weight] * 2, s.mpc_velocity_weight, [s.mpc_tilt_rate_weight] * 2])
        self._z_weights = np.tile(weights, n)
        input_weights = np.tile(np.array([s.mpc_input_weight[0]] * 3
                                         + [s.mpc_input_weight[1]] * 2), n)
        weighted = self._gamma_z * self._z_weights[:, None]
        self.hessian = self._gamma_z.T @ weighted + np.diag(input_weights)
        self.hessian = 0.5 * (self.hessian + self.hessian.T)
        self._gradient_of_z = weighted.T   # g = Gamma_z^T W (Phi_z x0 - R)
        # Rows of q and q' in Z, as (N, 5, ...) views.
        rows = np.arange(n * OUTPUTS).reshape(n, OUTPUTS)
        self._q_rows, self._rate_rows = rows[:, 5:10], rows[:, 10:15]
        self._gamma_q = self._gamma_z[self._q_rows]           # (N, 5, 5N)
        self._gamma_rate = self._gamma_z[self._rate_rows]     # (N, 5, 5N)
        self._perceived_rate_rows = rows[:, 3:5]
        # The vehicle's perception: the same bank, driven by the vehicle's motion.
        self._vehicle = vestibular_bank()
        self._reference_matrices(s)
        # Limits.
        actuators = limiter.actuator_limits
        share = s.mpc_limit_share
        self._velocity_max = share * actuators.velocity_max
        self._acceleration_max = share * actuators.acceleration_max
        limits = limits_of(limiter.geometry)
        margin = limiter.leg_length_margin
        self._length_min = limits.leg_length_min + margin if limits.leg_length_min > 0.0 \
            else -math.inf
        self._length_max = limits.leg_length_max - margin
        self._tilt_rate_max = s.tilt_rate_max * share
        #: The box of the cue coordinates: their reach alone, times mpc_workspace_share.
        self.reach = cue_reach(limiter)
        self._box = s.mpc_workspace_share * self.reach
        # Simple bounds on the inputs: the tilt's acceleration; the head's, loose.
        bound = np.tile(np.array([100.0] * 3 + [s.tilt_acceleration_max] * 2), n)
        self._input_bounds = (-bound, bound)
        #: Rows of the constraints that are soft (after 6N + 2N + 5 hard ones).
        self.hard_rows = 8 * n + DOF
        self.solver = solver if solver is not None else QpSolver(
            self.hessian, max_iterations=s.mpc_max_iterations, hard_rows=self.hard_rows,
            bounds=DOF * n)
        self._yaw = ClassicalWashout(s)
        self._yaw_gains = None
        self._cache = {}
        self.reset()

    def _reference_matrices(self, s) -> None:
        """Precompute ``R = Psi x_vehicle + Upsilon u_vehicle`` over the horizon."""
        n, h = self.horizon, self.step_time
        phi, gamma = discretised(self._vehicle.a, self._vehicle.b, h)
        c = self._vehicle.c[0:5]
        tau = s.mpc_reference_time_constant
        fading = 0.0 if tau == 0.0 else math.exp(-h / tau)
        inputs = gamma.shape[1]
        psi = np.zeros((n * 5, phi.shape[0]))
        upsilon = np.zeros((n * 5, inputs))
        # With a preview, the input u_j of each step j given: r_k = C Phi^(k+1) x
        # + sum_{j <= k} C Phi^(k-j) Gamma u_j (block lower triangular).
        upsilon_preview = np.zeros((n * 5, n * inputs))
        response = gamma
        for lag in range(n):
            block = c @ response
            for j in range(n - lag):
                upsilon_preview[5 * (j + lag):5 * (j + lag + 1), inputs * j:inputs * (j + 1)] = \
                    block
            response = phi @ response
        state_map, input_map = np.eye(phi.shape[0]), np.zeros_like(gamma)
        for k in range(n):
            input_map = phi @ input_map + gamma * (fading ** k)
            state_map = phi @ state_map
            psi[5 * k:5 * k + 5] = c @ state_map
            upsilon[5 * k:5 * k + 5] = c @ input_map
        self._psi_unit, self._upsilon_unit = psi, upsilon
        self._upsilon_preview_unit = upsilon_preview
        #: The aim: the reference's scale of the perceived force x, y, z and roll, pitch rate.
        self.reference_scale = np.concatenate([s.mpc_force_scale, s.rotation_scale[:2]])
        self._scale_reference()

    def _scale_reference(self) -> None:
        """Scale the reference's matrices by :attr:`reference_scale`."""
        scales = np.tile(self.reference_scale, self.horizon)[:, None]
        self._psi = self._psi_unit * scales
        self._upsilon = self._upsilon_unit * scales
        self._upsilon_preview = self._upsilon_preview_unit * scales

    def set_gains(self, gains) -> None:
        """
        Take the eight effective gains (intensity times each channel gain) from the next step.

        Called by :class:`~.controls.WashoutGains` at each step of a gain ramp
        (:class:`~.controls.GainRamp`: no jump). The gains ``e`` are compared with the
        configured ones ``c`` (this object's settings' ``translation_scale`` x y z,
        ``tilt_scale`` x y, ``rotation_scale`` roll pitch yaw, at intensity 1):

        - the force aim along x is ``mpc_force_scale`` x times ``(e_tx + e_tilt_x) /
          (c_tx + c_tilt_x)``, along y likewise with the y gains; along z times
          ``e_tz / c_tz``. The MPC has no tilt channel of its own: it meets the whole force
          reference with translation (onsets) and tilt (sustained) at once, so the tilt gain is
          folded into the force aim of its axis, weighted by the configured gains (equal ratios,
          as a change of intensity gives, scale the aim by that ratio exactly). A tilt gain of 0
          therefore lowers the aim but does not forbid tilt (``tilt_max`` does that). Where the
          configured gains are 0 the aim of that axis is left as configured;
        - the aim of the perceived roll and pitch rate is the effective rotation gain itself
          (the configured aim is ``rotation_scale``, so the ratio is the same);
        - yaw (the classical rotational channel kept): the effective yaw gain, as in the
          classical washout.

        The solver's warm start is kept: a ramp moves the reference a little at each step, so
        the plan moves a little too. No limit changes: the constraints do not depend on gains.

        :param gains: the effective gains, shape (8,), finite and >= 0 (checked by the caller).
        """
        gains = np.asarray(gains, dtype=float)
        s = self.settings
        configured = np.concatenate([s.translation_scale, s.tilt_scale, s.rotation_scale])
        force = np.ones(3)
        for axis, (now, then) in enumerate((
                (gains[0] + gains[3], configured[0] + configured[3]),
                (gains[1] + gains[4], configured[1] + configured[4]),
                (gains[2], configured[2]))):
            if then > 0.0:
                force[axis] = now / then
        self.reference_scale = np.concatenate([np.asarray(s.mpc_force_scale) * force,
                                               gains[5:7]])
        self._scale_reference()
        if self._yaw_gains is None:
            self._yaw_gains = WashoutGains(self._yaw)
        self._yaw_gains.apply(gains)

    def reset(self) -> None:
        """Forget the input: the next sample settles the vehicle's perception; cue at neutral."""
        self.state = np.zeros(STATES)
        self._settled = False
        self._plan = None
        self._plan_used = 0
        self._plan_time = 0.0
        self._input = np.zeros(DOF)
        self._last_yaw = None
        self._last_dt = self.step_time
        self._yaw_rate = 0.0
        self._yaw.reset()
        self.solver.reset()
        self.last_solved = True

    # The vehicle's motion relative to rest, as the bank takes it.
    def _vehicle_input(self, specific_force, angular_velocity) -> np.ndarray:
        u = np.empty(6)
        u[:3] = specific_force
        u[2] -= self.gravity
        u[3:] = angular_velocity
        return u

    def step(self, specific_force, angular_velocity, dt: float, preview=None) -> MpcStep:
        """
        Advance by one sample (as :meth:`.washout.ClassicalWashout.step`).

        :param preview: the vehicle's input to come, or ``None`` (predicted held and fading):
            its mean over each step of the horizon, shape (``mpc_horizon``, 6), the specific
            force (m/s^2, with gravity) and angular velocity (rad/s) as the sample's
            (:func:`~.vehicle_preview.interval_means` gives it from samples).
        :raises ValueError: naming the argument, for a malformed or non-finite input, dt or
            preview, or one beyond ``max_specific_force`` or ``max_angular_velocity``.
        """
        yaw = self._yaw.step(specific_force, angular_velocity, dt)   # checks the inputs
        if preview is not None:
            preview = as_float_array(preview, 'preview')
            if preview.shape != (self.horizon, 6) or not np.all(np.isfinite(preview)):
                raise ValueError(f'preview must be finite, of shape ({self.horizon}, 6), got '
                                 f'shape {preview.shape}')
        s = self.settings
        # Beyond these the model's products overflow (1e308: numpy's 'overflow encountered').
        for name, values, largest, unit in (
                ('specific_force', np.reshape(np.asarray(specific_force, float), (1, 3)),
                 s.max_specific_force, 'm/s^2'),
                ('angular_velocity', np.reshape(np.asarray(angular_velocity, float), (1, 3)),
                 s.max_angular_velocity, 'rad/s'),
                ('preview specific_force', None if preview is None else preview[:, :3],
                 s.max_specific_force, 'm/s^2'),
                ('preview angular_velocity', None if preview is None else preview[:, 3:],
                 s.max_angular_velocity, 'rad/s')):
            if values is not None:
                refuse_absurd_rows(name, values, largest, unit, row='row')
        return self._step(specific_force, angular_velocity, dt, yaw, preview)

    def step_checked(self, specific_force, angular_velocity, dt: float,
                     preview=None) -> MpcStep:
        """:meth:`step` for inputs already checked (3 finite floats each, ``dt >= 0``)."""
        yaw = self._yaw.step_checked(specific_force, angular_velocity, dt)
        return self._step(specific_force, angular_velocity, dt, yaw, preview)

    def _step(self, specific_force, angular_velocity, dt, yaw, preview) -> MpcStep:
        vehicle = self._vehicle_input(specific_force, angular_velocity)
        if not self._settled:
            self._vehicle.settle(vehicle)
            self._settled = True
        elif dt > 0.0:
            # The platform moves by the input chosen at the previous sample, over dt.
            phi, gamma = self._discretised(dt)
            self.state = phi @ self.state + gamma @ self._input
            self._vehicle.step(vehicle, dt)
            self._plan_time += dt
            self._last_dt = dt
        yaw_angle = float(yaw.rotation[2])
        if self._last_yaw is not None and dt > 0.0:
            self._yaw_rate = (yaw_angle - self._last_yaw) / dt
        self._last_yaw = yaw_angle
        findings = ()
        iterations = 0
        solved = False
        problem = self._problem(vehicle, yaw.rotation[2], preview)
        if problem is not None:
            result = self.solver.solve(*problem)
            iterations = result.iterations
            if result.solved:
                solved = True
                self._plan = result.x.reshape(self.horizon, DOF)
                self._plan_time = 0.0
                self._input = self._plan[0].copy()
        if not solved:
            self._input, reason = self._fallback()
            findings = (Finding(MPC_FALLBACK, f'the MPC found no plan ({reason}): '
                                + ('the rest of the last plan applied' if reason.endswith('plan')
                                   else 'braking the cue to rest')),)
        self.last_solved = solved
        x = self.state
        tilt = x[TILT].copy()
        rotation = np.array([0.0, 0.0, yaw.rotation[2]])
        angles = rotation.copy()
        angles[:2] += tilt
        return MpcStep(
            displacement=x[POSITION].copy(), velocity=x[VELOCITY].copy(),
            acceleration=self._input[:3].copy(), tilt=tilt, tilt_rate=x[TILT_RATE].copy(),
            tilt_target=(self._plan[-1, 3:5].copy() if self._plan is not None else tilt),
            rotation=rotation, angles=angles, findings=findings, solved=solved,
            iterations=iterations)

    def _discretised(self, dt):
        quanta = max(1, round(dt / TIME_QUANTUM))
        pair = self._cache.get(quanta)
        if pair is None:
            if len(self._cache) >= _CACHE_SIZE:
                self._cache.clear()
            pair = self._cache[quanta] = discretised(self._a, self._b, quanta * TIME_QUANTUM)
        return pair

    def leg_jacobian(self, yaw: float):
        """
        Return ``(lengths, L)`` at the current cue: leg lengths (6,) and ``dl/dq`` (6, 6).

        ``q = [x, y, z, roll, pitch, yaw]`` of the cue (head displacement and angles): the leg
        Jacobian rows of :func:`~stewart_kinematics.model.jacobians.jacobian` at the cue's
        pose times the derivative of the pose in ``q`` (central differences of
        :meth:`~.cue_limiter.CueLimiter.cue_poses`, exact to about 1e-10).
        """
        q = np.concatenate([self.state[POSITION], self.state[TILT], [yaw]])
        steps = np.eye(6) * _DIFFERENCE_STEP
        around = np.concatenate([q[None, :], q + steps, q - steps])
        poses = self.limiter.cue_poses(around[:, :3], around[:, 3:])
        pose_of_q = (poses[1:7] - poses[7:13]).T / (2.0 * _DIFFERENCE_STEP)
        lengths = inverse_kinematics(self.limiter.geometry, poses[0])
        return lengths, jacobian(self.limiter.geometry, poses[0]) @ pose_of_q

    def _problem(self, vehicle, yaw, preview=None):
        """
        Return the QP ``(g, A, lower, upper, bounds_lower, bounds_upper)``, or ``None``.

        ``None`` when the cue's pose has no finite leg lengths (linearisation impossible).
        """
        n = self.horizon
        x0 = self.state
        reference = self._psi @ self._vehicle.state
        if preview is None:
            reference += self._upsilon @ vehicle
        else:
            to_come = np.array(preview, dtype=float)
            to_come[:, 2] -= self.gravity   # relative to rest, as the bank takes it
            reference += self._upsilon_preview @ to_come.ravel()
        free = self._phi_z @ x0
        error = free.copy()
        error.reshape(n, OUTPUTS)[:, 0:5] -= reference.reshape(n, 5)
        gradient = self._gradient_of_z @ error
        lengths, legs = self.leg_jacobian(yaw)
        if not (np.all(np.isfinite(lengths)) and np.all(np.isfinite(legs))):
            return None
        jac, yaw_column = legs[:, :DOF], legs[:, DOF]
        free = free.reshape(n, OUTPUTS)
        q0 = np.concatenate([x0[POSITION], x0[TILT]])
        # Leg lengths: l_k = l_0 + L (q_k - q_0).
        stroke = np.einsum('ij,kjm->kim', jac, self._gamma_q).reshape(6 * n, DOF * n)
        stroke_free = (lengths + (free[:, 5:10] - q0) @ jac.T).ravel()
        # Leg velocities: L q'_k plus the yaw's (held).
        speed = np.einsum('ij,kjm->kim', jac, self._gamma_rate).reshape(6 * n, DOF * n)
        speed_free = (free[:, 10:15] @ jac.T + yaw_column * self._yaw_rate).ravel()
        # Leg accelerations: L u_k.
        acceleration = np.kron(np.eye(n), jac)
        tilt_rate = self._gamma_rate[:, 3:5].reshape(2 * n, DOF * n)
        box = self._gamma_q.reshape(DOF * n, DOF * n)
        perceived_rate = self._gamma_z[self._perceived_rate_rows].reshape(2 * n, DOF * n)
        rest = self._gamma_rate[-1]
        # Hard rows first (leg accelerations: inputs only; the tilt rate; rest at the end),
        # then the soft ones (leg lengths and velocities, the box: the linearisation may put
        # the state itself outside them; the perceived roll and pitch rate).
        a = np.vstack([acceleration, tilt_rate, rest, stroke, speed, box, perceived_rate])
        v, acc, rate = self._velocity_max, self._acceleration_max, self._tilt_rate_max
        tilt_max = self.settings.tilt_max
        box_low = np.maximum(self._box[0], [-math.inf] * 3 + [-tilt_max] * 2)
        box_high = np.minimum(self._box[1], [math.inf] * 3 + [tilt_max] * 2)
        lower = np.concatenate([
            np.full(6 * n, -acc), -rate - free[:, 13:15].ravel(), -free[-1, 10:15],
            self._length_min - stroke_free, -v - speed_free, (box_low - free[:, 5:10]).ravel(),
            -rate - free[:, 3:5].ravel()])
        upper = np.concatenate([
            np.full(6 * n, acc), rate - free[:, 13:15].ravel(), -free[-1, 10:15],
            self._length_max - stroke_free, v - speed_free, (box_high - free[:, 5:10]).ravel(),
            rate - free[:, 3:5].ravel()])
        return (gradient, a, lower, upper) + self._input_bounds

    def _fallback(self):
        """
        Return ``(input, reason)`` when the QP failed: the last plan's next input, or braking.

        Braking: each degree of freedom's rate to zero over the next sample (as long as the last
        one), scaled so that no leg's acceleration passes its limit (the linearised legs) and
        the tilt's acceleration stays within ``tilt_acceleration_max``.
        """
        if self._plan is not None:
            index = int(self._plan_time // self.step_time)
            if index < self.horizon:
                return self._plan[index].copy(), 'solver failed; the last plan'
        rates = np.concatenate([self.state[VELOCITY], self.state[TILT_RATE]])
        wanted = -rates / self._last_dt
        try:
            _, legs = self.leg_jacobian(0.0)
            leg_acceleration = np.max(np.abs(legs[:, :DOF] @ wanted))
        except ValueError:
            leg_acceleration = math.inf
        scale = 1.0
        if leg_acceleration > self._acceleration_max:
            scale = self._acceleration_max / leg_acceleration
        tilt_acceleration = float(np.max(np.abs(wanted[3:5])))
        if tilt_acceleration > self.settings.tilt_acceleration_max:
            scale = min(scale, self.settings.tilt_acceleration_max / tilt_acceleration)
        if not math.isfinite(scale):
            scale = 0.0
        return wanted * scale, 'solver failed; braking'
