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
The frame tree on ``/tf`` and ``/tf_static``, and frame transforms to and from messages.

Broadcasts as tf2_ros's broadcasters do (same topics, message and QoS) without depending on
tf2_ros: ``/tf`` reliable with depth 100, ``/tf_static`` reliable, transient local, depth 1
(the QoS declared in :mod:`stewart_kinematics.ros.interfaces`: :data:`~stewart_kinematics.ros.
interfaces.TF` and :data:`~stewart_kinematics.ros.interfaces.TF_STATIC`), with every static
transform of the node in each message. tf2_msgs comes with every ROS 2
installation; where it is missing (ROS from PyPI wheels), nothing is broadcast and the node
says so once in its log, the rest works as before.
"""

from geometry_msgs.msg import Transform as TransformMessage, TransformStamped
from std_msgs.msg import Header

from stewart_kinematics.model.frames import Transform
from stewart_kinematics.model.rotations import matrix_to_quaternion
from stewart_kinematics.ros.node_main import create_output_publisher

try:
    from tf2_msgs.msg import TFMessage
except ImportError:  # ROS from PyPI wheels: tf2_msgs is not among them
    TFMessage = None

#: What the log says once when tf2_msgs cannot be imported.
TF2_MSGS_MISSING = (
    'tf2_msgs is not installed, so nothing is broadcast on /tf and /tf_static; every other '
    'topic works. It comes with every ROS 2 installation (source /opt/ros/jazzy/setup.bash); '
    'without one, scripts/build_interfaces.sh builds it into a venv')


def transform_stamped(parent: str, child: str, transform: Transform, stamp) -> TransformStamped:
    """Return the geometry_msgs/msg/TransformStamped placing ``child`` in ``parent``."""
    message = TransformMessage()
    message.translation.x, message.translation.y, message.translation.z = (
        transform.position.tolist())
    rotation = message.rotation
    rotation.x, rotation.y, rotation.z, rotation.w = (
        matrix_to_quaternion(transform.rotation).tolist())
    return TransformStamped(header=Header(stamp=stamp, frame_id=parent), child_frame_id=child,
                            transform=message)


class TransformBroadcaster:
    """
    A node's publishers of ``/tf`` and ``/tf_static``; inert, with one log line, without tf2_msgs.

    :param node: the broadcasting node.
    :param dynamic: the node's declared ``/tf`` endpoint
        (:mod:`stewart_kinematics.ros.interfaces`), or ``None`` for no ``/tf`` publisher.
    :param static: likewise for ``/tf_static``.
    """

    def __init__(self, node, *, dynamic=None, static=None):
        self.available = TFMessage is not None
        self._tf = self._tf_static = None
        self._static_transforms = {}
        if not self.available:
            if dynamic is not None or static is not None:
                node.get_logger().warning(TF2_MSGS_MISSING)
            return
        if dynamic is not None:
            self._tf = create_output_publisher(node, dynamic)
        if static is not None:
            self._tf_static = create_output_publisher(node, static)

    def has_listeners(self) -> bool:
        """Whether anyone subscribes ``/tf``: a 1 kHz stream then skips building transforms."""
        return self._tf is not None and self._tf.get_subscription_count() > 0

    def send(self, parent: str, child: str, transform: Transform, stamp):
        """Broadcast one transform on ``/tf`` with ``stamp`` (builtin_interfaces/msg/Time)."""
        if self._tf is not None:
            self._tf.publish(TFMessage(transforms=[
                transform_stamped(parent, child, transform, stamp)]))

    def send_static(self, transforms, stamp):
        """
        Broadcast fixed transforms on ``/tf_static``, replacing earlier ones of the same child.

        As tf2_ros's static broadcaster does, each message holds every static transform the
        node has sent (the topic keeps one message per publisher for late joiners).

        :param transforms: ``(parent, child, transform)`` triples.
        """
        if self._tf_static is None:
            return
        for parent, child, transform in transforms:
            self._static_transforms[child] = transform_stamped(parent, child, transform, stamp)
        if self._static_transforms:   # nothing named: nothing to latch
            self._tf_static.publish(
                TFMessage(transforms=list(self._static_transforms.values())))

    def forget_static(self, child: str):
        """Stop including the static transform of ``child`` from the next broadcast on."""
        self._static_transforms.pop(child, None)
