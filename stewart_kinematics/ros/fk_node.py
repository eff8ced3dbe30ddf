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
Forward kinematics node: six leg lengths in, the platform pose out.

Subscribes ``leg_lengths`` (std_msgs/msg/Float64MultiArray, metres, leg 1..6), ``joint_states``
(sensor_msgs/msg/JointState, legs ``leg_1`` .. ``leg_6``), ``leg_velocities`` (Float64MultiArray,
m/s) and ``anchor_pose`` (geometry_msgs/msg/PoseStamped: a known pose of the tool frame, in the
base or user frame, to re-anchor the tracker). Publishes ``estimated_pose``
(geometry_msgs/msg/Pose: the tool frame in the base frame, metres), ``estimated_pose_stamped``
(geometry_msgs/msg/PoseStamped: the tool frame in ``estimated_pose_frame``, with the stamp of the
joint state it comes from, or the time of the estimate), ``estimated_twist``
(geometry_msgs/msg/Twist, base frame: from leg velocities, at the last pose; the velocity of the
tool frame's origin and the angular velocity, like every pose topic about the tool frame's point),
``estimated_wrench`` (geometry_msgs/msg/WrenchStamped, for joint states with efforts: the wrench
the environment applies to the platform, platform frame, about its origin, from
:func:`stewart_kinematics.dynamics.external_wrench.external_wrench`, statics), the platform
frame on ``/tf`` (with the same stamp) and the user and tool frames on ``/tf_static``
(see :mod:`stewart_kinematics.model.frames`). Each solve starts from the last good solution, since
a platform moves continuously, and falls back to the home pose when that fails; the service
``reset_tracker`` (std_srvs/srv/Trigger) makes the next solve start from the home pose, for homing
and restarts, and ``anchor_pose`` makes it start from a known pose. What to publish and what to
refuse is decided by :class:`stewart_kinematics.PoseTracker` (lengths out of the limits, lengths
that neither start solves, a solution whose pose is not fixed to pose_tolerance, out of the limits,
or in another assembly mode), and so are the tool frame's pose and twist it publishes (in the base
frame and in ``estimated_pose_frame``); the node converts the messages, publishes, and counts each
refusal and each warning (near a singularity) with the core's reason on the log and
``/diagnostics``.

Every ``assembly_mode_margin_period`` seconds the distance from the last solution to the
nearest other real assembly mode within the limits is computed in a worker process (a thread
would hold up the message callbacks: it shares the interpreter lock)
(:class:`stewart_kinematics.workers.margin_monitor.AssemblyModeMarginMonitor`, only when the
lengths changed) and reported with the other statuses, WARN when below
``assembly_mode_margin_warning``. With ``refuse_ambiguous_start`` the tracker refuses a first
solution (after a start or reset_tracker) when the lengths allow several modes within the
limits and none near the last known pose.

