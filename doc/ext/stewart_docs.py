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
  ...) from its specs when the site is built, so a page cannot drift from the declarations;
  ``GROUP`` may also be a part of a group that a page shows alone (:func:`parameter_parts`:
  ``MASS``, the masses and gravity; ``LIMIT_LEG_FORCE``, one limit kind's parameters).
- ``{refusal-codes}`` renders every code the package emits, from the registry of
  :mod:`stewart_kinematics.findings`.
- ``{limit-table}`` renders every kind of limit (evaluator, parameters, meaning), from their
  list, :data:`stewart_kinematics.limits.kinds.LIMIT_KINDS`.
- ``{node-interface} NODE`` renders a node's topics and services from their declaration in
  :mod:`stewart_kinematics.ros.interfaces`.
- ``{marker-colours}`` renders what the colours of ik_node's RViz markers mean, from the
  markers the node builds (:mod:`stewart_kinematics.ros.markers`).
- ``{config-file} NAME`` shows the shipped parameter file ``config/NAME`` as it is, found from
  the imported package (the source tree, or the installed ``share/stewart_kinematics/config``):
  rosdoc2 builds a copy of this folder, where a relative include would not find it.
- ``{module-reference} PACKAGE`` documents every module of a sub-package with autodoc, one
  section per module, in the order the sub-package's docstring names them: the API reference
  (``doc/api/``) has one page per sub-package, and a new module needs no edit there.
- ``{public-api}`` renders the table of every public name of the package root, each linked to
  where it is documented.
- Every public name of the package root is documented where it is defined (its sub-package's
  page) and reachable as ``stewart_kinematics.<name>`` (an alias of that entry,
  :func:`alias_public_names`); every module of the package has its section. The build warns,
  and so fails under ``-W``, when a name or a module is missing.

Loaded by ``doc/conf.py``'s ``setup()``.
"""

import importlib
import inspect
from pathlib import Path
import pkgutil
import re
import sys

from docutils import nodes
from docutils.statemachine import StringList
from sphinx import addnodes
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)

PACKAGE = 'stewart_kinematics'
#: The sub-packages in the API reference's reading order (doc/api/index.md): the public names'
#: table follows it. A sub-package not named here comes after these, alphabetically.
READING_ORDER = ('model', 'limits', 'pose_decisions', 'motion', 'analysis', 'cueing',
                 'parameters', 'findings', 'workers', 'ros', 'tools')


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


def parameter_parts() -> dict:
    """
    Return ``{PART: specs}``: parts of the parameter groups that a page shows alone.

    ``MASS``: the masses and gravity (``MASS_SPECS`` of the geometry group);
    ``LIMIT_<KIND>``: the parameters of one kind of limit (``LIMIT_LEG_FORCE``, ...), from the
    list of kinds. The nodes page shows every group whole (:func:`parameter_groups`).
    """
    from stewart_kinematics.limits.kinds import LIMIT_KINDS
    from stewart_kinematics.parameters import declarations
    specs = {spec.name: spec for spec in declarations.all_specs()}
    parts = {'MASS': declarations.MASS_SPECS}
    for kind in LIMIT_KINDS:
        parts[f'LIMIT_{kind.name.upper()}'] = tuple(
            specs[parameter.name] for parameter in kind.parameters)
    return parts


def parameter_table(group: str) -> str:
    """Return the Markdown table of one parameter group or part, as the specs render it."""
    from stewart_kinematics.parameters import markdown_table
    table = markdown_table({**parameter_parts(), **parameter_groups()}[group])
    # A description may say `<platform_frame>_commanded`: outside code spans, escape '<' so
    # that Markdown shows it rather than taking it for an HTML tag.
    return re.sub(r'(`[^`]*`)|<', lambda match: match.group(1) or r'\<', table)


def refusal_codes() -> list:
    """
    Every refusal or warning code the package can emit: ``(code, emitted by, meaning, kind)``.

    Read from the registry of :mod:`stewart_kinematics.findings` (:data:`CODES`), the one
    place where a code is defined with its meaning; test/package/test_findings.py checks that every
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
        known = {**parameter_parts(), **parameter_groups()}
        if group not in known:
            raise KeyError(f'no parameter group {group!r}; known: {sorted(known)}')
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


#: Names for the colours of the markers, by their (r, g, b): the nearest one names a colour.
COLOUR_NAMES = {'green': (0.2, 0.8, 0.2), 'red': (0.9, 0.1, 0.1), 'grey': (0.5, 0.5, 0.5),
                'blue': (0.12, 0.47, 0.71), 'light blue': (0.3, 0.6, 0.95),
                'orange': (1.0, 0.5, 0.05), 'purple': (0.58, 0.4, 0.74),
                'brown': (0.55, 0.34, 0.29), 'dark red': (0.75, 0.15, 0.16)}


def colour_cell(colour) -> str:
    """Return a table cell for a std_msgs/ColorRGBA: a swatch, its nearest name, its hex."""
    rgb = (colour.r, colour.g, colour.b)
    name = min(COLOUR_NAMES, key=lambda key: sum((a - b) ** 2
                                                 for a, b in zip(COLOUR_NAMES[key], rgb)))
    hexadecimal = '#' + ''.join(f'{round(255 * value):02x}' for value in rgb)
    return (f'<span style="background:{hexadecimal};padding:0 1.2em"></span> {name} '
            f'(`{hexadecimal}`)')


def marker_colours_table() -> str:
    """
    Return the Markdown table of what each colour of ik_node's markers means.

    Read from the markers :mod:`stewart_kinematics.ros.markers` builds (the platform's, with
    one leg breaking a limit, and the workspace boundary's, with one point per limit), so the
    table shows the colours RViz shows.
    """
    import numpy as np
    from std_msgs.msg import Header
    from stewart_kinematics import euler_zyx_to_matrix, load_geometry
    from stewart_kinematics.limits import LIMIT_NAMES
    from stewart_kinematics.ros.markers import platform_markers, workspace_markers
    geometry = load_geometry(config_file('paper_platform.yaml'))
    home = geometry.home_pose
    platform = platform_markers(Header(), geometry, home[:3], euler_zyx_to_matrix(home[3:]),
                                violating_legs=(1,)).markers
    legs = platform[2].colors
    rows = [('`platform_markers`', 'base outline (joints b_1 .. b_6)', platform[0].color),
            ('`platform_markers`', 'platform outline (joints p_1 .. p_6) at the pose asked',
             platform[1].color),
            ('`platform_markers`', 'a leg within every limit', legs[2]),
            ('`platform_markers`', 'a leg that breaks a limit (in a refused pose too)', legs[0])]
    boundary = workspace_markers(Header(), np.zeros((len(LIMIT_NAMES), 3)),
                                 np.arange(len(LIMIT_NAMES))).markers
    for marker in boundary:
        if marker.action == marker.ADD:
            rows.append(('`workspace_markers`',
                         f'boundary point where `{LIMIT_NAMES[marker.id]}` stops the platform',
                         marker.color))
    return '\n'.join(['| Topic | What | Colour |', '| --- | --- | --- |']
                     + [f'| {topic} | {what} | {colour_cell(colour)} |'
                        for topic, what, colour in rows])


class MarkerColours(MarkdownDirective):
    """``{marker-colours}``: what the colours of ik_node's RViz markers mean."""

    def markdown(self) -> str:
        """Render :func:`marker_colours_table`."""
        return marker_colours_table()


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
    """``{config-file} NAME``: the file ``config/NAME`` as a literal block (YAML, or XML)."""

    required_arguments = 1

    def run(self):
        """Return the file's text as a literal block."""
        try:
            path = config_file(self.arguments[0])
        except KeyError as error:
            raise self.error(f'{self.name}: {error}') from error
        self.env.note_dependency(str(path))
        text = path.read_text(encoding='utf-8')
        language = {'.urdf': 'xml', '.xml': 'xml'}.get(path.suffix, 'yaml')
        block = nodes.literal_block(text, text, language=language)
        return [block]


def package_modules(package: str) -> list:
    """
    Return the modules of a sub-package in reading order: as its docstring first names them.

    A sub-package's docstring names its modules as ``:mod:`.name``` (or a class in one,
    ``:class:`~.name.Class```) in the order a reader meets them; the modules it does not name
    follow, alphabetically. Sub-packages of it are listed like modules.

    :param package: the sub-package's dotted name, ``stewart_kinematics.model``.
    :return: the modules' dotted names.
    """
    module = importlib.import_module(package)
    names = sorted(info.name for info in pkgutil.iter_modules(module.__path__))
    ordered = []
    for name in re.findall(r'`~?\.(\w+)', module.__doc__ or ''):
        if name in names and name not in ordered:
            ordered.append(name)
    return [f'{package}.{name}' for name in ordered + sorted(set(names) - set(ordered))]


def all_modules() -> list:
    """Every module and sub-package of the package, dotted, the root first, in reading order."""
    import stewart_kinematics
    found = [info.name for info in
             pkgutil.walk_packages(stewart_kinematics.__path__, prefix=f'{PACKAGE}.')]
    tops = sorted({name.split('.')[1] for name in found},
                  key=lambda top: (READING_ORDER.index(top) if top in READING_ORDER
                                   else len(READING_ORDER), top))
    ordered = [PACKAGE]
    for top in tops:
        package = f'{PACKAGE}.{top}'
        ordered.append(package)
        if hasattr(importlib.import_module(package), '__path__'):
            ordered += package_modules(package)
    return ordered


def definition_of(name: str) -> str:
    """Where a public name of the package root is defined: ``module.qualname``."""
    import stewart_kinematics
    value = getattr(stewart_kinematics, name)
    return f'{value.__module__}.{value.__qualname__}'


def one_line(text: str) -> str:
    """Return the first paragraph of a docstring, as Markdown for a table cell."""
    paragraph = inspect.cleandoc(text or '').split('\n\n')[0]
    sentence = ' '.join(paragraph.split())
    # reST roles and literals to Markdown code; a '|' would end the table cell.
    sentence = re.sub(r':\w+:`~?([^`]+)`', lambda match: f'`{match.group(1)}`', sentence)
    return sentence.replace('``', '`').replace('|', '\\|')


def public_api_table() -> str:
    """Return the Markdown table of every public name of the root: link, kind, summary, module."""
    import stewart_kinematics
    rows = []
    for name in public_names():
        value = getattr(stewart_kinematics, name)
        kind = ('exception' if isinstance(value, type) and issubclass(value, BaseException)
                else 'class' if isinstance(value, type) else 'function')
        module = value.__module__
        rows.append((module, name, f'| {{py:obj}}`{name} <{PACKAGE}.{name}>` | {kind} | '
                     f'{one_line(value.__doc__)} | {{py:mod}}`{module}` |'))
    order = {module: index for index, module in enumerate(all_modules())}
    rows.sort(key=lambda row: (order.get(row[0], len(order)), row[1].lower()))
    return '\n'.join(['| Name | Kind | What it is | Defined in |', '| --- | --- | --- | --- |']
                     + [row[2] for row in rows])


class PublicApi(MarkdownDirective):
    """``{public-api}``: every public name of the package root, linked to its entry."""

    def markdown(self) -> str:
        """Render :func:`public_api_table`."""
        return public_api_table()


class ModuleReference(SphinxDirective):
    """
    ``{module-reference} PACKAGE``: a section per module of a sub-package, by autodoc.

    Each section is headed by the module's dotted name and holds its ``automodule`` (the
    module's docstring, then its documented members, in source order). Place it last on its
    page: the sections it adds close the page.
    """

    required_arguments = 1

    def run(self):
        """Parse one heading and one ``automodule`` per module, as Markdown with sections."""
        package = self.arguments[0]
        try:
            modules = package_modules(package)
        except (ImportError, AttributeError) as error:
            raise self.error(f'{self.name}: no package {package!r}: {error}') from error
        lines = []
        for module in modules:
            self.env.note_dependency(importlib.import_module(module).__file__)
            lines += [f'## `{module}`', '', '```{eval-rst}', f'.. automodule:: {module}',
                      '```', '']
        container = nodes.container()
        self.state.nested_parse(StringList(lines, source=self.get_source_info()[0]),
                                self.content_offset, container, match_titles=True)
        return container.children


def module_namespace_setup(module: str) -> str:
    """Return the doctest setup that gives an example its module's namespace, as doctest does."""
    return ('import importlib as _importlib\n'
            f'globals().update(vars(_importlib.import_module({module!r})))\n')


def group_docstring_examples(app, doctree):
    """
    Run each docstring's examples in its own module's namespace, as Python's doctest runs them.

    autodoc shows a docstring's ``>>>`` examples as doctest blocks; Sphinx's doctest builder
    would run all of a page's blocks in one shared namespace without the module's names. Each
    block gets instead the group of its docstring (the documented object, or the module for a
    module's docstring), set up with a copy of the module's namespace: an example may use the
    names of its module unimported, and starts without the names of another docstring's
    examples, exactly as ``python -m doctest`` and test/package/test_docs.py run it.
    """
    groups = {}
    module = None
    # In document order: a module's target id (moved by docutils onto the element after it,
    # its section or first paragraph) comes before the module's examples.
    for node in list(doctree.findall(nodes.Element)):
        if not isinstance(node, nodes.doctest_block):
            module = next((name[len('module-'):] for name in node.get('ids', ())
                           if name.startswith('module-')), module)
            continue
        description = node.parent
        while description is not None and not isinstance(description, addnodes.desc):
            description = description.parent
        if description is not None:
            signature = description.next_node(addnodes.desc_signature)
            owner = (signature.get('module'),
                     f"{signature.get('module')}.{signature.get('fullname')}")
        elif module is not None:
            owner = module, module
        else:
            continue
        node['groups'] = [owner[1]]
        groups[owner[1]] = owner[0]
    for group, owner_module in groups.items():
        code = module_namespace_setup(owner_module)
        doctree.append(nodes.comment(code, code, testnodetype='testsetup', groups=[group]))


def alias_public_names(app, env):
    """
    Make each public name of the root an alias of its entry: ``stewart_kinematics.Geometry``.

    A name is documented once, where it is defined (``stewart_kinematics.model.geometry
    .Geometry``, on its sub-package's page); the alias makes the root name, the one users
    import, a target of references and of the inventory (``objects.inv``) as well.
    """
    domain = env.get_domain('py')
    for name in public_names():
        entry = domain.objects.get(definition_of(name))
        alias = f'{PACKAGE}.{name}'
        if entry is not None and alias not in domain.objects:
            domain.objects[alias] = entry._replace(aliased=True)


def check_public_names(app, env):
    """Warn about every public name of the root, and every module, that no page documents."""
    domain = env.get_domain('py')
    missing = [f'{PACKAGE}.{name} ({definition_of(name)})' for name in public_names()
               if f'{PACKAGE}.{name}' not in domain.objects]
    if missing:
        logger.warning('the API reference does not document %s', ', '.join(missing))
    modules = [module for module in all_modules() if module not in domain.modules]
    if modules:
        logger.warning('the API reference (doc/api/) has no section for the modules %s: '
                       'add their sub-package to a page with {module-reference}',
                       ', '.join(modules))


def setup(app):
    """Register the directives and the completeness check."""
    app.add_directive('parameter-table', ParameterTable)
    app.add_directive('refusal-codes', RefusalCodes)
    app.add_directive('limit-table', LimitTable)
    app.add_directive('node-interface', NodeInterfaceTable)
    app.add_directive('config-file', ConfigFile)
    app.add_directive('marker-colours', MarkerColours)
    app.add_directive('module-reference', ModuleReference)
    app.add_directive('public-api', PublicApi)
    app.connect('doctree-read', group_docstring_examples)
    app.connect('env-updated', alias_public_names)
    app.connect('env-check-consistency', check_public_names)
    return {'version': '1', 'parallel_read_safe': True, 'parallel_write_safe': True}
