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
The executor switch, across real processes: every node answers on either executor.

The console scripts are started with ``--executor NAME`` (before ``--ros-args``) or with
``STEWART_EXECUTOR`` in their environment, whatever executor the rest of the session runs on:
each answers a pose or leg lengths, the default is the EventsExecutor, an unknown name stops
the start with exit code 1 and a message naming the allowed ones, SIGINT and SIGTERM stop
each cleanly, and ik_node's workspace outputs (computed in its worker process and handed to
the executor as a task, not through a guard condition) arrive on both.
"""

import os
from pathlib import Path
import signal
import subprocess
import time

from geometry_msgs.msg import Pose
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Float64MultiArray

from stewart_kinematics import inverse_kinematics, load_geometry
from stewart_kinematics.ros.message_conversions import legs_to_message, pose_to_message
from stewart_kinematics.ros.node_main import (
    DEFAULT_EXECUTOR,
    executor_name,
    EXECUTOR_VARIABLE,
    EXECUTORS,
    EXIT_START_FAILED,
)
from visualization_msgs.msg import MarkerArray

pytestmark = pytest.mark.process

#: Seconds a process gets to exit after a signal or a failed start.
EXIT_DEADLINE = 20.0
#: Queue depth of the test's publishers and subscriptions.
DEPTH = 10
CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: Seconds between two publications of the same message while no answer came.
REPUBLISH_PERIOD = 0.2
#: A pose 2 cm above home, slightly turned: metres and radians.
OFFSET = np.array([0.0, 0.01, 0.02, 0.01, -0.02, 0.03])


def kinematics_arguments(config_directory, executor=None, *extra):
    """Return the command line of ik_node and fk_node, with ``--executor`` if given."""
    option = [] if executor is None else ['--executor', executor]
    return [*option, '--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'solver.yaml'), *extra]


def environment(**changes):
    """Return this process's environment with ``changes`` (a value of None removes one)."""
    env = dict(os.environ)
    for name, value in changes.items():
        env.pop(name, None)
        if value is not None:
            env[name] = value
    return env


def wait_exit(process):
    """Return a process's exit code once it has exited (None: still running at the deadline)."""
    try:
        return process.process.wait(EXIT_DEADLINE)
    except subprocess.TimeoutExpired:
        return None


def exchange(client, process, publisher_topic, publisher_type, message, answer_topic,
             answer_type):
    """Publish ``message`` once both ends are connected; return the first answer."""
    answers = []
    subscription = client.node.create_subscription(answer_type, answer_topic, answers.append,
                                                   DEPTH)
    publisher = client.node.create_publisher(publisher_type, publisher_topic, DEPTH)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and subscription.get_publisher_count() >= 1,
                f'{process.name} connected on {publisher_topic} and {answer_topic}', [process])
    # A reliable volatile reader may match a moment after the writer saw it: publish again
    # until an answer comes.
    published = [-REPUBLISH_PERIOD]

    def answered():
        if not answers and time.monotonic() - published[0] >= REPUBLISH_PERIOD:
            publisher.publish(message)
            published[0] = time.monotonic()
        return bool(answers)
    client.wait(answered, f'an answer on {answer_topic}', [process])
    return answers[0]


@pytest.fixture(scope='module')
def geometry():
    """Return the paper's platform."""
    return load_geometry(CONFIG / 'paper_platform.yaml')


@pytest.mark.parametrize('executor', list(EXECUTORS))
@pytest.mark.parametrize('chosen_by', ['option', 'environment'])
def test_ik_node_answers_on_the_chosen_executor(client, start_node, config_directory,
                                                geometry, executor, chosen_by):
    """ik_node, given an executor by option or environment, says so and answers a pose."""
    if chosen_by == 'option':
        # The option wins over the environment.
        other = next(name for name in EXECUTORS if name != executor)
        node = start_node('ik_node', kinematics_arguments(config_directory, executor),
                          environment(**{EXECUTOR_VARIABLE: other}))
    else:
        node = start_node('ik_node', kinematics_arguments(config_directory),
                          environment(**{EXECUTOR_VARIABLE: executor}))
    pose = geometry.home_pose + OFFSET
    answer = exchange(client, node, 'target_pose', Pose, pose_to_message(pose), 'leg_lengths',
                      Float64MultiArray)

    assert_allclose(answer.data, inverse_kinematics(geometry, pose), rtol=0, atol=1e-12)
    assert f'spinning on the {executor} executor' in node.output()


