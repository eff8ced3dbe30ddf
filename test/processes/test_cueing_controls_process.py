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
motion_cueing_node's run-time controls as an operator uses them, over the wire.

A drive streams on ``vehicle_imu`` in real time (100 Hz); mid-stream the intensity is set
through the parameter service: taken, and the ``target_pose`` commands stay smooth (each step of
the legs within leg_velocity_max over the time between them, plus scheduling slack); a gain
beyond the travel and a NaN intensity are refused with the reason. Then the ``stop`` service
parks the platform: the last command is the park pose (the core's, whose shortest leg is 10 mm
above the stroke's 0.65 m). About 8 s.
"""

import math
import time

from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Pose
import numpy as np
import pytest
from rcl_interfaces.srv import GetParameters, SetParameters
from rclpy.parameter import Parameter
from reference import leg_lengths_of_matrix, quaternion_matrix
from sensor_msgs.msg import Imu
from std_srvs.srv import Trigger

from stewart_kinematics.cueing import MotionCueing
from stewart_kinematics.parameters import read_parameter_file

pytestmark = pytest.mark.process

G = 9.80665
DEPTH = 100
VELOCITY_MAX = 0.05
#: Slack for the scheduling of the node and of this client, seconds.
SLACK = 0.05


def imu(stamp_ns, force, rate=(0.0, 0.0, 0.0)):
    """sensor_msgs/msg/Imu with a stamp in nanoseconds."""
    message = Imu()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    (message.linear_acceleration.x, message.linear_acceleration.y,
     message.linear_acceleration.z) = force
    message.angular_velocity.x, message.angular_velocity.y, message.angular_velocity.z = rate
    return message


def legs(message):
    """|t + R p_i - b_i| of a Pose message, leg by leg, from the paper's tables."""
    o = message.orientation
    position = np.array([message.position.x, message.position.y, message.position.z])
    return np.array(leg_lengths_of_matrix(position, quaternion_matrix(o.x, o.y, o.z, o.w)))


def call(client, service, request, processes):
    """Call a service and return its response."""
    client.wait(service.service_is_ready, 'the service', processes)
    future = service.call_async(request)
    client.wait(future.done, 'the answer', processes)
    return future.result()


def test_intensity_set_mid_stream_stays_smooth_and_stop_parks(client, start_node,
                                                              config_directory):
    files = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
             '--params-file', str(config_directory / 'example_limits.yaml'),
             '--params-file', str(config_directory / 'motion_cueing.yaml'),
             '-p', 'gain_ramp_time:=0.5', '-p', 'soft_stop_time:=1.0']
    cueing = start_node('motion_cueing_node', files)
    node = client.node
    received = []
    node.create_subscription(Pose, 'target_pose',
                             lambda message: received.append((time.monotonic(), message)),
                             DEPTH)
    reports = []
    node.create_subscription(DiagnosticArray, '/diagnostics', reports.append, DEPTH)
    publisher = node.create_publisher(Imu, 'vehicle_imu', DEPTH)
    parameters = node.create_client(SetParameters, 'motion_cueing_node/set_parameters')
    stop = node.create_client(Trigger, 'stop')
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and node.count_publishers('target_pose') >= 1, 'motion_cueing_node connected',
                [cueing])
    client.spin_for(0.3)

    def setting(name, value):
        request = SetParameters.Request()
        request.parameters = [Parameter(name, value=value).to_parameter_msg()]
        return call(client, parameters, request, [cueing]).results[0]

    answers = {}
    for k in range(200):   # 2 s at 100 Hz, in real time
        t = k * 0.01
        force = (2.0 * math.sin(2.0 * math.pi * 0.5 * t), 1.0 * math.sin(2.0 * t), G)
        publisher.publish(imu(1_000_000_000 + k * 10_000_000, force, (0.0, 0.0, 0.2)))
        if k == 60:
            answers['intensity'] = setting('cueing_intensity', 0.4)
            answers['beyond'] = setting('translation_scale', [5.0, 0.2, 0.2])
            answers['nan'] = setting('cueing_intensity', math.nan)
        client.spin_for(0.01)

    def samples_counted():
        """Return the counters of the last /diagnostics status of vehicle_imu, as a dict."""
        found = [status for report in reports for status in report.status
                 if status.name.endswith('vehicle_imu')]
        return {value.key: value.value for value in found[-1].values} if found else {}
    # The node's own count of the samples it answered, once it took all 200 (a fixed 0.2 s
    # could end before the last answers on a loaded machine; poses counted on the wire
    # instead would also count those the watchdog sends, easing home, after the samples).
    client.wait(lambda: samples_counted().get('received') == '200',
                'a report counting the 200 samples', [cueing])

    assert answers['intensity'].successful, answers['intensity'].reason
    assert not answers['beyond'].successful
    assert 'translation_scale x = 5 times cueing_intensity 0.4' in answers['beyond'].reason
    assert 'travel' in answers['beyond'].reason
    assert not answers['nan'].successful and 'cueing_intensity' in answers['nan'].reason
    assert int(samples_counted()['published']) > 150
    times = np.array([moment for moment, _ in received])
    lengths = np.array([legs(message) for _, message in received])
    steps = np.abs(np.diff(lengths, axis=0)).max(axis=1)
    assert np.all(steps <= VELOCITY_MAX * (np.diff(times) + SLACK))
    assert np.ptp(lengths) > 0.005   # the cue did move the platform

    # Stop: brake, then down to park; the last command is the park pose.
    count = len(received)
    answer = call(client, stop, Trigger.Request(), [cueing])
    assert answer.success, answer.message

    values = {}
    for name in ('paper_platform.yaml', 'example_limits.yaml', 'motion_cueing.yaml'):
        values.update(read_parameter_file(config_directory / name, 'motion_cueing_node'))
    park = MotionCueing.from_parameters(values).park_pose
    park_legs = np.array(leg_lengths_of_matrix(park[:3], np.eye(3)))
    assert abs(park_legs.min() - 0.66) < 1e-6

    def parked():
        return len(received) > count and np.allclose(
            legs(received[-1][1]), park_legs, rtol=0, atol=1e-6)
    client.wait(parked, 'the platform parked', [cueing])
    after = np.array([legs(message) for _, message in received[count - 1:]])
    moments = np.array([moment for moment, _ in received[count - 1:]])
    steps = np.abs(np.diff(after, axis=0)).max(axis=1)
    assert np.all(steps <= VELOCITY_MAX * (np.diff(moments) + SLACK))
    assert cueing.stop() == 0, cueing.output()
    assert 'Traceback' not in cueing.output()


def test_a_p_after_the_parameter_files_takes_effect(client, start_node, config_directory):
    # `motion_cueing_node --ros-args --params-file ... -p cueing_method:=mpc` kept the file's
    # 'classical' (rcl's /** value loses to the file's section naming the node): the last value
    # given on the command line is the one taken. About 3 s.
    files = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
             '--params-file', str(config_directory / 'example_limits.yaml'),
             '--params-file', str(config_directory / 'motion_cueing.yaml'),
             '-p', 'cueing_method:=mpc', '-p', 'tilt_max_deg:=7.0']
    cueing = start_node('motion_cueing_node', files)
    service = client.node.create_client(GetParameters, 'motion_cueing_node/get_parameters')
    answer = call(client, service, GetParameters.Request(
        names=['cueing_method', 'tilt_max_deg']), [cueing])
    assert [value.string_value for value in answer.values[:1]] == ['mpc']
    assert [value.double_value for value in answer.values[1:]] == [7.0]
