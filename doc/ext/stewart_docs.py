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
The documentation's own Sphinx extension: tables generated from the code, and completeness checks.

- ``{parameter-table} GROUP`` renders the parameter group ``GROUP`` (``GEOMETRY``, ``SOLVER``,
  ...) from its specs when the site is built, so a page cannot drift from the declarations.
- ``{refusal-codes}`` renders every code the package emits, from the registry of
  :mod:`stewart_kinematics.findings`.
- ``{limit-table}`` renders every kind of limit (evaluator, parameters, meaning), from their
  list, :data:`stewart_kinematics.limits.kinds.LIMIT_KINDS`.
- ``{node-interface} NODE`` renders a node's topics and services from their declaration in
  :mod:`stewart_kinematics.ros.interfaces`.
- ``{config-file} NAME`` shows the shipped parameter file ``config/NAME`` as it is, found from
  the imported package (the source tree, or the installed ``share/stewart_kinematics/config``):
  rosdoc2 builds a copy of this folder, where a relative include would not find it.
- Every public name of the package root must be documented as ``stewart_kinematics.<name>``
  (:func:`public_names`): the build warns, and so fails under ``-W``, when one is missing.

Loaded by ``doc/conf.py``'s ``setup()``.
"""

from pathlib import Path
import re
import sys

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)

PACKAGE = 'stewart_kinematics'


def public_names() -> list:
    """Every public name of the package root: ``__all__`` and the lazily imported names."""
    import stewart_kinematics
    names = list(stewart_kinematics.__all__)
    names += [name for name in getattr(stewart_kinematics, '_CALIBRATION_NAMES', ())
              if name not in names]
    return names


def parameter_groups() -> dict:
    """Return ``{GROUP: specs}`` for every ``GROUP_PARAMETERS`` tuple of the declarations."""
    from stewart_kinematics.parameters import declarations
    return {name[:-len('_PARAMETERS')]: value for name, value in vars(declarations).items()
            if name.endswith('_PARAMETERS') and isinstance(value, tuple)}


def parameter_table(group: str) -> str:
    """Return the Markdown table of one parameter group, as the specs render it."""
    from stewart_kinematics.parameters import markdown_table
    table = markdown_table(parameter_groups()[group])
    # A description may say `<platform_frame>_commanded`: outside code spans, escape '<' so
    # that Markdown shows it rather than taking it for an HTML tag.
    return re.sub(r'(`[^`]*`)|<', lambda match: match.group(1) or r'\<', table)


def refusal_codes() -> list:
    """
    Every refusal or warning code the package can emit: ``(code, emitted by, meaning, kind)``.

    Read from the registry of :mod:`stewart_kinematics.findings` (:data:`CODES`), the one
    place where a code is defined with its meaning; test/test_findings.py checks that every
    code the package emits is registered.
    """
    from stewart_kinematics.findings import CODES
    return [(code.code, code.emitted_by, code.meaning, code.kind) for code in CODES.values()]


def refusal_codes_table() -> str:
    """Return the Markdown table of every code: :func:`stewart_kinematics.findings.codes_table`."""
    from stewart_kinematics.findings import codes_table
    return codes_table()


def limit_table() -> str:
    """Return the Markdown table of every kind of limit: :func:`~.limits.kinds.limits_table`."""
    from stewart_kinematics.limits.kinds import limits_table
    return limits_table()


class MarkdownDirective(SphinxDirective):
    """A directive whose content is Markdown generated when the page is built."""

    def markdown(self) -> str:
        """Return the Markdown to insert."""
        raise NotImplementedError

    def run(self):
        """Parse the generated Markdown in place of the directive."""
        try:
            text = self.markdown()
        except (KeyError, ValueError) as error:
            raise self.error(f'{self.name}: {error}') from error
        container = nodes.container()
        self.state.nested_parse(StringList(text.splitlines(), source=self.get_source_info()[0]),
                                self.content_offset, container)
        return container.children


class ParameterTable(MarkdownDirective):
    """``{parameter-table} GROUP``: the table of one parameter group, from its specs."""

    required_arguments = 1

    def markdown(self) -> str:
        """Render the group named by the argument."""
        group = self.arguments[0]
        if group not in parameter_groups():
            raise KeyError(f'no parameter group {group!r}; known: {sorted(parameter_groups())}')
        return parameter_table(group)


class LimitTable(MarkdownDirective):
    """``{limit-table}``: every kind of limit, from the list of kinds."""

    def markdown(self) -> str:
        """Render the table of limits."""
        return limit_table()


class RefusalCodes(MarkdownDirective):
    """``{refusal-codes}``: every refusal and warning code, with its meaning."""

    def markdown(self) -> str:
        """Render :func:`refusal_codes`."""
        return refusal_codes_table()


class NodeInterfaceTable(MarkdownDirective):
    """``{node-interface} NODE``: a node's topics and services, from their declaration."""

    required_arguments = 1

    def markdown(self) -> str:
        """Render the interface of the node named by the argument."""
        from stewart_kinematics.ros.interfaces import markdown_table, NODE_INTERFACES
        node = self.arguments[0]
        if node not in NODE_INTERFACES:
            raise KeyError(f'no node {node!r}; known: {sorted(NODE_INTERFACES)}')
        # '<' outside code spans would be read as an HTML tag.
        return re.sub(r'(`[^`]*`)|<', lambda match: match.group(1) or r'\<',
                      markdown_table(NODE_INTERFACES[node]))


def config_file(name: str) -> Path:
    """
    Find a shipped parameter file: beside the imported package, or where it is installed.

    :raises KeyError: naming the places searched.
    """
    import stewart_kinematics
    places = [Path(stewart_kinematics.__file__).resolve().parent.parent / 'config',
              Path(sys.prefix) / 'share' / PACKAGE / 'config']
    for place in places:
        if (place / name).is_file():
            return place / name
    raise KeyError(f'no config file {name!r} in {", ".join(map(str, places))}')


class ConfigFile(SphinxDirective):
    """``{config-file} NAME``: the parameter file ``config/NAME``, as a YAML block."""

    required_arguments = 1

    def run(self):
        """Return the file's text as a literal block."""
        try:
            path = config_file(self.arguments[0])
        except KeyError as error:
            raise self.error(f'{self.name}: {error}') from error
        self.env.note_dependency(str(path))
        text = path.read_text(encoding='utf-8')
        block = nodes.literal_block(text, text, language='yaml')
        return [block]


def check_public_names(app, env):
    """Warn about every public name of the package root that no page documents."""
    objects = env.get_domain('py').objects
    missing = [name for name in public_names() if f'{PACKAGE}.{name}' not in objects]
    if missing:
        logger.warning('the API reference does not document %s',
                       ', '.join(f'{PACKAGE}.{name}' for name in missing))


def setup(app):
    """Register the directives and the completeness check."""
    app.add_directive('parameter-table', ParameterTable)
    app.add_directive('refusal-codes', RefusalCodes)
    app.add_directive('limit-table', LimitTable)
    app.add_directive('node-interface', NodeInterfaceTable)
    app.add_directive('config-file', ConfigFile)
    app.connect('env-check-consistency', check_public_names)
    return {'version': '1', 'parallel_read_safe': True, 'parallel_write_safe': True}
