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
The robot-stack topics across real processes, and two platforms side by side in two namespaces.

``ik_node`` and ``fk_node`` run as console-script processes (conftest's ``start_node``), fk_node
fed by ik_node's ``joint_commands`` as its ``joint_states`` (``-r joint_states:=joint_commands``),
as the README chains them; the test's own rclpy node (conftest's ``client``) publishes stamped
poses and twists and checks ``joint_commands``, ``estimated_pose_stamped``, ``leg_velocities``,
``estimated_twist`` and ``platform_markers``. The expected numbers come from the geometry read
from the YAML files with PyYAML and the leg formula written out below in numpy, and the leg
velocities from a finite difference of that formula: nothing is shared with the package's code.
"""

import math

from builtin_interfaces.msg import Time
from geometry_msgs.msg import Pose, PoseStamped, Twist
from helpers import CLIENT_DEPTH, pose_message, Recorder, SETTLE_TIME, stop_cleanly
import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import (
    quaternion_matrix,
    rotation_vector_matrix,
    rotation_zyx as rotation_matrix,
)
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Header
from visualization_msgs.msg import MarkerArray
import yaml

pytestmark = pytest.mark.process

#: The shipped base_frame of config/paper_platform.yaml.
BASE_FRAME = 'stewart_base'
LEG_NAMES = [f'leg_{leg}' for leg in range(1, 7)]
#: Rows 3 and 8 of the paper's Table 3: X, Y, Z in metres, alpha, beta, gamma in radians.
POSE_A = np.array([0.03, 0.045, 0.4625, math.radians(4.5), math.radians(-4.5), math.radians(6)])
POSE_B = np.array([0.08, 0.12, 0.5125, math.radians(12), math.radians(-12), math.radians(16)])
#: A platform twist: m/s, then rad/s, base frame.
TWIST = np.array([0.1, -0.2, 0.05, 0.3, -0.1, 0.2])
#: Step of the central difference that checks leg_velocities, seconds.
DIFFERENCE_STEP = 1e-6


def read_geometry(path):
    """Return the base and platform joints (6, 3) of a parameter file's ``/**`` section."""
    with open(path, encoding='utf-8') as stream:
        parameters = yaml.safe_load(stream)['/**']['ros__parameters']
    return (np.reshape(parameters['base_joints'], (6, 3)),
            np.reshape(parameters['platform_joints'], (6, 3)))


def reference_lengths(geometry, position, rotation):
    """Leg lengths ``l_i = |position + R p_i - b_i|`` in metres."""
    base_joints, platform_joints = geometry
    return np.linalg.norm(position + platform_joints @ rotation.T - base_joints, axis=1)


def pose_lengths(geometry, pose):
    """Leg lengths of a pose ``[X, Y, Z, alpha, beta, gamma]``."""
    return reference_lengths(geometry, pose[:3], rotation_matrix(*pose[3:]))


def finite_difference_leg_velocities(geometry, pose, twist):
    """Rates of change of the leg lengths, by a central difference along the twist's motion."""
    position, rotation = pose[:3], rotation_matrix(*pose[3:])
    h = DIFFERENCE_STEP

    def lengths_after(dt):
        return reference_lengths(geometry, position + twist[:3] * dt,
                                 rotation_vector_matrix(twist[3:] * dt) @ rotation)
    return (lengths_after(h) - lengths_after(-h)) / (2.0 * h)


def stamped(pose, seconds, nanoseconds, frame=BASE_FRAME):
    """geometry_msgs/msg/PoseStamped with a recognisable stamp."""
    return PoseStamped(header=Header(frame_id=frame, stamp=Time(sec=seconds, nanosec=nanoseconds)),
                       pose=pose_message(pose))


def assert_pose(message, pose, what):
    """Check a Pose against ``[X, Y, Z, alpha, beta, gamma]`` to 1e-9 m and 1e-9 rad."""
    p, o = message.position, message.orientation
    assert_allclose([p.x, p.y, p.z], pose[:3], rtol=0.0, atol=1e-9, err_msg=f'{what}: position')
    assert_allclose(quaternion_matrix(o.x, o.y, o.z, o.w), rotation_matrix(*pose[3:]),
                    rtol=0.0, atol=1e-9, err_msg=f'{what}: orientation')


