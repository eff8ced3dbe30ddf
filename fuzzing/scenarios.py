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
Generators of the inputs issue 27's second adversarial pass found defects with.

Random messages rarely make the few cases that matter: these draw them on purpose, from the
platform's own geometry and limits, for the node fuzzer (:mod:`fuzzing.node_scenarios`) and
the soak (``benchmarks/soak.py``).

- :func:`bulging_trajectory`: a ``pose_trajectory`` of two or three waypoints, each within the
  stroke, whose given velocities make the Hermite piece between them bulge beyond it (or
  just inside it), in a piece shorter than one period of a low ``validation_rate`` (1 to 5
  Hz, :data:`LOW_VALIDATION_RATES`), and slow enough to keep the leg velocity and acceleration
  limits: only the points between the waypoints break a limit, and a check on the
  ``validation_rate`` grid does not see them (it saw waypoints only, and trajectory_node sent
  leg lengths of 0.785 m where the stroke ends at 0.75 m).
- :class:`ImuStream`: ``vehicle_imu`` samples a node accepts (finite, below
  ``max_specific_force`` and ``max_angular_velocity``) but as noisy as a vibrating vehicle:
  specific force noise of about 30 m/s^2 around gravity, rotation noise of about 5 rad/s; and
  stamps that run ten times as fast as they are sent (a recording played fast). The cue
  follower once held a pose and stopped legs moving at 0.0245 m/s within one 10 ms step
  (2.45 m/s^2, ten times leg_acceleration_max) on such input, and paced a fast recording by its
  stamps, ten times faster than the legs may move.
