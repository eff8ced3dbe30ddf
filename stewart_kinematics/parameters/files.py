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

import fnmatch
import math
import re
from typing import Optional

from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.parameters.builders import geometry_from_parameters
from stewart_kinematics.parameters.declarations import all_specs, check_known_names
import yaml

#: rcl's words for true and false (rcl_yaml_param_parser): YAML 1.1's, in three spellings.
_TRUE_WORDS = {'y', 'Y', 'yes', 'Yes', 'YES', 'true', 'True', 'TRUE', 'on', 'On', 'ON'}
_FALSE_WORDS = {'n', 'N', 'no', 'No', 'NO', 'false', 'False', 'FALSE', 'off', 'Off', 'OFF'}
_SPECIAL_FLOATS = {'.nan': math.nan, '.NaN': math.nan, '.NAN': math.nan, '.inf': math.inf,
                   '.Inf': math.inf, '.INF': math.inf, '+.inf': math.inf, '+.Inf': math.inf,
                   '+.INF': math.inf, '-.inf': -math.inf, '-.Inf': -math.inf,
                   '-.INF': -math.inf}
_STRING_TAG = 'tag:yaml.org,2002:str'
_RESOLVER = yaml.resolver.Resolver()
#: An integer as C's strtol reads it with base 0: decimal, 0x hexadecimal or 0 octal.
_INTEGER = re.compile(r'\s*[+-]?(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)\Z')


def rcl_scalar(text: str, quoted: bool = False):
    """
    Type a YAML scalar as rcl does: a quoted one is a string; else bool, integer, float, string.

    PyYAML follows YAML 1.1, where ``1e-3`` (no dot) is a string; rcl reads it as a double
    (strtod), as it reads ``.inf``. A node and this package's tools must see the same value.

    :param text: the scalar as written.
    :param quoted: whether it was written in quotes.
    """
    if quoted:
        return text
    if text in _TRUE_WORDS:
        return True
    if text in _FALSE_WORDS:
        return False
    if _INTEGER.match(text):
        return int(text, 8) if re.match(r'\s*[+-]?0[0-7]+\Z', text) else int(text, 0)
    if text in _SPECIAL_FLOATS:
        return _SPECIAL_FLOATS[text]
    if '_' in text:   # Python's float reads 1_000; strtod does not
        return text
    try:
        value = float(text)
    except ValueError:
        return text
    # strtod reads inf, nan and infinity in any case; YAML's own are handled above.
    return value


def _rcl_value(node, path):
    """Return the value of a composed YAML node, typed as rcl types it."""
    if isinstance(node, yaml.ScalarNode):
        # Quoted, or tagged !!str: a string, as for rcl.
        explicit_string = node.tag == _STRING_TAG and _RESOLVER.resolve(
            yaml.ScalarNode, node.value, (True, False)) != _STRING_TAG
        return rcl_scalar(node.value, node.style in ("'", '"') or explicit_string)
    if isinstance(node, yaml.SequenceNode):
        return [_rcl_value(item, path) for item in node.value]
    if isinstance(node, yaml.MappingNode):
        return {str(_rcl_value(key, path)): _rcl_value(value, path)
                for key, value in node.value}
    raise ValueError(f'parameter file {path}: unexpected YAML node {node!r}')


def parse_rcl_yaml(text: str):
    """
    Parse a YAML value as rcl parses the value of ``-p name:=value``.

    :raises ValueError: if it is not YAML.
    """
    try:
        node = yaml.compose(text)
    except yaml.YAMLError as error:
        raise ValueError(f'{text!r} is not a YAML value: {error}') from error
    return None if node is None else _rcl_value(node, repr(text))


def read_parameter_sections(path) -> dict:
    """
    Read a ROS 2 parameter file as rcl reads it: section name -> flat parameter values.

    Scalars are typed as rcl types them (:func:`rcl_scalar`), and nested maps become dotted
    names (``qos_overrides./topic.publisher.depth``), as rcl flattens them.

    :raises ValueError: if the file is missing, is not valid YAML or has no such layout.
    """
    try:
        with open(path, encoding='utf-8-sig') as stream:
            document = yaml.compose(stream)
    except OSError as error:
        raise ValueError(f'cannot read parameter file {path}: {error.strerror}') from error
    except yaml.YAMLError as error:
        raise ValueError(f'parameter file {path} is not valid YAML: {error}') from error
    except UnicodeDecodeError as error:
        raise ValueError(f'parameter file {path} is not UTF-8 text: {error}') from error
    document = None if document is None else _rcl_value(document, path)
    if not isinstance(document, dict):
        raise ValueError(f'parameter file {path} must map node names to ros__parameters')
    sections = {}
    for key, content in document.items():
        if not isinstance(content, dict) or not isinstance(content.get('ros__parameters'), dict):
            raise ValueError(
                f"section '{key}' of parameter file {path} has no ros__parameters map")
        sections[key] = _flatten(content['ros__parameters'])
    return sections


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
    :raises ValueError: if the file is missing, is not valid YAML or has no such layout.
    """
    sections = read_parameter_sections(path)
    values = dict(sections.get('/**', {}))
    if node_name is not None:
        for key, section in sections.items():
            if key == '/**':
                continue
            if section_applies(key, node_name) or (
                    '/' not in node_name and key.rsplit('/', 1)[-1] == node_name):
                values.update(section)
    return values


def read_parameter_files(paths, node_name: Optional[str] = None) -> dict:
    """
    Read layered parameter files as a node would get them: later files override earlier ones.

    Unlike rcl's merge, which keeps one type per name and so drops a quoted ``"0.9"`` layered
    over a double whatever the order, every file's own value must have its parameter's type.

    :param paths: a file or a list of them, in the order of repeated ``--params-file``.
    :param node_name: also apply this node's sections (see :func:`read_parameter_file`).
    :returns: parameter name -> value.
    :raises ValueError: naming the file, if a file cannot be read, names an unknown parameter
        or gives a value of the wrong type.
    """
    if isinstance(paths, (str, bytes)) or not hasattr(paths, '__iter__'):
        paths = [paths]
    specs = {spec.name: spec for spec in all_specs()}
    values = {}
    for path in paths:
        layer = read_parameter_file(path, node_name)
        check_known_names(layer, f'parameter file {path}')
        for name, value in layer.items():
            reason = specs[name].type_reason(value) if value is not None else ''
            if reason:
                raise ValueError(f'{reason}, in parameter file {path}')
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
