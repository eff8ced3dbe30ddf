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
How the fuzzer and the soak start a node: its parameter files, and what plausible input is.

:func:`parameter_files` chooses the files as a node's documentation starts it (the geometry
and limits, then every other file of ``config/`` with a section for the node by name);
:func:`plausible_hints` reads from the same files what a plausible message carries (home pose
and leg lengths, joint and frame names).
"""

from pathlib import Path
from typing import List, Optional

from fuzzing.fuzz_messages import Plausible
import rclpy

from stewart_kinematics.parameters import (
    ActuatorSettings,
    geometry_from_parameters,
    read_parameter_files,
)
from stewart_kinematics.parameters.files import read_parameter_sections

#: The geometry and limits every node is fuzzed with, from the package's config/ folder.
GEOMETRY_FILES = ('paper_platform.yaml', 'example_limits.yaml')
#: Optional layers over a node's own file, not how its documentation starts it: the MPC with a
#: preview (test_fuzz_nodes fuzzes motion_cueing_node with it in a run of its own).
OPTIONAL_LAYERS = ('motion_cueing_preview.yaml',)


def config_directory() -> Path:
    """Return the package's config/ folder (installed or in the source tree)."""
    from stewart_kinematics.tools.ramp_demo import default_config_directory
    return default_config_directory()


def parameter_files(node: str, directory: Optional[Path] = None) -> List[Path]:
    """
    Return the parameter files a node is fuzzed with: geometry and limits, then its own.

    Its own: every other file of ``config/`` with a section for the node by name (such as
    ``table3_ramp.yaml`` for trajectory_node), so a node added later with its own file is
    started as its documentation starts it; but not a file of another platform (one that
    sets joints, such as ``platform_6_3.yaml``), which replaces the geometry rather than adds
    to it, nor an optional layer (:data:`OPTIONAL_LAYERS`).
    """
    directory = directory or config_directory()
    files = [directory / name for name in GEOMETRY_FILES]
    for path in sorted(directory.glob('*.yaml')):
        sections = read_parameter_sections(path)
        if path.name not in GEOMETRY_FILES + OPTIONAL_LAYERS and any(
                key.strip('/') == node for key in sections) and not _sets_joints(sections):
            files.append(path)
    return files


def _sets_joints(sections) -> bool:
    """Whether a file's sections (name -> parameters) set a platform's joints."""
    return any(name in parameters for parameters in sections.values()
               for name in ('base_joints', 'platform_joints'))


def plausible_hints(files, node: str) -> Plausible:
    """Return the :class:`Plausible` hints of the platform the parameter files describe."""
    values = read_parameter_files(files, node)
    geometry = geometry_from_parameters(values)
    actuators = ActuatorSettings.from_values(values)
    frames = [values.get(name) or default for name, default in (
        ('base_frame', 'stewart_base'), ('platform_frame', 'stewart_platform'))]
    frames += [values[name] for name in ('user_frame', 'tool_frame') if values.get(name)]
    clock = rclpy.clock.Clock()

    def stamp():
        return clock.now().seconds_nanoseconds()

    return Plausible(
        home_position=tuple(geometry.home_pose[:3].tolist()),
        home_leg_lengths=tuple(geometry.home_leg_lengths.tolist()),
        actuator_offsets=tuple(actuators.actuator_offsets), joint_names=tuple(
            actuators.joint_names), frames=tuple(frames), stamp=stamp)
