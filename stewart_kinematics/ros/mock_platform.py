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
A simulated platform: leg commands in, the legs' joint states out; a stack without hardware.

Subscribes to the leg commands a driver takes (all, or the one ``command_input`` names):
``leg_lengths`` (std_msgs/msg/Float64MultiArray, metres, leg 1..6), ``joint_commands``
(sensor_msgs/msg/JointState, the joints ``joint_names``) and ``leg_trajectory``
(trajectory_msgs/msg/JointTrajectory, followed from its header stamp as
joint_trajectory_controller follows one). The newest command wins. Every
``1 / joint_state_rate`` s of the node's clock (simulated time too) the six simulated legs move
toward the command with a first-order lag (``time_constant``) within the stroke, velocity and
acceleration limits of the geometry's parameters, and ``joint_states``
(sensor_msgs/msg/JointState) is published: positions, velocities and, when the geometry carries
masses, the leg forces as efforts. Faults for tests, changeable at run time: ``stalled_legs``,
``position_noise`` (with ``noise_seed``) and ``position_bias``.

The simulation is :class:`stewart_kinematics.motion.mock_actuators.MockActuators`; the node
converts the messages, calls it, publishes, and counts each refused command with its reason
on the log and ``/diagnostics``.
"""

from diagnostic_msgs.msg import DiagnosticStatus, KeyValue
import numpy as np
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Header

from stewart_kinematics import findings
from stewart_kinematics.findings import Finding
from stewart_kinematics.motion.mock_actuators import (
    leg_selection,
    LegLimits,
    MockActuators,
    SimulatedForces,
    trajectory_command,
)
from stewart_kinematics.parameters import (
    actuator_interface_from_settings,
    actuator_limits_from_settings,
    geometry_from_settings,
    MockPlatformNodeSettings,
)
from stewart_kinematics.ros.interfaces import MOCK_PLATFORM
from stewart_kinematics.ros.managed import ManagedNode
from stewart_kinematics.ros.message_accounting import LogThrottle, NodeDiagnostics, WARNING_PERIOD
from stewart_kinematics.ros.message_conversions import (
    joint_state_message,
    leg_lengths_from_message,
    leg_trajectory_from_message,
    legs_from_joint_state,
)
from stewart_kinematics.ros.node_main import (
    create_input_subscription,
    create_output_publisher,
    run_node,
)
from stewart_kinematics.ros.ros_parameters import RunTimePayload
from trajectory_msgs.msg import JointTrajectory

#: The inputs mock_platform can take, as ``command_input`` names them.
COMMAND_INPUTS = ('leg_lengths', 'joint_commands', 'leg_trajectory')


def inputs_taken(command_input: str) -> tuple:
    """Return the command inputs the node subscribes to: the one command_input names, or all."""
    return COMMAND_INPUTS if command_input == 'all' else (command_input,)


def check_parameters(values) -> str:
    """Return ``''`` if the stalled legs name legs of ``joint_names``, else why not."""
    try:
        leg_selection(values['stalled_legs'], values['joint_names'])
    except ValueError as error:
        return str(error)
    return ''


class MockPlatform(ManagedNode):
    """
    Six simulated legs that follow the leg commands and publish their joint states.

    A managed node with ``managed: true`` (:class:`~stewart_kinematics.ros.managed.
    ManagedNode`): configure builds the legs at their initial lengths, deactivate stops them
    where they are (the simulated drives disabled), activate starts the simulation's clock
    again from the next tick.
    """

    SETTINGS = MockPlatformNodeSettings
    #: ``check(values) -> reason`` between parameters: the stalled legs' names.
    PARAMETERS_CHECK = staticmethod(check_parameters)

    def __init__(self, **kwargs):
        super().__init__('mock_platform', **kwargs)

    def run_time_payload(self):
        """Take a new payload at once: the efforts use it."""
        return RunTimePayload(lambda: self.geometry, self.set_mass_properties)

    def configure(self):
        """Check the parameters, build the simulated legs, the publisher and subscriptions."""
        settings = self.settings
        reason = check_parameters(settings.mock.as_values() | settings.actuators.as_values())
        if reason:
            raise ValueError(reason)
        self.geometry = geometry_from_settings(settings.geometry)
        self.actuators = actuator_interface_from_settings(settings.actuators)
        mock = settings.mock
        initial = np.array(mock.initial_leg_lengths)
        if not initial.any():
            initial = self.geometry.home_leg_lengths
        self.legs = MockActuators(
            LegLimits.of(self.geometry, actuator_limits_from_settings(settings.geometry)),
            initial, mock.time_constant, mock.max_time_step)
        self.apply_faults()
        self.forces = SimulatedForces(self.geometry)
        #: The node clock's time the simulation counts from, nanoseconds (the first read).
        self.epoch = None
        depth = settings.queue.queue_depth
        self.publisher = create_output_publisher(self, MOCK_PLATFORM['joint_states'], depth)
        diagnostics = NodeDiagnostics(self)
        self.log_throttle = LogThrottle(self.get_logger(), WARNING_PERIOD)
        self.report = LegsReport(self, diagnostics)
        diagnostics.reporters.append(self.report)
        callbacks = {'leg_lengths': self.on_leg_lengths, 'joint_commands': self.on_joint_commands,
                     'leg_trajectory': self.on_leg_trajectory}
        self.accounting = {}
        for name in inputs_taken(mock.command_input):
            self.accounting[name] = diagnostics.accounting(name)
            create_input_subscription(self, MOCK_PLATFORM[name], callbacks[name], depth)
        # After a jump back of the clock, rcl's timer ticks one period after it (rcl 9).
        self.create_timer(1.0 / mock.joint_state_rate, self.on_timer)
        self.get_logger().info(
            f'ready: legs at {np.round(self.legs.state.lengths, 6).tolist()} m, following '
            f'{mock.command_input} command(s) with a lag of {mock.time_constant:g} s')

    def activate(self):
        """Count the simulation's time from the next tick: no step across the inactive time."""
        self.legs.hold()

    def deactivate(self):
        """Stop the legs where they are, at rest: the simulated drives are disabled."""
        self.legs.hold()

    def apply_faults(self):
        """Hand the fault parameters (validated) to the simulated legs."""
        mock = self.settings.mock
        self.legs.set_stalled(leg_selection(mock.stalled_legs, self.actuators.joint_names))
        self.legs.set_noise(mock.position_noise, mock.noise_seed)
        self.legs.set_bias(mock.position_bias)

    def on_parameter_change(self, name, value):
        """Take a fault, the time constant or max_time_step (already validated) at once."""
        self.settings = self.settings.replace(**{name: value})
        if name == 'time_constant':
            self.legs.set_time_constant(value)
        elif name == 'max_time_step':
            self.legs.max_time_step = value
        elif name == 'stalled_legs':
            self.legs.set_stalled(leg_selection(value, self.actuators.joint_names))
        elif name in ('position_noise', 'noise_seed'):
            self.legs.set_noise(self.settings.mock.position_noise, self.settings.mock.noise_seed)
        elif name == 'position_bias':
            self.legs.set_bias(value)

    def set_mass_properties(self, geometry):
        """Take the geometry carrying a new payload: the efforts use it from now on."""
        self.geometry = geometry
        self.forces = SimulatedForces(geometry)

    def seconds(self, nanoseconds: int) -> float:
        """
        Return a time of the node's clock as the simulation counts it: seconds since its epoch.

        The epoch is the first time read: seconds since 1970 as a float resolve only 0.24 us,
        which would blur a step of 10 ms by 2e-5 of itself (and its acceleration with it).
        """
        if self.epoch is None:
            if nanoseconds == 0:   # a simulated clock not started: its zero
                return 0.0
            self.epoch = nanoseconds
        return (nanoseconds - self.epoch) * 1e-9

    def on_leg_lengths(self, message: Float64MultiArray):
        """Follow six leg lengths, or refuse them with the reason."""
        accounting = self.accounting['leg_lengths']
        accounting.receive()
        try:
            lengths = leg_lengths_from_message(message)
        except ValueError as error:
            accounting.reject(Finding(findings.INVALID_LEG_COMMAND, str(error)))
            return
        self.set_point(lengths, accounting)

    def on_joint_commands(self, message: JointState):
        """Follow the positions of the legs' joints, or refuse them with the reason."""
        accounting = self.accounting['joint_commands']
        accounting.receive()
        try:
            lengths, _ = legs_from_joint_state(message, self.actuators)
        except ValueError as error:
            accounting.reject(Finding(findings.INVALID_LEG_COMMAND, str(error)))
            return
        self.set_point(lengths, accounting)

    def set_point(self, lengths, accounting):
        """Hand the legs a set point; count it used or refused."""
        refusal = self.legs.command_lengths(lengths)
        if refusal is not None:
            accounting.reject(refusal)
            return
        accounting.use()

    def on_leg_trajectory(self, message: JointTrajectory):
        """Follow a leg trajectory from its start (stamp 0: now), or refuse it with the reason."""
        accounting = self.accounting['leg_trajectory']
        accounting.receive()
        try:
            arguments = leg_trajectory_from_message(message, self.actuators)
        except ValueError as error:
            accounting.reject(Finding(findings.INVALID_LEG_COMMAND, str(error)))
            return
        stamp = arguments.pop('start')
        now = self.seconds(self.get_clock().now().nanoseconds)
        start = now if stamp == 0 else self.seconds(stamp)
        command, refusal = trajectory_command(start, **arguments, limits=self.legs.limits,
                                              now=now)
        if refusal is not None:
            accounting.reject(refusal)
            return
        self.legs.command_trajectory(command)
        accounting.use()

    def on_timer(self):
        """Advance the legs to the node's clock and publish their joint states."""
        stamp = self.get_clock().now()
        if stamp.nanoseconds == 0:   # a simulated clock not started yet
            return
        warning = self.legs.advance(self.seconds(stamp.nanoseconds))
        if warning is not None:
            self.report.clock_jump(warning)
            self.log_throttle.log(warning.code, warning.message)
        state = self.legs.state
        efforts = None
        if not self.forces.massless:
            efforts, problem = self.forces.forces(state, self.legs.last_step)
            self.report.forces_problem = problem or ''
            if problem:
                self.log_throttle.log('efforts', f'joint_states without efforts: {problem}')
        self.publisher.publish(joint_state_message(
            Header(stamp=stamp.to_msg()), self.legs.measure(), state.velocities,
            self.actuators, efforts))


