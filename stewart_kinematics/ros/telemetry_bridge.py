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
Telemetry bridge: a simulator's UDP telemetry in, ``vehicle_imu`` for motion_cueing_node out.

Receives one telemetry packet per vehicle sample on a UDP socket (``telemetry_address``,
``telemetry_port``; the layout: :mod:`stewart_kinematics.cueing.telemetry_packet`) and
publishes each accepted one as ``vehicle_imu`` (sensor_msgs/msg/Imu): the specific force in
``linear_acceleration`` and the angular velocity in ``angular_velocity`` (vehicle frame, x
forward, y left, z up), ``header.stamp`` the packet's timestamp (the sender's clock: the
washout's time step is the simulator's), ``header.frame_id`` ``telemetry_frame_id``, no
orientation (``orientation_covariance[0] = -1``, as REP 145 says). Declared in
:data:`stewart_kinematics.ros.interfaces.TELEMETRY_BRIDGE`.

The socket is non-blocking and emptied by a timer (``telemetry_poll_rate``, at most
:data:`MAX_PACKETS_PER_POLL` datagrams a tick, so that a flood cannot hold the executor): the
executor never waits on it. Every datagram is counted on ``/diagnostics`` (status
``telemetry_bridge: udp <address>:<port>``), a refused one by its code (``malformed_packet``,
``invalid_packet_values``, ``packet_out_of_order``) with one throttled log line; the status
``telemetry_bridge: stream`` says whether packets come (OK), or none came for
``telemetry_timeout`` (STALE: nothing is published, the next packet starts a new stream), and
how many the sequence numbers say were lost.

