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
Run-time parameter changes for the node fuzzer: valid, invalid, and malformed requests.

A :class:`ParameterFuzzer` draws changes for the parameters a running node lists (through its
parameter services, so any node is covered) and decides what the node must answer from the
package's parameter specs (:func:`stewart_kinematics.parameters.all_specs`) and the node's own
descriptors: a value of another type, a read-only parameter, a value the spec refuses (NaN,
out of range, wrong length, a bad frame name), a name nobody declared, an unset value (an
attempt to undeclare) and a type code that does not exist must be refused; a value the spec
allows may be accepted (a rule between parameters, such as distinct frame names, may still
refuse it). A parameter without a spec (``use_sim_time``, ``qos_overrides.*``) only gets the
changes that must be refused: its meaning is rclpy's, and switching the clock is the soak's
business.

:func:`start_variant` draws start-up values of the read-only parameters that choose what a node
does (streamed commands, a broadcast, the ramp's mode, queue depths...), so that a fuzz run
also covers the code paths the shipped files leave off.
"""

from dataclasses import dataclass
import math
import random
from typing import Dict, List, Optional

from fuzzing.fuzz_messages import HOSTILE_DOUBLES, HOSTILE_STRINGS
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue

from stewart_kinematics import parameters

#: The field of rcl_interfaces/msg/ParameterValue that holds each type's value.
VALUE_FIELDS = {
    ParameterType.PARAMETER_BOOL: 'bool_value',
    ParameterType.PARAMETER_INTEGER: 'integer_value',
    ParameterType.PARAMETER_DOUBLE: 'double_value',
    ParameterType.PARAMETER_STRING: 'string_value',
    ParameterType.PARAMETER_BYTE_ARRAY: 'byte_array_value',
    ParameterType.PARAMETER_BOOL_ARRAY: 'bool_array_value',
    ParameterType.PARAMETER_INTEGER_ARRAY: 'integer_array_value',
    ParameterType.PARAMETER_DOUBLE_ARRAY: 'double_array_value',
    ParameterType.PARAMETER_STRING_ARRAY: 'string_array_value',
}
#: A value of each type, for a change of the wrong type.
SAMPLE_VALUES = {
    ParameterType.PARAMETER_BOOL: True,
    ParameterType.PARAMETER_INTEGER: 1,
    ParameterType.PARAMETER_DOUBLE: 1.0,
    ParameterType.PARAMETER_STRING: '1.0',
    ParameterType.PARAMETER_BYTE_ARRAY: [b'\x01'],
    ParameterType.PARAMETER_BOOL_ARRAY: [True],
    ParameterType.PARAMETER_INTEGER_ARRAY: [1],
    ParameterType.PARAMETER_DOUBLE_ARRAY: [1.0, 2.0, 3.0],
    ParameterType.PARAMETER_STRING_ARRAY: ['a'],
}
#: The ROS parameter type of each spec type.
SPEC_TYPES = {
    parameters.BOOL: ParameterType.PARAMETER_BOOL,
    parameters.INTEGER: ParameterType.PARAMETER_INTEGER,
    parameters.DOUBLE: ParameterType.PARAMETER_DOUBLE,
    parameters.STRING: ParameterType.PARAMETER_STRING,
    parameters.DOUBLE_ARRAY: ParameterType.PARAMETER_DOUBLE_ARRAY,
    parameters.STRING_ARRAY: ParameterType.PARAMETER_STRING_ARRAY,
}
#: What a change must get: refused, or either answer (a valid value).
REFUSED = 'refused'
EITHER = 'either'
#: Integers worth trying on an integer parameter.
HOSTILE_INTEGERS = (0, -1, 1, 2 ** 31, 2 ** 63 - 1, -2 ** 63, 10 ** 6)
#: What a start-up variant leaves as the parameter files set it: the platform, its limits, its
#: actuators and its frames, which the output checks and the plausible messages read; and
#: ``managed``, since a managed node waits, silent, for a lifecycle manager the fuzzer is not
#: (test/processes/test_lifecycle_adversary.py attacks the lifecycle itself).
FIXED_AT_START = frozenset(spec.name for spec in parameters.GEOMETRY_PARAMETERS
                           + parameters.ACTUATOR_PARAMETERS + parameters.FRAME_PARAMETERS
                           + parameters.LIFECYCLE_PARAMETERS)


@dataclass(frozen=True)
class ParameterChange:
    """
    One parameter change to request, and what the node must answer.

    :param message: the rcl_interfaces/msg/Parameter to send.
    :param expect: :data:`REFUSED` or :data:`EITHER`.
    :param why: why that answer, in words (``read-only``, the spec's reason...).
    :param value: the value the node holds if it accepts (Python, as a parameter file gives it).
    :param names_parameter: a refusal must name the parameter (the spec's own refusal).
    """

    message: Parameter
    expect: str
    why: str
    value: object = None
    names_parameter: bool = False

    @property
    def name(self) -> str:
        """Return the parameter's name."""
        return self.message.name

    def describe(self) -> str:
        """Return the change in words: ``name = value (type): must be refused (why)``."""
        value = self.message.value
        field = VALUE_FIELDS.get(value.type)
        shown = getattr(value, field) if field else f'<type code {value.type}>'
        if field and field.endswith('array_value'):
            shown = list(shown)
        text = repr(shown)
        if len(text) > 60:
            text = text[:60] + '...'
        return f'{self.name} = {text}: {self.expect} ({self.why})'


def parameter_message(name: str, type_code: int, value=None) -> Parameter:
    """Return an rcl_interfaces/msg/Parameter of a type code and a value of that type."""
    message = ParameterValue(type=type_code)
    field = VALUE_FIELDS.get(type_code)
    if field is not None and value is not None:
        setattr(message, field, value)
    return Parameter(name=name, value=message)


def python_value(message: ParameterValue):
    """Return the Python value of an rcl_interfaces/msg/ParameterValue (arrays as lists)."""
    field = VALUE_FIELDS.get(message.type)
    if field is None:
        return None
    value = getattr(message, field)
    return list(value) if field.endswith('array_value') else value


class ParameterFuzzer:
    """
    Draw parameter changes for one node, with the answer each must get.

    :param rng: the run's ``random.Random``.
    :param descriptors: the node's rcl_interfaces/msg/ParameterDescriptor of every parameter
        it lists, by name.
    :param values: the node's current values, by name (Python values); updated by
        :meth:`accepted`.
    """

    def __init__(self, rng: random.Random, descriptors: Dict[str, object],
                 values: Dict[str, object]):
        self.rng = rng
        self.descriptors = dict(descriptors)
        self.values = dict(values)
        # Candidates are drawn around the values the node started with, not the current ones:
        # which changes are accepted depends on timing, and the draws must not, to replay.
        self.initial = dict(values)
        #: Values a parameter may hold besides the last one accepted, by name.
        self.alternatives: Dict[str, list] = {}
        specs = {spec.name: spec for spec in parameters.all_specs()}
        self.specs = {name: specs[name] for name in descriptors if name in specs}

    def changes(self, count: int) -> List[ParameterChange]:
        """Draw ``count`` changes of different parameters (some may be of undeclared names)."""
        names = self.rng.sample(sorted(self.descriptors), min(count, len(self.descriptors)))
        return [self.change(name) for name in names]

    def change(self, name: Optional[str] = None) -> ParameterChange:
        """Draw one change of ``name`` (default: a random parameter, or an undeclared one)."""
        rng = self.rng
        if name is None:
            name = rng.choice(sorted(self.descriptors))
        if rng.random() < 0.03:
            return ParameterChange(parameter_message(
                rng.choice(('fuzz_undeclared', name + '_', name.upper(), '', '.', 'a..b')),
                ParameterType.PARAMETER_DOUBLE, 1.0), REFUSED, 'no such parameter')
        descriptor = self.descriptors[name]
        declared = descriptor.type
        draw = rng.random()
        if draw < 0.04:
            return ParameterChange(parameter_message(name, rng.choice((10, 42, 255))), REFUSED,
                                   'no such parameter type')
        if draw < 0.08:
            return ParameterChange(parameter_message(name, ParameterType.PARAMETER_NOT_SET),
                                   REFUSED, 'a declared parameter cannot be undeclared')
        if draw < 0.25 or name not in self.specs:
            other = rng.choice([code for code in SAMPLE_VALUES if code != declared])
            return ParameterChange(parameter_message(name, other, SAMPLE_VALUES[other]), REFUSED,
                                   'wrong type')
        spec = self.specs[name]
        value = self.candidate(spec)
        message = parameter_message(name, declared, value)
        if descriptor.read_only:
            return ParameterChange(message, REFUSED, 'read-only')
        reason = spec.check(_as_checked(spec, value))
        if reason:
            return ParameterChange(message, REFUSED, reason, names_parameter=True)
        return ParameterChange(message, EITHER, 'valid for its spec', value=value)

    def candidate(self, spec: parameters.ParameterSpec):
        """Draw a value of a spec's type: as often one the spec allows as one it refuses."""
        rng = self.rng
        current = self.initial.get(spec.name, spec.default)
        kind = spec.value_type
        plausible = rng.random() < 0.5
        if kind == parameters.BOOL:
            return not current if isinstance(current, bool) else rng.random() < 0.5
        if kind == parameters.INTEGER:
            if plausible and isinstance(current, int):
                return max(0, current + rng.choice((-1, 1, 5, -5)))
            return rng.choice(HOSTILE_INTEGERS)
        if kind == parameters.DOUBLE:
            if plausible and isinstance(current, float) and math.isfinite(current):
                return current * rng.choice((0.5, 0.9, 1.1, 2.0)) if current else 0.01
            return rng.choice(HOSTILE_DOUBLES)
        if kind == parameters.STRING:
            choices = string_choices(spec)
            if plausible:
                return rng.choice(choices + ['fuzz_tool', current or ''])
            return rng.choice(HOSTILE_STRINGS + ('stewart_base', 'stewart_platform'))
        if kind == parameters.DOUBLE_ARRAY:
            current = list(current or [0.0, 0.0, 0.0])
            if plausible:
                return [value + rng.uniform(-0.01, 0.01) * (100.0 if 'deg' in spec.name else 1.0)
                        for value in current]
            length = rng.choice((0, len(current) - 1, len(current) + 1, len(current)))
            return [rng.choice(HOSTILE_DOUBLES) for _ in range(max(0, length))]
        if kind == parameters.STRING_ARRAY:
            current = list(current or ['a'])
            return rng.choice(([], [''] * len(current), current[:1] * len(current),
                               current[:-1], current + ['extra']))
        raise ValueError(f'unknown spec type {kind!r} of {spec.name!r}')

    def accepted(self, change: ParameterChange):
        """Record that the node accepted a change: its value is the node's from now on."""
        self.values[change.name] = change.value

    def allow(self, change: ParameterChange):
        """Record that the node may hold a change's value (a request without an answer)."""
        self.alternatives.setdefault(change.name, []).append(change.value)

    def checked_values(self) -> Dict[str, object]:
        """Return the values the node must hold now: every writable parameter with a spec."""
        return {name: self.values[name] for name in self.specs
                if not self.descriptors[name].read_only and name in self.values}


def _as_checked(spec, value):
    """Return a value as the node's validator sees it (double arrays: floats)."""
    if spec.value_type == parameters.DOUBLE_ARRAY:
        return [float(item) for item in value]
    return value


def string_choices(spec: parameters.ParameterSpec) -> list:
    """Return the values a string parameter's spec names: its choices, and '' if allowed."""
    choices = [choice for validator in spec.validators if isinstance(validator, parameters.OneOf)
               for choice in validator.allowed]
    return choices + ([''] if not spec.check('') else [])


def start_variant(rng: random.Random, share: float = 0.5) -> Dict[str, object]:
    """
    Draw start-up values for some read-only parameters of the package (not the platform's).

    Each read-only parameter outside :data:`FIXED_AT_START` gets, with probability ``share``, a
    value its spec allows: the other boolean, another of the choices of a string, or a
    number near its default (twice, half, or 10 or 100 where the default is 0: a rate that turns
    a feature on). A node ignores the parameters it does not declare.

    :returns: parameter name -> value, for ``-p name:=value`` (see :func:`argument`).
    """
    variant = {}
    for spec in parameters.all_specs():
        if not spec.read_only or spec.name in FIXED_AT_START or rng.random() >= share:
            continue
        default = spec.default
        if spec.value_type == parameters.BOOL:
            candidates = [not default]
        elif spec.value_type == parameters.STRING:
            candidates = [choice for choice in string_choices(spec) if choice != default]
        elif spec.value_type == parameters.DOUBLE and isinstance(default, float) and (
                math.isfinite(default)):
            candidates = [default * 2.0, default / 2.0] if default else [10.0, 100.0]
        elif spec.value_type == parameters.INTEGER and isinstance(default, int):
            candidates = [default * 2, default // 2] if default else [1, 5]
        else:
            continue
        candidates = [value for value in candidates if not spec.check(value)]
        if candidates:
            variant[spec.name] = rng.choice(candidates)
    return variant


def argument(name: str, value) -> str:
    """Return ``name:=value`` as rcl reads a ``-p`` value (YAML): ``true``, ``1.0``, ``'x'``."""
    if isinstance(value, bool):
        text = 'true' if value else 'false'
    elif isinstance(value, float):
        text = repr(value)
    elif isinstance(value, str):
        text = "'" + value.replace("'", "''") + "'"
    else:
        text = str(value)
    return f'{name}:={text}'
