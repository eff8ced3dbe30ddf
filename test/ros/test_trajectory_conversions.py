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
Conversions of trajectory_msgs/MultiDOFJointTrajectory and nav_msgs/Path to the planner's input.

Messages built field by field here; the expected numbers are the ones typed into them.
"""

from builtin_interfaces.msg import Duration
from control_msgs.action import FollowJointTrajectory
from geometry_msgs.msg import PoseStamped, Transform, Twist
from nav_msgs.msg import Path
import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics.motion.pose_trajectory import MAX_WAYPOINTS
from stewart_kinematics.ros.message_conversions import (
    leg_trajectory_from_message,
    path_from_message,
    pose_trajectory_from_message,
)
from stewart_kinematics.ros.trajectory_action import goal_request
from trajectory_msgs.msg import (
    JointTrajectory,
    JointTrajectoryPoint,
    MultiDOFJointTrajectory,
    MultiDOFJointTrajectoryPoint,
)

pytestmark = pytest.mark.node


def twist(linear, angular):
    """Build a Twist of two triples."""
    message = Twist()
    message.linear.x, message.linear.y, message.linear.z = linear
    message.angular.x, message.angular.y, message.angular.z = angular
    return message


def point(seconds, nanoseconds, z, velocity=None, acceleration=None):
    """Build a point 'z' metres up, with a quaternion of norm 2 about z, and optional twists."""
    transform = Transform()
    transform.translation.z = z
    transform.rotation.z, transform.rotation.w = 0.0, 2.0
    return MultiDOFJointTrajectoryPoint(
        transforms=[transform], velocities=[velocity] if velocity else [],
        accelerations=[acceleration] if acceleration else [],
        time_from_start=Duration(sec=seconds, nanosec=nanoseconds))


def test_times_positions_quaternions_twists_and_accelerations_are_read():
    """Seconds and nanoseconds, normalised quaternions, twists and accelerations when all have."""
    message = MultiDOFJointTrajectory(joint_names=['platform'])
    message.header.frame_id = 'work'
    message.points = [
        point(0, 0, 0.4, twist((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
              twist((0.0, 0.0, 0.1), (0.0, 0.0, 0.2))),
        point(1, 500_000_000, 0.45, twist((0.0, 0.0, 0.02), (0.0, 0.0, 0.1)),
              twist((0.0, 0.0, -0.1), (0.0, 0.0, 0.0)))]
    arguments = pose_trajectory_from_message(message)
    assert_allclose(arguments['times'], [0.0, 1.5])
    assert_allclose(arguments['positions'], [[0.0, 0.0, 0.4], [0.0, 0.0, 0.45]])
    assert_allclose(arguments['quaternions'], [[0.0, 0.0, 0.0, 1.0]] * 2)
    assert_allclose(arguments['velocities'][1], [0.0, 0.0, 0.02])
    assert_allclose(arguments['angular_velocities'][1], [0.0, 0.0, 0.1])
    assert_allclose(arguments['accelerations'][0], [0.0, 0.0, 0.1])
    assert_allclose(arguments['angular_accelerations'][0], [0.0, 0.0, 0.2])
    assert arguments['frame_id'] == 'work'


@pytest.mark.parametrize('field', ['velocities', 'accelerations'])
def test_twists_on_only_some_points_are_refused(field):
    """All points or none."""
    message = MultiDOFJointTrajectory(joint_names=['platform'],
                                      points=[point(0, 0, 0.4), point(1, 0, 0.45)])
    getattr(message.points[1], field).append(Twist())
    with pytest.raises(ValueError, match=f'{field} must be given for every point'):
        pose_trajectory_from_message(message)


def test_an_empty_trajectory_converts_and_a_huge_one_is_refused_before_converting():
    """No point: empty arrays (the planner says why); too many: refused by count at once."""
    arguments = pose_trajectory_from_message(MultiDOFJointTrajectory())
    assert arguments['positions'].shape == (0, 3) and arguments['quaternions'].shape == (0, 4)
    message = MultiDOFJointTrajectory(points=[MultiDOFJointTrajectoryPoint()]
                                      * (MAX_WAYPOINTS + 1))
    with pytest.raises(ValueError, match='at most 100,000 waypoints, got 100,001'):
        pose_trajectory_from_message(message)


def test_a_zero_quaternion_is_refused_naming_the_point():
    """Point 1's quaternion is zero."""
    message = MultiDOFJointTrajectory(points=[point(0, 0, 0.4), point(1, 0, 0.45)])
    message.points[1].transforms[0].rotation.w = 0.0
    with pytest.raises(ValueError, match='point 1: a quaternion must be finite and not zero'):
        pose_trajectory_from_message(message)