Managed (``managed: true``) as every node: the socket is bound by configure and closed by
cleanup; while inactive, nothing is published, and activate throws away what arrived meanwhile.
"""

import socket
import time

from diagnostic_msgs.msg import DiagnosticStatus, KeyValue
from sensor_msgs.msg import Imu

from stewart_kinematics.cueing.telemetry_packet import TelemetryDecoder
from stewart_kinematics.parameters import TelemetryBridgeNodeSettings
from stewart_kinematics.ros.interfaces import TELEMETRY_BRIDGE
from stewart_kinematics.ros.managed import ManagedNode
from stewart_kinematics.ros.message_accounting import NodeDiagnostics
from stewart_kinematics.ros.node_main import create_output_publisher, run_node

#: Most datagrams read in one timer tick: a flood waits in the socket's buffer (and beyond it
#: is dropped by the kernel, seen as sequence gaps), never holding the executor longer.
MAX_PACKETS_PER_POLL = 1000
#: Bytes read per datagram: the largest UDP payload fits, so a wrong size is reported as it is.
RECEIVE_BUFFER = 65536
#: The socket's receive buffer asked of the kernel, bytes. The kernel doubles it, caps it at
#: net.core.rmem_max (twice) and charges each datagram its whole buffer (about 830 bytes for a
#: packet on loopback): measured, about 2,500 packets (0.25 s at 10 kHz) with rmem_max 4 MB,
#: about 500 with Linux's default 208 kB; a stall longer than that shows as sequence gaps.
SOCKET_BUFFER = 1 << 20


class TelemetryBridge(ManagedNode):
    """Publish every accepted telemetry packet of a UDP stream as ``vehicle_imu``."""

    SETTINGS = TelemetryBridgeNodeSettings

    def __init__(self, **kwargs):
        self.socket = None
        super().__init__('telemetry_bridge', **kwargs)

    def configure(self):
        """Bind the socket; build the publisher, the accounting and the poll timer."""
        telemetry = self.settings.telemetry
        address, port = telemetry.telemetry_address, telemetry.telemetry_port
        self.decoder = TelemetryDecoder()
        self.publisher = create_output_publisher(
            self, TELEMETRY_BRIDGE['vehicle_imu'], self.settings.queue.queue_depth)
        diagnostics = NodeDiagnostics(self)
        self.accounting = diagnostics.accounting(f'udp {address}:{port}')
        diagnostics.reporters.append(self)
        self.timeout = telemetry.telemetry_timeout
        self.last_packet = None     # monotonic time of the last accepted packet
        self.stale = True
        self.missed = 0
        self.streams = 0
        self.buffer = bytearray(RECEIVE_BUFFER)
        self.view = memoryview(self.buffer)
        udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            udp.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, SOCKET_BUFFER)
            udp.bind((address, port))
        except OSError as error:
            udp.close()
            raise ValueError(f'telemetry_bridge cannot listen on UDP {address}:{port}: '
                             f'{error.strerror or error}') from None
        udp.setblocking(False)
        self.socket = udp
        self.create_timer(1.0 / telemetry.telemetry_poll_rate, self.on_poll)
        self.get_logger().info(
            f'ready: telemetry packets on UDP {address}:{port} to vehicle_imu '
            f'(frame {telemetry.telemetry_frame_id!r})')

    def activate(self):
        """Throw away what arrived while inactive; the next packet starts a new stream."""
        self.drain()
        self.decoder.restart()
        self.last_packet, self.stale = None, True

    def cleanup(self):
        """Close the socket (the entities go with the mechanism)."""
        if self.socket is not None:
            self.socket.close()
            self.socket = None

    def drain(self) -> int:
        """Read and drop every datagram waiting in the socket; return how many."""
        dropped = 0
        while self.socket is not None:
            try:
                self.socket.recv_into(self.buffer)
            except OSError:   # BlockingIOError: empty; any other error ends the drain too
                return dropped
            dropped += 1
        return dropped

    def on_poll(self):
        """Read what the socket holds (at most MAX_PACKETS_PER_POLL), publish each packet."""
        for _ in range(MAX_PACKETS_PER_POLL):
            try:
                size = self.socket.recv_into(self.buffer)
            except BlockingIOError:
                break
            except OSError as error:   # never out of the executor: the next tick tries again
                self.get_logger().error(f'UDP receive failed: {error}', throttle_duration_sec=1.0)
                break
            self.accounting.receive()
            result = self.decoder.decode(self.view[:size])
            if result.refusal is not None:
                self.accounting.reject(result.refusal)
                continue
            self.publish_sample(result.sample)
        self.watch(time.monotonic())

    def publish_sample(self, sample):
        """Publish one accepted sample as vehicle_imu; note when the stream (re)started."""
        message = Imu()
        message.header.stamp.sec, message.header.stamp.nanosec = divmod(
            sample.timestamp_ns, 1_000_000_000)
        message.header.frame_id = self.settings.telemetry.telemetry_frame_id
        force, rate = message.linear_acceleration, message.angular_velocity
        force.x, force.y, force.z = sample.specific_force
        rate.x, rate.y, rate.z = sample.angular_velocity
        message.orientation_covariance[0] = -1.0   # no orientation (REP 145)
        self.accounting.publish(self.publisher, message)
        self.missed += sample.missed
        self.last_packet = time.monotonic()
        if self.stale:
            self.stale = False
            self.streams += 1
            self.get_logger().info(f'telemetry stream started (packet {sample.sequence})')

    def watch(self, now: float):
        """Without a valid packet for telemetry_timeout: stale, and the next one starts anew."""
        if not self.stale and now - self.last_packet > self.timeout:
            self.stale = True
            self.decoder.restart()
            self.get_logger().warning(
                f'telemetry stream stale: no valid packet for {self.timeout:g} s; publishing '
                'nothing until packets come again')

    def report(self) -> DiagnosticStatus:
        """Return the stream's status for /diagnostics: OK while packets come, else STALE."""
        since = ('never' if self.last_packet is None
                 else f'{time.monotonic() - self.last_packet:.3f}')
        if self.stale:
            level = DiagnosticStatus.STALE
            message = (f'no valid telemetry packet for {self.timeout:g} s: publishing nothing'
                       if self.last_packet is not None else 'no valid telemetry packet yet')
        else:
            level, message = DiagnosticStatus.OK, 'receiving'
        values = (('seconds since the last packet', since),
                  ('packets missed (sequence gaps)', self.missed),
                  ('streams started', self.streams),
                  ('last sequence', self.decoder.last_sequence))
        return DiagnosticStatus(
            level=level, name=f'{self.get_fully_qualified_name()}: stream', message=message,
            hardware_id=self.accounting.diagnostics.hardware_id,
            values=[KeyValue(key=key, value=str(value)) for key, value in values])


def main(args=None) -> int:
    """Run the telemetry bridge until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(TelemetryBridge, 'telemetry_bridge', args)


if __name__ == '__main__':
    raise SystemExit(main())
