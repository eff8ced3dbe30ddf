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
The fuzzer's own parts, without a node: message generation, the output oracle, parameters.

Property tests (hypothesis, the profiles of test/properties.py): for any seed and every message
type a declared node subscribes to (and a few more), every kind of message builds and
serializes, a plausible one has only finite numbers and unit quaternions, and one seed gives the
same messages twice. The oracle (:class:`OutputInvariants`) is checked against messages made by
hand on each side of each limit, and the parameter fuzzer's expectations against the specs.
The hostile parameter files (fuzzing/fuzz_parameter_files.py) are what they say, the package's
reader keeps every invariant on them, and the oracle finds the defects of issue 27 in a reader
built as the package's was (PyYAML's composer and a recursive walk).
"""

import math
from pathlib import Path
import random

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from fuzzing.fuzz_messages import (
    EVERY_SEQUENCE,
    MessageFuzzer,
    OVERSIZED_CHARACTERS,
    OVERSIZED_ELEMENTS,
    OVERSIZED_NAMES,
    OVERSIZED_VALUES,
    Plausible,
)
from fuzzing.fuzz_parameter_files import (
    alias_bomb,
    deep_list,
    deep_mapping,
    hostile_file,
    huge_scalar,
    KINDS,
    null_value,
    reader_problems,
)
from fuzzing.fuzz_parameters import (
    argument,
    ParameterFuzzer,
    REFUSED,
    start_variant,
)
from fuzzing.fuzz_targets import parameter_files
from fuzzing.node_fuzzer import _inputs_taken
from fuzzing.output_invariants import (
    log_problems,
    MAX_LOG_LINE,
    MAX_OUTPUT_STRING,
    numbers_problems,
    OutputInvariants,
    OutputLog,
    string_problems,
)
from geometry_msgs.msg import Pose, PoseStamped, Twist
from hypothesis import given, strategies as st
from nav_msgs.msg import Path as PathMessage
import numpy as np
from properties import budget
import pytest
from rcl_interfaces.msg import ParameterDescriptor, ParameterType
from rclpy.serialization import serialize_message
from sensor_msgs.msg import Imu, JointState
from std_msgs.msg import Float64MultiArray

from stewart_kinematics.parameters import all_specs
from stewart_kinematics.ros.interfaces import NODE_INTERFACES, SUBSCRIPTION
from trajectory_msgs.msg import (
    JointTrajectory,
    JointTrajectoryPoint,
    MultiDOFJointTrajectory,
)
import yaml

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: Every message type a declared node subscribes to, and a few more for the generic walk.
TYPES = sorted({endpoint.message_type for interface in NODE_INTERFACES.values()
                for endpoint in interface.of_kind(SUBSCRIPTION)} | {Imu, JointTrajectory},
               key=lambda kind: kind.__name__)
HINTS = Plausible(stamp=lambda: (1000, 0))


@pytest.fixture(scope='module')
def invariants():
    """Return the oracle of ik_node's files (paper platform, example limits)."""
    return OutputInvariants.from_parameter_files(parameter_files('ik_node', CONFIG), 'ik_node')


@budget(10)
@given(seed=st.integers(0, 2 ** 32 - 1),
       kind=st.sampled_from(['plausible', 'mutated', 'hostile']))
def test_every_kind_of_message_of_every_type_builds_and_serializes(seed, kind):
    """Any seed, any kind, any declared input type: a message that goes on the wire."""
    rng = random.Random(seed)
    for message_type in TYPES:
        message, done = MessageFuzzer(message_type, rng, HINTS, 'topic').message(kind)
        assert isinstance(message, message_type)
        assert serialize_message(message)
        assert (kind == 'plausible') == (not done)


@budget(10)
@given(seed=st.integers(0, 2 ** 32 - 1))
def test_a_plausible_message_is_finite_with_unit_quaternions(seed):
    """Plausible messages are what a platform could be sent: the oracle finds nothing."""
    rng = random.Random(seed)
    for message_type in TYPES:
        message, _ = MessageFuzzer(message_type, rng, HINTS).message('plausible')
        assert numbers_problems(message) == [], message


