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
A payload changed at run time, across real processes, through the parameter services.

ik_node and fk_node run as console scripts with the paper's platform, the example masses (a
20 kg payload) and ``leg_force_max`` 100 N. The test's node sets ``payload_mass`` as ``ros2
param set`` does: 40 kg makes ik_node refuse the next command of Table 3's row 3 naming
``leg_force_max`` (74 N with 20 kg, 120 N with 40 kg), 60 kg (home would need 120 N) is
refused naming the payload; on fk_node, the wrench of the same measured efforts changes by the
weight of the 5 kg the model gained, written here from mass and gravity.
"""

from geometry_msgs.msg import Pose, WrenchStamped
from helpers import pose_message, Recorder, stop_cleanly
import numpy as np
import pytest
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import SetParameters
from reference import TABLE_3
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray

from stewart_kinematics import inverse_kinematics, leg_forces, load_geometry
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

pytestmark = pytest.mark.process

GRAVITY = np.array([0.0, 0.0, -9.80665])
BUSY = np.array(TABLE_3[3])


def node_arguments(config_directory):
    """Return the arguments: the paper's platform, the example masses, 100 N a leg at most."""
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'example_masses.yaml'),
            '-p', 'leg_force_max:=100.0']


def set_payload_mass(client, node, process, value):
    """Set ``payload_mass`` on ``node`` through its parameter service; return the result."""
    service = client.node.create_client(SetParameters, f'/{node}/set_parameters')
    client.wait(service.service_is_ready, f'{node} parameter service', [process])
    future = service.call_async(SetParameters.Request(parameters=[Parameter(
        name='payload_mass',
        value=ParameterValue(type=ParameterType.PARAMETER_DOUBLE, double_value=value))]))
    client.wait(future.done, 'the parameter set', [process])
    return future.result().results[0]


def wrench_values(message):
    """Return ``[Fx, Fy, Fz, Mx, My, Mz]`` of a WrenchStamped."""
    force, torque = message.wrench.force, message.wrench.torque
    return np.array([force.x, force.y, force.z, torque.x, torque.y, torque.z])


def test_a_payload_set_at_run_time_reaches_the_limits_and_the_wrench(
        client, start_node, config_directory):
    arguments = node_arguments(config_directory)
    ik = start_node('ik_node', arguments)
    fk = start_node('fk_node', arguments)
    topics = Recorder(client, [ik, fk])
    topics.advertise(Pose, 'target_pose')
    topics.advertise(JointState, 'joint_states')
    topics.subscribe(Float64MultiArray, 'leg_lengths')
    topics.subscribe(WrenchStamped, 'estimated_wrench')
    topics.connect()

    topics.publishers['target_pose'].publish(pose_message(BUSY))
    topics.wait_for('leg_lengths', 1)
    assert set_payload_mass(client, 'ik_node', ik, 40.0).successful
    refused = set_payload_mass(client, 'ik_node', ik, 60.0)
    assert not refused.successful
    assert refused.reason.startswith('payload refused (payload_mass 60.0'), refused.reason
    assert 'leg_force_max' in refused.reason, refused.reason
    topics.publishers['target_pose'].publish(pose_message(BUSY))
    status = topics.rejection('/ik_node: target_pose', 'out_of_limits')
    values = {value.key: value.value for value in status.values}
    assert 'leg_force_max' in values['last rejection'], values['last rejection']
    assert len(topics.received['leg_lengths']) == 1

    geometry = load_geometry([str(config_directory / 'paper_platform.yaml'),
                              str(config_directory / 'example_masses.yaml')])
    efforts = leg_forces(geometry, BUSY)   # what the legs push for the 20 kg payload
    message = JointState(name=[f'leg_{leg}' for leg in range(1, 7)],
                         position=inverse_kinematics(geometry, BUSY).tolist(),
                         effort=efforts.tolist())
    topics.publishers['joint_states'].publish(message)
    topics.wait_for('estimated_wrench', 1)
    first = topics.received['estimated_wrench'][0]
    assert first.header.frame_id == 'stewart_platform'
    np.testing.assert_allclose(wrench_values(first), np.zeros(6), rtol=0.0, atol=1e-6)
    assert set_payload_mass(client, 'fk_node', fk, 25.0).successful
    topics.publishers['joint_states'].publish(message)
    topics.wait_for('estimated_wrench', 2)
    # The model now holds 5 kg more than the legs push: the environment holds it up.
    center = np.array(geometry.mass_properties.payload.center_of_mass)
    weight = 5.0 * euler_zyx_to_matrix(BUSY[3:]).T @ GRAVITY
    expected = -np.concatenate([weight, np.cross(center, weight)])
    np.testing.assert_allclose(wrench_values(topics.received['estimated_wrench'][1]), expected,
                               rtol=0.0, atol=1e-9 * np.abs(expected).max())
    for process in (ik, fk):
        stop_cleanly(process)
