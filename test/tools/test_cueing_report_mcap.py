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
``stewart_cueing --mcap``: a recording of ``vehicle_imu`` replayed as the node would cue it.

Each message is taken in its ``header.frame_id`` as motion_cueing_node takes it: the vehicle
frame as it is, ``imu_frame`` turned by ``imu_orientation_rpy_deg``, any other frame refused
naming it (before, every sample was replayed as if in the vehicle frame).
"""

from pathlib import Path

from geometry_msgs.msg import Pose
import numpy as np
import pytest
from rclpy.qos import QoSProfile
from rclpy.serialization import serialize_message
from sensor_msgs.msg import Imu
from stewart_kinematics.cueing.scenarios import scenario
from stewart_kinematics.tools.bag_writer import BagWriter
from stewart_kinematics.tools.cueing_report import main
import yaml

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
TUNED = ['--params-file', str(CONFIG / 'paper_platform.yaml'),
         '--params-file', str(CONFIG / 'example_limits.yaml'),
         '--params-file', str(CONFIG / 'motion_cueing.yaml')]
#: NED axes: x forward, y right, z down (roll 180 deg from the vehicle frame).
TO_NED = np.diag([1.0, -1.0, -1.0])


def record(folder, frame_id, turn=np.eye(3)):
    """Record the brake step at 50 Hz on /vehicle_imu in ``frame_id``, its axes ``turn``ed."""
    drive = scenario('brake_step', 50.0)
    writer = BagWriter(folder, [('/vehicle_imu', Imu, QoSProfile(depth=10))])
    for time, force, rate in zip(drive.times, drive.specific_force @ turn.T,
                                 drive.angular_velocity @ turn.T):
        message = Imu()
        stamp = 1000.0 + time
        message.header.stamp.sec, message.header.stamp.nanosec = int(stamp), round(
            (stamp % 1.0) * 1e9) % 1_000_000_000
        message.header.frame_id = frame_id
        message.linear_acceleration.x, message.linear_acceleration.y, \
            message.linear_acceleration.z = force.tolist()
        message.angular_velocity.x, message.angular_velocity.y, \
            message.angular_velocity.z = rate.tolist()
        writer.write('/vehicle_imu', int(stamp * 1e9), serialize_message(message))
    writer.close()
    return folder


def flat(numbers, prefix=''):
    """Return the numbers of a result as one mapping, ``a.b.c`` keys, unknowns left out."""
    if isinstance(numbers, dict):
        return {key: value for name, item in numbers.items()
                for key, value in flat(item, f'{prefix}{name}.').items()}
    if isinstance(numbers, list):
        return flat(dict(enumerate(numbers)), prefix)
    return {} if numbers is None else {prefix[:-1]: numbers}


def replayed(tmp_path, bag, name):
    """Replay ``bag`` with an NED IMU frame known to the parameters; return its numbers."""
    frames = tmp_path / 'frames.yaml'
    frames.write_text('/**:\n  ros__parameters:\n    imu_frame: imu_ned\n'
                      '    imu_orientation_rpy_deg: [180.0, 0.0, 0.0]\n', encoding='utf-8')
    output = tmp_path / f'{name}_out'
    code = main(TUNED + ['--params-file', str(frames), '--mcap', str(bag), '--no-figures',
                         '--quiet', '--output', str(output)])
    return code, output


def test_a_recording_in_the_imu_frame_is_cued_as_the_same_drive_in_the_vehicle_frame(tmp_path):
    """The same brake step, recorded in base_link and in NED axes: the same cue, to 1e-9."""
    _, vehicle = replayed(tmp_path, record(tmp_path / 'vehicle', 'base_link'), 'vehicle')
    _, ned = replayed(tmp_path, record(tmp_path / 'ned', 'imu_ned', TO_NED), 'ned')
    numbers = [yaml.safe_load((folder / 'cueing_results.yaml').read_text(encoding='utf-8'))
               for folder in (vehicle, ned)]
    (first,), (second,) = (list(run.values()) for run in numbers)
    assert flat(first) == pytest.approx(flat(second), rel=1e-9, abs=1e-9)
    # A braking that was cued, not a platform at rest.
    assert first['specific_force']['x']['peak'] > 0.5
    assert first['specific_force']['x']['correlation'] > 0.5


def test_a_recording_in_a_frame_the_parameters_do_not_place_exits_1_naming_it(tmp_path, capsys):
    """The node would refuse each sample (wrong_frame); the replay refuses the recording."""
    code, output = replayed(tmp_path, record(tmp_path / 'camera', 'camera_link'), 'camera')
    assert code == 1
    err = capsys.readouterr().err
    assert 'message 0 and ' in err and "the sample is in frame 'camera_link', which cannot " \
        "be placed in the vehicle frame: known are ['base_link', 'imu_ned']" in err
    assert not (output / 'cueing_results.yaml').exists()


def test_a_topic_of_another_type_exits_1_naming_it(tmp_path, capsys):
    """Poses recorded on the topic: refused naming the type (was "no attribute 'header'")."""
    writer = BagWriter(tmp_path / 'poses', [('/vehicle_imu', Pose, QoSProfile(depth=10))])
    for index in range(5):
        writer.write('/vehicle_imu', 10_000_000 * (index + 1), serialize_message(Pose()))
    writer.close()
    code, _ = replayed(tmp_path, tmp_path / 'poses', 'poses')
    assert code == 1
    assert capsys.readouterr().err.endswith(
        '/vehicle_imu holds geometry_msgs/msg/Pose, not sensor_msgs/msg/Imu\n')
