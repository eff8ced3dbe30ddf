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
motion_cueing_node's parameters, declared as the other nodes declare theirs (issue 28).

Before, the node declared its parameters without the node's own arguments and without a
run-time hook: a misspelt name given with the node's ``cli_args`` or ``parameter_overrides``
was ignored (the default stayed), and a tool frame set at run time was accepted but never
applied. Now a misspelt name stops the start with the name, every parameter but the tool
frame's is read-only, and a new tool frame applies from the next command on. The node's
callbacks are called directly, as its executor would.
"""

from array import array
import math
from pathlib import Path

from geometry_msgs.msg import Pose
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.parameter import Parameter
from sensor_msgs.msg import Imu

from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = ['--params-file', str(CONFIG / 'paper_platform.yaml'),
         '--params-file', str(CONFIG / 'example_limits.yaml'),
         '--params-file', str(CONFIG / 'motion_cueing.yaml')]
G = 9.80665
#: The tool frame, payload and control parameters: the only ones a user may change while the
#: node runs (a payload only while the platform rests at home: test_payload_parameters.py; the
#: gains ramped or refused: test_cueing_controls.py).
WRITABLE = {'tool_frame', 'tool_frame_position', 'tool_frame_orientation_deg', 'use_sim_time',
            'payload_mass', 'payload_center_of_mass', 'payload_inertia', 'cueing_intensity',
            'translation_scale', 'tilt_scale', 'rotation_scale', 'gain_ramp_time',
            'soft_start_time', 'soft_stop_time'}


def imu(stamp_ns):
    """sensor_msgs/msg/Imu of a vehicle at rest, stamped ``stamp_ns``."""
    message = Imu()
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    message.linear_acceleration.z = G
    return message


@pytest.fixture
def node(ros):
    """Make a motion_cueing_node with the shipped files, its target_pose messages recorded."""
    made = MotionCueingNode(cli_args=['--ros-args'] + FILES)
    made.sent = []
    made.target_publisher._publisher.publish = made.sent.append
    yield made
    made.destroy_node()


def position(message: Pose):
    """Return a Pose's position as an array."""
    return np.array([message.position.x, message.position.y, message.position.z])


@pytest.mark.parametrize('arguments', [
    {'cli_args': ['--ros-args'] + FILES + ['-p', 'tilt_rate_max_dg:=2.0']},
    {'cli_args': ['--ros-args'] + FILES,
     'parameter_overrides': [Parameter('input_timout', value=1.0)]},
])
def test_a_misspelt_parameter_given_to_the_node_stops_the_start_with_its_name(ros, arguments):
    """Before, rcl ignored it and the default stayed; now the start fails, naming it."""
    name = 'tilt_rate_max_dg' if 'parameter_overrides' not in arguments else 'input_timout'
    with pytest.raises(ValueError, match=name):
        MotionCueingNode(**arguments)


def test_a_tool_frame_set_at_run_time_applies_from_the_next_command(node):
    """tool_frame_position changed while running: the next target_pose is the new tool's pose."""
    home = node.cueing.geometry.home_pose
    node.on_imu(imu(1_000_000_000))
    assert_allclose(position(node.sent[-1]), home[:3], rtol=0.0, atol=1e-12)
    [result] = node.set_parameters([Parameter('tool_frame_position', value=[0.0, 0.0, 0.3])])
    assert result.successful, result.reason
    node.on_imu(imu(1_010_000_000))
    assert_allclose(position(node.sent[-1]), home[:3] + [0.0, 0.0, 0.3], rtol=0.0, atol=1e-12)
    assert node.settings.frames.tool_frame_position == (0.0, 0.0, 0.3)


def test_a_tool_frame_that_is_not_allowed_is_refused_with_the_reason(node):
    """Validated as at start-up: three finite values within 1000 m; the old frame stays."""
    for value in ([0.0, 0.0], [0.0, 0.0, math.nan], [0.0, 0.0, 1e4]):
        [result] = node.set_parameters([Parameter('tool_frame_position', value=value)])
        assert not result.successful and 'tool_frame_position' in result.reason
    node.on_imu(imu(1_000_000_000))
    assert_allclose(position(node.sent[-1]), node.cueing.geometry.home_pose[:3], atol=1e-12)


