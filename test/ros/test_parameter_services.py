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
The nodes' parameter services answer malformed requests instead of dying.

Found by the node fuzzer (test_fuzz_nodes.py): a SetParameters request whose value carries a
type code that rcl_interfaces does not define made rclpy's parameter service raise ValueError
inside the executor, and every node process exited with a traceback. Each node is built
in-process and called through its real services by a client node on the same executor.
"""

from pathlib import Path

import pytest
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import GetParameters, SetParameters, SetParametersAtomically
from rclpy.executors import SingleThreadedExecutor

from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.trajectory_node import TrajectoryNode

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
ARGUMENTS = ['--ros-args', '--params-file', str(CONFIG_DIRECTORY / 'paper_platform.yaml'),
             '--params-file', str(CONFIG_DIRECTORY / 'example_limits.yaml')]
#: Seconds to wait for an answer.
DEADLINE = 10.0


@pytest.fixture(params=[IkNode, FkNode, TrajectoryNode],
                ids=['ik_node', 'fk_node', 'trajectory_node'])
def served(ros, request):
    """Build a node and a client on one executor; yield (node, call)."""
    node = request.param(cli_args=ARGUMENTS)
    client = ros.create_node('parameter_client')
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    executor.add_node(client)

    def call(service_type, name, service_request):
        service = client.create_client(service_type, f'{node.get_fully_qualified_name()}/{name}')
        assert service.wait_for_service(timeout_sec=DEADLINE)
        future = service.call_async(service_request)
        executor.spin_until_future_complete(future, timeout_sec=DEADLINE)
        assert future.done(), f'no answer from {name}'
        return future.result()

    yield node, call
    executor.shutdown()
    client.destroy_node()
    node.destroy_node()


def double(name, value, type_code=ParameterType.PARAMETER_DOUBLE):
    """Return a Parameter message of a double value, with any type code."""
    return Parameter(name=name, value=ParameterValue(type=type_code, double_value=value))


def test_an_unknown_parameter_type_is_refused_and_the_others_applied(served):
    """Type code 42 beside a valid change: that one refused, naming the type; the valid one set."""
    node, call = served
    response = call(SetParameters, 'set_parameters', SetParameters.Request(parameters=[
        double('tool_frame_position', 1.0, type_code=42),
        Parameter(name='tool_frame_position', value=ParameterValue(
            type=ParameterType.PARAMETER_DOUBLE_ARRAY, double_array_value=[0.0, 0.0, 0.01]))]))
    refused, applied = response.results
    assert not refused.successful
    assert 'tool_frame_position' in refused.reason and '42' in refused.reason, refused.reason
    assert applied.successful, applied.reason
    values = call(GetParameters, 'get_parameters',
                  GetParameters.Request(names=['tool_frame_position'])).values
    assert list(values[0].double_array_value) == [0.0, 0.0, 0.01]


def test_an_unknown_parameter_type_refuses_an_atomic_request_whole(served):
    """An atomic request with one unknown type code changes nothing."""
    node, call = served
    response = call(SetParametersAtomically, 'set_parameters_atomically',
                    SetParametersAtomically.Request(parameters=[
                        Parameter(name='tool_frame', value=ParameterValue(
                            type=ParameterType.PARAMETER_STRING, string_value='fuzz_tool')),
                        double('tool_frame', 0.0, type_code=255)]))
    assert not response.result.successful
    assert '255' in response.result.reason, response.result.reason
    assert node.get_parameter('tool_frame').value == ''


def test_a_parameter_without_a_name_is_refused_and_not_created(served):
    """
    An empty name is refused; the node does not gain a parameter named ''.

    rclpy's check of undeclared names tests ``any(names)``, for which '' is false: without the
    node's own check, the request succeeded and list_parameters listed a parameter ''.
    """
    node, call = served
    response = call(SetParameters, 'set_parameters',
                    SetParameters.Request(parameters=[double('', 1.0)]))
    [result] = response.results
    assert not result.successful
    assert 'name' in result.reason, result.reason
    assert not node.has_parameter('')
    atomic = call(SetParametersAtomically, 'set_parameters_atomically',
                  SetParametersAtomically.Request(parameters=[double('', 1.0)]))
    assert not atomic.result.successful
    assert not node.has_parameter('')


def test_a_name_the_node_does_not_declare_is_refused_naming_it_and_the_closest(served):
    """
    A misspelt name: the refusal names it, the node and the closest name; nothing is set.

    rclpy's own refusal named none ("Invalid access to undeclared parameter(s): []": its
    check consumes the generator of names it then lists).
    """
    node, call = served
    response = call(SetParameters, 'set_parameters', SetParameters.Request(parameters=[
        double('queue_dpth', 5.0),
        Parameter(name='tool_frame', value=ParameterValue(
            type=ParameterType.PARAMETER_STRING, string_value=''))]))
    refused, applied = response.results
    assert not refused.successful and applied.successful, applied.reason
    assert refused.reason.startswith(
        f"parameter 'queue_dpth' is not a parameter of {node.get_name()} (did you mean "
        "'queue_depth'?); it has "), refused.reason
    assert not node.has_parameter('queue_dpth')
    atomic = call(SetParametersAtomically, 'set_parameters_atomically',
                  SetParametersAtomically.Request(parameters=[double('no_such_name', 1.0)]))
    assert not atomic.result.successful
    assert "parameter 'no_such_name' is not a parameter of" in atomic.result.reason