@budget(5)
@given(seed=st.integers(0, 2 ** 32 - 1))
def test_one_seed_gives_the_same_messages(seed):
    """Replaying a seed sends the same messages, kind by kind, type by type."""
    def draw():
        # repr, not the serialized bytes: CDR's alignment padding is not initialised.
        rng = random.Random(seed)
        return [repr(MessageFuzzer(message_type, rng, HINTS).message(kind)[0])
                for kind in ('plausible', 'mutated', 'hostile') for message_type in TYPES]
    assert draw() == draw()


def test_a_huge_message_has_a_sequence_of_100000():
    """The huge kind gives a trajectory 10^5 points."""
    from trajectory_msgs.msg import MultiDOFJointTrajectory
    message, done = MessageFuzzer(MultiDOFJointTrajectory, random.Random(1), HINTS).message(
        'huge')
    assert any('100000 elements' in what for what in done), done
    assert max(len(message.points), len(message.joint_names)) == 100_000


def test_the_oracle_finds_non_finite_numbers_and_non_unit_quaternions(invariants):
    """A NaN anywhere and a quaternion of norm 2 are problems on any topic."""
    pose = Pose()
    pose.orientation.w = 2.0
    assert 'norm' in invariants.problems('anything', pose)[0]
    message = JointTrajectory(points=[JointTrajectoryPoint(positions=[0.0, math.nan])])
    assert 'nan' in invariants.problems('other', message)[0]


def test_the_oracle_checks_leg_lengths_and_velocities_against_the_limits(invariants):
    """Stroke 0.65 to 0.90 m, leg_velocity_max 0.05 m/s: one side passes, the other fails."""
    inside = Float64MultiArray(data=[0.7] * 6)
    assert invariants.problems('leg_lengths', inside) == []
    outside = Float64MultiArray(data=[0.7] * 5 + [0.9000001])
    assert 'leg 6' in invariants.problems('leg_lengths', outside)[0]
    assert invariants.problems('leg_velocities', Float64MultiArray(data=[0.05] * 6)) == []
    assert invariants.problems('leg_velocities', Float64MultiArray(data=[0.0501] + [0.0] * 5))
    names = [f'leg_{index}' for index in range(1, 7)]
    good = JointState(name=names, position=[0.7] * 6, velocity=[0.01] * 6)
    assert invariants.problems('joint_commands', good) == []
    fast = JointState(name=names, position=[0.7] * 6, velocity=[0.06] + [0.0] * 5)
    assert 'velocity' in invariants.problems('joint_commands', fast)[0]


def test_the_oracle_checks_poses_under_the_frames_in_force(invariants):
    """Home passes; 0.3 m up breaks the stroke; a pose in an unknown frame is a problem."""
    home = Pose()
    home.position.z = 0.4325
    assert invariants.problems('estimated_pose', home) == []
    high = Pose()
    high.position.z = 0.7325
    assert 'leg_length_max' in invariants.problems('target_pose', high)[0]
    stamped = PoseStamped(pose=home)
    stamped.header.frame_id = 'elsewhere'
    assert invariants.problems('cue_pose', stamped)
    stamped.header.frame_id = 'stewart_base'
    assert invariants.problems('cue_pose', stamped) == []


def test_parameter_changes_the_spec_refuses_must_be_refused():
    """Every drawn change of a value its spec refuses expects a refusal that names it."""
    specs = {spec.name: spec for spec in all_specs()}
    descriptors = {name: ParameterDescriptor(type=_type_code(spec.value_type),
                                             read_only=spec.read_only)
                   for name, spec in specs.items()}
    values = {name: spec.default for name, spec in specs.items()}
    fuzzer = ParameterFuzzer(random.Random(7), descriptors, values)
    seen = set()
    for change in fuzzer.changes(len(descriptors)) + [fuzzer.change() for _ in range(400)]:
        seen.add(change.why.split("'")[0])
        if change.message.value.type in (10, 42, 255) or change.why in (
                'read-only', 'wrong type', 'no such parameter'):
            assert change.expect == REFUSED
        elif change.names_parameter:
            assert change.expect == REFUSED and f"'{change.name}'" in change.why
    assert {'read-only', 'wrong type', 'no such parameter type'} <= seen


