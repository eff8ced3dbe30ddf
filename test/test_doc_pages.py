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

"""The documentation pages stay true: the node pages' topics are the nodes' own, examples work."""

from pathlib import Path
import re

from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import load_geometry

pytestmark = pytest.mark.node

ROOT = Path(__file__).resolve().parent.parent
DOC = ROOT / 'doc'
NODES_PAGE = (DOC / 'nodes.md').read_text(encoding='utf-8')


def test_leg_lengths_example_is_the_home_pose():
    """The ros2 topic pub example of the workspace page sends the home pose's leg lengths."""
    page = (DOC / 'ros_workspace.md').read_text(encoding='utf-8')
    example = re.search(r'Float64MultiArray \\\n\s+"\{data: \[([^\]]+)\]\}"', page)
    assert example, 'leg_lengths example not found in doc/ros_workspace.md'
    lengths = [float(value) for value in example.group(1).split(',')]
    geometry = load_geometry(ROOT / 'config' / 'paper_platform.yaml')
    assert_allclose(lengths, geometry.home_leg_lengths, atol=1e-9)


def node_section(name):
    """Return the nodes page's section of one node, up to the next heading."""
    match = re.search(rf'^## {name}\n(.*?)\n## ', NODES_PAGE, re.DOTALL | re.MULTILINE)
    assert match, f'no section for {name} in doc/nodes.md'
    return match.group(1)


def topic_rows(section, kind):
    """Return {topic: type} from the node section's table of `kind` topics."""
    table = re.search(rf'\| {kind} topic \| Type \| Meaning \|\n\| --- .*?\n((?:\|.*\n)+)',
                      section + '\n')
    assert table, f'no {kind} topic table'
    return dict(re.findall(r'^\| `([^`]+)` \| ([\w/]+) \|', table.group(1), re.MULTILINE))


@pytest.mark.parametrize('node_name', ['ik_node', 'fk_node', 'trajectory_node',
                                       'motion_cueing_node'])
def test_topic_tables_match_the_nodes(ros, config_directory, node_name):
    """The nodes page's subscribed and published topics are exactly the node's own."""
    from stewart_kinematics.ros.fk_node import FkNode
    from stewart_kinematics.ros.ik_node import IkNode
    from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
    from stewart_kinematics.ros.trajectory_node import TrajectoryNode
    node_class = {'ik_node': IkNode, 'fk_node': FkNode, 'trajectory_node': TrajectoryNode,
                  'motion_cueing_node': MotionCueingNode}
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

        page_published = {topic if topic.startswith('/') else f'/{topic}': kind
                          for topic, kind in topic_rows(section, 'Published').items()}
        assert page_published == {
            topic: type_name(kind) for topic, kind in published.items()}
        if subscribed:
            assert topic_rows(section, 'Subscribed') == {
                topic: type_name(kind) for topic, kind in subscribed.items()}
    finally:
        node.destroy_node()


def test_links_between_pages_name_existing_pages():
    """Every relative link of a page names a page or a figure of doc/ (Sphinx checks anchors)."""
    for page in DOC.glob('*.md'):
        text = page.read_text(encoding='utf-8')
        for target in re.findall(r'\]\(((?!https?:)[^)#\s]+)(?:#[^)]*)?\)', text):
            assert (DOC / target).exists(), f'{page.name}: {target}'