def stamp_of(message):
    """Return ``(sec, nanosec)`` of a message's header."""
    return (message.header.stamp.sec, message.header.stamp.nanosec)


def endpoints(endpoint_infos):
    """Return ``{(namespace, name)}`` of the nodes of a list of TopicEndpointInfo."""
    return {(info.node_namespace, info.node_name) for info in endpoint_infos}


class Chain(Recorder):
    """ik_node and fk_node as processes, chained by joint_commands, and the client's endpoints."""

    def __init__(self, client, start_node, config_directory):
        """Start both nodes; topics are subscribed and advertised with :meth:`subscribe`."""
        files = ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
                 '--params-file', str(config_directory / 'solver.yaml')]
        super().__init__(client, [
            start_node('ik_node', files),
            start_node('fk_node', files + ['-r', 'joint_states:=joint_commands',
                                           '-r', 'leg_lengths:=unused_lengths']),
        ])

    def connect(self):
        """Wait until every endpoint matches and fk_node reads joint_commands, then settle."""
        graph = self.client.node

        def connected():
            return (self.matched()
                    and ('/', 'fk_node') in endpoints(
                        graph.get_subscriptions_info_by_topic('/joint_commands'))
                    and ('/', 'ik_node') in endpoints(
                        graph.get_publishers_info_by_topic('/joint_commands')))

        self.client.wait(connected, 'ik_node and fk_node chained and matched', self.nodes)
        self.client.spin_for(SETTLE_TIME)


@pytest.fixture
def chain(client, start_node, config_directory):
    """Start the ik_node -> joint_commands -> fk_node chain."""
    return Chain(client, start_node, config_directory)


@pytest.fixture
def paper_geometry(config_directory):
    """Joints of config/paper_platform.yaml, read with PyYAML."""
    return read_geometry(config_directory / 'paper_platform.yaml')


def test_stamp_goes_from_pose_through_joint_commands_to_estimated_pose(chain, paper_geometry):
    """
    A stamped pose's stamp reaches joint_commands and, through fk_node, estimated_pose_stamped.

    Two poses with two stamps (the second with an empty frame, which counts as base_frame):
    joint_commands names leg_1..leg_6 with the reference lengths (1e-12 m) and the pose's stamp;
    estimated_pose_stamped has the same stamp, frame base_frame and the pose (1e-9).
    """
    chain.subscribe(JointState, 'joint_commands')
    chain.subscribe(PoseStamped, 'estimated_pose_stamped')
    chain.advertise(PoseStamped, 'target_pose_stamped')
    chain.connect()
    inputs = [(POSE_A, (123, 456), BASE_FRAME), (POSE_B, (124, 789000), '')]

    for index, (pose, (seconds, nanoseconds), frame) in enumerate(inputs):
        chain.publishers['target_pose_stamped'].publish(
            stamped(pose, seconds, nanoseconds, frame))
        chain.wait_for('estimated_pose_stamped', index + 1)
    # joint_commands reaches this client on its own subscription: under load, after fk_node's
    # estimate of it.
    chain.wait_for('joint_commands', len(inputs))

    commands = chain.received['joint_commands']
    estimates = chain.received['estimated_pose_stamped']
    assert (len(commands), len(estimates)) == (2, 2)
    for (pose, stamp, _), command, estimate in zip(inputs, commands, estimates):
        assert list(command.name) == LEG_NAMES
        assert_allclose(command.position, pose_lengths(paper_geometry, pose), rtol=0.0,
                        atol=1e-12)
        assert list(command.velocity) == []
        assert stamp_of(command) == stamp
        assert stamp_of(estimate) == stamp
        assert estimate.header.frame_id == BASE_FRAME
        assert_pose(estimate.pose, pose, f'estimated_pose_stamped of stamp {stamp}')
    for node in chain.nodes:
        stop_cleanly(node)


