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
Every parameter's "allowed values" text is generated from its validators, and says what they do.

The documentation's tables and the ROS descriptors show ``spec.constraints``. Here that text is
read back as a user would read it (a parser written for this test, not the validators' code):
every phrase must be understood, and every value it names is probed at and beyond the bound
against the spec's own check: an interval's ends, ``> 0``, ``.inf allowed``, a length, the
choices, a frame name's rules. Only a spec's ``note`` (a rule between parameters) is prose.
"""

import dataclasses
import math
from pathlib import Path
import re

import pytest

from stewart_kinematics.model.validators import (
    FixedLength,
    InertiaTensor,
    InRange,
    IPv4Address,
    LegSelection,
    OneOf,
    ZeroOrInRange,
)
from stewart_kinematics.parameters import all_specs, ParameterSpec

pytestmark = pytest.mark.core

DECLARATIONS = (Path(__file__).resolve().parents[2] / 'stewart_kinematics' / 'parameters'
                / 'declarations.py')
NUMBER = r'-?(?:\d+(?:\.\d*)?(?:e[+-]?\d+)?|inf)'
INTERVAL = re.compile(rf'^in ([\[(])({NUMBER}), ({NUMBER})([\])])$')
HALF_LINE = re.compile(rf'^(>=|>) ({NUMBER})$')
LOWER_HALF_LINE = re.compile(rf'^(<=|<) ({NUMBER})$')
ZERO_OR = re.compile(rf'^0\.0 or in \[({NUMBER}), ({NUMBER})\]$')
INTEGERS = re.compile(r'^(-?\d+)(?:, (-?\d+))* or (-?\d+)$')
ARRAY = re.compile(r'^(\d+) (finite )?values(?: (.+))?$')
NAMES = re.compile(r'^(\d+) distinct, non-empty names$')
FRAME = "a frame name (no spaces, no leading '/', at most 256 characters)"
QUOTED = re.compile(r"^'[^']*'(?:, '[^']*')* or '[^']*'$")


def above(value, integer):
    """Return the next value above ``value`` of the type (an integer's, a double's)."""
    return value + 1 if integer else math.nextafter(value, math.inf)


def below(value, integer):
    """Return the next value below ``value`` of the type."""
    return value - 1 if integer else math.nextafter(value, -math.inf)


def number_claims(phrase, integer):
    """Return ``[(value, allowed)]`` that one phrase about a number claims, or None."""
    convert = int if integer else float
    if match := INTERVAL.match(phrase):
        low, high = convert(float(match.group(2))), convert(float(match.group(3)))
        return [(low, match.group(1) == '['), (below(low, integer), False),
                (high, match.group(4) == ']'), (above(high, integer), False),
                (convert((low + high) / 2) if integer else (low + high) / 2, True)]
    if match := HALF_LINE.match(phrase):
        low = convert(float(match.group(2)))
        return [(low, match.group(1) == '>='), (below(low, integer), False),
                (above(low, integer), True), (convert(1e9) if integer else 1e300, True)]
    if match := LOWER_HALF_LINE.match(phrase):
        high = convert(float(match.group(2)))
        return [(high, match.group(1) == '<='), (above(high, integer), False),
                (below(high, integer), True), (convert(-1e9) if integer else -1e300, True)]
    if match := ZERO_OR.match(phrase):
        low, high = float(match.group(1)), float(match.group(2))
        return [(0.0, True), (low / 2.0, False), (low, True), (high, True),
                (above(high, False), False), (-low, False)]
    if integer and INTEGERS.match(phrase):
        allowed = [int(text) for text in re.findall(r'-?\d+', phrase)]
        return [(value, True) for value in allowed] + [
            (min(allowed) - 1, False), (max(allowed) + 1, False)]
    return None


def claims(spec):
    """
    Read a spec's generated text and return every ``(value, allowed)`` it claims.

    :raises AssertionError: for a phrase this reader does not understand.
    """
    text = spec.constraints
    if spec.note:
        assert text.endswith('; ' + spec.note), text
        text = text[:-len(spec.note) - 2]
    kind = spec.value_type
    if kind == 'bool':
        assert text == '', text
        return [(True, True), (False, True)]
    if kind == 'string':
        if text in (FRAME, FRAME + " or ''"):
            return [('tool_0', True), ('a b', False), ('/tool', False), ('tool\t', False),
                    ('x' * 256, True), ('x' * 257, False), ('x' * 10_000, False),
                    ('', text.endswith("or ''"))]
        if text == IPv4Address().describe():
            return [('127.0.0.1', True), ('0.0.0.0', True), ('192.168.1.20', True), ('', False),
                    ('localhost', False), ('300.1.1.1', False), ('::1', False), ('1.2.3', False),
                    ('01.2.3.4', False)]
        if text == LegSelection().describe():
            return [('', True), ('1, 6', True), ('2 3', True), ('leg_1', True), ('7', False),
                    ('0', False), ('1;2', False), ('/leg_1', False)]
        assert QUOTED.match(text), text
        choices = re.findall(r"'([^']*)'", text)
        return [(choice, True) for choice in choices] + [('none_of_these', False), ('', False)]
    if kind == 'string_array':
        match = NAMES.match(text)
        assert match, text
        count = int(match.group(1))
        names = [f'joint_{index}' for index in range(count)]
        return [(names, True), (names[:-1], False), (names + ['extra'], False),
                (names[:-1] + [names[0]], False), ([''] + names[1:], False)]
    if kind == 'double_array':
        match = ARRAY.match(text)
        assert match, text
        count = int(match.group(1))
        base = list(spec.default) if spec.default is not None else [0.5] * count
        found = [(base, True), (base[:-1], False), (base + [base[0]], False)]
        finite = bool(match.group(2))
        if match.group(3) == InertiaTensor().describe():
            found += [([0.3, 0.3, 0.0, 0.0, 0.0, 0.0], True),     # a rod: the triangle's edge
                      ([0.1, 0.1, 0.5, 0.0, 0.0, 0.0], False),    # beyond the triangle
                      ([0.2, -0.2, 0.2, 0.0, 0.0, 0.0], False),   # a negative moment
                      ([0.2, 0.2, 0.2, 0.5, 0.0, 0.0], False)]    # indefinite
        elif match.group(3):
            element = number_claims(match.group(3), integer=False)
            assert element is not None, text
            found += [([value] + base[1:], allowed) for value, allowed in element]
            finite = finite or math.isfinite(element[0][0])
        found += [([math.nan] + base[1:], False)]
        if finite:
            found += [([math.inf] + base[1:], False), ([-math.inf] + base[1:], False)]
        return found
    integer = kind == 'integer'
    phrases = text.split('; ')
    infinity = '.inf allowed' in phrases
    negative_infinity = '-.inf allowed' in phrases
    phrases = [phrase for phrase in phrases if phrase not in ('.inf allowed', '-.inf allowed')]
    assert len(phrases) == 1, text
    parts = phrases[0].split(', ')
    finite = parts[0] == 'finite'
    found = number_claims(', '.join(parts[1:] if finite else parts), integer)
    assert found is not None, text
    if not integer:
        # Without '.inf allowed', infinity is refused (by 'finite', or by a bound).
        found += [(math.nan, False), (-math.inf, negative_infinity), (math.inf, infinity)]
    return found


@pytest.mark.parametrize('spec', all_specs(), ids=lambda spec: spec.name)
def test_the_allowed_values_text_says_what_the_check_does(spec):
    """Every value the text names is allowed, or refused, as the text says."""
    for value, allowed in claims(spec):
        reason = spec.check(value)
        assert (reason == '') == allowed, (spec.constraints, value, reason)


def test_no_spec_writes_its_allowed_values_by_hand():
    """A spec's constraints are a property of its validators: a spec cannot be given them."""
    assert 'constraints' not in {field.name for field in dataclasses.fields(ParameterSpec)}
    with pytest.raises(TypeError):
        ParameterSpec('x', 'double', 'x', constraints='in [0, 1]')
    assert 'constraints=' not in DECLARATIONS.read_text(encoding='utf-8')


def test_notes_are_few_and_say_what_no_validator_can():
    """Rules between parameters, or of the whole joint layout; nothing a validator says."""
    notes = {spec.name: spec.note for spec in all_specs() if spec.note}
    assert sorted(notes) == sorted([
        'base_joints', 'platform_joints', 'leg_length_min', 'leg_length_max', 'position_step',
        'orientation_step_deg', 'estimated_pose_frame', 'platform_inertia', 'payload_inertia',
        'leg_lower_inertia', 'leg_upper_inertia', 'initial_leg_lengths', 'stalled_legs',
        'park_position', 'park_orientation_deg'])


@pytest.mark.parametrize('validator, text', [
    (InRange(0.0, 10000.0), 'in [0, 10000]'),
    (InRange(0.0, 1e-2, low_inclusive=False), 'in (0, 0.01]'),
    (InRange(0.0, math.inf, low_inclusive=False), '> 0'),
    (InRange(1.0, math.inf), '>= 1'),
    (InRange(-math.inf, 5.0, high_inclusive=False), '< 5'),
    (ZeroOrInRange(0.002, 0.1), '0.0 or in [0.002, 0.1]'),
    (OneOf('table', 'interpolate', 'off'), "'table', 'interpolate' or 'off'"),
    (OneOf(1, 2), '1 or 2'),
    (FixedLength(18), '18 values'),
])
def test_a_validator_describes_itself(validator, text):
    assert validator.describe() == text


@pytest.mark.parametrize('validators, value_type, text', [
    ((FixedLength(3), InRange(0.0, 10.0)), 'double_array', '3 values in [0, 10]'),
    ((InRange(0.0, math.inf, low_inclusive=False),), 'double', '> 0; .inf allowed'),
    ((InRange(0.0, math.inf),), 'double', '>= 0; .inf allowed'),
])
def test_descriptions_compose_by_type(validators, value_type, text):
    assert ParameterSpec('x', value_type, 'x', validators=validators).constraints == text


def test_a_rule_in_degrees_converts_to_radians():
    """The geometry checks radians with the parameters' bounds in degrees."""
    rule = InRange(0.0, 180.0, low_inclusive=False).converted(math.radians)
    assert rule == InRange(0.0, math.pi, low_inclusive=False)
    assert rule.reason('angle', math.pi) == ''
    assert rule.reason('angle', 0.0) == 'angle must be in (0, 3.14159], got 0.0'
