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
Parameter files layered in any order, quoted numbers and misspelt names: applied or refused.

The defect (issue 21): a second parameter file with ``leg_length_max: "0.9"`` (a quoted
number, so a string) over paper_platform.yaml's ``.inf`` left the node running with no stroke
limit and no word, because rcl merges the two and keeps the double. The nodes now read their
``--params-file`` files and ``-p`` values again (public API only: rclpy keeps its overrides
private) and refuse a value whose type is wrong in any source, naming the parameter and the
file; a misspelt name is still refused with the closest known one.
"""

from pathlib import Path
import threading

import pytest
import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter

from stewart_kinematics import parameters
from stewart_kinematics.ros import fk_node, ik_node, ros_parameters, trajectory_node
from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ros_parameters import ParameterSources
import yaml

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
PLATFORM = str(CONFIG / 'paper_platform.yaml')
LIMITS = str(CONFIG / 'example_limits.yaml')
SOLVER = str(CONFIG / 'solver.yaml')
RAMP = str(CONFIG / 'table3_ramp.yaml')
MAINS = {'ik_node': (ik_node.main, []), 'fk_node': (fk_node.main, [SOLVER]),
         'trajectory_node': (trajectory_node.main, [RAMP])}
#: Seconds after which a main() that did not refuse its files is stopped.
WATCHDOG = 10.0


def write(tmp_path, name, text):
    """Write a parameter file; return its path."""
    path = tmp_path / name
    path.write_text(text, encoding='utf-8')
    return str(path)


def quoted_file(tmp_path, section='/**'):
    """Write a file that sets leg_length_max to the string '0.9'; return its path."""
    return write(tmp_path, 'quoted.yaml',
                 f'{section}:\n  ros__parameters:\n    leg_length_max: "0.9"\n')


def run_main(node_name, arguments):
    """Run a node's main() with these ROS arguments; stop it after WATCHDOG seconds."""
    main, extra = MAINS[node_name]
    arguments = [node_name, '--ros-args'] + arguments
    for path in extra:
        arguments += ['--params-file', path]
    watchdog = threading.Timer(WATCHDOG, rclpy.try_shutdown)
    watchdog.start()
    try:
        return main(arguments)
    finally:
        watchdog.cancel()


def fatal_line(capfd):
    """Return the fatal start-up line of the log."""
    captured = capfd.readouterr()
    lines = [line for line in (captured.out + captured.err).splitlines()
             if '[FATAL]' in line and 'cannot start' in line]
    assert lines, captured.out + captured.err
    return lines[0]


@pytest.mark.parametrize('node_name', MAINS)
@pytest.mark.parametrize('order', ['quoted last', 'quoted first'])
def test_a_quoted_number_in_a_layered_file_stops_every_node(tmp_path, capfd, node_name, order):
    quoted = quoted_file(tmp_path)
    files = [PLATFORM, quoted] if order == 'quoted last' else [quoted, PLATFORM]
    arguments = [argument for path in files for argument in ('--params-file', path)]
    assert run_main(node_name, arguments) == 1
    line = fatal_line(capfd)
    assert "'leg_length_max' must be of type double, got '0.9' (str)" in line
    assert 'quoted.yaml' in line and 'without quotes' in line


def test_a_quoted_number_given_with_p_over_a_file_stops_the_node(capfd):
    assert run_main('ik_node', ['--params-file', PLATFORM, '-p', 'leg_length_max:="0.9"']) == 1
    assert '-p leg_length_max:="0.9"' in fatal_line(capfd)


def test_a_quoted_number_in_a_node_section_stops_that_node_only(ros, tmp_path):
    quoted = quoted_file(tmp_path, section='fk_node')
    with pytest.raises(ValueError, match="'leg_length_max' must be of type double.*quoted"):
        FkNode(cli_args=['--ros-args', '--params-file', PLATFORM, '--params-file', quoted,
                         '--params-file', SOLVER])
    # The section of an fk_node in another namespace does not apply to this one.
    other = quoted_file(tmp_path, section='/robot_b/fk_node')
    node = FkNode(cli_args=['--ros-args', '--params-file', PLATFORM, '--params-file', other,
                            '--params-file', SOLVER])
    assert node.get_parameter('leg_length_max').value == float('inf')
    node.destroy_node()


def test_layered_files_are_applied_in_either_order(ros, tmp_path):
    for files in ([PLATFORM, LIMITS], [LIMITS, PLATFORM]):
        arguments = ['--ros-args'] + [a for path in files for a in ('--params-file', path)]
        node = FkNode(cli_args=arguments + ['--params-file', SOLVER])
        expected = 0.9 if files[-1] == LIMITS else float('inf')
        assert node.get_parameter('leg_length_max').value == expected
        assert node.geometry.leg_length_max == expected
        node.destroy_node()


