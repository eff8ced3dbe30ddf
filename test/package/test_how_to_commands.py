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
The how-to guides' commands run as written.

Each ``bash`` block marked ``% runnable`` runs whole, in a scratch folder that sees
``config/`` and ``scripts/``, with the venv's console scripts first on ``PATH``, and exits 0
with the output its page describes; every option a guide gives a tool is one the tool has.
The joint_trajectory_controller guide's wiring runs too: trajectory_node started with the
guide's arguments, sent the guide's path, publishes on the controller's topic a trajectory
that passes the checks the Jazzy JointTrajectoryController makes of one it receives
(``validate_trajectory_msg``, rewritten here: ros2_control has no wheels to install), within
the example URDF's limits.
"""

import os
from pathlib import Path
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

import doc_blocks
import numpy as np
import pytest
import yaml

pytestmark = pytest.mark.process

ROOT = doc_blocks.ROOT
BIN = Path(sys.executable).parent
#: The package's command-line tools a guide may run (the nodes take --ros-args instead).
TOOLS = ('stewart_geometry', 'stewart_calibrate', 'stewart_cueing', 'stewart_workspace',
         'stewart_forces', 'stewart_payload', 'telemetry_sender')
#: The JTC's "at rest" at the last point: ``std::numeric_limits<float>::epsilon()``.
FLOAT_EPSILON = float(np.finfo(np.float32).eps)
JTC_TOPIC = '/joint_trajectory_controller/joint_trajectory'
#: What each runnable block's output must say, as its page says it: ``{page: [patterns]}``.
EXPECTED_OUTPUT = {'how-to/calibrate.md': [r'outliers: \[12, 31\]', r'wrote poses\.csv',
                                           r'calibrated +position +\d'],
                   'how-to/motion_cueing.md': [r'zero limit violations: 0'],
                   'how-to/simulator.md': [r'sent 101 packets of slalom to 127\.0\.0\.1:47800'],
                   'how-to/size_actuators.md': [
                       r'4 \| +223\.3 \(2\.000\) \| +0\.0 \(-\)',
                       r'beyond leg_velocity_max 0\.05 m/s', r'wrote forces\.png',
                       r'wrote braking_forces\.png', r'retimed to the leg speed and '
                       r'acceleration limits: 2\.99\d s', r'4 \| +167\.1 \(2\.997\)'],
                   'how-to/identify_payload.md': [
                       r'mass \(kg\) +20\.0055 +0\.0271', r'centre z \(mm\) +50\.689 +0\.588',
                       r'warnings: none', r'mass error: \+0\.006 kg',
                       r'centre of mass error \(mm\): -0\.17, -0\.04, \+0\.69'],
                   'how-to/own_platform.md': [r'Design: 6-3 \(legs 1 and 6, 2 and 3, 4 and 5',
                                              r'Condition number at home: 6\.514\n',
                                              r'Warnings: none']}


def runnable_blocks():
    """Return every runnable block of the how-tos."""
    found = [block for page in doc_blocks.how_to_pages()
             for block in doc_blocks.blocks(page, 'bash') if block.runnable]
    assert len(found) >= 3, 'fewer runnable blocks than the guides have'
    return found


def scratch_environment(tmp_path):
    """Link config/ and scripts/ into a scratch folder; return an environment, venv first."""
    for name in ('config', 'scripts'):
        (tmp_path / name).symlink_to(ROOT / name)
    env = dict(os.environ)
    env['PATH'] = f'{BIN}{os.pathsep}{env.get("PATH", "")}'
    env['MPLBACKEND'] = 'Agg'
    return env


@pytest.mark.parametrize('page', sorted({block.page for block in runnable_blocks()}))
def test_runnable_blocks_exit_0_with_the_output_their_page_describes(tmp_path, page):
    """A page's runnable blocks, in order, in one scratch folder: each exits 0."""
    env = scratch_environment(tmp_path)
    output = ''
    for block in runnable_blocks():
        if block.page != page:
            continue
        run = subprocess.run(['bash', '-e', '-o', 'pipefail', '-c', block.text], cwd=tmp_path,
                             env=env, capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, f'{page}:\n{block.text}\n{run.stdout}\n{run.stderr}'
        output += run.stdout
    for pattern in EXPECTED_OUTPUT.get(page, ()):
        assert re.search(pattern, output), f'{page}: no {pattern!r} in\n{output}'


def tool_commands():
    """Return every command of the how-tos that runs a tool of the package: ``(page, words)``."""
    return [(block.page, words) for page in doc_blocks.how_to_pages()
            for block in doc_blocks.blocks(page, 'bash')
            for words in doc_blocks.commands(block) if words[0] in TOOLS]


def test_every_option_a_guide_gives_a_tool_is_one_it_has():
    """Each ``--option`` of a tool's command is in the tool's ``--help``."""
    helps = {}
    commands = tool_commands()
    assert {words[0] for _, words in commands} >= {'stewart_calibrate', 'stewart_cueing',
                                                   'stewart_geometry'}
    for page, words in commands:
        if words[0] not in helps:
            run = subprocess.run([str(BIN / words[0]), '--help'], capture_output=True,
                                 text=True, timeout=60)
            assert run.returncode == 0, run.stderr
            helps[words[0]] = set(re.findall(r'--[\w-]+', run.stdout))
        for word in words[1:]:
            if word.startswith('--'):
                assert word in helps[words[0]], f'{page}: {words[0]} has no {word}'


def guide_text():
    """Return the text of the joint_trajectory_controller guide."""
    return (doc_blocks.HOW_TO / 'joint_trajectory_controller.md').read_text(encoding='utf-8')


def guide_commands():
    """Return the JTC guide's trajectory_node arguments and its path: topic, type, fields."""
    page = doc_blocks.HOW_TO / 'joint_trajectory_controller.md'
    commands = [words for block in doc_blocks.blocks(page, 'bash')
                for words in doc_blocks.commands(block)]
    node = next(words for words in commands if words[0] == 'trajectory_node')
    publish = next(words for words in commands if words[:3] == ('ros2', 'topic', 'pub'))
    arguments = [word.replace('$SHARE/', f'{ROOT}/') for word in node[1:]]
    return arguments, publish[4], publish[5], yaml.safe_load(publish[6])


def set_fields(message, values):
    """Set a message's fields from the dictionary ``ros2 topic pub`` reads (YAML)."""
    for name, value in values.items():
        current = getattr(message, name)
        if isinstance(value, dict):
            set_fields(current, value)
        elif isinstance(value, list):
            item_type = type(message).get_fields_and_field_types()[name]
            item_class = message_class(item_type[len('sequence<'):-1])
            items = []
            for item_values in value:
                item = item_class()
                set_fields(item, item_values)
                items.append(item)
            setattr(message, name, items)
        else:
            setattr(message, name, type(current)(value))


def message_class(type_name):
    """Return the message class of ``package/Name`` or ``package/msg/Name``."""
    import importlib
    parts = type_name.split('/')
    return getattr(importlib.import_module(f'{parts[0]}.msg'), parts[-1])


def jtc_refusals(message, joints, allow_nonzero_end_velocity=False):
    """
    Return why the Jazzy JointTrajectoryController would refuse ``message``; empty: accepted.

    Rewritten from ``JointTrajectoryController::validate_trajectory_msg`` (ros2_controllers
    4.x) for a controller with ``allow_partial_joints_goal: false``, position command
    interfaces and no effort: every joint named once and known, at least one point,
    ``time_from_start`` strictly increasing, positions for every joint, velocities and
    accelerations empty or for every joint, no effort, and the last point at rest (no velocity
    above a float's epsilon, as the controller compares).
    """
    reasons = []
    names = list(message.joint_names)
    if len(names) != len(joints) or set(names) != set(joints) or len(set(names)) != len(names):
        reasons.append(f'joint names {names} are not the controller joints {joints}')
    if not message.points:
        reasons.append('empty trajectory')
    previous = None
    for index, point in enumerate(message.points):
        time = point.time_from_start.sec + point.time_from_start.nanosec * 1e-9
        if previous is not None and time <= previous:
            reasons.append(f'point {index}: time_from_start not increasing')
        previous = time
        if len(point.positions) != len(names):
            reasons.append(f'point {index}: {len(point.positions)} positions')
        for field in ('velocities', 'accelerations'):
            if len(getattr(point, field)) not in (0, len(names)):
                reasons.append(f'point {index}: {field} of the wrong size')
        if len(point.effort):
            reasons.append(f'point {index}: effort is not supported')
    if message.points and not allow_nonzero_end_velocity:
        if any(abs(velocity) > FLOAT_EPSILON for velocity in message.points[-1].velocities):
            reasons.append('velocity of the last point is not zero')
    return reasons


def urdf_limits():
    """Return the example URDF's position limits of each joint: ``{name: (lower, upper)}``."""
    robot = ElementTree.parse(ROOT / 'config' / 'ros2_control' / 'stewart_legs.urdf').getroot()
    return {joint.get('name'): (float(joint.find('limit').get('lower')),
                                float(joint.find('limit').get('upper')))
            for joint in robot.iter('joint') if joint.get('type') == 'prismatic'}


def test_jtc_refusals_refuse_what_the_controller_refuses():
    """The rewritten checks refuse a moving end, a missing joint and times out of order."""
    from builtin_interfaces.msg import Duration
    from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint
    joints = [f'leg_{leg}' for leg in range(1, 7)]
    message = JointTrajectory(joint_names=joints, points=[
        JointTrajectoryPoint(positions=[0.7] * 6, velocities=[0.0] * 6,
                             time_from_start=Duration(sec=0)),
        JointTrajectoryPoint(positions=[0.71] * 6, velocities=[0.0] * 6,
                             time_from_start=Duration(sec=1))])
    assert jtc_refusals(message, joints) == []
    message.points[-1].velocities = [1e-17] + [0.0] * 5     # a rounding error: at rest
    assert jtc_refusals(message, joints) == []
    message.points[-1].velocities = [1e-6] + [0.0] * 5
    assert jtc_refusals(message, joints) == ['velocity of the last point is not zero']
    assert jtc_refusals(message, joints, allow_nonzero_end_velocity=True) == []
    message.points[-1].velocities = [0.0] * 6
    message.points[-1].time_from_start = Duration(sec=0)
    assert jtc_refusals(message, joints) == ['point 1: time_from_start not increasing']
    message.points[-1].time_from_start = Duration(sec=1)
    message.joint_names = joints[:5] + ['leg_7']
    assert len(jtc_refusals(message, joints)) == 1


def test_trajectory_node_as_the_guide_starts_it_feeds_the_jtc(client, start_node):
    """
    The guide's trajectory_node and path: one trajectory on the JTC's topic that it accepts.

    The joints are the example controller's, every position within the example URDF's limits,
    and the path's last waypoint reached.
    """
    from trajectory_msgs.msg import JointTrajectory
    arguments, topic, type_name, values = guide_commands()
    assert f'leg_trajectory:={JTC_TOPIC}' in arguments
    controllers = yaml.safe_load((ROOT / 'config' / 'ros2_control' /
                                  'stewart_controllers.yaml').read_text(encoding='utf-8'))
    jtc = controllers['joint_trajectory_controller']['ros__parameters']
    node = start_node('trajectory_node', arguments)
    received = []
    client.node.create_subscription(JointTrajectory, JTC_TOPIC, received.append, 10)
    message = message_class(type_name)()
    set_fields(message, values)
    publisher = client.node.create_publisher(type(message), topic, 10)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and client.node.count_publishers(JTC_TOPIC) >= 1,
                f'trajectory_node on {topic} and {JTC_TOPIC}', [node])
    publisher.publish(message)
    client.wait(lambda: received, f'a trajectory on {JTC_TOPIC}', [node])
    trajectory = received[0]
    assert jtc_refusals(trajectory, jtc['joints'],
                        jtc['allow_nonzero_velocity_at_trajectory_end']) == []
    limits = urdf_limits()
    positions = np.array([point.positions for point in trajectory.points])
    lower = np.array([limits[name][0] for name in trajectory.joint_names])
    upper = np.array([limits[name][1] for name in trajectory.joint_names])
    assert np.all((positions >= lower) & (positions <= upper))
    assert len(trajectory.points) > len(values['poses'])
    # The log line the guide shows, its '...' standing for any text.
    shown = re.search(r'logs `(pose_path: [^`]+)`', ' '.join(guide_text().split())).group(1)
    pattern = '.*'.join(re.escape(part) for part in shown.split('...'))
    client.wait(lambda: re.search(pattern, node.output()), f'the log line {shown!r}', [node])