def test_a_path_is_read_in_its_frame_and_a_pose_in_another_is_refused():
    """Poses with the path's frame or none are read; a pose in another frame is refused."""
    message = Path()
    message.header.frame_id = 'work'
    for z, frame in ((0.4, ''), (0.45, 'work')):
        stamped = PoseStamped()
        stamped.header.frame_id = frame
        stamped.pose.position.z = z
        stamped.pose.orientation.w = 1.0
        message.poses.append(stamped)
    positions, quaternions, frame_id = path_from_message(message)
    assert_allclose(positions[:, 2], [0.4, 0.45]) and frame_id == 'work'
    assert_allclose(quaternions, np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)))
    message.poses[1].header.frame_id = 'elsewhere'
    with pytest.raises(ValueError, match="pose 1 of the path is in frame 'elsewhere'"):
        path_from_message(message)


def test_oversized_names_and_frames_are_refused_in_one_short_line():
    """Issue 27: joint names and frame ids of a message are previewed, never echoed whole."""
    trajectory = MultiDOFJointTrajectory(joint_names=[f'j{index}' for index in range(10 ** 5)],
                                         points=[point(0, 0, 0.4), point(1, 0, 0.45)])
    with pytest.raises(ValueError, match='one joint') as raised:
        pose_trajectory_from_message(trajectory)
    assert len(str(raised.value)) < 300 and '(100,000 values)' in str(raised.value)
    path = Path()
    path.header.frame_id = 'w' * 10 ** 7
    for frame in ('', 'e' * 10 ** 7):
        stamped = PoseStamped()
        stamped.header.frame_id = frame
        stamped.pose.orientation.w = 1.0
        path.poses.append(stamped)
    with pytest.raises(ValueError, match='pose 1 of the path is in frame') as raised:
        path_from_message(path)
    assert len(str(raised.value)) < 400 and str(raised.value).count('(10,000,000 characters)') == 2


def test_malformed_times_are_refused_naming_the_field_not_moved_by_seconds():
    """
    A nanosec of 4e9 (rclpy does not refuse it) would be 4 s more, silently.

    A pose trajectory's point, a leg trajectory's point and stamp, and a follow_joint_trajectory
    goal's point, stamp and goal_time_tolerance are each refused, naming the field.
    """
    message = MultiDOFJointTrajectory(joint_names=['platform'],
                                      points=[point(0, 0, 0.4), point(1, 4_000_000_000, 0.41)])
    with pytest.raises(ValueError, match="^point 1's time_from_start is malformed: nanosec "
                                         '4000000000 is not below 1000000000'):
        pose_trajectory_from_message(message)

    legs = JointTrajectory(joint_names=[f'leg_{leg}' for leg in range(1, 7)], points=[
        JointTrajectoryPoint(positions=[0.7] * 6, time_from_start=Duration(sec=1))])
    assert leg_trajectory_from_message(legs)['times'].tolist() == [1.0]
    legs.header.stamp.nanosec = 1_000_000_000
    with pytest.raises(ValueError, match='^header.stamp is malformed: nanosec 1000000000'):
        leg_trajectory_from_message(legs)
    legs.header.stamp.nanosec = 0
    legs.points[0].time_from_start.nanosec = 2_000_000_000
    with pytest.raises(ValueError, match="^point 0's time_from_start is malformed"):
        leg_trajectory_from_message(legs)

    goal = FollowJointTrajectory.Goal()
    goal.trajectory = legs
    refused = goal_request(goal)
    assert refused.code == 'invalid_goal'
    assert refused.message.startswith("point 0's time_from_start is malformed")
    legs.points[0].time_from_start.nanosec = 0
    assert goal_request(goal).times == (1.0,)
    goal.goal_time_tolerance.nanosec = 3_000_000_000
    assert goal_request(goal).message.startswith('goal_time_tolerance is malformed')
