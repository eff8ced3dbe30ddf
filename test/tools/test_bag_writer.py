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
BagWriter: raw CDR bytes in, a rosbag2 MCAP folder out that another reader decodes.

The messages are serialised by rclpy and read back by mcap with mcap-ros2-support (its own
CDR decoder, from the schema stored in the file); an earlier recording is replaced, anything
else never.
"""

from geometry_msgs.msg import Pose
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
import pytest
from rclpy.qos import DurabilityPolicy, QoSProfile
from rclpy.serialization import serialize_message
from stewart_kinematics.tools.bag_writer import BagWriter, remove_previous_bag
import yaml

pytestmark = pytest.mark.node


def write_poses(path, heights):
    """Record one Pose per height on /target_pose, 1 ms apart; return the metadata."""
    writer = BagWriter(path, [('/target_pose', Pose, QoSProfile(
        depth=5, durability=DurabilityPolicy.TRANSIENT_LOCAL))])
    for index, height in enumerate(heights):
        pose = Pose()
        pose.position.z = height
        writer.write('/target_pose', 1_000_000 * (index + 1), serialize_message(pose))
    writer.close()
    return yaml.safe_load((path / 'metadata.yaml').read_text())['rosbag2_bagfile_information']


def test_written_messages_decode_with_another_library(tmp_path):
    """Every message comes back from the MCAP file, in order, with its time and schema."""
    information = write_poses(tmp_path / 'bag', [0.4, 0.5, 0.6])

    assert information['storage_identifier'] == 'mcap'
    topic = information['topics_with_message_count'][0]
    assert topic['message_count'] == 3
    assert topic['topic_metadata']['offered_qos_profiles'][0]['durability'] == 'transient_local'
    with open(tmp_path / 'bag' / information['relative_file_paths'][0], 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        read = [(schema.name, message.log_time, decoded.position.z)
                for schema, _, message, decoded in reader.iter_decoded_messages()]
    assert read == [('geometry_msgs/msg/Pose', 1_000_000, 0.4),
                    ('geometry_msgs/msg/Pose', 2_000_000, 0.5),
                    ('geometry_msgs/msg/Pose', 3_000_000, 0.6)]


def test_an_earlier_recording_is_replaced_anything_else_refused(tmp_path):
    """remove_previous_bag deletes a rosbag2 folder, and refuses a folder without metadata."""
    write_poses(tmp_path / 'bag', [0.4])
    remove_previous_bag(tmp_path / 'bag')
    assert not (tmp_path / 'bag').exists()
    remove_previous_bag(tmp_path / 'absent')   # nothing there: nothing to do

    (tmp_path / 'mine').mkdir()
    (tmp_path / 'mine' / 'notes.txt').write_text('keep me')
    with pytest.raises(FileExistsError, match='not a rosbag2 folder'):
        remove_previous_bag(tmp_path / 'mine')
    assert (tmp_path / 'mine' / 'notes.txt').read_text() == 'keep me'
