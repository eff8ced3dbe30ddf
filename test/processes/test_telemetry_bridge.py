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
telemetry_bridge as a process, over real UDP on loopback: packets in, vehicle_imu out.

Packets built by hand (the documented layout) come out on ``vehicle_imu`` with their very
numbers; ``telemetry_sender`` plays a built-in drive at 1 kHz and every packet comes out, in
order, with the scenario's values; when the stream stops the bridge says STALE and publishes
nothing, and a restarted sender counting from 0 is taken. The adversary: an empty datagram, a
64 kB one, another protocol's data on the port, NaN, duplicates and late packets, a flood of
junk: each refused and counted by code on /diagnostics, the node running and still bridging.
About 15 s in all (the 1 kHz drive is 3 s).
"""

import math
import socket
import struct
import time

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from helpers import fail_with_output, SpinningClient, stop_cleanly
import numpy as np
from numpy.testing import assert_array_equal
import pytest
from sensor_msgs.msg import Imu

from stewart_kinematics.cueing.scenarios import scenario
from stewart_kinematics.ros.node_main import create_executor

pytestmark = pytest.mark.process

#: Depth of the client's subscription: a whole 1 kHz second.
DEPTH = 1000
FORCE = (1.5, -2.25, 9.80665)
RATE = (0.125, -0.5, 0.75)


def packet(sequence, stamp_ns, force=FORCE, rate=RATE, magic=b'SKTM'):
    """Build a packet: magic, version 1, flags 0, sequence, timestamp, 6 doubles."""
    return (magic + struct.pack('<HHIQ', 1, 0, sequence, stamp_ns)
            + struct.pack('<6d', *force, *rate))


def free_port():
    """Return a UDP port of loopback that nobody uses now."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


@pytest.fixture
def client(ros):
    """Create a client node spun by a thread of its own: the test sends UDP meanwhile."""
    client = SpinningClient(ros.create_node('stewart_telemetry_client'), create_executor(),
                            DEPTH)
    yield client
    client.close()


@pytest.fixture
def bridge(client, start_node):
    """Start telemetry_bridge on a free port; return (process, port, messages, statuses)."""
    port = free_port()
    process = start_node('telemetry_bridge', [
        '--ros-args', '-p', f'telemetry_port:={port}', '-p', 'queue_depth:=1000',
        '-p', 'telemetry_frame_id:=vehicle', '-p', 'telemetry_timeout:=0.3'])
    messages, statuses = [], []
    client.subscribe(Imu, 'vehicle_imu', messages.append)
    client.subscribe(DiagnosticArray, '/diagnostics',
                     lambda array: statuses.extend(array.status))
    client.wait(lambda: client.node.count_publishers('vehicle_imu') >= 1,
                'telemetry_bridge publishing vehicle_imu', [process])
    client.wait(lambda: any(status.name.startswith('/telemetry_bridge') for status in statuses),
                'a /diagnostics report of telemetry_bridge', [process])
    client.settle()
    return process, port, messages, statuses


def sender_socket(port):
    """Return a UDP socket connected to the bridge."""
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    udp.connect(('127.0.0.1', port))
    return udp


def latest(statuses, name):
    """Return the values of the latest status called ``name``, as a dict (or None)."""
    found = [status for status in statuses if status.name == name]
    return None if not found else (found[-1], {v.key: v.value for v in found[-1].values})


def flood_read(statuses, name):
    """Whether the last two statuses ``name`` count the same datagrams received, over 1000."""
    counts = [int({v.key: v.value for v in status.values}['received'])
              for status in statuses if status.name == name][-2:]
    return len(counts) == 2 and counts[0] == counts[1] > 1000


def test_packets_come_out_on_vehicle_imu_with_their_values(client, bridge):
    """50 packets: 50 messages, each with the packet's numbers, stamp and the frame id."""
    process, port, messages, _ = bridge
    with sender_socket(port) as udp:
        for k in range(50):
            udp.send(packet(k, 7 * 10 ** 9 + k * 10 ** 7,
                            (FORCE[0] + k, FORCE[1], FORCE[2]), RATE))
            time.sleep(0.001)
    client.wait(lambda: len(messages) >= 50, '50 vehicle_imu messages', [process])
    time.sleep(0.2)
    assert len(messages) == 50
    for k, message in enumerate(messages):
        force, rate = message.linear_acceleration, message.angular_velocity
        assert (force.x, force.y, force.z) == (FORCE[0] + k, FORCE[1], FORCE[2])
        assert (rate.x, rate.y, rate.z) == RATE
        assert (message.header.stamp.sec, message.header.stamp.nanosec) == (7, k * 10 ** 7)
        assert message.header.frame_id == 'vehicle'
        assert message.orientation_covariance[0] == -1.0
    stop_cleanly(process)


