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
The telemetry packet: one vehicle sample in a UDP datagram, and its checks.

A simulator sends one datagram per sample to ``telemetry_bridge``, which publishes it as
``vehicle_imu`` (sensor_msgs/msg/Imu) for motion_cueing_node. The layout, little-endian, 68
bytes, no padding (``struct`` format :data:`PACKET_FORMAT`, ``'<4sHHIQ6d'``):

====== ===== ========= ==================================================================
Offset Bytes Type      Field
====== ===== ========= ==================================================================
0      4     char[4]   magic, the ASCII bytes ``SKTM``
4      2     uint16    version, 1
6      2     uint16    flags, 0 (reserved)
8      4     uint32    sequence number: +1 per packet (wraps from 2**32 - 1 to 0)
12     8     uint64    timestamp, nanoseconds of the sender's clock (any origin, increasing)
20     24    float64   specific force x, y, z, m/s^2 (an accelerometer's reading: 9.81 on z
                       at rest), vehicle frame at the driver's head: x forward, y left, z up
44     24    float64   angular velocity x, y, z (roll, pitch, yaw rates), rad/s, same frame
====== ===== ========= ==================================================================

A datagram is refused (:class:`TelemetryDecoder`, never an exception) when it is not 68
bytes, its magic or version differs or its flags are set (``malformed_packet``); when a value
is not finite, or beyond :data:`MAX_SPECIFIC_FORCE` or :data:`MAX_ANGULAR_VELOCITY`, or the
timestamp is beyond :data:`MAX_TIMESTAMP_NS` (``invalid_packet_values``); when its sequence
number or timestamp does not move forward from the last accepted packet's: a duplicate, a
packet overtaken by a later one (``packet_out_of_order``). After a silence of the stream's
timeout the decoder starts afresh (:meth:`TelemetryDecoder.restart`): a restarted sender may
count from 0 again.