def test_every_other_parameter_is_read_only(node):
    """The geometry, the washout, the watchdog and the queue: refused at run time."""
    names = {name for name in node._parameters if not name.startswith('qos_overrides.')}
    assert WRITABLE <= names
    for name in sorted(names - WRITABLE):
        assert node.describe_parameter(name).read_only, name
    [result] = node.set_parameters([Parameter('input_timeout', value=2.0)])
    assert not result.successful
    assert node.cueing.settings.input_timeout == 0.5


def test_gains_set_together_are_checked_as_a_whole_and_taken_together(node):
    """A gain beyond the travel at intensity 1, with an intensity that brings it in: taken."""
    [alone] = node.set_parameters([Parameter('translation_scale', value=[2.0, 0.2, 0.2])])
    assert not alone.successful and 'travel' in alone.reason
    result = node.set_parameters_atomically([
        Parameter('translation_scale', value=[2.0, 0.2, 0.2]),
        Parameter('cueing_intensity', value=0.2)])
    assert result.successful, result.reason
    assert_allclose(node.cueing.gains.target[:3], [0.4, 0.04, 0.04], rtol=1e-12)
    assert node.cueing.settings.translation_scale == (2.0, 0.2, 0.2)
    [raised] = node.set_parameters([Parameter('cueing_intensity', value=1.0)])
    assert not raised.successful and 'cueing_intensity' in raised.reason
    assert_allclose(node.cueing.gains.target[:3], [0.4, 0.04, 0.04], rtol=1e-12)


def test_a_gain_set_at_run_time_is_logged_as_a_list(node, monkeypatch):
    """
    The log says the gains as numbers; it said rclpy's array('d', [0.5, 0.5, 0.5]).

    The parameter services give an array parameter as an array.array, as here.
    """
    logged = []

    class Logger:
        info = warning = error = logged.append

    monkeypatch.setattr(node, 'get_logger', Logger)
    [result] = node.set_parameters([Parameter('rotation_scale', value=array('d', [0.5] * 3))])
    assert result.successful, result.reason
    assert any(line.startswith('rotation_scale set to [0.5, 0.5, 0.5]: ramping over')
               for line in logged), logged


def test_a_p_given_after_the_files_wins_over_their_value(ros):
    # rcl takes a plain -p as a /** value, and the file's motion_cueing_node section won over it
    # whatever the order: cueing_method stayed 'classical', tilt_max_deg 10.
    made = MotionCueingNode(cli_args=['--ros-args'] + FILES + [
        '-p', 'cueing_method:=mpc', '-p', 'tilt_max_deg:=7.0', '-p', 'cueing_intensity:=0.5'])
    try:
        assert made.get_parameter('cueing_method').value == 'mpc'
        assert made.get_parameter('tilt_max_deg').value == 7.0
        assert made.get_parameter('cueing_intensity').value == 0.5
        assert made.cueing.settings.cueing_method == 'mpc'
        assert made.cueing.settings.tilt_max == pytest.approx(math.radians(7.0), abs=1e-12)
    finally:
        made.destroy_node()
    # A file given after the -p wins in turn: the last value given is the one taken.
    made = MotionCueingNode(cli_args=['--ros-args', '-p', 'cueing_method:=mpc'] + FILES)
    try:
        assert made.get_parameter('cueing_method').value == 'classical'
    finally:
        made.destroy_node()


def test_a_later_p_of_the_wrong_type_stops_the_start_with_its_source(ros):
    for text, words in (('cueing_method:=5', "'cueing_method' must be of type string"),
                        ('tilt_max_deg:=.nan', 'tilt_max_deg'),
                        ('tilt_max_deg:=1e308', 'tilt_max_deg'),
                        ('park_position:=[0.0]', 'park_position'),
                        ('park_orientation_deg:=[0.0, 60.0, 0.0]', 'beyond its limits'),
                        ('park_orientation_deg:=[0.0, .nan, 0.0]', 'park_orientation_deg')):
        with pytest.raises(Exception) as raised:
            MotionCueingNode(cli_args=['--ros-args'] + FILES + ['-p', text]).destroy_node()
        assert words in str(raised.value), (text, raised.value)
