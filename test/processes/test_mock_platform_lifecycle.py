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
mock_platform as a managed node, across processes: its transitions through the services.

Started with ``-p managed:=true``, driven with lifecycle_msgs/srv/ChangeState and GetState as
``ros2 lifecycle set`` does: nothing on joint_states until active; a bad initial length fails
configure with the node alive and configurable once corrected; deactivate stops the legs where
they are, commands are ignored while inactive, and once active again the legs start from there
at rest.
"""

from helpers import CLIENT_DEPTH, stop_cleanly
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState, GetState
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rcl_interfaces.srv import SetParameters
from rclpy.parameter import Parameter
import reference
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray
import yaml

pytestmark = pytest.mark.process

NAMES = [f'leg_{leg}' for leg in range(1, 7)]
#: Seconds the test listens to make sure nothing comes (a pause, never a wait for data).
QUIET_TIME = 1.0


def home_lengths(config_directory):
    """Return the leg lengths of the home pose, from the file's joints and the leg formula."""
    with open(config_directory / 'paper_platform.yaml', encoding='utf-8') as stream:
        parameters = yaml.safe_load(stream)['/**']['ros__parameters']
    return np.array(reference.leg_lengths(reference.HOME,
                                          np.reshape(parameters['base_joints'], (6, 3)),
                                          np.reshape(parameters['platform_joints'], (6, 3))))


def call(client, process, service, request):
    """Call a service and return its response (fail with the node's output if none)."""
    client.wait(service.service_is_ready, f'{service.srv_name} ready', [process])
    future = service.call_async(request)
    client.wait(future.done, f'an answer of {service.srv_name}', [process])
    return future.result()


def test_mock_platform_is_silent_until_active_and_deactivate_stops_its_legs(
        client, start_node, config_directory):
    """Unconfigured and inactive: nothing; a bad file value refused; deactivate: legs stop."""
    home = home_lengths(config_directory)
    process = start_node('mock_platform', [
        '--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
        '--params-file', str(config_directory / 'example_limits.yaml'), '-p', 'managed:=true',
        '-p', 'initial_leg_lengths:=[0.5, 0.5, 0.5, 0.5, 0.5, 0.5]'])
    node = client.node
    change = node.create_client(ChangeState, '/mock_platform/change_state')
    state = node.create_client(GetState, '/mock_platform/get_state')
    parameters = node.create_client(SetParameters, '/mock_platform/set_parameters')
    states = []
    node.create_subscription(JointState, 'joint_states', states.append, CLIENT_DEPTH)
    command = node.create_publisher(Float64MultiArray, 'leg_lengths', CLIENT_DEPTH)

    def transition(label):
        return call(client, process, change,
                    ChangeState.Request(transition=Transition(label=label))).success

    def label():
        return call(client, process, state, GetState.Request()).current_state.label

    # Initial lengths beyond the stroke: configure fails, the node stays unconfigured, alive.
    assert not transition('configure') and label() == 'unconfigured'
    result = call(client, process, parameters, SetParameters.Request(parameters=[
        Parameter('initial_leg_lengths', value=[0.0] * 6).to_parameter_msg()])).results[0]
    assert result.successful, result.reason
    assert transition('configure') and label() == 'inactive'
    client.spin_for(QUIET_TIME)
    assert states == []

    assert transition('activate') and label() == 'active'
    client.wait(lambda: len(states) >= 3 and command.get_subscription_count() >= 1,
                'joint states once active', [process])
    assert_allclose(states[-1].position, home, atol=1e-12)
    command.publish(Float64MultiArray(data=(home + 0.04).tolist()))
    client.wait(lambda: states[-1].position[0] > home[0] + 0.01, 'the legs moving', [process])

    # Deactivate mid-way: nothing published, a command ignored.
    assert transition('deactivate') and label() == 'inactive'
    client.spin_for(0.2)
    stopped = np.array(states[-1].position)
    count = len(states)
    command.publish(Float64MultiArray(data=(home - 0.04).tolist()))
    client.spin_for(QUIET_TIME)
    assert len(states) == count
    assert np.all(stopped < home + 0.04 - 1e-3)

    # Active again: from where they stopped, at rest, holding there (the command was ignored).
    assert transition('activate')
    client.wait(lambda: len(states) >= count + 20, 'joint states again', [process])
    after = np.array([message.position for message in states[count:]])
    assert_allclose(after, np.broadcast_to(stopped, after.shape), atol=1e-12)
    assert all(not any(message.velocity) for message in states[count:])

    assert transition('deactivate') and transition('cleanup') and label() == 'unconfigured'
    assert transition('shutdown')
    client.wait(lambda: not process.running(), 'the process ending after shutdown', [])
    output = stop_cleanly(process)
    assert 'configure failed, the node stays unconfigured' in output
    assert 'outside the stroke' in output