@pytest.mark.parametrize('executor', list(EXECUTORS))
def test_fk_node_answers_on_the_chosen_executor(client, start_node, config_directory,
                                                geometry, executor):
    """fk_node on each executor answers leg lengths with their pose."""
    node = start_node('fk_node', kinematics_arguments(config_directory, executor))
    pose = geometry.home_pose + OFFSET
    answer = exchange(client, node, 'leg_lengths', Float64MultiArray,
                      legs_to_message(inverse_kinematics(geometry, pose)), 'estimated_pose',
                      Pose)

    assert_allclose([answer.position.x, answer.position.y, answer.position.z], pose[:3],
                    rtol=0, atol=1e-9)
    assert f'spinning on the {executor} executor' in node.output()


@pytest.mark.parametrize('executor', list(EXECUTORS))
def test_stewart_platform_answers_on_the_chosen_executor(client, start_node, config_directory,
                                                         geometry, executor):
    """The three-node process on each executor: a pose in, the pose fk_node finds out."""
    node = start_node('stewart_platform', kinematics_arguments(config_directory, executor))
    pose = geometry.home_pose + OFFSET
    answer = exchange(client, node, 'target_pose', Pose, pose_to_message(pose),
                      'estimated_pose', Pose)

    assert_allclose([answer.position.x, answer.position.y, answer.position.z], pose[:3],
                    rtol=0, atol=1e-9)
    assert f'spinning on the {executor} executor' in node.output()


def test_the_default_executor_is_events(client, start_node, config_directory):
    """Without the option or the variable, a node spins on the EventsExecutor."""
    assert DEFAULT_EXECUTOR == 'events'
    assert executor_name((), {}) == 'events'
    node = start_node('ik_node', kinematics_arguments(config_directory),
                      environment(**{EXECUTOR_VARIABLE: None}))
    client.wait(lambda: 'spinning on the' in node.output(), 'the executor in the log', [node])

    assert 'spinning on the events executor' in node.output()


def test_a_node_on_simulated_time_spins_on_the_single_threaded_executor(
        client, start_node, config_directory):
    """use_sim_time with events asked for: single_threaded, and the log says why."""
    node = start_node('ik_node', [*kinematics_arguments(config_directory, 'events'),
                                  '-p', 'use_sim_time:=true'])
    client.wait(lambda: 'spinning on the' in node.output(), 'the executor in the log', [node])

    assert ('use_sim_time: spinning on the single_threaded executor, not events'
            in node.output())
    assert 'spinning on the single_threaded executor' in node.output()
    assert 'spinning on the events executor' not in node.output()


@pytest.mark.parametrize('executable, chosen_by', [
    ('ik_node', 'option'), ('ik_node', 'environment'), ('fk_node', 'option'),
    ('trajectory_node', 'option'), ('stewart_platform', 'option'),
    ('motion_cueing_node', 'option')])
def test_an_unknown_executor_is_refused(start_node, config_directory, executable, chosen_by):
    """An unknown executor name stops the start with code 1, naming the allowed ones."""
    if chosen_by == 'option':
        node = start_node(executable, kinematics_arguments(config_directory, 'multi_threaded'))
    else:
        node = start_node(executable, kinematics_arguments(config_directory),
                          environment(**{EXECUTOR_VARIABLE: 'multi_threaded'}))
    code = wait_exit(node)
    output = node.output()

    assert code == EXIT_START_FAILED, output
    source = '--executor' if chosen_by == 'option' else EXECUTOR_VARIABLE
    assert (f"unknown executor 'multi_threaded' (from {source}): allowed are events, "
            'single_threaded') in output
    assert 'Traceback' not in output


