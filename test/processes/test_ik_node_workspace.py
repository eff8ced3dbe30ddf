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
ik_node's workspace outputs, with ik_node started as a process.

``workspace_markers`` is latched and published again after a parameter change;
``travel_ranges`` starts from the last accepted pose.

The expected content is computed here with the core (:mod:`stewart_kinematics.analysis.workspace`),
whose own accuracy test/analysis/test_workspace.py checks against independent computations.
"""

import math
from pathlib import Path

from geometry_msgs.msg import Pose
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import SetParameters
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Float64MultiArray
from stewart_kinematics import load_geometry, travel_ranges
from stewart_kinematics.analysis import workspace
from stewart_kinematics.limits import check_poses_array, LIMIT_NAMES
from stewart_kinematics.ros.message_conversions import pose_to_message
from visualization_msgs.msg import Marker, MarkerArray

pytestmark = pytest.mark.process

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml']
GEOMETRY = load_geometry(FILES)
#: Coarse grids: the markers are quick to compute.
RESOLUTION, NEW_RESOLUTION = 0.02, 0.03
ARGUMENTS = ['--ros-args', '--params-file', str(FILES[0]), '--params-file', str(FILES[1]),
             '-p', f'workspace_resolution:={RESOLUTION}', '-p', 'travel_range_rate:=5.0']
POSE = np.array([0.03, -0.02, 0.47, math.radians(3.0), math.radians(-2.0), math.radians(10.0)])
LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)


def marker_points(array):
    """Return (points (M, 3), limit index (M,)) of a workspace MarkerArray, checking its form."""
    first, *rest = array.markers
    assert first.action == Marker.DELETEALL and first.ns == 'stewart_platform/workspace'
    points, limits = [], []
    for marker in rest:
        assert (marker.type, marker.action, marker.ns) == \
            (Marker.POINTS, Marker.ADD, 'stewart_platform/workspace')
        assert marker.header.frame_id == 'stewart_base' and 0 <= marker.id < len(LIMIT_NAMES)
        points += [(point.x, point.y, point.z) for point in marker.points]
        limits += [marker.id] * len(marker.points)
    return np.array(points), np.array(limits)


def assert_markers_show_the_workspace(array, resolution):
    """Assert the markers hold the core's workspace shell at this resolution."""
    points, limits = marker_points(array)
    expected = workspace.workspace_shell(GEOMETRY, resolution=resolution)
    assert len(points) == len(expected.points) > 500
    order, expected_order = np.lexsort(points.T), np.lexsort(expected.points.T)
    assert_allclose(points[order], expected.points[expected_order], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(limits[order], expected.limit[expected_order])
    # Every point is reachable at the home orientation.
    poses = np.column_stack([points, np.zeros((len(points), 3))])
    assert check_poses_array(GEOMETRY, poses).allowed.all()


def test_workspace_markers_and_travel_ranges(client, start_node):
    node = start_node('ik_node', ARGUMENTS)
    markers, ranges = [], []
    client.node.create_subscription(MarkerArray, 'workspace_markers', markers.append, LATCHED)
    client.node.create_subscription(Float64MultiArray, 'travel_ranges', ranges.append, 10)
    publisher = client.node.create_publisher(Pose, 'target_pose', 10)

    # Latched: the markers computed at start-up reach a subscriber that joins later.
    client.wait(lambda: markers, 'workspace_markers', [node])
    assert_markers_show_the_workspace(markers[0], RESOLUTION)

    # Travel ranges from the home pose until a pose is accepted, then from that pose.
    client.wait(lambda: ranges, 'travel_ranges', [node])
    message = ranges[-1]
    assert [(dim.size, dim.stride) for dim in message.layout.dim] == [(6, 12), (2, 2)]
    assert message.layout.dim[0].label.startswith('axis: X, Y, Z [m], alpha, beta, gamma')
    assert_allclose(message.data, travel_ranges(GEOMETRY).as_array().ravel(), atol=2e-7)
    client.wait(lambda: publisher.get_subscription_count() >= 1, 'ik_node on target_pose',
                [node])
    publisher.publish(pose_to_message(POSE))
    expected = travel_ranges(GEOMETRY, POSE).as_array().ravel()
    client.wait(lambda: np.allclose(ranges[-1].data, expected, rtol=0, atol=2e-7),
                'travel_ranges from the accepted pose', [node])
    # A refused pose does not move the start of the ranges.
    publisher.publish(pose_to_message(POSE + [0.0, 0.0, 0.5, 0.0, 0.0, 0.0]))
    count = len(ranges)
    client.wait(lambda: len(ranges) >= count + 2, 'two more travel_ranges', [node])
    assert_allclose(ranges[-1].data, expected, rtol=0, atol=2e-7)

    # A new resolution: the markers are computed and published again.
    service = client.node.create_client(SetParameters, '/ik_node/set_parameters')
    client.wait(service.service_is_ready, 'ik_node parameter service', [node])

    def set_resolution(value):
        request = SetParameters.Request(parameters=[Parameter(
            name='workspace_resolution',
            value=ParameterValue(type=ParameterType.PARAMETER_DOUBLE, double_value=value))])
        future = service.call_async(request)
        client.wait(future.done, 'the parameter set', [node])
        return future.result().results[0]

    refused = set_resolution(0.0005)
    assert not refused.successful and '0.0 or in [0.002, 0.1]' in refused.reason
    assert set_resolution(NEW_RESOLUTION).successful
    client.wait(lambda: len(markers) >= 2, 'workspace_markers after the change', [node])
    assert_markers_show_the_workspace(markers[-1], NEW_RESOLUTION)
    assert node.running()