def test_a_start_variant_keeps_the_platform_and_is_valid():
    """A start-up variant never touches the geometry, limits or frames; each value is allowed."""
    specs = {spec.name: spec for spec in all_specs()}
    for seed in range(20):
        variant = start_variant(random.Random(seed))
        for name, value in variant.items():
            assert specs[name].read_only and not specs[name].check(value)
            assert name not in ('leg_length_max', 'base_frame', 'joint_names')
            assert argument(name, value).startswith(f'{name}:=')
    assert argument('mode', 'off') == "mode:='off'" and argument('loop', True) == 'loop:=true'


def _type_code(value_type):
    return {'bool': ParameterType.PARAMETER_BOOL, 'integer': ParameterType.PARAMETER_INTEGER,
            'double': ParameterType.PARAMETER_DOUBLE, 'string': ParameterType.PARAMETER_STRING,
            'double_array': ParameterType.PARAMETER_DOUBLE_ARRAY,
            'string_array': ParameterType.PARAMETER_STRING_ARRAY}[value_type]


def test_numbers_problems_walks_arrays_of_any_depth():
    """An inf deep in a trajectory point's accelerations is found, with its path."""
    point = JointTrajectoryPoint(positions=[0.7] * 6, accelerations=[0.0] * 5 + [np.inf])
    problems = numbers_problems(JointTrajectory(points=[point, point]))
    assert problems and 'points[0].accelerations[5]' in problems[0]


def test_frames_a_node_would_refuse_add_no_frame_tree(invariants):
    """A tool frame named as the platform frame makes no tree: nothing added, nothing raised."""
    before = list(invariants.frames)
    invariants.add_frames({'tool_frame': 'stewart_platform'})
    assert invariants.frames == before


def test_oversized_places_are_every_field_a_sender_can_grow():
    """Strings and unbounded sequences, once per field; none in a Pose; fixed arrays never."""
    def places(message_type):
        return MessageFuzzer(message_type, random.Random(1), HINTS).oversized_places()
    assert places(Pose) == [] and places(Twist) == []
    assert places(Imu) == ['header.frame_id']   # its covariances are float64[9]
    assert places(JointState) == ['header.frame_id', 'name', 'name[0]', 'position', 'velocity',
                                  'effort', EVERY_SEQUENCE]
    assert {'header.frame_id', 'poses', 'poses[0].header.frame_id'} <= set(places(PathMessage))
    assert {'joint_names', 'points', 'points[0].transforms', EVERY_SEQUENCE} <= set(
        places(MultiDOFJointTrajectory))


def test_an_oversized_message_has_its_field_at_the_size_and_goes_on_the_wire():
    """Each place of each declared input type: the field grown, the rest plausible."""
    rng = random.Random(27)
    sizes = {}
    for message_type in TYPES:
        fuzzer = MessageFuzzer(message_type, rng, HINTS)
        for place in fuzzer.oversized_places():
            message, done = fuzzer.oversized(place)
            assert isinstance(message, message_type) and done, place
            if place != EVERY_SEQUENCE:
                assert len(serialize_message(message)) > 10 ** 5, (message_type, place)
            sizes[(message_type.__name__, place)] = message
    assert len(sizes[('Float64MultiArray', 'data')].data) == OVERSIZED_VALUES
    assert len(sizes[('PoseStamped', 'header.frame_id')].header.frame_id) == (
        OVERSIZED_CHARACTERS)
    assert len(sizes[('Path', 'poses')].poses) == OVERSIZED_ELEMENTS
    every = sizes[('JointState', EVERY_SEQUENCE)]
    assert len(every.name) == len(every.position) == len(every.velocity) == OVERSIZED_NAMES
    assert every.name[:5] == list(HINTS.joint_names[:5]) and HINTS.joint_names[5] not in every.name
    message, done = MessageFuzzer(Imu, random.Random(2), HINTS).message('oversized')
    assert done == [f'header.frame_id: {OVERSIZED_CHARACTERS:,} characters']


