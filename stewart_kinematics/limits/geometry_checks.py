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
The checks of a geometry's limits as functions: :class:`~.limit_model.LimitModel` of the geometry.

For a caller that holds a :class:`stewart_kinematics.Geometry` and no model: each function
calls the geometry's model (:meth:`~.limit_model.LimitModel.of_geometry`, built once per geometry),
so there is one computation of every limit. Nothing here imports ROS.
"""

from typing import List, Optional

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.findings import Finding
from stewart_kinematics.limits.base import PoseLegs
from stewart_kinematics.limits.joint_cones import JointCones
from stewart_kinematics.limits.limit_model import LimitChecks, LimitModel
from stewart_kinematics.limits.violation import Violation
from stewart_kinematics.model.arrays import as_float_array
from stewart_kinematics.model.inputs import as_leg_lengths, as_poses

#: How many failing samples :func:`check_samples` lists in full.
LISTED_FAILURES = 10


def check_pose(geometry, position, rotation, condition=None) -> List[Violation]:
    """
    Every limit that one pose breaks; empty when the pose is allowed.

    See :meth:`LimitModel.check_pose <stewart_kinematics.limits.LimitModel.check_pose>`.
    """
    return LimitModel.of_geometry(geometry).check_pose(position, rotation, condition=condition)


def check_poses_array(geometry, poses, *, condition_of_refused=True) -> LimitChecks:
    """
    Every limit that each of a batch of poses breaks, vectorised.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
    :param condition_of_refused: with False, the dear limits (singularity margin, leg
        collisions) only where the stroke and the cones pass (see ``every_reason`` of
        :meth:`LimitModel.check_poses <stewart_kinematics.limits.LimitModel.check_poses>`).
    :returns: a :class:`LimitChecks`; ``.violations(k)`` gives pose k's :class:`Violation` list.
    :raises ValueError: if a pose has the wrong shape or a non-finite value.

    >>> import numpy as np
    >>> from stewart_kinematics import load_geometry
    >>> from stewart_kinematics.limits import check_poses_array
    >>> geometry = load_geometry(['config/paper_platform.yaml', 'config/example_limits.yaml'])
    >>> poses = geometry.home_pose + [[0.0, 0, 0, 0, 0, 0], [0, 0, 0.2, 0, 0, 0],
    ...                               [0.1, 0, 0, 0, 0, 0]]
    >>> checks = check_poses_array(geometry, poses)
    >>> checks.allowed, checks.excess('leg_length_max').max(axis=-1).round(6)
    (array([ True, False,  True]), array([-0.181145,  0.01638 , -0.15812 ]))
    >>> print(checks.violations(1)[0])
    leg 1: leg_length_max 0.9 m broken by 0.01638 m (value 0.91638 m)
    """
    return LimitModel.of_geometry(geometry).check_poses(poses, every_reason=condition_of_refused)


def check_poses(geometry, poses) -> List[List[Violation]]:
    """
    Every limit that each of a batch of poses breaks, as lists.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (N, 6) or (6,).
    :returns: one list per pose, empty for an allowed pose, as :func:`check_pose` gives it.
    """
    checks = check_poses_array(geometry, poses)
    return [checks.violations(index) if not allowed else []
            for index, allowed in enumerate(checks.allowed.tolist())]


def leg_length_violations(geometry, lengths) -> List[Violation]:
    """
    Every leg length outside ``[leg_length_min, leg_length_max]``.

    :param lengths: leg lengths l_1..l_6 in metres, shape (6,).
    :raises ValueError: if the lengths are not six finite, positive numbers.
    """
    lengths = as_leg_lengths(lengths)
    if lengths.shape != (6,):
        raise ValueError(f'expected the 6 lengths of one pose, got shape {lengths.shape}')
    return LimitModel.of_geometry(geometry).leg_state_violations(lengths=lengths)


def joint_angles(geometry, position, rotation):
    """
    Cone angles of the joints: each leg's angle to its home direction, radians.

    :param position: platform position in the base frame, metres, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation, shape (3, 3) or (N, 3, 3).
    :returns: ``(base_angles, platform_angles)``, each shape (6,) or (N, 6): at the base joint
        measured in the base frame, at the platform joint measured in the platform frame; NaN
        for a leg of zero length.
    """
    position = as_float_array(position, 'position')
    rotation = as_float_array(rotation, 'rotation')
    if (position.shape[-1:] != (3,) or position.ndim > 2
            or rotation.shape != position.shape[:-1] + (3, 3)):
        raise ValueError(f'expected positions (3,) or (N, 3) and rotations (3, 3) or (N, 3, 3), '
                         f'got shapes {position.shape} and {rotation.shape}')
    single = position.ndim == 1
    legs = PoseLegs.of_matrices(geometry, np.atleast_2d(position),
                                rotation.reshape(-1, 3, 3))
    base, platform = JointCones(geometry).angles(legs)
    return (base[:, 0], platform[:, 0]) if single else (base.T, platform.T)


def check_samples(geometry, times, poses, what: str = 'ramp') -> Optional[Finding]:
    """
    Refuse a sampled motion any of whose samples breaks a limit of ``geometry``.

    trajectory_node checks every pose of its ramp with this before it plays it.

    :param times: seconds from the start of a pass, shape (N,).
    :param poses: the samples, ``[X, Y, Z, alpha, beta, gamma]``, shape (N, 6).
    :param what: what is refused, for the message.
    :returns: ``None`` when every sample is allowed; else an ``out_of_limits`` finding that
        lists the failing samples (time, pose, every violation; the first
        :data:`LISTED_FAILURES`), with the count and the first failing time in its details.
    """
    poses = np.atleast_2d(as_poses(poses))
    checks = check_poses_array(geometry, poses)
    failing = np.flatnonzero(~checks.allowed)
    if not failing.size:
        return None
    lines = [f'sample {index} at t={times[index]:.3f} s, pose '
             f'{np.round(poses[index], 6).tolist()}: '
             + '; '.join(map(str, checks.violations(index)))
             for index in failing[:LISTED_FAILURES]]
    more = len(failing) - LISTED_FAILURES
    first = checks.violations(failing[0])
    return Finding(
        findings.OUT_OF_LIMITS,
        f'{what} refused: {len(failing)} of {len(poses)} samples break the limits of the '
        'geometry:\n  ' + '\n  '.join(lines) + (f'\n  ... and {more} more' if more > 0 else ''),
        (('failing_samples', f'{len(failing)} of {len(poses)}'),
         ('first_failing_time_s', f'{times[failing[0]]:.3f}'))
        + findings.violation_details(first))
