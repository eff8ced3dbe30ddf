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

"""The README stays true: its tables, commands, files and numbers match the code."""

from pathlib import Path
import re

from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import parameters
from stewart_kinematics.parameters import load_geometry

pytestmark = pytest.mark.node

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / 'README.md').read_text(encoding='utf-8')


@pytest.mark.parametrize('specs', [
    parameters.GEOMETRY_PARAMETERS, parameters.SOLVER_PARAMETERS,
    parameters.FRAME_PARAMETERS, parameters.MARKER_PARAMETERS,
    parameters.QUEUE_PARAMETERS, parameters.RAMP_PARAMETERS,
    parameters.ASSEMBLY_MODE_PARAMETERS, parameters.ACTUATOR_PARAMETERS,
    parameters.MOTION_PARAMETERS, parameters.STREAMING_PARAMETERS,
    parameters.WORKSPACE_PARAMETERS,
], ids=['geometry', 'solver', 'frame', 'marker', 'queue', 'ramp', 'assembly_mode', 'actuator',
        'motion', 'streaming', 'workspace'])
def test_parameter_tables_match_the_declarations(specs):
    """Each parameter table in the README is the one generated from the specs."""
    assert parameters.markdown_table(specs) in README, (
        'README.md is out of date: run .venv/bin/python scripts/update_readme_tables.py')


def test_the_two_commands_exist_and_are_executable():
    """The README's two commands are scripts in the repository, and CI runs the test one."""
    for command in ('scripts/run_demo.sh', 'scripts/run_tests.sh'):
        assert f'{command}' in README
        assert (ROOT / command).is_file()
        assert (ROOT / command).stat().st_mode & 0o111, command
    assert 'scripts/run_tests.sh' in (ROOT / '.ci' / 'run').read_text(encoding='utf-8')


def test_linked_files_exist():
    """Every relative link in the README points to a file of the repository."""
    links = re.findall(r'\]\(((?!https?:)[^)#]+)\)', README)
    assert links
    for link in links:
        assert (ROOT / link).exists(), link


def test_console_scripts_named_in_the_readme_are_declared():
    """ik_node, fk_node, trajectory_node (ros/) and ramp_demo (tools/) are console scripts."""
    setup = (ROOT / 'setup.py').read_text(encoding='utf-8')
    for script in ('ik_node', 'fk_node', 'trajectory_node', 'ramp_demo'):
        assert f'`{script}`' in README
        pattern = rf"'{script} = stewart_kinematics\.(ros|tools)\.{script}:main'"
        assert re.search(pattern, setup), script


def test_leg_lengths_example_is_the_home_pose():
    """The ros2 topic pub example sends the home pose's leg lengths, to 1e-9 m."""
    example = re.search(r'Float64MultiArray \\\n\s+"\{data: \[([^\]]+)\]\}"', README)
    assert example, 'leg_lengths example not found'
    lengths = [float(value) for value in example.group(1).split(',')]
    geometry = load_geometry(ROOT / 'config' / 'paper_platform.yaml')
    assert_allclose(lengths, geometry.home_leg_lengths, atol=1e-9)


def node_section(name):
    """Return the README's section of one node, up to the next heading."""
    match = re.search(rf'### {name}\n(.*?)\n### ', README, re.DOTALL)
    assert match, f'no section for {name}'
    return match.group(1)


def topic_rows(section, kind):
    """Return {topic: type} from the node section's table of `kind` topics."""
    table = re.search(rf'\| {kind} topic \| Type \| Meaning \|\n\| --- .*?\n((?:\|.*\n)+)',
                      section + '\n')
    assert table, f'no {kind} topic table'
    return dict(re.findall(r'^\| `([^`]+)` \| ([\w/]+) \|', table.group(1), re.MULTILINE))


@pytest.mark.parametrize('node_name', ['ik_node', 'fk_node', 'trajectory_node'])
def test_topic_tables_match_the_nodes(ros, config_directory, node_name):
    """The README's subscribed and published topics are exactly the node's own."""
    from stewart_kinematics.ros.fk_node import FkNode
    from stewart_kinematics.ros.ik_node import IkNode
    from stewart_kinematics.ros.trajectory_node import TrajectoryNode
    node_class = {'ik_node': IkNode, 'fk_node': FkNode, 'trajectory_node': TrajectoryNode}
    arguments = ['--ros-args']
    for name in ('paper_platform.yaml', 'solver.yaml', 'table3_ramp.yaml'):
        arguments += ['--params-file', str(config_directory / name)]
    node = node_class[node_name](cli_args=arguments)
    try:
        ignored = {'/rosout', '/parameter_events'}
        subscribed = {s.topic_name.lstrip('/'): s.msg_type for s in node.subscriptions}
        published = {p.topic_name: p.msg_type for p in node.publishers
                     if p.topic_name not in ignored}
        section = node_section(node_name)

        def type_name(message_type):
            module = message_type.__module__.split('.')[0]
            return f'{module}/msg/{message_type.__name__}'

        readme_published = {topic if topic.startswith('/') else f'/{topic}': kind
                            for topic, kind in topic_rows(section, 'Published').items()}
        assert readme_published == {
            topic: type_name(kind) for topic, kind in published.items()}
        if subscribed:
            assert topic_rows(section, 'Subscribed') == {
                topic: type_name(kind) for topic, kind in subscribed.items()}
    finally:
        node.destroy_node()


def test_decision_objects_example_runs(monkeypatch, capsys):
    """The Python API's CommandCheck and PoseTracker example runs as written."""
    blocks = re.findall(r'```python\n(.*?)```', README, re.DOTALL)
    [example] = [block for block in blocks if 'CommandCheck' in block]
    monkeypatch.chdir(ROOT)
    sent = []
    geometry = load_geometry(ROOT / 'config' / 'paper_platform.yaml')
    exec(example, {'send_to_actuators': sent.append,  # noqa: S102 - the README's own code
                   'measured_lengths': geometry.home_leg_lengths})
    assert len(sent) == 1 and len(sent[0]) == 6
    printed = capsys.readouterr().out
    assert '[0.     0.     0.4325 0.     0.     0.    ]' in printed


def test_motion_example_runs(monkeypatch, capsys):
    """The Motion section's Python example runs and prints what its comments say."""
    blocks = re.findall(r'```python\n(.*?)```', README, re.DOTALL)
    [example] = [block for block in blocks if 'plan_motion' in block]
    monkeypatch.chdir(ROOT)
    namespace = {}
    exec(example, namespace)  # noqa: S102 - the README's own code
    printed = capsys.readouterr().out.split('\n')
    assert printed[0] == 'False too_fast'
    assert printed[1] == '4.09'
    assert namespace['points'].positions.shape == (412, 6)
