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
The documentation is shaped for its readers.

The site's tables of contents are the five sections doc/documentation.md describes, each page
in exactly one of them (the API pages in the API reference's own); the how-tos are in
``doc/how-to/``; motion cueing is reachable as a concept and as a how-to; the API reference
has a page per sub-package; the node reference starts with the nodes; the front pages count
the nodes the package has.
"""

from pathlib import Path
import pkgutil
import re

import pytest

import stewart_kinematics
from stewart_kinematics.ros.interfaces import NODE_INTERFACES

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / 'doc'
SECTIONS = ('Getting started', 'Concepts', 'How-to guides', 'Reference', 'Developers')
NUMBER_WORDS = {3: 'three', 4: 'four', 5: 'five', 6: 'six'}


def toctrees(page: Path) -> dict:
    """Return the toctrees of a page: ``{caption: [entries]}`` (an uncaptioned one under '')."""
    found = {}
    text = page.read_text(encoding='utf-8')
    for body in re.findall(r'```\{toctree\}\n(.*?)```', text, re.DOTALL):
        caption = re.search(r'^:caption: (.+)$', body, re.MULTILINE)
        entries = [line.strip() for line in body.splitlines()
                   if line.strip() and not line.startswith(':')]
        found[caption.group(1) if caption else ''] = entries
    return found


def test_the_index_has_the_five_sections_in_reading_order():
    """Getting started, Concepts, How-to guides, Reference, Developers: in that order."""
    assert tuple(toctrees(DOC / 'index.md')) == SECTIONS


def test_every_page_is_in_exactly_one_table_of_contents():
    """Each page of doc/ is named once: by the index's sections, or the API reference's."""
    named = []
    for caption, entries in toctrees(DOC / 'index.md').items():
        named += entries
    named += [f'api/{entry}' for entry in toctrees(DOC / 'api' / 'index.md')['']]
    pages = sorted(str(page.relative_to(DOC).with_suffix('')) for page in DOC.rglob('*.md')
                   if page.name != 'index.md' or page.parent != DOC)
    duplicates = sorted({entry for entry in named if named.count(entry) > 1})
    assert not duplicates, f'named by two tables of contents: {duplicates}'
    assert sorted(named) == pages


def test_how_tos_are_in_their_folder_and_motion_cueing_is_a_concept_and_a_how_to():
    """The How-to section holds exactly doc/how-to/; motion cueing has a page in both places."""
    sections = toctrees(DOC / 'index.md')
    how_tos = sorted(f'how-to/{page.stem}' for page in (DOC / 'how-to').glob('*.md'))
    assert sorted(sections['How-to guides']) == how_tos
    assert sections['How-to guides'][0] == 'how-to/own_platform'
    for page in ('own_platform', 'joint_trajectory_controller', 'rviz', 'calibrate',
                 'motion_cueing'):
        assert f'how-to/{page}' in how_tos, page
    assert 'motion_cueing' in sections['Concepts']


def test_the_api_reference_has_a_page_per_sub_package():
    """doc/api/ has a page for each sub-package, naming it in a {module-reference}."""
    packages = sorted(info.name for info in pkgutil.iter_modules(stewart_kinematics.__path__)
                      if info.ispkg)
    for package in packages:
        page = DOC / 'api' / f'{package}.md'
        assert page.is_file(), f'no API page for stewart_kinematics.{package}'
        text = page.read_text(encoding='utf-8')
        assert f'```{{module-reference}} stewart_kinematics.{package}\n' in text, package
    assert not (DOC / 'api.md').exists()


def test_the_node_reference_starts_with_the_nodes():
    """doc/nodes.md: its first sections are the nodes, each of them, before anything else."""
    text = (DOC / 'nodes.md').read_text(encoding='utf-8')
    headings = re.findall(r'^## (.+)$', text, re.MULTILINE)
    assert headings[:len(NODE_INTERFACES)] == list(NODE_INTERFACES)
    intro = text.split('\n## ', 1)[0]
    assert len(intro.splitlines()) < 40, 'the node reference opens with too much before a node'


def test_the_front_pages_count_the_nodes_the_package_has():
    """README.md and doc/index.md say how many nodes there are, and name each."""
    count = NUMBER_WORDS[len(NODE_INTERFACES)]
    for page in (ROOT / 'README.md', DOC / 'index.md'):
        opening = page.read_text(encoding='utf-8').split('\n## ', 1)[0]
        assert f'{count} thin rclpy nodes' in ' '.join(opening.split()), page.name
        for node in NODE_INTERFACES:
            assert f'`{node}`' in opening, (page.name, node)
