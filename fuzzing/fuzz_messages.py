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
Hostile messages of any ROS message type, built by walking its fields, for the node fuzzer.

A :class:`MessageFuzzer` knows a message type only through rosidl's description of it
(``get_fields_and_field_types()`` and ``SLOT_TYPES``), so every subscription of every node,
present or future, is fuzzed without a line written for its type. Each message starts
*plausible*: values a platform could be sent (poses near home, leg lengths near their home
lengths, increasing trajectory times; :class:`Plausible` holds these few hints, by type and
field name, and a type it does not know gets neutral values). Most messages are then mutated
where it hurts: NaN, infinities, 1e308, -0.0 and subnormal numbers; integers at their type's
bounds (stamps of -2^31 or 2^31 - 1 s, nanoseconds of 10^9 and more); empty, long, foreign and
wrong frame and joint names; sequences emptied, shortened, lengthened, duplicated, reversed,
and now and then given :data:`HUGE_LENGTH` elements. Some are hostile in every number.
*Oversized* ones (:meth:`MessageFuzzer.oversized`) make one field as large as a sender likes
(a million numbers, a string of a million characters, 10^5 names or elements) in an
otherwise plausible message, so that a refusal that echoes its input whole shows (issue 27).

Every draw comes from one ``random.Random(seed)``: the same seed gives the same messages in
the same order, so a failure replays from the seed a run prints.
"""

from dataclasses import dataclass, field
import importlib
import math
import random
import re
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from rosidl_parser import definition

#: Elements of a huge sequence (trajectory points, path poses, array data).
HUGE_LENGTH = 100_000
#: Largest finite float32, the bound rclpy checks a ``float`` field against.
FLOAT32_MAX = 3.4028234663852886e38
#: Hostile doubles: non-finite, huge, signed zero, subnormal, and the ordinary ones that
#: break code assuming positive or non-zero values.
HOSTILE_DOUBLES = (math.nan, math.inf, -math.inf, 1e308, -1e308, 1.7976931348623157e308,
                   -0.0, 0.0, 5e-324, -5e-324, 2.2250738585072014e-308, 1e-300, -1.0, 1e9,
                   -1e9, 1e20)
HOSTILE_FLOATS = (math.nan, math.inf, -math.inf, FLOAT32_MAX, -FLOAT32_MAX, -0.0, 0.0, 1e-45,
                  -1.0, 1e9)
#: Bounds of the integer types, as rclpy checks them.
INTEGER_BOUNDS = {
    'int8': (-2 ** 7, 2 ** 7 - 1), 'uint8': (0, 2 ** 8 - 1), 'char': (0, 2 ** 8 - 1),
    'int16': (-2 ** 15, 2 ** 15 - 1), 'uint16': (0, 2 ** 16 - 1), 'short': (-2 ** 15, 2 ** 15 - 1),
    'unsigned short': (0, 2 ** 16 - 1),
    'int32': (-2 ** 31, 2 ** 31 - 1), 'uint32': (0, 2 ** 32 - 1), 'long': (-2 ** 31, 2 ** 31 - 1),
    'unsigned long': (0, 2 ** 32 - 1),
    'int64': (-2 ** 63, 2 ** 63 - 1), 'uint64': (0, 2 ** 64 - 1),
    'long long': (-2 ** 63, 2 ** 63 - 1), 'unsigned long long': (0, 2 ** 64 - 1),
}
#: Integers worth trying besides a type's bounds: around zero, and a stamp's nanoseconds at
#: and beyond one second.
HOSTILE_INTEGERS = (0, 1, -1, 999_999_999, 1_000_000_000, 2 ** 31 - 1, -2 ** 31)
#: Hostile strings besides the plausible names: empty, blank, long, non-ASCII, almost right.
HOSTILE_STRINGS = ('', ' ', '\t\n', 'x' * 10_000, 'é漢字🙂', '..', '/', '*', 'leg_7', 'platform',
                   'tf', 'a b')
#: Mutations applied to a mutated message, at most.
MAX_MUTATIONS = 3
#: Sizes of an oversized field: values of a number sequence, characters of a string, names of
#: a string sequence, elements of a message sequence (trajectory points, path poses).
OVERSIZED_VALUES = 1_000_000
OVERSIZED_CHARACTERS = 1_000_000
OVERSIZED_NAMES = 100_000
OVERSIZED_ELEMENTS = 10_000
#: The oversized place that stands for every top-level sequence at once, each of
#: :data:`OVERSIZED_NAMES` elements (a JointState's names and positions, of one length).
EVERY_SEQUENCE = '*'
#: Plausible messages drawn, at most, to find a place inside a sequence (``joint_names[0]``).
PLACE_DRAWS = 32


def message_class(slot_type: definition.NamespacedType):
    """Return the Python class of a nested message type (``geometry_msgs/msg/Point``)."""
    module = importlib.import_module('.'.join(slot_type.namespaces))
    return getattr(module, slot_type.name)


def type_name(message_type) -> str:
    """Return ``package/Name`` of a message class (the hints' key)."""
    return f'{message_type.__module__.split(".")[0]}/{message_type.__name__}'


def fields_of(message_type) -> List[Tuple[str, object]]:
    """Return ``(field name, rosidl slot type)`` of each field of a message class, in order."""
    names = list(message_type.get_fields_and_field_types())
    slot_types = list(message_type.SLOT_TYPES)
    if len(names) != len(slot_types):
        raise TypeError(f'{message_type.__name__}: {len(names)} fields, {len(slot_types)} slot '
                        'types')
    return list(zip(names, slot_types))


@dataclass(frozen=True)
class Plausible:
    """
    What a plausible message carries on this platform: the hints that let messages go deep.

    Without hints a pose would be random and refused at the first check; with them about half
    the messages are ones a node accepts, so that its outputs are there to be checked. A type
    the hints do not name gets neutral values (numbers in [-1, 1], short sequences).

    :param home_position: the platform's home position, metres.
    :param home_leg_lengths: its home leg lengths, metres, leg 1..6.
    :param actuator_offsets: each actuator's zero as a leg length, metres.
    :param joint_names: the actuators' joint names, leg 1..6.
    :param frames: frame names a message may carry: the base frame first (the usual one),
        then the platform, user and tool frames.
    :param stamp: returns the stamp of now as ``(sec, nanosec)``.
    """

    home_position: Tuple[float, ...] = (0.0, 0.0, 0.4325)
    home_leg_lengths: Tuple[float, ...] = (0.7, 0.7, 0.7, 0.7, 0.7, 0.7)
    actuator_offsets: Tuple[float, ...] = (0.0,) * 6
    joint_names: Tuple[str, ...] = ('leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5', 'leg_6')
    frames: Tuple[str, ...] = ('stewart_base', 'stewart_platform')
    stamp: Callable[[], Tuple[int, int]] = field(default=lambda: (0, 0), compare=False)

    @property
    def names(self) -> Tuple[str, ...]:
        """Every name a string may plausibly hold: frames and joints."""
        return self.frames + self.joint_names


@dataclass
class Location:
    """
    One place in a message tree that a mutation may change.

    :param container: the dict (a message's fields) or list (a sequence) that holds it.
    :param key: the field name or the index.
    :param slot_type: its rosidl type.
    :param path: where it is, in words (``points[3].time_from_start.sec``).
    :param field_name: the name of the field it belongs to (an element: its sequence's).
    """

    container: object
    key: object
    slot_type: object
    path: str
    field_name: str


class MessageFuzzer:
    """
    Plausible and hostile messages of one type, drawn from a shared random generator.

    :param message_type: the message class (``Endpoint.message_type``).
    :param rng: the run's ``random.Random``: every draw comes from it.
    :param plausible: the platform's :class:`Plausible` hints.
    :param topic: the topic the messages go to (``leg_velocities`` makes leg arrays small
        velocities rather than lengths).
    """

    def __init__(self, message_type, rng: random.Random, plausible: Plausible, topic: str = ''):
        self.message_type = message_type
        self.rng = rng
        self.plausible = plausible
        self.topic = topic
        self._rates = 'velocit' in topic or 'twist' in topic

    # The message ------------------------------------------------------------------------------

    def message(self, kind: str) -> Tuple[object, List[str]]:
        """
        Draw one message.

        :param kind: ``plausible`` (as drawn), ``mutated`` (one to :data:`MAX_MUTATIONS`
            mutations of a plausible one), ``hostile`` (about half of every number and string
            hostile, sequences of random length), ``huge`` (a sequence of :data:`HUGE_LENGTH`
            elements, plus a mutation) or ``oversized`` (:meth:`oversized` at a place drawn
            from :meth:`oversized_places`).
        :returns: ``(message, what was done)``: the message and its mutations in words.
        """
        tree = self.plausible_tree(self.message_type)
        done = []
        if kind == 'mutated':
            for _ in range(self.rng.randint(1, MAX_MUTATIONS)):
                done.append(self.mutate(tree))
        elif kind == 'hostile':
            done.append(self.make_hostile(tree))
        elif kind == 'huge':
            done.append(self.make_huge(tree))
            done.append(self.mutate(tree))
        elif kind == 'oversized':
            places = self.oversized_places()
            if places:
                return self.oversized(self.rng.choice(places))
        elif kind != 'plausible':
            raise ValueError(f"kind must be 'plausible', 'mutated', 'hostile', 'huge' or "
                             f"'oversized', got {kind!r}")
        return build(self.message_type, tree), [what for what in done if what]

    # Plausible values -------------------------------------------------------------------------

    def plausible_tree(self, message_type, field_name: str = '') -> Dict[str, object]:
        """Return a plausible message of ``message_type`` as a dict of field values."""
        name = type_name(message_type)
        rng = self.rng
        hints = self.plausible
        if name == 'geometry_msgs/Quaternion':
            return dict(zip('xyzw', small_rotation(rng)))
        if name in ('geometry_msgs/Point', 'geometry_msgs/Vector3'):
            if field_name in ('position', 'translation'):
                centre = hints.home_position
                spread = 0.005
            elif field_name == 'linear_acceleration':
                centre, spread = (0.0, 0.0, 9.81), 0.5
            else:
                centre, spread = (0.0, 0.0, 0.0), 0.01
            return {axis: value + rng.uniform(-spread, spread)
                    for axis, value in zip('xyz', centre)}
        if name == 'builtin_interfaces/Time':
            sec, nanosec = hints.stamp()
            return {'sec': sec, 'nanosec': nanosec}
        if name == 'builtin_interfaces/Duration':
            return {'sec': 1, 'nanosec': 0}
        if name == 'std_msgs/MultiArrayLayout':
            return {'dim': [], 'data_offset': 0}
        tree = {}
        for child, slot_type in fields_of(message_type):
            tree[child] = self.plausible_value(slot_type, child, name)
        self._time_sequences(tree, message_type)
        return tree

    def plausible_value(self, slot_type, field_name: str, owner: str):
        """Return a plausible value of one field of the message type ``owner``."""
        rng = self.rng
        hints = self.plausible
        if isinstance(slot_type, definition.NamespacedType):
            return self.plausible_tree(message_class(slot_type), field_name)
        if isinstance(slot_type, definition.AbstractNestedType):
            element = slot_type.value_type
            if isinstance(slot_type, definition.Array):
                return [self.plausible_value(element, field_name, owner)
                        for _ in range(slot_type.size)]
            values = self.plausible_sequence(element, field_name, owner)
            if isinstance(slot_type, definition.BoundedSequence):
                values = values[:slot_type.maximum_size]
            return values
        if isinstance(slot_type, definition.AbstractGenericString):
            if field_name == 'frame_id' and self.topic.split('/')[-1] == 'vehicle_imu':
                return ''   # the vehicle frame: a frame named by a parameter the hints lack
            if field_name == 'frame_id':
                return hints.frames[0] if rng.random() < 0.8 else ''
            if field_name == 'child_frame_id':
                return hints.frames[1] if len(hints.frames) > 1 else 'child'
            return rng.choice(hints.names)
        return neutral_basic(slot_type.typename, rng)

    def plausible_sequence(self, element, field_name: str, owner: str) -> list:
        """Return a plausible sequence of ``element`` for a field of ``owner``."""
        rng = self.rng
        hints = self.plausible
        if isinstance(element, definition.NamespacedType):
            element_type = message_class(element)
            if field_name == 'transforms':
                count = 1
            elif field_name in ('velocities', 'accelerations'):
                count = 0
            elif field_name in ('points', 'poses'):
                count = rng.randint(2, 10)
            else:
                count = rng.randint(0, 3)
            return [self.plausible_tree(element_type, field_name) for _ in range(count)]
        if isinstance(element, definition.AbstractGenericString):
            if owner == 'trajectory_msgs/MultiDOFJointTrajectory':
                return rng.choice(([], ['platform']))
            names = list(hints.joint_names)
            rng.shuffle(names)
            return names
        typename = element.typename
        if typename in ('double', 'float'):
            if field_name in ('data', 'position'):
                if self._rates:
                    return [rng.uniform(-0.01, 0.01) for _ in range(6)]
                offsets = hints.actuator_offsets if field_name == 'position' else (0.0,) * 6
                return [length - offset + rng.uniform(-0.003, 0.003)
                        for length, offset in zip(hints.home_leg_lengths, offsets)]
            if field_name == 'velocity':
                return [rng.uniform(-0.01, 0.01) for _ in range(6)]
            if field_name == 'effort':
                return []
        return [neutral_basic(typename, rng) for _ in range(rng.randint(0, 8))]

    def _time_sequences(self, tree, message_type):
        """Give a sequence of elements with a ``time_from_start`` increasing times from 0."""
        for child, slot_type in fields_of(message_type):
            values = tree[child]
            if (isinstance(slot_type, definition.AbstractSequence) and values
                    and isinstance(values[0], dict) and 'time_from_start' in values[0]):
                step = self.rng.uniform(0.5, 1.5)
                for index, element in enumerate(values):
                    element['time_from_start'] = duration_tree(index * step)

    # Mutations --------------------------------------------------------------------------------

    def mutate(self, tree) -> str:
        """Apply one hostile mutation at a random place of ``tree``; return it in words."""
        locations = list(walk(tree, self.message_type))
        if not locations:
            return ''
        location = self.rng.choice(locations)
        return self.mutate_at(location)

    def mutate_at(self, location: Location) -> str:
        """Apply one hostile mutation at ``location``; return it in words."""
        rng = self.rng
        slot_type = location.slot_type
        container, key = location.container, location.key
        if isinstance(slot_type, definition.NamespacedType):
            element_type = message_class(slot_type)
            if rng.random() < 0.5:
                container[key] = default_tree(element_type)
                return f'{location.path} = default {type_name(element_type)}'
            container[key] = self.plausible_tree(element_type, location.field_name)
            return self.make_hostile(container[key], element_type, location.path)
        if isinstance(slot_type, definition.AbstractSequence):
            return self.mutate_sequence(location)
        if isinstance(slot_type, definition.Array):
            index = rng.randrange(slot_type.size) if slot_type.size else None
            if index is None:
                return ''
            inner = Location(container[key], index, slot_type.value_type,
                             f'{location.path}[{index}]', location.field_name)
            return self.mutate_at(inner)
        container[key] = self.hostile_basic(slot_type)
        return f'{location.path} = {short_repr(container[key])}'

    def mutate_sequence(self, location: Location) -> str:
        """Empty, shorten, lengthen, duplicate into or reverse a sequence; say which."""
        rng = self.rng
        values = location.container[location.key]
        bound = getattr(location.slot_type, 'maximum_size', None)
        operations = ['empty', 'drop', 'reverse', 'repeat', 'grow']
        operation = rng.choice(operations)
        if operation == 'empty' or not values:
            values[:] = []
            return f'{location.path} = []'
        if operation == 'drop':
            del values[rng.randrange(len(values))]
            return f'{location.path}: one element removed ({len(values)} left)'
        if operation == 'reverse':
            values.reverse()
            return f'{location.path}: reversed'
        if bound is not None and len(values) >= bound:
            return ''
        index = rng.randrange(len(values))
        if operation == 'repeat':
            values.insert(index, copy_tree(values[index]))
            return f'{location.path}[{index}] repeated'
        element = location.slot_type.value_type
        if isinstance(element, definition.NamespacedType):
            values.append(self.plausible_tree(message_class(element), location.field_name))
        elif isinstance(element, definition.AbstractGenericString):
            values.append(rng.choice(self.plausible.names + HOSTILE_STRINGS))
        else:
            values.append(self.hostile_basic(element))
        return f'{location.path}: one element added ({len(values)})'

    def make_hostile(self, tree, message_type=None, path: str = '') -> str:
        """Make about half of the numbers and strings of ``tree`` hostile; say how many."""
        message_type = message_type or self.message_type
        changed = 0
        for location in list(walk(tree, message_type, path)):
            slot_type = location.slot_type
            if isinstance(slot_type, (definition.BasicType, definition.AbstractGenericString)):
                if self.rng.random() < 0.5:
                    location.container[location.key] = self.hostile_basic(slot_type)
                    changed += 1
        return f'{path or type_name(message_type)}: {changed} values hostile'

    def make_huge(self, tree) -> str:
        """Give one sequence :data:`HUGE_LENGTH` elements (trajectory points first)."""
        sequences = [location for location in walk(tree, self.message_type)
                     if isinstance(location.slot_type, definition.UnboundedSequence)]
        if not sequences:
            return ''
        # A top-level sequence: trajectory points, path poses, an array's data, joint names.
        top = [location for location in sequences if location.path == location.field_name]
        location = self.rng.choice(top or sequences)
        values = location.container[location.key]
        element = location.slot_type.value_type
        if isinstance(element, definition.NamespacedType):
            template = values[0] if values else self.plausible_tree(
                message_class(element), location.field_name)
            values[:] = [copy_tree(template) for _ in range(HUGE_LENGTH)]
            if 'time_from_start' in template:
                step = self.rng.choice((1e-3, 0.01, 1.0))
                for index, value in enumerate(values):
                    value['time_from_start'] = duration_tree(index * step)
        elif isinstance(element, definition.AbstractGenericString):
            values[:] = [f'name_{index}' for index in range(HUGE_LENGTH)]
        else:
            values[:] = [neutral_basic(element.typename, self.rng)] * HUGE_LENGTH
        return f'{location.path}: {HUGE_LENGTH} elements'

    # Oversized fields -------------------------------------------------------------------------

    def oversized_places(self) -> List[str]:
        """
        Return each place of this type a sender can make as large as it likes, once.

        A place is the path of an unbounded sequence or an unbounded string in a plausible
        message (``header.frame_id``, ``name``, ``points``, ``poses[0].header.frame_id``),
        one per field whatever the element (``poses[0]`` stands for every pose); then
        :data:`EVERY_SEQUENCE` when the type has more than one top-level sequence. Fixed-size
        fields (an Imu's covariances) cannot be oversized; a type of fixed size (a Pose) has
        no place.
        """
        places = {}
        for location in walk(self.plausible_tree(self.message_type), self.message_type):
            if _unbounded(location.slot_type):
                places.setdefault(re.sub(r'\[\d+\]', '[0]', location.path), None)
        places = list(places)
        top_fields = dict(fields_of(self.message_type))
        tops = [place for place in places
                if isinstance(top_fields.get(place), definition.UnboundedSequence)]
        return places + ([EVERY_SEQUENCE] if len(tops) > 1 else [])

    def oversized(self, place: str) -> Tuple[object, List[str]]:
        """
        Draw a plausible message with one field grown, or all of them for :data:`EVERY_SEQUENCE`.

        A string becomes :data:`OVERSIZED_CHARACTERS` characters; a number sequence
        :data:`OVERSIZED_VALUES` copies of its first value; a string sequence
        :data:`OVERSIZED_NAMES` names, the platform's joint names but the last among them
        (so a node reads on and refuses the missing leg); a message sequence
        :data:`OVERSIZED_ELEMENTS` copies of its first element. With :data:`EVERY_SEQUENCE`
        each top-level sequence of numbers or strings gets :data:`OVERSIZED_NAMES` elements,
        so that they agree in length (a JointState's names and positions), and each sequence
        of messages :data:`OVERSIZED_ELEMENTS`.

        :param place: one of :meth:`oversized_places`.
        :returns: ``(message, what was done)``, as :meth:`message`.
        """
        for _ in range(PLACE_DRAWS):   # a place inside a sequence that a draw left empty
            tree = self.plausible_tree(self.message_type)
            locations = list(walk(tree, self.message_type))
            if place == EVERY_SEQUENCE or any(location.path == place for location in locations):
                break
        if place == EVERY_SEQUENCE:
            done = [self.oversize(location, None if isinstance(
                        location.slot_type.value_type, definition.NamespacedType)
                        else OVERSIZED_NAMES)
                    for location in locations if location.path == location.field_name
                    and isinstance(location.slot_type, definition.UnboundedSequence)]
        else:
            done = [self.oversize(location) for location in locations
                    if location.path == place][:1]
            if not done:
                raise ValueError(f'{type_name(self.message_type)} has no place {place!r}; '
                                 f'it has {self.oversized_places()}')
        return build(self.message_type, tree), done

    def oversize(self, location: Location, count: Optional[int] = None) -> str:
        """Make the sequence or string at ``location`` oversized (see :meth:`oversized`)."""
        slot_type = location.slot_type
        if isinstance(slot_type, definition.AbstractGenericString):
            location.container[location.key] = 'f' * (count or OVERSIZED_CHARACTERS)
            return f'{location.path}: {count or OVERSIZED_CHARACTERS:,} characters'
        values = location.container[location.key]
        element = slot_type.value_type
        if isinstance(element, definition.NamespacedType):
            count = count or OVERSIZED_ELEMENTS
            template = values[0] if values else self.plausible_tree(
                message_class(element), location.field_name)
            values[:] = [copy_tree(template) for _ in range(count)]
        elif isinstance(element, definition.AbstractGenericString):
            count = count or OVERSIZED_NAMES
            names = list(self.plausible.joint_names[:-1])
            values[:] = names + [f'joint_{index}' for index in range(len(names), count)]
        else:
            count = count or OVERSIZED_VALUES
            value = values[0] if values else neutral_basic(element.typename, self.rng)
            values[:] = [value] * count
        return f'{location.path}: {count:,} elements'

    def hostile_basic(self, slot_type):
        """Return a hostile value of a number, boolean or string type."""
        rng = self.rng
        if isinstance(slot_type, definition.AbstractGenericString):
            value = rng.choice(HOSTILE_STRINGS + self.plausible.names)
            maximum = getattr(slot_type, 'maximum_size', None)
            return value[:maximum] if maximum is not None else value
        typename = slot_type.typename
        if typename == 'double' or typename == 'long double':
            return rng.choice(HOSTILE_DOUBLES)
        if typename == 'float':
            return rng.choice(HOSTILE_FLOATS)
        if typename == 'boolean':
            return rng.random() < 0.5
        if typename == 'octet':
            return bytes([rng.choice((0, 255))])
        if typename == 'wchar':
            return rng.choice(('\0', 'é', 'x'))
        low, high = INTEGER_BOUNDS[typename]
        candidates = [low, high, high // 2 + 1] + [value for value in HOSTILE_INTEGERS
                                                   if low <= value <= high]
        return rng.choice(candidates)


def _unbounded(slot_type) -> bool:
    """Whether a field can be as large as a sender likes: an unbounded sequence or string."""
    if isinstance(slot_type, definition.AbstractGenericString):
        return not slot_type.has_maximum_size()
    return isinstance(slot_type, definition.UnboundedSequence)


def neutral_basic(typename: str, rng: random.Random):
    """Return an ordinary value of a basic type: a number in [-1, 1], a small integer."""
    if typename in ('double', 'float', 'long double'):
        return rng.uniform(-1.0, 1.0)
    if typename == 'boolean':
        return rng.random() < 0.5
    if typename == 'octet':
        return bytes([rng.randrange(256)])
    if typename == 'wchar':
        return 'x'
    low, high = INTEGER_BOUNDS[typename]
    return rng.randint(max(low, 0), min(high, 10))


def small_rotation(rng: random.Random, largest: float = 0.03) -> Tuple[float, ...]:
    """Return a unit quaternion ``(x, y, z, w)`` of a random rotation of at most ``largest``."""
    axis = [rng.gauss(0.0, 1.0) for _ in range(3)]
    norm = math.sqrt(sum(value * value for value in axis)) or 1.0
    half = rng.uniform(0.0, largest) / 2.0
    return tuple(value / norm * math.sin(half) for value in axis) + (math.cos(half),)


def duration_tree(seconds: float) -> Dict[str, int]:
    """Return a builtin_interfaces/Duration of ``seconds`` (>= 0) as a field dict."""
    nanoseconds = int(round(seconds * 1e9))
    return {'sec': nanoseconds // 1_000_000_000, 'nanosec': nanoseconds % 1_000_000_000}


def default_tree(message_type) -> Dict[str, object]:
    """Return a default-constructed message as a field dict (zeros, empty, identity)."""
    return to_tree(message_type())


def to_tree(message) -> Dict[str, object]:
    """Return a message as nested dicts and lists (the fuzzer's tree)."""
    tree = {}
    for name, slot_type in fields_of(type(message)):
        value = getattr(message, name)
        tree[name] = _to_tree_value(value, slot_type)
    return tree


def _to_tree_value(value, slot_type):
    if isinstance(slot_type, definition.NamespacedType):
        return to_tree(value)
    if isinstance(slot_type, definition.AbstractNestedType):
        if isinstance(slot_type.value_type, definition.NamespacedType):
            return [to_tree(element) for element in value]
        return [element.item() if hasattr(element, 'item') else element for element in value]
    return value


def copy_tree(tree):
    """Return a deep copy of a tree (dicts, lists and immutable leaves), fast."""
    if isinstance(tree, dict):
        return {key: copy_tree(value) for key, value in tree.items()}
    if isinstance(tree, list):
        return [copy_tree(value) for value in tree]
    return tree


def walk(tree, message_type, path: str = ''):
    """
    Yield a :class:`Location` for every field and every sequence element of a message tree.

    Nested messages are yielded before their own fields, sequences before their elements.
    """
    for name, slot_type in fields_of(message_type):
        where = f'{path}.{name}' if path else name
        yield Location(tree, name, slot_type, where, name)
        yield from _walk_value(tree[name], slot_type, where, name)


def _walk_value(value, slot_type, path: str, field_name: str):
    if isinstance(slot_type, definition.NamespacedType):
        yield from walk(value, message_class(slot_type), path)
    elif isinstance(slot_type, definition.AbstractSequence):
        element = slot_type.value_type
        # A huge sequence is walked through a sample of its elements: a mutation anywhere in
        # it is as telling, and the walk stays fast.
        indices = range(len(value)) if len(value) <= 64 else sorted(
            {0, len(value) - 1, *range(0, len(value), max(1, len(value) // 32))})
        for index in indices:
            where = f'{path}[{index}]'
            yield Location(value, index, element, where, field_name)
            yield from _walk_value(value[index], element, where, field_name)
    elif isinstance(slot_type, definition.Array) and isinstance(
            slot_type.value_type, definition.NamespacedType):
        for index, element in enumerate(value):
            yield from _walk_value(element, slot_type.value_type, f'{path}[{index}]', field_name)


def build(message_type, tree):
    """Build a message of ``message_type`` from its tree (nested dicts and lists)."""
    arguments = {}
    for name, slot_type in fields_of(message_type):
        arguments[name] = _build_value(tree[name], slot_type)
    return message_type(**arguments)


def _build_value(value, slot_type):
    if isinstance(slot_type, definition.NamespacedType):
        return build(message_class(slot_type), value)
    if isinstance(slot_type, definition.AbstractNestedType) and isinstance(
            slot_type.value_type, definition.NamespacedType):
        element_type = message_class(slot_type.value_type)
        return [build(element_type, element) for element in value]
    return value


def short_repr(value, limit: int = 40) -> str:
    """Return ``repr(value)`` cut to ``limit`` characters, for the description of a mutation."""
    text = repr(value)
    return text if len(text) <= limit else f'{text[:limit]}... ({len(value)} long)'


def summarize(done: Sequence[str], limit: int = 3) -> str:
    """Return the first ``limit`` mutations of a message in one line."""
    text = '; '.join(done[:limit])
    return text + (f'; and {len(done) - limit} more' if len(done) > limit else '')


def choose_kind(rng: random.Random, weights: Optional[Dict[str, float]] = None) -> str:
    """Draw the kind of the next message: mostly mutated, some plausible, some hostile."""
    weights = weights or {'plausible': 0.25, 'mutated': 0.6, 'hostile': 0.15}
    kinds = list(weights)
    return rng.choices(kinds, [weights[kind] for kind in kinds])[0]