def test_the_oracle_finds_long_strings_in_any_output_and_long_log_lines():
    """A frame id or a diagnostics value beyond the bound is a problem; the bound itself is not."""
    stamped = PoseStamped()
    stamped.pose.orientation.w = 1.0
    stamped.header.frame_id = 'f' * MAX_OUTPUT_STRING
    assert string_problems(stamped) == []
    stamped.header.frame_id += 'f'
    assert 'header.frame_id' in string_problems(stamped)[0]
    status = DiagnosticStatus(name='/fk_node: leg_lengths', values=[
        KeyValue(key='received', value='1'), KeyValue(key='last rejection', value='v' * 10 ** 6)])
    problems = string_problems(DiagnosticArray(status=[status]))
    assert problems and 'status[0].values[1].value' in problems[0] and '1,000,000' in problems[0]
    assert string_problems(Pose()) == [] and string_problems(JointTrajectory(points=[
        JointTrajectoryPoint(positions=[0.7] * 6)] * 1000)) == []
    short = '[WARN] [1.0] [fk_node]: ' + 'x' * (MAX_LOG_LINE - 24)
    assert log_problems(f'ok\n{short}\n') == []
    assert 'log line 2' in log_problems(f'ok\n{short}x\n')[0]


# Hostile parameter files -------------------------------------------------------------------


def _expanded_size(text):
    """Count the scalars an alias bomb's last anchor stands for, from its text alone."""
    sizes = {}
    for line in text.splitlines():
        if '&' not in line:
            continue
        anchor = line.split('&', 1)[1].split()[0]
        aliases = [word.strip('[]{},').split('*')[1] for word in line.split() if '*' in word]
        sizes[anchor] = sum(sizes[name] for name in aliases) if aliases else line.count('"lol"')
    return sizes[anchor]


@pytest.mark.parametrize('style', ['list', 'mapping'])
def test_an_alias_bomb_stands_for_width_to_the_levels_values(style):
    for seed in range(5):
        rng = random.Random(seed)
        levels, width = rng.randint(2, 9), rng.randint(2, 10)
        bomb = alias_bomb(rng, levels=levels, width=width, style=style)
        assert _expanded_size(bomb.data.decode()) == width ** levels
        assert bomb.refused and bomb.reason == 'alias' and len(bomb.data) < 2000


def test_deep_files_nest_as_deep_as_they_say():
    for style in ('flow', 'block'):
        hostile = deep_list(random.Random(0), depth=1000, style=style)
        body = hostile.data.decode().splitlines()[-1]
        assert body.count('[') == 1000 or body.count('- ') == 1000
        hostile = deep_mapping(random.Random(0), depth=500, style=style)
        text = hostile.data.decode()
        assert text.count('{') == 500 or text.count(':\n') == 2 + 499
        assert hostile.refused
    # Within the limit (the file's 3 levels above the value): either answer is right.
    assert not deep_list(random.Random(0), depth=61).refused
    assert deep_list(random.Random(0), depth=62).refused


def test_null_values_and_huge_scalars_are_written_as_drawn():
    for seed in range(30):
        hostile = null_value(random.Random(seed))
        value = hostile.data.decode().splitlines()[2:]
        assert hostile.null in ('null', '~', 'Null', 'NULL', '') and hostile.refused
        assert any(line.rstrip().endswith(f': {hostile.null}'.rstrip()) or
                   f', {hostile.null}, ' in line or line.strip() == '-' for line in value)
        hostile = huge_scalar(random.Random(seed))
        assert len(hostile.data) > 10 ** 4


def test_every_kind_is_drawn_and_one_seed_draws_one_file():
    kinds = {hostile_file(random.Random(seed), max_bytes=100_000).kind for seed in range(60)}
    assert kinds == set(KINDS)
    assert hostile_file(random.Random(9)) == hostile_file(random.Random(9))


def test_the_package_reader_keeps_every_invariant_on_drawn_files(tmp_path):
    for seed in range(60):
        hostile = hostile_file(random.Random(seed), max_bytes=300_000)
        assert not reader_problems(hostile, tmp_path, deadline=2.0), hostile.note


