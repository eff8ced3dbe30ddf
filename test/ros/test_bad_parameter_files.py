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
Every node's main() refuses a bad parameter file: exit code 1 and a log that names the problem.

Each case is config/paper_platform.yaml with one parameter changed (or removed), written to a
temporary folder and given to ik_node, fk_node and trajectory_node exactly as ``ros2 run``
would, through main(); main() initialises rclpy itself, so these tests use no ``ros`` fixture.
The log is read from the process's file descriptors (capfd), where rcutils writes it.

Hostile files too (issue 27): an alias bomb, a list 100,000 deep, a mapping 3,000 deep, a null
and an empty value are refused at once, the file and its line named, before rcl reads them
(rcl alone, parsing the deep list level by level, takes far longer).
"""

from pathlib import Path
import threading
import time

import pytest
import rclpy

from stewart_kinematics.ros import fk_node, ik_node, trajectory_node
import yaml

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
PLATFORM_FILE = CONFIG_DIRECTORY / 'paper_platform.yaml'
SOLVER_FILE = str(CONFIG_DIRECTORY / 'solver.yaml')
RAMP_FILE = str(CONFIG_DIRECTORY / 'table3_ramp.yaml')

#: Each node's main() and the valid files it gets after the bad geometry file.
NODES = {
    'ik_node': (ik_node.main, []),
    'fk_node': (fk_node.main, [SOLVER_FILE]),
    'trajectory_node': (trajectory_node.main, [RAMP_FILE]),
}
REMOVED = object()
#: Seconds after which a main() that did not refuse its file is stopped.
WATCHDOG = 10.0


def platform_parameters():
    """Return the ros__parameters of config/paper_platform.yaml."""
    with open(PLATFORM_FILE, encoding='utf-8') as stream:
        return yaml.safe_load(stream)['/**']['ros__parameters']


def joints_on_a_line():
    """Return six distinct base joints on the line y = x / 2, z = 0 (flat list, metres)."""
    return [float(v) for i in range(6) for v in (0.05 * i - 0.1, 0.025 * i - 0.05, 0.0)]


def platform_with_joints_1_and_3_on_joint_2():
    """Return the paper's platform joints with p_1 and p_3 moved onto p_2 (flat list, metres)."""
    joints = platform_parameters()['platform_joints']
    return joints[3:6] * 3 + joints[9:]


