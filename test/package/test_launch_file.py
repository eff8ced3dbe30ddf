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
launch/stewart_kinematics.launch.py, read and run without ``launch`` installed.

``launch`` and ``launch_ros`` cannot be installed here, so the launch file runs against small
stand-ins for the parts of their API it uses, put in ``sys.modules``: the constructors have the
real signatures (Jazzy: ``launch_ros.actions.Node(*, executable, package=None, name=None,
namespace=None, exec_name=None, parameters=None, remappings=None, ros_arguments=None,
arguments=None, **kwargs)`` with ``kwargs`` going to ``ExecuteProcess``;
``LaunchConfiguration(variable_name, *, default=None)``; ``DeclareLaunchArgument(name, *,
default_value=None, description=None, choices=None, **kwargs)``; ``IfCondition(
predicate_expression)``, ``UnlessCondition(predicate_expression)``; ``GroupAction(actions, *,
scoped=True, forwarding=True, launch_configurations=None, **kwargs)``;
``LaunchDescription(initial_entities=None, *, deprecated_reason=None)``;
``get_package_share_directory(package_name, print_warning=True)``) and refuse what the real
ones refuse. :func:`launch` then plays ``ros2 launch``'s part: it applies the command-line
arguments and the declared defaults, resolves the substitutions, evaluates the conditions and
expands each node's namespace as ``launch_ros`` does.