Where a fold singularity may have been crossed since the tracker was last anchored (see
doc/assembly_modes.md), the two assembly modes that meet there cannot be told apart by the
lengths: every pose is then still published, with an ``ambiguous_estimate`` warning counted on
its input's status, and the status ``assembly mode ambiguity`` is WARN, until the tracker is
re-anchored: ``reset_tracker`` (homing), a known pose on ``anchor_pose``, or a margin that
finds no other real mode the platform could be in.
"""

from diagnostic_msgs.msg import DiagnosticStatus, KeyValue
from geometry_msgs.msg import PoseStamped
import numpy as np
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Header
from std_srvs.srv import Trigger

from stewart_kinematics import findings
from stewart_kinematics.dynamics.external_wrench import external_wrench
from stewart_kinematics.findings import Finding
from stewart_kinematics.model.frames import Transform
from stewart_kinematics.parameters import (
    actuator_interface_from_settings,
    FkNodeSettings,
    frames_from_settings,
    geometry_from_settings,
    SolverSettings,
)
from stewart_kinematics.pose_decisions.pose_tracker import PoseTracker
from stewart_kinematics.pose_decisions.tracker_status import ambiguity_status, margin_status
from stewart_kinematics.ros.interfaces import FK_NODE
from stewart_kinematics.ros.managed import ManagedNode
from stewart_kinematics.ros.message_accounting import (
    LogThrottle,
    MessageAccounting,
    NodeDiagnostics,
    WARNING_PERIOD,
)
from stewart_kinematics.ros.message_conversions import (
    leg_efforts_from_joint_state,
    leg_lengths_from_message,
    legs_from_joint_state,
    pose_to_message,
    twist_to_message,
    wrench_to_message,
)
from stewart_kinematics.ros.node_main import (
    create_declared_service,
    create_input_subscription,
    create_output_publisher,
    run_node,
)
from stewart_kinematics.ros.ros_parameters import RunTimePayload
from stewart_kinematics.ros.transforms import TransformBroadcaster
from stewart_kinematics.workers.margin_monitor import AssemblyModeMarginMonitor


class FkNode(ManagedNode):
    """Publish the platform pose that matches every set of leg lengths received, or refuse."""

    SETTINGS = FkNodeSettings

    def __init__(self, **kwargs):
        super().__init__('fk_node', **kwargs)

    def run_time_payload(self):
        """Take a new payload at once: the wrench and the limits use it."""
        return RunTimePayload(lambda: self.geometry, self.set_mass_properties)

    def configure(self):
        """Build the geometry, the tracker, every publisher, subscription and service."""
        settings = self.settings
        self.geometry = geometry_from_settings(settings.geometry)
        self.actuators = actuator_interface_from_settings(settings.actuators)
        # Its frame tree is replaced whole when a tool frame parameter changes: one tree per
        # message. A ValueError (an estimated_pose_frame it cannot place) stops the start.
        self.tracker = PoseTracker(self.geometry, settings.solver,
                                   frames_from_settings(settings.frames),
                                   settings.fk_frames.estimated_pose_frame)
        depth = settings.queue.queue_depth
        self.pose_publisher = create_output_publisher(self, FK_NODE['estimated_pose'], depth)
        self.stamped_publisher = create_output_publisher(
            self, FK_NODE['estimated_pose_stamped'], depth)
        self.twist_publisher = create_output_publisher(self, FK_NODE['estimated_twist'], depth)
        self.wrench_publisher = create_output_publisher(
            self, FK_NODE['estimated_wrench'], depth)
        self.tf = TransformBroadcaster(self, dynamic=FK_NODE['/tf'], static=FK_NODE[
            '/tf_static']) if settings.fk_frames.publish_tf else None
        self.send_static_frames()
        diagnostics = NodeDiagnostics(self)
        self.accounting = diagnostics.accounting('leg_lengths')
        self.joint_state_accounting = diagnostics.accounting('joint_states')
        self.velocity_accounting = diagnostics.accounting('leg_velocities')
        self.anchor_accounting = diagnostics.accounting('anchor_pose')
        create_input_subscription(self, FK_NODE['leg_lengths'], self.on_leg_lengths, depth)
        create_input_subscription(self, FK_NODE['joint_states'], self.on_joint_states, depth)
        create_input_subscription(
            self, FK_NODE['leg_velocities'], self.on_leg_velocities, depth)
        create_input_subscription(self, FK_NODE['anchor_pose'], self.on_anchor_pose, depth)
        create_declared_service(self, FK_NODE['reset_tracker'], self.on_reset_tracker)
        diagnostics.reporters.append(AmbiguityReport(self, diagnostics))
        self.margin = None
        margin = settings.assembly_modes
        if margin.assembly_mode_margin_period > 0.0:
            self.margin = AssemblyModeMarginReport(
                self, diagnostics, AssemblyModeMarginMonitor(
                    self.geometry, margin.assembly_mode_margin_warning, worker='process'))
            diagnostics.reporters.append(self.margin)   # with the inputs, once a second
            self.create_timer(margin.assembly_mode_margin_period, self.on_margin_timer)
        self.get_logger().info(
            f'ready: tolerance {settings.solver.tolerance:g} m, '
            f'at most {settings.solver.max_iterations} iterations')

    def send_static_frames(self):
        """Send the user and tool frames on /tf_static (latched; managed: once active)."""
        if self.tf is not None:
            self.tf.send_static(self.tracker.frames.static_transforms(),
                                self.get_clock().now().to_msg())

    def activate(self):
        """Send the static frames, which a managed node could not send while inactive."""
        if self.managed:
            self.send_static_frames()

    def on_parameter_change(self, name, value):
        """Pass a solver parameter (already validated) to the tracker; take a new tool frame."""
        self.settings = self.settings.replace(**{name: value})
        if name.startswith('tool_frame'):
            old = self.tracker.frames
            self.tracker.set_frames(frames_from_settings(self.settings.frames))
            if self.tf is not None:
                if old.tool_frame != self.tracker.frames.tool_frame:
                    self.tf.forget_static(old.tool_frame)
                self.tf.send_static(self.tracker.frames.static_transforms(),
                                    self.get_clock().now().to_msg())
        if name in SolverSettings.names():
            self.tracker.configure(self.settings.solver)
        if name == 'assembly_mode_margin_warning' and self.margin is not None:
            self.margin.monitor.warning_distance = value

    def set_mass_properties(self, geometry):
        """Take the geometry carrying a new payload: the wrench and the limits use it now."""
        self.geometry = geometry
        self.tracker.set_mass_properties(geometry)

    def on_margin_timer(self):
        """
        Start computing the assembly-mode margin of the last solution, in the background.

        The latest margin goes to the tracker, which may flag its estimate ambiguous (another
        mode near) or re-anchor (no other mode the platform could be in).
        """
        if self.tracker.follow_margin(self.margin.monitor):
            self.get_logger().info(f'estimate unambiguous again: {self.tracker.anchored_by}')

    def cleanup(self):
        """Stop the margin's worker process, if configure got as far as starting it."""
        margin = getattr(self, 'margin', None)
        if margin is not None:
            margin.monitor.close()

    def on_leg_lengths(self, message: Float64MultiArray):
        """Solve for the pose of the received lengths and publish it, or say why not."""
        self.accounting.receive()
        try:
            lengths = leg_lengths_from_message(message)
        except ValueError as error:
            self.accounting.reject(Finding(findings.INVALID_LENGTHS, str(error)))
            return
        # Stamped with the time of the estimate, read only for an output that carries it.
        self.estimate(lengths, None, self.accounting)

    def on_joint_states(self, message: JointState):
        """
        Solve for the pose of a joint state; with leg velocities, publish the twist too.

        A joint state that names none of this platform's joints belongs to another (two
        hexapods may share one ``joint_states``): it is skipped, and not counted.
        """
        if not self.actuators.concerns(message.name):
            return
        self.joint_state_accounting.receive()
        try:
            lengths, velocities = legs_from_joint_state(message, self.actuators)
        except ValueError as error:
            self.joint_state_accounting.reject(Finding(findings.INVALID_LENGTHS, str(error)))
            return
        estimate = self.estimate(lengths, message.header, self.joint_state_accounting,
                                 velocities)
        if estimate.twist is not None:
            self.twist_publisher.publish(twist_to_message(estimate.tool_twist))
        if estimate.accepted:
            self.publish_wrench(message, estimate.pose)

    def publish_wrench(self, message: JointState, pose):
        """
        Publish the external wrench on the platform from a joint state's efforts, or warn why not.

        Statics: the model's forces are those that hold the pose still (doc/dynamics.md).

        :param message: the joint state, its names already matched to the legs.
        :param pose: the platform's pose it was solved to (metres, radians).
        """
        try:
            efforts = leg_efforts_from_joint_state(message, self.actuators)
            if efforts is None:
                if self.wrench_publisher.get_subscription_count() > 0:
                    self.joint_state_accounting.warn(Finding(
                        findings.INVALID_EFFORTS, 'no estimated_wrench: the joint state '
                        'carries no efforts (the measured leg forces, N)'))
                return
            wrench = external_wrench(self.geometry, pose, efforts)
        except ValueError as error:
            self.joint_state_accounting.warn(Finding(
                findings.INVALID_EFFORTS, f'no estimated_wrench: {error}'))
            return
        self.wrench_publisher.publish(wrench_to_message(
            Header(stamp=message.header.stamp,
                   frame_id=self.tracker.frames.platform_frame), wrench))

    def on_leg_velocities(self, message: Float64MultiArray):
        """Publish the platform twist of leg velocities at the last estimated pose."""
        self.velocity_accounting.receive()
        velocities = np.asarray(message.data, dtype=float)[message.layout.data_offset:]
        twist = self.tracker.twist(velocities)
        if not twist.accepted:
            self.velocity_accounting.reject(twist.refusal)
            return
        self.velocity_accounting.publish(self.twist_publisher,
                                         twist_to_message(twist.tool_twist))

    def on_reset_tracker(self, request: Trigger.Request, response: Trigger.Response):
        """Forget the last solution: the next solve starts from the home pose."""
        self.tracker.reset()
        response.success = True
        response.message = 'tracker reset: the next solve starts from the home pose'
        self.get_logger().info(response.message)
        return response

    def on_anchor_pose(self, message: PoseStamped):
        """Re-anchor the tracker at a known pose of the tool frame (base or user frame)."""
        accounting = self.anchor_accounting
        accounting.receive()
        point, orientation = message.pose.position, message.pose.orientation
        anchor = self.tracker.anchor_tool_pose(
            (point.x, point.y, point.z),
            (orientation.x, orientation.y, orientation.z, orientation.w),
            frame_id=message.header.frame_id)
        for warning in anchor.warnings:
            accounting.warn(warning)
        if not anchor.accepted:
            accounting.reject(anchor.refusal)
            return
        accounting.use()
        self.get_logger().info(
            'tracker anchored at a known pose: the next solve starts from the platform pose '
            f'{np.round(anchor.pose, 6).tolist()} (m, rad)', throttle_duration_sec=1.0)

    def estimate(self, lengths, header: Header, accounting: MessageAccounting,
                 velocities=None):
        """
        Publish the tracker's pose of six leg lengths, or reject them with its reason.

        :param header: stamp to carry to ``estimated_pose_stamped`` and ``/tf``, or ``None``
            for the time now (read only when one of them has a subscriber).
        :param velocities: the leg velocities of a joint state, or ``None``.
        :returns: the tracker's :class:`~stewart_kinematics.PoseEstimate` (with the twist of
            the velocities, if any, for the caller to publish).
        """
        estimate = self.tracker.update(lengths, velocities)
        for warning in estimate.warnings:
            accounting.warn(warning)
        if not estimate.accepted:
            accounting.reject(estimate.refusal)
            return estimate
        accounting.publish(self.pose_publisher, pose_to_message(estimate.tool_pose))
        # The other forms only for a subscriber, as ik_node's.
        stamped = self.stamped_publisher.get_subscription_count() > 0
        broadcast = self.tf is not None and self.tf.has_listeners()
        if not (stamped or broadcast):
            return estimate
        stamp = header.stamp if header is not None else self.get_clock().now().to_msg()
        if stamped:
            self.stamped_publisher.publish(PoseStamped(
                header=Header(stamp=stamp, frame_id=estimate.pose_frame),
                pose=pose_to_message(estimate.framed_tool_pose)))
        if broadcast:
            frames = estimate.frames
            self.tf.send(frames.base_frame, frames.platform_frame,
                         Transform.from_pose(estimate.pose), stamp)
        return estimate


