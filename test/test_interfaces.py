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

"""Each node offers exactly the topics and services its declaration in ros/interfaces.py names."""

import pytest

from stewart_kinematics.ros.interfaces import (
    FK_NODE,
    IK_NODE,
    markdown_table,
    MOTION_CUEING_NODE,
    NODE_INTERFACES,
    PUBLISHER,
    SERVICE,
    SUBSCRIPTION,
    TRAJECTORY_NODE,
)

pytestmark = pytest.mark.node

#: What rclpy gives every node: its log, parameter events and parameter services.
RCLPY_TOPICS = {'/rosout', '/parameter_events'}


def node_class(name):
    """Return the node class of a node name."""
    from stewart_kinematics.ros.fk_node import FkNode
    from stewart_kinematics.ros.ik_node import IkNode
    from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
    from stewart_kinematics.ros.trajectory_node import TrajectoryNode
    return {'ik_node': IkNode, 'fk_node': FkNode, 'trajectory_node': TrajectoryNode,
            'motion_cueing_node': MotionCueingNode}[name]


def absolute(name):
    """Return a declared name as the node in the root namespace has it."""
    return name if name.startswith('/') else '/' + name


@pytest.mark.parametrize('interface', [IK_NODE, FK_NODE, TRAJECTORY_NODE, MOTION_CUEING_NODE],
                         ids=lambda interface: interface.node)
def test_a_node_has_exactly_its_declared_topics_and_services(ros, config_directory, interface):
    """Every optional endpoint on: the node's publishers, subscriptions and services."""
    arguments = ['--ros-args']
    for name in ('paper_platform.yaml', 'solver.yaml', 'table3_ramp.yaml'):
        arguments += ['--params-file', str(config_directory / name)]
    arguments += ['-p', 'publish_commanded_tf:=true'] if interface is IK_NODE else []
    node = node_class(interface.node)(cli_args=arguments)
    try:
        def declared(kind):
            return {absolute(endpoint.name): endpoint.type_name
                    for endpoint in interface.of_kind(kind)}

        def type_name(message_type):
            return f'{message_type.__module__.split(".")[0]}/' \
                   f'{message_type.__module__.split(".")[1].lstrip("_")}/{message_type.__name__}'

        assert {subscription.topic_name: type_name(subscription.msg_type)
                for subscription in node.subscriptions} == declared(SUBSCRIPTION)
        assert {publisher.topic_name: type_name(publisher.msg_type)
                for publisher in node.publishers
                if publisher.topic_name not in RCLPY_TOPICS} == declared(PUBLISHER)
        parameter_services = f'/{interface.node}/'
        assert {absolute(service.srv_name): type_name(service.srv_type)
                for service in node.services
                if not absolute(service.srv_name).startswith(parameter_services)
                } == declared(SERVICE)
    finally:
        node.destroy_node()


def test_every_declared_type_imports_and_every_name_is_unique():
    for interface in NODE_INTERFACES.values():
        names = [(endpoint.kind, endpoint.name) for endpoint in interface.endpoints]
        assert len(names) == len(set(names)), interface.node
        for endpoint in interface.endpoints:
            assert endpoint.message_type.__name__ == endpoint.type_name.split('/')[-1]


def test_a_missing_name_is_refused_with_the_known_ones():
    with pytest.raises(KeyError, match="ik_node declares no 'leg_length'.*leg_lengths"):
        IK_NODE['leg_length']


def test_the_documentation_table_lists_every_endpoint_with_its_condition():
    table = markdown_table(FK_NODE)
    for endpoint in FK_NODE.endpoints:
        assert f'| `{endpoint.name}` | {endpoint.kind} | `{endpoint.type_name}` |' in table
    assert '(with `publish_tf`)' in table
