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
Motion cueing node: a vehicle's IMU in, the platform pose a person should feel out.

Subscribes ``vehicle_imu`` (sensor_msgs/msg/Imu: the specific force in ``linear_acceleration``,
9.81 m/s^2 on z at rest, and ``angular_velocity``, at the driver's head, vehicle frame x
forward, y left, z up; the orientation is not used). For each message it publishes
``target_pose`` (geometry_msgs/msg/Pose, the tool frame in the base frame, for ik_node),
``cue_pose`` (geometry_msgs/msg/PoseStamped, the platform frame in ``base_frame`` with the
message's stamp, for VR motion compensation and RViz) and ``perceived_accel``
(geometry_msgs/msg/AccelStamped, the specific force felt at ``head_position`` one message
behind, with that message's stamp). The ``reset`` service (std_srvs/srv/Trigger) washes out to
neutral. Declared once in :data:`stewart_kinematics.ros.interfaces.MOTION_CUEING_NODE`.

Everything is decided by :class:`stewart_kinematics.cueing.MotionCueing`: the washout's time
step is the difference of the stamps, the platform's the time between two commands on the
node's clock (wall or simulated), so a recording played fast never drives the legs faster than
their limits; a message in a frame that cannot be placed in ``vehicle_frame`` (``imu_frame``
turned by ``imu_orientation_rpy_deg`` can) or with a non-finite or absurd value is refused with
its reason and the platform takes the step at rest (bad input eases it back to neutral); a
stamp that does not move forward is refused and nothing is published. Every ``target_pose``
is the command gate's verdict on its very numbers (every pose limit and the leg velocity and
acceleration since the last command); one it refuses is replaced by a braking command
(``command_braking``). When no message came for ``input_timeout`` seconds, the platform eases
home on the node's clock until it rests (:meth:`stewart_kinematics.cueing.MotionCueing.watch`,
called on a timer; ``target_pose`` and ``cue_pose`` stamped now; no ``perceived_accel`` then).
Refusals and warnings are counted on ``/diagnostics``.

With ``cueing_method: mpc``, ``vehicle_preview`` (trajectory_msgs/msg/MultiDOFJointTrajectory)
tells the MPC the vehicle's motion to come, on the clock of ``vehicle_imu``'s stamps (per
point: ``time_from_start`` after ``header.stamp``, the specific force in
``accelerations[0].linear``, the angular velocity in ``velocities[0].angular``); each message
replaces the last (:meth:`stewart_kinematics.cueing.MotionCueing.set_preview`). One that cannot
be used is refused with its reason (``invalid_preview``), and the preview before it stays.

Run-time controls (doc/motion_cueing.md, "The node at run time"): ``cueing_intensity`` and the
gains ``translation_scale``, ``tilt_scale``, ``rotation_scale`` may be set at run time
(``ros2 param set``, the parameter services): the change is ramped over ``gain_ramp_time``, or
refused with the reason (the value, the cue it would give and the travel) where the cue of the
reference input would leave the platform's travel. The ``start``, ``stop``, ``pause`` and
``resume`` services (std_srvs/srv/Trigger) move the platform up from park, down to park, hold
it and go on; their motions are stepped on the node's clock by a timer
(:meth:`stewart_kinematics.cueing.MotionCueing.operate`), and while the platform is not cueing
the samples are counted as ``cueing_held`` and not cued. ``start_parked`` starts the node at
park, waiting for ``start``. Managed (``managed: true``), the node is configured at park, its
activate transition starts as ``start`` does (answering at once; the timer steps the motion),
and its deactivate stops as ``stop`` does, answering once the platform is parked (the commands
published while the node is still active).

