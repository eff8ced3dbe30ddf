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
The how-to guides and the example files they show name what the package really has.

Every command of a guide's ``bash`` blocks starts a program that exists (a console script of
the package, or a ROS or shell tool), gives a node only parameters it declares with values it
accepts, remaps only topics it has, and names files of ``config/`` and ``scripts/`` that exist;
``ros2 topic`` and ``ros2 service`` name a topic or service of a node with its type. The
example files for ros2_control (``config/ros2_control/``) and RViz
(``config/stewart_kinematics.rviz``) use the package's joint names, limits, home, topics, QoS
and frames. The runnable blocks themselves run in test_how_to_commands.py.
"""

import configparser
from pathlib import Path
import xml.etree.ElementTree as ElementTree

import doc_blocks
from numpy.testing import assert_allclose
import pytest
from stewart_kinematics import load_geometry
from stewart_kinematics.parameters import (ActuatorSettings, FkNodeSettings, FrameSettings,
                                           IkNodeSettings, MotionCueingNodeSettings,
                                           TelemetryBridgeNodeSettings, TrajectoryNodeSettings)
from stewart_kinematics.ros.interfaces import NODE_INTERFACES, PUBLISHER, SERVICE
import yaml

pytestmark = pytest.mark.core

ROOT = doc_blocks.ROOT
CONFIG = ROOT / 'config'
#: The settings class of each node: the parameters it declares.
NODE_SETTINGS = {'ik_node': IkNodeSettings, 'fk_node': FkNodeSettings,
                 'trajectory_node': TrajectoryNodeSettings,
                 'motion_cueing_node': MotionCueingNodeSettings,
                 'telemetry_bridge': TelemetryBridgeNodeSettings}
#: Parameters every rclpy node has besides the package's.
ROS_PARAMETERS = {'use_sim_time'}
#: Programs a guide may run that are not the package's: ROS 2's, and the shell's.
OTHER_PROGRAMS = {'ros2', 'rviz2', 'python', 'cp'}
#: The message type of each RViz display class the configuration uses.
RVIZ_DISPLAY_TYPES = {'rviz_default_plugins/MarkerArray': 'visualization_msgs/msg/MarkerArray',
                      'rviz_default_plugins/Pose': 'geometry_msgs/msg/PoseStamped'}
#: The JTC's topic for trajectories: ``/<controller name>/joint_trajectory``.
JTC = 'joint_trajectory_controller'


def console_scripts():
    """Return the package's console scripts, as setup.py declares them."""
    parser = configparser.ConfigParser()
    setup = (ROOT / 'setup.py').read_text(encoding='utf-8')
    scripts = setup.split("'console_scripts': [", 1)[1].split(']', 1)[0]
    lines = [line.strip().strip("',") for line in scripts.splitlines() if '=' in line]
    parser.read_string('[s]\n' + '\n'.join(lines))
    return set(parser['s'])


def shell_commands():
    """Return every command of every bash block of the how-tos: ``(page, words)``."""
    found = []
    for page in doc_blocks.how_to_pages():
        for block in doc_blocks.blocks(page, 'bash'):
            found += [(block.page, words) for words in doc_blocks.commands(block)]
    assert len(found) > 20, 'the how-tos have too few commands to be read right'
    return found


def repository_path(word: str):
    """Return the file of the repository a word names (``config/...``), or None."""
    for prefix in ('$SHARE/', '$(ros2 pkg prefix stewart_kinematics)/share/stewart_kinematics/'):
        word = word.removeprefix(prefix)
    if word.startswith(('config/', 'scripts/')):
        return ROOT / word
    return None


def parameters(path: Path, node: str = '') -> dict:
    """Return the parameters a node gets from a file: its ``/**`` and its own section."""
    sections = yaml.safe_load(path.read_text(encoding='utf-8'))
    found = {}
    for key in ('/**', node, f'/{node}'):
        found.update((sections.get(key) or {}).get('ros__parameters', {}))
    return found


def endpoint_names():
    """Every topic and service name of every node, without a leading slash: ``{name: types}``."""
    names = {}
    for interface in NODE_INTERFACES.values():
        for endpoint in interface.endpoints:
            names.setdefault(endpoint.name.lstrip('/'), set()).add(endpoint.type_name)
    return names


def test_every_program_is_the_packages_or_a_ros_tool():
    """A guide's command starts a console script of the package, or ROS 2's or the shell's."""
    scripts = console_scripts()
    assert {'ik_node', 'fk_node', 'trajectory_node', 'motion_cueing_node',
            'stewart_geometry', 'stewart_calibrate', 'stewart_cueing'} <= scripts
    for page, words in shell_commands():
        program = words[0].split('=', 1)[-1] if '=' in words[0] else words[0]
        program = program.removeprefix('$(')
        assert program in scripts or program in OTHER_PROGRAMS, f'{page}: {words}'
        if words[:2] == ('ros2', 'run') and words[2] == 'stewart_kinematics':
            assert words[3] in scripts, f'{page}: {words}'


