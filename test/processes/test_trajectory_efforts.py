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
Efforts on leg_trajectory across real processes: retimed under a binding force limit.

Two trajectory_node processes with the paper's platform and config/example_limits.yaml:
/massive with config/example_masses.yaml and ``leg_force_max`` 125 N (the wave below, retimed
without it, needs 144 N; its static forces stay below 117.4 N), /massless without masses. The
test publishes the same path (the motion benchmark's 100-waypoint wave) to both. From
/massive's points alone (leg lengths, velocities, accelerations) the test rebuilds each
point's pose (forward kinematics), twist (the leg velocities through the inverse Jacobian) and
acceleration (the leg accelerations less their twist's part, through the inverse Jacobian),
calls leg_forces on them, and compares with the efforts published; every effort is within
125 N. /massless publishes no efforts.
"""

import math

from geometry_msgs.msg import PoseStamped
from helpers import pose_message, Recorder
from nav_msgs.msg import Path
import numpy as np
from numpy.testing import assert_allclose
import pytest
from stewart_kinematics import forward_kinematics, leg_forces, load_geometry
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.model.velocities import leg_states, platform_twist, PoseSamples
from trajectory_msgs.msg import JointTrajectory

pytestmark = pytest.mark.process

FORCE_MAX = 125.0
POINT_RATE = 50.0
VELOCITY_MAX, ACCELERATION_MAX = 0.05, 0.25


def wave_poses(home, count=100):
    """Return the motion benchmark's wave: ``count`` poses around home, at rest at both ends."""
    u = np.linspace(0.0, 1.0, count)
    amplitudes = np.array([0.015, 0.015, 0.01, math.radians(4.0), math.radians(4.0),
                           math.radians(7.0)])
    harmonics = np.array([2, 3, 1, 2, 3, 1])
    return home + amplitudes * (1.0 - np.cos(np.outer(u, harmonics) * math.pi))


def path_message(poses):
    """nav_msgs/Path through the poses, without timing."""
    message = Path()
    message.header.frame_id = 'stewart_base'
    message.poses = [PoseStamped(pose=pose_message(pose)) for pose in poses]
    return message


def points_of(message):
    """Return lengths, velocities, accelerations, efforts of a JointTrajectory's points."""
    return tuple(np.array([getattr(point, field) for point in message.points])
                 for field in ('positions', 'velocities', 'accelerations', 'effort'))


def rebuilt_forces(geometry, lengths, velocities, accelerations):
    """Leg forces of points rebuilt from their leg states alone (see the module docstring)."""
    forces, guess = [], geometry.home_pose
    for length, velocity, acceleration in zip(lengths, velocities, accelerations):
        result = forward_kinematics(geometry, length, guess)
        assert result.converged, result.reason
        pose = np.array(result.pose)
        guess = pose
        twist = platform_twist(geometry, pose, velocity)
        sample = PoseSamples(pose[None, :3], euler_zyx_to_matrix(pose[3:])[None], twist[None, :3],
                             twist[None, 3:], np.zeros((1, 3)), np.zeros((1, 3)))
        quadratic = leg_states(geometry, sample).accelerations[0]
        platform_acceleration = platform_twist(geometry, pose, acceleration - quadratic)
        forces.append(leg_forces(geometry, pose, twist, platform_acceleration))
    return np.array(forces)


def test_retimed_efforts_within_the_force_limit_and_equal_to_the_dynamics(
        client, start_node, config_directory):
    """/massive: efforts within 125 N, equal to the rebuilt forces; /massless: no efforts."""
    files = [config_directory / name for name in ('paper_platform.yaml', 'example_limits.yaml')]
    masses = config_directory / 'example_masses.yaml'
    geometry = load_geometry(files + [masses])
    common = ['-p', "mode:='off'", '-p', f'publish_rate:={POINT_RATE}']
    arguments = {
        'massive': ['--ros-args', '--params-file', str(files[0]), '--params-file', str(files[1]),
                    '--params-file', str(masses), '-r', '__ns:=/massive', *common,
                    '-p', f'leg_force_max:={FORCE_MAX}'],
        'massless': ['--ros-args', '--params-file', str(files[0]), '--params-file',
                     str(files[1]), '-r', '__ns:=/massless', *common,
                     '-p', f'leg_force_max:={FORCE_MAX}']}
    nodes = [start_node('trajectory_node', arguments[name]) for name in arguments]
    recorder = Recorder(client, nodes)
    for name in arguments:
        recorder.subscribe(JointTrajectory, f'/{name}/leg_trajectory')
        recorder.advertise(Path, f'/{name}/pose_path')
    recorder.connect()
    message = path_message(wave_poses(geometry.home_pose))
    for name in arguments:
        recorder.publishers[f'/{name}/pose_path'].publish(message)
    for name in arguments:
        recorder.wait_for(f'/{name}/leg_trajectory', 1)

    massless = recorder.received['/massless/leg_trajectory'][0]
    assert all(len(point.effort) == 0 for point in massless.points)
    massive = recorder.received['/massive/leg_trajectory'][0]
    lengths, velocities, accelerations, efforts = points_of(massive)
    assert efforts.shape == lengths.shape and len(efforts) > 100
    assert efforts.max() <= FORCE_MAX
    assert efforts.max() > 0.99 * FORCE_MAX          # the limit binds
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-9)
    assert_allclose(efforts, rebuilt_forces(geometry, lengths, velocities, accelerations),
                    rtol=0, atol=1e-6 * FORCE_MAX)
    # Slower than without masses: the force limit, not the leg limits, times it.
    duration = massive.points[-1].time_from_start
    free = massless.points[-1].time_from_start
    assert duration.sec + duration.nanosec * 1e-9 > 1.02 * (free.sec + free.nanosec * 1e-9)
    for node in nodes:
        assert node.running()
