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
config/example_limits.yaml. Run: ``.venv/bin/python scripts/motion_figure.py [output.png]``.
"""

from pathlib import Path
import sys

import numpy as np

from stewart_kinematics import (
    ActuatorLimits,
    load_geometry,
    plan_motion,
    PoseTrajectory,
    Ramp,
)
from stewart_kinematics.parameter_spec import read_parameter_file
from stewart_kinematics.tools.plots import write_retiming_figure

ROOT = Path(__file__).resolve().parent.parent
CONFIG = [ROOT / 'config' / 'paper_platform.yaml', ROOT / 'config' / 'example_limits.yaml']
RAMP = ROOT / 'config' / 'table3_ramp.yaml'


def main(arguments) -> int:
    """Write the figure (default docs/retiming.png) and print the two durations."""
    output = Path(arguments[0]) if arguments else ROOT / 'docs' / 'retiming.png'
    geometry = load_geometry(CONFIG)
    actuator_limits = ActuatorLimits.from_parameters(read_parameter_file(CONFIG[1]))
    ramp = Ramp.from_parameters(read_parameter_file(RAMP, 'trajectory_node'))
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
