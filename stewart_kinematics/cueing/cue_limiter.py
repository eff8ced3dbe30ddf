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
From the washout's cue to a platform pose that keeps every limit, scaled back smoothly.

Two stages, each reported in the result:

1. **Workspace scale** ``sigma`` in [0, 1]: the cue (the head's displacement and the rotation
   angles) is scaled toward neutral until its pose keeps every limit of the limits model drawn
   in by the margins (:func:`~.limit_margins.with_margins`). ``sigma`` falls at once when it must
   and rises again no faster than ``workspace_recovery_rate``; the search runs only when the
   cue would leave the narrowed limits.
2. **Follower**: the platform follows the scaled cue's pose within the actuators' leg velocity
   and acceleration limits. Each step asks for the change of the pose velocity that would keep
   it on the cue (feed-forward of the cue's own motion, plus a critically damped correction at
   ``follower_frequency`` when it has fallen behind), and takes the largest fraction
   ``lambda`` in [0, 1] of that change for which every leg keeps ``|v| <= leg_velocity_max``,
   ``|dv / dt| <= leg_acceleration_max`` and can still brake to rest inside its stroke
   (``v dt + v^2 / (2 a) <= distance to the end``). The legs' velocities are nearly affine in
   ``lambda`` over one step, so ``lambda`` comes from two inverse kinematics and is verified on
   the exact leg lengths. A cue within the limits is followed exactly (``lambda = 1``, the pose
   equals the cue's); a cue too fast for the actuators is followed as closely as they allow,
   never with a jump and never frozen.

The output pose is judged by the limits model (:mod:`.limit_margins`): when it equals the cue's
pose, that pose already passed the narrower limits; otherwise it is checked again. When no next
pose keeps every limit, the legs brake at their limits (``command_braking``), never one step to
rest; at rest, the platform stays. Nothing here imports ROS.

``dt`` is the time between two commands as they are sent (the node's clock), not the input's:
the legs' rates are those the actuators see.

Leg forces: the command gate judges each pose sent with its motion's forces (with masses and a
force limit). When it refuses one for them, :class:`~.motion_cueing.MotionCueing` takes the
step again from the same state (:meth:`CueLimiter.state`, :meth:`CueLimiter.restore`) with a
smaller :attr:`CueLimiter.force_scale`: the follower then plans with that share of the leg
acceleration limit (gentler changes of motion, hence smaller inertial forces), and the share
grows back with time (:meth:`CueLimiter.recover_force_scale`).
"""

import dataclasses
from dataclasses import dataclass
import math
from typing import Tuple

import numpy as np

from stewart_kinematics.cueing.limit_margins import limit_margins, pose_violations, with_margins
from stewart_kinematics.dynamics.inverse_dynamics import leg_forces, masses_of
from stewart_kinematics.findings import ACTUATOR_LIMITED, COMMAND_BRAKING, CUE_SCALED, Finding
from stewart_kinematics.limits import limits_of
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.model.jacobians import twist_jacobian
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, matrix_to_euler_zyx

#: Share of the actuator limits the follower plans with; the rest absorbs the legs'
#: nonlinearity over one step (verified on the exact lengths).
PLANNING_SHARE = 0.98
#: The workspace scale is located to this (a share of the cue), or to a pose this close to the
#: boundary (metres, radians), within this many evaluations.
SCALE_TOLERANCE = 1e-9
SCALE_MARGIN_TOLERANCE = 1e-7
SCALE_ITERATIONS = 40
#: The first bracket reaches at least this far below the last step's share.
SCALE_WINDOW = 0.01
#: The follower counts as on the cue when every pose coordinate is within this.
ON_CUE_TOLERANCE = 1e-12
#: Shares of the longest braking time at which a pose off the narrowed limits is checked to
#: still keep the limits while the legs brake (a joint cone may peak before the stop).
BRAKING_CHECKS = (0.25, 0.5, 0.75, 1.0)
#: The follower's acceleration share after leg force refusals: halved per retry down to this,
#: doubling back every FORCE_SCALE_RECOVERY seconds of commands passed.
FORCE_SCALE_MIN = 1.0 / 16.0
#: With masses, the cue keeps its static leg forces this share of the room between the home
#: pose's and the force limits inside them: headroom for the forces of its motion (and of
#: braking it), which the command gate checks on every pose sent.
FORCE_HEADROOM = 0.5
FORCE_SCALE_RECOVERY = 0.5
#: What a step changes: :meth:`CueLimiter.state` keeps it, :meth:`CueLimiter.restore` puts it
#: back (each step replaces these values, never changes them in place).
_STEP_STATE = ('pose', 'velocity', 'lengths', 'leg_velocities', 'scale', 'tilt_scale',
               '_target', '_target_velocity', '_last_dt')


@dataclass(frozen=True)
class LimitedPose:
    """
    One step of :class:`CueLimiter`.

    :param pose: the platform pose to command, ``[X, Y, Z, alpha, beta, gamma]``, base frame,
        metres and radians, shape (6,); ``None`` when no pose could be found (the command gate
        then brakes from the last command).
    :param target: the scaled cue's pose, shape (6,).
    :param lengths: the leg lengths of ``pose``, metres, shape (6,), or ``None``.
    :param workspace_scale: ``sigma``, the share of the displacement and of the rotational
        channel kept to stay inside the limits.
    :param tilt_scale: the share of the tilt kept (below 1 only when the tilt alone would
        leave the limits).
    :param acceleration_scale: ``lambda``, the share of the wanted change of velocity the
        actuators allowed (1: the cue's motion was followed as asked).
    :param on_cue: whether ``pose`` equals ``target``.
    :param findings: warnings: the cue scaled, the actuators limiting, a pose held.
    """

    pose: np.ndarray
    target: np.ndarray
    lengths: np.ndarray
    workspace_scale: float
    tilt_scale: float
    acceleration_scale: float
    on_cue: bool
    findings: Tuple[Finding, ...] = ()


class CueLimiter:
    """
    Turn cues into platform poses within the limits model and the actuator limits.

    :param geometry: the platform, with its limits.
    :param actuator_limits: leg velocity and acceleration limits (``inf``: none).
    :param head_position: the cueing reference point in the platform frame, metres, (3,).
    :param settings: a :class:`~stewart_kinematics.cueing.CueingSettings` (margins, follower
        bandwidth, recovery rate).
    :raises ValueError: if the margins leave no room around the home pose.
    """

    def __init__(self, geometry, actuator_limits: ActuatorLimits, settings):
        self.geometry = geometry
        self.actuator_limits = actuator_limits
        self.settings = settings
        velocity_max = actuator_limits.velocity_max
        acceleration_max = actuator_limits.acceleration_max
        braking = (velocity_max ** 2 / (2.0 * acceleration_max)
                   if math.isfinite(velocity_max) and math.isfinite(acceleration_max) else 0.0)
        #: The narrowed limits the cue keeps; the stroke margin covers the braking distance.
        self.leg_length_margin = max(settings.leg_length_margin, braking)
        self.cue_geometry = _with_force_headroom(with_margins(
            geometry, self.leg_length_margin, settings.joint_angle_margin,
            settings.condition_margin))
        #: The limits a stopping pose is checked against: all but the stroke.
        self._stop_geometry = _with_force_headroom(dataclasses.replace(
            geometry, limits=limits_of(geometry).replace(leg_length_min=0.0,
                                                         leg_length_max=math.inf)))
        #: Inside these limits (the margins twice over) a pose can stop inside the limits for
        #: sure; beyond them, where it stops is computed (:meth:`_keeps_limits`): a joint cone
        #: may change by more than its margin while the legs brake.
        try:
            self._safe_geometry = _with_force_headroom(with_margins(
                geometry, 2.0 * self.leg_length_margin, 2.0 * settings.joint_angle_margin,
                max(2.0 * settings.condition_margin - 1.0, 1e-3)))
        except ValueError:   # no room for twice the margins: always compute where it stops
            self._safe_geometry = None
        self.limits_speed = actuator_limits.limits_speed
        self._velocity_plan = PLANNING_SHARE * velocity_max
        self._acceleration_plan = PLANNING_SHARE * acceleration_max
        #: The share of the acceleration planned with (below 1 after leg force refusals).
        self.force_scale = 1.0
        home = np.array(geometry.home_pose, dtype=float)
        self.home_pose = home
        self.home_rotation = euler_zyx_to_matrix(home[3:])
        self._home_is_level = bool(np.all(home[3:] == 0.0))
        self.head_position = np.array(settings.head_position, dtype=float)
        self._follower_weights = np.array(settings.follower_weights, dtype=float)
        self.head_home = home[:3] + self.home_rotation @ self.head_position
        self.home_lengths = inverse_kinematics(geometry, home)
        self.reset()

    def reset(self) -> None:
        """Put the platform at rest at the home pose, with the full cue allowed."""
        self.pose = self.home_pose.copy()
        self.velocity = np.zeros(6)
        self.lengths = self.home_lengths.copy()
        self.leg_velocities = np.zeros(6)
        self.scale = self.tilt_scale = 1.0
        self._target = self.home_pose.copy()
        self._target_velocity = np.zeros(6)
        self._last_dt = None
        self.set_force_scale(1.0)

    def set_force_scale(self, scale: float) -> None:
        """Plan with ``scale`` (in (0, 1]) of the leg acceleration limit from the next step."""
        self.force_scale = scale
        self._acceleration_plan = (PLANNING_SHARE * self.actuator_limits.acceleration_max
                                   * scale)

    def recover_force_scale(self, dt: float) -> None:
        """Let the acceleration share grow back toward 1 after ``dt`` seconds passed."""
        if self.force_scale < 1.0:
            self.set_force_scale(min(1.0, self.force_scale * 2.0 ** (dt / FORCE_SCALE_RECOVERY)))

    def state(self) -> dict:
        """Return what a :meth:`step` changes, to take the step again (:meth:`restore`)."""
        return {name: getattr(self, name) for name in _STEP_STATE}

    def restore(self, state: dict) -> None:
        """Put back a :meth:`state`: the limiter as it was before the step taken since."""
        for name, value in state.items():
            setattr(self, name, value)

    def cue_poses(self, displacement, angles) -> np.ndarray:
        """
        Platform poses of cues: the head displaced by ``d`` and the platform turned about it.

        :param displacement: the head's displacement, base frame, metres, (3,) or (N, 3).
        :param angles: roll, pitch, yaw of the cue, radians, (3,) or (N, 3).
        :returns: ``[X, Y, Z, alpha, beta, gamma]`` of the platform frame, (6,) or (N, 6):
            rotation ``R = R_cue R_home``, position ``head_home + d - R head_position``.
        """
        displacement = np.asarray(displacement, dtype=float)
        angles = np.asarray(angles, dtype=float)
        rotation = euler_zyx_to_matrix(angles)
        if not self._home_is_level:
            rotation = rotation @ self.home_rotation
            angles = matrix_to_euler_zyx(rotation)
        position = self.head_home + displacement - rotation @ self.head_position
        return np.concatenate([position, angles], axis=-1)

    def _scaled_target(self, displacement, rotation, tilt, dt):
        """
        Return ``(sigma, sigma_tilt, pose)``: the largest allowed shares of the cue.

        The displacement and the rotational channel are scaled first (``sigma``), the tilt
        only when the tilt alone leaves the narrowed limits (``sigma_tilt``): the tilt's rate
        limit then holds whatever ``sigma`` does. Both fall at once when they must and rise no
        faster than ``workspace_recovery_rate``.
        """
        recovery = self.settings.workspace_recovery_rate * dt
        ceiling = min(1.0, self.scale + recovery)
        tilt_ceiling = min(1.0, self.tilt_scale + recovery)
        tilt = np.array([tilt[0], tilt[1], 0.0])

        def poses(shares, tilt_shares):
            shares, tilt_shares = np.atleast_1d(shares)[:, None], np.atleast_1d(tilt_shares)
            return self.cue_poses(shares * displacement,
                                  shares * rotation + tilt_shares[:, None] * tilt)

        if self.scale == 1.0 and self.tilt_scale == 1.0:
            # Off the boundary last time: one check usually settles it.
            pose = self.cue_poses(displacement, rotation + tilt)
            if not pose_violations(self.cue_geometry, pose[:3], euler_zyx_to_matrix(pose[3:])):
                return ceiling, tilt_ceiling, pose
        found = _largest_allowed(self.cue_geometry, lambda shares: poses(shares, tilt_ceiling),
                                 ceiling, self.scale)
        if found is not None:
            return found[0], tilt_ceiling, found[1]
        tilt_share, pose = _largest_allowed(self.cue_geometry, lambda shares: poses(
            np.zeros_like(shares), shares), tilt_ceiling, self.tilt_scale, home_allowed=True)
        return 0.0, tilt_share, pose

    def step(self, displacement, rotation, tilt, dt: float) -> LimitedPose:
        """
        Advance the platform by ``dt`` seconds toward the cue.

        :param displacement: the head's displacement from neutral, base frame, metres, (3,).
        :param rotation: the rotational channel's roll, pitch, yaw, radians, (3,).
        :param tilt: the tilt channel's roll and pitch, radians, (2,).
        :param dt: seconds since the previous step, > 0.
        """
        findings = []
        scale, tilt_scale, target = self._scaled_target(
            np.asarray(displacement, dtype=float), np.asarray(rotation, dtype=float),
            np.asarray(tilt, dtype=float), dt)
        if min(scale, tilt_scale) < 1.0:
            findings.append(Finding(
                CUE_SCALED, f'cue scaled to {scale:.3f} of itself (tilt {tilt_scale:.3f}) to '
                'keep inside the limits', (('workspace_scale', f'{scale:.6g}'),
                                           ('tilt_scale', f'{tilt_scale:.6g}'))))
        target_velocity = (target - self._target) / dt
        gain = min(self.settings.follower_frequency, 0.5 / dt)
        # The change of the pose velocity that keeps the platform on the cue: the cue's own
        # change, plus a critically damped pull back onto it when it has fallen behind.
        wanted = (target_velocity - self._target_velocity + dt * (
            gain * gain * (self._target - self.pose)
            + 2.0 * gain * (self._target_velocity - self.velocity)))
        followed = self._follow(self.pose + dt * (self.velocity + wanted), dt)
        on_cue = followed is not None and bool(
            np.all(np.abs(followed[1] - target) <= ON_CUE_TOLERANCE))
        if followed is None or not on_cue and not self._keeps_limits(followed[1], followed[2],
                                                                     dt):
            followed = self._retreat(dt, findings)
        share, pose, lengths = followed
        if share < 1.0:
            findings.append(Finding(
                ACTUATOR_LIMITED, f'the cue asks more than the legs can do; followed at '
                f'{share:.3f} of the change asked', (('acceleration_scale', f'{share:.6g}'),)))
        if pose is not None:   # None: no pose found, the command gate brakes instead
            self._commit(pose, lengths, dt)
        self.scale, self.tilt_scale = scale, tilt_scale
        self._target, self._target_velocity = target, target_velocity
        return LimitedPose(pose=pose, target=target, lengths=lengths, workspace_scale=scale,
                           tilt_scale=tilt_scale, acceleration_scale=share, on_cue=on_cue,
                           findings=tuple(findings))

    def _commit(self, pose, lengths, dt) -> None:
        """Make ``pose`` (its ``lengths``), ``dt`` after the last one, the platform's."""
        self.leg_velocities = (lengths - self.lengths) / dt
        self.velocity = (pose - self.pose) / dt
        self.pose, self.lengths = np.array(pose, dtype=float), np.array(lengths, dtype=float)
        self._last_dt = dt

    def take_sent(self, pose, lengths, dt, previous) -> None:
        """
        Follow on from what was sent instead of the last step (the gate braked instead).

        :param pose: the pose sent, shape (6,); ``lengths`` its leg lengths.
        :param dt: seconds since the command before it.
        :param previous: ``(pose, lengths)`` of the command before it.
        """
        self.pose, self.lengths = (np.array(value, dtype=float) for value in previous)
        self._commit(pose, lengths, dt)

    def _leg_bounds(self, dt, stroke=True):
        """
        Return the per-leg bounds ``(lower, upper)`` on the next leg velocity.

        Speed, acceleration, and (``stroke``) the braking curve that keeps each leg able to
        stop inside its stroke.
        """
        span = dt if self._last_dt is None else min(dt, 0.5 * (dt + self._last_dt))
        acceleration = self._acceleration_plan
        change = acceleration * span
        speed = self._velocity_plan
        limits = limits_of(self.geometry)
        # Read once: a setting is a lookup in the limits' table, which six legs would repeat.
        longest, shortest = limits.leg_length_max, limits.leg_length_min
        stroke = stroke and math.isfinite(acceleration)
        lower, upper = [], []
        for length, velocity in zip(self.lengths.tolist(), self.leg_velocities.tolist()):
            low = max(-speed, velocity - change)
            high = min(speed, velocity + change)
            if stroke:
                # v dt + v^2 / (2 a) <= room: one step, then braking at the planned rate.
                if math.isfinite(longest):
                    room = max(longest - length, 0.0)
                    high = max(low, min(high, acceleration * (
                        -dt + math.sqrt(dt * dt + 2.0 * room / acceleration))))
                if shortest > 0.0:
                    room = max(length - shortest, 0.0)
                    low = min(high, max(low, -acceleration * (
                        -dt + math.sqrt(dt * dt + 2.0 * room / acceleration))))
            lower.append(low)
            upper.append(high)
        return lower, upper

    def _follow(self, wanted_pose, dt):
        """
        Return ``(share, pose, lengths)``: ``wanted_pose``, or the nearest the legs allow.

        When the leg velocities that reach ``wanted_pose`` break a leg's bounds
        (:meth:`_leg_bounds`), the next leg velocities are those within every bound whose
        motion differs least from the wanted one: a least-squares problem in the platform's
        twist, each axis weighted by ``follower_weights`` (:meth:`_twist_metric`), through the
        legs' twist Jacobian, with box constraints on each leg
        (:func:`box_least_squares`). The pose is then the forward kinematics of those lengths,
        started at the wanted pose. ``share`` is 1 minus the part of the wanted change of
        motion that the legs could not follow (in that metric).
        """
        lengths = inverse_kinematics(self.geometry, wanted_pose)
        if not self.limits_speed:
            return 1.0, wanted_pose, lengths
        if not np.all(np.isfinite(lengths)):
            return None
        wanted = (lengths - self.lengths) / dt
        lower, upper = self._leg_bounds(dt)
        if all(low <= value <= high for value, low, high in zip(wanted.tolist(), lower, upper)):
            return 1.0, wanted_pose, lengths
        metric = self._twist_metric()
        velocities = box_least_squares(metric, wanted, np.array(lower), np.array(upper))
        asked = wanted - self.leg_velocities
        missed = velocities - wanted
        asked_size = float(asked @ metric @ asked)
        share = (max(0.0, 1.0 - math.sqrt(float(missed @ metric @ missed) / asked_size))
                 if asked_size > 0.0 else 0.0)
        return self._pose_of(self.lengths + dt * velocities, wanted_pose, min(share, 1.0 - 1e-12))

    def _twist_metric(self) -> np.ndarray:
        """
        Return ``J^-T W J^-1`` at the current pose, ``J`` the twist Jacobian.

        A change of the leg velocities ``dv`` moves the platform by the twist ``J^-1 dv``
        (m/s along x, y, z, rad/s about them); its weighted squared size is
        ``dv^T J^-T W J^-1 dv``, ``W = diag(follower_weights)``: with weights all 1, metres and
        radians alike (a degree of rotation costs as much as 17 mm).
        """
        inverse = np.linalg.inv(twist_jacobian(self.geometry, self.pose[:3],
                                               euler_zyx_to_matrix(self.pose[3:])))
        return inverse.T @ (self._follower_weights[:, None] * inverse)

    def _brake(self, dt, guess):
        """
        Slow the legs down as fast as their bounds allow; return ``(0, pose, lengths)``.

        Each leg on its own, as near to rest as its bounds allow (speed, acceleration, stroke
        braking curve): the braking :meth:`_keeps_limits` foresees, as the command gate brakes.
        ``None`` when the pose of those lengths cannot be found.
        """
        lower, upper = self._leg_bounds(dt)
        velocities = np.clip(np.zeros(6), lower, upper)
        return self._pose_of(self.lengths + dt * velocities, guess, 0.0)

    def _pose_of(self, lengths, guess, share):
        """
        Return ``(share, pose, lengths)`` for leg lengths, by forward kinematics, or ``None``.

        From ``guess``, then from the platform's pose (``None`` when neither converges: the
        caller brakes; staying where the platform is would stop it in one step).
        """
        for start in (guess, self.pose):
            result = forward_kinematics(self.geometry, lengths, initial_guess=start)
            if result.converged:
                return share, np.asarray(result.pose, dtype=float), lengths
        return None

    def _keeps_limits(self, pose, lengths, dt) -> bool:
        """
        Whether ``pose`` and the poses the platform passes while it brakes keep the limits.

        A pose inside the limits narrowed by twice the margins passes at once. Otherwise the
        legs brake from it, each on its own at the planned acceleration to rest (as the command
        gate brakes them), and the poses at each quarter of that braking must keep the limits
        too (the stroke is kept leg by leg by the braking curves): a joint cone can move by
        more than its margin while the legs brake (seen: 2.3 deg at full speed). A platform
        already outside a limit (after braking that could not stay inside) may only come
        back: no limit broken further than the current pose breaks it.
        """
        rotation = euler_zyx_to_matrix(pose[3:])
        if self._safe_geometry is not None and not pose_violations(
                self._safe_geometry, pose[:3], rotation):
            return True
        if not self._no_further_out(pose_violations(self.geometry, pose[:3], rotation)):
            return False
        acceleration = self._acceleration_plan
        velocities = (np.asarray(lengths) - self.lengths) / dt
        if not math.isfinite(acceleration) or not np.any(velocities):
            return True
        # Where the legs are at each quarter of the longest braking, each leg braking on its own
        # at the planned rate to rest: a joint cone may peak before the stop.
        duration = float(np.max(np.abs(velocities))) / acceleration
        guess = pose
        for share in BRAKING_CHECKS:
            elapsed = np.minimum(share * duration, np.abs(velocities) / acceleration)
            on_the_way = lengths + velocities * elapsed - 0.5 * np.sign(velocities) * (
                acceleration * elapsed * elapsed)
            found = self._pose_of(on_the_way, guess, 0.0)
            if found is None:
                return False
            guess = found[1]
            if not self._no_further_out(pose_violations(
                    self._stop_geometry, guess[:3], euler_zyx_to_matrix(guess[3:]))):
                return False
        return True

    def _no_further_out(self, violations) -> bool:
        """Whether ``violations`` break no limit further than the platform's pose now does."""
        if not violations:
            return True
        now = {(violation.limit, violation.leg, violation.other_leg): violation.excess
               for violation in pose_violations(self.geometry, self.pose[:3],
                                                euler_zyx_to_matrix(self.pose[3:]))}
        return all(violation.excess <= now.get(
            (violation.limit, violation.leg, violation.other_leg), -1.0)
            for violation in violations)

    def _retreat(self, dt, findings):
        """
        Return the next pose when following the cue would leave the limits: brake, or go home.

        A moving platform brakes each leg as hard as it may; one at rest moves toward the
        home pose (always inside the limits) with the follower's dynamics. If neither keeps
        the limits, a moving platform brakes all the same (``command_braking``: no command
        within every limit exists; never a stop in one step) and one at rest stays.
        """
        moving = bool(np.any(self.leg_velocities != 0.0))
        braking = None
        if moving and self.limits_speed:
            braking = self._brake(dt, self.pose + dt * self.velocity)
        gain = min(self.settings.follower_frequency, 0.5 / dt)
        homeward = dt * (gain * gain * (self.home_pose - self.pose) - 2.0 * gain * self.velocity)
        candidates = [candidate for candidate in (
            braking, self._follow(self.pose + dt * (self.velocity + homeward), dt))
            if candidate is not None]
        for _, pose, lengths in candidates:
            if self._keeps_limits(pose, lengths, dt):
                findings.append(Finding(ACTUATOR_LIMITED, 'following the cue would have left the '
                                        'limits: braking or heading home instead'))
                return 0.0, pose, lengths
        for _, pose, lengths in candidates:
            # Too late to stop inside by the estimate, but this pose is inside: keep braking.
            if not pose_violations(self.geometry, pose[:3], euler_zyx_to_matrix(pose[3:])):
                findings.append(Finding(ACTUATOR_LIMITED, 'braking hard: the platform may not '
                                        'stop inside the cue margins'))
                return 0.0, pose, lengths
        if braking is not None:
            findings.append(Finding(COMMAND_BRAKING, 'every next pose would leave the limits: '
                                    'braking at the leg limits all the same'))
            return braking
        if moving and self.limits_speed:
            # The braking pose cannot be found: the command gate brakes from the last command.
            findings.append(Finding(COMMAND_BRAKING, 'every next pose would leave the limits, '
                                    'and the pose of a braking command cannot be found'))
            return 0.0, None, None
        findings.append(Finding(ACTUATOR_LIMITED, 'every next pose would leave the limits: the '
                                'platform rests where it is'))
        return 0.0, self.pose.copy(), self.lengths.copy()


def _with_force_headroom(geometry):
    """
    Return ``geometry`` with its force limits drawn in by :data:`FORCE_HEADROOM`.

    Unchanged without masses or without a force limit.
    """
    limits = limits_of(geometry)
    low, high = limits.leg_force_min, limits.leg_force_max
    masses = masses_of(geometry)
    if masses.massless or not (math.isfinite(low) or math.isfinite(high)):
        return geometry
    home = leg_forces(geometry, geometry.home_pose, mass_properties=masses)
    changes = {}
    if math.isfinite(high):
        changes['leg_force_max'] = high - FORCE_HEADROOM * max(high - float(home.max()), 0.0)
    if math.isfinite(low):
        changes['leg_force_min'] = low + FORCE_HEADROOM * max(float(home.min()) - low, 0.0)
    return dataclasses.replace(geometry, limits=limits.replace(**changes))


def box_least_squares(metric, target, lower, upper, max_iterations=30):
    """
    Minimise ``(x - target)^T metric (x - target)`` subject to ``lower <= x <= upper``.

    A primal active-set method for a small positive-definite ``metric``: solve with the free
    coordinates, fix those that leave their box at the bound they cross, release a fixed one
    whose gradient says it would rather move inside, until the Karush-Kuhn-Tucker conditions
    hold (Nocedal and Wright, *Numerical Optimization*, 2nd ed., section 16.5).

    :param metric: shape (n, n), symmetric positive definite.
    :param target: shape (n,).
    :param lower: shape (n,), ``lower <= upper``.
    :param upper: shape (n,).
    :returns: shape (n,), within the box (the clipped target if the iterations run out).
    """
    x = np.clip(target, lower, upper)
    fixed = (x != target)
    for _ in range(max_iterations):
        free = ~fixed
        if np.any(free):
            # Free coordinates minimise with the fixed ones held: Q_ff dx_f = -Q_fb dx_b.
            offset = x - target
            x[free] = target[free] - np.linalg.solve(
                metric[np.ix_(free, free)], metric[np.ix_(free, fixed)] @ offset[fixed])
        outside = free & ((x < lower) | (x > upper))
        if np.any(outside):
            x = np.clip(x, lower, upper)
            fixed |= outside
            continue
        gradient = metric @ (x - target)
        # At its lower bound a coordinate may stay if the objective wants it lower (g >= 0).
        wrong = fixed & (((x <= lower) & (gradient < 0.0)) | ((x >= upper) & (gradient > 0.0)))
        if not np.any(wrong):
            return x
        worst = int(np.argmax(np.where(wrong, np.abs(gradient), -1.0)))
        fixed[worst] = False
    return np.clip(x, lower, upper)


def _largest_allowed(geometry, make_poses, high, previous=0.0, home_allowed=False):
    """
    Return the largest share in [0, ``high``) whose pose keeps the limits.

    To :data:`SCALE_TOLERANCE`, or to a pose within :data:`SCALE_MARGIN_TOLERANCE` of the
    boundary.

    Regula falsi with the Illinois modification (Dahlquist and Bjorck, *Numerical Methods*,
    section 6.2) on the continuous :func:`~.limit_margins.limit_margins`. The first evaluation
    (one call) tries ``previous`` (the last step's share), a little below it, and ``high``: on
    a boundary that moves slowly, as it does, the bracket is then narrow and two or three more
    evaluations suffice; else it widens down to 0. The share found moves smoothly as the cue
    does, so the scaled cue does not jitter on the boundary.

    :param make_poses: shares (N,) -> poses (N, 6).
    :param previous: the last step's share.
    :param home_allowed: whether share 0 is known to be allowed (the home pose).
    :returns: ``(share, pose)`` on the allowed side, or ``None`` when share 0 breaks a limit.
    """
    previous = min(max(previous, 0.0), high)
    below = max(0.0, previous - max(SCALE_WINDOW, 2.0 * (high - previous)))
    shares = np.array([below, previous, high])
    poses = make_poses(shares)
    margins = limit_margins(geometry, poses)
    if below == 0.0 and home_allowed:
        margins[0] = min(margins[0], -1e-12)
    if not margins[2] >= 0.0:  # allowed after all (the single check was stricter): keep it
        return high, poses[2]
    if margins[1] < 0.0:
        low, low_margin, low_pose = previous, float(margins[1]), poses[1]
        high_margin = float(margins[2])
    elif margins[0] < 0.0:
        low, low_margin, low_pose = below, float(margins[0]), poses[0]
        high, high_margin = previous, float(margins[1])
    elif below == 0.0:
        return None
    else:
        return _largest_allowed(geometry, make_poses, below, 0.0, home_allowed)
    side = 0
    for _ in range(SCALE_ITERATIONS):
        if high - low <= SCALE_TOLERANCE or -SCALE_MARGIN_TOLERANCE < low_margin:
            break
        share = (high - high_margin * (high - low) / (high_margin - low_margin)
                 if math.isfinite(high_margin) and math.isfinite(low_margin)
                 else 0.5 * (low + high))
        share = min(max(share, low + 1e-3 * (high - low)), high - 1e-3 * (high - low))
        pose = make_poses(np.array([share]))
        margin = float(limit_margins(geometry, pose)[0])
        if margin < 0.0:
            low, low_margin, low_pose = share, margin, pose[0]
            if side == -1:
                high_margin *= 0.5
            side = -1
        else:
            high, high_margin = share, margin
            if side == 1:
                low_margin *= 0.5
            side = 1
    return low, low_pose
