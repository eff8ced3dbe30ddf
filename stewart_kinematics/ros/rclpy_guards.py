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
Guards against rclpy's own failures on malformed input: the node answers instead of dying.

Found by the node fuzzer and the soak: rclpy raises inside the executor, where nothing of the
node can catch it, and the process exits with a traceback, on

- a SetParameters request whose value has a type code that rcl_interfaces does not define
  (``Parameter.Type(42)``): :func:`guard_parameter_services` refuses such a value with a
  reason, handles the others of the request as usual, and refuses an atomic request whole
  (and so a name the node does not declare, which rclpy refuses naming none);
- a /clock message with negative seconds under ``use_sim_time`` (``Time(seconds=-5)``):
  :func:`guard_clock` skips it with a throttled warning, and the clock keeps its last time.
- a lifecycle ChangeState request (a managed node's ``~/change_state``) by a transition id
  that the state machine does not have from its state (``99``, or ``activate``'s id while
  unconfigured): rclpy raises ``RCLError`` in the executor; :func:`guard_change_state`
  refuses it (``success: false``) with a warning, and the state stays.

:func:`guard_node` installs both, and again when ``use_sim_time`` is switched on at run time
(rclpy then creates the /clock subscription). The guards wrap the ``callback`` attribute of
rclpy's own service and subscription objects, which every executor calls.
"""

import difflib

from lifecycle_msgs.srv import ChangeState
from rcl_interfaces.msg import SetParametersResult
from rcl_interfaces.srv import SetParameters, SetParametersAtomically
# rclpy exposes it only from its C extension.
from rclpy._rclpy_pybind11 import RCLError
from rclpy.parameter import Parameter
from rosgraph_msgs.msg import Clock

from stewart_kinematics.model.arrays import preview

#: The clock topic of sim time.
CLOCK_TOPIC = '/clock'
#: Seconds between two warnings about skipped clock messages.
WARNING_PERIOD = 1.0


def guard_node(node) -> None:
    """Install every guard on a node, and again whenever ``use_sim_time`` is set."""
    guard_parameter_services(node)
    guard_clock(node)

    def after_set(parameters):
        if any(parameter.name == 'use_sim_time' for parameter in parameters):
            guard_clock(node)

    node.add_post_set_parameters_callback(after_set)


def guard_parameter_services(node) -> None:
    """
    Make a node's SetParameters services refuse values of a type code that does not exist.

    rclpy's parameter service turns each value of a request into a ``Parameter`` and raises
    ``ValueError`` inside the executor for a type code that rcl_interfaces does not define (a
    hand-made or corrupted request): the node exits with a traceback. Wrapped here, such a
    value is refused with a reason, the other values of a ``set_parameters`` request are
    handled as usual, and an atomic request is refused whole. Idempotent.
    """
    def refusal(parameter) -> str:
        return _unknown_type_reason(parameter) or _undeclared_reason(node, parameter)

    for service in node.services:
        if getattr(service.callback, 'guards_parameter_types', False):
            continue
        if service.srv_type is SetParameters:
            service.callback = _guard_set_parameters(service.callback, refusal)
        elif service.srv_type is SetParametersAtomically:
            service.callback = _guard_set_parameters_atomically(service.callback, refusal)


#: The type codes of rcl_interfaces/msg/ParameterType that rclpy knows.
_KNOWN_TYPE_CODES = frozenset(parameter_type.value for parameter_type in Parameter.Type)


def _unknown_type_reason(parameter) -> str:
    """Say why a parameter message has a type code rclpy does not know, or return ''."""
    if parameter.value.type in _KNOWN_TYPE_CODES:
        return ''
    return (f'parameter {preview(parameter.name)}: no parameter type has code '
            f'{parameter.value.type} '
            f'(rcl_interfaces/msg/ParameterType defines {sorted(_KNOWN_TYPE_CODES)})')


def _undeclared_reason(node, parameter) -> str:
    """
    Say that a parameter message names no parameter of the node, with the closest name.

    rclpy's own refusal names none: ``Invalid access to undeclared parameter(s): []`` (its
    check consumes the generator of names it then lists). An empty name is left to the
    node's own check.
    """
    if not parameter.name or node.has_parameter(parameter.name):
        return ''
    names = node.list_parameters([], 0).names
    close = difflib.get_close_matches(parameter.name, names, n=1)
    return (f'parameter {preview(parameter.name)} is not a parameter of {node.get_name()}'
            + (f" (did you mean '{close[0]}'?)" if close else '')
            + f'; it has {len(names)}: doc/nodes.md lists them')


def _guard_set_parameters(callback, refusal):
    """Wrap rclpy's set_parameters callback: refuse bad values one by one, with a reason."""
    def guarded(request, response):
        reasons = [refusal(parameter) for parameter in request.parameters]
        if not any(reasons):
            return callback(request, response)
        known = SetParameters.Request(parameters=[
            parameter for parameter, reason in zip(request.parameters, reasons) if not reason])
        results = iter(callback(known, SetParameters.Response()).results
                       if known.parameters else ())
        response.results = [SetParametersResult(successful=False, reason=reason) if reason
                            else next(results) for reason in reasons]
        return response
    guarded.guards_parameter_types = True
    return guarded


