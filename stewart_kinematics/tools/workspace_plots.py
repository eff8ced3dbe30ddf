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
Figures of the workspace: slices with their boundary, orientation workspace, dexterity maps.

PNG files in the style of :mod:`stewart_kinematics.tools.plots` (matplotlib, Agg backend);
positions in millimetres and angles in degrees. Imported only when figures are wanted.
"""

import math
from pathlib import Path

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

from stewart_kinematics.limits.kinds import pose_bounds  # noqa: E402


def write_workspace_figures(directory, slices, orientation_slices):
    """
    Write the workspace figures and return their paths.

    :param directory: folder to write to, created if missing.
    :param slices: :class:`~stewart_kinematics.analysis.workspace.WorkspaceSlice` of the XY, XZ
        and YZ planes (any number of position slices).
    :param orientation_slices: alpha-beta slices, one per gamma.
    :returns: paths of workspace_slices.png, orientation_workspace.png, dexterity.png.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    return [
        _slices_figure(directory / 'workspace_slices.png', slices,
                       'Constant-orientation workspace: boundary coloured by the limit met'),
        _slices_figure(directory / 'orientation_workspace.png', orientation_slices,
                       'Orientation workspace at the home position (alpha, beta per gamma)'),
        _dexterity_figure(directory / 'dexterity.png', slices),
    ]


def _scale(axis):
    """Return the factor and unit that show a coordinate: millimetres or degrees."""
    return (1e3, 'mm') if axis < 3 else (math.degrees(1.0), 'deg')


def _labels(result):
    (u_scale, u_unit), (v_scale, v_unit) = _scale(result.axes[0]), _scale(result.axes[1])
    u_name, v_name = result.labels
    return u_scale, v_scale, f'{u_name} [{u_unit}]', f'{v_name} [{v_unit}]'


def _title(result):
    held = [index for index in range(6) if index not in result.axes]
    names = ('X', 'Y', 'Z', 'alpha', 'beta', 'gamma')
    parts = []
    for index in held:
        scale, unit = _scale(index)
        parts.append(f'{names[index]} = {result.pose[index] * scale:.4g} {unit}')
    return ', '.join(parts)


def _slices_figure(path, slices, title):
    figure, axes_list = plt.subplots(1, len(slices), figsize=(5.2 * len(slices), 5.0),
                                     squeeze=False)
    axes_list = axes_list[0]
    for axes, result in zip(axes_list, slices):
        u_scale, v_scale, u_label, v_label = _labels(result)
        axes.contourf(result.u * u_scale, result.v * v_scale, result.allowed.astype(float),
                      levels=[0.5, 1.5], colors=['0.88'])
        # One colour and label per limit, as its kind declares them, in report order.
        for index, bound in enumerate(pose_bounds()):
            chosen = result.boundary_limit == index
            if np.any(chosen):
                axes.scatter(result.boundary[chosen, 0] * u_scale,
                             result.boundary[chosen, 1] * v_scale, s=2.0,
                             color=bound.colour, label=bound.label)
        axes.set_xlabel(u_label)
        axes.set_ylabel(v_label)
        axes.set_aspect('equal', adjustable='datalim')
        axes.set_title(f'{_plane(result)} at {_title(result)}\n'
                       f'area {_area_text(result)}', fontsize='small')
    return _finish(figure, axes_list, title, path)


def _plane(result):
    return ''.join(result.labels) if max(result.axes) < 3 else '-'.join(result.labels)


def _area_text(result):
    translations = sum(axis < 3 for axis in result.axes)
    if translations == 2:
        return f'{result.area * 1e6:.0f} mm^2'
    if translations == 0:
        return f'{result.area * math.degrees(1.0) ** 2:.0f} deg^2'
    return f'{result.area * 1e3 * math.degrees(1.0):.0f} mm deg'


def _dexterity_figure(path, slices):
    figure, axes_list = plt.subplots(1, len(slices), figsize=(5.6 * len(slices), 5.0),
                                     squeeze=False)
    axes_list = axes_list[0]
    finite = np.concatenate([result.condition[np.isfinite(result.condition)]
                             for result in slices])
    bottom = float(finite.min()) if finite.size else 1.0
    top = float(np.percentile(finite, 99.5)) if finite.size else 2.0
    for axes, result in zip(axes_list, slices):
        u_scale, v_scale, u_label, v_label = _labels(result)
        mesh = axes.pcolormesh(result.u * u_scale, result.v * v_scale, result.condition,
                               shading='nearest', cmap='viridis', vmin=bottom, vmax=top)
        axes.scatter(result.boundary[:, 0] * u_scale, result.boundary[:, 1] * v_scale,
                     s=0.5, color='black')
        axes.set_xlabel(u_label)
        axes.set_ylabel(v_label)
        axes.set_aspect('equal', adjustable='datalim')
        axes.set_title(f'{_plane(result)} at {_title(result)}', fontsize='small')
        figure.colorbar(mesh, ax=axes, shrink=0.8, label='condition number (1 is ideal)')
    return _finish(figure, axes_list,
                   'Dexterity: condition number of the dimensionless Jacobian', path,
                   legend=False)


def _finish(figure, axes_list, title, path, legend=True):
    for axes in axes_list:
        axes.grid(True, alpha=0.3)
        if legend and axes.get_legend_handles_labels()[0]:
            axes.legend(loc='best', fontsize='small', markerscale=4.0)
    figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path
