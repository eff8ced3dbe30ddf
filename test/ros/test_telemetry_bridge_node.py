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
telemetry_bridge in this process: managed and unmanaged, its socket, its start-up refusals.

Managed, the socket is bound by configure and closed by cleanup, nothing is published while
inactive, and what arrived meanwhile is thrown away on activate; a port another socket holds
fails configure with the reason and leaves the node unconfigured and alive; an address that is
not IPv4 stops an unmanaged start with the reason (the parameter's validator). About 2 s.
"""

import socket
import struct

import pytest
from rclpy.exceptions import ParameterException
from rclpy.lifecycle import TransitionCallbackReturn
from rclpy.parameter import Parameter
from sensor_msgs.msg import Imu

from stewart_kinematics.ros.node_main import create_executor
from stewart_kinematics.ros.telemetry_bridge import TelemetryBridge

pytestmark = pytest.mark.node

SUCCESS, FAILURE = TransitionCallbackReturn.SUCCESS, TransitionCallbackReturn.FAILURE


def packet(sequence, stamp_ns):
    """Build a valid packet of the documented layout, the vehicle at rest."""
    return (b'SKTM' + struct.pack('<HHIQ', 1, 0, sequence, stamp_ns)
            + struct.pack('<6d', 0.0, 0.0, 9.81, 0.0, 0.0, 0.0))


def free_port():
    """Return a UDP port of loopback that nobody uses now."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


@pytest.fixture
def rig(ros, spin_until):
    """Build a bridge on a free port with a listener; yield (node, port, messages, spin)."""
    made = []

    def build(*overrides, port=None):
        port = free_port() if port is None else port
        node = TelemetryBridge(parameter_overrides=[
            Parameter('telemetry_port', value=port), *overrides])
        listener = ros.create_node('telemetry_listener')
        messages = []
        listener.create_subscription(Imu, 'vehicle_imu', messages.append, 100)
        executor = create_executor()
        executor.add_node(node)
        executor.add_node(listener)
        made.append((executor, node, listener))

        def spin(condition, timeout=5.0):
            return spin_until(executor, condition, timeout)
        return node, port, messages, spin
    yield build
    for executor, node, listener in made:
        executor.shutdown()
        node.destroy_node()
        listener.destroy_node()


def send(port, *datagrams):
    """Send datagrams to the bridge's port."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as udp:
        for datagram in datagrams:
            udp.sendto(datagram, ('127.0.0.1', port))


def test_managed_bridge_binds_on_configure_publishes_only_when_active(rig):
    """Unconfigured: no socket; inactive: nothing out, and activate drops what came."""
    node, port, messages, spin = rig(Parameter('managed', value=True))
    assert node.socket is None
    assert node.trigger_configure() == SUCCESS and node.socket is not None
    send(port, packet(1, 100))
    spin(lambda: False, timeout=0.3)
    assert messages == []
    assert node.trigger_activate() == SUCCESS
    send(port, packet(0, 50))     # a new stream: the packet of the inactive time is gone
    assert spin(lambda: len(messages) == 1)
    assert messages[0].header.stamp.nanosec == 50
    spin(lambda: False, timeout=0.3)
    assert len(messages) == 1 and node.accounting.received == 1
    assert node.trigger_deactivate() == SUCCESS and node.trigger_cleanup() == SUCCESS
    assert node.socket is None
    # The port is free again: another socket binds it.
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as other:
        other.bind(('127.0.0.1', port))


def test_a_port_in_use_fails_configure_and_leaves_the_node_unconfigured(rig):
    """Managed: configure refused with the reason, the node alive; it binds once freed."""
    holder = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    holder.bind(('127.0.0.1', 0))
    port = holder.getsockname()[1]
    node, _, messages, spin = rig(Parameter('managed', value=True), port=port)
    assert node.trigger_configure() == FAILURE
    assert node.lifecycle_state() == 'unconfigured'
    assert f'cannot listen on UDP 127.0.0.1:{port}' in str(node.configure_error)
    holder.close()
    assert node.trigger_configure() == SUCCESS and node.trigger_activate() == SUCCESS
    send(port, packet(3, 7))
    assert spin(lambda: len(messages) == 1)


@pytest.mark.parametrize('address', ['localhost', '300.1.1.1', '::1', '', '127.0.0.01'])
def test_an_address_that_is_not_ipv4_stops_the_start_with_the_reason(ros, address):
    """Unmanaged: refused by the parameter's validator, naming it and the value."""
    with pytest.raises((ValueError, ParameterException),
                       match="'telemetry_address' must be an IPv4 address"):
        TelemetryBridge(parameter_overrides=[Parameter('telemetry_address', value=address)])
