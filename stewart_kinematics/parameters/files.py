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
ROS 2 parameter files read as a node would read them, and the geometry loaded from them.

The YAML itself is read by :mod:`~stewart_kinematics.parameters.rcl_yaml` (limits, aliases
refused); a file that cannot be read raises a :class:`ParameterFileError`, one line, ``file:line:
what is wrong``. Nothing here imports ROS.
"""

import fnmatch
from typing import Optional

from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.parameters.builders import geometry_from_parameters
from stewart_kinematics.parameters.declarations import all_specs, check_known_names
from stewart_kinematics.parameters.rcl_yaml import (  # noqa: F401  (rcl_scalar: re-exported)
    ParameterFileError,
    parse_yaml_value,
    rcl_scalar,
    read_yaml_file,
)


def parse_rcl_yaml(text: str):
    """
    Parse a YAML value as rcl parses the value of ``-p name:=value``.

    :raises ValueError: (a :class:`ParameterFileError`) if it is not YAML, or breaks a rule
        or a limit of :mod:`~stewart_kinematics.parameters.rcl_yaml`.
    """
    return parse_yaml_value(text)


def read_parameter_sections(path) -> dict:
    """
    Read a ROS 2 parameter file as rcl reads it: section name -> flat parameter values.

    Scalars are typed as rcl types them (:func:`rcl_scalar`), and nested maps become dotted
    names (``qos_overrides./topic.publisher.depth``), as rcl flattens them.

    :raises ParameterFileError: (a ``ValueError``, ``file:line: what is wrong``) if the file
        is missing, is not valid YAML, breaks a limit of
        :mod:`~stewart_kinematics.parameters.rcl_yaml` (aliases, depth, size) or has no such
        layout.
    """
    return read_sections_and_lines(path)[0]


def read_sections_and_lines(path):
    """
    Read a parameter file as :func:`read_parameter_sections`, with the line of each value.

    :returns: ``(sections, lines)``: the sections, and ``(section, name) -> line``.
    :raises ParameterFileError: as :func:`read_parameter_sections`.
    """
    document = read_yaml_file(path)
    if not isinstance(document.value, dict):
        raise ParameterFileError(path, None, 'must map node names to ros__parameters')
    sections, lines = {}, {}
    for key, content in document.value.items():
        if not isinstance(content, dict) or not isinstance(content.get('ros__parameters'), dict):
            raise ParameterFileError(path, document.lines.get((key,)), (
                f"section '{key}' has no ros__parameters map"))
        sections[key] = _flatten(content['ros__parameters'])
        prefix = (key, 'ros__parameters')
        lines.update({(key, '.'.join(where[2:])): line
                      for where, line in document.lines.items()
                      if where[:2] == prefix and len(where) > 2})
    return sections, lines


def _flatten(values, prefix=''):
    flat = {}
    for name, value in values.items():
        if isinstance(value, dict):
            flat.update(_flatten(value, f'{prefix}{name}.'))
        else:
            flat[prefix + name] = value
    return flat


def section_applies(key: str, node_name: str) -> bool:
    """
    Whether a parameter file's section applies to a node, as rcl decides.

    :param key: the section's name: ``/**``, a node's name (``fk_node``: in the root
        namespace), a full name (``/robot/fk_node``), with ``*`` for one name and ``**`` for
        any number of them (``/**/fk_node``, ``/robot/*``).
    :param node_name: the node's fully qualified name (``/robot/fk_node``).
    """
    pattern = ('' if key.startswith('/') else '/') + key
    node_tokens = node_name.strip('/').split('/')
    pattern_tokens = pattern.strip('/').split('/')

    def match(pattern_index, node_index):
        if pattern_index == len(pattern_tokens):
            return node_index == len(node_tokens)
        token = pattern_tokens[pattern_index]
        if token == '**':
            return any(match(pattern_index + 1, index)
                       for index in range(node_index, len(node_tokens) + 1))
        return (node_index < len(node_tokens)
                and fnmatch.fnmatchcase(node_tokens[node_index], token)
                and match(pattern_index + 1, node_index + 1))
    return match(0, 0)


def read_parameter_file(path, node_name: Optional[str] = None) -> dict:
    """
    Read the parameters a node would get from a ROS 2 parameter file.

    Sections apply as rcl applies them: ``/**`` first, then the sections of ``node_name``,
    which override it. Values are typed as rcl types them (``1e-3`` is a float, ``'0.9'`` in
    quotes a string).

    :param path: a YAML file in the ``<node>: ros__parameters: {...}`` layout.
    :param node_name: the node whose view to return: a bare name (``fk_node``) matches its
        section in any namespace, a full name (``/robot_a/fk_node``) the sections rcl would
        apply to that node; ``None`` reads only ``/**``.
    :returns: parameter name -> value.
    :raises ParameterFileError: (a ``ValueError``, ``file:line: what is wrong``) if the file
        is missing, is not valid YAML, breaks a limit or has no such layout.
    """
    return _read_layer(path, node_name)[0]


def _read_layer(path, node_name):
    """Return what :func:`read_parameter_file` returns, and the line of each value."""
    sections, lines = read_sections_and_lines(path)
    keys = ['/**'] if '/**' in sections else []
    if node_name is not None:
        keys += [key for key in sections if key != '/**' and (
            section_applies(key, node_name) or (
                '/' not in node_name and key.rsplit('/', 1)[-1] == node_name))]
    values, value_lines = {}, {}
    for key in keys:
        values.update(sections[key])
        value_lines.update({name: lines.get((key, name)) for name in sections[key]})
    return values, value_lines


def read_parameter_files(paths, node_name: Optional[str] = None) -> dict:
    """
    Read layered parameter files as a node would get them: later files override earlier ones.

    Unlike rcl's merge, which keeps one type per name and so drops a quoted ``"0.9"`` layered
    over a double whatever the order, every file's own value must have its parameter's type.
    Every tool reads its parameter files with this function.

    :param paths: a file or a list of them, in the order of repeated ``--params-file``.
    :param node_name: also apply this node's sections (see :func:`read_parameter_file`).
    :returns: parameter name -> value.
    :raises ParameterFileError: (a ``ValueError``, ``file:line: what is wrong``) if a file
        cannot be read, names an unknown parameter or gives a value of the wrong type.
    """
    if isinstance(paths, (str, bytes)) or not hasattr(paths, '__iter__'):
        paths = [paths]
    specs = {spec.name: spec for spec in all_specs()}
    values = {}
    for path in paths:
        layer, lines = _read_layer(path, node_name)
        try:
            check_known_names(layer, 'the parameter file')
        except ValueError as error:
            first = min((line for name, line in lines.items()
                         if name not in specs and line is not None), default=None)
            raise ParameterFileError(path, first, str(error)) from None
        for name, value in layer.items():
            reason = specs[name].type_reason(value)
            if reason:
                raise ParameterFileError(path, lines.get(name), reason)
        values.update(layer)
    return values


def load_geometry(paths, node_name: Optional[str] = None) -> Geometry:
    """
    Read a geometry from ROS 2 parameter files, the same ones the nodes are given.

    :param paths: a YAML file with the geometry under ``/**:`` (or under ``node_name``), or a
        list of them applied in order, as repeated ``--params-file`` options are (for example
        ``['config/paper_platform.yaml', 'config/example_limits.yaml']``).
    :param node_name: also apply this node's sections, as that node would see them.
    :raises ValueError: naming the file, if a file cannot be read or its geometry is not
        allowed.

    >>> from stewart_kinematics import load_geometry
    >>> geometry = load_geometry(['config/paper_platform.yaml', 'config/example_limits.yaml'])
    >>> geometry.leg_length_min, geometry.leg_length_max
    (0.65, 0.9)
    """
    if isinstance(paths, (str, bytes)) or not hasattr(paths, '__iter__'):
        paths = [paths]
    values = read_parameter_files(paths, node_name)
    try:
        return geometry_from_parameters(values)
    except ValueError as error:
        raise ValueError(f'{", ".join(map(str, paths))}: {error}') from error


def load_settings(settings_class, paths, node_name: Optional[str] = None):
    """
    Read typed settings from ROS 2 parameter files, the same ones the nodes are given.

    :param settings_class: a settings class of :mod:`stewart_kinematics.parameters.settings`,
        such as ``TrajectoryNodeSettings`` or ``GeometrySettings``.
    :param paths: a YAML file, or a list of them applied in order, as repeated
        ``--params-file`` options are.
    :param node_name: also apply this node's sections, as that node would see them.
    :raises ValueError: naming the files, if a file cannot be read, names an unknown parameter,
        or gives a value that is not allowed.

    >>> from stewart_kinematics.parameters import load_settings, TrajectoryNodeSettings
    >>> settings = load_settings(TrajectoryNodeSettings, [
    ...     'config/paper_platform.yaml', 'config/example_limits.yaml',
    ...     'config/table3_ramp.yaml'], 'trajectory_node')
    >>> settings.geometry.leg_velocity_max, settings.ramp.mode
    (0.05, 'table')
    """
    if isinstance(paths, (str, bytes)) or not hasattr(paths, '__iter__'):
        paths = [paths]
    values = read_parameter_files(paths, node_name)
    try:
        return settings_class.from_values(values)
    except ValueError as error:
        raise ValueError(f'{", ".join(map(str, paths))}: {error}') from error