def _guard_set_parameters_atomically(callback, refusal):
    """Wrap rclpy's set_parameters_atomically callback: refuse a request with a bad value."""
    def guarded(request, response):
        reasons = [reason for reason in map(refusal, request.parameters) if reason]
        if not reasons:
            return callback(request, response)
        response.result = SetParametersResult(successful=False, reason='; '.join(reasons))
        return response
    guarded.guards_parameter_types = True
    return guarded


def guard_clock(node) -> None:
    """
    Make a node's /clock subscription (sim time) skip messages rclpy cannot take.

    A message with negative seconds is skipped with a warning (at most one a second); the
    node's clock keeps its last time. Does nothing without sim time (no /clock subscription).
    Idempotent.
    """
    for subscription in node.subscriptions:
        if (subscription.topic_name != CLOCK_TOPIC or subscription.msg_type is not Clock
                or getattr(subscription.callback, 'guards_clock', False)):
            continue
        subscription.callback = _guard_clock_callback(subscription.callback, node.get_logger())


def _guard_clock_callback(callback, logger):
    """Wrap rclpy's clock callback: skip a time it would raise on."""
    def guarded(message):
        if message.clock.sec < 0:
            # One call site, one kind of warning: rclpy's own throttle is enough here.
            logger.warning(
                f'{CLOCK_TOPIC} message of {message.clock.sec} s {message.clock.nanosec} ns '
                'skipped: a time cannot be negative; the clock keeps its last time',
                throttle_duration_sec=WARNING_PERIOD)
            return
        callback(message)
    guarded.guards_clock = True
    return guarded


def guard_change_state(node) -> None:
    """
    Make a lifecycle node's ``~/change_state`` refuse a transition its state does not have.

    rclpy's service asks the state machine for the transition by id and raises ``RCLError``
    inside the executor when there is none from the current state (a label is looked up
    first, and refused without raising): the node would exit with a traceback. Wrapped here,
    the request is answered ``success: false`` with a warning, as a label is. Idempotent.
    """
    for service in node.services:
        if service.srv_type is ChangeState and not getattr(
                service.callback, 'guards_transitions', False):
            service.callback = _guard_change_state(service.callback, node.get_logger())


def _guard_change_state(callback, logger):
    """Wrap rclpy's change_state callback: a transition that does not exist is refused."""
    def guarded(request, response):
        try:
            return callback(request, response)
        except RCLError as error:
            logger.warning(f'change_state: transition {request.transition.id} '
                           f'{preview(request.transition.label)} refused: {error}')
            response.success = False
            return response
    guarded.guards_transitions = True
    return guarded
