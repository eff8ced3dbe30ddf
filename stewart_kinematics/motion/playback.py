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
Playing poses on a clock: an accepted trajectory's tool poses, each checked as it is sent.

trajectory_node plays an accepted trajectory (with ``play``) as poses of the tool frame on
``target_pose``, for ik_node, at ``publish_rate``: :class:`TrajectoryPlayback` gives the pose
of the time asked as the command gate's verdict on the message's numbers
(:meth:`~stewart_kinematics.limits.CommandGate.tool_pose`: the platform pose ik_node will read
from them, against every pose limit). The poses are setpoints for ik_node; their pace is the
trajectory's, whose leg velocities and accelerations were checked whole when it was accepted.
A pose the gate refuses stops the playing there (the last pose sent stands), with the reason.

Units: metres, radians, seconds. Nothing here imports ROS.
"""

import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.limits import CommandGate, LegCommand, SETPOINT
from stewart_kinematics.model.frames import FrameTree, Transform
from stewart_kinematics.model.rotations import matrix_to_quaternion
from stewart_kinematics.motion.pose_trajectory import TimedTrajectory


class TrajectoryPlayback:
    """
    One accepted trajectory played from a start time: its tool poses, checked as sent.

    :param trajectory: the timed trajectory of the platform frame (base frame).
    :param geometry: the platform and its limits.
    :param frames: the frame tree the trajectory was planned with (its tool frame).
    :param start: the time the playing starts, seconds (the node's clock).
    """

    def __init__(self, trajectory: TimedTrajectory, geometry, frames: Optional[FrameTree],
                 start: float):
        self.trajectory = trajectory
        self.frames = frames if frames is not None else FrameTree()
        self.gate = CommandGate(geometry, timing=SETPOINT, frames=self.frames)
        self.start = float(start)
        self.stopped = False

    @property
    def duration(self) -> float:
        """Return the trajectory's duration, seconds."""
        return self.trajectory.duration

    def pose_at(self, time: float) -> Tuple[LegCommand, bool]:
        """
        Return the command of the pose at ``time``, and whether the playing is over after it.

        Before the start the first pose, after the end the last. A refused pose stops the
        playing (``over`` True); so does the last one.

        :param time: seconds, the node's clock.
        :returns: ``(command, over)``; ``command.tool_pose`` holds the message's numbers.
        """
        elapsed = float(time) - self.start
        if not math.isfinite(elapsed):
            elapsed = 0.0
        sample = self.trajectory.sample([min(max(elapsed, 0.0), self.duration)])
        tool = self.frames.tool_from_platform(Transform(sample.positions[0],
                                                        sample.rotations[0]))
        command = self.gate.tool_pose(np.asarray(tool.position, dtype=float),
                                      matrix_to_quaternion(tool.rotation))
        over = elapsed >= self.duration or not command.accepted
        self.stopped = self.stopped or over
        return command, over
