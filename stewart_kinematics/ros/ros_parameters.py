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
Turns the parameter specs of :mod:`stewart_kinematics.parameters` into ROS declarations.

A node calls :func:`declare_parameters` once in its constructor. It registers the validator
before declaring, so that a bad value from a parameter file fails the declaration with the
spec's reason (the node then stops at start-up), and a bad value set at run time is rejected
with that reason while the old value stays.

Before declaring, the parameters the node was given are read again from its command line
(:class:`ParameterSources`: the ``--params-file`` files and ``-p`` values of the process and of
the node's own ``cli_args``, and its ``parameter_overrides``), because rclpy keeps them to
itself and rcl's merge hides two mistakes: a misspelt name is ignored (the default stays), and
a value whose type differs between two layered files is dropped for the other one (a quoted
``leg_length_max: "0.9"`` over a file's ``.inf`` leaves ``.inf``). Both stop the node at
start-up, the parameter and the file named.

:func:`declare_parameters` also installs :func:`stewart_kinematics.ros.rclpy_guards.
guard_node`: rclpy's parameter services and sim-time clock survive the malformed requests and
messages that rclpy itself would raise on.
"""

import os
import sys
from typing import Callable, Dict, List, Optional, Sequence, Tuple
import weakref

from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.exceptions import ParameterException
from rclpy.parameter import Parameter

from stewart_kinematics import parameters
from stewart_kinematics.parameters import geometry_with_payload, PAYLOAD_PARAMETERS
from stewart_kinematics.parameters.files import (
    parse_rcl_yaml,
    read_sections_and_lines,
    section_applies,
)
from stewart_kinematics.ros.rclpy_guards import guard_node

#: The command-line arguments each rclpy context was initialised with, as
#: :func:`stewart_kinematics.ros.node_main.run_nodes` passed them (rclpy keeps them private).
_PROCESS_ARGUMENTS = weakref.WeakKeyDictionary()
#: Options of ``--ros-args`` that take a value, besides --params-file and -p (skipped).
_VALUE_OPTIONS = {'-r', '--remap', '-e', '--enclave', '--log-level', '--log-config-file',
                  '--log-file-name'}

_ROS_TYPES = {
    parameters.BOOL: Parameter.Type.BOOL,
    parameters.INTEGER: Parameter.Type.INTEGER,
    parameters.DOUBLE: Parameter.Type.DOUBLE,
    parameters.STRING: Parameter.Type.STRING,
    parameters.DOUBLE_ARRAY: Parameter.Type.DOUBLE_ARRAY,
    parameters.STRING_ARRAY: Parameter.Type.STRING_ARRAY,
}


def descriptor(spec: parameters.ParameterSpec) -> ParameterDescriptor:
    """ROS descriptor of a spec: description with unit, allowed values, read-only flag."""
    description = spec.description
    if spec.constraints:
        description += f' (allowed: {spec.constraints})'
    return ParameterDescriptor(
        name=spec.name, type=_ROS_TYPES[spec.value_type].value, description=description,
        read_only=spec.read_only)


def declare_parameters(node, specs, on_change=None, check=None,
                       node_options: Optional[dict] = None,
                       payload: Optional['RunTimePayload'] = None,
                       deferred: Optional['DeferredChecks'] = None) -> dict:
    """
    Declare ``specs`` on ``node`` with validation, and return their values.

    :param node: an ``rclpy.node.Node``.
    :param specs: the :class:`~stewart_kinematics.parameters.ParameterSpec` to declare.
    :param on_change: called as ``on_change(name, value)`` after a run-time change of one of
        them has been accepted.
    :param check: called at run time as ``check(values)`` with every value of ``specs`` as it
        would be after a change; returns ``''`` to accept it, else the reason to refuse it (for
        rules between parameters, such as distinct frame names).
    :param node_options: the keyword arguments the node was built with (``cli_args``,
        ``parameter_overrides``, ``use_global_arguments``), read for :class:`ParameterSources`.
    :param payload: how the node takes a new payload at run time (:class:`RunTimePayload`),
        or ``None``: the payload parameters are checked each alone, and not applied.
    :param deferred: for a managed node (:class:`DeferredChecks`): nothing raises, a problem
        of the values given is kept for its configure transition to refuse, and the read-only
        parameters may be set while it is unconfigured; ``None``: every problem raises here.
    :returns: parameter name -> value, as set by parameter files, overrides or defaults.
    :raises rclpy.exceptions.ParameterException: if a value has the wrong type or is not
        allowed; the message gives the spec's reason.
    :raises ValueError: if a required parameter is not set, a parameter file or override
        names a parameter that no node of the package declares, or a parameter file or ``-p``
        gives a value of the wrong type that rcl's merge of layered files would hide.
    """
    by_name = {spec.name: spec for spec in specs}
    sources = ParameterSources.of_node(node, node_options or {})
    # rclpy ignores overrides nobody declares: a misspelt name would silently keep a default.
    try:
        parameters.check_known_names(
            [name for name in sources.names()
             if not (node.has_parameter(name) or name.startswith('qos_overrides.'))],
            f'the parameters given to {node.get_fully_qualified_name()}')
    except ValueError as error:
        if deferred is None:
            raise
        deferred.problems[DeferredChecks.SOURCES] = str(error)
    # rcl keeps one type per name across layered sources (the one given alone is checked as
    # it is declared): check the value of each source.
    layered = sources.layered_names()
    for name, value, source in sources.values():
        # A null (an unquoted null or ~) or a number out of a double's range too: rcl gives a
        # string, and rclpy's refusal would not say why.
        spec = by_name.get(name) if name in layered or _holds_marked_string(value) else None
        reason = spec.type_reason(value) if spec is not None else ''
        if reason:
            if deferred is None:
                raise ValueError(f'{reason}, in {source}')
            deferred.problems.setdefault(name, f'{reason}, in {source}')
    declaring = [True]

    def validate(parameters):
        for parameter in parameters:
            if not parameter.name:
                # rclpy's check of undeclared names misses '' (it tests any(names)): the
                # request would create a parameter without a name.
                return SetParametersResult(successful=False,
                                           reason='a parameter needs a name, got an empty one')
            spec = by_name.get(parameter.name)
            if spec is None or parameter.type_ == Parameter.Type.NOT_SET:
                # Not ours, or a required parameter nobody set: reported after declaring.
                continue
            if deferred is not None:
                if declaring[0]:
                    continue   # a value given is checked by configure, which says why
                if spec.read_only and not deferred.configurable():
                    return SetParametersResult(successful=False, reason=(
                        f'parameter {spec.name!r} is read-only while the node is configured: '
                        'clean it up (cleanup transition), set it, configure again'))
            reason = spec.check(parameter.value)
            if reason:
                return SetParametersResult(successful=False, reason=reason)
        if deferred is not None and declaring[0]:
            return SetParametersResult(successful=True)
        if check is not None and all(node.has_parameter(name) for name in by_name):
            values = {name: node.get_parameter(name).value for name in by_name}
            values.update({parameter.name: parameter.value for parameter in parameters
                           if parameter.name in by_name})
            reason = check(values)
            if reason:
                return SetParametersResult(successful=False, reason=reason)
        if payload is not None and any(parameter.name in PAYLOAD_PARAMETERS
                                       for parameter in parameters) and all(
                node.has_parameter(name) for name in by_name) and not (
                deferred is not None and deferred.configurable()):   # not while declaring
            reason = payload.reason(node, parameters)
            if reason:
                return SetParametersResult(successful=False, reason=reason)
        return SetParametersResult(successful=True)

    node.add_on_set_parameters_callback(validate)
    guard_node(node)
    # A -p given after a file that names the node: its value, as the command line reads.
    later = sources.later_p_values()
    for spec in specs:
        default = _ROS_TYPES[spec.value_type] if spec.default is None else spec.default
        ignore = spec.name in later
        if ignore:
            default = later[spec.name]
        if deferred is None:
            node.declare_parameter(spec.name, default, descriptor(spec), ignore_override=ignore)
        else:
            deferred.declare(node, spec, default, descriptor(spec), ignore_override=ignore)
    declaring[0] = False

    if deferred is not None:
        def forget_fixed(parameters):
            for parameter in parameters:
                deferred.problems.pop(parameter.name, None)
        node.add_post_set_parameters_callback(forget_fixed)
    if on_change is not None or payload is not None:
        def apply(parameters):
            if deferred is not None and deferred.configurable():
                return   # unconfigured: configure reads every value
            for parameter in parameters:
                if parameter.name in by_name and on_change is not None:
                    on_change(parameter.name, parameter.value)
            # Once for the whole set: its payload parameters were checked together.
            if payload is not None and any(parameter.name in PAYLOAD_PARAMETERS
                                           for parameter in parameters):
                payload.apply(node)
        node.add_post_set_parameters_callback(apply)
    values = {spec.name: node.get_parameter_or(spec.name).value for spec in specs}
    # A required parameter that no file set was never validated: report it here.
    if deferred is None:
        parameters.check_values(specs, values)
    return values


def declare_settings(node, settings_class, on_change=None, check=None,
                     node_options: Optional[dict] = None,
                     payload: Optional['RunTimePayload'] = None, deferred=None, skip=()):
    """
    Declare a node's parameters (:func:`declare_parameters`) and return them as its settings.

    :param settings_class: the node's :class:`~stewart_kinematics.parameters.NodeSettings`
        subclass, such as ``IkNodeSettings``: its specs are declared.
    :param node_options: as for :func:`declare_parameters`.
    :param payload: as for :func:`declare_parameters`.
    :param deferred: as for :func:`declare_parameters`: then the values are returned as they
        were given (a dict), checked later by :meth:`DeferredChecks.settings`.
    :param skip: names of ``settings_class`` declared already (``managed``): read, not declared.
    :returns: an object of ``settings_class`` holding the values the node starts with.
    """
    values = declare_parameters(
        node, [spec for spec in settings_class.specs() if spec.name not in skip],
        on_change=on_change, check=check, node_options=node_options, payload=payload,
        deferred=deferred)
    values.update({name: node.get_parameter(name).value for name in skip})
    return values if deferred is not None else settings_class.from_values(values)


class DeferredChecks:
    """
    How a managed node declares its parameters: what is wrong is refused by configure.

    A managed node must exist, unconfigured, to be told what is wrong and to take a corrected
    value (``set_parameters``) or another transition. So nothing raises at declaration: a name
    no node declares or a value of the wrong type (the default is declared instead) is kept
    as a problem until the parameter is set, and a value a spec refuses is kept as it is; the
    configure transition refuses them (:meth:`settings`). Read-only parameters may be set
    while the node is unconfigured, and are read-only while it is configured.

    :param configurable: returns whether the node is unconfigured now.
    :param settable: whether read-only parameters are declared settable (while unconfigured);
        ``False`` declares them read-only, as an unmanaged node does.
    """

    #: The key of a problem of the parameter sources themselves (a name nobody declares).
    SOURCES = ''

    def __init__(self, configurable: Callable[[], bool], settable: bool = True):
        self.configurable = configurable
        self.settable = settable
        #: Parameter name (or :data:`SOURCES`) -> why its value given cannot be used.
        self.problems: Dict[str, str] = {}

    def declare(self, node, spec, default, ros_descriptor, ignore_override=False) -> None:
        """
        Declare one parameter settable while unconfigured; a wrong type: the default.

        :param ignore_override: ``default`` is the value given (a later ``-p``), not rcl's.
        """
        if self.settable:
            ros_descriptor.read_only = False
        try:
            node.declare_parameter(spec.name, default, ros_descriptor,
                                   ignore_override=ignore_override)
        except ParameterException as error:
            self.problems.setdefault(spec.name, str(error))
            fallback = _ROS_TYPES[spec.value_type] if spec.default is None else spec.default
            node.declare_parameter(spec.name, fallback, ros_descriptor, ignore_override=True)

    def settings(self, node, settings_class, check=None):
        """
        Return the node's settings as its parameters are now, or raise why they cannot be.

        :param check: ``check(values) -> reason`` between parameters, or ``None``.
        :raises ValueError: with the first problem kept, else the first value a spec refuses,
            else ``check``'s reason.
        """
        for problem in self.problems.values():
            raise ValueError(problem)
        values = {spec.name: node.get_parameter_or(spec.name).value
                  for spec in settings_class.specs()}
        parameters.check_values(settings_class.specs(), values)
        reason = check(values) if check is not None else ''
        if reason:
            raise ValueError(reason)
        return settings_class.from_values(values)


class RunTimePayload:
    """
    How a node takes a new payload at run time (``ros2 param set``, a parameter service).

    The payload parameters (:data:`~stewart_kinematics.parameters.PAYLOAD_PARAMETERS`) of one
    request are checked together, before they are set, with the geometry the node uses now
    (:func:`~stewart_kinematics.parameters.geometry_with_payload`: an inertia without a mass,
    or a payload too heavy for ``leg_force_max`` at home, is refused with the reason and the
    old payload stays); once set, the node is handed the geometry carrying them, at once.

    :param geometry: returns the geometry the node uses now.
    :param apply: called as ``apply(geometry)`` with the geometry carrying the new payload;
        the node hands it to every object that uses the masses.
    :param refusal: returns ``''`` when the node can take a new payload now, else why not
        (a node that must be at rest first); ``None``: always.
    """

    def __init__(self, geometry: Callable[[], object], apply: Callable[[object], None],
                 refusal: Optional[Callable[[], str]] = None):
        self.geometry = geometry
        self._apply = apply
        self._refusal = refusal

    def reason(self, node, changes) -> str:
        """Return ``''`` if the payload after ``changes`` (rclpy Parameters) fits, else why not."""
        refusal = self._refusal() if self._refusal is not None else ''
        if refusal:
            return refusal
        values = _payload_values(node)
        values.update({change.name: change.value for change in changes
                       if change.name in PAYLOAD_PARAMETERS})
        try:
            geometry_with_payload(self.geometry(), values)
        except ValueError as error:
            return str(error)
        return ''

    def apply(self, node) -> None:
        """Hand the node the geometry carrying the payload parameters as now set."""
        try:
            geometry = geometry_with_payload(self.geometry(), _payload_values(node))
        except ValueError as error:   # checked before the set: not expected, never raised
            node.get_logger().error(f'the new payload could not be taken: {error}')
            return
        self._apply(geometry)
        mass = node.get_parameter('payload_mass').value
        node.get_logger().info(f'payload changed: {mass:g} kg; the leg forces and the '
                               'leg_force limit use it from now on')


def _payload_values(node) -> dict:
    """Return the payload parameters' values on a node, as set now."""
    return {name: node.get_parameter(name).value for name in PAYLOAD_PARAMETERS}


def remember_process_arguments(context, arguments: Optional[Sequence[str]]) -> None:
    """
    Record the arguments an rclpy context was initialised with (``None``: ``sys.argv``).

    :func:`stewart_kinematics.ros.node_main.run_nodes` calls it after ``rclpy.init``, so that
    :func:`declare_parameters` can read the process's ``--params-file`` files again.
    """
    _PROCESS_ARGUMENTS[context] = list(sys.argv if arguments is None else arguments)


class ParameterSources:
    """
    Every parameter value a node was given, by source, read again from its arguments.

    :param node_name: the node's fully qualified name, to choose the files' sections.
    :param arguments: command-line arguments, the process's then the node's own; only those
        between ``--ros-args`` and ``--`` (or the end) count.
    :param overrides: ``parameter_overrides`` given to the node, name -> value.
    """

    def __init__(self, node_name: str, arguments: Sequence[str],
                 overrides: Optional[Dict[str, object]] = None):
        self.node_name = node_name
        #: ``(name, value, source)`` of every value given, in the order rcl applies them.
        self._values: List[Tuple[str, object, str]] = []
        for option, value in _ros_options(arguments):
            if option == '--params-file':
                sections, lines = read_sections_and_lines(value)
                for key, section in sections.items():
                    if section_applies(key, node_name):
                        self._values += [
                            (name, item, f'parameter file {value}:{lines.get((key, name))} '
                                         f"(section '{key}')")
                            for name, item in section.items()]
            else:
                assignment = _parameter_assignment(value)
                if assignment is not None and section_applies(assignment[0], node_name):
                    self._values.append((assignment[1], assignment[2], f'-p {value}'))
        self._values += [(name, item, 'parameter_overrides')
                         for name, item in (overrides or {}).items()]

    @classmethod
    def of_node(cls, node, node_options: dict) -> 'ParameterSources':
        """
        Return the sources of a node built with ``node_options`` (its keyword arguments).

        The process's arguments are those :func:`remember_process_arguments` recorded for the
        node's context, else ``sys.argv`` (what ``rclpy.init()`` reads by default).
        """
        arguments = []
        if node_options.get('use_global_arguments', True):
            arguments += _PROCESS_ARGUMENTS.get(node.context, sys.argv)
        arguments += list(node_options.get('cli_args') or [])
        overrides = {parameter.name: parameter.value
                     for parameter in node_options.get('parameter_overrides') or []}
        return cls(node.get_fully_qualified_name(), arguments, overrides)

    def names(self) -> List[str]:
        """Return every parameter name given, once each."""
        return list(dict.fromkeys(name for name, _, _ in self._values))

    def layered_names(self) -> set:
        """Return the names that more than one source gives (rcl merges their values)."""
        counts = {}
        for name, _, _ in self._values:
            counts[name] = counts.get(name, 0) + 1
        return {name for name, count in counts.items() if count > 1}

    def values(self) -> List[Tuple[str, object, str]]:
        """Return ``(name, value, source)`` for every value given."""
        return list(self._values)

    def later_p_values(self) -> Dict[str, object]:
        """
        Return name -> value of each ``-p`` given after a parameter file gave the same name.

        The command line is read left to right, the last value given winning; rcl does not:
        a plain ``-p name:=value`` is a ``/**`` value, and a file's section naming the node
        wins over it whatever their order (``--params-file motion_cueing.yaml -p
        cueing_method:=mpc`` kept the file's ``classical``). Only a ``-p`` that is the last
        value of its name counts (``parameter_overrides`` come last and win in any case).
        """
        later = {}
        filed = set()
        for name, value, source in self._values:
            if source.startswith('parameter file'):
                filed.add(name)
                later.pop(name, None)
            elif source.startswith('-p ') and name in filed:
                later[name] = value
            else:
                later.pop(name, None)
        return later


def parameter_file_problem(arguments: Sequence[str]) -> str:
    """
    Read every ``--params-file`` of the ROS arguments with the package's reader, before rcl.

    rcl reads a list nested 100,000 deep for half a minute before any node exists; the
    package's reader refuses it at once (:mod:`stewart_kinematics.parameters.rcl_yaml`). A
    file that does not exist is left to rcl, which says so.

    :param arguments: the process's command-line arguments.
    :returns: ``''``, or the first problem: one line, ``file:line: what is wrong``.
    """
    specs = {spec.name: spec for spec in parameters.all_specs()}
    for option, value in _ros_options(arguments):
        if option == '--params-file' and os.path.isfile(value):
            try:
                sections, lines = read_sections_and_lines(value)
            except ValueError as error:
                return str(error)
            # rcl refuses a list of mixed types ("Sequence should be of same type") before any
            # node exists, in words that name no parameter and show a null as a string.
            for section, values in sections.items():
                for name, item in values.items():
                    if _mixed_list(item):
                        reason = (specs[name].type_reason(item) if name in specs else '') or (
                            f"parameter '{name}' is a list of mixed types: rcl takes a list of "
                            'one type')
                        where = lines.get((section, name))
                        return f'{value}:{where}: {reason}' if where else f'{value}: {reason}'
    return ''


def _mixed_list(value) -> bool:
    """Whether a value read from a file is a list of scalars of more than one rcl type."""
    if not isinstance(value, list) or any(isinstance(item, (list, dict)) for item in value):
        return False
    kinds = {bool if isinstance(item, bool) else type(item) if not isinstance(item, str)
             else str for item in value}
    return len(kinds) > 1


def _holds_marked_string(value) -> bool:
    """Whether a value read from a file is or holds a null or a number rcl made a string of."""
    items = value if isinstance(value, list) else [value]
    return any(isinstance(item, (parameters.NullString, parameters.OutOfRangeNumber))
               for item in items)


def _ros_options(arguments):
    """Yield ``(option, value)`` for each --params-file and -p of the ROS arguments."""
    inside = False
    arguments = list(arguments)
    index = 0
    while index < len(arguments):
        argument = arguments[index]
        if argument == '--ros-args':
            inside = True
        elif argument == '--':
            inside = False
        elif inside and argument in ('--params-file', '-p', '--param') and index + 1 < len(
                arguments):
            yield ('--params-file' if argument == '--params-file' else '-p',
                   arguments[index + 1])
            index += 1
        elif inside and argument in _VALUE_OPTIONS:
            index += 1
        index += 1


def _parameter_assignment(text):
    """``(node pattern, name, value)`` of ``[node:]name:=value``, typed as rcl types it."""
    if ':=' not in text:
        return None
    target, value = text.split(':=', 1)
    node, _, name = target.rpartition(':')
    try:
        parsed = parse_rcl_yaml(value)
    except ValueError:   # rcl refuses it before any node is built
        return None
    return (node or '/**'), name, parsed
