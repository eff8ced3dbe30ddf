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
RViz markers of the platform: base, platform and the six legs, coloured by limit status.

Builds a visualization_msgs/msg/MarkerArray from numpy arrays; the nodes publish it, ik_node's
platform markers through :class:`PlatformMarkerPublisher` (at most at ``marker_rate``).
"""

from geometry_msgs.msg import Point
import numpy as np
from std_msgs.msg import ColorRGBA, Header
from stewart_kinematics.limits.kinds import pose_bounds
from visualization_msgs.msg import Marker, MarkerArray

#: Colours (r, g, b, a): a leg within its limits, a leg that breaks one, base and platform.
LEG_OK = ColorRGBA(r=0.2, g=0.8, b=0.2, a=1.0)
LEG_VIOLATING = ColorRGBA(r=0.9, g=0.1, b=0.1, a=1.0)
BASE_COLOUR = ColorRGBA(r=0.4, g=0.4, b=0.45, a=0.8)
PLATFORM_COLOUR = ColorRGBA(r=0.3, g=0.5, b=0.9, a=0.8)
#: Marker line widths, metres.
LEG_WIDTH = 0.01
OUTLINE_WIDTH = 0.006
#: Opacity of the workspace boundary points, whose colours are their limits' (as each kind
#: declares them, :func:`stewart_kinematics.limits.kinds.pose_bounds`; as in the figures).
LIMIT_ALPHA = 0.8
#: Size of a workspace boundary point, metres.
WORKSPACE_POINT_SIZE = 0.004


def platform_markers(header, geometry, position, rotation, violating_legs=(),
                     namespace='stewart_platform') -> MarkerArray:
    """
    Markers of the platform at a pose, in the base frame.

    :param header: std_msgs/msg/Header whose ``frame_id`` is the base frame.
    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param position: platform position, metres, shape (3,).
    :param rotation: platform-to-base rotation, shape (3, 3).
    :param violating_legs: legs (1..6) drawn red because they break a limit; with leg
        ``None`` in it (a limit of the whole platform, such as the singularity margin), all six.
    :param namespace: marker namespace, so that two platforms can share RViz.
    :returns: three markers: the base outline (id 0), the platform outline (id 1) and the
        legs (id 2, one colour per leg).
    """
    platform_joints = (rotation @ geometry.platform_joints.T).T + position
    violating = set(violating_legs)
    if None in violating:
        violating = set(range(1, 7))

    def outline(marker_id, joints, colour):
        marker = Marker(header=header, ns=namespace, id=marker_id, type=Marker.LINE_STRIP,
                        action=Marker.ADD, color=colour)
        marker.pose.orientation.w = 1.0
        marker.scale.x = OUTLINE_WIDTH
        marker.points = [_point(joint) for joint in np.vstack([joints, joints[:1]])]
        return marker

    legs = Marker(header=header, ns=namespace, id=2, type=Marker.LINE_LIST, action=Marker.ADD)
    legs.pose.orientation.w = 1.0
    legs.scale.x = LEG_WIDTH
    for leg, (base, top) in enumerate(zip(geometry.base_joints, platform_joints), start=1):
        colour = LEG_VIOLATING if leg in violating else LEG_OK
        legs.points += [_point(base), _point(top)]
        legs.colors += [colour, colour]
    return MarkerArray(markers=[outline(0, geometry.base_joints, BASE_COLOUR),
                                outline(1, platform_joints, PLATFORM_COLOUR), legs])


class PlatformMarkerPublisher:
    """
    ik_node's ``platform_markers``: the platform of a command, at most at ``marker_rate``.

    Only while someone subscribes, paced by the node's clock. A refused command is shown too
    when its limits were evaluated (the legs at fault in red: what was asked, and why it was
    refused); one that could not be evaluated (a malformed or unreachable pose) is not.

    :param node: the node (its clock and namespace).
    :param publisher: the rclpy publisher of ``platform_markers``.
    :param geometry: the platform.
    :param base_frame: the frame of the markers.
    :param marker_rate: hertz; 0 for no markers.
    """

    def __init__(self, node, publisher, geometry, base_frame: str, marker_rate: float):
        self.node = node
        self.publisher = publisher
        self.geometry = geometry
        self.base_frame = base_frame
        self.period_ns = 1e9 / marker_rate if marker_rate > 0.0 else None
        self.namespace = node.get_namespace().strip('/') or 'stewart_platform'
        #: When the markers were last published, nanoseconds of the node's clock, or ``None``.
        self.last_ns = None

    def show(self, command, stamp=None) -> None:
        """
        Publish the markers of a :class:`~stewart_kinematics.limits.LegCommand`, if due.

        :param stamp: the markers' stamp (a builtin_interfaces/msg/Time), or ``None``: now.
        """
        if not (command.violations or command.accepted) or self.period_ns is None or (
                self.publisher.get_subscription_count() == 0):
            return
        now = self.node.get_clock().now()
        if self.last_ns is not None and now.nanoseconds - self.last_ns < self.period_ns:
            return
        self.last_ns = now.nanoseconds
        self.publisher.publish(platform_markers(
            Header(stamp=now.to_msg() if stamp is None else stamp, frame_id=self.base_frame),
            self.geometry, command.position, command.rotation, command.legs_at_fault,
            self.namespace))


def workspace_markers(header, points, limits, namespace='stewart_platform') -> MarkerArray:
    """
    Markers of the workspace boundary: points coloured by the limit met there.

    :param header: std_msgs/msg/Header whose ``frame_id`` is the base frame.
    :param points: boundary points, metres, base frame, shape (M, 3).
    :param limits: per point, the index of its limit in
        :data:`stewart_kinematics.limits.LIMIT_NAMES`.
    :param namespace: the markers' namespace is this plus ``/workspace``.
    :returns: a DELETEALL marker (so that a new boundary replaces the old one), then one
        POINTS marker per limit met, its id the limit's index.
    """
    namespace = f'{namespace}/workspace'
    clear = Marker(header=header, ns=namespace, action=Marker.DELETEALL)
    markers = [clear]
    points = np.asarray(points, dtype=float)
    limits = np.asarray(limits)
    for index, bound in enumerate(pose_bounds()):
        chosen = points[limits == index]
        if not len(chosen):
            continue
        red, green, blue = bound.colour
        marker = Marker(header=header, ns=namespace, id=index, type=Marker.POINTS,
                        action=Marker.ADD,
                        color=ColorRGBA(r=red, g=green, b=blue, a=LIMIT_ALPHA))
        marker.pose.orientation.w = 1.0
        marker.scale.x = marker.scale.y = WORKSPACE_POINT_SIZE
        marker.points = [Point(x=x, y=y, z=z) for x, y, z in chosen.tolist()]
        markers.append(marker)
    return MarkerArray(markers=markers)


def _point(xyz) -> Point:
    return Point(x=float(xyz[0]), y=float(xyz[1]), z=float(xyz[2]))
