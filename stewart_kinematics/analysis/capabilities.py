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
What a geometry can do: its design, its home pose's margins, its reach and its assembly modes.

:func:`geometry_report` reports on a :class:`~stewart_kinematics.Geometry`;
:func:`parameters_report` on parameter values as the nodes' files give them, even when the
home pose breaks the limits (a geometry the nodes refuse: the report says which limit, by how
much). The report holds, in SI units:

- the design (``6-6``, ``6-3``, ``3-3``, ...), the joints two legs share and the angle between
  those two legs at home, and pairs of joints that nearly coincide but count as two;
- the home leg lengths, the Jacobian's condition number at home and the margin to each limit
  that is set (the stroke, the joint cones, whose axes are the home directions, the
  singularity margin, the clearance between legs, and the static leg forces of the masses
  the geometry carries: not checked while every mass is 0);
- the travel range along each pose coordinate from home and the volume of the workspace at the
  home orientation on a coarse grid (:mod:`.workspace`);
- every assembly mode of the home leg lengths (:mod:`.assembly_modes`): how many are real,
  complex or lost at infinity, how many keep the limits, and the nearest other one;
- warnings, each a :class:`~stewart_kinematics.Finding` whose code is registered in
  :mod:`stewart_kinematics.findings`.

``stewart_geometry`` (:mod:`stewart_kinematics.tools.geometry_report`) prints it. Nothing here
imports ROS.
"""

from dataclasses import dataclass, replace
import math
from typing import Mapping, Optional, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.analysis.assembly_modes import (
    assembly_mode_margin,
    assembly_modes,
    AssemblyMode,
    AssemblyModes,
)
from stewart_kinematics.analysis.workspace import (
    travel_ranges,
    TravelRanges,
    workspace_volume,
    WorkspaceVolume,
)
from stewart_kinematics.limits.base import LEG_PAIRS, PoseLegs
from stewart_kinematics.limits.kinds import pose_settings
from stewart_kinematics.limits.leg_collision import LegCollision
from stewart_kinematics.limits.leg_forces import LegForces
from stewart_kinematics.limits.settings import limits_of
from stewart_kinematics.model.geometry import (
    Geometry,
    joint_separations,
    joint_set_scale,
    SHARED_JOINT_TOLERANCE,
    SharedJoint,
    SIDES,
)
from stewart_kinematics.model.jacobians import jacobian_condition
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import geometry_from_settings, GeometrySettings

#: A home pose whose condition number is above this (or above half of the singularity
#: margin) is near a singularity: the paper's home is at 9.5, the 6-3 and 3-3 examples' at 6.5
#: and 5.1.
HOME_CONDITION_WARNING = 20.0
#: Two joints of a set closer than this fraction of its size (but not shared) nearly
#: coincide; without ``leg_radius``, two legs' axes closer than this fraction of the platform
#: radius at home nearly touch.
NEAR_FRACTION = 0.01
#: Grid step of the workspace volume, metres: coarse and fast (well under a second).
DEFAULT_VOLUME_RESOLUTION = 0.02
#: The pose limits' values that mean "no limit", by setting of PoseLimits (their kinds').
NO_LIMITS = {name: parameter.setting_default for name, parameter in pose_settings().items()}
#: The same in parameter names and units (degrees for the cones).
_NO_LIMIT_PARAMETERS = {parameter.name: parameter.default
                        for parameter in pose_settings().values()}


@dataclass(frozen=True)
class HomeMargin:
    """
    How far the home pose is from one limit.

    :param limit: the limit's name (``leg_length_max``, ``leg_collision``, ...).
    :param allowed: the limit, SI units (for ``leg_collision``: ``2 * leg_radius``).
    :param value: the closest value at home: the longest leg, the nearest two legs' axes, ...
    :param margin: how far the value may still go, SI units; negative where broken.
    :param unit: ``m``, ``rad``, ``N`` (the static leg forces) or ``''`` (the condition
        number).
    :param subject: the leg or legs of the closest value (``leg 3``, ``legs 1 and 2``), or
        ``''``.
    """

    limit: str
    allowed: float
    value: float
    margin: float
    unit: str
    subject: str

    @property
    def broken(self) -> bool:
        """Whether the home pose breaks this limit."""
        return not self.margin >= 0.0

    def __str__(self):
        scale, unit = {'m': (1e3, ' mm'), 'rad': (math.degrees(1.0), ' deg'), 'N': (1.0, ' N'),
                       '': (1.0, '')}[self.unit]
        subject = f' ({self.subject})' if self.subject else ''
        return (f'{self.limit} {self.allowed * scale:.6g}{unit}: at home '
                f'{self.value * scale:.6g}{unit}{subject}, margin '
                f'{self.margin * scale:.4g}{unit}')


@dataclass(frozen=True)
class NearJoints:
    """
    Two joints of one side closer than :data:`NEAR_FRACTION` of its size, but two joints.

    :param side: ``'base'`` or ``'platform'``.
    :param legs: the two legs, 1..6.
    :param distance: how far apart they are, metres.
    """

    side: str
    legs: Tuple[int, int]
    distance: float


@dataclass(frozen=True)
class GeometryReport:
    """
    What a geometry can do (see the module's documentation). SI units: metres and radians.

    :param design: ``'6-6'``, ``'6-3'``, ``'3-3'``, ...: distinct base and platform joints.
    :param shared_joints: the joints two legs share (:attr:`Geometry.shared_joints`).
    :param shared_joint_angles: per shared joint, the angle between its two legs at home.
    :param nearly_shared: joints that nearly coincide but count as two.
    :param home_pose: ``[X, Y, Z, alpha, beta, gamma]``.
    :param home_leg_lengths: shape (6,).
    :param home_condition: the dimensionless Jacobian's condition number at home.
    :param margins: one :class:`HomeMargin` per limit that is set.
    :param home_refusal: why the nodes refuse the geometry (its home pose breaks the limits),
        or ``''`` when they take it.
    :param travel: travel ranges from home; ``None`` when refused.
    :param volume: the workspace at the home orientation; ``None`` when refused.
    :param modes: every assembly mode of the home leg lengths.
    :param modes_within_limits: how many of them keep every limit (home included); ``None``
        when refused.
    :param nearest_mode: the nearest other real mode that keeps the limits (any real one when
        refused), or ``None``.
    :param nearest_mode_distance: its distance from home (``pose_distance``), metres; ``inf``
        when there is none.
    :param volume_resolution: the grid step of ``volume``, metres.
    :param warnings: the :class:`~stewart_kinematics.Finding` warnings, each code registered.
    """

    design: str
    shared_joints: Tuple[SharedJoint, ...]
    shared_joint_angles: Tuple[float, ...]
    nearly_shared: Tuple[NearJoints, ...]
    home_pose: np.ndarray
    home_leg_lengths: np.ndarray
    home_condition: float
    margins: Tuple[HomeMargin, ...]
    home_refusal: str
    travel: Optional[TravelRanges]
    volume: Optional[WorkspaceVolume]
    modes: AssemblyModes
    modes_within_limits: Optional[int]
    nearest_mode: Optional[AssemblyMode]
    nearest_mode_distance: float
    volume_resolution: float
    warnings: Tuple[findings.Finding, ...]

    @property
    def usable(self) -> bool:
        """Whether the nodes take this geometry: its home pose keeps every limit."""
        return not self.home_refusal

    def text(self) -> str:
        """Return the report as text: millimetres and degrees."""
        lines = [f'Design: {self.design} ({_design_words(self)})']
        for joint, angle in zip(self.shared_joints, self.shared_joint_angles):
            lines.append(f'  {joint}; the two legs meet at {math.degrees(angle):.1f} deg at home')
        for near in self.nearly_shared:
            lines.append(f'  {near.side} joints of legs {near.legs[0]} and {near.legs[1]} are '
                         f'{near.distance * 1e3:.4g} mm apart: two joints')
        pose = self.home_pose
        lines += [
            f'Home pose: X {pose[0]:.6g} m, Y {pose[1]:.6g} m, Z {pose[2]:.6g} m, '
            + ', '.join(f'{name} {math.degrees(angle):.6g} deg'
                        for name, angle in zip(('alpha', 'beta', 'gamma'), pose[3:])),
            'Home leg lengths: ' + ', '.join(f'{length:.6f}' for length in self.home_leg_lengths)
            + ' m',
            f'Condition number at home: {self.home_condition:.4g}']
        lines.append('Margins at home:' if self.margins else 'Margins at home: no limit is set')
        lines += [f'  {margin}' + (' BROKEN' if margin.broken else '') for margin in self.margins]
        if self.home_refusal:
            lines.append(f'Refused by the nodes: {self.home_refusal}')
        else:
            lines += ['Travel from home, each coordinate alone:', self.travel.table()]
            volume = self.volume
            unbounded = '' if volume.bounded else ' (UNBOUNDED: the part within the span)'
            lines.append(f'Workspace at the home orientation: {volume.volume:.4g} m^3 '
                         f'({volume.volume * 1e3:.4g} litres) on a '
                         f'{self.volume_resolution * 1e3:g} mm grid{unbounded}')
        modes = self.modes
        lines.append(
            f"Assembly modes of home's leg lengths: {len(modes)} real"
            + ('' if self.modes_within_limits is None
               else f' ({self.modes_within_limits} within the limits)')
            + f', {modes.complex_solutions} complex, {modes.at_infinity} at infinity'
            + ('' if modes.complete else f'; INCOMPLETE: {modes.reason}'))
        if self.nearest_mode is None:
            lines.append('  nearest other mode within the limits: none')
        else:
            nearest = self.nearest_mode
            lines.append(
                '  nearest other mode' + ('' if self.home_refusal else ' within the limits')
                + f': {self.nearest_mode_distance * 1e3:.4g} mm away '
                f'({nearest.position_distance * 1e3:.4g} mm and '
                f'{math.degrees(nearest.angle_distance):.4g} deg)')
        lines.append('Warnings:' if self.warnings else 'Warnings: none')
        lines += [f'  [{warning.code}] {warning.message}' for warning in self.warnings]
        return '\n'.join(lines)

    def as_dict(self) -> dict:
        """Return the report as plain numbers, lists and strings (for JSON), SI units."""
        travel = None if self.travel is None else {
            axis.axis: {'unit': axis.unit, 'negative': float(axis.negative),
                        'positive': float(axis.positive),
                        'negative_limit': axis.negative_limit,
                        'negative_leg': axis.negative_leg,
                        'positive_limit': axis.positive_limit,
                        'positive_leg': axis.positive_leg} for axis in self.travel.axes}
        volume = None if self.volume is None else {
            'volume_m3': float(self.volume.volume), 'resolution_m': self.volume_resolution,
            'bounded': bool(self.volume.bounded)}
        return {
            'design': self.design, 'usable': self.usable, 'home_refusal': self.home_refusal,
            'shared_joints': [{'side': joint.side, 'legs': list(joint.legs),
                               'angle_at_home_rad': float(angle)}
                              for joint, angle in zip(self.shared_joints,
                                                      self.shared_joint_angles)],
            'nearly_shared_joints': [{'side': near.side, 'legs': list(near.legs),
                                      'distance_m': float(near.distance)}
                                     for near in self.nearly_shared],
            'home_pose': [float(value) for value in self.home_pose],
            'home_leg_lengths_m': [float(value) for value in self.home_leg_lengths],
            'home_condition': _number(self.home_condition),
            'margins': [{'limit': margin.limit, 'allowed': _number(margin.allowed),
                         'value': _number(margin.value), 'margin': _number(margin.margin),
                         'unit': margin.unit, 'subject': margin.subject, 'broken': margin.broken}
                        for margin in self.margins],
            'travel_ranges': travel, 'workspace_volume': volume,
            'assembly_modes': {
                'real': len(self.modes), 'within_limits': self.modes_within_limits,
                'complex': self.modes.complex_solutions, 'at_infinity': self.modes.at_infinity,
                'paths': self.modes.paths, 'complete': self.modes.complete,
                'nearest_other_distance_m': _number(self.nearest_mode_distance),
                'nearest_other_pose': (None if self.nearest_mode is None else
                                       [float(value) for value in self.nearest_mode.pose])},
            'warnings': [{'code': warning.code, 'message': warning.message}
                         for warning in self.warnings],
        }


def geometry_report(geometry: Geometry, *,
                    volume_resolution: float = DEFAULT_VOLUME_RESOLUTION) -> GeometryReport:
    """
    Report what a geometry can do (see the module's documentation).

    :param geometry: a :class:`~stewart_kinematics.Geometry` (its home pose keeps its limits,
        or it would not exist: :func:`parameters_report` reports on one that does not).
    :param volume_resolution: grid step of the workspace volume, metres.

    >>> from stewart_kinematics import load_geometry
    >>> from stewart_kinematics.analysis.capabilities import geometry_report
    >>> report = geometry_report(load_geometry('config/platform_3_3.yaml'))
    >>> report.design, report.modes_within_limits, len(report.modes), report.warnings
    ('3-3', 1, 16, ())
    """
    if not isinstance(geometry, Geometry):
        raise ValueError(f'geometry must be a Geometry, got {type(geometry).__name__}')
    limits = limits_of(geometry).values()
    return _report(replace(geometry, limits=None), limits, geometry, '',
                   _resolution(volume_resolution))


def parameters_report(values: Mapping, *,
                      volume_resolution: float = DEFAULT_VOLUME_RESOLUTION) -> GeometryReport:
    """
    Report on the geometry that parameter values describe, as the nodes' files give them.

    Unlike building the geometry (which refuses a home pose that breaks a limit), a home pose
    beyond the limits is reported: by how much each limit is broken, with the rest of the
    report that does not need the limits (design, leg lengths, condition, assembly modes).

    :param values: parameter name -> value (:data:`~stewart_kinematics.parameters.
        GEOMETRY_PARAMETERS` names and units), as
        :func:`~stewart_kinematics.parameters.read_parameter_files` returns them.
    :param volume_resolution: grid step of the workspace volume, metres.
    :raises ValueError: if a value is missing or not allowed, or the joints make no platform
        at all (a joint shared by three legs, two legs sharing both joints, collinear joints).
    """
    settings = GeometrySettings.from_values(values)
    bare = geometry_from_settings(settings.replace(**_NO_LIMIT_PARAMETERS))
    limits = {name: parameter.setting_value(getattr(settings, parameter.name))
              for name, parameter in pose_settings().items()}
    try:
        full, refusal = geometry_from_settings(settings), ''
    except ValueError as error:
        full, refusal = None, str(error)
    return _report(bare, limits, full, refusal, _resolution(volume_resolution))


def _resolution(value) -> float:
    """Return a grid step in metres, or refuse it naming what is allowed."""
    if (isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating))
            or not 1e-3 <= value <= 0.2):
        raise ValueError(f'volume_resolution must be a number in [0.001, 0.2] metres, got '
                         f'{value!r}')
    return float(value)


def _report(bare, limits, full, refusal, volume_resolution) -> GeometryReport:
    """
    Build the report of a geometry without limits (``bare``) and its limits' values.

    :param full: the geometry with its limits, or ``None`` when its home pose breaks them.
    :param refusal: why ``full`` is ``None``, or ``''``.
    """
    home = bare.home_pose
    rotation = euler_zyx_to_matrix(home[3:])
    legs = PoseLegs.of_poses(bare, home[None])
    lengths = legs.lengths[:, 0]
    vectors = np.stack([vector[:, 0] for vector in legs.vectors[:3]], axis=-1)
    directions = vectors / lengths[:, None]
    condition = float(jacobian_condition(bare, home[:3], rotation))
    distances = LegCollision(bare).values(legs)[0][:, 0]
    # The force limit's own evaluator gives the static forces at home; it has no bound (and
    # the forces are not checked) while every mass is 0.
    force_evaluator = LegForces(bare, force_max=1.0)
    forces = force_evaluator.values(legs)[0][:, 0] if force_evaluator.bounds else None
    margins = _margins(lengths, condition, distances, limits, forces)
    angles = tuple(
        float(math.atan2(np.linalg.norm(np.cross(directions[i - 1], directions[j - 1])),
                         float(directions[i - 1] @ directions[j - 1])))
        for i, j in (joint.legs for joint in bare.shared_joints))
    nearly_shared = _nearly_shared(bare)

    travel = volume = None
    if full is not None:
        travel = travel_ranges(full)
        volume = workspace_volume(full, resolution=volume_resolution)
    modes = assembly_modes(full or bare, lengths)
    if full is not None:
        margin = assembly_mode_margin(full, home, lengths, modes)
        within, nearest, distance = margin.modes_within_limits, margin.nearest, margin.distance
    else:
        others = [mode for mode in modes.modes if mode.distance > 1e-6]
        within, nearest = None, (others[0] if others else None)
        distance = nearest.distance if nearest else math.inf

    warnings = _warnings(bare, limits, margins, refusal, condition, distances, nearly_shared,
                         modes, within, nearest, distance)
    return GeometryReport(
        design=bare.design, shared_joints=bare.shared_joints, shared_joint_angles=angles,
        nearly_shared=nearly_shared, home_pose=np.array(home), home_leg_lengths=lengths.copy(),
        home_condition=condition, margins=margins, home_refusal=refusal, travel=travel,
        volume=volume, modes=modes, modes_within_limits=within, nearest_mode=nearest,
        nearest_mode_distance=float(distance), volume_resolution=volume_resolution,
        warnings=warnings)


def _margins(lengths, condition, distances, limits, forces=None) -> Tuple[HomeMargin, ...]:
    """
    Return the margin at home to each limit that is set (the values of NO_LIMITS are not).

    :param forces: the static leg forces at home, N, or ``None`` when every mass is 0 (the
        force limit is then not checked).
    """
    margins = []
    shortest, longest = int(np.argmin(lengths)), int(np.argmax(lengths))
    if limits['leg_length_min'] != NO_LIMITS['leg_length_min']:
        allowed = limits['leg_length_min']
        margins.append(HomeMargin('leg_length_min', allowed, float(lengths[shortest]),
                                  float(lengths[shortest] - allowed), 'm', f'leg {shortest + 1}'))
    if limits['leg_length_max'] != NO_LIMITS['leg_length_max']:
        allowed = limits['leg_length_max']
        margins.append(HomeMargin('leg_length_max', allowed, float(lengths[longest]),
                                  float(allowed - lengths[longest]), 'm', f'leg {longest + 1}'))
    # The cones' axes are the home directions: at home every leg is on its axis.
    for name in ('base_joint_max_angle', 'platform_joint_max_angle'):
        if limits[name] != NO_LIMITS[name]:
            margins.append(HomeMargin(name, limits[name], 0.0, limits[name], 'rad',
                                      'every leg'))
    if limits['max_jacobian_condition'] != NO_LIMITS['max_jacobian_condition']:
        allowed = limits['max_jacobian_condition']
        margins.append(HomeMargin('max_jacobian_condition', allowed, condition,
                                  allowed - condition, '', ''))
    if limits['leg_radius'] != NO_LIMITS['leg_radius']:
        allowed = 2.0 * limits['leg_radius']
        nearest = int(np.argmin(distances))
        first, second = LEG_PAIRS[nearest]
        margins.append(HomeMargin('leg_collision', allowed, float(distances[nearest]),
                                  float(distances[nearest] - allowed), 'm',
                                  f'legs {first} and {second}'))
    if forces is not None:
        weakest, strongest = int(np.argmin(forces)), int(np.argmax(forces))
        if limits['leg_force_min'] != NO_LIMITS['leg_force_min']:
            allowed = limits['leg_force_min']
            margins.append(HomeMargin('leg_force_min', allowed, float(forces[weakest]),
                                      float(forces[weakest] - allowed), 'N',
                                      f'leg {weakest + 1}'))
        if limits['leg_force_max'] != NO_LIMITS['leg_force_max']:
            allowed = limits['leg_force_max']
            margins.append(HomeMargin('leg_force_max', allowed, float(forces[strongest]),
                                      float(allowed - forces[strongest]), 'N',
                                      f'leg {strongest + 1}'))
    return tuple(margins)


def _nearly_shared(geometry) -> Tuple[NearJoints, ...]:
    """Pairs of joints closer than NEAR_FRACTION of their set's size that count as two."""
    near = []
    shared = {(joint.side, joint.legs) for joint in geometry.shared_joints}
    for side in SIDES:
        joints = getattr(geometry, f'{side}_joints')
        size = joint_set_scale(joints)
        separation = joint_separations(joints)
        for i, j in zip(*np.nonzero(np.triu(separation <= NEAR_FRACTION * size))):
            legs = (int(i) + 1, int(j) + 1)
            if (side, legs) not in shared and separation[i, j] > SHARED_JOINT_TOLERANCE * size:
                near.append(NearJoints(side, legs, float(separation[i, j])))
    return tuple(near)


def _warnings(geometry, limits, margins, refusal, condition, distances, nearly_shared, modes,
              within, nearest, distance) -> Tuple[findings.Finding, ...]:
    warnings = []
    broken = [margin for margin in margins if margin.broken and margin.limit != 'leg_collision']
    if broken or (refusal and not any(margin.broken for margin in margins)):
        warnings.append(findings.Finding(
            findings.LIMIT_BROKEN_AT_HOME,
            ('the home pose breaks ' + '; '.join(str(margin) for margin in broken)
             if broken else refusal) + ': no node starts with these files'))
    collisions = [margin for margin in margins
                  if margin.broken and margin.limit == 'leg_collision']
    if collisions:
        pairs = [f'legs {LEG_PAIRS[k][0]} and {LEG_PAIRS[k][1]} ({distances[k] * 1e3:.4g} mm)'
                 for k in np.flatnonzero(distances < collisions[0].allowed)]
        warnings.append(findings.Finding(
            findings.LEGS_COLLIDE_AT_HOME,
            f'at home the axes of {", ".join(pairs)} are closer than 2 * leg_radius = '
            f'{collisions[0].allowed * 1e3:.4g} mm: the legs collide'))
    elif limits['leg_radius'] == 0.0:
        close = np.flatnonzero(distances < NEAR_FRACTION * geometry.platform_radius)
        if close.size:
            pairs = [f'legs {LEG_PAIRS[k][0]} and {LEG_PAIRS[k][1]} ({distances[k] * 1e3:.4g} mm)'
                     for k in close]
            warnings.append(findings.Finding(
                findings.LEGS_COLLIDE_AT_HOME,
                f'at home the axes of {", ".join(pairs)} (sharing no joint) nearly touch; no '
                'collision is checked without leg_radius'))
    limit = limits['max_jacobian_condition']
    if not any(margin.limit == 'max_jacobian_condition' for margin in broken) and (
            condition > HOME_CONDITION_WARNING or condition > 0.5 * limit):
        warnings.append(findings.Finding(
            findings.NEAR_SINGULAR_HOME,
            f'the condition number at home is {condition:.4g} (a warning above '
            f'{min(HOME_CONDITION_WARNING, 0.5 * limit):.4g}): the home pose is near a '
            'singularity, where small leg errors give large pose errors'))
    if nearly_shared:
        warnings.append(findings.Finding(
            findings.JOINTS_NEARLY_SHARED,
            '; '.join(f'the {near.side} joints of legs {near.legs[0]} and {near.legs[1]} are '
                      f'{near.distance * 1e3:.4g} mm apart' for near in nearly_shared)
            + ': two joints; if they are one joint shared by two legs, give both legs the same '
            'coordinates'))
    if within is not None and within > 1 and nearest is not None:
        warnings.append(findings.Finding(
            findings.OTHER_MODE_WITHIN_LIMITS,
            f'{within} assembly modes of the home leg lengths keep every limit; the nearest '
            f'other one is {distance * 1e3:.4g} mm away ({nearest.position_distance * 1e3:.4g} '
            f'mm, {math.degrees(nearest.angle_distance):.4g} deg): the leg lengths alone do not '
            'tell them apart'))
    return tuple(warnings)


def _design_words(report) -> str:
    """Say which legs share which joints, in words."""
    if not report.shared_joints:
        return 'no joint is shared'
    parts = []
    for side in SIDES:
        pairs = [joint.legs for joint in report.shared_joints if joint.side == side]
        if pairs:
            named = ', '.join(f'{i} and {j}' for i, j in pairs)
            parts.append(f'legs {named} share their {side} joints' if len(pairs) > 1
                         else f'legs {named} share a {side} joint')
    return '; '.join(parts)


def _number(value):
    """Return a float for JSON: finite as it is, infinite as 'inf' (JSON has no inf)."""
    value = float(value)
    return value if math.isfinite(value) else ('inf' if value > 0 else '-inf')