#: (case id, {parameter: bad value or REMOVED}, words the log must contain).
BAD_GEOMETRY = [
    ('required base_joints missing', {'base_joints': REMOVED},
     ["'base_joints' is required"]),
    ('string for a double array', {'base_joints': 'b1 b2 b3 b4 b5 b6'},
     ["'base_joints'", 'DOUBLE_ARRAY']),
    ('integer list for a double list', {'home_position': [0, 0, 1]},
     ["'home_position'", 'INTEGER_ARRAY', 'DOUBLE_ARRAY']),
    ('string for a double', {'leg_length_max': 'long'},
     ["'leg_length_max'", 'STRING', 'DOUBLE']),
    ('17 base joint values', {'base_joints': [0.1] * 17},
     ["'base_joints' must have exactly 18 elements, got 17"]),
    ('2 home_position values', {'home_position': [0.0, 0.4325]},
     ["'home_position' must have exactly 3 elements, got 2"]),
    ('NaN in the platform joints',
     {'platform_joints': [float('nan')] + platform_parameters()['platform_joints'][1:]},
     ["'platform_joints' must be finite"]),
    ('three legs on one platform joint',
     {'platform_joints': platform_with_joints_1_and_3_on_joint_2()},
     ['platform_joints: joints 1, 2 and 3 coincide (3 legs on one point); a joint may be '
      'shared by 2 legs at most']),
    ('collinear base joints', {'base_joints': joints_on_a_line()},
     ['base_joints: the six joints are collinear']),
    ('leg_length_max zero', {'leg_length_max': 0.0},
     ["'leg_length_max' must be in (0, inf], got 0.0"]),
    ('leg_length_max negative', {'leg_length_max': -0.5},
     ["'leg_length_max' must be in (0, inf], got -0.5"]),
    ('leg_length_min negative', {'leg_length_min': -0.1},
     ["'leg_length_min' must be in [0, inf], got -0.1"]),
    ('leg_length_min above leg_length_max', {'leg_length_min': 0.8, 'leg_length_max': 0.7},
     ['leg_length_min < leg_length_max', 'leg_length_min=0.8', 'leg_length_max=0.7']),
    ('base cone 0 deg', {'base_joint_max_angle_deg': 0.0},
     ["'base_joint_max_angle_deg' must be in (0, 180], got 0.0"]),
    ('base cone 200 deg', {'base_joint_max_angle_deg': 200.0},
     ["'base_joint_max_angle_deg' must be in (0, 180], got 200.0"]),
    ('platform cone 200 deg', {'platform_joint_max_angle_deg': 200.0},
     ["'platform_joint_max_angle_deg' must be in (0, 180], got 200.0"]),
    ('condition limit 0.5', {'max_jacobian_condition': 0.5},
     ["'max_jacobian_condition' must be in [1, inf], got 0.5"]),
    ('home pose beyond leg_length_max', {'leg_length_max': 0.71},
     ['the home pose breaks the limits: leg 1: leg_length_max 0.71 m']),
    ('home orientation 270 deg', {'home_orientation_deg': [0.0, 0.0, 270.0]},
     ["'home_orientation_deg' must be in [-180, 180]"]),
]


def write_platform_file(tmp_path, changes):
    """Write paper_platform.yaml with ``changes`` applied (REMOVED deletes); return its path."""
    parameters = platform_parameters()
    for name, value in changes.items():
        if value is REMOVED:
            del parameters[name]
        else:
            parameters[name] = value
    path = tmp_path / 'bad_platform.yaml'
    path.write_text(yaml.safe_dump({'/**': {'ros__parameters': parameters}}), encoding='utf-8')
    return str(path)


def main_with_watchdog(main, arguments):
    """
    Call a node's main() and return its exit code; shut rclpy down if it is still running.

    A node that wrongly accepts its file would spin forever: after WATCHDOG seconds rclpy is
    shut down, main() returns 0, and the test fails instead of hanging.
    """
    watchdog = threading.Timer(WATCHDOG, rclpy.try_shutdown)
    watchdog.start()
    try:
        return main(arguments)
    finally:
        watchdog.cancel()


def run_main(node_name, files):
    """Run a node's main() with these parameter files, as ros2 run would; return its code."""
    main, extra_files = NODES[node_name]
    arguments = [node_name, '--ros-args']
    for path in files + extra_files:
        arguments += ['--params-file', path]
    return main_with_watchdog(main, arguments)


def assert_refused(code, capfd, words):
    """Check exit code 1, rclpy shut down, and a fatal log line containing every word."""
    captured = capfd.readouterr()
    log = captured.out + captured.err
    assert code == 1, log
    assert not rclpy.ok()
    fatal = [line for line in log.splitlines() if '[FATAL]' in line and 'cannot start' in line]
    assert fatal, log
    for word in words:
        assert word in fatal[0], f'{word!r} not in {fatal[0]!r}'


@pytest.mark.parametrize('node_name', NODES)
@pytest.mark.parametrize('changes, words', [case[1:] for case in BAD_GEOMETRY],
                         ids=[case[0] for case in BAD_GEOMETRY])
def test_main_refuses_a_bad_geometry(tmp_path, capfd, node_name, changes, words):
    """A bad geometry parameter makes main() return 1 with a log naming it and the problem."""
    path = write_platform_file(tmp_path, changes)
    assert_refused(run_main(node_name, [path]), capfd, words)