def test_executor_option_without_a_value_is_refused(start_node, config_directory):
    """``--executor`` as the last argument before ``--ros-args`` has no value: exit code 1."""
    node = start_node('ik_node', ['--executor', '--ros-args', '--params-file',
                                  str(config_directory / 'paper_platform.yaml')])
    code = wait_exit(node)

    assert code == EXIT_START_FAILED, node.output()
    assert "unknown executor '--ros-args'" in node.output() or (
        '--executor needs a value' in node.output())


def test_executor_name_reads_option_then_environment():
    """The option wins over the variable, the variable over the default; both forms parse."""
    assert executor_name(['ik_node', '--executor', 'single_threaded'], {}) == 'single_threaded'
    assert executor_name(['--executor=single_threaded'], {EXECUTOR_VARIABLE: 'events'}) == (
        'single_threaded')
    assert executor_name([], {EXECUTOR_VARIABLE: 'single_threaded'}) == 'single_threaded'
    assert executor_name([], {EXECUTOR_VARIABLE: ''}) == 'events'
    with pytest.raises(ValueError, match='needs a value: one of events, single_threaded'):
        executor_name(['--executor'], {})
    with pytest.raises(ValueError, match=r"unknown executor 'Events' \(from STEWART_EXECUTOR\)"):
        executor_name([], {EXECUTOR_VARIABLE: 'Events'})


@pytest.mark.parametrize('executor', list(EXECUTORS))
@pytest.mark.parametrize('executable', ['ik_node', 'stewart_platform'])
@pytest.mark.parametrize('signal_number', [signal.SIGINT, signal.SIGTERM],
                         ids=['SIGINT', 'SIGTERM'])
def test_signal_stops_cleanly_on_either_executor(client, start_node, config_directory,
                                                 executor, executable, signal_number):
    """
    SIGINT and SIGTERM stop a running node with exit code 0 and no traceback.

    (test_node_processes.py and test_load_and_faults.py check every node, and under load, on
    the session's executor.)
    """
    node = start_node(executable, kinematics_arguments(config_directory, executor))
    client.wait(lambda: any(info.node_name == 'ik_node' for info in
                            client.node.get_subscriptions_info_by_topic('target_pose')),
                f'{executable} subscribed to target_pose', [node])

    node.send_signal(signal_number)
    code = wait_exit(node)
    output = node.output()

    assert code == 0, f'{executable} on {executor}: exit code {code}:\n{output}'
    assert 'Traceback' not in output, output


@pytest.mark.parametrize('executor', list(EXECUTORS))
def test_workspace_outputs_arrive_on_either_executor(client, start_node, config_directory,
                                                     executor):
    """
    ik_node's worker results reach the executor: workspace_markers and travel_ranges arrive.

    The markers (latched) come once the topic has a subscriber; travel ranges at 5 Hz, twelve
    finite numbers with the negative end at or below zero and the positive at or above.
    """
    # With limits: without them the workspace has no boundary to show.
    node = start_node('ik_node', kinematics_arguments(
        config_directory, executor, '--params-file', str(config_directory / 'example_limits.yaml'),
        '-p', 'workspace_resolution:=0.02', '-p', 'travel_range_rate:=5.0'))
    markers, ranges = [], []
    latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                         durability=DurabilityPolicy.TRANSIENT_LOCAL)
    client.node.create_subscription(MarkerArray, 'workspace_markers', markers.append, latched)
    client.node.create_subscription(Float64MultiArray, 'travel_ranges', ranges.append, DEPTH)
    client.wait(lambda: markers and len(ranges) >= 2,
                'workspace_markers and two travel_ranges', [node])

    assert any(len(marker.points) > 0 for marker in markers[-1].markers)
    values = np.array(ranges[-1].data).reshape(6, 2)
    assert np.all(np.isfinite(values))
    assert np.all(values[:, 0] <= 0.0) and np.all(values[:, 1] >= 0.0)
    assert 'computation failed' not in node.output()
