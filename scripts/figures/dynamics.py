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
Draw the figures of doc/dynamics.md and print its table of travel ranges.

- docs/leg_forces_ramp.png: the six leg forces along the Table 3 ramp played in 2 s, with a
  20 kg payload 0.1 m above the platform origin (massless platform and legs): moving (solid)
  and static (dashed);
- docs/travel_ranges_payload.png: the travel ranges from home under config/example_limits.yaml,
  without masses and with that payload under the force limits :data:`FORCE_LIMITS`.

Run: ``.venv/bin/python scripts/figures/dynamics.py [output folder]``; it prints the Markdown
table of the page (test/dynamics/test_dynamics_page.py checks that the page holds it).
"""

import math
from pathlib import Path
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from stewart_kinematics import (  # noqa: E402
    leg_forces, load_geometry, MassProperties, matrix_to_euler_zyx, PoseTrajectory, Ramp,
    RigidBody, travel_ranges)
from stewart_kinematics.analysis.workspace import describe_limit  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent.parent
CONFIG = [ROOT / 'config' / 'paper_platform.yaml', ROOT / 'config' / 'example_limits.yaml']
#: The worked example's payload: 20 kg, its centre 0.1 m above the platform frame's origin.
PAYLOAD = RigidBody(20.0, [0.0, 0.0, 0.1], name='payload')
#: The actuators' force limits of the travel range comparison, newtons.
FORCE_LIMITS = {'leg_force_min': -60.0, 'leg_force_max': 120.0}
#: The ramp's duration, seconds, and the step of its samples.
DURATION = 2.0
SAMPLE_STEP = 0.01


def ramp_forces(geometry, masses):
    """
    Return ``(times (N,), static (N, 6), moving (N, 6), twists, accelerations)`` of the ramp.

    The Table 3 ramp (home to ``[0.1, 0.15, 0.5325]`` m and ``[15, -15, 20]`` degrees in ten
    steps) played in :data:`DURATION` seconds: a cubic through its 11 rows, at rest at both
    ends (``PoseTrajectory.from_poses``), sampled every :data:`SAMPLE_STEP`. Seconds, newtons,
    the twists and accelerations in the base frame (m/s, rad/s, m/s^2, rad/s^2).
    """
    ramp = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])
    path = PoseTrajectory.from_poses(np.linspace(0.0, DURATION, len(ramp.rows)), ramp.rows)
    times = np.linspace(0.0, DURATION, round(DURATION / SAMPLE_STEP) + 1)
    samples = path.sample(times)
    poses = np.hstack([samples.positions, matrix_to_euler_zyx(samples.rotations)])
    twists = np.hstack([samples.velocities, samples.angular_velocities])
    accelerations = np.hstack([samples.accelerations, samples.angular_accelerations])
    static = leg_forces(geometry, poses, mass_properties=masses)
    moving = leg_forces(geometry, poses, twists, accelerations, mass_properties=masses)
    return times, poses, static, moving, twists, accelerations


def payload_travel_ranges(geometry):
    """
    Return ``(without, with_payload)``: travel ranges from home without and with the payload.

    Without masses (the force limits are then not checked), and carrying :data:`PAYLOAD`
    under :data:`FORCE_LIMITS` and the geometry's other limits.
    """
    loaded = geometry.__class__(
        geometry.base_joints, geometry.platform_joints, geometry.home_pose,
        limits=geometry.limits.replace(**FORCE_LIMITS),
        mass_properties=MassProperties(payload=PAYLOAD))
    return travel_ranges(geometry), travel_ranges(loaded)


def markdown_table(without, with_payload) -> str:
    """Return the page's table: per axis, both ends without and with the payload, and why."""
    lines = ['| Axis | Without masses | With the 20 kg payload | Stopped by, with the payload |',
             '| --- | --- | --- | --- |']
    for before, after in zip(without.axes, with_payload.axes):
        scale, unit = (1e3, 'mm') if before.unit == 'm' else (math.degrees(1.0), 'deg')

        def ends(axis):
            return f'{axis.negative * scale:.1f} .. {axis.positive * scale:+.1f} {unit}'

        stops = (f'{describe_limit(after.negative_limit, after.negative_leg)}; '
                 f'{describe_limit(after.positive_limit, after.positive_leg)}')
        lines.append(f'| {before.axis} | {ends(before)} | {ends(after)} | {stops} |')
    return '\n'.join(lines)


