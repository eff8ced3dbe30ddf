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
Managed (lifecycle) nodes: one node class, managed or not by its read-only ``managed`` parameter.

Every node of the package is a :class:`ManagedNode`, an ``rclpy.lifecycle`` node
(``LifecycleNodeMixin`` over ``rclpy.node.Node``) built in two steps, which is how ``managed``
is read before the lifecycle part exists: ``Node.__init__`` first, then the ``managed``
parameter is declared and read (from the parameter files, ``-p`` or ``parameter_overrides``,
as any parameter), then, only if it is true, ``LifecycleNodeMixin.__init__``, which makes the
lifecycle state machine and its services. So there is one class per node and no second
reading of the command line. (Not ``enable_communication_interface=False`` for an unmanaged
node: rcl_lifecycle creates the ``~/transition_event`` publisher even then, and the node would
not be the node it was.)

- ``managed: false`` (the default, what ``ros2 run`` gives): no state machine, no lifecycle
  service or topic; the constructor does the configure and activate transitions' work itself,
  and a parameter it refuses raises there, so the process exits with the reason, exactly as
  the nodes always did. The node is the same node as before.
- ``managed: true``: the node has the standard services (``~/change_state``, ``~/get_state``,
  ``~/get_available_states``, ``~/get_available_transitions``, ``~/get_transition_graph``) and
  publishes ``~/transition_event``. It starts **unconfigured**: its parameters are declared
  (a bad value or a bad file is kept, not refused: :class:`~stewart_kinematics.ros.
  ros_parameters.DeferredChecks`), nothing else exists, nothing is published.

