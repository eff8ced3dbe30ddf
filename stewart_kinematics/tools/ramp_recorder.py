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

"""A node that records what the ramp demo's nodes publish, in order of arrival."""

import time

from geometry_msgs.msg import Pose
import rclpy
from rclpy.node import Node
from std_msgs.msg import Float64MultiArray

from stewart_kinematics.ros.message_conversions import leg_lengths_from_message, pose_from_message

#: Queue depth of the recorder's subscriptions: deep enough for a whole ramp.
RECORD_DEPTH = 1000


class RampRecorder(Node):
    """Record ``target_pose``, ``leg_lengths`` and ``estimated_pose`` as arrays."""

    def __init__(self, **kwargs):
        super().__init__('ramp_recorder', **kwargs)
        self.target_poses, self.leg_lengths, self.estimated_poses = [], [], []
        self.create_subscription(
            Pose, 'target_pose', lambda m: self.target_poses.append(pose_from_message(m)),
            RECORD_DEPTH)
        self.create_subscription(
            Float64MultiArray, 'leg_lengths',
            lambda m: self.leg_lengths.append(leg_lengths_from_message(m)), RECORD_DEPTH)
        self.create_subscription(
            Pose, 'estimated_pose', lambda m: self.estimated_poses.append(pose_from_message(m)),
            RECORD_DEPTH)

    def counts(self):
        """Numbers of target poses, leg lengths and estimated poses received."""
        return len(self.target_poses), len(self.leg_lengths), len(self.estimated_poses)

    def complete(self, count) -> bool:
        """Whether ``count`` messages arrived on each topic."""
        return min(self.counts()) >= count

    def kinematics_nodes_connected(self) -> bool:
        """Whether ik_node and fk_node are subscribed and publishing where expected."""
        return (self.count_subscribers('target_pose') >= 2
                and self.count_subscribers('leg_lengths') >= 2
                and self.count_publishers('leg_lengths') >= 1
                and self.count_publishers('estimated_pose') >= 1)

    def spin_until(self, condition, deadline, processes=()) -> bool:
        """
        Spin this node until ``condition()`` holds, or give up.

        It gives up when the monotonic ``deadline`` passes or one of ``processes`` exits.

        :returns: whether the condition holds.
        """
        while not condition():
            if time.monotonic() > deadline or not all(p.running() for p in processes):
                return False
            rclpy.spin_once(self, timeout_sec=0.05)
        return True