def test_every_file_a_command_names_exists():
    """Every ``config/...`` and ``scripts/...`` a command names is in the repository."""
    named = 0
    for page, words in shell_commands():
        for word in words:
            for part in word.replace(')', ' ').replace('$(cat ', ' ').split():
                path = repository_path(part.split(':=', 1)[-1])
                if path is not None:
                    named += 1
                    assert path.is_file(), f'{page}: {part} does not exist'
    assert named > 20


def test_a_node_gets_only_parameters_it_declares_with_values_it_accepts():
    """Each ``-p name:=value`` of a node is one of its parameters, with a value it accepts."""
    checked = 0
    for page, words in shell_commands():
        if words[0] not in NODE_SETTINGS:
            continue
        specs = {spec.name: spec for spec in NODE_SETTINGS[words[0]].specs()}
        for option in doc_blocks.options(words, '-p'):
            name, value = option.split(':=', 1)
            if name in ROS_PARAMETERS:
                continue
            assert name in specs, f'{page}: {words[0]} has no parameter {name!r}'
            reason = specs[name].check(yaml.safe_load(value))
            assert not reason, f'{page}: {option}: {reason}'
            checked += 1
        for path in doc_blocks.options(words, '--params-file'):
            file = repository_path(path)
            if file is not None:
                unknown = set(parameters(file, words[0])) - set(specs)
                assert not unknown, f'{page}: {words[0]} does not declare {unknown} of {path}'
    assert checked >= 3


def test_a_node_is_remapped_only_on_topics_it_has():
    """Each ``-r name:=...`` of a node names one of its topics (or ``__ns``)."""
    remaps = 0
    for page, words in shell_commands():
        if words[0] not in NODE_INTERFACES:
            continue
        names = {endpoint.name for endpoint in NODE_INTERFACES[words[0]].endpoints}
        for option in doc_blocks.options(words, '-r'):
            name = option.split(':=', 1)[0]
            assert name in names | {'__ns', '__node'}, f'{page}: {words[0]} has no {name!r}'
            remaps += 1
    assert remaps >= 2


def test_ros2_topic_and_service_commands_name_the_nodes_topics_and_types():
    """``ros2 topic pub/echo``, ``ros2 service call`` and ``ros2 bag record`` name real ones."""
    names = endpoint_names()
    pages = {}
    for page, words in shell_commands():
        # A topic that a guide remaps a node's topic to is the user's (a simulator's IMU).
        targets = pages.setdefault(page, set())
        for option in doc_blocks.options(words, '-r'):
            targets.add(option.split(':=', 1)[1].lstrip('/'))
    for page, words in shell_commands():
        if words[:2] in (('ros2', 'topic'), ('ros2', 'service')):
            operands = [word for word in words[3:] if not word.startswith('-')]
            topic = operands[0].lstrip('/')
            if topic in pages[page]:
                continue
            assert topic in names, f'{page}: no node has {operands[0]}'
            if len(operands) > 1:
                assert operands[1] in names[topic], f'{page}: {operands[0]} is {names[topic]}'
        if words[:3] == ('ros2', 'bag', 'record'):
            topics = [word.lstrip('/') for word in words[3:] if word.startswith('/')]
            for topic in topics:
                assert topic in names or topic in pages[page], f'{page}: {topic}'


def example_limits():
    """Return the paper's platform with example_limits.yaml, as the ros2_control example."""
    files = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml']
    values = {**parameters(files[0]), **parameters(files[1])}
    return load_geometry(files), values


def test_controllers_example_uses_the_packages_joint_names():
    """The controllers' joints are the default ``joint_names``, in leg order."""
    controllers = yaml.safe_load(
        (CONFIG / 'ros2_control' / 'stewart_controllers.yaml').read_text(encoding='utf-8'))
    joint_names = list(ActuatorSettings().joint_names)
    manager = controllers['controller_manager']['ros__parameters']
    assert manager[JTC]['type'] == 'joint_trajectory_controller/JointTrajectoryController'
    for name in (JTC, 'leg_position_controller'):
        assert name in manager, name
        assert controllers[name]['ros__parameters']['joints'] == joint_names, name
    jtc = controllers[JTC]['ros__parameters']
    assert set(jtc['command_interfaces']) <= {'position', 'velocity'}
    assert jtc['state_interfaces'] == ['position', 'velocity']
    # leg_trajectory ends at rest and names every leg: the JTC's strict settings fit it.
    assert jtc['allow_partial_joints_goal'] is False
    assert jtc['allow_nonzero_velocity_at_trajectory_end'] is False
    # trajectory_node's leg_trajectory is the type the JTC subscribes to.
    leg_trajectory = NODE_INTERFACES['trajectory_node']['leg_trajectory']
    assert leg_trajectory.kind == PUBLISHER
    assert leg_trajectory.type_name == 'trajectory_msgs/msg/JointTrajectory'
    guide = (doc_blocks.HOW_TO / 'joint_trajectory_controller.md').read_text(encoding='utf-8')
    assert f'-r leg_trajectory:=/{JTC}/joint_trajectory' in guide