"""

from dataclasses import dataclass
import math
import random
from typing import Optional, Sequence, Tuple

from builtin_interfaces.msg import Duration
from geometry_msgs.msg import Transform as TransformMessage, Twist
import numpy as np
from sensor_msgs.msg import Imu
from std_msgs.msg import Header

from stewart_kinematics.model.frames import Transform
from stewart_kinematics.model.inverse import leg_vectors
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, matrix_to_quaternion
from stewart_kinematics.motion.pose_trajectory import PoseTrajectory
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

#: The low validation rates a bulging trajectory is made for, hertz (the parameter's lowest).
LOW_VALIDATION_RATES = (1.0, 5.0)
#: Samples per second at which a generator looks for a piece's extreme leg lengths and rates.
PROBE_RATE = 2000.0
#: Share of the leg velocity and acceleration limits a bulging trajectory uses at most.
RATE_SHARE = 0.85
#: A bulge beyond the stroke passes it by this share of its height, drawn (a bulge inside
#: stays this share of its height away from it).
BULGE_SHARES = (0.2, 0.8)
#: Metres the waypoints are moved at most along the bulge to place its top.
PLACEMENT_RANGE = 0.3
#: Steps of the bisection that places the bulge's top (to PLACEMENT_RANGE / 2^steps).
PLACEMENT_STEPS = 30
#: Noise of a noisy IMU sample, as the adversarial pass drew it: specific force (m/s^2, around
#: gravity) and angular velocity (rad/s), standard deviations of each axis' normal draw; each
#: vector is kept below this share of the node's bound (so that it is accepted).
FORCE_NOISE = 30.0
RATE_NOISE = 5.0
BOUND_SHARE = 0.95
#: How much faster than they are sent the stamps of a fast recording run.
FAST_FACTOR = 10.0


@dataclass(frozen=True)
class BulgeCase:
    """
    What :func:`bulging_trajectory` drew.

    :param validation_rate: the validation rate it is made for, hertz.
    :param times: the waypoints' times, seconds.
    :param speed: the tool frame's speed at a moving waypoint, m/s.
    :param peak_excess: how far the extreme leg length between the waypoints passes the stroke,
        metres (negative: inside it by that much), by sampling at :data:`PROBE_RATE`.
    :param waypoint_excess: the same at the waypoints (negative: inside).
    :param beyond: whether the bulge was made to pass the stroke.
    """

    validation_rate: float
    times: Tuple[float, ...]
    speed: float
    peak_excess: float
    waypoint_excess: float
    beyond: bool

    def describe(self) -> str:
        """Return the case in words."""
        return (f'{len(self.times)} waypoints over {self.times[-1]:.3f} s at {self.speed:.4f} '
                f'm/s for validation_rate {self.validation_rate:.2f} Hz: its legs pass the '
                f'stroke by {self.peak_excess * 1e3:+.3f} mm between the waypoints '
                f'({self.waypoint_excess * 1e3:+.3f} mm at them)')


class _Piece:
    """The waypoints of a bulging trajectory, moved as one along ``direction``."""

    def __init__(self, geometry, frames, times, base, rotation, direction, pattern,
                 with_accelerations):
        self.geometry, self.frames = geometry, frames
        self.times = np.asarray(times, dtype=float)
        self.base, self.rotation, self.direction = base, rotation, direction
        self.pattern = np.asarray(pattern, dtype=float)
        self.with_accelerations = with_accelerations
        self.probe = np.linspace(0.0, self.times[-1], int(self.times[-1] * PROBE_RATE) + 2)

    def tool_motion(self, offset, speed):
        """Return the tool frame's waypoints: positions, rotations, velocities, accelerations."""
        count = len(self.times)
        positions = np.tile(self.base + offset * self.direction, (count, 1))
        rotations = np.tile(self.rotation, (count, 1, 1))
        velocities = speed * self.pattern[:, None] * self.direction
        accelerations = np.zeros((count, 3)) if self.with_accelerations else None
        return positions, rotations, velocities, accelerations

    def legs(self, offset, speed):
        """Return the leg lengths at the probe times and at the waypoints, metres."""
        positions, rotations, velocities, accelerations = self.tool_motion(offset, speed)
        zeros = np.zeros_like(velocities)
        motion = self.frames.platform_motion(
            positions, rotations, velocities, zeros, accelerations,
            None if accelerations is None else zeros)
        trajectory = PoseTrajectory(self.times, *motion)
        samples = trajectory.sample(self.probe)
        lengths = np.linalg.norm(leg_vectors(self.geometry, samples.positions,
                                             samples.rotations), axis=-1)
        waypoints = np.linalg.norm(leg_vectors(self.geometry, motion[0], motion[1]), axis=-1)
        return lengths, waypoints

    def excess(self, lengths) -> float:
        """
        Return how far leg lengths pass the stroke's end the bulge points to, metres.

        Negative: inside by that much. Up, the longest leg against ``leg_length_max``; down,
        the shortest against ``leg_length_min``.
        """
        geometry = self.geometry
        if self.direction[2] > 0.0:
            return float(np.max(lengths) - geometry.limits.leg_length_max)
        return float(geometry.limits.leg_length_min - np.min(lengths))

    def place(self, speed, share) -> float:
        """
        Return the offset at which the bulge passes the stroke by ``share`` of its height.

        The height: the extreme leg length between the waypoints minus that at them, at the
        home pose. Found by bisection over ``[0, PLACEMENT_RANGE]`` metres.

        :raises ValueError: if no offset in that range reaches the target.
        """
        lengths, waypoints = self.legs(0.0, speed)
        target = share * (self.excess(lengths) - self.excess(waypoints))
        low, high = 0.0, PLACEMENT_RANGE
        if self.excess(self.legs(high, speed)[0]) < target:
            raise ValueError('no placement of the waypoints reaches the end of the stroke')
        for _ in range(PLACEMENT_STEPS):
            middle = 0.5 * (low + high)
            if self.excess(self.legs(middle, speed)[0]) < target:
                low = middle
            else:
                high = middle
        return low

    def rates(self, offset, speed):
        """Return the largest leg velocity and acceleration along the piece, m/s and m/s^2."""
        lengths, _ = self.legs(offset, speed)
        step = self.probe[1] - self.probe[0]
        velocities = np.diff(lengths, axis=0) / step
        accelerations = np.diff(velocities, axis=0) / step
        return float(np.max(np.abs(velocities))), float(np.max(np.abs(accelerations)))


