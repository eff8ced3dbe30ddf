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
The documentation's table and figure of every assembly mode at the end of the paper's Table 3.

``python scripts/figures/assembly_modes.py [docs/assembly_modes.png]`` prints
the table (Markdown) and draws the modes side by side, each platform with its legs and base,
as a PNG (matplotlib, Agg backend).
"""

import math
from pathlib import Path
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

from stewart_kinematics import (  # noqa: E402
    assembly_modes, inverse_kinematics, load_geometry)
from stewart_kinematics.model.rotations import euler_zyx_to_matrix  # noqa: E402

CONFIG = Path(__file__).resolve().parent.parent.parent / 'config'
#: The last row of Table 3: metres, then degrees.
TABLE_3_END = (0.1, 0.15, 0.5325, 15.0, -15.0, 20.0)


def table_3_end_modes(limits_file=True):
    """
    Every real mode of the paper's platform for the lengths at the end of Table 3.

    :param limits_file: also load config/example_limits.yaml, so that the modes say which
        limits they break.
    :returns: ``(geometry, AssemblyModes)``.
    """
    files = [CONFIG / 'paper_platform.yaml']
    if limits_file:
        files.append(CONFIG / 'example_limits.yaml')
    geometry = load_geometry(files)
    pose = np.array(TABLE_3_END[:3] + tuple(math.radians(a) for a in TABLE_3_END[3:]))
    return geometry, assembly_modes(geometry, inverse_kinematics(geometry, pose),
                                    reference_pose=pose)


def markdown_table(modes):
    """Return the modes as a Markdown table: pose, distance from the commanded pose, limits."""
    rows = ['| Mode | X [mm] | Y [mm] | Z [mm] | alpha [deg] | beta [deg] | gamma [deg] | '
            'Distance [mm] | Turned [deg] | Condition | Within example_limits.yaml |',
            '| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |']
    for index, mode in enumerate(modes.modes, start=1):
        x, y, z = mode.pose[:3] * 1000.0
        alpha, beta, gamma = np.degrees(mode.pose[3:])
        limits = 'yes' if mode.within_limits else 'no: ' + ', '.join(
            sorted({violation.limit for violation in mode.violations}))
        rows.append(
            f'| {index} | {x:.1f} | {y:.1f} | {z:.1f} | {alpha:.1f} | {beta:.1f} | '
            f'{gamma:.1f} | {mode.position_distance * 1000.0:.1f} | '
            f'{math.degrees(mode.angle_distance):.1f} | {mode.condition:.1f} | {limits} |')
    return '\n'.join(rows)


def draw(geometry, modes, path):
    """Draw the modes side by side (3D, base frame) and write the PNG to ``path``."""
    count = len(modes.modes)
    figure = plt.figure(figsize=(3.4 * count, 5.2))
    base = np.vstack([geometry.base_joints, geometry.base_joints[:1]])
    for index, mode in enumerate(modes.modes):
        axes = figure.add_subplot(1, count, index + 1, projection='3d')
        rotation = euler_zyx_to_matrix(mode.pose[3:])
        joints = mode.pose[:3] + geometry.platform_joints @ rotation.T
        ring = np.vstack([joints, joints[:1]])
        colour = 'tab:green' if mode.within_limits else 'tab:red'
        axes.plot(*base.T, color='black', linewidth=1.5)
        axes.plot(*ring.T, color=colour, linewidth=2.0)
        axes.add_collection3d(_polygon(joints, colour))
        for start, end in zip(geometry.base_joints, joints):
            axes.plot(*np.stack([start, end]).T, color='tab:blue', linewidth=1.0)
        axes.set_xlim(-0.6, 0.6)
        axes.set_ylim(-0.6, 0.6)
        axes.set_zlim(-1.2, 0.7)
        axes.set_box_aspect((1.2, 1.2, 1.9))
        axes.view_init(elev=15, azim=-60)
        axes.set_xlabel('X [m]')
        axes.set_ylabel('Y [m]')
        axes.set_zlabel('Z [m]')
        state = 'within the limits' if mode.within_limits else 'breaks the limits'
        axes.set_title(f'mode {index + 1}: Z {mode.pose[2] * 1000:.0f} mm\n'
                       f'{mode.position_distance * 1000:.0f} mm, '
                       f'{math.degrees(mode.angle_distance):.0f} deg away\n{state}',
                       fontsize=9)
    figure.suptitle('Every assembly mode of the paper platform for the leg lengths at the end '
                    'of Table 3 (mode 1: the commanded pose; red: breaks example_limits.yaml)',
                    fontsize=10, y=0.98)
    figure.subplots_adjust(left=0.02, right=0.97, bottom=0.06, top=0.82, wspace=0.15)
    figure.savefig(path, dpi=90)
    plt.close(figure)
    return path


def _polygon(points, colour):
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    return Poly3DCollection([points], alpha=0.25, facecolor=colour)


def main(argv=None):
    """Print the table and write the figure (default docs/assembly_modes.png)."""
    argv = sys.argv[1:] if argv is None else argv
    path = Path(argv[0]) if argv else CONFIG.parent / 'docs' / 'assembly_modes.png'
    geometry, modes = table_3_end_modes()
    print(markdown_table(modes))
    print(f'complete: {modes.complete}; {len(modes)} real, {modes.complex_solutions} complex, '
          f'{modes.at_infinity} beyond reach')
    print(f'wrote {draw(geometry, modes, path)}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