def test_urdf_example_fits_joint_names_limits_and_home():
    """The URDF's joints are ``joint_names``; stroke, speed and initial values the package's."""
    geometry, values = example_limits()
    offsets = ActuatorSettings().actuator_offsets
    joint_names = list(ActuatorSettings().joint_names)
    text = (CONFIG / 'ros2_control' / 'stewart_legs.urdf').read_text(encoding='utf-8')
    # Passed as a ROS parameter value (-p robot_description:="$(cat ...)"), which is YAML.
    assert ': ' not in text
    robot = ElementTree.fromstring(text)
    prismatic = [joint for joint in robot.iter('joint') if joint.get('type') == 'prismatic']
    assert [joint.get('name') for joint in prismatic] == joint_names
    for joint, offset in zip(prismatic, offsets):
        limit = joint.find('limit')
        assert_allclose([float(limit.get('lower')), float(limit.get('upper'))],
                        [geometry.leg_length_min - offset, geometry.leg_length_max - offset],
                        atol=1e-12)
        assert_allclose(float(limit.get('velocity')), values['leg_velocity_max'], atol=1e-12)
    control = robot.find('ros2_control')
    joints = control.findall('joint')
    assert [joint.get('name') for joint in joints] == joint_names
    for joint, home, offset in zip(joints, geometry.home_leg_lengths, offsets):
        assert [item.get('name') for item in joint.findall('command_interface')] == ['position']
        states = joint.findall('state_interface')
        assert [item.get('name') for item in states] == ['position', 'velocity']
        initial = states[0].find("param[@name='initial_value']")
        assert_allclose(float(initial.text), home - offset, atol=1e-6)


def rviz_displays():
    """Return the visualization manager of the shipped RViz configuration."""
    config = yaml.safe_load((CONFIG / 'stewart_kinematics.rviz').read_text(encoding='utf-8'))
    return config['Visualization Manager']


def test_rviz_configuration_shows_topics_the_nodes_publish_with_their_qos():
    """Each display's topic is a node's publisher of that type, with the declared QoS."""
    published = {}
    for interface in NODE_INTERFACES.values():
        for endpoint in interface.of_kind(PUBLISHER):
            published.setdefault(endpoint.name.lstrip('/'), []).append(endpoint)
    topics = []
    for display in rviz_displays()['Displays']:
        if 'Topic' not in display:
            continue
        topic = display['Topic']
        name = topic['Value'].lstrip('/')
        assert name in published, f'{display["Name"]}: no node publishes {topic["Value"]}'
        endpoints = [endpoint for endpoint in published[name]
                     if endpoint.type_name == RVIZ_DISPLAY_TYPES[display['Class']]]
        assert endpoints, f'{display["Name"]}: {topic["Value"]} is not {display["Class"]}'
        for endpoint in endpoints:
            qos = endpoint.qos
            assert topic['Reliability Policy'] == qos.reliability.replace('_', ' ').title()
            assert topic['Durability Policy'] == qos.durability.replace('_', ' ').title()
        topics.append(name)
    assert {'platform_markers', 'workspace_markers', 'estimated_pose_stamped',
            'cue_pose'} <= set(topics)


def test_rviz_configuration_is_in_the_base_frame_with_the_nodes_tf():
    """The fixed frame is the default ``base_frame``; the TF display shows the nodes' frames."""
    manager = rviz_displays()
    assert manager['Global Options']['Fixed Frame'] == FrameSettings().base_frame
    classes = [display['Class'] for display in manager['Displays']]
    assert 'rviz_default_plugins/TF' in classes
    tf_publishers = [name for name, interface in NODE_INTERFACES.items()
                     if any(endpoint.name == '/tf' for endpoint in interface.endpoints)]
    assert {'fk_node', 'ik_node'} <= set(tf_publishers)


def test_rviz_guide_names_the_configurations_topics():
    """The RViz guide's table names every topic the configuration shows."""
    guide = (doc_blocks.HOW_TO / 'rviz.md').read_text(encoding='utf-8')
    for display in rviz_displays()['Displays']:
        if 'Topic' in display:
            assert f'`{display["Topic"]["Value"]}`' in guide, display['Name']
    assert f'`{FrameSettings().base_frame}`' in guide


def test_services_in_the_guides_are_declared():
    """A service a guide calls is a node's declared service."""
    services = {endpoint.name for interface in NODE_INTERFACES.values()
                for endpoint in interface.of_kind(SERVICE)}
    for page, words in shell_commands():
        if words[:3] == ('ros2', 'service', 'call'):
            assert words[3].lstrip('/') in services, f'{page}: {words[3]}'