The transitions, the same for every node (the node's own parts in brackets)::

    configure   check every parameter, build the geometry and everything else: publishers,
                subscriptions, services, timers, worker threads and processes [configure()];
                a refusal logs the reason, releases what was built, and the node stays
                unconfigured, alive, answering the next transition
    activate    publishers enabled, inputs acted on [activate()]
    deactivate  [deactivate(): stop commanding, leave the platform at rest], then nothing
                is published and no input is acted on
    cleanup     [cleanup(): worker threads and processes], then every publisher,
                subscription, service, timer and waitable made by configure is destroyed;
                read-only parameters may be set again
    shutdown    from any state: deactivate and cleanup as needed; the process ends once
                every node it runs is finalized

How "nothing is published and no input is acted on" holds: while managed, the publishers are
``LifecyclePublisher``s, which drop a message unless the node is active, and every callback the
node gets (subscriptions and services made by ``node_main``, timers, and the tasks worker threads
hand to the executor with ``hand_to_executor``) goes through :meth:`ManagedNode.gated`: while
inactive, a message is **ignored** (counted by topic, and logged at most once a second), a
timer tick does nothing, a task is dropped (a worker's result waits for its next tick), and
a service of the std_srvs/Trigger kind answers ``success: false`` saying the node is inactive.
A message received while inactive is never acted on later: nothing of it is kept.

A node takes part by deriving from :class:`ManagedNode`, naming its settings class, and
providing its parts (doc/lifecycle.md shows it in a few lines)::

    class MyNode(ManagedNode):
        SETTINGS = MyNodeSettings      # its parameters, declared by ManagedNode

        def __init__(self, **kwargs):
            super().__init__('my_node', **kwargs)

        def configure(self):           # self.settings holds the checked parameters
            ...                        # raise ValueError(reason) to refuse
        def deactivate(self):          # bring the platform to rest (may block briefly)
            ...
        def cleanup(self):             # stop threads and processes (entities: done here)
            ...
"""

import time

from rclpy.exceptions import ParameterException
from rclpy.lifecycle import LifecycleNodeMixin, LifecyclePublisher, TransitionCallbackReturn
from rclpy.node import Node

from stewart_kinematics.parameters import frame_parameters_reason, LIFECYCLE_PARAMETERS
from stewart_kinematics.ros.rclpy_guards import guard_change_state
from stewart_kinematics.ros.ros_parameters import (
    declare_parameters,
    declare_settings,
    DeferredChecks,
)

#: Seconds between two log lines about inputs ignored while inactive.
IGNORED_LOG_PERIOD = 1.0


class ManagedNode(LifecycleNodeMixin, Node):
    """
    A node of the package: managed (lifecycle) with ``managed: true``, else active at once.

    :param node_name: the node's default name.
    :param kwargs: ``rclpy.node.Node``'s keyword arguments (``parameter_overrides``, ...).
    :raises ValueError, rclpy.exceptions.ParameterException: unmanaged, for a parameter it
        refuses (the node cannot start); managed, only for a bad ``managed`` itself.
    """

    #: The node's settings class (a :class:`~stewart_kinematics.parameters.NodeSettings`).
    SETTINGS = None
    #: ``check(values) -> reason`` between parameters (distinct frame names, ...).
    PARAMETERS_CHECK = staticmethod(frame_parameters_reason)

    def __init__(self, node_name: str, **kwargs):
        Node.__init__(self, node_name, **kwargs)
        # managed first, alone: the names and values of the others are checked just below.
        first = DeferredChecks(lambda: False, settable=False)
        self.managed = bool(declare_parameters(
            self, LIFECYCLE_PARAMETERS, node_options=kwargs, deferred=first)['managed'])
        if 'managed' in first.problems:
            raise ValueError(first.problems['managed'])
        if self.managed:
            # Unmanaged, no state machine at all: rcl_lifecycle would create the
            # ~/transition_event publisher even without its communication interface.
            LifecycleNodeMixin.__init__(self)
            guard_change_state(self)
        #: Whether inputs are acted on and outputs published (lifecycle state ``active``).
        self.active = False
        #: Whether the node is built (``inactive`` or ``active``).
        self.configured = False
        #: Whether the shutdown transition has run: the process may end.
        self.finalized = False
        #: Why the last configure failed (the exception), or ``None``.
        self.configure_error = None
        #: Messages ignored while inactive, by topic.
        self.ignored_inputs = {}
        self._ignored_logged = 0.0
        self._built = None
        self._deferred = DeferredChecks(lambda: not self.configured) if self.managed else None
        #: The settings the node runs with (a dict of the values given while unconfigured).
        self.settings = declare_settings(
            self, self.SETTINGS, on_change=self.on_parameter_change,
            check=self.parameters_check, node_options=kwargs, payload=self.run_time_payload(),
            deferred=self._deferred, skip=('managed',))
        if not self.managed:
            # The same parts as the transitions, called in turn: the node is active.
            if self._configure() != TransitionCallbackReturn.SUCCESS:
                raise self.configure_error
            self._activate()

    # The node's parts: overridden by each node.

    def run_time_payload(self):
        """Return how the node takes a new payload at run time, or ``None``."""
        return None

    def parameters_check(self, values) -> str:
        """Return ``''`` if the parameter values (all, after a change) may be set, else why not."""
        return self.PARAMETERS_CHECK(values)

    def on_parameter_change(self, name, value):
        """Take a validated run-time change of a parameter (the node is configured)."""

    def configure(self):
        """Build everything from ``self.settings``; raise ``ValueError`` to refuse."""

    def activate(self):
        """Start acting (publishers are enabled already)."""

    def deactivate(self):
        """Stop commanding and leave the platform at rest (publishers still enabled)."""

    def cleanup(self):
        """Stop worker threads and processes (entities are destroyed by the mechanism)."""

    # The mechanism.

    def gated(self, callback, topic=None, service=False):
        """
        Return ``callback``, acted on only while the node is active (unmanaged: unchanged).

        :param topic: the input's topic: a message while inactive is counted as ignored.
        :param service: a service callback: answered ``success: false`` while inactive.
        """
        if not getattr(self, 'managed', False):
            return callback

        def gate(*args):
            if self.active:
                return callback(*args)
            if service:
                response = args[1]
                if hasattr(response, 'success') and hasattr(response, 'message'):
                    response.success = False
                    response.message = (f'{self.get_name()} is not active (lifecycle state '
                                        f'{self.lifecycle_state()}): nothing done')
                return response
            if topic is not None:
                self._ignore(topic)
            return None
        return gate

    def _ignore(self, topic):
        """Count a message ignored while inactive; say so at most once a second."""
        self.ignored_inputs[topic] = self.ignored_inputs.get(topic, 0) + 1
        now = time.monotonic()
        if now - self._ignored_logged >= IGNORED_LOG_PERIOD:
            self._ignored_logged = now
            self.get_logger().info(
                f'{topic}: message ignored, the node is not active (lifecycle state '
                f'{self.lifecycle_state()}); {self.ignored_inputs[topic]} so far')

    def lifecycle_state(self) -> str:
        """Return the label of the lifecycle state: unconfigured, inactive, active, ..."""
        if not self.managed:
            return 'active' if self.active else 'finalized'
        return self._state_machine.current_state[1]

    def create_timer(self, timer_period_sec, callback, *args, **kwargs):
        """Create a timer whose ticks do nothing while the node is inactive (managed)."""
        if callback is not None:
            callback = self.gated(callback)
        return super().create_timer(timer_period_sec, callback, *args, **kwargs)

    def create_publisher(self, *args, **kwargs):
        """Create a publisher; managed, a LifecyclePublisher (nothing sent while inactive)."""
        if getattr(self, '_built', None) is not None and self.managed and (
                'publisher_class' not in kwargs):
            publisher = self.create_lifecycle_publisher(*args, **kwargs)
            if self.active:   # made while active (lazily): it sends at once
                publisher.on_activate(None)
            return publisher
        return super().create_publisher(*args, **kwargs)

    def on_configure(self, state) -> TransitionCallbackReturn:
        """Check the parameters and build the node; a refusal leaves it unconfigured."""
        result = self._configure()
        if result != TransitionCallbackReturn.SUCCESS:
            return result
        return super().on_configure(state)

    def _configure(self) -> TransitionCallbackReturn:
        """Do the configure transition's work: SUCCESS, or FAILURE with ``configure_error`` set."""
        self.configure_error = None
        try:
            if self._deferred is not None:
                self.settings = self._deferred.settings(self, self.SETTINGS,
                                                        self.parameters_check)
            self._built = _entities(self)
            self.configure()
        except Exception as error:  # noqa: B902 - a managed node stays alive, whatever failed
            self.configure_error = error
            if self.managed:
                kind = '' if isinstance(error, (ValueError, ParameterException)) else (
                    f'{type(error).__name__}: ')
                self.get_logger().error(
                    f'configure failed, the node stays unconfigured: {kind}{error}')
            self._release()
            return TransitionCallbackReturn.FAILURE
        self.configured = True
        if self.managed:
            self.get_logger().info('configured (inactive): activate it to start')
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state) -> TransitionCallbackReturn:
        """Enable the publishers, act on inputs."""
        result = super().on_activate(state)
        if result != TransitionCallbackReturn.SUCCESS:
            return result
        if not self._activate():
            super().on_deactivate(state)
            return TransitionCallbackReturn.FAILURE
        self.get_logger().info('active')
        return result

    def _activate(self) -> bool:
        """Do the activate transition's work; return whether it succeeded (else inactive)."""
        self.active = True
        try:
            self.activate()
        except Exception as error:  # noqa: B902 - the transition fails, the node stays inactive
            self.active = False
            if self.managed:
                self.get_logger().error(f'activate failed, the node stays inactive: {error}')
            else:
                raise
            return False
        return True

    def on_deactivate(self, state) -> TransitionCallbackReturn:
        """Bring the platform to rest, then publish nothing and ignore inputs."""
        self._deactivate()
        self.get_logger().info('deactivated (inactive)')
        return super().on_deactivate(state)

    def _deactivate(self):
        """Do the deactivate transition's work: the node's part, then inactive whatever happens."""
        try:
            self.deactivate()
        except Exception as error:  # noqa: B902 - inactive whatever happened
            self.get_logger().error(f'deactivate: {type(error).__name__}: {error}')
        self.active = False

    def on_cleanup(self, state) -> TransitionCallbackReturn:
        """Release everything configure built: the node is unconfigured again."""
        self._release()
        self.get_logger().info('cleaned up (unconfigured)')
        return super().on_cleanup(state)

    def on_shutdown(self, state) -> TransitionCallbackReturn:
        """From any state: deactivate and clean up as needed; the node is finalized."""
        if self.active:
            self._deactivate()
            super().on_deactivate(state)
        self._release()
        self.finalized = True
        self.get_logger().info('shut down (finalized)')
        return TransitionCallbackReturn.SUCCESS

    def on_error(self, state) -> TransitionCallbackReturn:
        """After a transition raised: release everything; the node is unconfigured."""
        self.active = False
        self._release()
        return TransitionCallbackReturn.SUCCESS

    def _release(self):
        """Stop the node's workers, then destroy every entity built since configure began."""
        self.active = False
        if self._built is None:
            return
        try:
            self.cleanup()
        except Exception as error:  # noqa: B902 - the entities are released all the same
            self.get_logger().error(f'cleanup: {type(error).__name__}: {error}')
        publishers, subscriptions, services, clients, timers, waitables = self._built
        self._built = None
        self.configured = False
        for timer in [timer for timer in self.timers if timer not in timers]:
            self.destroy_timer(timer)
        for subscription in [item for item in self.subscriptions if item not in subscriptions]:
            self.destroy_subscription(subscription)
        for service in [item for item in self.services if item not in services]:
            self.destroy_service(service)
        for client in [item for item in self.clients if item not in clients]:
            self.destroy_client(client)
        for publisher in [item for item in self.publishers if item not in publishers]:
            if isinstance(publisher, LifecyclePublisher):
                self.destroy_lifecycle_publisher(publisher)
            else:
                self.destroy_publisher(publisher)
        for waitable in [item for item in self.waitables if item not in waitables]:
            # An action server, say; the event handlers went with their entities.
            self.remove_waitable(waitable)
            destroy = getattr(waitable, 'destroy', None)
            if destroy is not None:
                destroy()

    def destroy_node(self):
        """Stop the node's workers (a clean stop in any state), then destroy the node."""
        if self._built is not None:
            try:
                self.cleanup()
            except Exception as error:  # noqa: B902 - the node is destroyed all the same
                self.get_logger().error(f'cleanup: {type(error).__name__}: {error}')
            self._built = None
        self.active = self.configured = False
        return super().destroy_node()


def _entities(node):
    """Return the node's entities now, by kind: what configure adds is released by cleanup."""
    return (set(node.publishers), set(node.subscriptions), set(node.services),
            set(node.clients), set(node.timers), set(node.waitables))
