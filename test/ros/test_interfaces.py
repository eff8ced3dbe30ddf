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
Each node offers exactly the topics, services and actions its ros/interfaces.py declaration names.

With the QoS declared there: each publisher's, subscription's and service's actual profile is
the declared one (at a queue_depth other than any fixed depth, so a depth taken from elsewhere
shows).
"""

from helpers import free_udp_port
import pytest

from stewart_kinematics.ros import interfaces
from stewart_kinematics.ros.interfaces import (
    ACTION,
    FK_NODE,
    IK_NODE,
    markdown_table,
    MOCK_PLATFORM,
    MOTION_CUEING_NODE,
    NODE_INTERFACES,
    PUBLISHER,
    Qos,
    SERVICE,
    SUBSCRIPTION,
    TELEMETRY_BRIDGE,
    TRAJECTORY_NODE,
)

pytestmark = pytest.mark.node

#: What rclpy gives every node: its log, parameter events and parameter services.
RCLPY_TOPICS = {'/rosout', '/parameter_events'}
#: The queue_depth the nodes run with here: no declared fixed depth is 7.
QUEUE_DEPTH = 7


def node_class(name):
    """Return the node class of a node name."""
    from stewart_kinematics.ros.fk_node import FkNode
    from stewart_kinematics.ros.ik_node import IkNode
    from stewart_kinematics.ros.mock_platform import MockPlatform
    from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
    from stewart_kinematics.ros.telemetry_bridge import TelemetryBridge
    from stewart_kinematics.ros.trajectory_node import TrajectoryNode
    return {'ik_node': IkNode, 'fk_node': FkNode, 'trajectory_node': TrajectoryNode,
            'motion_cueing_node': MotionCueingNode, 'mock_platform': MockPlatform,
            'telemetry_bridge': TelemetryBridge}[name]


def absolute(name):
    """Return a declared name as the node in the root namespace has it."""
    return name if name.startswith('/') else '/' + name


@pytest.mark.parametrize('interface', [IK_NODE, FK_NODE, TRAJECTORY_NODE, MOTION_CUEING_NODE,
                                       MOCK_PLATFORM, TELEMETRY_BRIDGE],
                         ids=lambda interface: interface.node)
def test_a_node_has_exactly_its_declared_topics_and_services(ros, config_directory, tmp_path,
                                                             interface):
    """Every optional endpoint on: the node's publishers, subscriptions, services, actions."""
    from rclpy.action import get_action_server_names_and_types_by_node
    arguments = ['--ros-args']
    for name in ('paper_platform.yaml', 'solver.yaml', 'table3_ramp.yaml'):
        arguments += ['--params-file', str(config_directory / name)]
    # The node's own section, last: it wins over the files' sections for the node.
    depth_file = tmp_path / 'queue_depth.yaml'
    depth_file.write_text(f'{interface.node}:\n  ros__parameters:\n'
                          f'    queue_depth: {QUEUE_DEPTH}\n', encoding='utf-8')
    arguments += ['--params-file', str(depth_file)]
    arguments += ['-p', 'publish_commanded_tf:=true'] if interface is IK_NODE else []
    if interface is TELEMETRY_BRIDGE:   # a free port: two test workers never collide
        arguments += ['-p', f'telemetry_port:={free_udp_port()}']
    node = node_class(interface.node)(cli_args=arguments)
    try:
        assert node.get_parameter('queue_depth').value == QUEUE_DEPTH

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
        # An action server shows in the graph as the action (its services and topics are hidden).
        assert {name: types[0] for name, types in get_action_server_names_and_types_by_node(
            node, node.get_name(), node.get_namespace())} == declared(ACTION)

        def actual(entities, name_of):
            return {name_of(entity): entity.qos_profile for entity in entities}

        def declared_qos(kind):
            return {absolute(endpoint.name): endpoint.qos.profile(QUEUE_DEPTH)
                    for endpoint in interface.of_kind(kind)}

        assert actual(node.subscriptions, lambda entity: entity.topic_name) == declared_qos(
            SUBSCRIPTION)
        assert {name: profile for name, profile in actual(
            node.publishers, lambda entity: entity.topic_name).items()
            if name not in RCLPY_TOPICS} == declared_qos(PUBLISHER)
        assert {name: profile for name, profile in actual(
            node.services, lambda entity: absolute(entity.srv_name)).items()
            if not name.startswith(parameter_services)} == declared_qos(SERVICE)
    finally:
        node.destroy_node()


def test_an_override_in_one_node_leaves_the_next_node_its_declared_qos(ros, config_directory):
    """
    Give each endpoint a profile of its own: rclpy applies qos_overrides to it, in place.

    A profile shared by every node of a process (the /tf one was a module constant) took one
    node's override into the next node's publisher; each endpoint now gets a profile of its own.
    """
    from stewart_kinematics.ros.fk_node import FkNode
    base = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml')]
    first = FkNode(cli_args=base + ['-p', 'qos_overrides./tf.publisher.depth:=5'])
    second = FkNode(cli_args=base + ['-r', '__node:=fk_node_b'])
    try:
        def tf_depth(node):
            return next(publisher.qos_profile.depth for publisher in node.publishers
                        if publisher.topic_name == '/tf')
        assert tf_depth(first) == 5
        assert tf_depth(second) == interfaces.TF.depth == 100
    finally:
        first.destroy_node()
        second.destroy_node()


def test_a_declared_qos_prints_itself_and_builds_its_profile(ros):
    """What the documentation shows, and the rclpy profile the nodes create endpoints with."""
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
    assert str(interfaces.QUEUE) == 'reliable, keep last `queue_depth`'
    assert str(interfaces.TF_STATIC) == (
        'reliable, transient local, keep last 1 (as tf2_ros static broadcasts)')
    assert str(Qos(reliability='best_effort', history='keep_all')) == 'best effort, keep all'
    assert interfaces.QUEUE.profile(queue_depth=3) == QoSProfile(
        depth=3, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
        history=HistoryPolicy.KEEP_LAST)
    assert interfaces.LATCHED.profile(queue_depth=3) == QoSProfile(
        depth=1, reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST)
    from rclpy.qos import qos_profile_services_default
    assert interfaces.SERVICE_QOS.profile() == qos_profile_services_default
    with pytest.raises(ValueError, match='give queue_depth'):
        interfaces.QUEUE.profile()


@pytest.mark.parametrize('changes, message', [
    ({'reliability': 'reliabel'}, 'reliability must be one of reliable, best_effort'),
    ({'durability': 'latched'}, 'durability must be one of volatile, transient_local'),
    ({'depth': 0}, 'depth must be a positive integer'),
    ({'depth': True}, 'depth must be a positive integer'),
    ({'depth': 'queue'}, 'depth must be a positive integer'),
])
def test_a_qos_declaration_refuses_what_rclpy_would_not_take(changes, message):
    with pytest.raises(ValueError, match=message):
        Qos(**changes)


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
