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
The calibration's model: its parameters, their layout, and the actuator readings they predict.

42 parameters, in :data:`PARAMETER_NAMES` order: the six base joints ``b_i`` (base frame), the
six platform joints ``p_i`` (platform frame) and the six actuator offsets ``o_i``, all metres.
At a pose ``[X, Y, Z, alpha, beta, gamma]`` actuator i reads ``a_i = |t + R p_i - b_i| - o_i``.
Joints that two legs share are one point (:class:`ParameterLayout`). The fit and what poses can
determine are in :mod:`.calibration`, which uses these functions.
"""

from dataclasses import dataclass
from typing import Tuple

import numpy as np

from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.model.inputs import as_poses
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

#: Parameters of one leg: base joint (3), platform joint (3), actuator offset (1).
PARAMETERS_PER_LEG = 7
#: All parameters: 18 base joint coordinates, 18 platform joint coordinates, 6 offsets (fewer
#: are free where legs share a joint: see ParameterLayout).
PARAMETER_COUNT = 6 * PARAMETERS_PER_LEG
#: The names of the 42 parameters, in the order of
#: :attr:`.calibration.CalibrationResult.parameters`.
PARAMETER_NAMES = tuple(
    [f'b{leg}.{axis}' for leg in range(1, 7) for axis in 'xyz']
    + [f'p{leg}.{axis}' for leg in range(1, 7) for axis in 'xyz']
    + [f'o{leg}' for leg in range(1, 7)])
#: Column positions of leg i's seven parameters in the 42-vector.
LEG_COLUMNS = np.array([[3 * leg, 3 * leg + 1, 3 * leg + 2,
                         18 + 3 * leg, 18 + 3 * leg + 1, 18 + 3 * leg + 2, 36 + leg]
                        for leg in range(6)])


@dataclass(frozen=True)
class ParameterLayout:
    """
    Which of the 42 parameters are free: a joint that two legs share is one point.

    :param index: shape (42,): for each parameter in :data:`PARAMETER_NAMES` order, its column
        among the free parameters (two legs' coordinates of a shared joint, one column).
    :param names: the free parameters' names: ``b1.x`` as in :data:`PARAMETER_NAMES`, and
        ``b1,2.x`` for the base joint that legs 1 and 2 share (``p`` for the platform's).
    :param blocks: the legs (1..6) fitted together: legs tied by shared joints, each leg alone
        on a 6-6 platform. The identification Jacobian is block diagonal by them.
    """

    index: np.ndarray
    names: Tuple[str, ...]
    blocks: Tuple[Tuple[int, ...], ...]

    @property
    def count(self) -> int:
        """Return the number of free parameters (42 on a 6-6 platform, 24 on a 3-3 one)."""
        return len(self.names)

    @property
    def tied(self) -> Tuple[str, ...]:
        """Return the names of the free parameters that stand for a shared joint's coordinates."""
        return tuple(name for name in self.names if ',' in name)

    def columns(self, block: Tuple[int, ...]) -> np.ndarray:
        """Return the free columns of a block's parameters, ascending."""
        return np.unique(self.index[LEG_COLUMNS[np.array(block) - 1]])

    def expand(self, free) -> np.ndarray:
        """Return the 42 parameters of the free ones (a shared joint's copied to both legs)."""
        return np.asarray(free)[..., self.index]

    def reduce(self, parameters) -> np.ndarray:
        """Return the free parameters of 42 (a shared joint: the lower leg's coordinates)."""
        first = np.array([np.flatnonzero(self.index == column)[0]
                          for column in range(self.count)])
        return np.asarray(parameters, dtype=float)[first]

    def tie(self, jacobian) -> np.ndarray:
        """Return the identification Jacobian (rows, 42) in the free parameters (rows, n)."""
        tied = np.zeros((jacobian.shape[0], self.count))
        for column, free in enumerate(self.index):
            tied[:, free] += jacobian[:, column]
        return tied


def parameter_layout(geometry: Geometry) -> ParameterLayout:
    """
    Return the free parameters of a geometry: its shared joints tied, the rest one each.

    >>> from stewart_kinematics import load_geometry
    >>> from stewart_kinematics.analysis.calibration_model import parameter_layout
    >>> layout = parameter_layout(load_geometry('config/platform_3_3.yaml'))
    >>> layout.count, layout.blocks
    (24, ((1, 2, 3, 4, 5, 6),))
    >>> layout.tied[:4]
    ('b1,2.x', 'b1,2.y', 'b1,2.z', 'b3,4.x')
    """
    owner = np.arange(PARAMETER_COUNT)
    component = list(range(6))
    for joint in geometry.shared_joints:
        first, second = joint.legs[0] - 1, joint.legs[1] - 1
        offset = 0 if joint.side == 'base' else 18
        owner[offset + 3 * second:offset + 3 * second + 3] = owner[
            offset + 3 * first:offset + 3 * first + 3]
        old, new = component[second], component[first]
        component = [new if c == old else c for c in component]
    representatives, index = np.unique(owner, return_inverse=True)
    names = []
    for representative in representatives:
        legs = [column // 3 % 6 + 1 for column in np.flatnonzero(owner == representative)]
        name = PARAMETER_NAMES[representative]
        if len(legs) > 1:
            name = name[0] + ','.join(map(str, legs)) + name[name.index('.'):]
        names.append(name)
    blocks = {}
    for leg, c in enumerate(component):
        blocks.setdefault(c, []).append(leg + 1)
    return ParameterLayout(index=index, names=tuple(names),
                           blocks=tuple(tuple(legs) for legs in blocks.values()))


def predict_actuator_positions(geometry: Geometry, actuator_offsets, poses) -> np.ndarray:
    """
    Predict actuator positions at poses: leg lengths minus the actuator offsets.

    :param geometry: the platform.
    :param actuator_offsets: o_1..o_6, metres, shape (6,).
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (N, 6).
    :returns: metres, shape (N, 6).
    """
    parameters = parameter_vector(geometry, actuator_offsets)
    poses = np.atleast_2d(as_poses(poses))
    return predicted_positions(parameters, poses[:, :3], euler_zyx_to_matrix(poses[:, 3:]))


def parameter_vector(geometry: Geometry, actuator_offsets) -> np.ndarray:
    """Return the 42 parameters of a geometry and its actuator offsets (metres)."""
    offsets = np.asarray(actuator_offsets, dtype=float)
    if offsets.shape != (6,) or not np.all(np.isfinite(offsets)):
        raise ValueError(f'actuator offsets must be 6 finite values (metres), got '
                         f'{preview(offsets)}')
    return np.concatenate([geometry.base_joints.ravel(), geometry.platform_joints.ravel(),
                           offsets])


def leg_vectors(values, positions, rotations):
    """Return one leg's vectors ``t + R p - b`` (N, 3), metres, base frame, of its [b, p, o]."""
    return np.einsum('kab,b->ka', rotations, values[3:6]) + positions - values[:3]


def leg_lengths(values, positions, rotations):
    """Return one leg's lengths (N,), metres, of its seven parameters at N poses."""
    return np.linalg.norm(leg_vectors(values, positions, rotations), axis=-1)


def leg_jacobian(values, positions, rotations):
    """Return d(actuator reading) / d(one leg's seven parameters), (N, 7): -u, R^T u, -1."""
    legs = leg_vectors(values, positions, rotations)
    directions = legs / np.linalg.norm(legs, axis=-1, keepdims=True)
    jac = np.empty((positions.shape[0], PARAMETERS_PER_LEG))
    jac[:, :3] = -directions
    jac[:, 3:6] = np.einsum('kba,kb->ka', rotations, directions)
    jac[:, 6] = -1.0
    return jac


def predicted_positions(parameters, positions, rotations):
    """Return the actuator positions (N, 6) of the 42 parameters at N poses."""
    return np.stack([leg_lengths(parameters[columns], positions, rotations)
                     - parameters[columns[6]] for columns in LEG_COLUMNS], axis=1)


def identification_jacobian(parameters, positions, rotations):
    """Return the identification Jacobian (6N, 42): leg blocks on its diagonal, row 6k + i."""
    count = positions.shape[0]
    jac = np.zeros((count, 6, PARAMETER_COUNT))
    for leg, columns in enumerate(LEG_COLUMNS):
        jac[:, leg, columns] = leg_jacobian(parameters[columns], positions, rotations)
    return jac.reshape(count * 6, PARAMETER_COUNT)


def block_rows(jac, layout, legs):
    """Return a block's rows and columns of a tied Jacobian (6N, n): (N * legs, columns)."""
    rows = jac.reshape(-1, 6, layout.count)[:, np.array(legs) - 1]
    return rows.reshape(-1, layout.count)[:, layout.columns(legs)]