class AssemblyModeMarginReport:
    """
    The assembly-mode margin as a diagnostic status, reported with the node's inputs.

    :param node: the fk_node.
    :param diagnostics: its :class:`NodeDiagnostics`.
    :param monitor: the core's :class:`AssemblyModeMarginMonitor`, which decides the warning.
    """

    def __init__(self, node, diagnostics: NodeDiagnostics, monitor: AssemblyModeMarginMonitor):
        self.monitor = monitor
        self.status_name = f'{node.get_fully_qualified_name()}: assembly mode margin'
        self.hardware_id = diagnostics.hardware_id
        self._log_throttle = LogThrottle(node.get_logger(), WARNING_PERIOD)

    def report(self) -> DiagnosticStatus:
        """Return the latest margin: WARN with the core's reason when it deserves a warning."""
        status = margin_status(self.monitor)
        if status.warning is not None:
            self._log_throttle.log(status.warning.code, status.warning.message)
        return DiagnosticStatus(
            level=DiagnosticStatus.WARN if status.warning else DiagnosticStatus.OK,
            name=self.status_name, message=status.message, hardware_id=self.hardware_id,
            values=[KeyValue(key=key, value=value) for key, value in status.values])


class AmbiguityReport:
    """
    Whether the tracker's estimate may be in another assembly mode, as a diagnostic status.

    WARN with the tracker's reason from the first sign of a fold crossing until the tracker is
    re-anchored, whether messages arrive or not.

    :param node: the fk_node (its tracker is read at each report).
    :param diagnostics: its :class:`NodeDiagnostics`.
    """

    def __init__(self, node, diagnostics: NodeDiagnostics):
        self.node = node
        self.status_name = f'{node.get_fully_qualified_name()}: assembly mode ambiguity'
        self.hardware_id = diagnostics.hardware_id

    def report(self) -> DiagnosticStatus:
        """Return the tracker's ambiguity: WARN with its finding while it holds, else OK."""
        status = ambiguity_status(self.node.tracker)
        return DiagnosticStatus(
            level=DiagnosticStatus.WARN if status.warning else DiagnosticStatus.OK,
            name=self.status_name, message=status.message, hardware_id=self.hardware_id,
            values=[KeyValue(key=key, value=value) for key, value in status.values])


def main(args=None) -> int:
    """Run the FK node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(FkNode, 'fk_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
