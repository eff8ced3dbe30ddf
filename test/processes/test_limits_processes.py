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
Every actuator output within every limit, across real processes.

ik_node and trajectory_node run as console-script processes with the shipped parameter files
(the paper's platform and config/example_limits.yaml: legs 0.65 to 0.90 m, 0.05 m/s,
0.25 m/s^2, 2.5 m/s^3); the test's own node publishes on their topics and reads what comes
out, and /diagnostics for why not. Checked here: a twist beyond the leg velocity limit never
gives leg velocities beyond it (and 1e308 or NaN gives a refusal); streamed commands survive
far, huge and non-finite targets, every step within the velocity, acceleration and jerk limits
(from the published positions and velocities) and the stroke; a pose where two legs collide is
refused by ik_node, in a trajectory and by the ramp's pre-check, with the two legs named.
"""

import math
import subprocess

from geometry_msgs.msg import Pose, Twist
from helpers import pose_message, raw_pose_message, Recorder, stop_cleanly, trajectory_message
import numpy as np
import pytest
import reference
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray
from trajectory_msgs.msg import MultiDOFJointTrajectory

pytestmark = pytest.mark.process

#: Seconds a node that cannot start has to exit.
DEADLINE = 20.0
VELOCITY_MAX, ACCELERATION_MAX, JERK_MAX = 0.05, 0.25, 2.5
TABLE_3 = np.array(reference.TABLE_3)
HOME, TABLE_3_END = TABLE_3[0], TABLE_3[-1]
#: Legs of 50 mm: legs 2 and 3 collide at the end of Table 3 (axes 47.3 mm apart), nothing
#: else of the example limits is broken there.
THICK_LEGS = ['-p', 'leg_radius:=0.025']


def arguments(config_directory, *extra, limits=True):
    """ROS arguments: the paper's platform, the example limits (or none), then ``extra``."""
    files = ['paper_platform.yaml'] + (['example_limits.yaml'] if limits else [])
    result = ['--ros-args']
    for name in files:
        result += ['--params-file', str(config_directory / name)]
    return result + list(extra)


def twist_message(values):
    """geometry_msgs/msg/Twist of ``[vx, vy, vz, wx, wy, wz]``, any floats."""
    message = Twist()
    (message.linear.x, message.linear.y, message.linear.z, message.angular.x,
     message.angular.y, message.angular.z) = (float(value) for value in values)
    return message


class Client(Recorder):
    """helpers' Recorder, with /diagnostics counters by key."""

    def publish(self, topic, message):
        """Publish one message on ``topic``."""
        self.publishers[topic].publish(message)

    def counted(self, status_name, key, count=1):
        """Wait for a /diagnostics status ``status_name`` whose ``key`` counts ``count``."""
        def found():
            return [status for status in self.statuses if status.name == status_name and any(
                value.key == key and int(value.value) >= count for value in status.values)]
        self.client.wait(found, f'{key} >= {count} in {status_name} on /diagnostics',
                         self.nodes)
        return {value.key: value.value for value in found()[-1].values}


