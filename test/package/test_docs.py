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
The documentation site builds with no warning, its examples run, and it documents every name.

The site in ``doc/`` is built as ``sphinx-build -W --keep-going`` builds it (MyST Markdown
pages, autodoc from the docstrings), into a temporary folder: a warning fails the test with
Sphinx's own output. Then the doctest builder runs every ``>>>`` example of the pages and of the
documented docstrings, and the tests check that the generated tables (parameters, refusal
codes) and the API reference hold what the code declares. The docstring examples of modules the
reference does not show (such as ``stewart_kinematics.limits``) run too, with Python's doctest.

To build the site yourself: ``.venv/bin/sphinx-build -W --keep-going doc doc/_build/html``.
"""

import doctest
import html
import importlib
import os
from pathlib import Path
import re
import subprocess
import sys

import pytest

pytestmark = pytest.mark.lint

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / 'doc'
PACKAGE = 'stewart_kinematics'


def sphinx_build(builder, output, doctrees):
    """Run sphinx-build with warnings as errors; return the finished process."""
    return subprocess.run(
        [sys.executable, '-m', 'sphinx', '-W', '--keep-going', '-b', builder,
         '-d', str(doctrees), str(DOC), str(output)],
        cwd=ROOT, capture_output=True, text=True, timeout=600)


def failure_text(run):
    """Sphinx's warnings and the end of its log, for an assertion message."""
    return f'sphinx-build exited {run.returncode}\n{run.stderr}\n{run.stdout[-4000:]}'


@pytest.fixture(scope='module')
def site(tmp_path_factory):
    """Build the HTML site once for this module; return its folder (the build must succeed)."""
    folder = tmp_path_factory.mktemp('doc')
    run = sphinx_build('html', folder / 'html', folder / 'doctrees')
    assert run.returncode == 0, failure_text(run)
    return folder


def load_extension():
    """doc/ext/stewart_docs.py, imported (the generators of the tables)."""
    sys.path.insert(0, str(DOC / 'ext'))
    try:
        return importlib.import_module('stewart_docs')
    finally:
        sys.path.remove(str(DOC / 'ext'))


def text_of(html_file):
    """Return the text of a built page: tags removed, entities decoded, whitespace collapsed."""
    text = re.sub(r'<[^>]+>', '', html_file.read_text(encoding='utf-8'))
    return ' '.join(html.unescape(text).split())


def test_site_builds_without_warnings(site):
    """The site builds with -W (the fixture fails with Sphinx's output otherwise)."""
    assert (site / 'html' / 'index.html').is_file()
    for page in DOC.rglob('*.md'):
        built = site / 'html' / page.relative_to(DOC).with_suffix('.html')
        assert built.is_file(), page.relative_to(DOC)


def test_examples_in_pages_and_docstrings_run(site):
    """The doctest builder runs every example of the pages and of the documented docstrings."""
    run = sphinx_build('doctest', site / 'doctest', site / 'doctrees')
    assert run.returncode == 0, failure_text(run) + (
        (site / 'doctest' / 'output.txt').read_text(encoding='utf-8')
        if (site / 'doctest' / 'output.txt').is_file() else '')
    summary = (site / 'doctest' / 'output.txt').read_text(encoding='utf-8')
    counts = [int(count) for count in re.findall(r'^\s+(\d+) tests\s*$', summary, re.MULTILINE)]
    assert counts and sum(counts) >= 50, summary
    for document in ('api/model', 'api/motion', 'python_api', 'motion', 'assembly_modes'):
        assert f'Document: {document}\n' in summary, f'no doctest ran in {document}'


def test_every_public_name_is_in_the_api_reference(site):
    """Each name of the package root (__all__ and the lazy calibration names) is documented."""
    from sphinx.util.inventory import InventoryFile
    with open(site / 'html' / 'objects.inv', 'rb') as stream:
        inventory = InventoryFile.load(stream, '', os.path.join)
    documented = set()
    for kind, entries in inventory.data.items() if hasattr(inventory, 'data') else (
            inventory.items()):
        if kind.startswith('py:'):
            documented.update(entries)
    names = load_extension().public_names()
    import stewart_kinematics
    assert set(stewart_kinematics.__all__) <= set(names)
    lazy = {'calibrate', 'CalibrationError', 'CalibrationResult', 'measurement_poses'}
    assert lazy <= set(names)
    missing = [name for name in names if f'{PACKAGE}.{name}' not in documented]
    assert not missing, f'not in the API reference (doc/api/): {missing}'


def test_parameter_tables_show_every_parameter_group(site):
    """Each parameter group has its generated table on the nodes page, with every parameter."""
    extension = load_extension()
    groups = extension.parameter_groups()
    source = (DOC / 'nodes.md').read_text(encoding='utf-8')
    shown = re.findall(r'^```\{parameter-table\} (\w+)$', source, re.MULTILINE)
    assert sorted(shown) == sorted(groups), 'doc/nodes.md: a {parameter-table} per group'
    page = text_of(site / 'html' / 'nodes.html')
    for specs in groups.values():
        for spec in specs:
            assert spec.name in page and ' '.join(spec.description.split()) in page, spec.name


def test_refusal_code_table_lists_every_code(site):
    """The safety page's table has a row for each code the package defines, with its meaning."""
    rows = load_extension().refusal_codes()
    from stewart_kinematics import findings
    codes = {value for name, value in vars(findings).items()
             if name.isupper() and isinstance(value, str)}
    assert codes <= {row[0] for row in rows}
    page = text_of(site / 'html' / 'safety.html')
    for code, _, meaning, _ in rows:
        assert code in page and meaning.replace('`', '') in page, code


def docstring_modules():
    """Every module of the package whose docstrings hold a ``>>>`` example."""
    found = []
    for path in sorted((ROOT / PACKAGE).rglob('*.py')):
        if '>>>' in path.read_text(encoding='utf-8'):
            relative = path.relative_to(ROOT).with_suffix('')
            found.append('.'.join(relative.parts).removesuffix('.__init__'))
    return found


@pytest.mark.parametrize('module_name', docstring_modules())
def test_docstring_examples_of_every_module_run(monkeypatch, module_name):
    """Python's doctest runs each module's examples too, documented in the reference or not."""
    monkeypatch.chdir(ROOT)
    module = importlib.import_module(module_name)
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    failures, tried = doctest.testmod(module, optionflags=flags, verbose=False, report=True)
    assert tried > 0, f'{module_name}: no example found'
    assert failures == 0, f'{module_name}: {failures} of {tried} examples failed (output above)'
