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
The publishers of actuator commands: they send the command gate's verdicts, and nothing else.

Every topic that commands an actuator is declared so in
:mod:`stewart_kinematics.ros.interfaces` (``Endpoint.commands``), and
:func:`stewart_kinematics.ros.node_main.create_output_publisher` gives it a
:class:`CommandPublisher` instead of an rclpy publisher: its :meth:`~CommandPublisher.publish`
takes an accepted :class:`~stewart_kinematics.limits.Verdict` of the command gate
(:class:`~stewart_kinematics.limits.CommandGate`) and builds the message from the numbers the
gate checked, with the converter the node gave when it created the publisher. A bare array or
message, or a refused verdict, raises: a node cannot send a command that did not pass the gate.
"""

from stewart_kinematics.findings import CODES
from stewart_kinematics.limits import Verdict


class CommandPublisher:
    """
    A publisher of actuator commands that takes only the command gate's accepted verdicts.

    :param publisher: the rclpy publisher of the declared topic (kept private).
    :param endpoint: its :class:`~stewart_kinematics.ros.interfaces.Endpoint`.
    :param to_message: ``to_message(verdict, *extra) -> message``: the message of a verdict,
        from the numbers the gate checked (``extra``: a header, say).
    """

    def __init__(self, publisher, endpoint, to_message):
        self._publisher = publisher
        self.endpoint = endpoint
        self._to_message = to_message

    @property
    def topic_name(self) -> str:
        """Return the topic's resolved name."""
        return self._publisher.topic_name

    def get_subscription_count(self) -> int:
        """Return how many subscriptions are matched (to skip building an unread message)."""
        return self._publisher.get_subscription_count()

    def prepare(self, verdict, *extra) -> 'PreparedCommand':
        """
        Build the message of an accepted verdict now, to send later (any thread: no ROS call).

        For a large message (a leg trajectory of thousands of points) built off the executor.

        :raises TypeError: for anything but a :class:`~stewart_kinematics.limits.Verdict`.
        :raises ValueError: for a refused verdict.
        """
        if not isinstance(verdict, Verdict):
            raise TypeError(f'{self.endpoint.name} commands actuators: it sends only a verdict of '
                            f'the command gate, got {type(verdict).__name__}')
        if not verdict.accepted:
            raise ValueError(f'{self.endpoint.name}: a refused command cannot be sent '
                             f'({verdict.refusal.code})')
        return PreparedCommand(self, verdict, self._to_message(verdict, *extra))

    def publish(self, verdict, *extra) -> None:
        """
        Send the message of an accepted verdict of the command gate (or one :meth:`prepare` made).

        :raises TypeError: for anything but a :class:`~stewart_kinematics.limits.Verdict`, or a
            :class:`PreparedCommand` of another publisher.
        :raises ValueError: for a refused verdict.
        """
        if isinstance(verdict, PreparedCommand):
            if verdict.publisher is not self:
                raise TypeError(f'{self.endpoint.name}: a command prepared for '
                                f'{verdict.publisher.endpoint.name}')
            self._publisher.publish(verdict.message)
            return
        self._publisher.publish(self.prepare(verdict, *extra).message)

    def destroy(self) -> None:
        """Destroy the underlying publisher (with the node, as rclpy does)."""
        self._publisher.destroy()


class PreparedCommand:
    """
    The message of an accepted verdict, built by :meth:`CommandPublisher.prepare`, to send later.

    Its header may still be set (stamped when it is sent); its numbers are the verdict's.
    """

    __slots__ = ('publisher', 'verdict', 'message')

    def __init__(self, publisher, verdict, message):
        self.publisher, self.verdict, self.message = publisher, verdict, message

    @property
    def accepted(self) -> bool:
        """Return True: only an accepted verdict is prepared."""
        return True

    @property
    def warnings(self):
        """Return the verdict's warnings."""
        return self.verdict.warnings


def send_command(publisher: CommandPublisher, accounting, verdict, *extra) -> bool:
    """
    Send a verdict on its publisher and count it with its input's accounting.

    A refused verdict is counted as a rejection with its reason and nothing is sent. An
    accepted one is sent; its warnings are counted, and one of the refusal class (a braking
    command that replaces a refused one: ``command_braking``) counts the input as rejected:
    what was asked for was not sent.

    :param accounting: the input's :class:`~stewart_kinematics.ros.message_accounting.
        MessageAccounting`.
    :returns: whether something was sent.
    """
    if not verdict.accepted:
        accounting.reject(verdict.refusal)
        return False
    replaced = False
    for finding in verdict.warnings:
        if CODES[finding.code].kind == 'refusal':
            accounting.reject(finding)
            replaced = True
        else:
            accounting.warn(finding)
    if replaced:
        publisher.publish(verdict, *extra)
    else:
        accounting.publish(publisher, verdict, *extra)
    return True