@pytest.mark.parametrize('node_name', NODES)
def test_main_refuses_a_missing_file(tmp_path, capfd, node_name):
    """A parameter file that does not exist makes main() return 1 with a log naming it."""
    missing = str(tmp_path / 'no_such_platform.yaml')
    assert_refused(run_main(node_name, [missing]), capfd, [missing, 'params file'])


@pytest.mark.parametrize('name, value, words', [
    ('max_iterations', 0, ["'max_iterations' must be in [1, 1000], got 0"]),
    ('max_iterations', 2.5, ["'max_iterations'", 'DOUBLE', 'INTEGER']),
    ('tolerance', 'tight', ["'tolerance'", 'STRING', 'DOUBLE']),
    ('near_singularity_condition', 0.5,
     ["'near_singularity_condition' must be in [1, inf], got 0.5"]),
    ('assembly_guard_position_change', 0.0,
     ["'assembly_guard_position_change' must be in (0, 10], got 0.0"]),
], ids=['max_iterations 0', 'max_iterations 2.5', 'tolerance string',
        'near_singularity_condition 0.5', 'assembly guard 0 m'])
def test_fk_main_refuses_bad_solver_settings(tmp_path, capfd, name, value, words):
    """A bad solver setting in the fk_node section makes fk_node's main() return 1."""
    path = tmp_path / 'bad_solver.yaml'
    path.write_text(yaml.safe_dump({'fk_node': {'ros__parameters': {name: value}}}),
                    encoding='utf-8')
    code = main_with_watchdog(fk_node.main, [
        'fk_node', '--ros-args', '--params-file', str(PLATFORM_FILE), '--params-file', str(path)])
    assert_refused(code, capfd, words)


#: Hostile files (issue 27): (case id, the layer's text, its line at fault, words of the log).
HOSTILE = [
    ('alias bomb', '\n'.join(f'    a{level}: &a{level} [' + ', '.join(
        [f'*a{level - 1}' if level else '1.0'] * 9) + ']' for level in range(9)),
     4, ['YAML alias *a0']),
    ('list 100000 deep', '    deep: ' + '[' * 100_000 + ']' * 100_000, 3,
     ['nested more than 64 levels deep']),
    ('mapping 3000 deep', '    deep: ' + '{a: ' * 3000 + '1.0' + '}' * 3000, 3,
     ['nested more than 64 levels deep']),
    ('null value', '    leg_length_max: null', 3,
     ["'leg_length_max' must be of type double, got null (an empty value"]),
    ('empty value', '    leg_length_max:', 3, ["the value of 'leg_length_max' is empty"]),
    # rcl refuses a list of mixed types before any node exists, in words that show the null
    # as a string and name no parameter (found by the parameter-file fuzzer, seed 2523776678).
    ('null in a list', '    base_joints: [0.1, ~, 0.2]', 3,
     ["'base_joints' must be of type double_array, got ~ in the list"]),
    ('mixed list', "    joint_names: ['a', 2, 'c', 'd', 'e', 'f']", 3,
     ["'joint_names' must be"]),
]


@pytest.mark.parametrize('node_name', NODES)
@pytest.mark.parametrize('text, line, words', [case[1:] for case in HOSTILE],
                         ids=[case[0] for case in HOSTILE])
def test_main_refuses_a_hostile_file_at_once(tmp_path, capfd, node_name, text, line, words):
    """An alias bomb, deep nesting or a null: refused at once, naming file and line."""
    path = tmp_path / 'hostile.yaml'
    path.write_text('/**:\n  ros__parameters:\n' + text + '\n', encoding='utf-8')
    started = time.monotonic()
    code = run_main(node_name, [str(PLATFORM_FILE), str(path)])
    # rcl alone reads the deep list far longer than this: the package's reader refuses first.
    assert time.monotonic() - started < 5.0
    assert_refused(code, capfd, [f'{path}:{line}'] + words)