The package's share directory is a temporary folder holding what setup.py installs into it
(``config/*.yaml``), so a parameter file that would not be installed is found missing.
"""

import ast
import importlib.machinery
import importlib.util
from pathlib import Path
import re
import shutil
import sys
import types

from lifecycle_msgs.msg import Transition
import pytest
from rclpy.validate_namespace import validate_namespace
from stewart_kinematics.parameters.files import section_applies
import yaml

pytestmark = pytest.mark.node

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = 'stewart_kinematics'
LAUNCH_FILE = ROOT / 'launch' / 'stewart_kinematics.launch.py'
#: The modules the launch file may import: the stand-ins below, and the standard library's os
#: and lifecycle_msgs (installed: its Transition ids are the real ones).
STUBBED_MODULES = ('launch', 'launch.actions', 'launch.conditions', 'launch.substitutions',
                   'launch.events', 'launch_ros', 'launch_ros.actions',
                   'launch_ros.event_handlers', 'launch_ros.events',
                   'launch_ros.events.lifecycle', 'ament_index_python',
                   'ament_index_python.packages')
#: Real modules the launch file may import.
REAL_MODULES = ('os', 'lifecycle_msgs.msg')
#: Keyword arguments that launch_ros's Node passes on to ExecuteProcess, ExecuteLocal and Action.
EXECUTE_PROCESS_KEYWORDS = frozenset({
    'prefix', 'cwd', 'env', 'additional_env', 'shell', 'sigterm_timeout', 'sigkill_timeout',
    'emulate_tty', 'output', 'output_format', 'cached_output', 'log_cmd', 'on_exit', 'respawn',
    'respawn_delay', 'condition'})


class LaunchConfiguration:
    """Stand-in for launch.substitutions.LaunchConfiguration: the value of a launch argument."""

    def __init__(self, variable_name, *, default=None):
        """Keep the argument's name and default, as the real constructor does."""
        self.variable_name = variable_name
        self.default = default


class IfCondition:
    """Stand-in for launch.conditions.IfCondition."""

    def __init__(self, predicate_expression):
        """Keep the expression; :func:`launch` evaluates it as the real class does."""
        self.predicate_expression = predicate_expression


class UnlessCondition(IfCondition):
    """Stand-in for launch.conditions.UnlessCondition: IfCondition's opposite."""


class GroupAction:
    """Stand-in for launch.actions.GroupAction (Jazzy's signature)."""

    def __init__(self, actions, *, scoped=True, forwarding=True, launch_configurations=None,
                 **kwargs):
        """Check the arguments as the real constructor does, and keep the actions."""
        unknown = set(kwargs) - {'condition'}
        if unknown:
            raise TypeError(f'GroupAction got unexpected keyword arguments {unknown}')
        self.actions = list(actions)
        self.condition = kwargs.get('condition')


class DeclareLaunchArgument:
    """Stand-in for launch.actions.DeclareLaunchArgument."""

    def __init__(self, name, *, default_value=None, description=None, choices=None, **kwargs):
        """Check the arguments as the real constructor does, and keep them."""
        unknown = set(kwargs) - {'condition'}
        if unknown:
            raise TypeError(f'DeclareLaunchArgument got unexpected keyword arguments {unknown}')
        if choices is not None:
            if len(choices) == 0:
                raise RuntimeError('Provided choices arg is empty. Use None to ignore the choice '
                                   'list.')
            if isinstance(default_value, str) and default_value not in choices:
                raise RuntimeError(
                    f"Provided default_value '{default_value}' is not in provided choices "
                    f"'{choices}'.")
        self.name = name
        self.default_value = default_value
        self.description = description
        self.choices = choices


class Node:
    """Stand-in for launch_ros.actions.Node (Jazzy's signature)."""

    def __init__(self, *, executable, package=None, name=None, namespace=None, exec_name=None,
                 parameters=None, remappings=None, ros_arguments=None, arguments=None,
                 **kwargs):
        """Check the arguments as the real constructor does, and keep them."""
        unknown = set(kwargs) - EXECUTE_PROCESS_KEYWORDS
        if unknown:
            raise TypeError(f'Node got unexpected keyword arguments {unknown}')
        if parameters is not None and not isinstance(parameters, list):
            raise TypeError(f"Node: 'parameters' must be a list, got {type(parameters)}")
        self.executable = executable
        self.package = package
        self.name = name
        self.namespace = namespace
        self.parameters = parameters or []
        self.remappings = remappings or []
        self.ros_arguments = ros_arguments or []
        self.arguments = arguments or []
        self.condition = kwargs.get('condition')


class LifecycleNode(Node):
    """Stand-in for launch_ros.actions.LifecycleNode (Jazzy: name and namespace required)."""

    def __init__(self, *, name, namespace, **kwargs):
        """Check the arguments as the real constructor does, and keep them."""
        super().__init__(name=name, namespace=namespace, **kwargs)


class AndSubstitution:
    """Stand-in for launch.substitutions.AndSubstitution: 'true' if both are true."""

    def __init__(self, left, right):
        """Keep both operands."""
        self.left, self.right = left, right


class NotSubstitution:
    """Stand-in for launch.substitutions.NotSubstitution."""

    def __init__(self, value):
        """Keep the operand."""
        self.value = value


class EmitEvent:
    """Stand-in for launch.actions.EmitEvent."""

    def __init__(self, *, event, **kwargs):
        """Check the arguments as the real constructor does, and keep them."""
        unknown = set(kwargs) - {'condition'}
        if unknown:
            raise TypeError(f'EmitEvent got unexpected keyword arguments {unknown}')
        self.event = event
        self.condition = kwargs.get('condition')


class RegisterEventHandler:
    """Stand-in for launch.actions.RegisterEventHandler."""

    def __init__(self, event_handler, **kwargs):
        """Check the arguments as the real constructor does, and keep them."""
        unknown = set(kwargs) - {'condition'}
        if unknown:
            raise TypeError(f'RegisterEventHandler got unexpected keyword arguments {unknown}')
        if not isinstance(event_handler, OnStateTransition):
            raise TypeError(f'unexpected event handler {event_handler!r}')
        self.event_handler = event_handler
        self.condition = kwargs.get('condition')


class ChangeState:
    """Stand-in for launch_ros.events.lifecycle.ChangeState."""

    def __init__(self, *, lifecycle_node_matcher, transition_id):
        """Keep the matcher and the transition, as the real constructor does."""
        if not callable(lifecycle_node_matcher):
            raise TypeError('lifecycle_node_matcher must be callable')
        self.lifecycle_node_matcher = lifecycle_node_matcher
        self.transition_id = transition_id


class OnStateTransition:
    """Stand-in for launch_ros.event_handlers.OnStateTransition (Jazzy's signature)."""

    def __init__(self, *, entities=None, target_lifecycle_node=None, transition=None,
                 start_state=None, goal_state=None, matcher=None, **kwargs):
        """Check the arguments as the real constructor does, and keep them."""
        if kwargs:
            raise TypeError(f'OnStateTransition got unexpected keyword arguments {set(kwargs)}')
        if target_lifecycle_node is not None and matcher is not None:
            raise RuntimeError("Cannot specify both 'matcher' and 'target_lifecycle_node'")
        if target_lifecycle_node is not None and not isinstance(
                target_lifecycle_node, LifecycleNode):
            raise TypeError("OnStateTransition requires a 'LifecycleNode' action as the target")
        self.entities = list(entities or [])
        self.target_lifecycle_node = target_lifecycle_node
        self.transition, self.start_state, self.goal_state = transition, start_state, goal_state


def matches_action(target_action):
    """Stand-in for launch.events.matches_action: a matcher of one action."""
    def matcher(action):
        return action is target_action
    matcher.target = target_action
    return matcher


class LaunchDescription:
    """Stand-in for launch.LaunchDescription."""

    def __init__(self, initial_entities=None, *, deprecated_reason=None):
        """Keep the entities in order."""
        self.entities = list(initial_entities or [])


class PackageNotFoundError(KeyError):
    """Stand-in for ament_index_python.packages.PackageNotFoundError."""


def stub_modules(share_directory):
    """Return the stand-in modules by name; the package's share is ``share_directory``."""
    def get_package_share_directory(package_name, print_warning=True):
        if package_name != PACKAGE:
            raise PackageNotFoundError(f"package '{package_name}' not found")
        return str(share_directory)

    contents = {
        'launch': {'LaunchDescription': LaunchDescription},
        'launch.actions': {'DeclareLaunchArgument': DeclareLaunchArgument,
                           'GroupAction': GroupAction, 'EmitEvent': EmitEvent,
                           'RegisterEventHandler': RegisterEventHandler},
        'launch.conditions': {'IfCondition': IfCondition, 'UnlessCondition': UnlessCondition},
        'launch.events': {'matches_action': matches_action},
        'launch.substitutions': {'LaunchConfiguration': LaunchConfiguration,
                                 'AndSubstitution': AndSubstitution,
                                 'NotSubstitution': NotSubstitution},
        'launch_ros': {},
        'launch_ros.actions': {'Node': Node, 'LifecycleNode': LifecycleNode},
        'launch_ros.event_handlers': {'OnStateTransition': OnStateTransition},
        'launch_ros.events': {},
        'launch_ros.events.lifecycle': {'ChangeState': ChangeState},
        'ament_index_python': {},
        'ament_index_python.packages': {
            'get_package_share_directory': get_package_share_directory,
            'PackageNotFoundError': PackageNotFoundError},
    }
    modules = {}
    for name, attributes in contents.items():
        modules[name] = types.ModuleType(name)
        modules[name].__dict__.update(attributes)
    for name, module in modules.items():
        parent, _, child = name.rpartition('.')
        if parent:
            setattr(modules[parent], child, module)
    return modules


@pytest.fixture
def share_directory(tmp_path):
    """Lay out share/stewart_kinematics as setup.py installs it: config/*.yaml."""
    setup = (ROOT / 'setup.py').read_text(encoding='utf-8')
    assert "glob('config/*.yaml')" in setup, 'setup.py no longer installs config/*.yaml'
    share = tmp_path / 'install' / 'share' / PACKAGE
    (share / 'config').mkdir(parents=True)
    for path in sorted(ROOT.glob('config/*.yaml')):
        shutil.copy(path, share / 'config' / path.name)
    return share


@pytest.fixture
def stand_ins(monkeypatch, share_directory):
    """Put the stand-in modules in sys.modules for one test."""
    for name, module in stub_modules(share_directory).items():
        monkeypatch.setitem(sys.modules, name, module)


def launch_description():
    """Load the launch file as ros2 launch does and return its LaunchDescription."""
    loader = importlib.machinery.SourceFileLoader('stewart_kinematics_launch', str(LAUNCH_FILE))
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(loader.name, loader))
    loader.exec_module(module)
    description = module.generate_launch_description()
    assert isinstance(description, LaunchDescription)
    return description


@pytest.fixture
def launch(stand_ins):
    """
    Provide a function that runs the launch file as ``ros2 launch`` would.

    Its keyword arguments are the ``name:=value`` pairs of the command line. It returns one dict
    per node that would start: ``executable``, ``package``, ``namespace`` (expanded as
    launch_ros does: absolute, '/' for none), ``parameter_files`` (resolved paths, in order),
    ``remappings``, ``arguments``, ``ros_arguments``, ``lifecycle`` (a LifecycleNode), and
    ``state``: for a lifecycle node, the state it reaches by the launch's own events
    (:func:`run_lifecycle_events`; ``unconfigured`` without any).
    """
    def run(**arguments):
        description = launch_description()
        configurations = dict(arguments)
        nodes = []
        actions = {}
        emitted = []
        handlers = []

        def visit(entities):
            for entity in entities:
                if isinstance(entity, DeclareLaunchArgument):
                    declare(entity, configurations)
                elif entity.condition is not None and not evaluate(
                        entity.condition, configurations):
                    continue
                elif isinstance(entity, Node):
                    nodes.append(expand(entity, configurations))
                    actions[id(entity)] = nodes[-1]
                elif isinstance(entity, GroupAction):
                    visit(entity.actions)
                elif isinstance(entity, EmitEvent):
                    emitted.append(entity.event)
                elif isinstance(entity, RegisterEventHandler):
                    handlers.append(entity.event_handler)
                else:
                    raise AssertionError(f'unexpected launch entity {entity!r}')
        visit(description.entities)
        run_lifecycle_events(actions, emitted, handlers)
        unknown = set(arguments) - {e.name for e in description.entities
                                    if isinstance(e, DeclareLaunchArgument)}
        assert not unknown, f'launch arguments {unknown} are not declared'
        return nodes
    return run


#: The lifecycle state machine (lifecycle_msgs): (state, transition) -> (intermediate, goal).
LIFECYCLE = {
    ('unconfigured', Transition.TRANSITION_CONFIGURE): ('configuring', 'inactive'),
    ('inactive', Transition.TRANSITION_ACTIVATE): ('activating', 'active'),
    ('active', Transition.TRANSITION_DEACTIVATE): ('deactivating', 'inactive'),
    ('inactive', Transition.TRANSITION_CLEANUP): ('cleaningup', 'unconfigured'),
}


def run_lifecycle_events(actions, emitted, handlers):
    """
    Play the launch's ChangeState events on its lifecycle nodes, as launch_ros would.

    Each node's transitions succeed (the node's part is tested in test/processes); an
    OnStateTransition handler of a node fires its entities when the node goes from its
    ``start_state`` to its ``goal_state``. A ChangeState of a transition not available in
    the node's state fails the test, as launch_ros logs it.
    """
    for node in actions.values():
        node['state'] = 'unconfigured' if node['lifecycle'] else None
    queue = list(emitted)
    for _ in range(100):
        if not queue:
            return
        event = queue.pop(0)
        assert isinstance(event, ChangeState), event
        target = event.lifecycle_node_matcher.target
        node = actions.get(id(target))
        if node is None:   # its node does not start (a condition): launch_ros ignores it
            continue
        assert node['lifecycle'], 'ChangeState of a node that is no LifecycleNode'
        step = LIFECYCLE.get((node['state'], event.transition_id))
        assert step, f"{node['executable']}: transition {event.transition_id} from " \
            f"{node['state']}"
        start, (middle, goal) = node['state'], step
        node['state'] = goal
        for handler in handlers:
            if handler.target_lifecycle_node is target and (
                    handler.goal_state in (None, goal)) and handler.start_state in (
                    None, start, middle):
                for entity in handler.entities:
                    assert isinstance(entity, EmitEvent), entity
                    queue.append(entity.event)
    raise AssertionError('the lifecycle events do not end')


def resolve(value, configurations):
    """Resolve a substitution (text, LaunchConfiguration, Path or a list of them) to text."""
    if isinstance(value, str):
        return value
    if isinstance(value, (AndSubstitution, NotSubstitution)):
        operands = [value.left, value.right] if isinstance(value, AndSubstitution) else [
            value.value]
        truths = []
        for operand in operands:
            text = resolve(operand, configurations).lower()
            assert text in ('true', '1', 'false', '0'), f"invalid boolean '{text}'"
            truths.append(text in ('true', '1'))
        return str(all(truths) if isinstance(value, AndSubstitution) else not truths[0]).lower()
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, LaunchConfiguration):
        if value.variable_name in configurations:
            return configurations[value.variable_name]
        if value.default is None:
            raise AssertionError(f"launch configuration '{value.variable_name}' does not exist")
        return resolve(value.default, configurations)
    if isinstance(value, (list, tuple)):
        return ''.join(resolve(item, configurations) for item in value)
    raise AssertionError(f'unsupported substitution {value!r}')


def declare(argument, configurations):
    """Apply a DeclareLaunchArgument as launch does: default if not given, check choices."""
    if argument.name not in configurations:
        assert argument.default_value is not None, f'required argument {argument.name} missing'
        configurations[argument.name] = resolve(argument.default_value, configurations)
    if argument.choices is not None and configurations[argument.name] not in argument.choices:
        raise AssertionError(f"argument {argument.name}: '{configurations[argument.name]}' "
                             f'is not one of {argument.choices}')


def evaluate(condition, configurations):
    """Evaluate an If/UnlessCondition as launch does: 'true'/'1' or 'false'/'0', any case."""
    assert isinstance(condition, IfCondition), f'unexpected condition {condition!r}'
    text = resolve(condition.predicate_expression, configurations).lower()
    assert text in ('true', '1', 'false', '0'), f"invalid condition expression '{text}'"
    return (text in ('true', '1')) != isinstance(condition, UnlessCondition)


def expand(node, configurations):
    """Return what a Node would start: its substitutions resolved, its namespace absolute."""
    namespace = resolve(node.namespace, configurations) if node.namespace is not None else ''
    if not namespace.startswith('/'):
        namespace = '/' + namespace
    validate_namespace(namespace)
    for parameters in node.parameters:
        assert not isinstance(parameters, dict), 'inline parameters: keep them in config/'
    return {
        'executable': resolve(node.executable, configurations),
        'package': resolve(node.package, configurations),
        'namespace': namespace,
        'parameter_files': [resolve(p, configurations) for p in node.parameters],
        'remappings': node.remappings,
        'arguments': [resolve(argument, configurations) for argument in node.arguments],
        'ros_arguments': [resolve(argument, configurations) for argument in node.ros_arguments],
        'lifecycle': isinstance(node, LifecycleNode),
        'name': node.name,
    }


def console_scripts():
    """Names of the console scripts that setup.py declares."""
    tree = ast.parse((ROOT / 'setup.py').read_text(encoding='utf-8'))
    for node in ast.walk(tree):
        if isinstance(node, ast.Dict):
            for key, value in zip(node.keys, node.values):
                if isinstance(key, ast.Constant) and key.value == 'console_scripts':
                    return {entry.value.split('=')[0].strip() for entry in value.elts}
    raise AssertionError('no console_scripts in setup.py')


def test_launch_file_parses_and_imports_only_what_is_stubbed():
    """The file is valid Python, defines generate_launch_description(), is installed."""
    tree = ast.parse(LAUNCH_FILE.read_text(encoding='utf-8'), str(LAUNCH_FILE))
    functions = {node.name: node for node in tree.body if isinstance(node, ast.FunctionDef)}
    assert 'generate_launch_description' in functions
    assert not functions['generate_launch_description'].args.args
    imported = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            imported.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            imported.add(node.module)
    assert imported <= set(STUBBED_MODULES) | set(REAL_MODULES), imported
    assert "glob('launch/*.py')" in (ROOT / 'setup.py').read_text(encoding='utf-8')


def test_default_launch_starts_the_three_nodes_with_the_installed_config(
        launch, share_directory):
    """Without arguments: ik_node, fk_node, trajectory_node, root namespace, README's files."""
    nodes = launch()

    config = share_directory / 'config'
    expected = {
        'ik_node': [config / 'paper_platform.yaml'],
        'fk_node': [config / 'paper_platform.yaml', config / 'solver.yaml'],
        'trajectory_node': [config / 'paper_platform.yaml', config / 'table3_ramp.yaml'],
    }
    assert [node['executable'] for node in nodes] == list(expected)
    scripts = console_scripts()
    for node in nodes:
        assert node['package'] == PACKAGE
        assert node['executable'] in scripts, f'{node["executable"]} is no console script'
        assert node['namespace'] == '/'
        assert node['parameter_files'] == [str(path) for path in expected[node['executable']]]
        for path in node['parameter_files']:
            assert Path(path).is_file(), f'{path} is not installed'
            assert (ROOT / 'config' / Path(path).name).is_file()
        assert node['remappings'] == [] and node['arguments'] == []
        # Unmanaged: plain nodes, the managed parameter left at its default.
        assert not node['lifecycle'] and node['ros_arguments'] == []


@pytest.mark.parametrize('namespace', ['platform_a', '/robots/platform_b'])
def test_namespace_argument_moves_every_node(launch, namespace):
    """namespace:=... puts all three nodes (and so their relative topics) in that namespace."""
    nodes = launch(namespace=namespace)

    assert len(nodes) == 3
    expected = namespace if namespace.startswith('/') else '/' + namespace
    assert {node['namespace'] for node in nodes} == {expected}


def sections_taken(node):
    """Return, per file a node gets, the sections that rcl applies to the node's full name."""
    full_name = node['namespace'].rstrip('/') + '/' + node['executable']
    taken = []
    for path in node['parameter_files']:
        document = yaml.safe_load(Path(path).read_text(encoding='utf-8'))
        taken.append(sorted(key for key in document if section_applies(key, full_name)))
    return taken


def test_a_namespace_changes_no_section_a_node_takes(launch):
    """namespace:=platform_a: each node still takes its own section (the ramp, the solver)."""
    for root, inside in zip(launch(), launch(namespace='platform_a')):
        assert inside['namespace'] == '/platform_a'
        assert sections_taken(inside) == sections_taken(root), inside['executable']


def test_platform_config_and_play_ramp_arguments(launch, share_directory, tmp_path):
    """platform_config:= replaces the geometry of every node; play_ramp:=false drops the ramp."""
    geometry = tmp_path / 'platform_b.yaml'
    nodes = launch(namespace='platform_b', platform_config=str(geometry), play_ramp='false')

    assert [node['executable'] for node in nodes] == ['ik_node', 'fk_node']
    assert nodes[0]['parameter_files'] == [str(geometry)]
    assert nodes[1]['parameter_files'] == [
        str(geometry), str(share_directory / 'config' / 'solver.yaml')]
    assert {node['namespace'] for node in nodes} == {'/platform_b'}


@pytest.mark.parametrize('play_ramp', ['true', 'false'])
def test_one_process_runs_the_nodes_in_stewart_platform(launch, share_directory, play_ramp):
    """one_process:=true starts one stewart_platform with every file, and passes play_ramp."""
    nodes = launch(one_process='true', namespace='platform_a', play_ramp=play_ramp)

    config = share_directory / 'config'
    assert [node['executable'] for node in nodes] == ['stewart_platform']
    assert nodes[0]['executable'] in console_scripts()
    assert nodes[0]['namespace'] == '/platform_a'
    assert nodes[0]['parameter_files'] == [
        str(config / 'paper_platform.yaml'), str(config / 'solver.yaml'),
        str(config / 'table3_ramp.yaml')]
    assert nodes[0]['arguments'] == ['--play-ramp', play_ramp]


def test_play_ramp_accepts_only_true_or_false(launch):
    """play_ramp is declared with its choices, as ros2 launch checks them."""
    with pytest.raises(AssertionError, match='play_ramp'):
        launch(play_ramp='maybe')


def test_docs_list_the_launch_arguments_and_their_defaults(stand_ins, share_directory):
    """The docs' table of launch arguments names every declared one, with its default."""
    page = (ROOT / 'doc' / 'ros_workspace.md').read_text(encoding='utf-8')
    table = re.search(r'\| Argument \| Default \| Meaning \|\n\| --- .*\n((?:\|.*\n)+)', page)
    assert table, 'no launch argument table in doc/ros_workspace.md'
    rows = dict(re.findall(r'^\| `([^`]+)` \| `([^`]*)`', table.group(1), re.MULTILINE))
    declared = {entity.name: entity.default_value for entity in launch_description().entities
                if isinstance(entity, DeclareLaunchArgument)}

    assert set(rows) == set(declared)
    for name, default in declared.items():
        if default.startswith(str(share_directory)):
            default = Path(default).relative_to(share_directory).as_posix()
        elif default == '':
            default = "''"
        assert rows[name] == default, name


@pytest.mark.parametrize('construct', [
    lambda: Node(package=PACKAGE, node_executable='ik_node'),
    lambda: Node(package=PACKAGE, executable='ik_node', node_namespace='a'),
    lambda: Node(package=PACKAGE, executable='ik_node', parameters='config.yaml'),
    lambda: LaunchConfiguration('namespace', 'default'),
    lambda: DeclareLaunchArgument('play', default_value='yes', choices=['true', 'false']),
    lambda: GroupAction([], UnlessCondition('true')),
], ids=['dashing_executable', 'dashing_namespace', 'parameters_not_a_list',
        'default_not_keyword', 'default_not_a_choice', 'group_condition_not_keyword'])
def test_stand_ins_refuse_what_launch_refuses(construct):
    """The stand-ins are strict: a launch file misusing the real API fails here too."""
    with pytest.raises((TypeError, RuntimeError)):
        construct()


@pytest.mark.parametrize('play_ramp', ['true', 'false'])
def test_managed_starts_lifecycle_nodes_configured_and_activated(launch, play_ramp):
    """managed:=true: LifecycleNodes given managed:=true, each configured then activated."""
    nodes = launch(managed='true', play_ramp=play_ramp, namespace='platform_a')

    expected = ['ik_node', 'fk_node'] + (['trajectory_node'] if play_ramp == 'true' else [])
    assert [node['executable'] for node in nodes] == expected
    for node in nodes:
        assert node['lifecycle'], node
        # launch_ros needs the name to address the node's lifecycle services.
        assert node['name'] == node['executable']
        assert node['ros_arguments'] == ['-p', 'managed:=true']
        assert node['namespace'] == '/platform_a'
        assert node['state'] == 'active', node


def test_managed_without_autostart_leaves_the_nodes_unconfigured(launch):
    """autostart:=false: no transition is asked for: a lifecycle manager drives them."""
    nodes = launch(managed='true', autostart='false')

    assert len(nodes) == 3
    assert all(node['lifecycle'] and node['state'] == 'unconfigured' for node in nodes)


def test_managed_keeps_the_parameter_files(launch):
    """A managed node gets the same parameter files as an unmanaged one."""
    plain = {node['executable']: node['parameter_files'] for node in launch()}
    managed = {node['executable']: node['parameter_files'] for node in launch(managed='true')}

    assert plain == managed


@pytest.mark.parametrize('autostart', ['true', 'false'])
def test_one_process_managed_passes_managed_and_autostart(launch, autostart):
    """one_process:=true managed:=true: stewart_platform --autostart, its nodes managed."""
    nodes = launch(one_process='true', managed='true', autostart=autostart)

    assert [node['executable'] for node in nodes] == ['stewart_platform']
    assert nodes[0]['arguments'] == ['--play-ramp', 'true', '--autostart', autostart]
    assert nodes[0]['ros_arguments'] == ['-p', 'managed:=true']


@pytest.mark.parametrize('name', ['managed', 'autostart'])
def test_managed_and_autostart_accept_only_true_or_false(launch, name):
    """Both are declared with their choices."""
    with pytest.raises(AssertionError, match=name):
        launch(**{name: 'yes'})


@pytest.mark.parametrize('construct', [
    lambda: LifecycleNode(package=PACKAGE, executable='ik_node', namespace=''),
    lambda: OnStateTransition(target_lifecycle_node=Node(executable='ik_node')),
    lambda: EmitEvent(ChangeState(lifecycle_node_matcher=print, transition_id=1)),
    lambda: ChangeState(lifecycle_node_matcher='ik_node', transition_id=1),
], ids=['lifecycle_node_without_name', 'handler_of_a_plain_node', 'event_not_keyword',
        'matcher_not_callable'])
def test_lifecycle_stand_ins_refuse_what_launch_refuses(construct):
    """The lifecycle stand-ins are strict, as the others."""
    with pytest.raises((TypeError, RuntimeError)):
        construct()
