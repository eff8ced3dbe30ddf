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

"""The documentation pages stay true: examples work, links name existing pages."""

from pathlib import Path
import re

from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import load_geometry

pytestmark = pytest.mark.node

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / 'doc'


def test_leg_lengths_example_is_the_home_pose():
    """The ros2 topic pub example of the workspace page sends the home pose's leg lengths."""
    page = (DOC / 'ros_workspace.md').read_text(encoding='utf-8')
    example = re.search(r'Float64MultiArray \\\n\s+"\{data: \[([^\]]+)\]\}"', page)
    assert example, 'leg_lengths example not found in doc/ros_workspace.md'
    lengths = [float(value) for value in example.group(1).split(',')]
    geometry = load_geometry(ROOT / 'config' / 'paper_platform.yaml')
    assert_allclose(lengths, geometry.home_leg_lengths, atol=1e-9)


def test_links_between_pages_name_existing_pages():
    """Every relative link of a page names a page or a figure of doc/ (Sphinx checks anchors)."""
    for page in DOC.rglob('*.md'):
        text = page.read_text(encoding='utf-8')
        for target in re.findall(r'\]\(((?!https?:)[^)#\s]+)(?:#[^)]*)?\)', text):
            assert (page.parent / target).exists(), f'{page.relative_to(DOC)}: {target}'
