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
The payload changed at run time (``ros2 param set``): every node takes it at once, or says why not.

ik_node with the example masses (a 20 kg payload) and ``leg_force_max`` 100 N: Table 3's row 3
needs 74 N of its busiest leg with 20 kg, 120 N with 40 kg (home: 52 N and 86 N). Set to 40 kg,
the next command of that pose is refused naming ``leg_force_max``; 60 kg is refused (home itself
would need 120 N), as are values a payload cannot have, each naming the parameter, and the old
payload stays. The other mass parameters stay read-only. trajectory_node plans with the new
payload; motion_cueing_node takes one only while the platform rests at home. fk_node's wrench:
test_fk_node_wrench.py.
"""

import math
from pathlib import Path

from geometry_msgs.msg import Pose
from helpers import pose_message
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.node import Node
from rclpy.parameter import Parameter
from reference import TABLE_3
from std_msgs.msg import Float64MultiArray

from stewart_kinematics import travel_ranges
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
from stewart_kinematics.ros.trajectory_node import TrajectoryNode

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
MASSES = ['--ros-args', '--params-file', str(CONFIG / 'paper_platform.yaml'),
          '--params-file', str(CONFIG / 'example_masses.yaml')]
FORCE_LIMIT = [Parameter('leg_force_max', value=100.0)]
HOME, BUSY = TABLE_3[0], TABLE_3[3]


@pytest.fixture
def ik(node_rig, spin_until):
    """Return ``(node, command)``: command(pose) sends it and waits for the node's verdict."""
    node = node_rig.add(IkNode(cli_args=MASSES, parameter_overrides=FORCE_LIMIT))
    probe = node_rig.add(Node('payload_probe'))
    publisher = probe.create_publisher(Pose, 'target_pose', 10)
    lengths = []
    probe.create_subscription(Float64MultiArray, 'leg_lengths', lengths.append, 10)
    node_rig.connect(lambda: publisher.get_subscription_count() >= 1
                     and node.lengths_publisher.get_subscription_count() >= 1, 'ik_node')

    def command(pose):
        """Return ``None`` if the pose was commanded, else the reason it was refused."""
        accounting = node.accounting
        before = (accounting.published, accounting.rejected)
        publisher.publish(pose_message(pose))
        assert spin_until(node_rig.executor, lambda: (
            accounting.published, accounting.rejected) != before)
        return None if accounting.rejected == before[1] else accounting.last_rejection.message
    return node, command


def set_one(node, name, value):
    """Set one parameter; return the result (successful, reason)."""
    [result] = node.set_parameters([Parameter(name, value=value)])
    return result


def test_a_heavier_payload_set_at_run_time_refuses_the_next_pose_by_leg_force_max(ik):
    node, command = ik
    assert command(BUSY) is None
    result = set_one(node, 'payload_mass', 40.0)
    assert result.successful, result.reason
    assert node.get_parameter('payload_mass').value == 40.0
    reason = command(BUSY)
    assert reason is not None and 'leg_force_max' in reason, reason
    assert command(HOME) is None
    # And back: the pose is accepted again.
    assert set_one(node, 'payload_mass', 20.0).successful
    assert command(BUSY) is None


def test_a_payload_too_heavy_for_home_is_refused_naming_it_and_the_old_one_stays(ik):
    node, command = ik
    result = set_one(node, 'payload_mass', 60.0)
    assert not result.successful
    assert result.reason.startswith('payload refused (payload_mass 60.0, payload_center_of_mass '
                                    '[0.0, 0.0, 0.375], payload_inertia'), result.reason
    assert 'home pose breaks the limits' in result.reason and 'leg_force_max' in result.reason
    assert '\n' not in result.reason
    assert node.get_parameter('payload_mass').value == 20.0
    assert node.geometry.mass_properties.payload.mass == 20.0
    assert command(BUSY) is None


@pytest.mark.parametrize('name, value, words', [
    ('payload_mass', -1.0, 'payload_mass'),
    ('payload_mass', math.nan, 'payload_mass'),
    ('payload_mass', math.inf, 'payload_mass'),
    ('payload_mass', 1e308, 'payload_mass'),
    # An inertia (the example's 0.2 kg m^2) on a body of mass 0.
    ('payload_mass', 0.0, "parameters 'payload_mass' and 'payload_inertia'"),
    ('payload_center_of_mass', [0.0, 0.0], 'payload_center_of_mass'),
    ('payload_center_of_mass', [0.0, math.nan, 0.0], 'payload_center_of_mass'),
    ('payload_center_of_mass', [0.0, 0.0, 1e308], 'payload_center_of_mass'),
    ('payload_inertia', [1.0, 1.0, 3.0, 0.0, 0.0, 0.0], 'payload_inertia'),
    ('payload_inertia', [-0.2, 0.2, 0.2, 0.0, 0.0, 0.0], 'payload_inertia'),
    ('payload_inertia', [0.2] * 5, 'payload_inertia'),
])
def test_a_bad_payload_value_is_refused_naming_the_parameter(ik, name, value, words):
    node, command = ik
    old = node.get_parameter(name).value
    result = set_one(node, name, value)
    assert not result.successful
    assert words in result.reason and '\n' not in result.reason, result.reason
    assert list(node.get_parameter(name).value) == list(old) if isinstance(old, list) or (
        not isinstance(old, float)) else node.get_parameter(name).value == old
    assert node.geometry.mass_properties.payload.mass == 20.0
    assert command(BUSY) is None


