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

Nothing here imports ROS.
"""

from typing import Optional

from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.parameters.builders import geometry_from_parameters
from stewart_kinematics.parameters.declarations import check_known_names
import yaml


def read_parameter_file(path, node_name: Optional[str] = None) -> dict:
    """
    Read the parameters a node would get from a ROS 2 parameter file.

    Sections apply as rcl applies them: ``/**`` first, then the section of ``node_name``
    (``name``, ``/name`` or ``/namespace/name``), which overrides it.

    :param path: a YAML file in the ``<node>: ros__parameters: {...}`` layout.
    :param node_name: the node whose view to return: a bare name (``fk_node``) matches its
        section in any namespace, a full name (``/robot_a/fk_node``) only that one; ``None``
        reads only ``/**``.
    :returns: parameter name -> value.
    :raises ValueError: if the file is missing, is not valid YAML or has no such layout.
    """
    try:
        with open(path, encoding='utf-8') as stream:
            document = yaml.safe_load(stream)
    except OSError as error:
        raise ValueError(f'cannot read parameter file {path}: {error.strerror}') from error
    except yaml.YAMLError as error:
        raise ValueError(f'parameter file {path} is not valid YAML: {error}') from error
    if not isinstance(document, dict):
        raise ValueError(f'parameter file {path} must map node names to ros__parameters')

    def applies(key, section):
        if section == '/**' or '/' in section:
            return key.lstrip('/') == section.lstrip('/')
        return key.rsplit('/', 1)[-1] == section

    values = {}
    for section in ['/**'] + ([] if node_name is None else [node_name]):
        for key, content in document.items():
            if applies(str(key), section):
                if not isinstance(content, dict) or not isinstance(
                        content.get('ros__parameters'), dict):
                    raise ValueError(
                        f"section '{key}' of parameter file {path} has no ros__parameters map")
                values.update(content['ros__parameters'])
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
    values = {}
    for path in paths:
        values.update(read_parameter_file(path, node_name))
    try:
        check_known_names(values, 'the file')
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
    values = {}
    for path in paths:
        values.update(read_parameter_file(path, node_name))
    try:
        check_known_names(values, 'the file')
        return settings_class.from_values(values)
    except ValueError as error:
        raise ValueError(f'{", ".join(map(str, paths))}: {error}') from error
