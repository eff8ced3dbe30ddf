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
launch/motion_cueing.launch.py, run without ``launch`` installed, as test_launch_file.py does.

The same strict stand-ins of launch and launch_ros (test_launch_file.py) play ``ros2 launch``'s
part; the package's share directory holds what setup.py installs (config/*.yaml and
config/cueing_presets/*.yaml). The chain starts telemetry_bridge, motion_cueing_node and
ik_node with the files the how-to names, and every file and every ``-p`` it gives a node is
one the node takes.
"""

import importlib.machinery
import importlib.util
from pathlib import Path
import shutil
import sys

import pytest
from stewart_kinematics.parameters import (IkNodeSettings, MotionCueingNodeSettings,
                                           TelemetryBridgeNodeSettings)
from stewart_kinematics.parameters.files import section_applies
import test_launch_file as stand_ins
import yaml

pytestmark = pytest.mark.node

ROOT = stand_ins.ROOT
LAUNCH_FILE = ROOT / 'launch' / 'motion_cueing.launch.py'
PRESETS = sorted(path.stem for path in (ROOT / 'config' / 'cueing_presets').glob('*.yaml'))
SETTINGS = {'telemetry_bridge': TelemetryBridgeNodeSettings,
            'motion_cueing_node': MotionCueingNodeSettings, 'ik_node': IkNodeSettings}


@pytest.fixture
def share_directory(tmp_path):
    """Lay out share/stewart_kinematics as setup.py installs it, presets included."""
    setup = (ROOT / 'setup.py').read_text(encoding='utf-8')
    assert "glob('config/cueing_presets/*.yaml')" in setup, 'the presets are not installed'
    share = tmp_path / 'install' / 'share' / stand_ins.PACKAGE
    for pattern in ('config/*.yaml', 'config/cueing_presets/*.yaml'):
        for path in sorted(ROOT.glob(pattern)):
            target = share / path.relative_to(ROOT)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(path, target)
    return share


@pytest.fixture
def launch(monkeypatch, share_directory):
    """Run the launch file with ``name=value`` arguments; return what each node would start."""
    for name, module in stand_ins.stub_modules(share_directory).items():
        monkeypatch.setitem(sys.modules, name, module)

    def run(**arguments):
        loader = importlib.machinery.SourceFileLoader('motion_cueing_launch', str(LAUNCH_FILE))
        module = importlib.util.module_from_spec(
            importlib.util.spec_from_loader(loader.name, loader))
        loader.exec_module(module)
        description = module.generate_launch_description()
        configurations = dict(arguments)
        nodes = []
        for entity in description.entities:
            if isinstance(entity, stand_ins.DeclareLaunchArgument):
                stand_ins.declare(entity, configurations)
            elif isinstance(entity, stand_ins.Node):
                assert entity.condition is None
                nodes.append(stand_ins.expand(entity, configurations))
            else:
                raise AssertionError(f'unexpected launch entity {entity!r}')
        declared = {entity.name for entity in description.entities
                    if isinstance(entity, stand_ins.DeclareLaunchArgument)}
        assert set(arguments) <= declared, set(arguments) - declared
        return nodes
    return run


def given_parameters(node):
    """Return the parameters a node gets from its files and ``-p``, as rcl layers them."""
    full_name = node['namespace'].rstrip('/') + '/' + node['executable']
    values = {}
    for path in node['parameter_files']:
        sections = yaml.safe_load(Path(path).read_text(encoding='utf-8'))
        # rcl matches a section against the node's full name: 'ik_node' is /ik_node only.
        for key in ['/**'] + [key for key in sections if key != '/**']:
            if section_applies(key, full_name):
                values.update((sections.get(key) or {}).get('ros__parameters', {}))
    arguments = node['ros_arguments']
    for flag, option in zip(arguments[::2], arguments[1::2]):
        assert flag == '-p', arguments
        name, value = option.split(':=', 1)
        values[name] = yaml.safe_load(value)
    return values


def test_the_launch_file_imports_only_what_is_stubbed():
    """As the other launch file: only the stand-ins' modules and os."""
    source = LAUNCH_FILE.read_text(encoding='utf-8')
    for line in source.splitlines():
        if line.startswith(('import ', 'from ')):
            module = line.split()[1]
            assert module in stand_ins.STUBBED_MODULES + ('os',), line


def test_default_launch_is_the_chain_with_the_car_preset(launch, share_directory):
    """telemetry_bridge -> motion_cueing_node -> ik_node, the paper's platform, car.yaml."""
    nodes = launch()

    config = share_directory / 'config'
    assert [node['executable'] for node in nodes] == [
        'telemetry_bridge', 'motion_cueing_node', 'ik_node']
    bridge, cueing, ik = nodes
    assert bridge['parameter_files'] == [str(config / 'telemetry_bridge.yaml')]
    assert bridge['ros_arguments'] == ['-p', 'telemetry_address:=127.0.0.1',
                                       '-p', 'telemetry_port:=47800']
    platform = [str(config / 'paper_platform.yaml'), str(config / 'example_limits.yaml')]
    assert cueing['parameter_files'] == platform + [str(config / 'cueing_presets' / 'car.yaml')]
    assert ik['parameter_files'] == platform
    # ik_node streams: the drives get the leg rates at the times joint_commands is stamped,
    # not the cue's as the transport delivered it (uneven by a few ms at 100 Hz).
    assert ik['ros_arguments'] == ['-p', 'command_rate:=100.0']
    assert launch(command_rate='250.0')[2]['ros_arguments'] == ['-p', 'command_rate:=250.0']
    scripts = stand_ins.console_scripts()
    for node in nodes:
        assert node['executable'] in scripts and node['namespace'] == '/'
        assert node['remappings'] == []   # the relative topics connect as they are
        for path in node['parameter_files']:
            assert Path(path).is_file(), f'{path} is not installed'


@pytest.mark.parametrize('preset', PRESETS)
def test_each_preset_is_a_choice_and_every_parameter_is_declared_and_allowed(launch, preset):
    """preset:=<name> gives motion_cueing_node its file; each node takes every value it gets."""
    assert PRESETS == ['aircraft', 'car', 'race_car']
    nodes = launch(preset=preset, telemetry_port='50000', namespace='sim')
    assert nodes[1]['parameter_files'][-1].endswith(f'cueing_presets/{preset}.yaml')
    for node in nodes:
        assert node['namespace'] == '/sim'
        specs = {spec.name: spec for spec in SETTINGS[node['executable']].specs()}
        for name, value in given_parameters(node).items():
            assert name in specs, f"{node['executable']} has no parameter {name}"
            assert not specs[name].check(value), (name, value, specs[name].check(value))
    assert given_parameters(nodes[0])['telemetry_port'] == 50000


@pytest.mark.parametrize('preset', PRESETS)
def test_a_namespace_changes_no_parameter_a_node_gets(launch, preset):
    """namespace:=sim: each node still gets its section of the shipped files (its preset)."""
    plain = launch(preset=preset)
    spaced = launch(preset=preset, namespace='sim')
    for root, inside in zip(plain, spaced):
        assert inside['namespace'] == '/sim'
        assert given_parameters(inside) == given_parameters(root), inside['executable']
    assert given_parameters(spaced[0])['queue_depth'] == 100   # telemetry_bridge.yaml's
    assert given_parameters(spaced[1])['queue_depth'] == 100   # the preset's


def test_files_of_ones_own_replace_the_shipped_ones(launch, tmp_path):
    """platform_config, limits_config and cueing_config: the user's files, in that order."""
    files = {name: str(tmp_path / f'{name}.yaml') for name in ('platform', 'limits', 'cueing')}
    nodes = launch(platform_config=files['platform'], limits_config=files['limits'],
                   cueing_config=files['cueing'], telemetry_address='0.0.0.0')
    assert nodes[1]['parameter_files'] == [files['platform'], files['limits'], files['cueing']]
    assert nodes[2]['parameter_files'] == [files['platform'], files['limits']]
    assert nodes[0]['ros_arguments'][1] == 'telemetry_address:=0.0.0.0'


def test_an_unknown_preset_is_refused(launch):
    """The preset argument is declared with its choices, as ros2 launch checks them."""
    with pytest.raises(AssertionError, match='preset'):
        launch(preset='tractor')
