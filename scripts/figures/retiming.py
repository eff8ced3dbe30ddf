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
Draw docs/retiming.png: the Table 3 ramp's legs against their limits, before and after retiming.

Before: the 11 rows one second apart (the ramp's timing in 'table' mode), through the
package's smooth interpolation; after: the same path retimed by toppra under
config/example_limits.yaml. Run: ``.venv/bin/python scripts/figures/retiming.py [output.png]``.
"""

from pathlib import Path
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from stewart_kinematics import (  # noqa: E402
    load_geometry, plan_motion, PoseTrajectory, Ramp)
from stewart_kinematics.parameters import (  # noqa: E402
    actuator_limits_from_settings, load_settings, TrajectoryNodeSettings)

ROOT = Path(__file__).resolve().parent.parent.parent
CONFIG = [ROOT / 'config' / 'paper_platform.yaml', ROOT / 'config' / 'example_limits.yaml']
RAMP = ROOT / 'config' / 'table3_ramp.yaml'


def write_retiming_figure(path, runs, velocity_max, acceleration_max):
    """
    Write leg velocities and accelerations against their limits, before and after retiming.

    :param path: PNG file to write; its folder is created if missing.
    :param runs: ``[(title, times (N,), velocities (N, 6), accelerations (N, 6))]``, one
        column of the figure each: seconds, m/s, m/s^2.
    :param velocity_max: leg velocity limit, m/s, drawn at plus and minus.
    :param acceleration_max: leg acceleration limit, m/s^2, likewise.
    :returns: the path.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure, axes = plt.subplots(2, len(runs), sharey='row', figsize=(5 * len(runs), 6),
                                squeeze=False)
    for column, (title, times, velocities, accelerations) in enumerate(runs):
        for row, (values, limit, label) in enumerate((
                (velocities * 1e3, velocity_max * 1e3, 'leg velocity [mm/s]'),
                (accelerations * 1e3, acceleration_max * 1e3, 'leg acceleration [mm/s^2]'))):
            plot = axes[row][column]
            for leg in range(6):
                plot.plot(times, values[:, leg], label=f'leg {leg + 1}')
            for sign in (1.0, -1.0):
                plot.axhline(sign * limit, color='red', linestyle='--',
                             label='limit' if sign > 0 else None)
            plot.set_ylabel(label)
            plot.set_xlabel('time [s]')
            plot.set_title(title if row == 0 else None)
    for row in axes:
        for plot in row:
            plot.grid(True, alpha=0.3)
    axes[0][-1].legend(loc='lower center', fontsize='small', ncol=4)
    figure.suptitle('Leg velocity and acceleration against the example limits')
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path


def main(arguments) -> int:
    """Write the figure (default docs/retiming.png) and print the two durations."""
    output = Path(arguments[0]) if arguments else ROOT / 'docs' / 'retiming.png'
    geometry = load_geometry(CONFIG)
    settings = load_settings(TrajectoryNodeSettings, CONFIG + [RAMP], 'trajectory_node')
    actuator_limits = actuator_limits_from_settings(settings.geometry)
    ramp = Ramp.from_settings(settings.ramp)
    path = PoseTrajectory.from_poses(np.arange(len(ramp.rows), dtype=float), ramp.rows)
    runs = []
    for title, retime in (('rows 1 s apart, interpolated', False), ('retimed (toppra)', True)):
        plan = plan_motion(path, geometry, actuator_limits, retime_path=retime)
        times = np.linspace(0.0, plan.trajectory.duration, 2001)
        legs = plan.trajectory.legs(geometry, times)
        runs.append((f'{title}: {plan.trajectory.duration:.2f} s', times, legs.velocities,
                     legs.accelerations))
        print(f'{title}: {plan.trajectory.duration:.3f} s')
    print(write_retiming_figure(output, runs, actuator_limits.velocity_max,
                                actuator_limits.acceleration_max))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
