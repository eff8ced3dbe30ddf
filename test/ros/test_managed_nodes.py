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
The managed-node mechanism (stewart_kinematics.ros.managed) in the test's own process.

The transitions are taken with rclpy's ``trigger_*`` (the services call the same code; the
process tests call the services); the node's entities are read from rclpy's lists.
"""

import math
from pathlib import Path

from geometry_msgs.msg import Pose
from helpers import trajectory_message
import numpy as np
import pytest
from rclpy.exceptions import ParameterException
from rclpy.lifecycle import LifecyclePublisher, TransitionCallbackReturn
from rclpy.parameter import Parameter
import reference
from std_msgs.msg import Float64MultiArray
from std_srvs.srv import Trigger

from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
from stewart_kinematics.ros.node_main import create_executor
from stewart_kinematics.ros.trajectory_node import TrajectoryNode
from visualization_msgs.msg import Marker

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
ARGS = ['--ros-args', '--params-file', str(CONFIG / 'paper_platform.yaml'),
        '--params-file', str(CONFIG / 'example_limits.yaml')]
MANAGED = Parameter('managed', value=True)
SUCCESS, FAILURE = TransitionCallbackReturn.SUCCESS, TransitionCallbackReturn.FAILURE
NODES = [IkNode, FkNode, TrajectoryNode, MotionCueingNode]
#: Seconds within which trajectory_node plans 300 waypoints over 100 s (under 1 s here).
PLANNING_TIME = 4.0


def entities(node):
    """Count the node's entities by kind."""
    return {kind: len(list(getattr(node, kind))) for kind in (
        'publishers', 'subscriptions', 'services', 'timers', 'waitables')}


def callback_of(node, topic):
    """Return the callback rclpy calls for the node's subscription on ``topic``."""
    return next(sub.callback for sub in node.subscriptions if sub.topic_name == topic)


@pytest.fixture
def build(ros):
    """Build nodes for one test; destroy them at its end."""
    nodes = []

    def make(node_class, *overrides, args=ARGS):
        nodes.append(node_class(cli_args=args, parameter_overrides=list(overrides)))
        return nodes[-1]
    yield make
    for node in nodes:
        node.destroy_node()


@pytest.mark.parametrize('node_class', NODES)
def test_unmanaged_nodes_are_what_they_were(build, node_class):
    """Unmanaged: active at once, no state machine, no lifecycle service or topic."""
    node = build(node_class)

    assert node.managed is False and node.active and node.configured
    assert not hasattr(node, '_state_machine')
    assert not any('state' in service.srv_name or 'transition' in service.srv_name
                   for service in node.services)
    assert not any('transition_event' in publisher.topic_name for publisher in node.publishers)
    assert not any(isinstance(publisher, LifecyclePublisher) for publisher in node.publishers)
    assert node.describe_parameter('managed').read_only


@pytest.mark.parametrize('node_class', NODES)
def test_managed_nodes_build_on_configure_and_release_on_cleanup(build, node_class):
    """Unconfigured: only the parameters; configure builds, cleanup releases it all, twice."""
    node = build(node_class, MANAGED)
    assert node.managed and node.lifecycle_state() == 'unconfigured'
    before = entities(node)
    assert before['subscriptions'] == 0 and before['timers'] == 0

    assert node.trigger_configure() == SUCCESS and node.lifecycle_state() == 'inactive'
    built = entities(node)
    assert built['publishers'] > before['publishers'] and built['subscriptions'] > 0
    added = set(node.publishers)
    assert all(isinstance(publisher, LifecyclePublisher) for publisher in added
               if publisher.topic_name not in ('/rosout', '/parameter_events'))
    assert node.trigger_activate() == SUCCESS and node.active
    assert node.trigger_deactivate() == SUCCESS and not node.active
    assert node.trigger_cleanup() == SUCCESS
    assert entities(node) == before
    assert node.trigger_configure() == SUCCESS and entities(node) == built
    assert node.trigger_shutdown() == SUCCESS
    assert node.lifecycle_state() == 'finalized' and node.finalized
    assert entities(node) == before