def _reader_as_it_was(paths):
    """Read as the reader of issue 27 did: PyYAML's composer, a walk expanding every alias."""
    def walk(node):
        if isinstance(node, yaml.SequenceNode):
            return [walk(item) for item in node.value]
        if isinstance(node, yaml.MappingNode):
            return {key.value: walk(value) for key, value in node.value}
        return node.value
    for path in paths:
        with open(path, encoding='utf-8') as stream:
            walk(yaml.compose(stream))


def test_the_oracle_finds_the_defects_of_the_reader_as_it_was(tmp_path):
    bomb = alias_bomb(random.Random(0), levels=9, width=9, style='list')
    assert reader_problems(bomb, tmp_path, _reader_as_it_was, deadline=0.5) == [
        f'{bomb.note}: no answer within 0.5 s']
    for hostile in (deep_list(random.Random(0), depth=100_000, style='flow'),
                    deep_mapping(random.Random(0), depth=3000, style='flow')):
        assert reader_problems(hostile, tmp_path, _reader_as_it_was) == [
            f'{hostile.note}: RecursionError']
    # Read without a word: refused files must be refused.
    small = deep_list(random.Random(0), depth=100, style='flow')
    assert reader_problems(small, tmp_path, _reader_as_it_was) == [
        f'{small.note}: read without a refusal']


def test_a_leg_trajectory_point_beyond_the_stroke_is_found_and_never_excused(invariants):
    """
    Issue 27's bulge: one point of leg_trajectory 0.1 um past leg_length_max is a problem.

    Its index and leg are named, and no braking count on /diagnostics excuses it: only a pose
    or a command stream may be a braking command.
    """
    names = [f'leg_{index}' for index in range(1, 7)]
    points = [JointTrajectoryPoint(positions=[0.85] * 6) for _ in range(5)]
    for index, point in enumerate(points):
        point.time_from_start.nanosec = index * 20_000_000
    trajectory = JointTrajectory(joint_names=names, points=points)
    assert invariants.problems('leg_trajectory', trajectory) == []
    points[3].positions = [0.85] * 3 + [0.9000001] + [0.85] * 2
    trajectory = JointTrajectory(joint_names=names, points=points)
    problems = invariants.problems('leg_trajectory', trajectory)
    assert problems == ['leg_trajectory point 3: leg 4 length 0.9000001 m outside the stroke '
                        '[0.65, 0.9]']
    log = OutputLog(invariants)
    log.callback('leg_trajectory')(trajectory, {})
    assert log.problems(allowance=10) == [f'published on leg_trajectory: {problems[0]}']
    high = Pose()
    high.position.z = 0.7325   # a pose beyond the stroke: a braking command may be one
    log.callback('target_pose')(high, {})
    assert len(log.problems(allowance=1)) == 1
    assert 'more than the 0' in log.problems(allowance=0)[1]


def test_the_fuzzer_feeds_mock_platform_only_the_command_input_it_takes():
    """
    A variant with command_input: leg_lengths subscribes to that input alone.

    Once a -p after the files took effect, the fuzzer waited for the other inputs to match
    for ever (CI: 'not matched on its inputs within 20 s').
    """
    from stewart_kinematics.ros.interfaces import IK_NODE, MOCK_PLATFORM, SUBSCRIPTION
    every = list(MOCK_PLATFORM.of_kind(SUBSCRIPTION))
    assert len(every) == 3
    assert _inputs_taken(MOCK_PLATFORM, {'command_input': 'leg_lengths'}) == [
        MOCK_PLATFORM['leg_lengths']]
    assert _inputs_taken(MOCK_PLATFORM, {'command_input': 'all'}) == every
    assert _inputs_taken(MOCK_PLATFORM, {}) == every
    # Another node's inputs do not hang on a parameter of that name.
    assert _inputs_taken(IK_NODE, {'command_input': 'leg_lengths'}) == list(
        IK_NODE.of_kind(SUBSCRIPTION))
