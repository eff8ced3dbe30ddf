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
Every code the package can emit is in the one registry (findings.CODES) and in the docs' table.

The package's source is read (not imported): every ``Finding(...)`` construction is found, and
its code resolved to a constant of stewart_kinematics.findings. A code written as a string, or
as a constant defined elsewhere (such as ik_node's former ``WRONG_FRAME``), fails with its
module and line; so does a registered code that nothing emits any more.
"""

import ast
from pathlib import Path

import pytest

from stewart_kinematics import findings

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / 'stewart_kinematics'


def findings_names(tree):
    """Names a module imports from stewart_kinematics.findings, and its alias for the module."""
    names, modules = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module == 'stewart_kinematics.findings':
            names.update(alias.asname or alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module == 'stewart_kinematics':
            modules.update(alias.asname or alias.name for alias in node.names
                           if alias.name == 'findings')
    return names, modules


def enclosing_functions(tree):
    """Map each node to the function (or module) it is in, for local assignments."""
    owner = {}

    def visit(node, function):
        for child in ast.iter_child_nodes(node):
            owner[child] = function
            visit(child, child if isinstance(child, (ast.FunctionDef,
                                                     ast.AsyncFunctionDef)) else function)
    visit(tree, tree)
    return owner


def resolve(expression, scope, names, modules, path, seen=()):
    """
    Return the codes an expression can be: findings constants, through local assignments.

    :raises AssertionError: naming the file and line, for anything else.
    """
    where = f'{path.relative_to(ROOT)}:{expression.lineno}'
    if isinstance(expression, ast.Attribute) and isinstance(expression.value, ast.Name) and (
            expression.value.id in modules):
        return {getattr(findings, expression.attr)}
    if isinstance(expression, ast.Name) and expression.id in names:
        return {getattr(findings, expression.id)}
    if path.name == 'findings.py' and isinstance(expression, ast.Name) and hasattr(
            findings, expression.id) and expression.id.isupper():
        return {getattr(findings, expression.id)}
    if isinstance(expression, ast.IfExp):
        return (resolve(expression.body, scope, names, modules, path, seen)
                | resolve(expression.orelse, scope, names, modules, path, seen))
    if isinstance(expression, ast.Name) and expression.id not in seen:
        values = [node.value for node in ast.walk(scope) if isinstance(node, ast.Assign)
                  and any(isinstance(target, ast.Name) and target.id == expression.id
                          for target in node.targets)]
        assert values, f'{where}: code {expression.id} is not a constant of findings.py'
        codes = set()
        for value in values:
            codes |= resolve(value, scope, names, modules, path, seen + (expression.id,))
        return codes
    raise AssertionError(f'{where}: a Finding whose code is not a findings.py constant: '
                         f'{ast.unparse(expression)}')


def emitted_codes():
    """Every code of every Finding the package constructs: {code: ['file:line', ...]}."""
    emitted = {}
    for path in sorted(PACKAGE.rglob('*.py')):
        tree = ast.parse(path.read_text(encoding='utf-8'))
        names, modules = findings_names(tree)
        owner = enclosing_functions(tree)
        for node in ast.walk(tree):
            if not isinstance(node, ast.Call):
                continue
            function = node.func
            called = function.id if isinstance(function, ast.Name) else (
                function.attr if isinstance(function, ast.Attribute) else None)
            if called != 'Finding':
                continue
            code = node.args[0] if node.args else next(
                keyword.value for keyword in node.keywords if keyword.arg == 'code')
            for value in resolve(code, owner[node], names, modules, path):
                emitted.setdefault(value, []).append(f'{path.relative_to(ROOT)}:{node.lineno}')
    return emitted


def test_every_code_emitted_is_registered_and_every_registered_code_is_emitted():
    """The AST scan finds each Finding's code in the registry, and each registered code used."""
    emitted = emitted_codes()
    assert set(emitted) <= set(findings.CODES), sorted(set(emitted) - set(findings.CODES))
    assert set(findings.CODES) <= set(emitted), (
        'registered but emitted nowhere: ' + ', '.join(sorted(set(findings.CODES)
                                                              - set(emitted))))
    # The scan sees the nodes too: the codes that moved there from ik_node and trajectory_node.
    assert any('pose_decisions/pose_commands.py' in place for place in emitted['wrong_frame'])
    assert any('motion/streaming.py' in place for place in emitted['stream_held'])


def test_no_code_is_defined_outside_the_registry():
    """No module but findings.py assigns a registered code to a constant of its own."""
    defined = []
    for path in sorted(PACKAGE.rglob('*.py')):
        if path.name == 'findings.py':
            continue
        for node in ast.parse(path.read_text(encoding='utf-8')).body:
            if (isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant)
                    and node.value.value in findings.CODES):
                defined.append(f'{path.relative_to(ROOT)}:{node.lineno} '
                               f'{ast.unparse(node)}')
    assert not defined, defined


def test_the_scan_fails_on_a_code_defined_elsewhere():
    """The check above can fail: a module-level code of a node's own is refused."""
    path = PACKAGE / 'ros' / 'ik_node.py'
    tree = ast.parse("WRONG_FRAME = 'wrong_frame'\n"
                     'def on_pose():\n    return Finding(WRONG_FRAME, "no")\n')
    call = next(node for node in ast.walk(tree) if isinstance(node, ast.Call))
    with pytest.raises(AssertionError, match='not a findings.py constant'):
        resolve(call.args[0], tree, set(), set(), path)
    with pytest.raises(AssertionError, match='not a findings.py constant'):
        resolve(ast.parse("Finding('invalid_pose', 'no')").body[0].value.args[0], tree, set(),
                set(), path)


def test_every_code_has_a_kind_an_emitter_and_a_meaning():
    """Each registry entry says whether it refuses or warns, who emits it and what it means."""
    for code, entry in findings.CODES.items():
        assert entry.code == code and code == code.lower() and ' ' not in code
        assert entry.kind in ('refusal', 'warning', 'refusal or warning')
        assert entry.emitted_by and entry.meaning.endswith('.'), code
    constants = {value for name, value in vars(findings).items()
                 if name.isupper() and isinstance(value, str)}
    assert constants == set(findings.CODES)


def test_the_doc_table_is_the_registry_and_the_safety_page_shows_it():
    """codes_table() has one row per code; doc/safety.md renders it with {refusal-codes}."""
    table = findings.codes_table().splitlines()
    assert table[0] == '| Code | Kind | Emitted by | Meaning |'
    rows = table[2:]
    assert [row.split('`')[1] for row in rows] == list(findings.CODES)
    for row, entry in zip(rows, findings.CODES.values()):
        assert entry.meaning in row and entry.kind in row
    page = (ROOT / 'doc' / 'safety.md').read_text(encoding='utf-8')
    assert '```{refusal-codes}\n```' in page