def test_inactive_inputs_are_ignored_counted_and_never_acted_on(build):
    """ik_node inactive: a pose is counted as ignored; active again, it was not kept."""
    node = build(IkNode, MANAGED)
    assert node.trigger_configure() == SUCCESS
    on_pose = callback_of(node, '/target_pose')
    far = reference.TABLE_3[3]
    message = Pose()
    message.position.x, message.position.y, message.position.z = far[:3]
    message.orientation.w = 1.0

    on_pose(message)
    on_pose(message)

    assert node.ignored_inputs == {'target_pose': 2}
    assert node.check.last_pose is None and node.accounting.received == 0
    assert node.trigger_activate() == SUCCESS
    assert node.check.last_pose is None
    on_pose(message)
    assert node.accounting.received == 1 and node.check.last_pose is not None


def test_inactive_trigger_services_answer_that_the_node_is_not_active(build):
    """fk_node's reset_tracker while inactive: success false, saying why; active: done."""
    node = build(FkNode, MANAGED)
    assert node.trigger_configure() == SUCCESS
    service = next(s for s in node.services if s.srv_name.endswith('reset_tracker'))

    answer = service.callback(Trigger.Request(), Trigger.Response())

    assert not answer.success and 'not active (lifecycle state inactive)' in answer.message
    assert node.trigger_activate() == SUCCESS
    assert service.callback(Trigger.Request(), Trigger.Response()).success


def test_a_value_refused_at_declaration_is_refused_by_configure_until_fixed(build):
    """A stroke of the wrong type: unmanaged, the node cannot start; managed, configure says."""
    wrong = Parameter('leg_length_max', value='0.9')
    with pytest.raises((ParameterException, ValueError)):
        build(FkNode, wrong)
    node = build(FkNode, MANAGED, wrong)

    assert node.trigger_configure() == FAILURE
    assert 'leg_length_max' in str(node.configure_error)
    assert node.lifecycle_state() == 'unconfigured'
    assert node.set_parameters([Parameter('leg_length_max', value=0.9)])[0].successful
    assert node.trigger_configure() == SUCCESS
    assert node.settings.geometry.leg_length_max == 0.9


def test_configure_refusal_of_the_geometry_releases_what_was_built(build):
    """A ramp beyond the limits (trajectory_node's check in configure): refused, nothing left."""
    node = build(TrajectoryNode, MANAGED, Parameter('leg_length_max', value=0.72), args=[
        *ARGS, '--params-file', str(CONFIG / 'table3_ramp.yaml')])
    before = entities(node)

    assert node.trigger_configure() == FAILURE
    assert 'leg_length_max' in str(node.configure_error)
    assert entities(node) == before and not node.configured
    assert node.set_parameters([Parameter('leg_length_max', value=0.9)])[0].successful
    assert node.trigger_configure() == SUCCESS


def test_an_unexpected_error_in_configure_fails_it_and_releases(build, monkeypatch):
    """A bug (not a refusal) in a node's configure: the transition fails, the node lives."""
    node = build(FkNode, MANAGED)
    before = entities(node)
    original = FkNode.configure

    def broken(self):
        original(self)
        raise RuntimeError('a bug')
    monkeypatch.setattr(FkNode, 'configure', broken)

    assert node.trigger_configure() == FAILURE
    assert isinstance(node.configure_error, RuntimeError)
    assert entities(node) == before
    monkeypatch.setattr(FkNode, 'configure', original)
    assert node.trigger_configure() == SUCCESS


@pytest.mark.parametrize('value', ['yes', 1, [True]])
def test_managed_of_the_wrong_type_stops_the_node(ros, value):
    """Stop the node at once for a managed of the wrong type: it is read before the rest."""
    with pytest.raises((ParameterException, ValueError)):
        IkNode(cli_args=ARGS, parameter_overrides=[Parameter('managed', value=value)])


def test_read_only_parameters_are_settable_only_while_unconfigured(build):
    """Read-only parameters: set while unconfigured, refused once configured, checked always."""
    node = build(FkNode, MANAGED)
    assert not node.set_parameters([Parameter('leg_length_max', value=-1.0)])[0].successful
    assert node.set_parameters([Parameter('leg_length_max', value=0.88)])[0].successful
    assert not node.set_parameters([Parameter('managed', value=False)])[0].successful
    assert node.trigger_configure() == SUCCESS
    refused = node.set_parameters([Parameter('leg_length_max', value=0.9)])[0]
    assert not refused.successful and 'read-only' in refused.reason
    assert node.trigger_cleanup() == SUCCESS
    assert node.set_parameters([Parameter('leg_length_max', value=0.9)])[0].successful