Parameters are declared as for the other nodes (a bad parameter file or a misspelt name stops
the start with the reason). Every one is read-only but the tool frame's (``tool_frame``,
``tool_frame_position``, ``tool_frame_orientation_deg``), which applies from the next command
on, the gains and intensity above, and ``gain_ramp_time``, ``soft_start_time`` and
``soft_stop_time`` (from the next ramp, start or stop).
"""

import math
import time

from geometry_msgs.msg import AccelStamped, PoseStamped
from rclpy.time import Time
from sensor_msgs.msg import Imu
from std_msgs.msg import Header

from stewart_kinematics.cueing import MotionCueing
from stewart_kinematics.cueing.motion_cueing import PARKED, WATCHDOG_PERIOD
from stewart_kinematics.findings import Finding, INVALID_PREVIEW, TIME_NOT_INCREASING
from stewart_kinematics.parameters import (
    frame_parameters_reason,
    frames_from_settings,
    MotionCueingNodeSettings,
)
from stewart_kinematics.ros.command_publishing import send_command
from stewart_kinematics.ros.interfaces import MOTION_CUEING_NODE
from stewart_kinematics.ros.managed import ManagedNode
from stewart_kinematics.ros.message_accounting import NodeDiagnostics
from stewart_kinematics.ros.message_conversions import (
    command_pose_message,
    malformed_time_reason,
    pose_to_message,
    vehicle_preview_from_message,
)
from stewart_kinematics.ros.node_main import (
    create_declared_service,
    create_input_subscription,
    create_output_publisher,
    run_node,
)
from stewart_kinematics.ros.ros_parameters import RunTimePayload
from trajectory_msgs.msg import MultiDOFJointTrajectory

#: Longest the deactivate transition waits for park beyond ``soft_stop_time``, seconds (a
#: bound: braking takes a fraction of a second, a stop the limits slow a few more).
MAX_STOP_SECONDS = 120.0
#: The parameters that set the cue's gains at run time (ramped, checked against the travel).
GAIN_PARAMETERS = ('cueing_intensity', 'translation_scale', 'tilt_scale', 'rotation_scale')
#: The control times, taken from the next ramp, start or stop.
CONTROL_TIMES = ('gain_ramp_time', 'soft_start_time', 'soft_stop_time')


class MotionCueingNode(ManagedNode):
    """Turn every vehicle IMU message into a platform pose within the limits."""

    SETTINGS = MotionCueingNodeSettings

    def __init__(self, **kwargs):
        super().__init__('motion_cueing_node', **kwargs)

    def run_time_payload(self):
        """Take a new payload only at rest at home."""
        return RunTimePayload(
            lambda: self.cueing.geometry, self.set_mass_properties, lambda: '' if (
                self.cueing.settled()) else 'motion_cueing_node takes a new payload only '
            'at rest at home: call reset, wait until the platform is home, then set it')

    def configure(self):
        """Build the motion cueing, every publisher, subscription, service and timer."""
        # Managed: configured at park, where deactivate leaves the platform; activate starts.
        self.cueing = self.make_cueing(parked=self.managed or None)
        depth = self.settings.queue.queue_depth
        interface = MOTION_CUEING_NODE
        self.target_publisher = create_output_publisher(
            self, interface['target_pose'], depth, command_pose_message)
        self.cue_publisher = create_output_publisher(self, interface['cue_pose'], depth)
        self.perceived_publisher = create_output_publisher(
            self, interface['perceived_accel'], depth)
        diagnostics = NodeDiagnostics(self)
        self.accounting = diagnostics.accounting('vehicle_imu')
        self.preview_accounting = diagnostics.accounting('vehicle_preview')
        create_input_subscription(self, interface['vehicle_imu'], self.on_imu, depth)
        create_input_subscription(self, interface['vehicle_preview'], self.on_preview, depth)
        create_declared_service(self, interface['reset'], self.on_reset)
        for name in ('start', 'stop', 'pause', 'resume'):
            create_declared_service(self, interface[name], self.control_service(name))
        #: The first stamp, nanoseconds: times are kept relative to it (float precision).
        self.origin_ns = None
        #: The node clock's origin, nanoseconds: the commands' times are seconds since it.
        self.clock_origin_ns = self.get_clock().now().nanoseconds
        # The watchdog's timer also steps start, stop and pause (operate).
        self.create_timer(self.cueing.watchdog_period or WATCHDOG_PERIOD, self.on_watchdog)
        self.get_logger().info(
            f'ready: cueing vehicle_imu into target_pose (head at '
            f'{list(self.cueing.settings.head_position)} m, tilt rate at most '
            f'{self.settings.cueing.tilt_rate_max_deg:g} deg/s)')

    def activate(self):
        """
        Start from park, as the ``start`` service does, when managed (unmanaged: nothing).

        The platform was configured at park (or parked by the last deactivate): the soft
        start to neutral over ``soft_start_time`` is stepped by the timer from now on, and
        cueing begins once it rests at neutral (samples meanwhile: ``cueing_held``). The
        transition answers at once.
        """
        if not self.managed:
            return
        answer = self.cueing.start()
        log = self.get_logger().info if answer.success else self.get_logger().warning
        log(f'activate: {answer.message}')

    def deactivate(self):
        """
        Stop to park, as the ``stop`` service does, and answer once the platform is parked.

        From any mode (cueing or paused: braked to rest first; starting: turned back to park
        from where it is; parked: nothing to do), one command a watchdog period through the
        command gate (leg velocity and acceleration within the limits), published while the
        node is still active: the deactivate transition answers once the legs rest at park
        (``soft_stop_time`` or longer when the limits need, at most :data:`MAX_STOP_SECONDS`
        more). The next activate starts from park.
        """
        cueing = self.cueing
        answer = cueing.stop()
        period = WATCHDOG_PERIOD
        moment = self.command_time(self.get_clock().now())
        if cueing.gate.last_time is not None:
            moment = max(moment, cueing.gate.last_time)
        sent = 0
        steps = math.ceil((cueing.controls.soft_stop_time + MAX_STOP_SECONDS) / period)
        for _ in range(steps if answer.success else 0):
            if cueing.mode == PARKED:
                break
            moment += period
            result = cueing.operate(moment)
            if result is not None:
                self.target_publisher.publish(result.command)
                # Stamped with the command's time, as the gate checked it: a simulated clock
                # stands still during the transition.
                self.publish_extras(result, Time(
                    nanoseconds=self.clock_origin_ns + round(moment * 1e9),
                    clock_type=self.get_clock().clock_type).to_msg(), perceived=False)
                sent += 1
            time.sleep(period)
        if cueing.mode == PARKED:
            self.get_logger().info(f'deactivated: stopped to park in {sent} commands')
        else:
            self.get_logger().error(
                f'deactivate: the platform did not reach park ({cueing.mode} after {sent} '
                f'commands: {answer.message}); it goes on stopping once active again')

    def parameters_check(self, values) -> str:
        """
        Return ``''`` if the values after a change may be set, else why not.

        The frames' rules, then (configured) a change of intensity or gains: refused where the
        cue of the reference input would leave the travel (the core's ``gain_refusal``).
        """
        reason = frame_parameters_reason(values)
        if reason or not self.configured or getattr(self, 'cueing', None) is None:
            return reason
        cueing = self.cueing
        now = {'cueing_intensity': cueing.controls.cueing_intensity,
               'translation_scale': cueing.settings.translation_scale,
               'tilt_scale': cueing.settings.tilt_scale,
               'rotation_scale': cueing.settings.rotation_scale}
        changed = {name: values[name] for name in GAIN_PARAMETERS if name in values
                   and _differs(values[name], now[name])}
        if not changed:
            return ''
        refusal = cueing.gain_refusal(
            intensity=changed.get('cueing_intensity'),
            translation_scale=changed.get('translation_scale'),
            tilt_scale=changed.get('tilt_scale'), rotation_scale=changed.get('rotation_scale'))
        return refusal.message if refusal is not None else ''

    def on_parameter_change(self, name, value):
        """Take a validated run-time change: tool frame, gains (ramped), control times."""
        self.settings = self.settings.replace(**{name: value})
        if name.startswith('tool_frame'):
            self.cueing.set_frames(frames_from_settings(self.settings.frames))
        elif name in GAIN_PARAMETERS:
            # Every gain as now set (a request setting several is checked as a whole).
            cueing, controls = self.settings.cueing, self.settings.controls
            refusal = self.cueing.set_gains(
                controls.cueing_intensity, cueing.translation_scale, cueing.tilt_scale,
                cueing.rotation_scale, check_travel=False)
            if refusal is not None:   # checked before the set: not expected
                self.get_logger().error(f'{name} not taken: {refusal.message}')
            else:
                # rclpy gives an array parameter as array('d', [...]): say it as a list.
                shown = value if isinstance(value, float) else [float(v) for v in value]
                self.get_logger().info(
                    f'{name} set to {shown}: ramping over '
                    f'{self.cueing.controls.gain_ramp_time:g} s')
        elif name in CONTROL_TIMES:
            self.cueing.controls = self.cueing.controls.replace(**{name: value})

    def set_mass_properties(self, geometry):
        """Cue with a new payload (the platform rests at home): a new cueing of the settings."""
        self.cueing = self.make_cueing(parked=self.cueing.mode == PARKED)

    def make_cueing(self, parked=None) -> MotionCueing:
        """
        Return the motion cueing of the settings.

        :param parked: whether the platform starts at park; ``None``: as ``start_parked``.
        """
        values = self.settings.as_values()
        if parked is not None:
            values['start_parked'] = bool(parked)
        return MotionCueing.from_parameters(values, frames_from_settings(self.settings.frames))

    def control_service(self, name):
        """Return the callback of the ``start``, ``stop``, ``pause`` or ``resume`` service."""
        def answer(request, response):
            result = getattr(self.cueing, name)()
            response.success, response.message = result.success, result.message
            self.get_logger().info(f'{name}: {result.message}')
            return response
        return answer

    def on_imu(self, message: Imu):
        """
        Cue one sample; publish the pose (also for a refused value: it eases home).

        A sample refused for its time is no input: refused for ``input_timeout``, the
        platform eases home (:meth:`on_watchdog`), and the next sample starts a new time line.
        """
        self.accounting.receive()
        stamp = message.header.stamp
        malformed = malformed_time_reason(stamp, 'header.stamp')
        if malformed:   # no time at all: no input, as a backward stamp
            self.accounting.reject(Finding(TIME_NOT_INCREASING, f'{malformed}; sample ignored'))
            return
        stamp_ns = self.stamp_ns(stamp)
        force, rate = message.linear_acceleration, message.angular_velocity
        result = self.cueing.cue((stamp_ns - self.origin_ns) * 1e-9,
                                 (force.x, force.y, force.z), (rate.x, rate.y, rate.z),
                                 self.command_time(self.get_clock().now()),
                                 message.header.frame_id)
        if result.command is None:   # a refused time, or not cueing: nothing moved
            if result.refusal is not None:
                self.accounting.reject(result.refusal)
            else:
                # Held (parked, starting, stopping, paused): its time is kept, nothing cued;
                # it ends counted as used, as every message ends as an output or a refusal.
                self.accounting.use()
            for finding in result.warnings:
                self.accounting.warn(finding)
            return
        if result.refusal is not None:
            # The sample is refused; the step taken at rest (easing home) is still sent.
            self.accounting.reject(result.refusal)
            for finding in result.warnings:
                self.accounting.warn(finding)
            if result.command.accepted:
                self.target_publisher.publish(result.command)
        else:
            for finding in result.warnings:
                if finding not in result.command.warnings:
                    self.accounting.warn(finding)
            send_command(self.target_publisher, self.accounting, result.command)
        if result.pose is not None:
            self.publish_extras(result, stamp)

    def stamp_ns(self, stamp) -> int:
        """Return a stamp in nanoseconds; the first stamp seen is the origin of the times."""
        stamp_ns = stamp.sec * 1_000_000_000 + stamp.nanosec
        if self.origin_ns is None:
            self.origin_ns = stamp_ns
        return stamp_ns

    def on_preview(self, message: MultiDOFJointTrajectory):
        """Take the vehicle's motion to come (cueing_method mpc), or refuse it saying why."""
        self.preview_accounting.receive()
        try:
            # Checked first: a malformed stamp must not become the origin of the times.
            offsets, forces, rates, frame_id = vehicle_preview_from_message(message)
            start = (self.stamp_ns(message.header.stamp) - self.origin_ns) * 1e-9
            self.cueing.set_preview(start + offsets, forces, rates, frame_id)
        except ValueError as error:
            self.preview_accounting.reject(Finding(INVALID_PREVIEW, str(error)))
            return
        self.preview_accounting.use()

    def command_time(self, now) -> float:
        """Return the seconds of the node's clock ``now`` since its origin: a command's time."""
        return (now.nanoseconds - self.clock_origin_ns) * 1e-9

    def publish_extras(self, result, stamp, perceived=True):
        """Publish cue_pose and (``perceived``) perceived_accel, each only to a subscriber."""
        base_frame = self.settings.frames.base_frame
        if self.cue_publisher.get_subscription_count():
            self.cue_publisher.publish(PoseStamped(
                header=Header(stamp=stamp, frame_id=base_frame),
                pose=pose_to_message(result.pose)))
        if (perceived and result.perceived is not None
                and self.perceived_publisher.get_subscription_count()):
            time, force = result.perceived
            message = AccelStamped()
            message.header.frame_id = self.settings.frames.platform_frame
            if isinstance(time, float) and self.origin_ns is not None:
                nanoseconds = self.origin_ns + round(time * 1e9)
                message.header.stamp.sec, message.header.stamp.nanosec = divmod(
                    nanoseconds, 1_000_000_000)
            else:
                message.header.stamp = stamp
            linear = message.accel.linear
            linear.x, linear.y, linear.z = (float(value) for value in force)
            self.perceived_publisher.publish(message)

    def on_reset(self, request, response):
        """Wash out to neutral from the next sample (or on the watchdog without input)."""
        self.cueing.reset()
        response.success = True
        response.message = ('washing out to neutral: the washout restarts from the next '
                            'sample, the platform glides home within the actuator limits')
        return response

    def on_watchdog(self):
        """
        Step a start, stop or pause; else, without input, ease the platform home.

        The core's ``operate``, else ``watch`` (no input for input_timeout: until it rests).
        """
        now = self.get_clock().now()
        result = self.cueing.operate(self.command_time(now))
        if result is None and self.cueing.watchdog_period is not None:
            result = self.cueing.watch(self.command_time(now))
        if result is None:
            return
        self.target_publisher.publish(result.command)
        # No sample to stamp the felt force with: only the pose, stamped now.
        self.publish_extras(result, now.to_msg(), perceived=False)


def _differs(value, now) -> bool:
    """Whether a parameter value (a number or a list) differs from the cueing's (a tuple)."""
    if isinstance(now, tuple):
        return [float(entry) for entry in value] != list(now)
    return float(value) != now


def main(args=None) -> int:
    """Run the motion cueing node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(MotionCueingNode, 'motion_cueing_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