def test_a_number_without_a_dot_is_a_double_for_nodes_and_tools_alike(ros, tmp_path):
    # rcl reads 9e-1 as a double; PyYAML alone would read a string.
    limits = write(tmp_path, 'exponent.yaml', '/**:\n  ros__parameters:\n    '
                   'leg_length_max: 9e-1\n    leg_length_min: 65e-2\n')
    node = FkNode(cli_args=['--ros-args', '--params-file', PLATFORM, '--params-file', limits,
                            '--params-file', SOLVER])
    assert node.geometry.leg_length_max == 0.9 and node.geometry.leg_length_min == 0.65
    node.destroy_node()
    from stewart_kinematics import load_geometry
    assert load_geometry([PLATFORM, limits]).leg_length_max == 0.9


def test_a_misspelt_name_given_to_a_node_built_in_process_is_refused(ros, tmp_path):
    typo = write(tmp_path, 'typo.yaml', '/**:\n  ros__parameters:\n    leg_lenght_max: 0.9\n')
    with pytest.raises(ValueError, match="'leg_lenght_max' \\(did you mean 'leg_length_max'"):
        FkNode(cli_args=['--ros-args', '--params-file', PLATFORM, '--params-file', typo])
    with pytest.raises(ValueError, match="'tolerence' \\(did you mean 'tolerance'"):
        FkNode(cli_args=['--ros-args', '--params-file', PLATFORM],
               parameter_overrides=[Parameter('tolerence', value=1e-9)])
    with pytest.raises(ValueError, match="'max_iteration' \\(did you mean 'max_iterations'"):
        FkNode(cli_args=['--ros-args', '--params-file', PLATFORM, '-p', 'max_iteration:=5'])


@pytest.mark.parametrize('namespace', ['', '/robot', '/a/b'])
def test_sections_apply_to_a_node_as_rcl_applies_them(ros, tmp_path, namespace):
    # Compared with rclpy's own view, read through its public API: a node that declares every
    # override it was given.
    keys = ['/**', 'probe', '/probe', '/**/probe', '/*', '/robot/probe', 'robot/probe',
            '/*/probe', '**', '/robot/**', '/robot/*', '/*/*/probe', '/a/**', '/a/**/probe',
            'other', '/robot/other', '/a/b/probe']
    document = {key: {'ros__parameters': {f'p{index}': index}}
                for index, key in enumerate(keys)}
    path = write(tmp_path, 'sections.yaml', yaml.safe_dump(document))
    arguments = ['--ros-args', '--params-file', path, '-p', 'probe:q:=1', '-p', 'other:r:=2']
    node = Node('probe', namespace=namespace, cli_args=arguments,
                automatically_declare_parameters_from_overrides=True)
    try:
        rclpy_names = set(node.list_parameters([], 0).names) - {
            'use_sim_time', 'start_type_description_service'}
        sources = ParameterSources(node.get_fully_qualified_name(), arguments)
        assert set(sources.names()) == rclpy_names
    finally:
        node.destroy_node()


#: Scalars whose type rcl decides by C's strtol and strtod, not by YAML 1.1 (issue 27), and a
#: null, which rcl reads as a string and the package's reader marks as null.
EDGE_SCALARS = ['1', '-9223372036854775808', '0777', '0x1F', '99999999999999999999',
                '0x7fffffffffffffff1', '1e-3', '.inf', '08', '1e999', '1e-400', '5e-324',
                '1_000', 'yes', 'Off', 'abc', 'null', '~', "'0.9'", '!!str 1.0', '!!float 3',
                '"' + '1' * 5000 + '"', '1' * 5000]


def test_every_scalar_is_typed_as_rcl_types_it(ros, tmp_path):
    # Compared with rclpy's own view: a node that declares every override it was given. The
    # keys are written as rcl takes them too (on, 1e-3: not YAML's true and 0.001).
    lines = ''.join(f'    p{index}: {text}\n' for index, text in enumerate(EDGE_SCALARS))
    path = write(tmp_path, 'scalars.yaml', '/**:\n  ros__parameters:\n' + lines
                 + '    on: 1\n    1e-3: 2\n')
    node = Node('probe', cli_args=['--ros-args', '--params-file', path],
                automatically_declare_parameters_from_overrides=True)
    try:
        ours = ros_parameters.ParameterSources('/probe', ['--ros-args', '--params-file', path])
        ours = {name: value for name, value, _ in ours.values()}
        for name in [f'p{index}' for index in range(len(EDGE_SCALARS))] + ['on', '1e-3']:
            theirs = node.get_parameter(name).value
            assert type(ours[name]) in (type(theirs), parameters.NullString,
                                        parameters.OutOfRangeNumber), name
            assert ours[name] == theirs, (name, ours[name], theirs)
    finally:
        node.destroy_node()


def test_no_private_rclpy_attribute_is_read():
    source = Path(ros_parameters.__file__).read_text(encoding='utf-8')
    assert '_parameter_overrides' not in source
