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
The cue's commands with masses (issue 29): never beyond the leg force limit, whatever the input.

:class:`~stewart_kinematics.cueing.MotionCueing` with the example masses and a leg force limit
that the cue's motion would break, fed the adversarial input of issue 27 (specific force noise
of 30 m/s^2 around gravity, rotation noise of 5 rad/s, at 100 Hz). The forces of each command
are computed here independently: the platform pose of each ``target_pose`` message, its twist
and acceleration by finite differences at the send times (rotation vectors by scipy), and
:func:`stewart_kinematics.leg_forces` of those.
"""

from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference
from scipy.spatial.transform import Rotation

from stewart_kinematics import leg_forces, load_geometry
from stewart_kinematics.cueing import MotionCueing
from stewart_kinematics.model.rotations import quaternion_to_matrix
from stewart_kinematics.parameters import read_parameter_files

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml',
         CONFIG / 'motion_cueing.yaml', CONFIG / 'example_masses.yaml']
G = 9.80665
#: The unlimited cue of this input asks about 300 N of a leg; at rest at home about 56 N.
FORCE_MAX = 110.0
STEPS = 600


def run(count=STEPS, **overrides):
    """Feed the noisy input; return the send times, the sent poses and the steps."""
    values = read_parameter_files(FILES, 'motion_cueing_node')
    values.update(overrides)
    motion = MotionCueing.from_parameters(values)
    rng = np.random.default_rng(1)
    times, poses, steps = [], [], []
    for k in range(count):
        step = motion.cue(k * 0.01, [0.0, 0.0, G] + rng.normal(0.0, 30.0, 3),
                          rng.normal(0.0, 5.0, 3))
        assert step.command.accepted, step.command.refusal
        position, quaternion = step.command.tool_pose
        rotation = quaternion_to_matrix(quaternion / np.linalg.norm(quaternion))
        times.append(k * 0.01)
        poses.append((position, rotation))
        steps.append(step)
    return np.array(times), poses, steps


def independent_forces(times, poses):
    """Leg forces of sent poses at their send times (from rest), by finite differences."""
    masses = load_geometry(FILES).mass_properties
    positions = np.array([position for position, _ in poses])
    rotations = Rotation.from_matrix(np.array([rotation for _, rotation in poses]))
    vectors = np.concatenate([positions, rotations.as_euler('ZYX')[:, ::-1]], axis=1)
    assert_allclose(reference.rotations_zyx(vectors[:, 3:]), rotations.as_matrix(), atol=1e-12)
    steps = np.diff(times)
    twists = np.zeros(vectors.shape)
    twists[1:, :3] = np.diff(positions, axis=0) / steps[:, None]
    twists[1:, 3:] = (rotations[1:] * rotations[:-1].inv()).as_rotvec() / steps[:, None]
    spans = 0.5 * (steps + np.concatenate([[steps[0]], steps[:-1]]))
    accelerations = np.zeros(vectors.shape)
    accelerations[1:] = np.diff(twists, axis=0) / spans[:, None]
    return leg_forces(load_geometry(CONFIG / 'paper_platform.yaml'), vectors, twists,
                      accelerations, mass_properties=masses)


@pytest.fixture(scope='module')
def limited():
    """Return the noisy input's commands with leg_force_max set."""
    return run(leg_force_max=FORCE_MAX)


def test_without_the_force_limit_the_cue_asks_more():
    """The same input, unlimited, breaks leg_force_max: the limit has work to do."""
    times, poses, steps = run(200)
    forces = independent_forces(times, poses)
    assert forces.max() > FORCE_MAX + 50.0
    assert_allclose(np.array([step.command.forces for step in steps]), forces, atol=0.01)


def test_noisy_input_with_masses_never_yields_a_command_beyond_the_force_limit(limited):
    times, poses, steps = limited
    forces = independent_forces(times, poses)
    assert forces.max() <= FORCE_MAX + 0.01
    # Each command's forces are those of its pose sent, with the motion's twist and acceleration.
    assert_allclose(np.array([step.command.forces for step in steps]), forces, atol=0.01)
    assert np.all(np.array([step.command.forces for step in steps]) <= FORCE_MAX)


def test_what_the_force_limit_changed_is_said_naming_the_legs(limited):
    _, _, steps = limited
    named = [finding for step in steps for finding in step.warnings
             if finding.code in ('force_limited', 'command_braking')
             and 'leg_force_max' in finding.message]
    assert named
    assert all(any(key.startswith('leg_force_max leg') for key, _ in finding.details)
               for finding in named)
