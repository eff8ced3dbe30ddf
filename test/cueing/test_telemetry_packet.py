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
The telemetry packet: its layout byte by byte, its decoding, and every datagram it refuses.

The expected bytes are written out by hand from the documented table (offsets, little-endian
types), not with the module's own format string, so a change of the layout fails here.
"""

import math
import struct

from hypothesis import given, strategies as st
from properties import budget
import pytest

from stewart_kinematics.cueing.telemetry_packet import (
    encode,
    MAX_ANGULAR_VELOCITY,
    MAX_SPECIFIC_FORCE,
    PACKET_SIZE,
    TelemetryDecoder,
)
from stewart_kinematics.findings import CODES

pytestmark = pytest.mark.core

FORCE = (1.5, -2.25, 9.80665)
RATE = (0.125, -0.5, 0.75)


def hand_packet(sequence, stamp_ns, force=FORCE, rate=RATE, magic=b'SKTM', version=1, flags=0):
    """Build a packet of the documented layout, each field packed alone at its offset."""
    data = bytearray(68)
    data[0:4] = magic
    data[4:6] = version.to_bytes(2, 'little')
    data[6:8] = flags.to_bytes(2, 'little')
    data[8:12] = sequence.to_bytes(4, 'little')
    data[12:20] = stamp_ns.to_bytes(8, 'little')
    for index, value in enumerate(tuple(force) + tuple(rate)):
        data[20 + 8 * index:28 + 8 * index] = struct.pack('<d', value)
    return bytes(data)


def test_encode_writes_the_documented_layout():
    """68 bytes: magic, version 1, flags 0, sequence, timestamp, 3 + 3 doubles, little-endian."""
    packet = encode(0x01020304, 1_234_567_890_123, FORCE, RATE)
    assert PACKET_SIZE == 68
    assert packet == hand_packet(0x01020304, 1_234_567_890_123)
    assert packet[8:12] == bytes([4, 3, 2, 1])   # little-endian


def test_decode_returns_the_values_of_a_hand_made_packet():
    """The sample carries exactly the numbers written, and no packet missed."""
    result = TelemetryDecoder().decode(hand_packet(41, 5_000_000_000))
    assert result.accepted
    sample = result.sample
    assert (sample.sequence, sample.timestamp_ns, sample.missed) == (41, 5_000_000_000, 0)
    assert sample.specific_force == FORCE and sample.angular_velocity == RATE


@pytest.mark.parametrize('datagram, words', [
    (b'', 'is 68 bytes, got 0'),
    (hand_packet(1, 1)[:67], 'got 67'),
    (hand_packet(1, 1) + b'\0', 'got 69'),
    (bytes(65507), 'got 65,507'),
    (hand_packet(1, 1, magic=b'XPLN'), "starts with b'SKTM'"),
    (hand_packet(1, 1, version=2), 'version 2 is not supported: allowed is 1'),
    (hand_packet(1, 1, flags=1), 'flags must be 0'),
], ids=['empty', 'short', 'long', 'largest_udp', 'magic', 'version', 'flags'])
def test_malformed_datagrams_are_refused_with_the_reason(datagram, words):
    """Wrong size, magic, version or flags: malformed_packet, the value named."""
    decoder = TelemetryDecoder()
    result = decoder.decode(datagram)
    assert not result.accepted and result.sample is None
    assert result.refusal.code == 'malformed_packet'
    assert words in result.reason
    # The stream is untouched: the next good packet is accepted.
    assert decoder.decode(hand_packet(1, 1)).accepted


@pytest.mark.parametrize('force, rate, words', [
    ((math.nan, 0.0, 9.8), RATE, 'specific force [nan'),
    ((0.0, math.inf, 9.8), RATE, 'specific force'),
    ((0.0, 0.0, -1e308), RATE, 'within +-1000 m/s^2'),
    (FORCE, (0.0, 0.0, math.nan), 'angular velocity'),
    (FORCE, (0.0, 100.5, 0.0), 'within +-100 rad/s'),
], ids=['nan', 'inf', 'huge', 'rate_nan', 'rate_absurd'])
def test_non_finite_and_absurd_values_are_refused(force, rate, words):
    """invalid_packet_values, naming the vector; the bounds are the documented ones."""
    result = TelemetryDecoder().decode(hand_packet(3, 10, force, rate))
    assert result.refusal.code == 'invalid_packet_values'
    assert words in result.reason
    assert MAX_SPECIFIC_FORCE == 1000.0 and MAX_ANGULAR_VELOCITY == 100.0


def test_values_at_the_bounds_are_accepted():
    """+-1000 m/s^2 and +-100 rad/s are still a packet."""
    result = TelemetryDecoder().decode(hand_packet(1, 1, (1000.0, -1000.0, 0.0),
                                                   (100.0, -100.0, 0.0)))
    assert result.accepted


def test_a_timestamp_beyond_a_ros_time_is_refused():
    """A ROS time's seconds are an int32: 2**31 s and more cannot be stamped."""
    decoder = TelemetryDecoder()
    assert decoder.decode(hand_packet(1, (2 ** 31 - 1) * 10 ** 9)).accepted
    result = TelemetryDecoder().decode(hand_packet(1, 2 ** 31 * 10 ** 9))
    assert result.refusal.code == 'invalid_packet_values' and 'ROS time' in result.reason


