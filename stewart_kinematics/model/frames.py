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
The platform's frame tree: base, platform, and the user and tool frames hexapod users work in.

::

    base_frame ──(pose from the kinematics)──> platform_frame ──(tool pose)──> tool_frame
        └──(user pose)──> user_frame

- The **base frame** is fixed; the geometry's base joints are given in it.
- The **platform frame** moves with the platform; the platform joints are given in it, and a
  pose of the kinematics (:func:`~stewart_kinematics.inverse_kinematics`) places it.
- The **tool frame** is fixed to the platform (a tool centre point, a payload's centre): its
  origin is the pivot point. A commanded pose is the tool frame's, so a pure rotation turns the
  platform about that point, as hexapod controllers do; the default tool frame is the platform
  frame itself.
- The **user frame** is fixed to the base (a work piece, a camera): a commanded or estimated
  pose may be expressed in it instead of in the base frame.

A :class:`Transform` ``T_a_b`` places frame b in frame a: a point with coordinates ``x_b`` in b
has coordinates ``x_a = R x_b + t`` in a. Composition is ``T_a_c = T_a_b @ T_b_c``. Nothing here
imports ROS; the nodes turn messages into these objects and back.
"""

from dataclasses import dataclass, field, replace

import numpy as np

from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, matrix_to_euler_zyx


@dataclass(frozen=True, eq=False)
class Transform:
    """
    A rigid transform: a rotation, then a translation.

    :param position: translation t, shape (3,), metres, in the parent frame.
    :param rotation: rotation matrix R, shape (3, 3), mapping child-frame vectors to the parent.
    """

    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    rotation: np.ndarray = field(default_factory=lambda: np.eye(3))

    def __post_init__(self):
        """Store float copies; refuse anything but a finite (3,) and a rotation (3, 3)."""
        position = np.array(as_float_array(self.position, 'position'))
        rotation = np.array(as_float_array(self.rotation, 'rotation'))
        if position.shape != (3,) or rotation.shape != (3, 3):
            raise ValueError(f'a transform needs a position of shape (3,) and a rotation of '
                             f'shape (3, 3), got {position.shape} and {rotation.shape}')
        if not (np.all(np.isfinite(position)) and np.all(np.isfinite(rotation))):
            raise ValueError(f'a transform must be finite, got position {position.tolist()}')
        if not np.allclose(rotation @ rotation.T, np.eye(3), rtol=0.0, atol=1e-9) or (
                np.linalg.det(rotation) < 0.0):
            raise ValueError('a transform needs a proper rotation matrix (orthonormal, det +1)')
        object.__setattr__(self, 'position', position)
        object.__setattr__(self, 'rotation', rotation)

    @classmethod
    def from_pose(cls, pose) -> 'Transform':
        """
        Build from a pose vector ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).

        The angles follow the package's convention, ``R = Rz(gamma) Ry(beta) Rx(alpha)``. An
        all-zero pose gives :data:`IDENTITY` itself, which the frame tree skips at no cost.
        """
        pose = as_float_array(pose, 'pose')
        if pose.shape != (6,):
            raise ValueError(f'a pose vector has 6 values, got shape {pose.shape}')
        if not pose.any():
            return IDENTITY
        return cls(pose[:3], euler_zyx_to_matrix(pose[3:]))

    def as_pose(self) -> np.ndarray:
        """Return the pose vector ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians)."""
        return np.concatenate([self.position, matrix_to_euler_zyx(self.rotation)])

    def __matmul__(self, other: 'Transform') -> 'Transform':
        """Compose: ``(T_a_b @ T_b_c)`` is ``T_a_c``."""
        return Transform(self.position + self.rotation @ other.position,
                         self.rotation @ other.rotation)

    def inverse(self) -> 'Transform':
        """Return the transform that undoes this one: ``T_b_a`` for ``T_a_b``."""
        return Transform(-(self.rotation.T @ self.position), self.rotation.T)

    def apply(self, points) -> np.ndarray:
        """
        Map points (3,) or (N, 3) from the child frame to the parent frame, metres.

        :raises ValueError: for what is not numbers of that shape.
        """
        points = as_float_array(points, 'points')
        if points.ndim not in (1, 2) or points.shape[-1] != 3:
            raise ValueError(f'points must have shape (3,) or (N, 3), got {points.shape}')
        return points @ self.rotation.T + self.position

    def is_identity(self) -> bool:
        """Whether this transform changes nothing (exactly)."""
        return not self.position.any() and np.array_equal(self.rotation, np.eye(3))


#: The transform that changes nothing.
IDENTITY = Transform()


@dataclass(frozen=True)
class FrameTree:
    """
    The frame names and the fixed transforms of a platform; see the module docstring.

    Immutable: a node replaces its tree as a whole when a parameter changes, so a message is
    handled with one tree from start to end.

    :param base_frame: name of the base frame.
    :param platform_frame: name of the platform frame.
    :param user_frame: name of the user frame, ``''`` for none.
    :param user_pose: ``T_base_user``, the user frame placed in the base frame.
    :param tool_frame: name of the tool frame, ``''`` to leave it unnamed (its pose still
        applies: commanded and estimated poses are those of the tool frame).
    :param tool_pose: ``T_platform_tool``, the tool frame placed in the platform frame; its
        origin is the pivot point.
    :raises ValueError: for an empty base or platform frame name, or names that repeat.
    """

    base_frame: str = 'stewart_base'
    platform_frame: str = 'stewart_platform'
    user_frame: str = ''
    user_pose: Transform = IDENTITY
    tool_frame: str = ''
    tool_pose: Transform = IDENTITY

    def __post_init__(self):
        """Check the names: the base and platform frames are named, no name repeats."""
        if not self.base_frame or not self.platform_frame:
            raise ValueError('the base frame and the platform frame need names')
        names = [name for name in (self.base_frame, self.platform_frame, self.user_frame,
                                   self.tool_frame) if name]
        if len(set(names)) != len(names):
            raise ValueError(f'frame names must differ, got {preview(names)}')

    def with_tool(self, tool_frame: str, tool_pose: Transform) -> 'FrameTree':
        """Return this tree with another tool frame (a change at run time)."""
        return replace(self, tool_frame=tool_frame, tool_pose=tool_pose)

    def reference(self, frame_id: str) -> Transform:
        """
        Place a frame a pose may be given in: ``T_base_frame``.

        :param frame_id: the base frame, the user frame, or ``''`` (taken as the base frame).
        :raises ValueError: for any other frame, saying which ones are accepted.
        """
        if not frame_id or frame_id == self.base_frame:
            return IDENTITY
        if self.user_frame and frame_id == self.user_frame:
            return self.user_pose
        accepted = f"base_frame '{self.base_frame}'" + (
            f" or user_frame '{self.user_frame}'" if self.user_frame else '')
        raise ValueError(f'it is in frame {preview(frame_id)}, not in {accepted}; transform it '
                         'first')

    def platform_from_tool(self, tool: Transform, frame_id: str = '') -> Transform:
        """
        Where the platform frame must be for the tool frame to be at ``tool``.

        :param tool: the commanded tool frame, placed in ``frame_id``.
        :returns: ``T_base_platform = T_base_ref @ T_ref_tool @ inverse(T_platform_tool)``.
        :raises ValueError: for a frame :meth:`reference` does not accept.
        """
        reference = self.reference(frame_id)
        in_base = tool if reference is IDENTITY else reference @ tool
        return in_base if self.tool_pose is IDENTITY else in_base @ self.tool_pose.inverse()

    def tool_from_platform(self, platform: Transform, frame_id: str = '') -> Transform:
        """
        Where the tool frame is when the platform frame is at ``platform``, seen from a frame.

        :param platform: ``T_base_platform``, as forward kinematics finds it.
        :param frame_id: the frame to express the tool frame in (base or user frame).
        :returns: ``T_ref_tool = inverse(T_base_ref) @ T_base_platform @ T_platform_tool``.
        :raises ValueError: for a frame :meth:`reference` does not accept.
        """
        reference = self.reference(frame_id)
        tool = platform if self.tool_pose is IDENTITY else platform @ self.tool_pose
        return tool if reference is IDENTITY else reference.inverse() @ tool

    def platform_in_base(self, position, rotation, frame_id: str = ''):
        """
        Like :meth:`platform_from_tool`, on a position (3,) and a rotation matrix (3, 3).

        The hot path of a command stream: with no tool frame and a pose in the base frame it
        returns its arguments as float arrays (float arrays of shapes (3,) and (3, 3)
        untouched, at no cost; not checked to be a rotation).

        :returns: ``(position, rotation)`` of the platform frame in the base frame.
        :raises ValueError: for a frame :meth:`reference` does not accept, or a position or
            rotation that is no rigid transform.
        """
        if self.tool_pose is IDENTITY and self.reference(frame_id) is IDENTITY:
            position = as_float_array(position, 'position')
            rotation = as_float_array(rotation, 'rotation')
            if position.shape == (3,) and rotation.shape == (3, 3):
                return position, rotation
        platform = self.platform_from_tool(Transform(position, rotation), frame_id)
        return platform.position, platform.rotation

    def tool_pose_vector(self, platform_pose, frame_id: str = ''):
        """
        Like :meth:`tool_from_platform`, on pose vectors ``[X, Y, Z, alpha, beta, gamma]``.

        With no tool frame and the base frame asked for, returns ``platform_pose`` as a float
        array (the very array, when it is one).

        :raises ValueError: for a frame :meth:`reference` does not accept, or a pose that is not
            six numbers.
        """
        platform_pose = as_float_array(platform_pose, 'platform_pose')
        if (self.tool_pose is IDENTITY and self.reference(frame_id) is IDENTITY
                and platform_pose.shape == (6,)):
            return platform_pose
        return self.tool_from_platform(Transform.from_pose(platform_pose), frame_id).as_pose()

    def platform_pose_vectors(self, tool_poses):
        """
        Return the platform poses, shape (N, 6), that put the tool frame at ``tool_poses``.

        :param tool_poses: poses of the tool frame in the base frame, shape (N, 6).
        """
        tool_poses = as_float_array(tool_poses, 'tool_poses')
        if tool_poses.ndim != 2 or tool_poses.shape[1] != 6:
            raise ValueError(f'tool_poses must have shape (N, 6), got {tool_poses.shape}')
        if self.tool_pose is IDENTITY:
            return tool_poses
        return np.array([self.platform_from_tool(Transform.from_pose(pose)).as_pose()
                         for pose in tool_poses]).reshape(tool_poses.shape)

    def platform_motion(self, positions, rotations, velocities=None, angular_velocities=None,
                        accelerations=None, angular_accelerations=None, frame_id: str = ''):
        """
        Move the motion of the tool frame to the platform frame, in the base frame (N poses).

        The poses are placed as :meth:`platform_from_tool` places one. The velocities are
        rotated from ``frame_id`` to the base frame and moved from the tool frame's origin to
        the platform's: with ``d = R_platform p_tool`` (the tool frame's origin seen from the
        platform's, base frame), ``v_platform = v_tool - w x d`` and ``a_platform = a_tool -
        alpha x d - w x (w x d)``; the angular velocity and acceleration are the same for
        both frames (both are fixed to the platform).

        :param positions: the tool frame's origins, metres, shape (N, 3), in ``frame_id``.
        :param rotations: the tool frame's orientations, shape (N, 3, 3), in ``frame_id``.
        :param velocities: of the tool frame's origin, m/s, (N, 3), with the
            ``angular_velocities`` (rad/s); ``accelerations`` (m/s^2) with the
            ``angular_accelerations`` (rad/s^2); each pair optional (``None``).
        :param frame_id: the base frame, the user frame, or ``''`` (the base frame).
        :returns: ``(positions, rotations, velocities, angular_velocities, accelerations,
            angular_accelerations)`` of the platform frame in the base frame, as arrays;
            ``None`` where not given.
        :raises ValueError: for a frame :meth:`reference` does not accept, or a wrong shape.
        """
        positions = _vectors('positions', positions)
        count = positions.shape[0]
        rotations = as_float_array(rotations, 'rotations')
        if rotations.shape != (count, 3, 3):
            raise ValueError(f'rotations must have shape ({count}, 3, 3), got {rotations.shape}')
        vectors = [None if value is None else _vectors(name, value, count) for name, value in (
            ('velocities', velocities), ('angular velocities', angular_velocities),
            ('accelerations', accelerations), ('angular accelerations', angular_accelerations))]
        reference = self.reference(frame_id)
        if reference is not IDENTITY:
            turn = reference.rotation
            positions = reference.apply(positions)
            rotations = turn @ rotations
            vectors = [None if value is None else value @ turn.T for value in vectors]
        if self.tool_pose is not IDENTITY:
            rotations = rotations @ self.tool_pose.rotation.T
            offsets = rotations @ self.tool_pose.position
            positions = positions - offsets
            velocity, omega, acceleration, alpha = vectors
            if velocity is not None and omega is not None:
                vectors[0] = velocity - np.cross(omega, offsets)
            if acceleration is not None and alpha is not None and omega is not None:
                vectors[2] = (acceleration - np.cross(alpha, offsets)
                              - np.cross(omega, np.cross(omega, offsets)))
        return (positions, rotations, *vectors)

    def platform_twist_from_tool(self, twist, platform_rotation) -> np.ndarray:
        """
        Return the platform origin's twist of a twist about the tool frame's origin (base).

        :param twist: ``[vx, vy, vz, wx, wy, wz]`` of the tool frame's origin, base frame,
            m/s and rad/s, shape (6,).
        :param platform_rotation: the platform's orientation, shape (3, 3).
        :returns: ``[v - w x d, w]`` with ``d = R_platform p_tool``; the twist itself when the
            tool frame's origin is the platform's.
        """
        twist = as_float_array(twist, 'twist')
        if not self.tool_pose.position.any() or twist.shape != (6,):
            return twist   # a wrong shape is the caller's to refuse, with its reason
        offset = as_float_array(platform_rotation, 'platform_rotation') @ self.tool_pose.position
        with np.errstate(all='ignore'):   # a NaN or huge twist stays one: refused by the caller
            return np.concatenate([twist[:3] - np.cross(twist[3:], offset), twist[3:]])

    def tool_twist_from_platform(self, twist, platform_rotation) -> np.ndarray:
        """
        Return the twist about the tool frame's origin of the platform origin's (base).

        The inverse of :meth:`platform_twist_from_tool`: ``[v + w x d, w]``.
        """
        twist = as_float_array(twist, 'twist')
        if not self.tool_pose.position.any() or twist.shape != (6,):
            return twist
        offset = as_float_array(platform_rotation, 'platform_rotation') @ self.tool_pose.position
        with np.errstate(all='ignore'):
            return np.concatenate([twist[:3] + np.cross(twist[3:], offset), twist[3:]])

    def static_transforms(self):
        """
        Return the fixed transforms of named frames, for ``/tf_static``.

        :returns: ``(parent, child, transform)`` for the user frame (from the base frame) and
            the tool frame (from the platform frame), where they are named.
        """
        transforms = []
        if self.user_frame:
            transforms.append((self.base_frame, self.user_frame, self.user_pose))
        if self.tool_frame:
            transforms.append((self.platform_frame, self.tool_frame, self.tool_pose))
        return transforms


def _vectors(name, values, count=None):
    """Convert to a float array of shape (N, 3), or (count, 3), saying what is wrong."""
    array = np.array(as_float_array(values, name))
    if array.size == 0 and count in (None, 0):
        return array.reshape(0, 3)
    if array.ndim != 2 or array.shape[1] != 3 or (count is not None and array.shape[0] != count):
        shown = 'N' if count is None else count
        raise ValueError(f'{name} must have shape ({shown}, 3), got {array.shape}')
    return array
