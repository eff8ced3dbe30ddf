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
The four test drives of the motion cueing, generated: specific force and angular velocity.

Each :class:`Scenario` samples what an IMU at the driver's head reads (vehicle frame: x
forward, y left, z up; specific force ``[0, 0, g]`` at rest) at ``rate`` hertz, and says when
the input comes to rest for good (``rest_time``), after which the platform must return to
neutral. Every scenario starts and ends at rest, with smooth (raised-cosine) onsets.

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

Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Tuple

import numpy as np

from stewart_kinematics.cueing.settings import STANDARD_GRAVITY

#: The scenarios' names, in the order of the documentation's table.
SCENARIO_NAMES = ('acceleration_braking', 'slalom', 'multi_sine', 'lap')
#: Default sampling rate, hertz (a game's or a vehicle model's telemetry).
DEFAULT_RATE = 100.0
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
    if not (math.isfinite(rate) and rate > 0.0):
        raise ValueError(f'rate must be a positive number of hertz, got {rate!r}')
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


def scenario(name: str, rate: float = DEFAULT_RATE) -> Scenario:
    """
    Return the scenario named ``name`` sampled at ``rate`` hertz.

    :raises ValueError: for an unknown name or a rate that is not positive.
    """
    makers = {'acceleration_braking': acceleration_braking, 'slalom': slalom,
              'multi_sine': multi_sine, 'lap': lap}
    if name not in makers:
        raise ValueError(f'unknown scenario {name!r}; known: {", ".join(SCENARIO_NAMES)}')
    return makers[name](rate)


def all_scenarios(rate: float = DEFAULT_RATE) -> Tuple[Scenario, ...]:
    """Return the four scenarios, in :data:`SCENARIO_NAMES` order."""
    return tuple(scenario(name, rate) for name in SCENARIO_NAMES)
