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
What the nodes share: ``main()`` (start-up, spinning, a clean stop), publishers, subscriptions.

Every node process spins on rclpy's ``EventsExecutor`` (``rclpy.experimental``, rclpy 7.1.6)
unless told otherwise, before ``--ros-args`` or in the environment (the argument wins)::

    ik_node --executor single_threaded --ros-args ...
    STEWART_EXECUTOR=single_threaded ros2 launch stewart_kinematics ...

An executor exists before any node, so a ROS parameter cannot choose it. See :data:`EXECUTORS`.
A process whose nodes start with ``use_sim_time`` spins on the single-threaded executor
whatever was asked (:func:`executor_for_nodes`): the events executor's timers do not keep to a
simulated clock.

Every publisher, subscription and service of the package is created here, from its declaration
in :mod:`stewart_kinematics.ros.interfaces`, with the QoS declared there; publishers and
subscriptions with ``QoSOverridingOptions.with_default_policies()``: the standard
``qos_overrides.<topic>.<publisher|subscription>.<reliability|history|depth>`` parameters then
apply to them.
"""

import os
import signal
import sys

import rclpy
# rclpy exposes these two only from its C extension.
from rclpy._rclpy_pybind11 import RCLError, UnknownROSArgsError
from rclpy.event_handler import PublisherEventCallbacks
from rclpy.exceptions import ParameterException
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.experimental import EventsExecutor
from rclpy.lifecycle import TransitionCallbackReturn
from rclpy.qos_overriding_options import QoSOverridingOptions
from rclpy.signals import SignalHandlerOptions
from rclpy.task import Future
from rclpy.utilities import get_default_context, remove_ros_args

from stewart_kinematics.ros.command_publishing import CommandPublisher
from stewart_kinematics.ros.ros_parameters import (
    parameter_file_problem,
    remember_process_arguments,
)

#: Exit code of a node that could not start (bad parameters, bad arguments).
EXIT_START_FAILED = 1
#: Longest a node waits for work before it checks again whether it was asked to stop, seconds.
SPIN_SLICE = 0.1
#: The signals that stop a node cleanly: Ctrl-C and what a supervisor sends.
STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)
#: The executors a node process can spin on, by the name that chooses them.
EXECUTORS = {
    # Callbacks run as rmw reports events, without rebuilding a wait set for each message:
    # under half the processor time per message of the single-threaded executor
    # (doc/benchmarks.md).
    'events': EventsExecutor,
    # rclpy's default executor; it also supports guard conditions.
    'single_threaded': SingleThreadedExecutor,
}
DEFAULT_EXECUTOR = 'events'
#: The environment variable that chooses the executor of every node process it reaches.
EXECUTOR_VARIABLE = 'STEWART_EXECUTOR'
#: The command-line option, before ``--ros-args``, that chooses it for one process.
EXECUTOR_OPTION = '--executor'
#: The executor of a process whose nodes run on a simulated clock (``use_sim_time``). rclpy's
#: EventsExecutor drives timers from its own timer manager, which does not follow a simulated
#: clock (rclcpp's has the same limit, ros2/rclcpp#2457): under processor load, a timer of the
#: simulated clock fired once too often and then skipped the next tick, so trajectory_node
#: published a sample twice and not the next one (test/processes/test_sim_time.py failed 5 of
#: 14 runs with two busy processes beside it, and none of 8 on this executor).
SIM_TIME_EXECUTOR = 'single_threaded'
#: The future a slice of the EventsExecutor waits for (:func:`spin_slice`): never done.
_NEVER_DONE = Future()


def executor_name(arguments=(), environment=None) -> str:
    """
    Return the name of the executor chosen: by ``--executor``, else the environment, else events.

    :param arguments: the process's arguments without the ROS ones (``remove_ros_args``):
        ``--executor NAME`` or ``--executor=NAME``.
    :param environment: where :data:`EXECUTOR_VARIABLE` is read; default ``os.environ``.
    :raises ValueError: for a name not in :data:`EXECUTORS`, naming the allowed ones.
    """
    environment = os.environ if environment is None else environment
    name, source = environment.get(EXECUTOR_VARIABLE, ''), EXECUTOR_VARIABLE
    if not name:
        name, source = DEFAULT_EXECUTOR, 'default'
    arguments = list(arguments)
    for index, argument in enumerate(arguments):
        if argument == EXECUTOR_OPTION:
            if index + 1 == len(arguments):
                raise ValueError(f'{EXECUTOR_OPTION} needs a value: one of '
                                 f'{", ".join(EXECUTORS)}')
            name, source = arguments[index + 1], EXECUTOR_OPTION
        elif argument.startswith(EXECUTOR_OPTION + '='):
            name, source = argument.partition('=')[2], EXECUTOR_OPTION
    if name not in EXECUTORS:
        raise ValueError(f'unknown executor {name!r} (from {source}): allowed are '
                         f'{", ".join(EXECUTORS)}')
    return name


def create_executor(name=None, context=None):
    """
    Create an executor by name; ``None`` takes the one the environment chooses.

    The Python signal handlers in place stay in place: the EventsExecutor leaves them alone
    (checked on rclpy 7.1.6), and this keeps it so whatever a later rclpy does.

    :param name: a key of :data:`EXECUTORS`, or ``None`` for :func:`executor_name` ``()``.
    :param context: the rclpy context; default the default one.
    :raises ValueError: as :func:`executor_name`.
    """
    name = executor_name() if name is None else name
    if name not in EXECUTORS:
        raise ValueError(f'unknown executor {name!r}: allowed are {", ".join(EXECUTORS)}')
    handlers = {number: signal.getsignal(number) for number in STOP_SIGNALS}
    executor = EXECUTORS[name](context=context)
    for number, handler in handlers.items():
        if handler is not None and signal.getsignal(number) is not handler:
            signal.signal(number, handler)
    return executor


def spin_slice(executor, seconds: float = SPIN_SLICE) -> None:
    """
    Run the executor's callbacks for up to ``seconds``, then return; safe to call in a loop.

    The EventsExecutor runs every callback that comes within the slice without coming back to
    Python between two (``spin_until_future_complete`` on a future that never completes):
    its ``spin_once`` returns after each callback, and the Python loop around it then costs
    every message its own round trip. The single-threaded executor returns after each callback
    whatever it is asked (its ``spin_until_future_complete`` loops on ``spin_once`` in
    Python), so it spins once.

    :param executor: an executor of :data:`EXECUTORS`.
    :param seconds: the longest the call takes when callbacks keep coming, and the longest it
        waits for one, seconds.
    """
    if isinstance(executor, SingleThreadedExecutor):
        executor.spin_once(timeout_sec=seconds)
    else:
        executor.spin_until_future_complete(_NEVER_DONE, timeout_sec=seconds)


def run_node(node_class, name: str, args=None) -> int:
    """
    Initialise rclpy, build and spin a node until SIGINT or SIGTERM, then shut down.

    :param node_class: the node's class, constructed without arguments.
    :param name: the node's default name, for the log of a failed start.
    :param args: command-line arguments (``--ros-args ...``); ``None`` reads ``sys.argv``.
    :returns: as :func:`run_nodes`.
    """
    return run_nodes([node_class], name, args)


def executor_for_nodes(name: str, nodes):
    """
    Return the executor the nodes spin on, and why it is not ``name`` (or ``''``).

    :param name: the executor asked for (:func:`executor_name`).
    :param nodes: the process's nodes, built: a node with ``use_sim_time`` set takes
        :data:`SIM_TIME_EXECUTOR`.
    """
    if name != SIM_TIME_EXECUTOR and any(getattr(node, 'SERVES_ACTIONS', False)
                                         for node in nodes):
        # rclpy 7.1.6's EventsExecutor never answered a FollowJointTrajectory goal.
        return SIM_TIME_EXECUTOR, (
            f'an action server: spinning on the {SIM_TIME_EXECUTOR} executor, not {name} (it '
            'does not run rclpy action servers)')
    if name == SIM_TIME_EXECUTOR or not any(
            node.get_parameter('use_sim_time').value for node in nodes):
        return name, ''
    return SIM_TIME_EXECUTOR, (
        f'use_sim_time: spinning on the {SIM_TIME_EXECUTOR} executor, not {name} (its timers '
        'do not keep to a simulated clock)')


def run_nodes(node_classes, name: str, args=None, autostart: bool = False) -> int:
    """
    Initialise rclpy, build nodes and spin them in one executor until SIGINT or SIGTERM.

    The executor is the one :func:`executor_name` chooses (``--executor`` before
    ``--ros-args``, else ``STEWART_EXECUTOR``, else events). It spins in slices of
    :data:`SPIN_SLICE` in this thread: the signals only set a flag, checked between two
    slices, so neither a KeyboardInterrupt nor a context shut down from rclpy's signal thread
    can land in the middle of a callback, of a take or of the clean-up, on either executor.

    :param node_classes: the nodes' classes, each constructed without arguments, in order.
    :param name: the process's name, for the log of a failed start.
    :param args: command-line arguments (``--ros-args ...``); ``None`` reads ``sys.argv``.
    :param autostart: configure then activate each managed node (``managed: true``) once it
        spins, as a lifecycle manager's autostart would; a refused configure leaves that node
        unconfigured (its log says why), the others go on.
    :returns: 0 after a clean stop, :data:`EXIT_START_FAILED` when a parameter file cannot
        be read, a node could not be built or the executor is unknown, with a fatal log that
        says why.
    """
    stop_requests = []
    previous = {number: signal.signal(number, lambda number, frame: stop_requests.append(number))
                for number in STOP_SIGNALS}
    try:
        # The package's reader first: rcl takes half a minute to parse a list nested 100,000
        # deep; ours refuses it at once, naming the file and the line.
        problem = parameter_file_problem(sys.argv if args is None else args)
        if problem:
            rclpy.logging.get_logger(name).fatal(f'cannot start: {problem}')
            return EXIT_START_FAILED
        try:
            rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
            remember_process_arguments(get_default_context(), args)
        except (RCLError, UnknownROSArgsError) as error:
            rclpy.logging.get_logger(name).fatal(f'cannot start: {error}')
            return EXIT_START_FAILED
        try:
            # After rclpy.init, which has said what is wrong with the ROS arguments, if anything.
            executor_kind = executor_name(remove_ros_args(sys.argv if args is None else args))
        except ValueError as error:
            rclpy.logging.get_logger(name).fatal(f'cannot start: {error}')
            rclpy.try_shutdown()
            return EXIT_START_FAILED
        nodes = []
        try:
            for node_class in node_classes:
                nodes.append(node_class())
        except (ParameterException, ValueError) as error:
            rclpy.logging.get_logger(name).fatal(f'cannot start: {error}')
            for node in nodes:
                node.destroy_node()
            rclpy.try_shutdown()
            return EXIT_START_FAILED
        executor = None
        try:
            executor_kind, reason = executor_for_nodes(executor_kind, nodes)
            if reason:
                rclpy.logging.get_logger(name).info(reason)
            executor = create_executor(executor_kind)
            for node in nodes:
                executor.add_node(node)
            rclpy.logging.get_logger(name).info(f'spinning on the {executor_kind} executor')
            for node in nodes if autostart else ():
                if getattr(node, 'managed', False) and (
                        node.trigger_configure() == TransitionCallbackReturn.SUCCESS):
                    node.trigger_activate()
            # A managed node's shutdown transition finalizes it: with every node finalized,
            # the process has nothing left to do.
            while not stop_requests and rclpy.ok() and not all(
                    getattr(node, 'finalized', False) for node in nodes):
                spin_slice(executor)
        except ExternalShutdownException:
            pass
        finally:
            # The executor first: the EventsExecutor unhooks its callbacks from the entities,
            # which must still exist.
            if executor is not None:
                executor.shutdown()
            for node in nodes:
                node.destroy_node()
            rclpy.try_shutdown()
        return 0
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)


def hand_to_executor(node, callback) -> bool:
    """
    Have ``callback()`` called by the executor that spins ``node``; safe from any thread.

    The worker threads' way back to the executor (ik_node's workspace results, trajectory_node's
    plans): ``executor.create_task``, which both executors take from another thread and which
    wakes them. The EventsExecutor supports no guard condition, the usual way.

    :returns: whether it was handed over: not while the node is in no executor (the caller
        keeps what it had to deliver and tries again later).
    """
    executor = node.executor
    if executor is None:
        return False
    # A managed node drops it while inactive (stewart_kinematics.ros.managed).
    gated = getattr(node, 'gated', None)
    executor.create_task(callback if gated is None else gated(callback))
    return True


def create_output_publisher(node, endpoint, queue_depth=None, to_message=None):
    """
    Create a declared publisher (by default reliable, keep-last) without rclpy's event handlers.

    rclpy's executor visits every event handler of a node at each wait, two per publisher by
    default (incompatible QoS, incompatible type), and on a 1 kHz input that work costs the
    node a third of its rate. A subscriber whose QoS does not match still reports it on its
    own side; the nodes' subscriptions keep their handlers, so a mismatched input is reported
    here. The ``qos_overrides`` parameters of the topic's publisher apply.

    A topic declared to command actuators (``endpoint.commands``) gets a
    :class:`~stewart_kinematics.ros.command_publishing.CommandPublisher`: it publishes only the
    command gate's accepted verdicts, as messages built by ``to_message``.

    :param endpoint: the publisher's :class:`~stewart_kinematics.ros.interfaces.Endpoint`,
        created with its declared QoS.
    :param queue_depth: the node's ``queue_depth`` parameter, for an endpoint whose QoS keeps
        that many messages (messages); the others ignore it.
    :param to_message: for a command topic, ``to_message(verdict, *extra) -> message``; must
        be ``None`` for any other.
    :raises ValueError: for a command topic without ``to_message``, or another with one.
    """
    if endpoint.commands != (to_message is not None):
        raise ValueError(f'{endpoint.name}: a topic that commands actuators needs to_message '
                         "to build its messages from the gate's verdicts, and no other takes one")
    publisher = node.create_publisher(
        endpoint.message_type, endpoint.name, endpoint.qos.profile(queue_depth),
        event_callbacks=PublisherEventCallbacks(use_default_callbacks=False),
        qos_overriding_options=QoSOverridingOptions.with_default_policies())
    return CommandPublisher(publisher, endpoint, to_message) if endpoint.commands else publisher


def create_input_subscription(node, endpoint, callback, queue_depth=None):
    """
    Create a declared subscription (by default reliable, keep-last) whose QoS may be overridden.

    The ``qos_overrides`` parameters of the topic's subscription apply: for example
    ``qos_overrides./joint_states.subscription.reliability: best_effort`` for a driver that
    publishes best effort. rclpy's default event handlers stay: a mismatch is logged.

    :param endpoint: the subscription's :class:`~stewart_kinematics.ros.interfaces.Endpoint`,
        created with its declared QoS.
    :param queue_depth: the node's ``queue_depth`` parameter, for an endpoint whose QoS keeps
        that many messages (messages); the others ignore it.
    """
    gated = getattr(node, 'gated', None)
    if gated is not None:   # a managed node ignores messages while inactive
        callback = gated(callback, topic=endpoint.name)
    return node.create_subscription(
        endpoint.message_type, endpoint.name, callback, endpoint.qos.profile(queue_depth),
        qos_overriding_options=QoSOverridingOptions.with_default_policies())


def create_declared_service(node, endpoint, callback):
    """
    Create a declared service, with its declared QoS.

    :param endpoint: the service's :class:`~stewart_kinematics.ros.interfaces.Endpoint`.
    """
    gated = getattr(node, 'gated', None)
    if gated is not None:   # a managed node answers that it is inactive
        callback = gated(callback, service=True)
    return node.create_service(endpoint.message_type, endpoint.name, callback,
                               qos_profile=endpoint.qos.profile())