def test_a_payload_removed_whole_in_one_request_is_taken(ik):
    node, command = ik
    result = node.set_parameters_atomically([
        Parameter('payload_mass', value=0.0), Parameter('payload_inertia', value=[0.0] * 6)])
    assert result.successful, result.reason
    assert node.geometry.mass_properties.payload.mass == 0.0
    assert command(BUSY) is None


@pytest.mark.parametrize('name, value', [('platform_mass', 1.0), ('leg_lower_mass', 1.0),
                                         ('gravity', [0.0, 0.0, -1.0])])
def test_the_other_mass_parameters_stay_read_only(ik, name, value):
    node, _ = ik
    assert not set_one(node, name, value).successful
    assert node.describe_parameter(name).read_only


def test_trajectory_node_plans_with_the_new_payload(ros):
    # 250 N: the default ramp (Table 3) needs at most 153 N with 20 kg, home 250 N with 137 kg.
    node = TrajectoryNode(cli_args=MASSES,
                          parameter_overrides=[Parameter('leg_force_max', value=250.0)])
    try:
        assert node.planner.planner.geometry.mass_properties.payload.mass == 20.0
        assert set_one(node, 'payload_mass', 30.0).successful
        assert node.planner.planner.geometry.mass_properties.payload.mass == 30.0
        assert not set_one(node, 'payload_mass', 150.0).successful
        assert node.planner.planner.geometry.mass_properties.payload.mass == 30.0
    finally:
        node.destroy_node()


def test_motion_cueing_node_takes_a_payload_only_at_rest_at_home(ros):
    node = MotionCueingNode(cli_args=MASSES + [
        '--params-file', str(CONFIG / 'example_limits.yaml'),
        '--params-file', str(CONFIG / 'motion_cueing.yaml')])
    try:
        assert set_one(node, 'payload_mass', 25.0).successful
        assert node.cueing.geometry.mass_properties.payload.mass == 25.0
        # A vehicle that brakes hard: the platform tilts and moves away from home.
        for step in range(20):
            node.cueing.cue(step * 0.01, (-5.0, 0.0, 9.80665), (0.0, 0.0, 0.0), step * 0.01)
        assert not node.cueing.settled()
        result = set_one(node, 'payload_mass', 10.0)
        assert not result.successful
        assert 'only at rest at home' in result.reason, result.reason
        assert node.cueing.geometry.mass_properties.payload.mass == 25.0
    finally:
        node.destroy_node()


def test_ik_node_travel_ranges_follow_a_new_payload(node_rig, spin_until):
    """
    The travel ranges (computed in ik_node's worker process) take the new payload at once.

    With 20 kg and leg_force_max 100 N the force stops some ends; with 40 kg they shrink, and
    the node's ranges are those of the platform carrying 40 kg, not the 20 kg it started with.
    """
    node = node_rig.add(IkNode(cli_args=MASSES, parameter_overrides=FORCE_LIMIT + [
        Parameter('travel_range_rate', value=5.0)]))
    probe = node_rig.add(Node('travel_probe'))
    received = []
    probe.create_subscription(Float64MultiArray, 'travel_ranges',
                              lambda message: received.append(list(message.data)), 10)
    node_rig.connect(lambda: node.workspace.travel_publisher.get_subscription_count() >= 1,
                     'ik_node travel_ranges')
    before = travel_ranges(node.geometry).as_array().ravel()
    assert spin_until(node_rig.executor, lambda: received, timeout=30.0)
    assert_allclose(received[-1], before, rtol=0.0, atol=1e-12)
    assert set_one(node, 'payload_mass', 40.0).successful
    after = travel_ranges(node.geometry).as_array().ravel()
    assert np.any(np.abs(after) < np.abs(before) - 1e-3)   # the heavier payload shrinks them
    assert spin_until(node_rig.executor, lambda: np.allclose(received[-1], after, rtol=0.0,
                                                             atol=1e-12), timeout=30.0), (
        f'still {received[-1]}, expected {after.tolist()}')