class LegsReport:
    """
    The simulated legs as a diagnostic status: where they are, the faults set, clock jumps.

    WARN while a fault is set or after a clock jump since the last report.

    :param node: the mock_platform node.
    :param diagnostics: its :class:`NodeDiagnostics`.
    """

    def __init__(self, node: MockPlatform, diagnostics: NodeDiagnostics):
        self.node = node
        self.status_name = f'{node.get_fully_qualified_name()}: legs'
        self.hardware_id = diagnostics.hardware_id
        self.clock_jumps = 0
        self.last_clock_jump = None
        self.forces_problem = ''
        self._reported_jumps = 0

    def clock_jump(self, warning: Finding):
        """Count a clock jump."""
        self.clock_jumps += 1
        self.last_clock_jump = warning

    def report(self) -> DiagnosticStatus:
        """Return the legs' status since the last report."""
        legs = self.node.legs
        stalled = [self.node.actuators.joint_names[leg] for leg in np.flatnonzero(legs.stalled)]
        faults = []
        if stalled:
            faults.append('stalled ' + ', '.join(stalled))
        if legs.noise > 0.0:
            faults.append(f'position noise {legs.noise:g} m')
        if legs.bias.any():
            faults.append(f'position bias {legs.bias.tolist()} m')
        jumps = self.clock_jumps - self._reported_jumps
        self._reported_jumps = self.clock_jumps
        if jumps:
            faults.append(f'{jumps} clock jump(s): {self.last_clock_jump.message}')
        values = [('lengths', str(np.round(legs.state.lengths, 6).tolist())),
                  ('velocities', str(np.round(legs.state.velocities, 6).tolist())),
                  ('stalled_legs', ', '.join(stalled)), ('position_noise', f'{legs.noise:g}'),
                  ('position_bias', str(legs.bias.tolist())),
                  (f'warned {findings.CLOCK_JUMP}', str(self.clock_jumps))]
        if self.forces_problem:
            values.append(('efforts', self.forces_problem))
        return DiagnosticStatus(
            level=DiagnosticStatus.WARN if faults else DiagnosticStatus.OK,
            name=self.status_name, message='; '.join(faults) or 'simulating',
            hardware_id=self.hardware_id,
            values=[KeyValue(key=key, value=value) for key, value in values])


def main(args=None) -> int:
    """Run mock_platform until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(MockPlatform, 'mock_platform', args)


if __name__ == '__main__':
    raise SystemExit(main())