def test_a_twist_beyond_the_velocity_limit_never_gives_leg_velocities_beyond_it(
        client, start_node, config_directory):
    """
    Two ik_nodes at the same pose: /refuse (the default) and /scale (twist_over_limit scale).

    1 m/s (twenty times too fast): /refuse publishes nothing (too_fast); /scale publishes it
    scaled, its fastest leg at exactly 0.05 m/s. 1e308 and NaN: refused by both
    (invalid_twist). A slow twist: published by both, unchanged. Both keep running.
    """
    nodes = {name: start_node('ik_node', arguments(
        config_directory, '-r', f'__ns:=/{name}', *extra))
        for name, extra in (('refuse', ()), ('scale', ('-p', "twist_over_limit:='scale'")))}
    topics = Client(client, list(nodes.values()))
    for name in nodes:
        topics.advertise(Pose, f'/{name}/target_pose')
        topics.advertise(Twist, f'/{name}/target_twist')
        topics.subscribe(Float64MultiArray, f'/{name}/leg_lengths')
        topics.subscribe(Float64MultiArray, f'/{name}/leg_velocities')
    topics.connect()
    pose = TABLE_3[3]
    twists = [(1.0, 0.0, 0.0, 0.0, 0.0, 0.0), (1e308, 0.0, 0.0, 0.0, 0.0, 0.0),
              (math.nan, 0.0, 0.0, 0.0, 0.0, 0.0), (0.001, 0.0, 0.0, 0.0, 0.0, 0.002)]
    for name in nodes:
        topics.publish(f'/{name}/target_pose', pose_message(pose))
        topics.wait_for(f'/{name}/leg_lengths', 1)
        for twist in twists:
            topics.publish(f'/{name}/target_twist', twist_message(twist))
    topics.wait_for('/refuse/leg_velocities', 1)
    topics.wait_for('/scale/leg_velocities', 2)
    refused = topics.counted('/refuse/ik_node: target_twist', 'rejected', 3)
    assert (refused['rejected too_fast'], refused['rejected invalid_twist']) == ('1', '2')
    assert refused['published'] == '1'
    scaled = topics.counted('/scale/ik_node: target_twist', 'rejected', 2)
    assert scaled['rejected invalid_twist'] == '2' and scaled['warned twist_scaled'] == '1'
    jacobian = reference.twist_jacobian(pose)
    slow = jacobian @ np.array(twists[3])
    np.testing.assert_allclose(topics.received['/refuse/leg_velocities'][0].data, slow,
                               rtol=0.0, atol=1e-15)
    fast, again = (np.array(message.data) for message in topics.received['/scale/leg_velocities'])
    assert np.max(np.abs(fast)) <= VELOCITY_MAX
    assert np.max(np.abs(fast)) == pytest.approx(VELOCITY_MAX, rel=1e-12)
    unscaled = jacobian @ np.array(twists[0])
    np.testing.assert_allclose(fast, unscaled * VELOCITY_MAX / np.max(np.abs(unscaled)),
                               rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(again, slow, rtol=0.0, atol=1e-15)
    for message in topics.received['/refuse/leg_velocities'] + topics.received[
            '/scale/leg_velocities']:
        assert np.all(np.isfinite(message.data))
        assert np.max(np.abs(message.data)) <= VELOCITY_MAX
    for process in nodes.values():
        stop_cleanly(process)


def stamp_times(messages):
    """Return the seconds of the messages' header stamps since the first (digits kept)."""
    nanoseconds = np.array([m.header.stamp.sec * 1_000_000_000 + m.header.stamp.nanosec
                            for m in messages])
    return (nanoseconds - nanoseconds[0]) * 1e-9


def assert_steps_within_the_limits(messages, period, stroke=None):
    """
    Every published step: velocity, and position, velocity and acceleration differences.

    The steps are judged in the time they were sent, their stamps: each covers the time since
    the last on the node's clock (a timer fires a little late or early), ``period`` on average.
    """
    positions = np.array([message.position for message in messages])
    velocities = np.array([message.velocity for message in messages])
    steps = np.diff(stamp_times(messages))
    assert np.all(np.isfinite(positions)) and np.all(np.isfinite(velocities))
    assert np.all(steps > 0.0) and np.median(steps) == pytest.approx(period, rel=0.2)
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    assert (np.abs(np.diff(positions, axis=0)) / steps[:, None]).max() <= (
        VELOCITY_MAX * (1 + 1e-9))
    # The change of velocity over a step is the mean acceleration over it; the change of
    # those over a step a mean of the jerk.
    accelerations = np.diff(velocities, axis=0) / steps[:, None]
    assert np.abs(accelerations).max() <= ACCELERATION_MAX * (1 + 1e-9)
    jerks = np.diff(accelerations, axis=0) / (0.5 * (steps[1:] + steps[:-1]))[:, None]
    assert np.abs(jerks).max() <= 2.0 * JERK_MAX
    if stroke is not None:
        assert stroke[0] <= positions.min() and positions.max() <= stroke[1]


def test_streamed_commands_survive_far_huge_and_non_finite_targets(
        client, start_node, config_directory):
    """
    The defect: a far target with command_rate set made ruckig fail and ik_node exit.

    /free (the speed limits, no stroke) is sent targets 1 km, then 1e150 m away: it keeps
    streaming at 0.05 m/s toward each. NaN, inf and an overflowing pose are refused. /bound
    (every example limit) refuses the far targets and streams within the stroke. Every
    published step of both is within the velocity, acceleration and jerk limits.
    """
    rate = 100.0
    speeds = ['-p', f'leg_velocity_max:={VELOCITY_MAX}', '-p',
              f'leg_acceleration_max:={ACCELERATION_MAX}', '-p', f'leg_jerk_max:={JERK_MAX}']
    nodes = {
        'free': start_node('ik_node', arguments(config_directory, '-r', '__ns:=/free',
                                                '-p', f'command_rate:={rate}', *speeds,
                                                limits=False)),
        'bound': start_node('ik_node', arguments(config_directory, '-r', '__ns:=/bound',
                                                 '-p', f'command_rate:={rate}')),
    }
    topics = Client(client, list(nodes.values()))
    for name in nodes:
        topics.advertise(Pose, f'/{name}/target_pose')
        topics.subscribe(JointState, f'/{name}/joint_commands')
    topics.connect()
    targets = [pose_message(TABLE_3[2])] + [raw_pose_message(*numbers) for numbers in [
        [(1000.0, 0.0, 0.4325)], [(math.nan, 0.0, 0.4325)], [(0.0, math.inf, 0.4325)],
        [(1e200, 0.0, 0.4325)], [(0.0, 0.0, 0.4325), (0, 0, 0, math.nan)],
        [(1e150, 1e150, 0.4325)]]]
    for target in targets:
        for name in nodes:
            topics.publish(f'/{name}/target_pose', target)
        count = len(topics.received['/free/joint_commands'])
        topics.wait_for('/free/joint_commands', count + 30)
    topics.wait_for('/free/joint_commands', len(topics.received['/free/joint_commands']) + 100)
    free = topics.counted('/free/ik_node: target_pose', 'rejected', 4)
    assert (free['published'], free['rejected invalid_pose'], free['rejected unreachable']) == (
        '3', '3', '1')
    bound = topics.counted('/bound/ik_node: target_pose', 'rejected', 6)
    assert bound['published'] == '1' and bound['rejected out_of_limits'] == '2'
    stream = topics.counted('/free/ik_node: command_stream', 'published', 100)
    assert stream['rejected'] == '0'
    assert_steps_within_the_limits(topics.received['/free/joint_commands'], 1.0 / rate)
    assert_steps_within_the_limits(topics.received['/bound/joint_commands'], 1.0 / rate,
                                   stroke=(0.65, 0.90))
    # Toward 1e150 m the legs run at full speed, all in proportion to their distances.
    last = np.array(topics.received['/free/joint_commands'][-1].velocity)
    assert np.max(np.abs(last)) == pytest.approx(VELOCITY_MAX, rel=1e-9)
    for process in nodes.values():
        stop_cleanly(process)


def test_a_pose_where_two_legs_collide_is_refused_everywhere_naming_them(
        client, start_node, config_directory):
    """
    Legs of 50 mm: the end of Table 3 puts the axes of legs 2 and 3 47.3 mm apart.

    ik_node refuses that pose (the legs named on /diagnostics) and accepts home; a trajectory
    from home to it is refused by trajectory_node, naming the legs; and trajectory_node asked
    to play the Table 3 ramp refuses to start, listing the samples where they collide.
    """
    ik = start_node('ik_node', arguments(config_directory, *THICK_LEGS))
    planner = start_node('trajectory_node', arguments(config_directory, *THICK_LEGS,
                                                      '-p', "mode:='off'"))
    topics = Client(client, [ik, planner])
    topics.advertise(Pose, 'target_pose')
    topics.advertise(MultiDOFJointTrajectory, 'pose_trajectory')
    topics.subscribe(Float64MultiArray, 'leg_lengths')
    topics.connect()
    topics.publish('target_pose', pose_message(TABLE_3_END))
    topics.publish('target_pose', pose_message(HOME))
    topics.wait_for('leg_lengths', 1)
    status = topics.counted('/ik_node: target_pose', 'rejected out_of_limits')
    assert status['last rejection'].startswith('the pose is out of the limits: legs 2 and 3: '
                                               'leg_collision, clearance -0.0027')
    assert 'leg_collision legs 2 and 3' in status
    np.testing.assert_allclose(topics.received['leg_lengths'][0].data,
                               reference.leg_lengths(HOME), rtol=0.0, atol=1e-12)
    assert len(topics.received['leg_lengths']) == 1

    topics.publish('pose_trajectory', trajectory_message([0.0, 10.0], [HOME, TABLE_3_END]))
    status = topics.counted('/trajectory_node: pose_trajectory', 'rejected out_of_limits')
    assert 'legs 2 and 3: leg_collision' in status['last rejection']
    assert 'between points 0 and 1' in status['last rejection']
    stop_cleanly(ik)
    stop_cleanly(planner)

    ramp = start_node('trajectory_node', arguments(
        config_directory, '--params-file', str(config_directory / 'table3_ramp.yaml'),
        *THICK_LEGS))
    try:
        code = ramp.process.wait(DEADLINE)
    except subprocess.TimeoutExpired:
        code = None
    output = ramp.output()
    assert code == 1, output
    assert 'cannot start: ramp refused: 4 of 11 samples break the limits' in output
    assert output.count('legs 2 and 3: leg_collision') == 4 and 'Traceback' not in output


#: The example masses (28 kg on the platform, legs of 2 kg) and a push of at most 60 N a leg:
#: home needs at most 52.4 N a leg, this tilted pose 65.8, 82.8 and 69.7 N on legs 3, 4 and 6
#: (and keeps every other example limit).
HEAVY = ['--params-file', 'example_masses.yaml', '-p', 'leg_force_max:=60.0']
HEAVY_POSE = np.array([0.02, -0.01, 0.44, 0.08, -0.05, 0.1])


def test_a_pose_whose_static_forces_break_leg_force_max_is_refused_naming_the_legs(
        client, start_node, config_directory):
    """ik_node refuses the tilted pose naming leg_force_max and legs 3, 4 and 6; home passes."""
    extra = list(HEAVY)
    extra[1] = str(config_directory / extra[1])
    ik = start_node('ik_node', arguments(config_directory, *extra))
    topics = Client(client, [ik])
    topics.advertise(Pose, 'target_pose')
    topics.subscribe(Float64MultiArray, 'leg_lengths')
    topics.connect()
    topics.publish('target_pose', pose_message(HEAVY_POSE))
    topics.publish('target_pose', pose_message(HOME))
    topics.wait_for('leg_lengths', 1)
    status = topics.counted('/ik_node: target_pose', 'rejected out_of_limits')
    rejection = status['last rejection']
    assert rejection.startswith('the pose is out of the limits: leg 3: leg_force_max'), rejection
    for leg in (3, 4, 6):
        assert f'leg {leg}: leg_force_max' in rejection, rejection
    assert 'leg 1:' not in rejection and 'leg 2:' not in rejection, rejection
    np.testing.assert_allclose(topics.received['leg_lengths'][0].data,
                               reference.leg_lengths(HOME), rtol=0.0, atol=1e-12)
    assert len(topics.received['leg_lengths']) == 1
    stop_cleanly(ik)
