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
Write received messages to a rosbag2 folder in MCAP format, as ``ros2 bag record -s mcap`` does.

rosbag2 itself is not on PyPI; ``rosbags`` (pure Python) writes the same folder: a
``metadata.yaml`` and one ``.mcap`` file whose schemas are the ROS 2 Jazzy message definitions,
so ``ros2 bag info``/``play``, Foxglove and PlotJuggler read it. Messages are stored as they
arrived: the serialised CDR bytes of an rclpy subscription created with ``raw=True``, untouched.
"""

from pathlib import Path
import shutil

#: The rosbag2 metadata version written (Jazzy's rosbag2 reads versions up to 9).
ROSBAG2_VERSION = 9


def message_type_name(message_type) -> str:
    """Return the ROS name of an rclpy message class, e.g. ``'geometry_msgs/msg/Pose'``."""
    return f'{message_type.__module__.split(".")[0]}/msg/{message_type.__name__}'


def remove_previous_bag(path: Path):
    """
    Delete the rosbag2 folder at ``path`` so that a new recording can replace it.

    :raises FileExistsError: when ``path`` exists but is not a rosbag2 folder (no
        ``metadata.yaml`` in it): nothing else is ever deleted.
    """
    path = Path(path)
    if not path.exists():
        return
    if not (path / 'metadata.yaml').is_file():
        raise FileExistsError(f'{path} exists and is not a rosbag2 folder: not replacing it')
    shutil.rmtree(path)


class BagWriter:
    """
    A new rosbag2 folder in MCAP format, one connection per topic.

    :param path: the folder to create; it must not exist.
    :param topics: ``(absolute topic name, message class, rclpy QoSProfile)`` triples; the
        profile is stored as the topic's offered QoS (``ros2 bag play`` replays with it).
    :raises ImportError: when rosbags is not installed.
    """

    def __init__(self, path, topics):
        # Imported here: nothing else in the package needs rosbags.
        from rosbags.rosbag2 import StoragePlugin, Writer
        from rosbags.typesys import get_typestore, Stores
        self.path = Path(path)
        typestore = get_typestore(Stores.ROS2_JAZZY)
        self._writer = Writer(self.path, version=ROSBAG2_VERSION,
                              storage_plugin=StoragePlugin.MCAP)
        self._writer.open()
        self._connections = {
            topic: self._writer.add_connection(
                topic, message_type_name(message_type), typestore=typestore,
                offered_qos_profiles=[_rosbags_qos(qos)])
            for topic, message_type, qos in topics}
        #: Messages written so far, per topic.
        self.counts = dict.fromkeys(self._connections, 0)

    def write(self, topic: str, time_ns: int, data: bytes):
        """
        Append one serialised message.

        :param time_ns: the receive time, nanoseconds (the recording node's clock).
        :param data: the CDR bytes, as a ``raw=True`` subscription hands them over.
        """
        self._writer.write(self._connections[topic], time_ns, data)
        self.counts[topic] += 1

    def close(self):
        """Finish the MCAP file and write ``metadata.yaml``: the folder is then complete."""
        self._writer.close()


def _rosbags_qos(qos):
    """Return the rosbags form of an rclpy QoSProfile (deadline, lifespan: the defaults)."""
    from rosbags.interfaces import (
        Qos, QosDurability, QosHistory, QosLiveliness, QosReliability, QosTime)
    # rosbags' enums carry rmw's values, as rclpy's do.
    default_time = QosTime(0, 0)
    return Qos(QosHistory(qos.history.value), qos.depth, QosReliability(qos.reliability.value),
               QosDurability(qos.durability.value), default_time, default_time,
               QosLiveliness(qos.liveliness.value), default_time, False)
