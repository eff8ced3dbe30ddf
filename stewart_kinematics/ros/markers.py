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

Builds a visualization_msgs/msg/MarkerArray from numpy arrays; the nodes publish it.
"""

from geometry_msgs.msg import Point
import numpy as np
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray

#: Colours (r, g, b, a): a leg within its limits, a leg that breaks one, base and platform.
LEG_OK = ColorRGBA(r=0.2, g=0.8, b=0.2, a=1.0)
LEG_VIOLATING = ColorRGBA(r=0.9, g=0.1, b=0.1, a=1.0)
BASE_COLOUR = ColorRGBA(r=0.4, g=0.4, b=0.45, a=0.8)
PLATFORM_COLOUR = ColorRGBA(r=0.3, g=0.5, b=0.9, a=0.8)
#: Marker line widths, metres.
LEG_WIDTH = 0.01
OUTLINE_WIDTH = 0.006


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


def _point(xyz) -> Point:
    return Point(x=float(xyz[0]), y=float(xyz[1]), z=float(xyz[2]))
