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
ik_node's workspace outputs, ``workspace_markers`` and ``travel_ranges``, off the command path.

The core's :mod:`stewart_kinematics.analysis.workspace` does the work in a worker process of its
own (:class:`~stewart_kinematics.workers.workspace_worker.WorkspaceWorker`: a thread would share
the interpreter lock with the executor, and a measured 1 kHz command path waited up to tens of
milliseconds for it on a busy machine). Each result is handed back to the node's executor as a task
(:func:`~stewart_kinematics.ros.node_main.hand_to_executor`; the EventsExecutor supports no
guard condition), which only converts and publishes. So a 3 s workspace computation or a 0.2 s
travel range never holds up a pose in the command stream, and at most one job of each kind is
in flight: a travel range due while the last one is still running is skipped.
"""

import threading

import numpy as np
from std_msgs.msg import Float64MultiArray, Header, MultiArrayDimension

from stewart_kinematics.analysis import workspace
from stewart_kinematics.model.rotations import matrix_to_euler_zyx
from stewart_kinematics.ros.interfaces import IK_NODE
from stewart_kinematics.ros.markers import workspace_markers
from stewart_kinematics.ros.node_main import create_output_publisher, hand_to_executor
from stewart_kinematics.workers.workspace_worker import WorkspaceWorker

#: How often ik_node looks for a first subscriber of workspace_markers without travel
#: ranges, seconds (with them, at each travel range).
MARKER_CHECK_PERIOD = 1.0
#: Layout of travel_ranges: (axis, end), row-major; offsets from the pose, m and rad.
TRAVEL_RANGE_LAYOUT = (
    MultiArrayDimension(label='axis: X, Y, Z [m], alpha, beta, gamma [rad]', size=6,
                        stride=12),
    MultiArrayDimension(label='end: negative, positive (offset from the last accepted pose)',
                        size=2, stride=2),
)


def travel_ranges_to_message(ranges) -> Float64MultiArray:
    """Return the 12 values ``[X-, X+, Y-, Y+, ..., gamma+]`` with their labelled layout."""
    message = Float64MultiArray(data=ranges.as_array().ravel().tolist())
    message.layout.dim = list(TRAVEL_RANGE_LAYOUT)
    return message


class WorkspacePublisher:
    """
    Publish ``workspace_markers`` (latched) and ``travel_ranges`` for a node.

    Nothing is computed for nobody: the worker process starts, and the workspace is computed,
    once ``workspace_markers`` has a subscriber (checked at each travel range, or every
    second; latched, so later subscribers get it too), again when the resolution changes; a
    travel range is computed only while ``travel_ranges`` has a subscriber and the last
    accepted pose has moved since the last one (otherwise that one is published again).

    :param node: the node (ik_node).
    :param geometry: its :class:`stewart_kinematics.Geometry`.
    :param base_frame: frame of the markers.
    :param resolution: grid step of the workspace, metres; 0 for no markers.
    :param travel_range_rate: hertz; 0 for no travel ranges.
    :param last_pose: a callable returning the last accepted ``(position, rotation)`` or None
        (the home pose is used until a pose has been accepted).
    :param depth: queue depth of travel_ranges.
    """

    def __init__(self, node, geometry, base_frame, resolution, travel_range_rate, last_pose,
                 depth):
        self.node, self.geometry, self.base_frame = node, geometry, base_frame
        self.last_pose = last_pose
        self.namespace = node.get_namespace().strip('/') or 'stewart_platform'
        self.lock = threading.Lock()
        self.worker = None
        #: Which worker process is the current one (one per geometry the node had).
        self.worker_generation = 0
        #: Results waiting for the executor: kind -> (generation, value or exception).
        self.results = {}
        #: Set by :meth:`shutdown`: a result that arrives later is dropped.
        self.closed = False
        self.busy = set()
        self.marker_generation = 0
        self.resolution = resolution
        self.markers_due = False
        #: The last travel range message and the pose it was computed from.
        self.travel = None
        # Without rclpy's default QoS event handlers, and one timer for both outputs: every
        # entity of a node adds to its executor's work at each message of the command stream.
        self.marker_publisher = create_output_publisher(node, IK_NODE['workspace_markers'])
        self.travel_publisher = create_output_publisher(node, IK_NODE['travel_ranges'], depth)
        self.travel_rate = travel_range_rate
        self.timer = node.create_timer(
            1.0 / travel_range_rate if travel_range_rate > 0.0 else MARKER_CHECK_PERIOD,
            self.on_timer)
        self.set_resolution(resolution)

    def on_timer(self):
        """Start what is due: the markers for a first subscriber, a travel range."""
        # A result that came while the node had no executor yet waits for this tick.
        self.publish_results()
        self.request_markers()
        if self.travel_rate > 0.0:
            self.request_travel_ranges()

    def set_resolution(self, resolution):
        """Compute the workspace at a new resolution (0: clear the markers) and publish it."""
        self.marker_generation += 1
        self.resolution = resolution
        self.markers_due = resolution > 0.0
        if resolution > 0.0:
            self.request_markers()
        else:
            self.marker_publisher.publish(workspace_markers(self._header(), np.zeros((0, 3)),
                                                            [], self.namespace))

    def set_geometry(self, geometry):
        """
        Compute from now on with ``geometry`` (a new payload: its force limits move the boundary).

        The worker process holds the old geometry: it is stopped (a computation under way is
        dropped) and started again with the new one when next needed; the markers are computed
        again for their subscribers, and the next travel range from the last accepted pose.
        """
        with self.lock:
            self.results = {}
            self.worker_generation += 1   # what the old worker still sends is dropped
        if self.worker is not None:
            self.worker.close()
            self.worker = None
        self.geometry = geometry
        self.busy.clear()
        self.travel = None
        self.set_resolution(self.resolution)

    def request_markers(self):
        """Start the workspace computation if it is due and someone subscribes."""
        if self.markers_due and self.marker_publisher.get_subscription_count():
            self.markers_due = False
            self._submit('markers', self.marker_generation, workspace.workspace_shell,
                         resolution=self.resolution)

    def request_travel_ranges(self):
        """Start a travel range computation from the last accepted pose, unless one runs."""
        if 'travel' in self.busy or not self.travel_publisher.get_subscription_count():
            return
        last = self.last_pose()
        pose = np.array(self.geometry.home_pose, dtype=float)
        if last is not None:
            pose = np.concatenate([last[0], matrix_to_euler_zyx(last[1])])
        if self.travel is not None and np.array_equal(self.travel[0], pose):
            self.travel_publisher.publish(self.travel[1])
            return
        self._submit('travel', pose, workspace.travel_ranges, pose)

    def _submit(self, kind, tag, function, *args, **kwargs):
        if self.worker is None:
            # A result of a worker stopped since (the old geometry's) is told apart by this.
            self.worker_generation += 1
            generation = self.worker_generation
            self.worker = WorkspaceWorker(
                self.geometry, lambda tag, value: self._on_result(tag, value, generation))
        self.busy.add(kind)
        self.worker.submit((kind, tag), function, *args, **kwargs)

    def _on_result(self, tag, value, worker_generation=None):
        """Keep a finished result and hand it to the node's executor (the reader thread)."""
        kind, generation = tag
        with self.lock:
            if self.closed or worker_generation != self.worker_generation:
                return
            self.results[kind] = (generation, value)
            # Under the lock: shutdown() cannot free the node meanwhile.
            hand_to_executor(self.node, self.publish_results)

    def publish_results(self):
        """Publish the results the worker has finished (executor thread)."""
        with self.lock:
            if self.closed:   # a task queued before the node was destroyed
                return
            results, self.results = self.results, {}
        for kind, (tag, value) in results.items():
            self.busy.discard(kind)
            if isinstance(value, Exception):
                self.node.get_logger().error(f'{kind} computation failed: {value}')
            elif kind == 'travel':
                self.travel = tag, travel_ranges_to_message(value)
                self.travel_publisher.publish(self.travel[1])
            elif tag == self.marker_generation:
                self.marker_publisher.publish(workspace_markers(
                    self._header(), value.points, value.limit, self.namespace))
                self.node.get_logger().info(
                    f'workspace_markers: {len(value.points)} boundary points, volume '
                    f'{value.volume:.6f} m^3 at the home orientation')

    def _header(self):
        return Header(stamp=self.node.get_clock().now().to_msg(), frame_id=self.base_frame)

    def shutdown(self):
        """Stop the worker process (a computation under way is dropped); free the entities."""
        with self.lock:
            self.closed = True
        if self.worker is not None:
            self.worker.close()
            self.worker = None
        self.node.destroy_timer(self.timer)
        # No cycle through the node is left for the garbage collector.
        self.last_pose = self.timer = None
