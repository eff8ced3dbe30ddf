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
Every node started with the 6-3 and the 3-3 platform files, as a user starts them.

For each design (config/platform_6_3.yaml, config/platform_3_3.yaml, each the only file given)
four console scripts run at once: ik_node and fk_node (a pose in, leg lengths out, the pose
back), trajectory_node in ``/trajectory`` (a timed trajectory in, the legs' trajectory out)
and motion_cueing_node in ``/cue`` (vehicle motion in, poses out). Expected leg lengths come
from the joints read with PyYAML and the textbook leg formula of test/reference.py.
"""

from geometry_msgs.msg import Pose
from helpers import pose_message, trajectory_message
import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference
from sensor_msgs.msg import Imu
from std_msgs.msg import Float64MultiArray
from trajectory_msgs.msg import JointTrajectory, MultiDOFJointTrajectory
import yaml

pytestmark = pytest.mark.process

DEPTH = 100
SETTLE_TIME = 0.5
DESIGN_FILES = {'6-3': 'platform_6_3.yaml', '3-3': 'platform_3_3.yaml'}
#: A pose away from home (relative to it): metres and radians.
OFFSET = np.array([0.03, -0.02, 0.04, 0.08, -0.06, 0.15])
#: Imu samples of the drive: 200 Hz, a push forward of 3 m/s^2 for a second and a half.
RATE, SAMPLES, GRAVITY = 200.0, 300, 9.80665


def read_file(path):
    """Return the ``/**`` parameters of a file: joints (6, 3), home pose, stroke."""
    with open(path, encoding='utf-8') as stream:
        parameters = yaml.safe_load(stream)['/**']['ros__parameters']
    home = np.concatenate([parameters['home_position'],
                           np.radians(parameters['home_orientation_deg'])])
    return (np.reshape(parameters['base_joints'], (6, 3)),
            np.reshape(parameters['platform_joints'], (6, 3)), home,
            (parameters['leg_length_min'], parameters['leg_length_max']))


def message_pose(message):
    """Return a Pose's position (3,) and rotation matrix (3, 3)."""
    o = message.orientation
    return (np.array([message.position.x, message.position.y, message.position.z]),
            reference.quaternion_matrix(o.x, o.y, o.z, o.w))


def imu(k):
    """Sample k of the drive: a push forward from sample 20 on, no rotation."""
    message = Imu()
    stamp = 1_000_000_000 + int(k * 1e9 / RATE)
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(stamp, 1_000_000_000)
    message.linear_acceleration.x = 3.0 if k >= 20 else 0.0
    message.linear_acceleration.z = GRAVITY
    return message


@pytest.mark.parametrize('design', sorted(DESIGN_FILES))
def test_every_node_runs_the_design(client, start_node, config_directory, design):
    """ik_node, fk_node, trajectory_node and motion_cueing_node each round-trip a pose."""
    path = config_directory / DESIGN_FILES[design]
    base, platform, home, (shortest, longest) = read_file(path)

    def lengths_of(pose):
        return np.array(reference.leg_lengths(pose, base, platform))

    files = ['--ros-args', '--params-file', str(path)]
    nodes = [start_node('ik_node', files), start_node('fk_node', files),
             start_node('trajectory_node', files + ['-r', '__ns:=/trajectory',
                                                    '-p', "mode:='off'"]),
             start_node('motion_cueing_node', files + ['-r', '__ns:=/cue'])]
    node = client.node
    lengths, estimates, legs, cues = [], [], [], []
    subscriptions = [
        node.create_subscription(Float64MultiArray, 'leg_lengths', lengths.append, DEPTH),
        node.create_subscription(Pose, 'estimated_pose', estimates.append, DEPTH),
        node.create_subscription(JointTrajectory, '/trajectory/leg_trajectory', legs.append,
                                 DEPTH),
        node.create_subscription(Pose, '/cue/target_pose', cues.append, DEPTH)]
    publishers = [node.create_publisher(Pose, 'target_pose', DEPTH),
                  node.create_publisher(MultiDOFJointTrajectory, '/trajectory/pose_trajectory',
                                        DEPTH),
                  node.create_publisher(Imu, '/cue/vehicle_imu', DEPTH)]
    client.wait(lambda: all(p.get_subscription_count() >= 1 for p in publishers)
                and all(s.get_publisher_count() >= 1 for s in subscriptions)
                and node.count_subscribers('leg_lengths') >= 2,
                f'the four nodes of the {design} platform matched', nodes)
    client.spin_for(SETTLE_TIME)

    # ik_node and fk_node: a pose, its leg lengths, and the pose back from them.
    pose = home + OFFSET
    publishers[0].publish(pose_message(pose))
    client.wait(lambda: lengths and estimates, 'leg_lengths and estimated_pose', nodes)
    assert_allclose(lengths[0].data, lengths_of(pose), rtol=0.0, atol=1e-12)
    position, rotation = message_pose(estimates[0])
    assert_allclose(position, pose[:3], rtol=0.0, atol=1e-9)
    assert reference.rotation_angle(rotation, reference.rotation_zyx(*pose[3:])) < 1e-9

    # trajectory_node: home to the pose and back in 10 s; the legs' trajectory passes
    # through the poses' leg lengths.
    publishers[1].publish(trajectory_message([0, 5, 10], [home, pose, home]))
    client.wait(lambda: legs, 'the leg trajectory', nodes)
    points = legs[0].points
    times = np.array([p.time_from_start.sec + p.time_from_start.nanosec * 1e-9 for p in points])
    positions = np.array([p.positions for p in points])
    middle = int(np.argmin(np.abs(times - 5.0)))
    assert times[0] == 0.0 and times[middle] == pytest.approx(5.0, abs=1e-9)
    assert times[-1] == pytest.approx(10.0, abs=1e-9)
    assert_allclose(positions[[0, middle, -1]],
                    [lengths_of(home), lengths_of(pose), lengths_of(home)], rtol=0.0, atol=1e-9)

    # motion_cueing_node: a push forward, cued by poses whose legs stay within the stroke.
    for k in range(SAMPLES):
        publishers[2].publish(imu(k))
        if k % 50 == 49:
            client.wait(lambda: len(cues) > k, f'{k + 1} cue poses', nodes)
    cue_lengths = np.array([reference.leg_lengths_of_matrix(*message_pose(cue), base, platform)
                            for cue in cues])
    assert len(cues) == SAMPLES
    assert shortest <= cue_lengths.min() and cue_lengths.max() <= longest
    surge = max(abs(message_pose(cue)[0][0] - home[0]) for cue in cues)
    assert surge > 0.005              # the cue moved the platform
    for process in nodes:
        assert process.stop() == 0, process.output()
        assert 'Traceback' not in process.output()