def test_twist_gives_leg_velocities_and_fk_node_gives_it_back(chain, paper_geometry):
    """
    target_twist at the last pose -> leg_velocities, equal to a finite difference of the IK.

    fk_node turns those leg velocities back into the twist on estimated_twist, at the pose it
    estimated from joint_commands.
    """
    chain.subscribe(PoseStamped, 'estimated_pose_stamped')
    chain.subscribe(Float64MultiArray, 'leg_velocities')
    chain.subscribe(Twist, 'estimated_twist')
    chain.advertise(PoseStamped, 'target_pose_stamped')
    chain.advertise(Twist, 'target_twist')
    chain.connect()
    chain.publishers['target_pose_stamped'].publish(stamped(POSE_B, 7, 0))
    chain.wait_for('estimated_pose_stamped', 1)

    twist = Twist()
    twist.linear.x, twist.linear.y, twist.linear.z = TWIST[:3]
    twist.angular.x, twist.angular.y, twist.angular.z = TWIST[3:]
    chain.publishers['target_twist'].publish(twist)
    chain.wait_for('leg_velocities', 1)
    chain.wait_for('estimated_twist', 1)

    velocities = chain.received['leg_velocities']
    assert len(velocities) == 1
    assert [(d.label, d.size) for d in velocities[0].layout.dim] == [('leg', 6)]
    expected = finite_difference_leg_velocities(paper_geometry, POSE_B, TWIST)
    assert np.max(np.abs(expected)) > 0.01, 'the twist should move the legs'
    assert_allclose(velocities[0].data, expected, rtol=0.0, atol=1e-8)
    back = chain.received['estimated_twist'][0]
    assert_allclose([back.linear.x, back.linear.y, back.linear.z,
                     back.angular.x, back.angular.y, back.angular.z], TWIST, rtol=0.0, atol=1e-9)
    for node in chain.nodes:
        stop_cleanly(node)


def test_platform_markers_arrive_as_a_marker_array(chain, paper_geometry):
    """platform_markers: base, platform and legs of the commanded pose, in base_frame."""
    chain.subscribe(MarkerArray, 'platform_markers')
    chain.advertise(PoseStamped, 'target_pose_stamped')
    chain.connect()
    chain.publishers['target_pose_stamped'].publish(stamped(POSE_A, 42, 17))
    chain.wait_for('platform_markers', 1)

    base, platform, legs = chain.received['platform_markers'][0].markers
    base_joints, platform_joints = paper_geometry
    for marker in (base, platform, legs):
        assert marker.header.frame_id == BASE_FRAME
        assert stamp_of(marker) == (42, 17)
        assert marker.ns == 'stewart_platform'
    assert [base.id, platform.id, legs.id] == [0, 1, 2]
    assert_allclose([[p.x, p.y, p.z] for p in base.points[:6]], base_joints, atol=1e-12)
    rotation = rotation_matrix(*POSE_A[3:])
    assert_allclose([[p.x, p.y, p.z] for p in platform.points[:6]],
                    POSE_A[:3] + platform_joints @ rotation.T, rtol=0.0, atol=1e-12)
    bottoms = np.array([[p.x, p.y, p.z] for p in legs.points[0::2]])
    tops = np.array([[p.x, p.y, p.z] for p in legs.points[1::2]])
    assert_allclose(bottoms, base_joints, atol=1e-12)
    assert_allclose(np.linalg.norm(tops - bottoms, axis=1), pose_lengths(paper_geometry, POSE_A),
                    rtol=0.0, atol=1e-12)
    for node in chain.nodes:
        stop_cleanly(node)


def platform_b_file(path, paper_geometry):
    """
    Write a second platform's parameter file: another geometry, home and base frame.

    The paper's joints with the base 10 % wider and platform joint 3 at z = 0.275 m (the
    symmetric platform the README mentions), home at z = 0.45 m.
    """
    base_joints, platform_joints = paper_geometry
    base_joints = base_joints * 1.1
    platform_joints = platform_joints.copy()
    platform_joints[2, 2] = 0.275
    parameters = {
        'base_joints': [float(v) for v in base_joints.ravel()],
        'platform_joints': [float(v) for v in platform_joints.ravel()],
        'home_position': [0.0, 0.0, 0.45],
        'base_frame': 'platform_b_base',
    }
    path.write_text(yaml.safe_dump({'/**': {'ros__parameters': parameters}}))
    return base_joints, platform_joints


