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
Sphinx configuration of the stewart_kinematics documentation (MyST Markdown pages, autodoc).

Built two ways, from the same files:

- here, by ``sphinx-build -W --keep-going doc OUT`` (test/package/test_docs.py, in the test
  command), with the package importable from the venv;
- on docs.ros.org, by rosdoc2 (``rosdoc2.yaml`` at the package root names this folder). rosdoc2
  copies this folder elsewhere and runs this file from its own wrapping ``conf.py``, so nothing
  here may rely on ``__file__``: the local extension (``ext/stewart_docs.py``) is found from
  ``app.srcdir`` in :func:`setup` (which also gets past rosdoc2's list of allowed extensions),
  and the repository from the imported package.
"""

import doctest
import os
import sys

project = 'stewart_kinematics'
author = 'stewart_kinematics developers'
copyright = '2026, stewart_kinematics developers. License: Apache-2.0'  # noqa: A001

extensions = [
    'myst_parser',
    'sphinx.ext.autodoc',
    'sphinx.ext.doctest',
    'sphinx_rtd_theme',
]

root_doc = 'index'
source_suffix = {'.md': 'markdown', '.rst': 'restructuredtext'}
# rosdoc2 writes pages of its own beside ours: an index.rst (ours is index.md), the README and
# package.xml as "standard documents" (the README's links point into the repository, not into
# this site), and rosdoc2 0.2.1 also copies this folder to user_docs/ and runs sphinx-apidoc
# (newer versions honour never_run_sphinx_apidoc in rosdoc2.yaml). None of that is this site.
exclude_patterns = ['_build', 'ext', 'index.rst', 'README.md', '__*.rst', 'standard_docs',
                    'standards.rst', 'user_docs', 'user_docs*.rst', 'modules.rst',
                    'stewart_kinematics*.rst']
templates_path = []

# The theme rosdoc2 imposes on docs.ros.org, so that a local build looks the same.
html_theme = 'sphinx_rtd_theme'
html_theme_options = {'navigation_depth': 3, 'collapse_navigation': False}
html_title = 'stewart_kinematics'
# Straight quotes and dashes: the pages quote parameter values ('table', 1e-9, ...) as code does.
smartquotes = False

# MyST: ``{directive}`` fences, ``:::`` fences, $math$ not needed; headings get anchors to level 3
# so that ``[text](page.md#heading)`` links resolve.
myst_enable_extensions = ['colon_fence', 'deflist']
myst_heading_anchors = 3

# autodoc: the public API is documented through the package root (stewart_kinematics.X), in
# source order, with the signature's types in the description rather than the signature line.
autodoc_member_order = 'bysource'
autodoc_typehints = 'description'
autodoc_class_signature = 'mixed'
autodoc_default_options = {'members': True}
# Names the package imports only where used (its optional dependencies): docs.ros.org's
# builder may not have them, and the reference never needs them to be importable.
autodoc_mock_imports = ['toppra', 'ruckig', 'matplotlib', 'rosbags']

# Doctests (``sphinx-build -b doctest``): every ``>>>`` example of the docstrings and the pages
# runs, importing what it uses, from the repository root, so that
# ``load_geometry('config/paper_platform.yaml')`` works as written.
doctest_global_setup = """
import os as _os
from pathlib import Path as _Path

import stewart_kinematics as _package

_doctest_previous_directory = _os.getcwd()
_os.chdir(_Path(_package.__file__).resolve().parent.parent)
"""
doctest_global_cleanup = """
_os.chdir(_doctest_previous_directory)
"""
# Only the examples written as examples run: ``>>>`` blocks (docstrings and pages) and the
# pages' ``{doctest}`` blocks; plain code blocks are shown, not run.
doctest_test_doctest_blocks = 'default'
# numpy wraps a long array's repr over lines: compare whitespace loosely, as a reader does.
doctest_default_flags = (doctest.ELLIPSIS | doctest.IGNORE_EXCEPTION_DETAIL
                         | doctest.DONT_ACCEPT_TRUE_FOR_1 | doctest.NORMALIZE_WHITESPACE)

# Read by rosdoc2 only: keep our extensions and settings, take its theme.
rosdoc2_settings = {'override_theme': True, 'support_markdown': True}


def setup(app):
    """Load the project's own extension (generated tables, the API completeness check)."""
    sys.path.insert(0, os.path.join(os.path.abspath(app.srcdir), 'ext'))
    app.setup_extension('stewart_docs')
