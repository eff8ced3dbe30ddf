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
The cueing presets (config/cueing_presets/): each loads into motion_cueing_node, within limits.

Each preset, after the paper's platform and example_limits.yaml as the how-to gives them,
starts motion_cueing_node with every value of the file applied, and the first 8 s of the
built-in slalom through the same cueing break no limit. The how-to's table names every preset.
About 3 s.
"""

from pathlib import Path

import pytest
from stewart_kinematics.cueing import MotionCueing, replay
from stewart_kinematics.cueing.scenarios import scenario
from stewart_kinematics.parameters import load_settings, MotionCueingNodeSettings
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
import yaml

pytestmark = pytest.mark.node

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / 'config'
PRESETS = sorted((CONFIG / 'cueing_presets').glob('*.yaml'))
PLATFORM = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml']


def test_the_presets_are_the_three_vehicles():
    """car, race_car and aircraft, each named in the how-to's table of presets."""
    assert [path.stem for path in PRESETS] == ['aircraft', 'car', 'race_car']
    page = (ROOT / 'doc' / 'how-to' / 'simulator.md').read_text(encoding='utf-8')
    for path in PRESETS:
        assert f'| `{path.stem}` |' in page, path.stem


@pytest.mark.parametrize('path', PRESETS, ids=lambda path: path.stem)
def test_a_preset_starts_motion_cueing_node_with_its_values(ros, path):
    """Every value of the file is declared by the node and is the value it runs with."""
    arguments = ['--ros-args']
    for file in PLATFORM + [path]:
        arguments += ['--params-file', str(file)]
    node = MotionCueingNode(cli_args=arguments)
    try:
        values = yaml.safe_load(path.read_text(encoding='utf-8'))[
            '/**/motion_cueing_node']['ros__parameters']
        assert len(values) > 15
        for name, value in values.items():
            assert node.has_parameter(name), name
            assert node.get_parameter(name).value == value, name
    finally:
        node.destroy_node()


@pytest.mark.parametrize('path', PRESETS, ids=lambda path: path.stem)
def test_a_preset_cues_the_slalom_within_every_limit(path):
    """8 s of the slalom at 50 Hz: the cue moves, and no command breaks a limit."""
    settings = load_settings(MotionCueingNodeSettings, PLATFORM + [path])
    cueing = MotionCueing.from_parameters(settings.as_values())
    drive = scenario('slalom', 50.0)
    count = 400
    result = replay(cueing, drive.times[:count], drive.specific_force[:count],
                    drive.angular_velocity[:count])
    assert abs(result.poses[:, 1] - result.poses[0, 1]).max() > 1e-3   # sway moved
    lengths = result.lengths
    assert lengths.min() >= 0.65 and lengths.max() <= 0.90   # example_limits' stroke