def test_two_platforms_run_side_by_side_in_two_namespaces(client, start_node, config_directory,
                                                          paper_geometry, tmp_path):
    """
    ik_node and fk_node in /platform_a (the paper's platform) and /platform_b (another one).

    Each namespace answers its own pose with its own platform's leg lengths (to 1e-12 m) and
    estimated pose (1e-9); each topic is served by its own namespace's node only, nothing
    reaches the other namespace or the root namespace.
    """
    geometry_b_file = tmp_path / 'platform_b.yaml'
    geometries = {'platform_a': paper_geometry,
                  'platform_b': platform_b_file(geometry_b_file, paper_geometry)}
    files = {'platform_a': config_directory / 'paper_platform.yaml',
             'platform_b': geometry_b_file}
    poses = {'platform_a': POSE_A, 'platform_b': POSE_B}
    nodes, received, subscriptions, publishers = [], {}, [], {}
    for namespace, path in files.items():
        arguments = ['--ros-args', '--params-file', str(path), '--params-file',
                     str(config_directory / 'solver.yaml'), '-r', f'__ns:=/{namespace}']
        nodes += [start_node('ik_node', arguments), start_node('fk_node', arguments)]
    for namespace in ('platform_a', 'platform_b', ''):
        for message_type, topic in ((Float64MultiArray, 'leg_lengths'),
                                    (Pose, 'estimated_pose')):
            name = f'{namespace}/{topic}'.lstrip('/')
            received[name] = []
            subscriptions.append(client.node.create_subscription(
                message_type, '/' + name, received[name].append, CLIENT_DEPTH))
    for namespace in poses:
        publishers[namespace] = client.node.create_publisher(
            Pose, f'/{namespace}/target_pose', CLIENT_DEPTH)

    def served(namespace):
        graph = client.node
        own = {(f'/{namespace}', 'ik_node')}
        return (endpoints(graph.get_subscriptions_info_by_topic(f'/{namespace}/target_pose'))
                == own
                and endpoints(graph.get_publishers_info_by_topic(f'/{namespace}/leg_lengths'))
                == own
                and (f'/{namespace}', 'fk_node') in endpoints(
                    graph.get_subscriptions_info_by_topic(f'/{namespace}/leg_lengths'))
                and endpoints(graph.get_publishers_info_by_topic(f'/{namespace}/estimated_pose'))
                == {(f'/{namespace}', 'fk_node')})

    client.wait(lambda: served('platform_a') and served('platform_b')
                and all(p.get_subscription_count() == 1 for p in publishers.values())
                and all(s.get_publisher_count() >= 1 for s in subscriptions[:4]),
                'both namespaces served by their own nodes', nodes)
    client.spin_for(SETTLE_TIME)

    for namespace, pose in poses.items():
        publishers[namespace].publish(pose_message(pose))
    client.wait(lambda: all(received[f'{n}/estimated_pose'] and received[f'{n}/leg_lengths']
                            for n in poses), 'leg lengths and pose in both namespaces', nodes)
    # A message that crossed namespaces would come with these; absence has no other deadline.
    client.spin_for(SETTLE_TIME)

    for namespace, pose in poses.items():
        lengths = received[f'{namespace}/leg_lengths']
        estimates = received[f'{namespace}/estimated_pose']
        assert (len(lengths), len(estimates)) == (1, 1), namespace
        assert_allclose(lengths[0].data, pose_lengths(geometries[namespace], pose), rtol=0.0,
                        atol=1e-12, err_msg=f'{namespace}/leg_lengths')
        assert_pose(estimates[0], pose, f'{namespace}/estimated_pose')
    other = pose_lengths(geometries['platform_a'], POSE_B)
    assert np.min(np.abs(other - pose_lengths(geometries['platform_b'], POSE_B))) > 5e-4, (
        'the two platforms should give different lengths for every leg')
    assert received['leg_lengths'] == [] and received['estimated_pose'] == []
    for node in nodes:
        stop_cleanly(node)