def bulging_trajectory(rng: random.Random, geometry, actuator_limits, frames,
                       validation_rate: Optional[float] = None, beyond: Optional[bool] = None,
                       frame_id: str = '') -> Tuple[MultiDOFJointTrajectory, BulgeCase]:
    """
    Draw a trajectory whose waypoints keep the stroke and whose Hermite piece may not.

    Two or three waypoints at one pose of the tool frame (at its home orientation), moved
    together along a direction (up or down, a little sideways) so that the piece's extreme leg
    length passes the stroke's end by a drawn share of the bulge's height (or stays inside by
    that much). Given velocities along that direction (at the start, at both ends, or through
    the middle waypoint; with zero accelerations now and then, a quintic) make the bulge. The
    whole trajectory lasts less than one period of ``validation_rate``, and its speed keeps
    :data:`RATE_SHARE` of the leg velocity and acceleration limits all along.

    :param geometry: the platform and its stroke.
    :param actuator_limits: leg velocity and acceleration limits (finite).
    :param frames: the node's frame tree (its tool frame, as trajectory_node reads a
        waypoint).
    :param validation_rate: hertz (default: drawn from :data:`LOW_VALIDATION_RATES`).
    :param beyond: whether the bulge passes the stroke (default: drawn, one in two).
    :param frame_id: the message's frame (the base frame).
    :returns: ``(message, case)``.
    :raises ValueError: if no placement reaches the stroke's end (a stroke beyond reach).
    """
    if validation_rate is None:
        validation_rate = rng.uniform(*LOW_VALIDATION_RATES)
    if beyond is None:
        beyond = rng.random() < 0.5
    count = rng.choice((2, 3))
    period = 1.0 / validation_rate
    duration = rng.uniform(0.5, 0.95) * period
    times = np.linspace(0.0, duration, count)
    patterns = ([(1.0, 0.0), (1.0, -1.0), (0.0, -1.0)] if count == 2
                else [(0.0, 1.0, 0.0), (1.0, 0.0, -1.0), (1.0, 1.0, 0.0)])
    pattern = rng.choice(patterns)
    up = rng.random() < 0.75
    direction = np.array([rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), 1.0 if up else -1.0])
    direction /= np.linalg.norm(direction)
    home = geometry.home_pose
    tool = frames.tool_from_platform(Transform(np.array(home[:3], dtype=float),
                                               euler_zyx_to_matrix(np.array(home[3:]))))
    piece = _Piece(geometry, frames, times, np.array(tool.position, dtype=float),
                   np.array(tool.rotation, dtype=float), direction, pattern,
                   rng.random() < 0.3)
    # The speed: linear in the rates for a small motion, so one probe gives it; then the top
    # of the bulge is placed by bisection, and both again at the placed pose (the legs'
    # curvature changes the rates a little, and the rates the bulge).
    speed, offset = 1.0, 0.0
    target = rng.uniform(*BULGE_SHARES) * (1.0 if beyond else -1.0)
    for _ in range(3):
        for _ in range(2):
            velocity, acceleration = piece.rates(offset, speed)
            speed *= RATE_SHARE * min(actuator_limits.velocity_max / velocity,
                                      actuator_limits.acceleration_max / acceleration)
        offset = piece.place(speed, target)
    lengths, waypoints = piece.legs(offset, speed)
    case = BulgeCase(validation_rate, tuple(times.tolist()), speed, piece.excess(lengths),
                     piece.excess(waypoints), beyond)
    return trajectory_message(piece.tool_motion(offset, speed), times, frame_id), case


def trajectory_message(motion, times: Sequence[float], frame_id: str) -> MultiDOFJointTrajectory:
    """
    Build the pose_trajectory message of the tool frame's waypoints.

    :param motion: ``(positions (N, 3), rotations (N, 3, 3), velocities (N, 3),
        accelerations (N, 3) or None)``; angular rates zero.
    :param times: seconds, (N,).
    """
    positions, rotations, velocities, accelerations = motion
    points = []
    for index, time in enumerate(times):
        transform = TransformMessage()
        transform.translation.x, transform.translation.y, transform.translation.z = (
            float(value) for value in positions[index])
        quaternion = matrix_to_quaternion(rotations[index])
        (transform.rotation.x, transform.rotation.y, transform.rotation.z,
         transform.rotation.w) = (float(value) for value in quaternion)
        twist = Twist()
        twist.linear.x, twist.linear.y, twist.linear.z = (float(v) for v in velocities[index])
        nanoseconds = int(round(time * 1e9))
        point = MultiDOFJointTrajectoryPoint(
            transforms=[transform], velocities=[twist],
            accelerations=[] if accelerations is None else [Twist()],
            time_from_start=Duration(sec=nanoseconds // 1_000_000_000,
                                     nanosec=nanoseconds % 1_000_000_000))
        points.append(point)
    return MultiDOFJointTrajectory(header=Header(frame_id=frame_id), points=points)


