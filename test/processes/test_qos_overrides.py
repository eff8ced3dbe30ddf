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
QoS overrides across processes: a best-effort driver reaches fk_node once it is told to listen.

Many actuator drivers publish joint states best effort (rclpy's SensorDataQoS). A reliable
subscription does not match such a publisher; the standard ``qos_overrides.<topic>.subscription.
reliability`` parameter, given in a parameter file as ``ros2 param`` users write it, makes
fk_node's subscription best effort. Two fk_node processes run side by side in two namespaces,
one overridden and one not; the test's best-effort publisher of each gets the incompatible-QoS
event where it cannot match, which shows the mismatch without waiting for nothing to come.
"""

from geometry_msgs.msg import Pose
import pytest
from rclpy.event_handler import PublisherEventCallbacks
from rclpy.qos import qos_profile_sensor_data
from reference import HOME, leg_lengths
from sensor_msgs.msg import JointState

pytestmark = pytest.mark.process

OVERRIDES = """\
/**:
  ros__parameters:
    qos_overrides:
      /overridden/joint_states:
        subscription:
          reliability: best_effort
"""


def joint_state(lengths):
    """sensor_msgs/msg/JointState of the six legs at ``lengths``, metres."""
    return JointState(name=[f'leg_{leg}' for leg in range(1, 7)],
                      position=[float(length) for length in lengths])


def test_best_effort_joint_states_reach_fk_node_only_when_overridden(
        client, start_node, config_directory, tmp_path):
    """The overridden fk_node answers a SensorDataQoS publisher; the default one cannot match."""
    overrides = tmp_path / 'qos_overrides.yaml'
    overrides.write_text(OVERRIDES)
    arguments = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
                 '--params-file', str(overrides)]
    nodes = [start_node('fk_node', [*arguments, '-r', f'__ns:=/{namespace}'])
             for namespace in ('overridden', 'default')]
    incompatible = {'overridden': [], 'default': []}
    publishers, estimates = {}, {'overridden': [], 'default': []}
    for namespace in incompatible:
        publishers[namespace] = client.node.create_publisher(
            JointState, f'/{namespace}/joint_states', qos_profile_sensor_data,
            event_callbacks=PublisherEventCallbacks(
                incompatible_qos=incompatible[namespace].append))
        client.node.create_subscription(
            Pose, f'/{namespace}/estimated_pose', estimates[namespace].append, 10)

    client.wait(lambda: publishers['overridden'].get_subscription_count() >= 1,
                'the overridden fk_node matched the best-effort publisher', nodes)
    client.wait(lambda: incompatible['default'],
                'the incompatible-QoS event of the default fk_node', nodes)
    message = joint_state(leg_lengths(HOME))
    client.wait(lambda: estimates['overridden'] or publishers['overridden'].publish(message),
                'the overridden fk_node estimated the pose', nodes)

    position = estimates['overridden'][0].position
    assert [position.x, position.y, position.z] == pytest.approx(HOME[:3], abs=1e-9)
    assert incompatible['overridden'] == []
    assert publishers['default'].get_subscription_count() == 0
    assert incompatible['default'][0].last_policy_kind.name.endswith('RELIABILITY')
    assert estimates['default'] == []
