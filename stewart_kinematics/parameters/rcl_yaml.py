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
YAML read as rcl reads a parameter file, within limits: the package's one YAML reader.

Every parameter file and ``-p`` value the package reads (the command-line tools, the nodes'
second reading of their own arguments, the fuzzer) goes through :func:`read_yaml_file` or
:func:`parse_yaml_value`. They build the values from PyYAML's event stream (libyaml's parser
where PyYAML was built with it, the parser rcl_yaml_param_parser uses), with an explicit stack
instead of PyYAML's recursive composer, and refuse what a real parameter file never holds:

- an alias (``*name``, ``<<: *base``): rcl refuses every alias too ("Will not support
  aliasing"), and 500 bytes of nested aliases expand to 10^9 values;
- collections nested deeper than :data:`MAX_DEPTH`;
- more than :data:`MAX_VALUES` values, or a file larger than :data:`MAX_FILE_BYTES`;
- an empty value (``name:`` with nothing after it), as rcl does ("No value at line N"), an
  empty key or one that is a list or a mapping, and a second YAML document.

Each refusal is a :class:`ParameterFileError`: one line, ``file:line: what is wrong``. Reading
is bounded in time by the limits (a file at the limits reads in about a second with libyaml).

Scalars are typed as rcl types them (:func:`rcl_scalar`); an unquoted ``null`` or ``~`` stays
the string rcl makes of it, marked as a :class:`~stewart_kinematics.parameters.spec.NullString`
so that a refusal can say it was an empty value, not a string in quotes. Nothing here imports
ROS.
"""

from dataclasses import dataclass, field
import math
import re
import sys
from typing import Dict, Optional, Tuple

from stewart_kinematics.parameters.spec import NullString, OutOfRangeNumber
import yaml

#: Deepest nesting of collections (mappings and lists) allowed. A parameter file needs a few
#: levels: the file's mapping, a namespace or two, the node's name, ``ros__parameters``,
#: dotted parameter names written as nested maps (``qos_overrides: /topic: publisher:
#: depth``, 6 levels) and a list. 64 leaves a wide margin over any real file, and keeps every
#: walk of the values (flattening, matching) far from Python's recursion limit of 1000.
MAX_DEPTH = 64
#: Most values (scalars and collections) in one file. The package's largest file holds a few
#: hundred; the cap bounds the reader's work and memory far above that, so that a hostile
#: file cannot make the reader build more.
MAX_VALUES = 1_000_000
#: Largest file read, in bytes: a parameter file is kilobytes (a robot description inlined as
#: a string, the largest value seen in ROS parameter files, is at most a few megabytes).
MAX_FILE_BYTES = 16 * 1024 * 1024

#: rcl's words for true and false (rcl_yaml_param_parser): YAML 1.1's, in three spellings.
_TRUE_WORDS = {'y', 'Y', 'yes', 'Yes', 'YES', 'true', 'True', 'TRUE', 'on', 'On', 'ON'}
_FALSE_WORDS = {'n', 'N', 'no', 'No', 'NO', 'false', 'False', 'FALSE', 'off', 'Off', 'OFF'}
#: YAML's words for null (an empty value); rcl reads them as strings.
_NULL_WORDS = {'null', 'Null', 'NULL', '~'}
_SPECIAL_FLOATS = {'.nan': math.nan, '.NaN': math.nan, '.NAN': math.nan, '.inf': math.inf,
                   '.Inf': math.inf, '.INF': math.inf, '+.inf': math.inf, '+.Inf': math.inf,
                   '+.INF': math.inf, '-.inf': -math.inf, '-.Inf': -math.inf,
                   '-.INF': -math.inf}
_STRING_TAG = 'tag:yaml.org,2002:str'
_INT64_MIN, _INT64_MAX = -2 ** 63, 2 ** 63 - 1
#: An integer as C's strtol reads it with base 0: decimal, 0x hexadecimal or 0 octal.
_INTEGER = re.compile(r'\s*[+-]?(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)\Z')
#: libyaml's parser where PyYAML has it (rcl's own, and compiled: much faster), else PyYAML's.
_LOADER = getattr(yaml, 'CSafeLoader', yaml.SafeLoader)
#: Longest text of a value or key quoted in a message.
_PREVIEW_CHARACTERS = 60


class ParameterFileError(ValueError):
    """
    A parameter file (or ``-p`` value) that cannot be read: ``file:line: what is wrong``.

    :param source: the file's path (or the value, for ``-p``).
    :param line: the line the problem is on (1 for the first), or ``None`` for the whole file.
    :param problem: what is wrong, one line.
    """

    def __init__(self, source, line: Optional[int], problem: str):
        self.source, self.line = str(source), line
        self.problem = ' '.join(str(problem).split())
        where = self.source if line is None else f'{self.source}:{line}'
        super().__init__(f'{where}: {self.problem}')


@dataclass
class YamlDocument:
    """
    What a YAML file holds, and where.

    :param value: the values: dicts, lists and rcl-typed scalars; ``None`` for an empty file.
    :param lines: the line of every key of a mapping, by its path of keys from the top
        (``('/**', 'ros__parameters', 'leg_length_max')``).
    """

    value: object = None
    lines: Dict[Tuple[str, ...], int] = field(default_factory=dict)


def rcl_scalar(text: str, quoted: bool = False):
    """
    Type a YAML scalar as rcl does: a quoted one is a string; else bool, integer, float, string.

    rcl tries C's strtol (base 0) then strtod, and keeps the first that reads the whole text
    without a range error. So ``1e-3`` (no dot, a string in YAML 1.1) is a double, an integer
    beyond 64 bits is a double, and ``1e999`` or ``1e-400`` (out of a double's range) is a
    string, marked as an :class:`~stewart_kinematics.parameters.spec.OutOfRangeNumber`. A node
    and this package's tools must see the same value. An unquoted ``null`` or ``~`` is a string
    for rcl too: it comes back as a :class:`~stewart_kinematics.parameters.spec.NullString`.
    A refusal names either for what it is, not as a value written in quotes.

    :param text: the scalar as written.
    :param quoted: whether it was written in quotes (or tagged ``!!str``).
    """
    if quoted:
        return text
    if text in _NULL_WORDS:
        return NullString(text)
    if text in _TRUE_WORDS:
        return True
    if text in _FALSE_WORDS:
        return False
    if text[-1:].isspace():   # strtol and strtod stop before it: a string for rcl
        return text
    if _INTEGER.match(text):
        value = _strtol(text.strip())
        if value is not None:
            return value
    if text in _SPECIAL_FLOATS:
        return _SPECIAL_FLOATS[text]
    return _strtod(text)


def _strtol(text: str) -> Optional[int]:
    """Return an integer as strtol reads it (base 0), or ``None`` beyond 64 bits (ERANGE)."""
    digits = text.lstrip('+-')
    if digits[:2] in ('0x', '0X'):
        value = int(text, 16)
    elif digits.startswith('0'):
        value = int(text, 8)
    elif len(digits) > 19:   # beyond 64 bits (and Python's limit of digits to convert)
        return None
    else:
        value = int(text)
    return value if _INT64_MIN <= value <= _INT64_MAX else None


def _strtod(text: str):
    """Return a float as strtod reads it, or the text when strtod would not (ERANGE too)."""
    if '_' in text:   # Python's float reads 1_000; strtod does not
        return text
    stripped = text.strip()
    hexadecimal = re.match(r'[+-]?0[xX]', stripped) is not None
    try:
        value = float.fromhex(stripped) if hexadecimal else float(stripped)
    except (ValueError, OverflowError):
        return text
    # strtod reads inf, nan and infinity in any case; YAML's own are handled above.
    if math.isinf(value) and 'inf' not in stripped.lower():
        return OutOfRangeNumber(text)   # overflow: strtod sets ERANGE
    if (value == 0.0 and _nonzero_mantissa(stripped, hexadecimal)) or (
            value != 0.0 and abs(value) < sys.float_info.min):
        return OutOfRangeNumber(text)   # underflow to zero or to a subnormal: ERANGE (glibc)
    return value


def _nonzero_mantissa(text: str, hexadecimal: bool) -> bool:
    """Whether the digits before a number's exponent hold one that is not zero."""
    if hexadecimal:
        mantissa = re.split('[pP]', text.split('x', 1)[-1].split('X', 1)[-1])[0]
        return re.search('[1-9a-fA-F]', mantissa) is not None
    return re.search('[1-9]', re.split('[eE]', text)[0]) is not None


def preview(text: str, quoted: bool = True) -> str:
    """Return ``text`` (in quotes), shortened to its start and its length when it is long."""
    shown = repr if quoted else str
    if len(text) <= _PREVIEW_CHARACTERS:
        return shown(text)
    return f'{shown(text[:_PREVIEW_CHARACTERS])}... ({len(text)} characters)'


def read_yaml_file(path) -> YamlDocument:
    """
    Read a YAML file within the limits; see the module's documentation.

    :param path: the file.
    :raises ParameterFileError: if the file cannot be read, is larger than
        :data:`MAX_FILE_BYTES`, is not UTF-8 YAML, or breaks a rule or a limit.
    """
    try:
        with open(path, 'rb') as stream:
            data = stream.read(MAX_FILE_BYTES + 1)
    except OSError as error:
        raise ParameterFileError(path, None, f'cannot read parameter file: {error.strerror}'
                                 ) from None
    if len(data) > MAX_FILE_BYTES:
        raise ParameterFileError(path, None, (
            f'larger than {MAX_FILE_BYTES} bytes: not a parameter file'))
    try:
        text = data.decode('utf-8-sig')
    except UnicodeDecodeError as error:
        line = data[:error.start].count(b'\n') + 1
        raise ParameterFileError(path, line, (
            f'not UTF-8 text: byte 0x{data[error.start]:02x} cannot be decoded')) from None
    return _compose(text, path)


def parse_yaml_value(text: str):
    """
    Parse a YAML value as rcl parses the value of ``-p name:=value``, within the limits.

    :returns: the value, typed as rcl types it (``None`` for no value at all).
    :raises ParameterFileError: (a ``ValueError``) if it is not YAML or breaks a rule or a
        limit; the message names the value.
    """
    return _compose(text, preview(text)).value


class _Collection:
    """One mapping or list being built, and the key waiting for its value."""

    __slots__ = ('value', 'key', 'path')

    def __init__(self, value, path):
        self.value, self.key, self.path = value, None, path


def _compose(text: str, source) -> YamlDocument:
    """Build the values of one YAML document from its events, without recursion."""
    document = YamlDocument()
    stack = []
    values = 0
    documents = 0
    try:
        for event in yaml.parse(text, Loader=_LOADER):
            line = event.start_mark.line + 1
            if isinstance(event, yaml.AliasEvent):
                raise ParameterFileError(source, line, (
                    f'YAML alias *{preview(event.anchor, quoted=False)} refused: a parameter '
                    'file cannot use aliases (rcl refuses them too); write the values out'))
            if isinstance(event, yaml.DocumentStartEvent):
                documents += 1
                if documents > 1:
                    raise ParameterFileError(source, line, (
                        'a second YAML document (---): a parameter file holds one'))
                continue
            if not isinstance(event, (yaml.ScalarEvent, yaml.CollectionStartEvent,
                                      yaml.CollectionEndEvent)):
                continue
            if isinstance(event, yaml.CollectionEndEvent):
                _add(document, stack, stack.pop().value)
                continue
            values += 1
            if values > MAX_VALUES:
                raise ParameterFileError(source, line, (
                    f'more than {MAX_VALUES} values: not a parameter file'))
            top = stack[-1] if stack else None
            waiting_for_key = top is not None and isinstance(top.value, dict) and (
                top.key is None)
            if isinstance(event, yaml.CollectionStartEvent):
                if waiting_for_key:
                    raise ParameterFileError(source, line, (
                        'a key must be a name, not a list or a mapping'))
                if len(stack) >= MAX_DEPTH:
                    raise ParameterFileError(source, line, (
                        f'nested more than {MAX_DEPTH} levels deep: a parameter file needs a '
                        'few (node name, ros__parameters, parameter names)'))
                if top is None:
                    path = ()
                else:
                    path = top.path + (top.key,) if isinstance(top.value, dict) else top.path
                stack.append(_Collection(
                    {} if isinstance(event, yaml.MappingStartEvent) else [], path))
                continue
            # rcl: a scalar in quotes, or tagged !!str, is a string; other tags are ignored.
            quoted = event.style in ("'", '"') or event.tag == _STRING_TAG
            empty = event.value == '' and not quoted
            if waiting_for_key:
                if event.value == '':   # rcl: "No key", quoted or not
                    raise ParameterFileError(source, line, 'a key is empty')
                top.key = event.value
                document.lines[top.path + (top.key,)] = line
                continue
            if empty and stack:
                key = f' {preview(top.key)}' if isinstance(top.value, dict) else ''
                raise ParameterFileError(source, line, (
                    f'the value of{key or " a list item"} is empty: write a value, or remove '
                    'the line to keep the default (rcl refuses an empty value)'))
            if empty:
                continue   # an empty document
            _add(document, stack, rcl_scalar(event.value, quoted))
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        problem = error.problem or error.context or 'cannot be parsed'
        context = f' ({error.context})' if error.context and error.problem else ''
        raise ParameterFileError(source, None if mark is None else mark.line + 1, (
            f'not valid YAML: {problem}{context}')) from None
    except yaml.YAMLError as error:   # ReaderError: a character YAML does not allow
        position = getattr(error, 'position', None)
        line = None if position is None else text[:position].count('\n') + 1
        reason = getattr(error, 'reason', None) or 'cannot be parsed'
        raise ParameterFileError(source, line, f'not valid YAML: {reason}') from None
    return document


def _add(document, stack, value):
    """Put a finished value into the collection being built (or make it the document's)."""
    if not stack:
        document.value = value
        return
    top = stack[-1]
    if isinstance(top.value, list):
        top.value.append(value)
        return
    # rcl keeps the last of repeated keys, as PyYAML does.
    top.value[top.key] = value
    top.key = None
