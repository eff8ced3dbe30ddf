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
The documentation's own Sphinx extension: tables generated from the code, and completeness checks.

- ``{parameter-table} GROUP`` renders the parameter group ``GROUP`` (``GEOMETRY``, ``SOLVER``,
  ...) from its specs when the site is built, so a page cannot drift from the declarations.
- ``{refusal-codes}`` renders every code the package emits, from :func:`refusal_codes`.
- Every public name of the package root must be documented as ``stewart_kinematics.<name>``
  (:func:`public_names`): the build warns, and so fails under ``-W``, when one is missing.

Loaded by ``doc/conf.py``'s ``setup()``.
"""

import ast
from pathlib import Path
import re

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)

PACKAGE = 'stewart_kinematics'


def package_directory() -> Path:
    """Return the folder of the imported package (the repository's, in an editable install)."""
    import stewart_kinematics
    return Path(stewart_kinematics.__file__).resolve().parent


def public_names() -> list:
    """Every public name of the package root: ``__all__`` and the lazily imported names."""
    import stewart_kinematics
    names = list(stewart_kinematics.__all__)
    names += [name for name in getattr(stewart_kinematics, '_CALIBRATION_NAMES', ())
              if name not in names]
    return names


def parameter_groups() -> dict:
    """Return ``{GROUP: specs}`` for every ``GROUP_PARAMETERS`` tuple of the declarations."""
    from stewart_kinematics.parameters import declarations
    return {name[:-len('_PARAMETERS')]: value for name, value in vars(declarations).items()
            if name.endswith('_PARAMETERS') and isinstance(value, tuple)}


def parameter_table(group: str) -> str:
    """Return the Markdown table of one parameter group, as the specs render it."""
    from stewart_kinematics.parameters import markdown_table
    table = markdown_table(parameter_groups()[group])
    # A description may say `<platform_frame>_commanded`: outside code spans, escape '<' so
    # that Markdown shows it rather than taking it for an HTML tag.
    return re.sub(r'(`[^`]*`)|<', lambda match: match.group(1) or r'\<', table)


#: Where the codes are defined today, read from the source (the ROS modules are not imported):
#: every string constant of findings.py, and the named ones of the other modules.
CODE_SOURCES = {
    'findings.py': None,
    'ros/ik_node.py': ('WRONG_FRAME',),
    'ros/trajectory_node.py': ('TOOL_FRAME_NOT_SUPPORTED',),
}

#: What each code means and who emits it, until the registry of issue 18 carries both.
MEANINGS = {
    'invalid_pose': (
        '`CommandCheck` (ik_node: `target_pose`, `target_pose_stamped`)',
        'A pose with a NaN or infinite coordinate, a zero or NaN quaternion, or the wrong '
        'shape.'),
    'invalid_twist': (
        '`CommandCheck.twist` (ik_node: `target_twist`)',
        'A twist that is not six finite numbers.'),
    'invalid_lengths': (
        '`PoseTracker` (fk_node: `leg_lengths`, `joint_states`)',
        'Leg lengths that are not six finite, positive numbers (or a malformed message).'),
    'invalid_velocities': (
        '`PoseTracker.twist` (fk_node: `leg_velocities`, `joint_states`)',
        'Leg velocities that are not six finite numbers.'),
    'out_of_limits': (
        '`CommandCheck`, `PoseTracker`, `plan_motion` (every node)',
        'A pose, a set of leg lengths or a trajectory sample that breaks a limit (stroke, joint '
        'cone, singularity margin); every violation is listed with the leg, the value and the '
        'limit.'),
    'unreachable': (
        '`CommandCheck` (ik_node)',
        'A pose whose leg lengths are not finite and positive: a platform joint on its base '
        'joint, or a pose so far away that the lengths overflow.'),
    'no_pose_yet': (
        '`CommandCheck.twist` (ik_node: `target_twist`)',
        'A twist before any pose was accepted: there is no pose to apply it at.'),
    'no_solution': (
        '`PoseTracker` (fk_node)',
        'Forward kinematics found no solution (iteration limit, singular Jacobian, '
        'divergence), with the iterations and the residual.'),
    'inaccurate_pose': (
        '`PoseTracker` (fk_node)',
        'A converged solution whose `pose_error_bound` exceeds `pose_tolerance`: near a '
        'singularity the lengths fix the pose only loosely.'),
    'assembly_mode_jump': (
        '`PoseTracker` (fk_node)',
        'A solution more than `assembly_guard_position_change` or '
        '`assembly_guard_angle_change_deg` from the last one while no leg changed by more '
        'than `assembly_guard_length_change`.'),
    'ambiguous_assembly_mode': (
        '`PoseTracker` (fk_node, with `refuse_ambiguous_start`)',
        'After a start or `reset_tracker`, more than one assembly mode lies within the limits '
        "and none near the last known pose; with the number of modes and the nearest one's "
        'distance.'),
    'assembly_mode_margin': (
        'fk_node (a warning)',
        'Another real assembly mode within the limits lies closer than '
        '`assembly_mode_margin_warning` to the estimated pose.'),
    'near_singularity': (
        '`PoseTracker` (fk_node; a warning on a pose, a refusal of a twist)',
        "The Jacobian's condition number exceeds `near_singularity_condition`: the pose is "
        'published with a warning, and leg velocities are not turned into a twist there.'),
    'too_fast': (
        '`plan_motion`, `check_trajectory` (trajectory_node)',
        'A timed trajectory, not retimed, that breaks a leg velocity or acceleration limit, '
        'naming the time, the segment, the legs and the limits.'),
    'retiming_failed': (
        '`plan_motion` (trajectory_node)',
        'toppra found no timing of the path within the leg limits.'),
    'invalid_trajectory': (
        'trajectory_node (`pose_trajectory`, `pose_path`)',
        'A malformed trajectory or path: another frame, more than one joint, times not '
        'increasing, velocities on only some points, a turn of half a revolution or more '
        'between two waypoints, two equal consecutive waypoints of a path.'),
    'wrong_frame': (
        'ik_node (`target_pose_stamped`)',
        "A stamped pose in a frame other than `base_frame`, `user_frame` or `''`."),
    'tool_frame_not_supported': (
        'trajectory_node (`pose_trajectory`, `pose_path`)',
        'A trajectory or path received while the tool frame is offset from the platform frame '
        '(trajectories are planned for the platform frame).'),
    'invalid_vehicle_motion': (
        '`MotionCueing` (motion_cueing_node: `vehicle_imu`)',
        'A specific force or angular velocity that is not three finite numbers, or beyond '
        '`max_specific_force` or `max_angular_velocity`; the platform takes the step as if the '
        'vehicle were at rest, so that bad input eases it back to neutral.'),
    'time_not_increasing': (
        '`MotionCueing` (motion_cueing_node: `vehicle_imu`)',
        'A sample whose time (header.stamp) is not after the previous one: repeated, backward '
        'or not finite; nothing moves.'),
    'input_gap': (
        '`MotionCueing` (motion_cueing_node), a warning',
        'More than `max_input_gap` since the previous sample: counted as `max_input_gap` (the '
        "washout's clock pauses)."),
    'cue_scaled': (
        '`MotionCueing` (motion_cueing_node), a warning',
        'The cue was scaled toward neutral to keep inside the limits model (with its margins); '
        'the details give the workspace and tilt scales.'),
    'actuator_limited': (
        '`MotionCueing` (motion_cueing_node), a warning',
        'The cue asked more leg velocity or acceleration than the actuators allow: the platform '
        'followed as closely as they allow (or braked, or headed home).'),
    'limits_held': (
        '`MotionCueing` (motion_cueing_node), a warning',
        'Every next pose would have left the limits: the pose was held (not expected; the '
        'margins prevent it).'),
}


def _string_constants(path: Path, names) -> dict:
    """Return ``{NAME: value}`` of the module-level string constants of one source file."""
    found = {}
    for statement in ast.parse(path.read_text(encoding='utf-8')).body:
        if (isinstance(statement, ast.Assign) and len(statement.targets) == 1
                and isinstance(statement.targets[0], ast.Name)
                and isinstance(statement.value, ast.Constant)
                and isinstance(statement.value.value, str)):
            name = statement.targets[0].id
            if (names is None and name.isupper()) or (names is not None and name in names):
                found[name] = statement.value.value
    missing = set(names or ()) - set(found)
    if missing:
        raise ValueError(f'{path}: no string constant {sorted(missing)}')
    return found


def refusal_codes() -> list:
    """
    Every refusal or warning code the package can emit: ``(code, emitted by, meaning, where)``.

    The one source of the docs' table of codes. Today the codes are constants of three modules
    (:data:`CODE_SOURCES`) and their meanings are written here (:data:`MEANINGS`); when the
    registry of every code with its meaning exists (issue 18, in findings.py), read it here
    instead and drop both. Raises ``ValueError`` when a code has no meaning or a meaning no
    code, so the table cannot drift from the code.
    """
    directory = package_directory()
    where = {}
    for relative, names in CODE_SOURCES.items():
        module = f'{PACKAGE}.' + relative[:-len('.py')].replace('/', '.')
        for name, code in _string_constants(directory / relative, names).items():
            where.setdefault(code, f'{module}.{name}')
    undescribed = sorted(set(where) - set(MEANINGS))
    stale = sorted(set(MEANINGS) - set(where))
    if undescribed or stale:
        raise ValueError(f'refusal codes without a meaning: {undescribed}; meanings of codes '
                         f'that do not exist: {stale} (doc/ext/stewart_docs.py)')
    return [(code, *MEANINGS[code], where[code]) for code in where]


def refusal_codes_table() -> str:
    """Return the Markdown table of :func:`refusal_codes`."""
    lines = ['| Code | Emitted by | Meaning | Defined as |', '| --- | --- | --- | --- |']
    for code, emitted_by, meaning, constant in refusal_codes():
        lines.append(f'| `{code}` | {emitted_by} | {meaning} | `{constant}` |')
    return '\n'.join(lines)


class MarkdownDirective(SphinxDirective):
    """A directive whose content is Markdown generated when the page is built."""

    def markdown(self) -> str:
        """Return the Markdown to insert."""
        raise NotImplementedError

    def run(self):
        """Parse the generated Markdown in place of the directive."""
        try:
            text = self.markdown()
        except (KeyError, ValueError) as error:
            raise self.error(f'{self.name}: {error}') from error
        container = nodes.container()
        self.state.nested_parse(StringList(text.splitlines(), source=self.get_source_info()[0]),
                                self.content_offset, container)
        return container.children


class ParameterTable(MarkdownDirective):
    """``{parameter-table} GROUP``: the table of one parameter group, from its specs."""

    required_arguments = 1

    def markdown(self) -> str:
        """Render the group named by the argument."""
        group = self.arguments[0]
        if group not in parameter_groups():
            raise KeyError(f'no parameter group {group!r}; known: {sorted(parameter_groups())}')
        return parameter_table(group)


class RefusalCodes(MarkdownDirective):
    """``{refusal-codes}``: every refusal and warning code, with its meaning."""

    def markdown(self) -> str:
        """Render :func:`refusal_codes`."""
        return refusal_codes_table()


def check_public_names(app, env):
    """Warn about every public name of the package root that no page documents."""
    objects = env.get_domain('py').objects
    missing = [name for name in public_names() if f'{PACKAGE}.{name}' not in objects]
    if missing:
        logger.warning('the API reference does not document %s',
                       ', '.join(f'{PACKAGE}.{name}' for name in missing))


def setup(app):
    """Register the directives and the completeness check."""
    app.add_directive('parameter-table', ParameterTable)
    app.add_directive('refusal-codes', RefusalCodes)
    app.connect('env-check-consistency', check_public_names)
    return {'version': '1', 'parallel_read_safe': True, 'parallel_write_safe': True}
