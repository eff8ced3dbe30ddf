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
Figures of a ramp run: the paper's Figures 5, 7 and 9, and the round-trip error, as PNG files.

Uses matplotlib without a display (the Agg backend); imported only when figures are wanted.
"""

from pathlib import Path

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

POSE_LABELS = (('X', 'Y', 'Z'), ('alpha', 'beta', 'gamma'))


def write_figures(directory, times, input_poses, lengths, estimated_poses,
                  position_errors, orientation_errors):
    """
    Write four PNG figures of a ramp run and return their paths.

    :param directory: folder to write to, created if missing.
    :param times: seconds from the first row, shape (N,).
    :param input_poses: poses sent, ``[X, Y, Z, alpha, beta, gamma]`` (m, rad), shape (N, 6).
    :param lengths: leg lengths received, metres, shape (N, 6).
    :param estimated_poses: poses from forward kinematics, shape (N, 6).
    :param position_errors: round-trip position errors, metres, shape (N,).
    :param orientation_errors: round-trip orientation errors, radians, shape (N,).
    :returns: paths of input_pose.png, leg_lengths.png, fk_pose.png, round_trip_error.png.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    paths = [
        _pose_figure(directory / 'input_pose.png', times, input_poses,
                     'Input pose to inverse kinematics (paper Fig. 5)'),
        _lengths_figure(directory / 'leg_lengths.png', times, lengths),
        _pose_figure(directory / 'fk_pose.png', times, estimated_poses,
                     'Pose from forward kinematics (paper Fig. 9)'),
        _error_figure(directory / 'round_trip_error.png', times, position_errors,
                      orientation_errors),
    ]
    return paths


def _pose_figure(path, times, poses, title):
    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    for axis, label in enumerate(POSE_LABELS[0]):
        top.plot(times, poses[:, axis] * 1e3, marker='o', label=label)
    for axis, label in enumerate(POSE_LABELS[1]):
        bottom.plot(times, np.degrees(poses[:, 3 + axis]), marker='o', label=label)
    top.set_ylabel('position [mm]')
    bottom.set_ylabel('orientation [deg]')
    bottom.set_xlabel('time [s]')
    return _finish(figure, (top, bottom), title, path)


def _lengths_figure(path, times, lengths):
    figure, axes = plt.subplots(figsize=(8, 5))
    for leg in range(6):
        axes.plot(times, lengths[:, leg] * 1e3, marker='o', label=f'leg {leg + 1}')
    axes.set_ylabel('leg length [mm]')
    axes.set_xlabel('time [s]')
    return _finish(figure, (axes,),
                   'Leg lengths from inverse kinematics (paper Fig. 7)', path)


def _error_figure(path, times, position_errors, orientation_errors):
    figure, axes = plt.subplots(figsize=(8, 5))
    # Exact zeros (the home pose) cannot be drawn on a log scale: show them at the floor.
    floor = 1e-17
    axes.semilogy(times, np.maximum(position_errors, floor), marker='o', label='position [m]')
    axes.semilogy(times, np.maximum(orientation_errors, floor), marker='s',
                  label='orientation [rad]')
    axes.axhline(1e-9, color='red', linestyle='--', label='required (1e-9)')
    axes.axhline(1e-4, color='grey', linestyle=':', label="paper's tolerance (1e-4)")
    axes.set_ylabel('round-trip error (0 drawn at 1e-17)')
    axes.set_xlabel('time [s]')
    return _finish(figure, (axes,), 'Round-trip error: FK(IK(pose)) - pose', path)


def _finish(figure, axes_list, title, path):
    for axes in axes_list:
        axes.grid(True, alpha=0.3)
        axes.legend(loc='best', fontsize='small')
    figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path


def calibration_figure(path, result):
    """
    Write a PNG of a calibration's residuals per leg, before and after, and return its path.

    Top: RMS and worst residual of each leg (inlier poses) for the nominal and the calibrated
    model, on a log scale. Bottom: every calibrated residual by pose, outlier poses marked.

    :param path: the PNG file to write.
    :param result: a :class:`stewart_kinematics.analysis.calibration.CalibrationResult`.
    """
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7))
    legs = np.arange(1, 7)
    width = 0.2
    for shift, values, label, color in (
            (-1.5, result.rms_before, 'RMS, nominal', 'tab:red'),
            (-0.5, result.worst_before, 'worst, nominal', 'salmon'),
            (0.5, result.rms_after, 'RMS, calibrated', 'tab:blue'),
            (1.5, result.worst_after, 'worst, calibrated', 'lightblue')):
        top.bar(legs + shift * width, values * 1e6, width, label=label, color=color)
    top.set_yscale('log')
    top.set_xticks(legs, [f'leg {leg}' for leg in legs])
    top.set_ylabel('|predicted - measured| [um]')
    top.set_title(f'Actuator position residuals, {int(result.inliers.sum())} poses '
                  f'({len(result.outliers)} outliers set aside)')
    poses = np.arange(result.inliers.size)
    for leg in range(6):
        bottom.plot(poses[result.inliers], result.residuals_after[result.inliers, leg] * 1e6,
                    '.', label=f'leg {leg + 1}')
    if result.outliers:
        outliers = np.array(result.outliers)
        limit = 4.0 * np.max(np.abs(result.residuals_after[result.inliers])) * 1e6
        worst = np.max(np.abs(result.residuals_after[outliers]), axis=1) * 1e6
        bottom.plot(outliers, np.minimum(worst, limit), 'kx', markersize=9,
                    label='outlier (worst leg, clipped)')
        for index, value in zip(outliers, worst):
            bottom.annotate(f' {value:.0f} um', (index, min(value, limit)), fontsize='small',
                            va='center')
    bottom.set_xlabel('pose')
    bottom.set_ylabel('calibrated residual [um]')
    return _finish(figure, (top, bottom), 'Calibration: nominal against calibrated model', path)
