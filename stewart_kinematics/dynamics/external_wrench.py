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
The external wrench on the platform, from measured leg forces: a force sensor from the actuators.

What the legs push beyond what the model needs (:func:`~.inverse_dynamics.leg_forces` of the
pose, with the masses the model knows) balances a load the model does not know: an unmodelled
payload, a contact, a hand. :func:`external_wrench` gives that load as the wrench it applies to
the platform, in the **platform frame**, its moment **about the platform frame's origin**, as a
force-torque sensor fixed to the platform would report it (doc/dynamics.md).
"""

import numpy as np

from stewart_kinematics.dynamics.inverse_dynamics import leg_forces, platform_wrench
from stewart_kinematics.model.arrays import check_finite_output, preview
from stewart_kinematics.model.inputs import as_poses, as_rows
from stewart_kinematics.model.rotations import euler_zyx_to_matrix


def external_wrench(geometry, poses, measured_forces, twists=None, accelerations=None, *,
                    mass_properties=None) -> np.ndarray:
    """
    Wrench that the environment applies to the platform, from the measured leg forces.

    ``w_ext = -J^T (f_measured - f_model)``, with ``f_model`` the forces the model needs at the
    pose (:func:`~.inverse_dynamics.leg_forces`, statics unless ``twists`` and
    ``accelerations`` are given), then turned from the base frame into the platform frame. An
    unmodelled payload of mass ``m`` whose centre of mass is at ``c`` (platform frame) gives its
    weight ``m R^T g`` and the moment ``c x m R^T g``. At rest with efforts equal to the
    model's forces it is 0. A platform that moves while the model is given no twists and
    accelerations adds its own inertial forces to the wrench.

    :param geometry: a :class:`stewart_kinematics.Geometry`; its masses are the model's.
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
    :param measured_forces: the actuators' axial forces f_1..f_6, newtons, positive pushing the
        platform away from the base, shape (6,) or (N, 6).
    :param twists: ``[v, w]`` as :func:`~.inverse_dynamics.leg_forces` takes it, or ``None``:
        at rest.
    :param accelerations: ``[dv/dt, dw/dt]``, or ``None``: zero.
    :param mass_properties: the model's masses (``None``: the geometry's).
    :returns: ``[Fx, Fy, Fz, Mx, My, Mz]``: the force (N) and its moment (N m) about the
        platform frame's origin, both in the platform frame; shape (6,) or (N, 6).
    :raises ValueError: if an argument is malformed or not finite, the pose is singular (no
        forces balance the load there), or the wrench overflows.

    >>> from stewart_kinematics import leg_forces, load_geometry, MassProperties, RigidBody
    >>> geometry = load_geometry('config/paper_platform.yaml')
    >>> pose = [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0]
    >>> payload = MassProperties(payload=RigidBody(20.0, [0.0, 0.0, 0.1], name='payload'))
    >>> measured = leg_forces(geometry, pose, mass_properties=payload)
    >>> external_wrench(geometry, pose, measured).round(6) + 0.0   # the model has no payload
    array([   0.   ,    0.   , -196.133,    0.   ,    0.   ,    0.   ])
    """
    measured = as_rows(measured_forces, 'measured_forces')
    if not np.all(np.isfinite(measured)):
        raise ValueError('measured_forces must be finite (N, one per leg), got '
                         f'{preview(measured.tolist())}')
    model = leg_forces(geometry, poses, twists, accelerations, mass_properties=mass_properties)
    try:
        np.broadcast_shapes(model.shape, measured.shape)
    except ValueError:
        raise ValueError(f'poses {model.shape} and measured_forces {measured.shape} must hold '
                         'the same number of rows, or one of them a single one') from None
    with np.errstate(all='ignore'):   # an overflow is refused below
        excess = measured - model
    excess = check_finite_output(excess, 'the measured forces minus the model forces',
                                 'the measured forces')
    wrench = platform_wrench(geometry, poses, -excess)
    rotations = euler_zyx_to_matrix(as_poses(poses)[..., 3:])
    wrench = np.broadcast_to(wrench, np.broadcast_shapes(wrench.shape, excess.shape))
    with np.errstate(all='ignore'):
        # R^T F and R^T M: each row of R^T is a column of R.
        force = np.einsum('...ji,...j->...i', rotations, wrench[..., :3])
        moment = np.einsum('...ji,...j->...i', rotations, wrench[..., 3:])
    return check_finite_output(np.concatenate([force, moment], axis=-1), 'the external wrench',
                               'the measured forces')
