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

"""The README stays true: its commands, links, example, node table and size."""

from pathlib import Path
import re

from numpy.testing import assert_allclose
import pytest

from reference import leg_lengths as reference_leg_lengths, rotation_zyx

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / 'README.md').read_text(encoding='utf-8')
#: The README is the front door; the rest lives in doc/.
MAX_LINES = 250


def test_readme_is_short():
    """At most 250 lines: what does not fit belongs on a page of doc/."""
    assert len(README.splitlines()) <= MAX_LINES


def test_the_two_commands_exist_and_are_executable():
    """The README's two commands are scripts in the repository, and CI runs the test one."""
    for command in ('scripts/run_demo.sh', 'scripts/run_tests.sh'):
        assert f'{command}' in README
        assert (ROOT / command).is_file()
        assert (ROOT / command).stat().st_mode & 0o111, command
    assert 'scripts/run_tests.sh' in (ROOT / '.ci' / 'run').read_text(encoding='utf-8')


def test_linked_files_exist():
    """Every relative link in the README points to a file of the repository."""
    links = re.findall(r'\]\(((?!https?:)[^)#]+)(?:#[^)]*)?\)', README)
    assert links
    for link in links:
        assert (ROOT / link).exists(), link


def test_anchors_of_doc_pages_exist():
    """A link to a heading of a doc page (page.md#anchor) names a heading of that page."""
    for page, anchor in re.findall(r'\]\((doc/[\w/]+\.md)#([\w-]+)\)', README):
        headings = re.findall(r'^#+ (.+)$', (ROOT / page).read_text(encoding='utf-8'),
                              re.MULTILINE)
        slugs = {re.sub(r'[^\w\- ]', '', heading).strip().lower().replace(' ', '-')
                 for heading in headings}
        assert anchor in slugs, f'{page}#{anchor}'


def test_console_scripts_named_in_the_readme_are_declared():
    """ik_node, fk_node and trajectory_node (ros/) are console scripts."""
    setup = (ROOT / 'setup.py').read_text(encoding='utf-8')
    for script in ('ik_node', 'fk_node', 'trajectory_node'):
        assert f'`{script}`' in README
        pattern = rf"'{script} = stewart_kinematics\.(ros|tools)\.{script}:main'"
        assert re.search(pattern, setup), script


def test_node_table_names_every_topic_and_service_of_each_node():
    """The README's one table of nodes names each endpoint its node declares."""
    from stewart_kinematics.ros.interfaces import NODE_INTERFACES
    for node, interface in NODE_INTERFACES.items():
        row = re.search(rf'^\| `{node}` \|(.*)$', README, re.MULTILINE)
        assert row, f'no row for {node} in the README'
        for endpoint in interface.endpoints:
            assert f'`{endpoint.name}`' in row.group(1), (
                f'{node}: {endpoint.name} missing from the README row')


def test_decision_objects_example_runs(monkeypatch, capsys):
    """The CommandCheck and PoseTracker example runs as written, and its answers are right."""
    [example] = [block for block in re.findall(r'```python\n(.*?)```', README, re.DOTALL)
                 if 'CommandCheck' in block]
    assert len(example.strip().splitlines()) <= 16
    monkeypatch.chdir(ROOT)
    namespace = {}
    exec(example, namespace)  # noqa: S102 - the README's own code
    command, estimate = namespace['command'], namespace['estimate']
    pose = [0.0, 0.0, 0.45, 0.0, 0.0, 0.1]
    assert command.accepted and estimate.accepted
    assert_allclose(command.lengths, reference_leg_lengths(pose), atol=1e-12)
    assert_allclose(estimate.pose, pose, atol=1e-9)
    assert_allclose(rotation_zyx(*estimate.pose[3:]), rotation_zyx(*pose[3:]), atol=1e-9)
    printed = capsys.readouterr().out
    assert printed.count('\n') >= 2 and 'out_of_limits' not in printed