def test_duplicates_late_packets_and_backward_time_are_refused():
    """Sequence or timestamp not after the last accepted: packet_out_of_order; gaps counted."""
    decoder = TelemetryDecoder()
    assert decoder.decode(hand_packet(10, 1000)).accepted
    for sequence, stamp, words in ((10, 2000, 'not after packet 10'),
                                   (9, 2000, 'not after packet 10'),
                                   (11, 1000, 'timestamp 1000 ns is not after')):
        result = decoder.decode(hand_packet(sequence, stamp))
        assert result.refusal.code == 'packet_out_of_order' and words in result.reason
    result = decoder.decode(hand_packet(14, 2000))
    assert result.accepted and result.sample.missed == 3   # 11, 12 and 13 never came


def test_sequence_numbers_wrap_around():
    """2**32 - 1 then 0 is a step forward; 0 then 2**32 - 1 is a step back."""
    decoder = TelemetryDecoder()
    assert decoder.decode(hand_packet(2 ** 32 - 1, 1)).accepted
    assert decoder.decode(hand_packet(0, 2)).sample.missed == 0
    assert decoder.decode(hand_packet(2 ** 32 - 1, 3)).refusal.code == 'packet_out_of_order'


def test_restart_accepts_a_sender_counting_from_zero_again():
    """After restart() (the stream went stale), sequence 0 and an earlier time are accepted."""
    decoder = TelemetryDecoder()
    assert decoder.decode(hand_packet(500, 10 ** 9)).accepted
    assert not decoder.decode(hand_packet(0, 10)).accepted
    decoder.restart()
    assert decoder.decode(hand_packet(0, 10)).accepted


def test_the_codes_are_registered():
    """Every refusal the decoder gives is in the registry, as a refusal."""
    for code in ('malformed_packet', 'invalid_packet_values', 'packet_out_of_order'):
        assert CODES[code].kind == 'refusal'


@budget(200)
@given(st.binary(max_size=200))
def test_any_bytes_are_decoded_or_refused_never_raised(datagram):
    """An adversary's datagram: an answer, never an exception; an accepted one is finite."""
    result = TelemetryDecoder().decode(datagram)
    if result.accepted:
        assert len(datagram) == PACKET_SIZE
        values = result.sample.specific_force + result.sample.angular_velocity
        assert all(math.isfinite(value) for value in values)
    else:
        assert result.refusal.code in CODES and len(result.reason) < 300


@budget(100)
@given(st.lists(st.tuples(st.integers(0, 2 ** 32 - 1), st.integers(0, 2 ** 40)), max_size=30))
def test_accepted_packets_move_forward(packets):
    """Whatever order packets come in, the accepted ones have increasing timestamps."""
    decoder = TelemetryDecoder()
    stamps = [decoder.decode(hand_packet(sequence, stamp)) for sequence, stamp in packets]
    accepted = [result.sample.timestamp_ns for result in stamps if result.accepted]
    assert accepted == sorted(set(accepted))
