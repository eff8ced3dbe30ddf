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
The ``ramp_demo`` console script, run as a user runs it.

It starts ik_node, fk_node and trajectory_node as processes of their own, plays the paper's
Table 3 through them and prints three tables (the paper's Figures 5, 7 and 9). These tests
read that printout: every table has the 11 rows, the poses are the table's, the round trip is
within 1e-9, and a broken parameter file ends the demo with the node's own error message. The
run's rosbag2 recording (MCAP, written with rosbags) is read back with another library, mcap
with mcap-ros2-support (its own CDR decoder, from the schemas stored in the file), and must
hold the leg lengths the demo printed.
"""

import re
import shutil
import subprocess

from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from numpy.testing import assert_allclose
import pytest
from stewart_kinematics.tools.node_processes import NodeProcess
import yaml

pytestmark = pytest.mark.process

#: Seconds the demo may take; it waits at most --timeout for the nodes and the ramp.
DEMO_DEADLINE = 60.0
#: The demo's own deadline for the nodes and the ramp, seconds.
DEMO_TIMEOUT = '30'
#: Titles of the three tables the demo prints.
INPUT_TITLE = 'Input pose received on target_pose'
LENGTHS_TITLE = 'Leg lengths from ik_node on leg_lengths'
ESTIMATE_TITLE = 'Pose from fk_node on estimated_pose'
#: A paper_platform.yaml with one base joint coordinate missing.
BROKEN_PLATFORM = """\
/**:
  ros__parameters:
    base_joints: [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4,
                  1.5, 1.6]
    home_position: [0.0, 0.0, 0.4325]
"""
#: The tables print 4 decimals (mm, deg): a printed value is within 5e-5 of the true one.
PRINT_TOLERANCE = 1e-4


def table3_row_mm_deg(index):
    """Row ``index`` of the paper's Table 3: X, Y, Z in mm, alpha, beta, gamma in degrees."""
    return [10.0 * index, 15.0 * index, 432.5 + 10.0 * index,
            1.5 * index, -1.5 * index, 2.0 * index]


def run_ramp_demo(arguments):
    """
    Run the ramp_demo console script to its end.

    :returns: ``(exit code, everything it printed)``; the exit code is None if it did not
        finish within :data:`DEMO_DEADLINE` (it is then stopped with SIGINT, which also stops
        its nodes).
    """
    with NodeProcess('ramp_demo', arguments) as demo:
        try:
            code = demo.process.wait(DEMO_DEADLINE)
        except subprocess.TimeoutExpired:
            code = None
        return code, demo.output()


def printed_table(output, title):
    """
    Parse the table printed under ``title``.

    :returns: a list of ``(row number, [values])``, in printed order.
    """
    lines = output.splitlines()
    starts = [number for number, line in enumerate(lines) if line.startswith(title)]
    assert len(starts) == 1, f'table {title!r} printed {len(starts)} times:\n{output}'
    assert lines[starts[0] + 1].split()[0] == 'row', output
    rows = []
    for line in lines[starts[0] + 2:]:
        if not line.strip():
            break
        number, *values = line.split()
        rows.append((int(number), [float(value) for value in values]))
    return rows


@pytest.fixture(scope='module')
def figure_directory(tmp_path_factory):
    """Return the folder the demo writes its figures to."""
    return tmp_path_factory.mktemp('figures')


@pytest.fixture(scope='module')
def bag_directory(figure_directory):
    """Return the rosbag2 folder the demo records to."""
    return figure_directory / 'recording'


@pytest.fixture(scope='module')
def demo_run(figure_directory, bag_directory):
    """Exit code and printout of one ramp_demo run with the shipped configuration."""
    return run_ramp_demo(['--row-period', '0.05', '--timeout', DEMO_TIMEOUT,
                          '--figures', str(figure_directory), '--bag', str(bag_directory)])


def recorded_messages(bag_directory, topic):
    """Decode every message of ``topic`` in the bag's MCAP file with mcap-ros2-support."""
    metadata = yaml.safe_load((bag_directory / 'metadata.yaml').read_text())
    files = metadata['rosbag2_bagfile_information']['relative_file_paths']
    assert len(files) == 1, files
    with open(bag_directory / files[0], 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        return [(schema.name, decoded)
                for schema, _, _, decoded in reader.iter_decoded_messages(topics=[topic])]


def test_ramp_demo_records_a_rosbag2_mcap_folder(demo_run, bag_directory):
    """metadata.yaml names the MCAP storage and counts 11 messages on each data topic."""
    code, output = demo_run
    assert code == 0, output
    assert f'recorded (rosbag2, MCAP): {bag_directory}' in output, output
    information = yaml.safe_load(
        (bag_directory / 'metadata.yaml').read_text())['rosbag2_bagfile_information']
    assert information['storage_identifier'] == 'mcap'
    counts = {entry['topic_metadata']['name']: (entry['topic_metadata']['type'],
                                                entry['message_count'])
              for entry in information['topics_with_message_count']}
    assert counts['/target_pose'] == ('geometry_msgs/msg/Pose', 11), counts
    assert counts['/leg_lengths'] == ('std_msgs/msg/Float64MultiArray', 11), counts
    assert counts['/estimated_pose'] == ('geometry_msgs/msg/Pose', 11), counts
    assert counts['/diagnostics'][0] == 'diagnostic_msgs/msg/DiagnosticArray', counts
    # fk_node's estimates on /tf too (tf2_msgs is built into the test venv); fk_node builds
    # /tf only for a matched listener, and its side may match the recorder after row 0.
    assert counts['/tf'][0] == 'tf2_msgs/msg/TFMessage', counts
    assert counts['/tf'][1] in (10, 11), counts


def test_recorded_leg_lengths_are_the_printed_table(demo_run, bag_directory):
    """An independent reader finds, in order, the 11 leg length rows the demo printed."""
    _, output = demo_run
    printed = [values for _, values in printed_table(output, LENGTHS_TITLE)]
    recorded = recorded_messages(bag_directory, '/leg_lengths')
    assert [name for name, _ in recorded] == ['std_msgs/msg/Float64MultiArray'] * 11
    recorded_mm = [[length * 1e3 for length in message.data] for _, message in recorded]
    assert_allclose(recorded_mm, printed, rtol=0.0, atol=PRINT_TOLERANCE)
    poses = recorded_messages(bag_directory, '/target_pose')
    assert_allclose([[message.position.x * 1e3, message.position.y * 1e3,
                      message.position.z * 1e3] for _, message in poses],
                    [table3_row_mm_deg(index)[:3] for index in range(11)],
                    rtol=0.0, atol=1e-9)


def test_ramp_demo_writes_the_four_figures(demo_run, figure_directory):
    """The demo writes the paper's Figures 5, 7 and 9 and the round-trip error as PNG."""
    code, output = demo_run
    assert code == 0, output
    for name in ('input_pose', 'leg_lengths', 'fk_pose', 'round_trip_error'):
        path = figure_directory / f'{name}.png'
        assert path.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n', path
        assert str(path) in output


def test_ramp_demo_passes(demo_run):
    """The demo exits 0, stops its nodes cleanly and says PASS."""
    code, output = demo_run
    assert code == 0, output
    lines = output.splitlines()
    assert 'PASS' in lines, output
    assert 'nodes stopped cleanly' in lines, output
    assert 'Traceback' not in output, output


def test_ramp_demo_prints_eleven_rows_per_table(demo_run):
    """Each of the three tables has the 11 rows of Table 3, numbered 0 to 10."""
    _, output = demo_run
    for title, columns in ((INPUT_TITLE, 6), (LENGTHS_TITLE, 6), (ESTIMATE_TITLE, 8)):
        rows = printed_table(output, title)
        assert [number for number, _ in rows] == list(range(11)), output
        assert all(len(values) == columns for _, values in rows), output


def test_ramp_demo_poses_are_table3(demo_run):
    """The poses received and the poses estimated are Table 3's, to the printed precision."""
    _, output = demo_run
    for title in (INPUT_TITLE, ESTIMATE_TITLE):
        for number, values in printed_table(output, title):
            assert_allclose(values[:6], table3_row_mm_deg(number), rtol=0.0,
                            atol=PRINT_TOLERANCE, err_msg=f'{title}, row {number}')


def test_ramp_demo_round_trip_error_is_below_1e_9(demo_run):
    """The largest round-trip error printed is below 1e-9 m and 1e-9 rad, as is every row's."""
    _, output = demo_run
    match = re.search(r'^largest round-trip error: (\S+) m, (\S+) rad', output, re.MULTILINE)
    assert match, output
    position_error, orientation_error = float(match.group(1)), float(match.group(2))
    assert position_error < 1e-9
    assert orientation_error < 1e-9
    for number, values in printed_table(output, ESTIMATE_TITLE):
        assert max(values[6:]) < 1e-9, f'row {number}: {values[6:]}'


def test_ramp_demo_with_broken_config_fails_with_node_error(config_directory, tmp_path):
    """A broken paper_platform.yaml ends the demo non-zero, showing ik_node's start-up error."""
    broken = tmp_path / 'config'
    shutil.copytree(config_directory, broken)
    (broken / 'paper_platform.yaml').write_text(BROKEN_PLATFORM)

    code, output = run_ramp_demo(['--config-dir', str(broken), '--timeout', DEMO_TIMEOUT])

    assert code is not None and code > 0, f'exit code {code}:\n{output}'
    assert "parameter 'base_joints' must have exactly 18 elements, got 17" in output, output
    assert 'Traceback' not in output, output