>>> packet = encode(7, 1_000_000_000, (0.5, 0.0, 9.81), (0.0, 0.0, 0.1))
>>> len(packet)
68
>>> decoder = TelemetryDecoder()
>>> decoder.decode(packet).sample.specific_force
(0.5, 0.0, 9.81)
>>> decoder.decode(packet).refusal.code
'packet_out_of_order'
"""

from dataclasses import dataclass
import math
import struct
from typing import Optional, Sequence, Tuple

from stewart_kinematics.findings import (
    Decision,
    Finding,
    INVALID_PACKET_VALUES,
    MALFORMED_PACKET,
    PACKET_OUT_OF_ORDER,
)

#: The packet's layout for ``struct``: magic, version, flags, sequence, timestamp, 6 doubles.
PACKET_FORMAT = '<4sHHIQ6d'
PACKET_SIZE = struct.calcsize(PACKET_FORMAT)
MAGIC = b'SKTM'
VERSION = 1
#: Largest specific force a packet may carry per axis, m/s^2 (about 100 g): beyond it the
#: value is garbage, not a vehicle (motion_cueing_node's own ``max_specific_force`` is tighter).
MAX_SPECIFIC_FORCE = 1000.0
#: Largest angular velocity per axis, rad/s (about 16 turns a second).
MAX_ANGULAR_VELOCITY = 100.0
#: Largest timestamp, nanoseconds: a ROS time's seconds are an int32.
MAX_TIMESTAMP_NS = (2 ** 31 - 1) * 1_000_000_000
#: Sequence numbers are uint32: a step forward is within half their range (wrap-around).
SEQUENCE_MODULUS = 2 ** 32
_STRUCT = struct.Struct(PACKET_FORMAT)


@dataclass(frozen=True)
class TelemetrySample:
    """
    One accepted packet's sample.

    :param sequence: the sequence number.
    :param timestamp_ns: the sender's time, nanoseconds.
    :param specific_force: x, y, z, m/s^2, vehicle frame (x forward, y left, z up).
    :param angular_velocity: x, y, z, rad/s, vehicle frame.
    :param missed: packets skipped by the sequence number since the last accepted one (lost
        on the way, or dropped by a full socket buffer).
    """

    sequence: int
    timestamp_ns: int
    specific_force: Tuple[float, float, float]
    angular_velocity: Tuple[float, float, float]
    missed: int = 0


@dataclass(frozen=True)
class PacketResult(Decision):
    """A datagram's outcome: its sample, or the refusal (``Decision``'s ``.accepted``)."""

    sample: Optional[TelemetrySample]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()


def encode(sequence: int, timestamp_ns: int, specific_force: Sequence[float],
           angular_velocity: Sequence[float], *, version: int = VERSION,
           magic: bytes = MAGIC, flags: int = 0) -> bytes:
    """
    Build one packet (for senders and tests; a bad value is packed as given, to be refused).

    :param sequence: 0 to 2**32 - 1.
    :param timestamp_ns: the sender's time, nanoseconds, 0 to 2**64 - 1.
    :param specific_force: x, y, z, m/s^2, vehicle frame (x forward, y left, z up).
    :param angular_velocity: x, y, z, rad/s, vehicle frame.
    :raises struct.error: for a field that does not fit its type.
    """
    return _STRUCT.pack(magic, version, flags, sequence, timestamp_ns,
                        *(float(value) for value in specific_force),
                        *(float(value) for value in angular_velocity))


def _malformed(message: str) -> PacketResult:
    return PacketResult(None, Finding(MALFORMED_PACKET, message))


class TelemetryDecoder:
    """
    Decode datagrams one by one into samples, refusing what is not a packet or is out of order.

    Keeps the last accepted sequence number and timestamp; never raises for a datagram.
    """

    def __init__(self):
        self.restart()

    def restart(self):
        """Forget the stream: the next valid packet is accepted whatever its sequence number."""
        self.last_sequence = None
        self.last_timestamp_ns = None

    def decode(self, datagram: bytes) -> PacketResult:
        """
        Return the sample of one datagram, or why it is refused.

        :param datagram: the bytes received, any length.
        """
        size = len(datagram)
        if size != PACKET_SIZE:
            return _malformed(f'a telemetry packet is {PACKET_SIZE} bytes, got {size:,}')
        magic, version, flags, sequence, stamp, *values = _STRUCT.unpack(datagram)
        if magic != MAGIC:
            return _malformed(f'a telemetry packet starts with {MAGIC!r}, got {magic!r}')
        if version != VERSION:
            return _malformed(f'telemetry packet version {version} is not supported: '
                              f'allowed is {VERSION}')
        if flags != 0:
            return _malformed(f'telemetry packet flags must be 0 (reserved), got {flags}')
        force, rate = tuple(values[:3]), tuple(values[3:])
        for name, vector, bound, unit in (
                ('specific force', force, MAX_SPECIFIC_FORCE, 'm/s^2'),
                ('angular velocity', rate, MAX_ANGULAR_VELOCITY, 'rad/s')):
            if not all(math.isfinite(value) and abs(value) <= bound for value in vector):
                return PacketResult(None, Finding(
                    INVALID_PACKET_VALUES,
                    f'telemetry packet {sequence}: {name} {list(vector)} {unit} is not three '
                    f'finite numbers within +-{bound:g} {unit}'))
        if stamp > MAX_TIMESTAMP_NS:
            return PacketResult(None, Finding(
                INVALID_PACKET_VALUES, f'telemetry packet {sequence}: timestamp {stamp} ns is '
                f'beyond {MAX_TIMESTAMP_NS} ns (a ROS time)'))
        missed = 0
        if self.last_sequence is not None:
            step = (sequence - self.last_sequence) % SEQUENCE_MODULUS
            if step == 0 or step >= SEQUENCE_MODULUS // 2:
                return PacketResult(None, Finding(
                    PACKET_OUT_OF_ORDER, f'telemetry packet {sequence} is not after packet '
                    f'{self.last_sequence}: a duplicate or a late one'))
            if stamp <= self.last_timestamp_ns:
                return PacketResult(None, Finding(
                    PACKET_OUT_OF_ORDER, f'telemetry packet {sequence}: timestamp {stamp} ns is '
                    f"not after the previous packet's, {self.last_timestamp_ns} ns"))
            missed = step - 1
        self.last_sequence, self.last_timestamp_ns = sequence, stamp
        return PacketResult(TelemetrySample(sequence, stamp, force, rate, missed))