class ImuStream:
    """
    ``vehicle_imu`` samples a node accepts: a noisy vehicle, or a smooth recording.

    ``noise``: the specific force is gravity plus a normal draw of :data:`FORCE_NOISE` m/s^2 on
    each axis, the angular velocity a normal draw of :data:`RATE_NOISE` rad/s on each axis;
    ``recording``: a drive's smooth motion (a few m/s^2 and tenths of a rad/s, sums of sines of
    0.2 to 2 Hz of the sample's stamp), to be stamped :data:`FAST_FACTOR` times as fast as it
    is sent. A draw whose magnitude would reach :data:`BOUND_SHARE` of ``max_specific_force`` or
    ``max_angular_velocity`` is drawn again: every sample is valid, none is refused.

    :param rng: the run's random generator.
    :param kind: ``'noise'`` or ``'recording'``.
    :param max_specific_force: the node's bound, m/s^2; ``max_angular_velocity``, rad/s.
    :param gravity: m/s^2.
    """

    def __init__(self, rng: random.Random, kind: str, max_specific_force: float,
                 max_angular_velocity: float, gravity: float = 9.81):
        if kind not in ('noise', 'recording'):
            raise ValueError(f"kind must be 'noise' or 'recording', got {kind!r}")
        self.rng, self.kind, self.gravity = rng, kind, gravity
        self.force_bound = BOUND_SHARE * max_specific_force
        self.rate_bound = BOUND_SHARE * max_angular_velocity
        #: The recording's sines: (amplitude, angular frequency, phase) per axis, two each.
        self.waves = [[(rng.uniform(0.5, amplitude), rng.uniform(0.4, 4.0) * math.pi,
                        rng.uniform(0.0, 2.0 * math.pi)) for _ in range(2)]
                      for amplitude in (3.0, 3.0, 1.0, 0.2, 0.2, 0.3)]

    def sample(self, seconds: float) -> Tuple[np.ndarray, np.ndarray]:
        """Return ``(specific force (3,), angular velocity (3,))`` at a stamp, seconds."""
        if self.kind == 'recording':
            values = [sum(amplitude * math.sin(frequency * seconds + phase)
                          for amplitude, frequency, phase in waves) for waves in self.waves]
            force = np.array(values[:3]) + [0.0, 0.0, self.gravity]
            return force, np.array(values[3:])
        rng = self.rng
        while True:
            force = np.array([rng.gauss(0.0, FORCE_NOISE) for _ in range(3)])
            force[2] += self.gravity
            if np.linalg.norm(force) < self.force_bound:
                break
        while True:
            rate = np.array([rng.gauss(0.0, RATE_NOISE) for _ in range(3)])
            if np.linalg.norm(rate) < self.rate_bound:
                return force, rate

    def message(self, stamp_ns: int, frame_id: str = ''):
        """Return a sensor_msgs/msg/Imu of the sample at ``stamp_ns`` (its stamp)."""
        force, rate = self.sample(stamp_ns * 1e-9)
        message = Imu()
        stamp = message.header.stamp
        stamp.sec, stamp.nanosec = divmod(int(stamp_ns), 1_000_000_000)
        message.header.frame_id = frame_id
        message.orientation.w = 1.0
        vector = message.linear_acceleration
        vector.x, vector.y, vector.z = (float(value) for value in force)
        vector = message.angular_velocity
        vector.x, vector.y, vector.z = (float(value) for value in rate)
        return message
