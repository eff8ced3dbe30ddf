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
``telemetry_sender``: play a built-in drive as telemetry packets over UDP, as a simulator would.

Sends one packet (:mod:`stewart_kinematics.cueing.telemetry_packet`) per sample of a scenario
of :mod:`stewart_kinematics.cueing.scenarios`, at the scenario's rate, in real time (or
``--speed`` times faster), to ``telemetry_bridge``; the timestamps are this machine's monotonic
clock at the start plus the scenario's time, the sequence numbers count from
``--first-sequence``. For trying the bridge and the cueing without a simulator, and for tests::

    telemetry_sender --scenario slalom --rate 100 --port 47800
    telemetry_sender --scenario lap --duration 10 --loops 0    # the first 10 s, forever

Exits 0 when every packet was sent, 2 for a bad option, 1 when the socket fails.
"""

import argparse
import socket
import sys
import time

from stewart_kinematics.cueing.scenarios import DEFAULT_RATE, scenario, SCENARIO_NAMES
from stewart_kinematics.cueing.telemetry_packet import encode, SEQUENCE_MODULUS
from stewart_kinematics.tools.cli_arguments import (
    integer_at_least,
    number_in,
    positive_number,
)

#: Longest scenario sample rate, hertz (the bridge is measured loss-free at 1 kHz).
MAX_RATE = 10000.0


def build_parser() -> argparse.ArgumentParser:
    """Return the command line's parser."""
    parser = argparse.ArgumentParser(
        prog='telemetry_sender', description=__doc__.split('\n\n')[1].replace('\n', ' '),
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument('--scenario', choices=SCENARIO_NAMES, default='slalom',
                        help='the built-in drive to play (see stewart_cueing)')
    parser.add_argument('--rate', type=number_in(1.0, MAX_RATE), default=DEFAULT_RATE,
                        help='samples (packets) a second, hertz')
    parser.add_argument('--address', default='127.0.0.1',
                        help="telemetry_bridge's address (its telemetry_address)")
    parser.add_argument('--port', type=integer_at_least(1), default=47800,
                        help="telemetry_bridge's UDP port (its telemetry_port)")
    parser.add_argument('--duration', type=positive_number, default=None,
                        help='play only the first seconds of the scenario')
    parser.add_argument('--loops', type=integer_at_least(0), default=1,
                        help='how many times to play it; 0 forever (Ctrl-C stops)')
    parser.add_argument('--speed', type=number_in(0.01, 1000.0), default=1.0,
                        help='play this many times faster than real time')
    parser.add_argument('--first-sequence', type=integer_at_least(0), default=0,
                        help="the first packet's sequence number (wraps at 2**32)")
    return parser


def main(argv=None) -> int:
    """Send the packets; return the exit code."""
    parser = build_parser()
    arguments = parser.parse_args(argv)
    if arguments.port > 65535:
        parser.error(f'argument --port: must be at most 65535, got {arguments.port}')
    drive = scenario(arguments.scenario, arguments.rate)
    count = len(drive.times)
    if arguments.duration is not None:
        count = min(count, int(arguments.duration * arguments.rate) + 1)
    period = 1.0 / arguments.rate
    try:
        udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        udp.connect((arguments.address, arguments.port))
    except (OSError, UnicodeError) as error:
        print(f'telemetry_sender: cannot send to {arguments.address}:{arguments.port}: '
              f'{error}', file=sys.stderr)
        return 1
    sequence = arguments.first_sequence % SEQUENCE_MODULUS
    sent = 0
    start = time.monotonic()
    origin_ns = time.monotonic_ns()
    loop = 0
    try:
        while arguments.loops == 0 or loop < arguments.loops:
            for k in range(count):
                index = loop * count + k
                due = start + index * period / arguments.speed
                delay = due - time.monotonic()
                if delay > 0:
                    time.sleep(delay)
                packet = encode(sequence, origin_ns + round(index * period * 1e9),
                                drive.specific_force[k], drive.angular_velocity[k])
                try:
                    udp.send(packet)
                except ConnectionRefusedError:
                    pass   # nobody listens yet (an ICMP answer to an earlier packet)
                sequence = (sequence + 1) % SEQUENCE_MODULUS
                sent += 1
            loop += 1
    except KeyboardInterrupt:
        pass
    except OSError as error:
        print(f'telemetry_sender: sending failed after {sent} packets: {error}',
              file=sys.stderr)
        return 1
    finally:
        udp.close()
    elapsed = time.monotonic() - start
    print(f'sent {sent} packets of {arguments.scenario} to {arguments.address}:'
          f'{arguments.port} in {elapsed:.2f} s ({sent / max(elapsed, 1e-9):.0f} per second)')
    return 0


if __name__ == '__main__':
    sys.exit(main())
