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
Every parameter file in config/ loads, and each node starts with the files meant for it.

rclpy silently ignores a parameter file entry that the node does not declare, so a misspelt
name would go unnoticed at start-up: these tests compare every name in the files with the
parameter specs and check that each value the files give is the value the node ends up with.
"""

import math
from pathlib import Path

from helpers import free_udp_port
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.parameter import Parameter

from stewart_kinematics import parameters
from stewart_kinematics.parameters import load_geometry
from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.mock_platform import MockPlatform
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
from stewart_kinematics.ros.telemetry_bridge import TelemetryBridge
from stewart_kinematics.ros.trajectory_node import TrajectoryNode
import yaml

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
CONFIG_FILES = sorted(CONFIG_DIRECTORY.glob('*.yaml'))

#: The parameters each node declares, as its constructor does.
NODE_SPECS = {
    'ik_node': (parameters.GEOMETRY_PARAMETERS + parameters.ACTUATOR_PARAMETERS
                + parameters.FRAME_PARAMETERS + parameters.MARKER_PARAMETERS
                + parameters.WORKSPACE_PARAMETERS + parameters.STREAMING_PARAMETERS
                + parameters.QUEUE_PARAMETERS),
    'fk_node': (parameters.GEOMETRY_PARAMETERS + parameters.ACTUATOR_PARAMETERS
                + parameters.SOLVER_PARAMETERS + parameters.FRAME_PARAMETERS
                + parameters.QUEUE_PARAMETERS),
    'trajectory_node': (parameters.GEOMETRY_PARAMETERS + parameters.ACTUATOR_PARAMETERS
                        + parameters.FRAME_PARAMETERS + parameters.RAMP_PARAMETERS
                        + parameters.MOTION_PARAMETERS + parameters.QUEUE_PARAMETERS),
    'motion_cueing_node': parameters.MotionCueingNodeSettings.specs(),
    'mock_platform': parameters.MockPlatformNodeSettings.specs(),
    'telemetry_bridge': parameters.TelemetryBridgeNodeSettings.specs(),
}
#: Each node class and the config files it is meant to take, in order.
NODE_FILES = {
    'ik_node': (IkNode, ('paper_platform.yaml', 'example_limits.yaml', 'solver.yaml',
                         'example_masses.yaml')),
    'fk_node': (FkNode, ('paper_platform.yaml', 'example_limits.yaml', 'solver.yaml')),
    'trajectory_node': (TrajectoryNode, ('paper_platform.yaml', 'example_limits.yaml',
                                         'table3_ramp.yaml')),
    # motion_cueing_preview.yaml is layered last: the MPC with a preview, over the classical.
    'motion_cueing_node': (MotionCueingNode, ('paper_platform.yaml', 'example_limits.yaml',
                                              'motion_cueing.yaml', 'motion_cueing_preview.yaml')),
    'mock_platform': (MockPlatform, ('paper_platform.yaml', 'example_limits.yaml',
                                     'example_masses.yaml', 'mock_platform.yaml')),
    'telemetry_bridge': (TelemetryBridge, ('telemetry_bridge.yaml',)),
}
#: The platform designs that share joints, each one file for every node (geometry, limits and
#: trajectory_node's ramp), and the design its geometry must be.
DESIGN_FILES = {'platform_6_3.yaml': '6-3', 'platform_3_3.yaml': '3-3'}


def load(path):
    """Parse a YAML file with yaml.safe_load."""
    with open(path, encoding='utf-8') as stream:
        return yaml.safe_load(stream)


def names_of(specs):
    """Return the set of parameter names of some specs."""
    return {spec.name for spec in specs}


def node_of(key):
    """Return the node a section is for: ``ik_node``, ``/ik_node`` or ``/**/ik_node``."""
    return key[len('/**/'):] if key.startswith('/**/') else key.lstrip('/')


def file_view(paths, node_name):
    """
    Return the parameters a node sees from some files, as rcl applies them.

    Later files override earlier ones; within a file the node's own section overrides ``/**``.
    """
    values = {}
    for path in paths:
        document = load(path)
        for section in ('/**', '/**/' + node_name, node_name, '/' + node_name):
            if section in document:
                values.update(document[section]['ros__parameters'])
    return values


@pytest.fixture
def nodes(ros):
    """Collect nodes to destroy when the test ends."""
    created = []
    yield created
    for node in created:
        node.destroy_node()


def test_config_directory_has_yaml_files():
    """The package ships its parameter files in config/."""
    assert {path.name for path in CONFIG_FILES} >= {
        'paper_platform.yaml', 'solver.yaml', 'table3_ramp.yaml'}


@pytest.mark.parametrize('path', CONFIG_FILES, ids=lambda path: path.name)
def test_file_parses_with_the_ros_parameters_layout(path):
    """Each file is YAML mapping a node name or /** to a ros__parameters map, and nothing else."""
    document = load(path)
    assert isinstance(document, dict) and document, f'{path.name} is empty or not a map'
    for key, section in document.items():
        assert key == '/**' or node_of(key) in NODE_SPECS, (
            f'{path.name}: section {key!r} is neither /** nor a node of this package')
        assert isinstance(section, dict) and list(section) == ['ros__parameters'], (
            f'{path.name}: section {key!r} must hold exactly ros__parameters')
        assert isinstance(section['ros__parameters'], dict) and section['ros__parameters']


@pytest.mark.parametrize('path', CONFIG_FILES, ids=lambda path: path.name)
def test_file_names_only_declared_parameters(path):
    """A node's section names only that node's parameters; /** names only declared ones."""
    every_name = set().union(*(names_of(specs) for specs in NODE_SPECS.values()))
    for key, section in load(path).items():
        names = set(section['ros__parameters'])
        if key == '/**':
            unknown = names - every_name
        else:
            unknown = names - names_of(NODE_SPECS[node_of(key)])
        assert not unknown, f'{path.name}: section {key!r} sets unknown parameters {unknown}'


@pytest.mark.parametrize('path', CONFIG_FILES, ids=lambda path: path.name)
def test_file_values_pass_the_specs(path):
    """Every value in every section is allowed by its spec (type and validators)."""
    specs = {spec.name: spec for specs in NODE_SPECS.values() for spec in specs}
    for key, section in load(path).items():
        for name, value in section['ros__parameters'].items():
            if name in specs:
                assert specs[name].check(value) == '', f'{path.name}: {key}/{name}'


@pytest.mark.parametrize('node_name', sorted(NODE_FILES))
def test_node_starts_with_its_config_files(nodes, node_name):
    """Each node starts with its files; every parameter they set is declared and applied."""
    node_class, file_names = NODE_FILES[node_name]
    paths = [str(CONFIG_DIRECTORY / name) for name in file_names]
    arguments = ['--ros-args']
    for path in paths:
        arguments += ['--params-file', path]
    # telemetry_bridge on a free port, not the file's: two test workers never collide.
    overrides = {'telemetry_port': free_udp_port()} if node_name == 'telemetry_bridge' else {}
    node = node_class(cli_args=arguments, parameter_overrides=[
        Parameter(name, value=value) for name, value in overrides.items()])
    nodes.append(node)
    assert node.get_name() == node_name
    seen = {**file_view(paths, node_name), **overrides}
    # /** sections may hold parameters of other nodes; each of this node's own is applied.
    declared = names_of(NODE_SPECS[node_name])
    assert set(seen) & declared, f'{node_name} takes nothing from {file_names}'
    for name in declared:
        assert node.has_parameter(name), f'{node_name} does not declare {name}'
    for name, value in seen.items():
        if name in declared:
            assert node.get_parameter(name).value == value, name
    for file_name in file_names:
        for key, section in load(CONFIG_DIRECTORY / file_name).items():
            if node_of(key) == node_name:
                assert set(section['ros__parameters']) <= declared


def test_every_wildcard_parameter_is_declared_by_a_node_that_takes_the_file():
    """Each /** parameter of a file reaches at least one node meant to take that file."""
    for file_name in {name for _, names in NODE_FILES.values() for name in names}:
        takers = [node for node, (_, names) in NODE_FILES.items() if file_name in names]
        wildcard = load(CONFIG_DIRECTORY / file_name).get('/**', {'ros__parameters': {}})
        for name in wildcard['ros__parameters']:
            assert any(name in names_of(NODE_SPECS[node]) for node in takers), (
                f'{file_name}: /** parameter {name} is declared by none of {takers}')


# The nodes with a geometry (telemetry_bridge has none).
@pytest.mark.parametrize('node_name', sorted(set(NODE_FILES) - {'telemetry_bridge'}))
@pytest.mark.parametrize('file_name', sorted(DESIGN_FILES))
def test_node_starts_with_a_design_file_alone(nodes, node_name, file_name):
    """Each node starts with a 6-3 or 3-3 file alone; every value it sets is applied."""
    path = CONFIG_DIRECTORY / file_name
    node = NODE_FILES[node_name][0](cli_args=['--ros-args', '--params-file', str(path)])
    nodes.append(node)
    seen = file_view([path], node_name)
    declared = names_of(NODE_SPECS[node_name])
    assert {'base_joints', 'platform_joints'} <= set(seen) & declared
    for name, value in seen.items():
        if name in declared:
            assert node.get_parameter(name).value == value, name
    if hasattr(node, 'geometry'):
        assert node.geometry.design == DESIGN_FILES[file_name]


@pytest.mark.parametrize('file_name', sorted(DESIGN_FILES))
def test_design_files_load_as_their_design(file_name):
    """load_geometry reads each design file; its home pose keeps the file's own limits."""
    geometry = load_geometry(CONFIG_DIRECTORY / file_name)
    assert geometry.design == DESIGN_FILES[file_name]
    assert len(geometry.shared_joints) == 12 - sum(map(int, geometry.design.split('-')))
    assert geometry.leg_length_min < geometry.home_leg_lengths.min()
    assert geometry.home_leg_lengths.max() < geometry.leg_length_max
    assert geometry.leg_radius > 0.0 and math.isfinite(geometry.max_jacobian_condition)


def test_every_config_file_is_taken_by_a_node():
    """No config file is left out of the node start-up tests above."""
    used = {name for _, names in NODE_FILES.values() for name in names} | set(DESIGN_FILES)
    assert {path.name for path in CONFIG_FILES} <= used


def test_ik_and_fk_see_the_same_geometry(nodes):
    """The shared /** geometry reaches both kinematics nodes identically."""
    arguments = ['--ros-args', '--params-file', str(CONFIG_DIRECTORY / 'paper_platform.yaml'),
                 '--params-file', str(CONFIG_DIRECTORY / 'solver.yaml')]
    ik, fk = IkNode(cli_args=arguments), FkNode(cli_args=arguments)
    nodes.extend([ik, fk])
    assert_allclose(ik.geometry.base_joints, fk.geometry.base_joints, atol=0.0)
    assert_allclose(ik.geometry.platform_joints, fk.geometry.platform_joints, atol=0.0)
    assert_allclose(ik.geometry.home_pose, fk.geometry.home_pose, atol=0.0)
    assert (fk.tracker.settings.tolerance, fk.tracker.settings.max_iterations) == (1e-12, 50)


def test_load_geometry_reads_the_paper_platform():
    """load_geometry reads Tables 1 and 2 (mm typed here, / 1000) and the home pose."""
    geometry = load_geometry(CONFIG_DIRECTORY / 'paper_platform.yaml')
    base_mm = [[48.6989, 219.6666, 0.0], [165.8874, 152.0078, 0.0],
               [165.8874, -152.0078, 0.0], [48.6989, -219.6666, 0.0],
               [-214.5863, -67.6588, 0.0], [-214.5863, 67.6588, 0.0]]
    platform_mm = [[-51.3030, 140.9539, 275.0], [147.7212, 26.0472, 275.0],
                   [147.7212, -26.0472, 257.0], [-51.3030, -140.9539, 275.0],
                   [-96.4181, -114.9067, 275.0], [-96.4181, 114.9067, 275.0]]
    assert_allclose(geometry.base_joints, np.array(base_mm) / 1000.0, rtol=0.0, atol=1e-15)
    assert_allclose(geometry.platform_joints, np.array(platform_mm) / 1000.0,
                    rtol=0.0, atol=1e-15)
    assert_allclose(geometry.home_pose, [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0], atol=0.0)
    assert geometry.leg_length_min == 0.0
    assert geometry.leg_length_max == float('inf')
    # Leg 1 at home: |(0, 0, 0.4325) + p_1 - b_1|, worked out by hand.
    leg_1 = np.array([-0.0513030 - 0.0486989, 0.1409539 - 0.2196666, 0.4325 + 0.275])
    assert geometry.home_leg_lengths[0] == pytest.approx(np.linalg.norm(leg_1), abs=1e-15)
    assert_allclose(
        geometry.home_leg_lengths,
        [0.71885487, 0.71885488, 0.70114644, 0.71885487, 0.71885488, 0.71885488], atol=1e-8)


def test_load_geometry_with_a_node_name():
    """Reading the file as a named node applies /** as well (that node has no own section)."""
    plain = load_geometry(CONFIG_DIRECTORY / 'paper_platform.yaml')
    as_ik = load_geometry(CONFIG_DIRECTORY / 'paper_platform.yaml', node_name='ik_node')
    assert_allclose(as_ik.base_joints, plain.base_joints, atol=0.0)
    assert_allclose(as_ik.home_leg_lengths, plain.home_leg_lengths, atol=0.0)