def test_fk_node_publishes_nothing_while_inactive(build):
    """Configured fk_node: a leg length message while inactive publishes no pose."""
    node = build(FkNode, MANAGED)
    assert node.trigger_configure() == SUCCESS
    callback_of(node, '/leg_lengths')(Float64MultiArray(data=list(
        reference.leg_lengths(reference.HOME))))

    assert node.accounting.received == 0 and node.accounting.published == 0
    assert node.ignored_inputs == {'leg_lengths': 1}


def test_ik_node_sends_its_latched_cleared_markers_once_active(build, monkeypatch):
    """workspace_resolution 0: the latched, cleared workspace_markers go out on activate."""
    node = build(IkNode, MANAGED, Parameter('workspace_resolution', value=0.0))
    assert node.trigger_configure() == SUCCESS
    publisher = node.workspace.marker_publisher
    sent = []
    original = LifecyclePublisher.publish

    def record(self, message):
        if self is publisher and self.is_activated:
            sent.append(message)
        return original(self, message)
    monkeypatch.setattr(LifecyclePublisher, 'publish', record)

    node.workspace.set_resolution(0.0)   # inactive: dropped
    assert sent == []
    assert node.trigger_activate() == SUCCESS

    assert len(sent) == 1 and sent[0].markers[0].action == Marker.DELETEALL


def test_a_plan_under_way_at_deactivate_is_never_published(build, spin_until):
    """trajectory_node: a long plan cancelled by deactivate never comes out, even once active."""
    node = build(TrajectoryNode, MANAGED, Parameter('mode', value='off'))
    executor = create_executor()
    executor.add_node(node)
    try:
        assert node.trigger_configure() == SUCCESS and node.trigger_activate() == SUCCESS
        on_trajectory = callback_of(node, '/pose_trajectory')
        times = np.linspace(0.0, 100.0, 300)
        waves = np.array(reference.HOME) + 0.01 * np.outer(
            1.0 - np.cos(2.0 * math.pi * times / 100.0), [1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
        on_trajectory(trajectory_message(times, waves))
        assert node.trigger_deactivate() == SUCCESS
        assert node.trigger_activate() == SUCCESS
        accounting = node.trajectory_accounting
        # Planned whole it would be published within seconds (without the new worker it was).
        spin_until(executor, lambda: accounting.published > 0, timeout=PLANNING_TIME)
        assert accounting.published == 0 and accounting.received == 1
        # The new worker plans what comes now.
        on_trajectory(trajectory_message([0.0, 5.0], [reference.HOME, reference.HOME]))
        assert spin_until(executor, lambda: accounting.published == 1)
    finally:
        executor.shutdown()


@pytest.mark.parametrize('node_class', NODES)
def test_every_node_refuses_a_bad_limit_at_configure_and_takes_it_fixed(build, node_class):
    """leg_velocity_max -1 m/s: configure fails naming it; set right, configure succeeds."""
    node = build(node_class, MANAGED, Parameter('leg_velocity_max', value=-1.0))

    assert node.trigger_configure() == FAILURE
    assert 'leg_velocity_max' in str(node.configure_error)
    assert node.lifecycle_state() == 'unconfigured'
    assert node.set_parameters([Parameter('leg_velocity_max', value=0.05)])[0].successful
    assert node.trigger_configure() == SUCCESS
    assert node.trigger_shutdown() == SUCCESS and node.lifecycle_state() == 'finalized'


@pytest.mark.parametrize('node_class', NODES)
def test_cleanup_of_a_configure_refused_before_its_workers_started(build, node_class):
    """Cleanup runs after any refused configure: with nothing built it has nothing to stop."""
    node = build(node_class, MANAGED)

    node.cleanup()  # raised AttributeError in ik_node, fk_node and trajectory_node
    assert node.trigger_configure() == SUCCESS


def test_a_publisher_made_while_active_sends_at_once(build):
    """A publisher a managed node makes while active (lazily) is enabled; inactive, not."""
    node = build(FkNode, MANAGED)
    assert node.trigger_configure() == SUCCESS
    inactive_made = node.create_publisher(Pose, 'made_inactive', 10)
    assert node.trigger_activate() == SUCCESS
    active_made = node.create_publisher(Pose, 'made_active', 10)

    assert isinstance(active_made, LifecyclePublisher) and active_made.is_activated
    assert inactive_made.is_activated   # enabled by activate with the others
    assert node.trigger_deactivate() == SUCCESS
    assert not active_made.is_activated and not inactive_made.is_activated