def write_leg_forces_figure(path, times, static, moving):
    """
    Write the six leg forces along the ramp: moving (solid) and static (dashed), N against s.

    :param path: PNG file to write; its folder is created if missing.
    :param times: seconds, shape (N,).
    :param static: static forces, N, shape (N, 6).
    :param moving: forces with the ramp's velocities and accelerations, N, shape (N, 6).
    :returns: the path.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure, plot = plt.subplots(figsize=(8, 4.5))
    colours = plt.rcParams['axes.prop_cycle'].by_key()['color']
    for leg in range(6):
        plot.plot(times, moving[:, leg], color=colours[leg], label=f'leg {leg + 1}')
        plot.plot(times, static[:, leg], color=colours[leg], linestyle='--', linewidth=0.8)
    plot.plot([], [], color='black', linestyle='--', linewidth=0.8, label='static')
    plot.axhline(0.0, color='black', linewidth=0.5)
    plot.set_xlabel('time [s]')
    plot.set_ylabel('leg force [N] (positive: push)')
    plot.set_title('Table 3 ramp in 2 s, 20 kg payload: leg forces (dashed: static)')
    plot.grid(True, alpha=0.3)
    plot.legend(loc='lower left', fontsize='small', ncol=4)
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path


def write_travel_ranges_figure(path, without, with_payload):
    """
    Write the travel ranges without masses and with the payload, as bars from 0 each way.

    :param path: PNG file to write; its folder is created if missing.
    :param without: :class:`~stewart_kinematics.analysis.workspace.TravelRanges` without masses.
    :param with_payload: the same with the payload and the force limits.
    :returns: the path.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure, axes = plt.subplots(1, 2, figsize=(10, 4))
    for plot, first, unit, scale in ((axes[0], 0, 'mm', 1e3),
                                     (axes[1], 3, 'deg', math.degrees(1.0))):
        names = [axis.axis for axis in without.axes[first:first + 3]]
        places = np.arange(3)
        for offset, ranges, label, colour in (
                (-0.2, without, 'without masses', 'tab:blue'),
                (0.2, with_payload, '20 kg payload, forces -60..120 N', 'tab:orange')):
            values = ranges.as_array()[first:first + 3] * scale
            for side in (0, 1):
                plot.bar(places + offset, values[:, side], width=0.38, color=colour,
                         label=label if side else None)
        plot.axhline(0.0, color='black', linewidth=0.5)
        plot.set_xticks(places, names)
        plot.set_ylabel(f'travel from home [{unit}]')
        plot.grid(True, axis='y', alpha=0.3)
    figure.legend(*axes[0].get_legend_handles_labels(), loc='lower center', ncol=2,
                  fontsize='small')
    figure.suptitle('Travel ranges from home, each axis alone (example limits)')
    figure.tight_layout(rect=(0.0, 0.07, 1.0, 1.0))
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path


def main(arguments) -> int:
    """Write both figures (default into docs/) and print the page's table."""
    folder = Path(arguments[0]) if arguments else ROOT / 'docs'
    geometry = load_geometry(CONFIG)
    times, _, static, moving, _, _ = ramp_forces(geometry, MassProperties(payload=PAYLOAD))
    without, with_payload = payload_travel_ranges(geometry)
    print(markdown_table(without, with_payload))
    print(write_leg_forces_figure(folder / 'leg_forces_ramp.png', times, static, moving))
    print(write_travel_ranges_figure(folder / 'travel_ranges_payload.png', without,
                                     with_payload))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
