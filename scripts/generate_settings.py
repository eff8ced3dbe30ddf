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
Write the settings classes out as code, from the parameter specs.

stewart_kinematics/parameters/settings.py holds one frozen dataclass per parameter
group (one typed field per parameter, with its default and its description, unit and allowed
values as the field's docstring) and one per node (one field per group), so that an IDE and a
type checker see every field. The file is checked in; test/parameters/test_settings.py
regenerates it in memory and fails when it differs. Run after changing a spec in
parameters/declarations.py, or a group below::

    .venv/bin/python scripts/generate_settings.py          # rewrite the file
    .venv/bin/python scripts/generate_settings.py --check  # exit 1 if it is out of date
"""

import argparse
import importlib
import math
from pathlib import Path
import sys
import textwrap
import types

ROOT = Path(__file__).resolve().parent.parent


def import_declarations():
    """
    Import parameters/declarations.py, without the package's ``__init__`` if not imported yet.

    The package imports the generated file, which may be out of date (a group renamed): the
    script must run all the same, so it reads the declarations (and what they import: the
    specs, model/) alone.
    """
    if 'stewart_kinematics' not in sys.modules:
        sys.path.insert(0, str(ROOT))
        for name in ('stewart_kinematics', 'stewart_kinematics.parameters'):
            package = types.ModuleType(name)
            package.__path__ = [str(ROOT.joinpath(*name.split('.')))]
            sys.modules[name] = package
    return importlib.import_module('stewart_kinematics.parameters.declarations')


declarations = import_declarations()
BOOL, INTEGER, DOUBLE, STRING, DOUBLE_ARRAY, STRING_ARRAY = (
    'bool', 'integer', 'double', 'string', 'double_array', 'string_array')

#: The file this script writes.
TARGET = ROOT / 'stewart_kinematics' / 'parameters' / 'settings.py'
#: The longest line (ament flake8).
MAX_LINE = 99

#: The parameter groups: class name, the declarations' tuple of specs, what the group configures.
GROUPS = (
    ('GeometrySettings', 'GEOMETRY_PARAMETERS',
     'The platform: joints, home pose, and every limit (stroke, joint cones, singularity '
     'margin, leg speed); :func:`~stewart_kinematics.parameters.builders.geometry_from_settings` '
     'builds the Geometry.'),
    ('ActuatorSettings', 'ACTUATOR_PARAMETERS',
     'The actuators as a driver names them: joint names and zeros.'),
    ('SolverSettings', 'SOLVER_PARAMETERS',
     "The forward kinematics solver and the pose tracker's checks (fk_node)."),
    ('AssemblyModeSettings', 'ASSEMBLY_MODE_PARAMETERS',
     'The assembly-mode margin that fk_node reports.'),
    ('FrameSettings', 'FRAME_PARAMETERS',
     'The base, platform, user and tool frames; '
     ':func:`~stewart_kinematics.parameters.builders.frames_from_settings` builds the '
     'FrameTree.'),
    ('FkFrameSettings', 'FK_FRAME_PARAMETERS', "fk_node's broadcast of the estimated pose."),
    ('IkFrameSettings', 'IK_FRAME_PARAMETERS', "ik_node's broadcast of the commanded pose."),
    ('MarkerSettings', 'MARKER_PARAMETERS', 'The RViz markers.'),
    ('WorkspaceSettings', 'WORKSPACE_PARAMETERS', "ik_node's workspace outputs."),
    ('QueueSettings', 'QUEUE_PARAMETERS', 'The queues of every subscription and publisher.'),
    ('LifecycleSettings', 'LIFECYCLE_PARAMETERS',
     'Whether a node runs managed (lifecycle); see '
     ':mod:`stewart_kinematics.ros.managed`.'),
    ('RampSettings', 'RAMP_PARAMETERS', 'The Table 3 ramp and how trajectory_node plays it.'),
    ('MotionSettings', 'MOTION_PARAMETERS',
     'Trajectories and paths received by trajectory_node: checking, retiming, playing.'),
    ('ActionSettings', 'ACTION_PARAMETERS',
     "trajectory_node's follow_joint_trajectory action: execution, feedback, joints and the "
     'default tolerances.'),
    ('StreamingSettings', 'STREAMING_PARAMETERS', "ik_node's streamed, jerk-limited commands."),
    ('CueingParameterSettings', 'MOTION_CUEING_PARAMETERS',
     "motion_cueing_node's washout, limit margins and input checks, as the node declares its "
     "parameters (degrees where named); not the motion cueing's own settings, "
     ':class:`stewart_kinematics.cueing.CueingSettings` (SI units), which '
     ':meth:`~stewart_kinematics.cueing.CueingSettings.from_parameters` builds from these.'),
    ('CueingControlSettings', 'CUEING_CONTROL_PARAMETERS',
     "motion_cueing_node's run-time controls: intensity and gain ramps, soft start and stop, "
     'park (:mod:`stewart_kinematics.cueing.controls`).'),
    ('MockPlatformSettings', 'MOCK_PLATFORM_PARAMETERS',
     "mock_platform's simulated legs: the commands they take, their lag, the joint states' "
     'rate, and the faults a test gives them.'),
)

#: The nodes: class name, what it is, and its groups (field name, class) in declaration order.
NODES = (
    ('IkNodeSettings',
     "ik_node's settings: one field per parameter group it declares, in that order.", (
        ('geometry', 'GeometrySettings'), ('actuators', 'ActuatorSettings'),
        ('frames', 'FrameSettings'), ('ik_frames', 'IkFrameSettings'),
        ('markers', 'MarkerSettings'), ('workspace', 'WorkspaceSettings'),
        ('streaming', 'StreamingSettings'), ('queue', 'QueueSettings'),
        ('lifecycle', 'LifecycleSettings'))),
    ('FkNodeSettings',
     "fk_node's settings: one field per parameter group it declares, in that order.", (
        ('geometry', 'GeometrySettings'), ('actuators', 'ActuatorSettings'),
        ('solver', 'SolverSettings'), ('assembly_modes', 'AssemblyModeSettings'),
        ('frames', 'FrameSettings'), ('fk_frames', 'FkFrameSettings'),
        ('markers', 'MarkerSettings'), ('queue', 'QueueSettings'),
        ('lifecycle', 'LifecycleSettings'))),
    ('MotionCueingNodeSettings',
     "motion_cueing_node's settings: one field per group it declares, in that order.", (
        ('geometry', 'GeometrySettings'), ('frames', 'FrameSettings'),
        ('cueing', 'CueingParameterSettings'), ('controls', 'CueingControlSettings'),
        ('queue', 'QueueSettings'), ('lifecycle', 'LifecycleSettings'))),
    ('TrajectoryNodeSettings',
     "trajectory_node's settings: one field per group it declares, in that order.", (
        ('geometry', 'GeometrySettings'), ('actuators', 'ActuatorSettings'),
        ('frames', 'FrameSettings'), ('ramp', 'RampSettings'), ('motion', 'MotionSettings'),
        ('action', 'ActionSettings'), ('queue', 'QueueSettings'),
        ('lifecycle', 'LifecycleSettings'))),
    ('MockPlatformNodeSettings',
     "mock_platform's settings: one field per parameter group it declares, in that order.", (
        ('geometry', 'GeometrySettings'), ('actuators', 'ActuatorSettings'),
        ('mock', 'MockPlatformSettings'), ('queue', 'QueueSettings'))),
)

#: The annotation of each parameter type.
FIELD_TYPES = {
    BOOL: 'bool',
    INTEGER: 'int',
    DOUBLE: 'float',
    STRING: 'str',
    DOUBLE_ARRAY: 'Tuple[float, ...]',
    STRING_ARRAY: 'Tuple[str, ...]',
}

HEADER = '''\
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

# GENERATED FILE: do not edit. Written by scripts/generate_settings.py from the parameter specs
# of stewart_kinematics/parameters/declarations.py; after changing a spec, run
#     .venv/bin/python scripts/generate_settings.py
# (test/parameters/test_settings.py fails until this file is what the script writes).

"""
The settings classes, written out from the parameter specs: one per parameter group, one per node.

Generated (see the comment above): each field of a group is one parameter, with its type, its
default and its description, unit and allowed values, so that an IDE and a type checker see
every field; a field without a default is a required parameter. Each node's class has one field
per group it declares. The behaviour (every value checked by its spec's validators when an
object is made, :meth:`~stewart_kinematics.parameters.settings_base.Settings.from_values`,
``replace``, ``as_values``) is that of the base classes in
:mod:`stewart_kinematics.parameters.settings_base`.
"""

from dataclasses import dataclass
import math  # noqa: F401 - the defaults .inf are math.inf
from typing import ClassVar, Tuple

from stewart_kinematics.parameters import declarations
from stewart_kinematics.parameters.settings_base import NodeSettings, Settings
from stewart_kinematics.parameters.spec import ParameterSpec
'''


def literal(value) -> str:
    """Return the Python source of a default value (lists as tuples, ``math.inf``)."""
    if isinstance(value, (list, tuple)):
        items = [literal(item) for item in value]
        return '(' + ', '.join(items) + (',)' if len(items) == 1 else ')')
    if isinstance(value, float) and math.isinf(value):
        return 'math.inf' if value > 0 else '-math.inf'
    if isinstance(value, str):
        if "'" in value or '\\' in value:
            raise ValueError(f'a default string this script does not quote: {value!r}')
        return f"'{value}'"
    if isinstance(value, (bool, int, float)):
        return repr(value)
    raise ValueError(f'a default this script cannot write: {value!r}')


def docstring(text: str, indent: str) -> list:
    """Return the lines of a docstring: one line if it fits, else its text wrapped."""
    if '"""' in text or '\\' in text:
        raise ValueError(f'a text this script does not quote: {text!r}')
    one_line = f'{indent}"""{text}"""'
    if len(one_line) <= MAX_LINE:
        return [one_line]
    wrapped = textwrap.wrap(text, width=MAX_LINE - len(indent), break_long_words=False,
                            break_on_hyphens=False)
    return [f'{indent}"""'] + [indent + line for line in wrapped] + [f'{indent}"""']


def field_text(spec) -> str:
    """Return a field's docstring: the description, the allowed values, required, read-only."""
    text = spec.description.rstrip('.') + '.'
    if spec.constraints:
        text += f' Allowed: {spec.constraints}.'
    if spec.default is None:
        text += ' Required.'
    if spec.read_only:
        text += ' Read-only at run time.'
    return text


def field_lines(spec) -> list:
    """Return the lines of one field: its annotation, default and docstring."""
    annotation = f'    {spec.name}: {FIELD_TYPES[spec.value_type]}'
    if spec.default is not None:
        annotation += f' = {literal(spec.default)}'
    if len(annotation) > MAX_LINE:
        raise ValueError(f'{spec.name}: its line is longer than {MAX_LINE} characters')
    return [annotation] + docstring(field_text(spec), '    ')


def group_lines(name: str, attribute: str, text: str) -> list:
    """Return the lines of one group's class."""
    specs = getattr(declarations, attribute)
    lines = ['', '', '@dataclass(frozen=True, kw_only=True)', f'class {name}(Settings):',
             '    """',
             f'    One field per parameter of :data:`~stewart_kinematics.parameters.{attribute}`.',
             '', *(f'    {line}' for line in textwrap.wrap(
                 text, width=MAX_LINE - 4, break_long_words=False, break_on_hyphens=False)),
             '    """', '',
             f'    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.{attribute}']
    for spec in specs:
        lines += [''] + field_lines(spec)
    return lines


def node_lines(name: str, text: str, groups) -> list:
    """Return the lines of one node's class."""
    lines = ['', '', '@dataclass(frozen=True, kw_only=True)', f'class {name}(NodeSettings):',
             f'    """{text}"""', '']
    lines += [f'    {field}: {group}' for field, group in groups]
    return lines


def render() -> str:
    """Return the text of parameters/settings.py as the specs make it."""
    lines = HEADER.splitlines()
    for group in GROUPS:
        lines += group_lines(*group)
    for node in NODES:
        lines += node_lines(*node)
    too_long = [line for line in lines if len(line) > MAX_LINE]
    if too_long:
        raise ValueError(f'lines longer than {MAX_LINE} characters: {too_long}')
    return '\n'.join(lines) + '\n'


def main(argv=None) -> int:
    """Write the file, or with ``--check`` say whether it is up to date (exit 1 if not)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--check', action='store_true',
                        help='write nothing; exit 1 if the file is not what would be written')
    arguments = parser.parse_args(argv)
    text = render()
    current = TARGET.read_text(encoding='utf-8') if TARGET.is_file() else ''
    name = TARGET.relative_to(ROOT)
    if arguments.check:
        print(f'{name} is up to date' if current == text else
              f'{name} is out of date: run scripts/generate_settings.py')
        return 0 if current == text else 1
    if current != text:
        TARGET.write_text(text, encoding='utf-8')
    print(f'{name} written' if current != text else f'{name} already up to date')
    return 0


if __name__ == '__main__':
    sys.exit(main())
