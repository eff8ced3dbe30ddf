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
Playing poses on a clock: the ramp's and an accepted trajectory's, each checked as it is sent.

trajectory_node publishes poses of the tool frame on ``target_pose``, for ik_node, from two
players, each called by the node's timer with the node's clock and answering with the command
gate's verdict on the message's numbers
(:meth:`~stewart_kinematics.limits.CommandGate.tool_pose`: the platform pose ik_node will read
from them, against every pose limit) and whether the playing is over:

- :class:`RampPlayback`: the Table 3 ramp of a :class:`~stewart_kinematics.motion.ramp.
  RampSchedule`: in table mode the next row at each tick, in interpolate mode the ramp sampled
  at the time of the tick; a pass starts again when looping, else the playing is over after
  its last pose. It starts once ``min_subscribers`` listen, ``start_delay`` later. A pose the
  gate refuses (a tool frame changed since the ramp was checked at start-up) is not sent; the
  ramp goes on.
- :class:`TrajectoryPlayback`: an accepted trajectory (with ``play``) at ``publish_rate``; its
  pace is the trajectory's, whose leg velocities and accelerations were checked whole when it
  was accepted. A pose the gate refuses stops the playing there (the last pose sent stands).

The poses are setpoints for ik_node. Units: metres, radians, seconds. Nothing here imports ROS.
"""

import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.findings import Finding
from stewart_kinematics.limits import CommandGate, LegCommand, SETPOINT
from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.frames import FrameTree, Transform
from stewart_kinematics.model.rotations import matrix_to_quaternion
from stewart_kinematics.motion.pose_trajectory import TimedTrajectory
from stewart_kinematics.motion.ramp import RampSchedule
from stewart_kinematics.parameters.settings import RampSettings


class RampPlayback:
    """
    The ramp played on trajectory_node's timer: the pose of each tick, checked as sent.

    :param schedule: the ramp and how it is played (mode, period, duration, loop).
    :param geometry: the platform and its limits.
    :param frames: the frame tree of the ``target_pose`` messages (their tool frame), or
        ``None``: the platform frame.
    :param min_subscribers: how many subscribers must listen before the ramp starts.
    :param start_delay: seconds from then to the first pose.
    """

    def __init__(self, schedule: RampSchedule, geometry, frames: Optional[FrameTree] = None,
                 min_subscribers: int = 0, start_delay: float = 0.0):
        self.schedule = schedule
        self.geometry = geometry
        self.min_subscribers = int(min_subscribers)
        self.start_delay = float(start_delay)
        #: The table's rows (table mode), computed once.
        self.rows = schedule.ramp.rows
        self.set_frames(frames)
        self._row = 0
        self._pass_start = None
        #: Whether the playing is over (a ramp that does not loop, after its last pose).
        self.finished = False

    @classmethod
    def from_settings(cls, settings: RampSettings, geometry,
                      frames: Optional[FrameTree] = None) -> 'RampPlayback':
        """
        Build it from trajectory_node's ramp settings.

        :raises ValueError: naming the parameters, for a table or a timing not allowed.
        """
        return cls(RampSchedule.from_settings(settings), geometry, frames,
                   settings.min_subscribers, settings.start_delay)

    @property
    def plays(self) -> bool:
        """Return whether there is a ramp to play (the mode is not ``'off'``)."""
        return self.schedule.plays

    @property
    def period(self) -> float:
        """Return the seconds between two ticks: one pose each."""
        return self.schedule.period

    def set_frames(self, frames: Optional[FrameTree]) -> None:
        """Take a new frame tree (a tool frame changed at run time) from the next pose on."""
        self.frames = frames if frames is not None else FrameTree()
        self.gate = CommandGate(self.geometry, timing=SETPOINT, frames=self.frames)

    def check(self) -> Optional[Finding]:
        """
        Check every pose of a pass against the limits, before playing.

        As :meth:`~stewart_kinematics.motion.ramp.RampSchedule.check`, with this ramp's frames.

        :returns: ``None``, or the ``out_of_limits`` finding that lists the failing samples.
        """
        return self.schedule.check(self.geometry, self.frames)

    def may_start(self, subscribers: int) -> bool:
        """Return whether the ramp may start with ``subscribers`` listening."""
        return subscribers >= self.min_subscribers

    def start(self, time: float) -> None:
        """Start a pass at ``time`` (seconds, the node's clock): the first pose comes next."""
        self._row = 0
        self._pass_start = _seconds(time)
        self.finished = False

    def next_pose(self, time: float) -> Tuple[LegCommand, bool]:
        """
        Return the command of the pose to publish at this tick, and whether the playing is over.

        Table mode: the next row (the time is not used). Interpolate mode: the ramp
        ``time - start`` seconds into the pass (the last pose once past ``duration``, where
        the pass ends). At the end of a pass a looping ramp starts the next; otherwise the
        playing is over (``over`` True, and :attr:`finished`). Starts a pass first if none was.

        :param time: seconds, the node's clock (a time that is not finite counts as the
            start of the pass).
        :returns: ``(command, over)``: the gate's verdict, its ``tool_pose`` the message's
            numbers; not to be sent when refused.
        :raises ValueError: for a time that is not a number.
        """
        if self._pass_start is None:
            self.start(time)
        schedule = self.schedule
        if schedule.mode == 'table':
            pose = self.rows[self._row]
            self._row += 1
            ended = self._row == len(self.rows)
            if ended:
                self._row = 0
        else:
            now = _seconds(time, None)
            elapsed = 0.0 if now is None else now - self._pass_start
            pose = schedule.pose_at(elapsed)
            ended = elapsed >= schedule.duration
            if ended:
                self._pass_start = now
        over = ended and not schedule.loop
        self.finished = self.finished or over
        return self.gate.pose_vector(pose), over


def _seconds(time, otherwise=0.0):
    """Return ``time`` as a float when finite, else ``otherwise``; refuse what is no number."""
    try:
        seconds = float(time)
    except (TypeError, ValueError):
        raise ValueError(f'a time must be a number of seconds, got {preview(time)}') from None
    return seconds if math.isfinite(seconds) else otherwise


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
