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
A node that records what the ramp demo's nodes publish, in order of arrival.

One subscription per topic, taking the serialised message (``raw=True``): the bytes go
untouched to the rosbag2 recording when there is one, and are decoded for the demo's tables.
"""

import time

from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Pose
import rclpy
from rclpy.node import Node
from rclpy.qos import QoSProfile
from rclpy.serialization import deserialize_message
from std_msgs.msg import Float64MultiArray

from stewart_kinematics.ros import interfaces
from stewart_kinematics.ros.message_conversions import leg_lengths_from_message, pose_from_message
from stewart_kinematics.ros.transforms import TFMessage

#: Queue depth of the recorder's subscriptions: deep enough for a whole ramp.
RECORD_DEPTH = 1000


class RampRecorder(Node):
    """
    Record ``target_pose``, ``leg_lengths`` and ``estimated_pose`` as arrays.

    :param bag_path: a rosbag2 folder (MCAP) to create and record every topic into, with
        ``/diagnostics``, and ``/tf`` and ``/tf_static`` where tf2_msgs is installed; ``None``
        records nothing to disk. Call :meth:`close` at the end.
    """

    def __init__(self, bag_path=None, **kwargs):
        super().__init__('ramp_recorder', **kwargs)
        self.target_poses, self.leg_lengths, self.estimated_poses = [], [], []
        qos = QoSProfile(depth=RECORD_DEPTH)
        topics = [  # topic, message class, QoS, where its decoded form goes
            ('target_pose', Pose, qos,
             lambda m: self.target_poses.append(pose_from_message(m))),
            ('leg_lengths', Float64MultiArray, qos,
             lambda m: self.leg_lengths.append(leg_lengths_from_message(m))),
            ('estimated_pose', Pose, qos,
             lambda m: self.estimated_poses.append(pose_from_message(m))),
            ('/diagnostics', DiagnosticArray, qos, None),
        ]
        if TFMessage is not None:
            topics += [('/tf', TFMessage, interfaces.TF.profile(), None),
                       ('/tf_static', TFMessage, interfaces.TF_STATIC.profile(), None)]
        if bag_path is None:
            topics = [entry for entry in topics if entry[3] is not None]
            self.bag = None
        else:
            from stewart_kinematics.tools.bag_writer import BagWriter
            self.bag = BagWriter(bag_path, [
                (self.resolve_topic_name(topic), message_type, profile)
                for topic, message_type, profile, _ in topics])
        for topic, message_type, profile, record in topics:
            self.create_subscription(
                message_type, topic,
                self._receiver(self.resolve_topic_name(topic), message_type, record), profile,
                raw=True)

    def _receiver(self, topic, message_type, record):
        """Return the callback of ``topic``: to the bag as received, then to ``record``."""
        def receive(data: bytes):
            if self.bag is not None:
                self.bag.write(topic, self.get_clock().now().nanoseconds, data)
            if record is not None:
                record(deserialize_message(data, message_type))
        return receive

    def close(self):
        """Complete the recording, if any (its metadata.yaml is written now)."""
        if self.bag is not None:
            self.bag.close()

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
                and self.count_publishers('estimated_pose') >= 1
                and (TFMessage is None or self.count_publishers('/tf') >= 1))

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
