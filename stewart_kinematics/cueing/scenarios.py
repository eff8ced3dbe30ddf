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
The nine test drives of the motion cueing, generated: specific force and angular velocity.

Each :class:`Scenario` samples what an IMU at the driver's head reads (vehicle frame: x
forward, y left, z up; specific force ``[0, 0, g]`` at rest) at ``rate`` hertz, and says when
the input comes to rest for good (``rest_time``), after which the platform must return to
neutral. Every scenario starts and ends at rest, with smooth (raised-cosine) onsets, except
where a step is the point (``brake_step``'s end).

- ``acceleration_braking``: a sustained 3 m/s^2 acceleration for 4 s, coasting, then braking
  at 6 m/s^2 to a stop.
- ``slalom``: at 15 m/s between cones 30 m apart: lateral acceleration of 4 m/s^2 peak at
  0.25 Hz, the yaw rate that goes with it, four periods.
- ``multi_sine``: 0.5, 1 and 2 Hz sines of 0.5 m/s^2 each, longitudinal and lateral (other
  phases), 20 s, tapered in and out.
- ``lap``: a recorded-looking lap: a point-mass vehicle drives a track of straights and
  corners (curvature smoothed over 15 m, as clothoids would) as fast as 8 m/s^2 of lateral,
  3 m/s^2 of forward and 7 m/s^2 of braking acceleration allow, from standstill to
  standstill; the body's roll and pitch follow the accelerations, and a seeded road noise
  (0.15 m/s^2 RMS, 0.05 rad/s RMS, low-passed at about 8 Hz) is added.
- ``brake_step``: from 15 m/s, braking at 6 m/s^2 (a 0.3 s raised-cosine onset) to
  standstill, where the force ends in a step (from -6 m/s^2 to 0 in one sample: the car has
  stopped). The felt-at-rest case: anything still felt after the stop is a false cue.
- ``lane_change``: at 25 m/s, one full sine period of lateral acceleration, 0.4 g
  (3.92 m/s^2) peak at 0.5 Hz (2 s: left, then right, about 2.5 m aside), with the yaw rate
  ``a_y / v`` that goes with it; the 4 s manoeuvre judged is the sine and the 2 s after it.
- ``coordinated_turn``: an aircraft at 100 m/s rolls into a 30 deg bank in 3 s (raised
  cosine bank angle: roll rate up to 15.7 deg/s), turns for 10 s, rolls out in 3 s. The
  turn is coordinated: the specific force stays along the body z (``g / cos(bank)``, 1.15 g),
  with no lateral force in the vehicle frame; the body rates are the roll rate and the turn
  rate ``g tan(bank) / V`` resolved in the body (pitch ``sin(bank)``, yaw ``cos(bank)``).
- ``mixed_drive``: 60 s of driving from standstill to standstill, seeded: a launch at
  3 m/s^2, then accelerations (1.5 to 3 m/s^2), braking (3 to 6 m/s^2), corners (3 to 6 m/s^2
  lateral, 2 to 5 s) and lane changes (one sine period of 2 to 4 m/s^2 at 0.3 to 0.6 Hz) in a
  random order and strength, 0.5 to 2 s apart (speed kept within 5 to 30 m/s), and a final
  stop at no more than 4 m/s^2; yaw rate ``a_y / v``, the body's roll and pitch following the
  accelerations (0.5 deg per m/s^2 lateral, 0.4 per m/s^2 forward), and road noise (0.1 m/s^2
  RMS, 0.5 to 8 Hz). Peaks about 6 m/s^2 forward and lateral.
- ``bumpy_road``: 20 s at a steady 15 m/s over a rough road: band-passed road noise (about 1
  to 10 Hz) of 0.5 m/s^2 RMS in heave and 0.03 rad/s RMS in pitch rate, plus five bumps at
  seeded times: each wheel rises over one 4 Hz period of 6 m/s^2 vertical acceleration, the
  rear wheels 2.7 m (0.18 s) after the front; the head takes their mean (3.0 m/s^2 peak of a
  bump alone) and the pitch rate their difference over the wheelbase (10.1 deg/s peak); with
  the noise, about 4.1 m/s^2 and 13.9 deg/s. No force along x or y, no roll or yaw.

Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Tuple

import numpy as np

from stewart_kinematics.cueing.settings import STANDARD_GRAVITY

#: The scenarios' names, in the order of the documentation's table.
SCENARIO_NAMES = ('acceleration_braking', 'slalom', 'multi_sine', 'lap', 'brake_step',
                  'lane_change', 'coordinated_turn', 'mixed_drive', 'bumpy_road')
#: Default sampling rate, hertz (a game's or a vehicle model's telemetry).
DEFAULT_RATE = 100.0
#: Largest sampling rate, hertz (``stewart_cueing --rate`` allows as much).
MAX_RATE = 10000.0
#: Seconds of rest after the input comes to rest: long enough to judge the return to neutral.
REST_AFTER = 12.0
#: Frequencies of the multi-sine, hertz.
MULTI_SINE_FREQUENCIES = (0.5, 1.0, 2.0)


@dataclass(frozen=True)
class Scenario:
    """
    A generated drive, sampled.

    :param name: one of :data:`SCENARIO_NAMES`.
    :param description: one sentence.
    :param times: seconds, shape (N,), from 0.
    :param specific_force: m/s^2, vehicle frame, shape (N, 3).
    :param angular_velocity: rad/s, vehicle frame, shape (N, 3).
    :param rest_time: from this time on the input is at rest, seconds.
    """

    name: str
    description: str
    times: np.ndarray
    specific_force: np.ndarray
    angular_velocity: np.ndarray
    rest_time: float


def _smooth_step(times, start, duration):
    """0 before ``start``, 1 after ``start + duration``, a raised cosine between."""
    phase = np.clip((times - start) / duration, 0.0, 1.0)
    return 0.5 - 0.5 * np.cos(math.pi * phase)


def _pulse(times, start, hold, ramp, level):
    """``level`` from ``start + ramp`` for ``hold`` seconds, with raised-cosine ramps."""
    rise = _smooth_step(times, start, ramp)
    fall = _smooth_step(times, start + ramp + hold, ramp)
    return level * (rise - fall)


def _times(duration, rate):
    if isinstance(rate, bool) or not isinstance(rate, (int, float, np.integer, np.floating)) \
            or not (math.isfinite(rate) and 0.0 < rate <= MAX_RATE):
        raise ValueError(f'rate must be a positive number of hertz up to {MAX_RATE:g}, got '
                         f'{rate!r}')
    return np.arange(int(round(duration * rate)) + 1) / rate


def _assemble(name, description, times, forward, lateral, vertical=None, rates=None,
              rest_time=0.0, gravity=STANDARD_GRAVITY):
    force = np.zeros((times.size, 3))
    force[:, 0], force[:, 1] = forward, lateral
    force[:, 2] = gravity + (0.0 if vertical is None else vertical)
    angular = np.zeros((times.size, 3)) if rates is None else rates
    return Scenario(name, description, times, force, angular, float(rest_time))


def acceleration_braking(rate: float = DEFAULT_RATE) -> Scenario:
    """Return the sustained acceleration, coasting, then braking to a stop."""
    ramp = 0.5
    braking_start = 1.0 + 2 * ramp + 4.0 + 2.0
    # 3 m/s^2 for 4.5 s (ramps included) is 13.5 m/s; 6 m/s^2 for 2.25 s brings it to rest.
    rest_time = braking_start + 2 * ramp + 1.75
    times = _times(rest_time + REST_AFTER, rate)
    forward = (_pulse(times, 1.0, 4.0, ramp, 3.0)
               + _pulse(times, braking_start, 1.75, ramp, -6.0))
    return _assemble('acceleration_braking', 'sustained 3 m/s^2 acceleration for 4 s, coasting '
                     '2 s, braking at 6 m/s^2 to a stop', times, forward, 0.0,
                     rest_time=rest_time)


def slalom(rate: float = DEFAULT_RATE) -> Scenario:
    """Return a slalom at 15 m/s: 4 m/s^2 of lateral acceleration at 0.25 Hz, four periods."""
    speed, peak, frequency, periods, start = 15.0, 4.0, 0.25, 4, 1.0
    duration = periods / frequency
    rest_time = start + duration
    times = _times(rest_time + REST_AFTER, rate)
    window = _smooth_step(times, start, 0.5 / frequency) * (
        1.0 - _smooth_step(times, rest_time - 0.5 / frequency, 0.5 / frequency))
    lateral = peak * window * np.sin(2.0 * math.pi * frequency * (times - start))
    rates = np.zeros((times.size, 3))
    rates[:, 2] = lateral / speed
    return _assemble('slalom', 'slalom at 15 m/s between cones 30 m apart: 4 m/s^2 lateral at '
                     '0.25 Hz, four periods', times, 0.0, lateral, rates=rates,
                     rest_time=rest_time)


def multi_sine(rate: float = DEFAULT_RATE) -> Scenario:
    """Return 0.5, 1 and 2 Hz sines of 0.5 m/s^2 each, longitudinal and lateral, 20 s."""
    start, duration, taper, amplitude = 1.0, 20.0, 1.0, 0.5
    rest_time = start + duration
    times = _times(rest_time + REST_AFTER, rate)
    window = _smooth_step(times, start, taper) * (1.0 - _smooth_step(times, rest_time - taper,
                                                                     taper))
    forward = np.zeros(times.size)
    lateral = np.zeros(times.size)
    for index, frequency in enumerate(MULTI_SINE_FREQUENCIES):
        phase = 2.0 * math.pi * frequency * (times - start)
        forward += amplitude * np.sin(phase + 0.7 * index)
        lateral += amplitude * np.sin(phase + 2.1 + 1.3 * index)
    return _assemble('multi_sine', '0.5, 1 and 2 Hz sines of 0.5 m/s^2 each, longitudinal and '
                     'lateral (other phases), 20 s', times, window * forward, window * lateral,
                     rest_time=rest_time)


#: The lap's track: (length in metres, curvature in 1/m; positive turns left).
LAP_TRACK = ((80.0, 0.0), (47.1, 1 / 30.0), (120.0, 0.0), (39.3, -1 / 25.0), (60.0, 0.0),
             (78.5, 1 / 50.0), (90.0, 0.0), (31.4, 1 / 20.0), (70.0, 0.0), (62.8, -1 / 40.0),
             (100.0, 0.0))
#: The lap's vehicle: top speed m/s, lateral, forward and braking accelerations m/s^2.
LAP_LIMITS = (30.0, 8.0, 3.0, 7.0)


def _lap_profile(step=0.5):
    """Return ``(s, curvature, speed)`` along the lap, sampled every ``step`` metres."""
    lengths = np.array([length for length, _ in LAP_TRACK])
    ends = np.cumsum(lengths)
    s = np.arange(0.0, ends[-1], step)
    curvature = np.array([LAP_TRACK[int(np.searchsorted(ends, value, side='right'))][1]
                          for value in s])
    window = int(15.0 / step)
    curvature = np.convolve(np.pad(curvature, window, mode='edge'),
                            np.ones(window) / window, mode='same')[window:-window]
    top, lateral, forward, braking = LAP_LIMITS
    speed = np.minimum(top, np.sqrt(lateral / np.maximum(np.abs(curvature), 1e-9)))
    speed[0] = speed[-1] = 0.0
    for k in range(1, s.size):  # forward pass: how fast it can accelerate
        speed[k] = min(speed[k], math.sqrt(speed[k - 1] ** 2 + 2.0 * forward * step))
    for k in range(s.size - 2, -1, -1):  # backward pass: how late it can brake
        speed[k] = min(speed[k], math.sqrt(speed[k + 1] ** 2 + 2.0 * braking * step))
    return s, curvature, speed


def _moving_average(values, width):
    """Centred moving average over ``width`` samples, the ends padded with their values."""
    if width <= 1:
        return values
    padded = np.pad(values, (width // 2, width - 1 - width // 2), mode='edge')
    return np.convolve(padded, np.ones(width) / width, mode='valid')


def lap(rate: float = DEFAULT_RATE, seed: int = 23) -> Scenario:
    """Return a recorded-looking lap from standstill to standstill (see the module)."""
    s, curvature, speed = _lap_profile()
    # Time along the track: dt = ds / mean speed of each piece (the start takes off from 0).
    pieces = np.diff(s)
    mean_speed = np.maximum(0.5 * (speed[1:] + speed[:-1]), 1e-3)
    track_time = np.concatenate([[0.0], np.cumsum(pieces / mean_speed)])
    start, settle = 1.0, 0.5
    rest_time = start + track_time[-1] + settle
    times = _times(rest_time + REST_AFTER, rate)
    driving = (times >= start) & (times <= start + track_time[-1])
    v = np.interp(times - start, track_time, speed) * driving
    kappa = np.interp(times - start, track_time, curvature) * driving
    # Tyres and suspension smooth the accelerations over about 0.2 s.
    width = max(1, int(round(0.2 * rate)))
    forward = _moving_average(np.gradient(v, times), width)
    lateral = _moving_average(v * v * kappa, width)
    rng = np.random.default_rng(seed)

    def noise(rms):
        # White noise through a moving average of 1/8 s (about 8 Hz), scaled to rms.
        raw = _moving_average(rng.standard_normal(times.size), max(1, int(round(rate / 8.0))))
        return rms * raw / max(np.std(raw), 1e-12) * driving

    rates = np.zeros((times.size, 3))
    rates[:, 2] = _moving_average(v * kappa, width) + noise(0.01)
    # The body leans: 0.5 deg of roll per m/s^2 lateral, 0.4 deg of pitch per m/s^2 braking.
    rates[:, 0] = math.radians(0.5) * np.gradient(lateral, times) + noise(0.05)
    rates[:, 1] = -math.radians(0.4) * np.gradient(forward, times) + noise(0.05)
    return _assemble('lap', 'a lap of a 780 m track by a point-mass vehicle (8 m/s^2 lateral, '
                     '3 forward, 7 braking), standstill to standstill, with road noise', times,
                     forward + noise(0.15), lateral + noise(0.15), vertical=noise(0.15),
                     rates=rates, rest_time=rest_time)


def brake_step(rate: float = DEFAULT_RATE, gravity: float = STANDARD_GRAVITY) -> Scenario:
    """Return braking at 6 m/s^2 from 15 m/s to standstill, the force ending in a step."""
    start, speed, level, ramp = 1.0, 15.0, 6.0, 0.3
    # The raised-cosine onset takes off level * ramp / 2; the rest is braked at the level.
    stop = start + ramp + (speed - 0.5 * level * ramp) / level
    times = _times(stop + REST_AFTER, rate)
    forward = np.where(times < stop, -level * _smooth_step(times, start, ramp), 0.0)
    return _assemble('brake_step', 'braking at 6 m/s^2 from 15 m/s to standstill, the force '
                     'ending in a step at the stop', times, forward, 0.0, rest_time=stop,
                     gravity=gravity)


#: The lane change: speed m/s, peak lateral acceleration in g, frequency Hz.
LANE_CHANGE = (25.0, 0.4, 0.5)


def lane_change(rate: float = DEFAULT_RATE, gravity: float = STANDARD_GRAVITY) -> Scenario:
    """Return one full sine period of 0.4 g lateral acceleration at 0.5 Hz, at 25 m/s."""
    speed, peak, frequency = LANE_CHANGE
    start = 1.0
    rest_time = start + 1.0 / frequency
    times = _times(rest_time + REST_AFTER, rate)
    inside = (times >= start) & (times < rest_time)
    lateral = np.where(inside, peak * gravity * np.sin(2.0 * math.pi * frequency
                                                       * (times - start)), 0.0)
    rates = np.zeros((times.size, 3))
    rates[:, 2] = lateral / speed
    return _assemble('lane_change', 'lane change at 25 m/s: one sine period of 0.4 g lateral '
                     'acceleration at 0.5 Hz', times, 0.0, lateral, rates=rates,
                     rest_time=rest_time, gravity=gravity)


#: The coordinated turn: airspeed m/s, bank degrees, roll-in seconds, turn seconds.
COORDINATED_TURN = (100.0, 30.0, 3.0, 10.0)


def coordinated_turn(rate: float = DEFAULT_RATE,
                     gravity: float = STANDARD_GRAVITY) -> Scenario:
    """Return an aircraft's coordinated turn: roll in to 30 deg, turn 10 s, roll out."""
    speed, bank_deg, roll_time, turn_time = COORDINATED_TURN
    start = 1.0
    rest_time = start + 2.0 * roll_time + turn_time
    times = _times(rest_time + REST_AFTER, rate)
    bank = math.radians(bank_deg)
    out_start = start + roll_time + turn_time
    phi = bank * (_smooth_step(times, start, roll_time)
                  - _smooth_step(times, out_start, roll_time))

    def step_rate(begin):
        # The derivative of _smooth_step(times, begin, roll_time).
        phase = (times - begin) / roll_time
        inside = (phase > 0.0) & (phase < 1.0)
        return np.where(inside, 0.5 * math.pi / roll_time * np.sin(math.pi * phase), 0.0)

    turn_rate = gravity * np.tan(phi) / speed
    rates = np.zeros((times.size, 3))
    rates[:, 0] = bank * (step_rate(start) - step_rate(out_start))
    rates[:, 1] = turn_rate * np.sin(phi)
    rates[:, 2] = turn_rate * np.cos(phi)
    # Coordinated: the force stays along the body z, 1 / cos(bank) g; none sideways.
    vertical = gravity / np.cos(phi) - gravity
    return _assemble('coordinated_turn', 'aircraft at 100 m/s: roll into a 30 deg coordinated '
                     'turn in 3 s, turn 10 s, roll out in 3 s (no lateral force)', times, 0.0,
                     0.0, vertical=vertical, rates=rates, rest_time=rest_time, gravity=gravity)


def _band_noise(rng, times, rate, rms, low=1.0, high=10.0):
    """Return white noise band-passed by moving averages (about ``low`` to ``high`` Hz)."""
    raw = rng.standard_normal(times.size)
    smooth = _moving_average(raw, max(1, int(round(rate / high))))
    band = smooth - _moving_average(smooth, max(1, int(round(rate / low))))
    return rms * band / max(float(np.std(band)), 1e-12)


#: The mixed drive: length of the drive, s; top and lowest speed while driving, m/s.
MIXED_DRIVE = (60.0, 30.0, 5.0)


def mixed_drive(rate: float = DEFAULT_RATE, seed: int = 31,
                gravity: float = STANDARD_GRAVITY) -> Scenario:
    """Return 60 s of accelerations, corners, lane changes and braking (see the module)."""
    duration, top, lowest = MIXED_DRIVE
    start = 1.0
    rest_time = start + duration
    times = _times(rest_time + REST_AFTER, rate)
    rng = np.random.default_rng(seed)
    forward = np.zeros(times.size)
    lateral = np.zeros(times.size)
    ramp = 0.5
    # Launch: 3 m/s^2 for 4 s (ramps included 4.5 s): 13.5 m/s.
    forward += _pulse(times, start, 4.0, ramp, 3.0)
    t, v = start + 5.0, 13.5
    while True:
        kind = ('accelerate', 'brake', 'corner', 'lane_change')[int(rng.integers(4))]
        if kind == 'accelerate' and v > top - 5.0:
            kind = 'brake'
        if kind == 'brake' and v < lowest + 5.0:
            kind = 'accelerate'
        if kind == 'accelerate':
            level, hold = rng.uniform(1.5, 3.0), rng.uniform(1.0, 3.0)
            hold = min(hold, (top - v) / level - ramp)
            length, change = hold + 2.0 * ramp, level * (hold + ramp)
        elif kind == 'brake':
            level, hold = -rng.uniform(3.0, 6.0), rng.uniform(0.5, 2.0)
            hold = min(hold, (v - lowest) / -level - ramp)
            length, change = hold + 2.0 * ramp, level * (hold + ramp)
        elif kind == 'corner':
            level, hold, corner_ramp = rng.choice([-1.0, 1.0]) * rng.uniform(3.0, 6.0), \
                rng.uniform(2.0, 5.0), 1.0
            length, change = hold + 2.0 * corner_ramp, 0.0
        else:
            level, frequency = rng.choice([-1.0, 1.0]) * rng.uniform(2.0, 4.0), \
                rng.uniform(0.3, 0.6)
            length, change = 1.0 / frequency, 0.0
        pause = rng.uniform(0.5, 2.0)
        # Leave room for the final stop at no more than 4 m/s^2.
        if t + length + pause + (v + change) / 4.0 + 2.0 * ramp > rest_time:
            break
        if kind in ('accelerate', 'brake'):
            forward += _pulse(times, t, max(hold, 0.0), ramp, level)
        elif kind == 'corner':
            lateral += _pulse(times, t, hold, corner_ramp, level)
        else:
            inside = (times >= t) & (times < t + length)
            lateral += np.where(inside, level * np.sin(2.0 * math.pi * frequency * (times - t)),
                                0.0)
        t, v = t + length + pause, v + change
    # The final stop ends at rest_time: hold + 2 ramps long, taking off v.
    hold = rest_time - t - 2.0 * ramp
    forward += _pulse(times, t, hold, ramp, -v / (hold + ramp))
    driving = (times >= start) & (times < rest_time)
    steps = np.diff(times, prepend=times[0])
    speed = np.maximum(np.cumsum(forward * steps), 1.0)
    rates = np.zeros((times.size, 3))
    rates[:, 2] = lateral / speed * driving
    # The body leans: 0.5 deg of roll per m/s^2 lateral, 0.4 deg of pitch per m/s^2 braking.
    rates[:, 0] = math.radians(0.5) * np.gradient(lateral, times) * driving
    rates[:, 1] = -math.radians(0.4) * np.gradient(forward, times) * driving

    def noise(rms):
        return _band_noise(rng, times, rate, rms, low=0.5, high=8.0) * driving

    return _assemble('mixed_drive', '60 s of accelerations, corners, lane changes and braking, '
                     'standstill to standstill, seeded, with road noise', times,
                     forward + noise(0.1), lateral + noise(0.1), vertical=noise(0.1),
                     rates=rates, rest_time=rest_time, gravity=gravity)


#: The bumpy road: speed m/s, wheelbase m, bumps, a wheel's bump (peak m/s^2, Hz).
BUMPY_ROAD = (15.0, 2.7, 5, 6.0, 4.0)


def bumpy_road(rate: float = DEFAULT_RATE, seed: int = 7,
               gravity: float = STANDARD_GRAVITY) -> Scenario:
    """Return 20 s over a rough road with five bumps, in heave and pitch (see the module)."""
    speed, wheelbase, bumps, peak, frequency = BUMPY_ROAD
    start, duration, taper = 1.0, 20.0, 0.5
    rest_time = start + duration
    times = _times(rest_time + REST_AFTER, rate)
    rng = np.random.default_rng(seed)
    window = _smooth_step(times, start, taper) * (1.0 - _smooth_step(times, rest_time - taper,
                                                                     taper))
    heave = _band_noise(rng, times, rate, 0.5)
    pitch_rate = _band_noise(rng, times, rate, 0.03)
    lag = wheelbase / speed
    for hit in np.sort(rng.uniform(start + 2.0, rest_time - 2.0, size=bumps)):
        for wheel, sign in ((hit, -1.0), (hit + lag, 1.0)):
            phase = 2.0 * math.pi * frequency * (times - wheel)
            inside = (times >= wheel) & (times < wheel + 1.0 / frequency)
            # The wheel's vertical acceleration and velocity over one period of the bump.
            acceleration = np.where(inside, peak * np.sin(phase), 0.0)
            velocity = np.where(inside, peak / (2.0 * math.pi * frequency)
                                * (1.0 - np.cos(phase)), 0.0)
            heave += 0.5 * acceleration
            # Front wheel up: nose up (negative pitch rate about y left); rear: nose down.
            pitch_rate += sign * velocity / wheelbase
    rates = np.zeros((times.size, 3))
    rates[:, 1] = pitch_rate * window
    return _assemble('bumpy_road', '20 s at 15 m/s over a rough road: road noise and five '
                     'bumps in heave and pitch', times, 0.0, 0.0, vertical=heave * window,
                     rates=rates, rest_time=rest_time, gravity=gravity)


def scenario(name: str, rate: float = DEFAULT_RATE) -> Scenario:
    """
    Return the scenario named ``name`` sampled at ``rate`` hertz.

    :raises ValueError: for an unknown name or a rate that is not positive.
    """
    makers = {'acceleration_braking': acceleration_braking, 'slalom': slalom,
              'multi_sine': multi_sine, 'lap': lap, 'brake_step': brake_step,
              'lane_change': lane_change, 'coordinated_turn': coordinated_turn,
              'mixed_drive': mixed_drive, 'bumpy_road': bumpy_road}
    if name not in makers:
        raise ValueError(f'unknown scenario {name!r}; known: {", ".join(SCENARIO_NAMES)}')
    return makers[name](rate)


def all_scenarios(rate: float = DEFAULT_RATE) -> Tuple[Scenario, ...]:
    """Return every scenario, in :data:`SCENARIO_NAMES` order."""
    return tuple(scenario(name, rate) for name in SCENARIO_NAMES)