def test_bad_packets_are_refused_counted_and_the_bridge_keeps_bridging(client, bridge):
    """Each kind of bad datagram counted by its code; a flood of junk; good ones still pass."""
    process, port, messages, statuses = bridge
    name = f'/telemetry_bridge: udp 127.0.0.1:{port}'
    bad = [b'',                                        # empty
           bytes(65000),                               # 64 kB
           b'GET / HTTP/1.1\r\nHost: x\r\n\r\n',       # another protocol on the port
           packet(1, 10, magic=b'XPLN'),               # another simulator's packet
           packet(1, 10, force=(math.nan, 0.0, 9.8)),  # NaN
           packet(1, 10, rate=(0.0, 0.0, 1e308)),      # absurd
           ]
    with sender_socket(port) as udp:
        for datagram in bad:
            udp.send(datagram)
        udp.send(packet(5, 100))       # accepted
        udp.send(packet(5, 200))       # duplicate
        udp.send(packet(4, 300))       # late
        udp.send(packet(6, 100))       # time not forward
        udp.send(packet(7, 400))       # accepted
        client.wait(lambda: len(messages) >= 2, 'the two good packets', [process])

        def counted():
            report = latest(statuses, name)
            return report is not None and report[1].get('received') == '11'
        client.wait(counted, 'the 11 datagrams counted on /diagnostics', [process])
        status, values = latest(statuses, name)
        assert values['rejected malformed_packet'] == '4'
        assert values['rejected invalid_packet_values'] == '2'
        assert values['rejected packet_out_of_order'] == '3'
        assert values['published'] == '2'
        # A flood: 20,000 junk datagrams as fast as the socket takes them.
        junk = np.random.default_rng(5).integers(0, 256, (20000, 68), dtype=np.uint8)
        for row in junk:
            udp.send(row.tobytes())
        # What overflowed the socket's buffer the kernel dropped; once it is read, good
        # packets pass again.
        # Read to its end: two reports (a second apart) with the same count past 1000. A fixed
        # 0.5 s could end with the buffer still full on a loaded machine, the packet dropped.
        client.wait(lambda: flood_read(statuses, name), 'the flood read', [process])
        udp.send(packet(8, 500))
        client.wait(lambda: len(messages) >= 3, 'a good packet after the flood', [process])
    assert [m.header.stamp.nanosec for m in messages] == [100, 400, 500]
    client.wait(lambda: latest(statuses, name)[1]['published'] == '3', 'the last one counted',
                [process])
    values = latest(statuses, name)[1]
    # Every datagram read is one output or one refusal; the junk all malformed.
    assert int(values['received']) == 3 + int(values['rejected'])
    assert int(values['rejected']) == int(values['rejected malformed_packet']) + 5
    assert process.running()
    output = stop_cleanly(process)
    assert output.count('rejected') < 40   # throttled: a line per kind a second


def test_a_1_khz_drive_is_carried_loss_free_then_stale_then_restarted(
        client, bridge, start_node):
    """telemetry_sender at 1 kHz for 3 s: every packet, in order, with the scenario's values."""
    process, port, messages, statuses = bridge
    sender = start_node('telemetry_sender', ['--scenario', 'multi_sine', '--rate', '1000',
                                             '--duration', '3', '--port', str(port)])
    drive = scenario('multi_sine', 1000.0)
    count = 3001
    client.wait(lambda: not sender.running(), 'the sender done', [process], timeout=30.0)
    assert sender.stop() == 0, sender.output()
    assert f'sent {count} packets' in sender.output()
    if not client.wait(lambda: len(messages) >= count, f'{count} messages', [process],
                       fail=False):
        fail_with_output(f'{len(messages)} of {count} packets came out', [process])
    time.sleep(0.2)
    assert len(messages) == count
    forces = np.array([[m.linear_acceleration.x, m.linear_acceleration.y,
                        m.linear_acceleration.z] for m in messages])
    assert_array_equal(forces, drive.specific_force[:count])
    stamps = np.array([m.header.stamp.sec * 10 ** 9 + m.header.stamp.nanosec
                       for m in messages])
    assert_array_equal(np.diff(stamps), np.full(count - 1, 10 ** 6))
    stream = '/telemetry_bridge: stream'

    def stale():
        report = latest(statuses, stream)
        return report is not None and report[0].level == DiagnosticStatus.STALE and (
            report[1]['seconds since the last packet'] != 'never')
    client.wait(stale, 'the stream reported stale', [process])
    assert latest(statuses, stream)[1]['packets missed (sequence gaps)'] == '0'
    # A restarted sender counts from 0 again, with an earlier clock: a new stream.
    with sender_socket(port) as udp:
        udp.send(packet(0, 10))
    client.wait(lambda: len(messages) == count + 1, 'the new stream bridged', [process])
    stop_cleanly(process)


def test_a_port_in_use_stops_the_start_with_the_reason(start_node):
    """Another socket holds the port: exit 1, one line naming the address and port."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as holder:
        holder.bind(('127.0.0.1', 0))
        port = holder.getsockname()[1]
        process = start_node('telemetry_bridge', ['--ros-args', '-p',
                                                  f'telemetry_port:={port}'])
        deadline = time.monotonic() + 20.0
        while process.running() and time.monotonic() < deadline:
            time.sleep(0.05)
        code = process.stop()
    output = process.output()
    assert code == 1, output
    assert f'cannot listen on UDP 127.0.0.1:{port}' in output and 'Traceback' not in output
