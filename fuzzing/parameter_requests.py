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
Parameter requests to a running node, and whether its answers are right.

:func:`parameter_clients` and :func:`parameter_fuzzer_of` read what a node lists, describes and
holds through its parameter services; :class:`ParameterRequests` sends the changes a
:class:`~fuzzing.fuzz_parameters.ParameterFuzzer` draws and checks each answer
as it arrives (a change that must be refused is, with a reason; an accepted frame change gives
the output checks its frame tree); :func:`held_value_problems` checks at the end that the node
holds the last values it accepted. Shared by the node fuzzer and the soak.
"""

import math
import threading
from typing import Dict, List, Optional

from fuzzing.fuzz_parameters import (
    EITHER,
    ParameterFuzzer,
    python_value,
    REFUSED,
)
from fuzzing.output_invariants import OutputInvariants
from rcl_interfaces.srv import (
    DescribeParameters,
    GetParameters,
    ListParameters,
    SetParameters,
    SetParametersAtomically,
)

from stewart_kinematics.parameters import FRAME_PARAMETERS

#: Names of the frame parameters: an accepted change gives the output checks a frame tree.
FRAME_NAMES = frozenset(spec.name for spec in FRAME_PARAMETERS)
#: Seconds to wait for an answer, by default.
DEADLINE = 20.0


def parameter_clients(node, target: str) -> dict:
    """Return clients of the parameter services of the node ``target`` (its full name), by type."""
    return {kind: node.create_client(kind, f'{target}/{name}') for kind, name in (
        (SetParameters, 'set_parameters'), (SetParametersAtomically, 'set_parameters_atomically'),
        (GetParameters, 'get_parameters'), (ListParameters, 'list_parameters'),
        (DescribeParameters, 'describe_parameters'))}


def parameter_fuzzer_of(client, services, rng, timeout: float = DEADLINE
                        ) -> Optional[ParameterFuzzer]:
    """
    List, describe and read a node's parameters; return the fuzzer of their changes.

    :param services: the node's :func:`parameter_clients`.
    :returns: the fuzzer, or ``None`` when a service did not answer within ``timeout``.
    """
    listed = client.call(services[ListParameters], ListParameters.Request(), timeout)
    if listed is None:
        return None
    names = sorted(listed.result.names)
    described = client.call(services[DescribeParameters],
                            DescribeParameters.Request(names=names), timeout)
    values = client.call(services[GetParameters], GetParameters.Request(names=names), timeout)
    if described is None or values is None:
        return None
    return ParameterFuzzer(rng, dict(zip(names, described.descriptors)),
                           {name: python_value(value)
                            for name, value in zip(names, values.values)})


class ParameterRequests:
    """
    The parameter requests sent to one node, checked as their answers arrive.

    :param fuzzer: the node's :class:`ParameterFuzzer` (told what was accepted).
    :param invariants: the output checks (told of accepted frame changes).
    """

    def __init__(self, fuzzer: ParameterFuzzer, invariants: OutputInvariants):
        self.fuzzer = fuzzer
        self.invariants = invariants
        self.pending = []
        self.sent = []
        self.problems: List[str] = []
        self.counts: Dict[str, int] = {}
        self._lock = threading.Lock()

    def send(self, client, changes, atomic: bool):
        """Send a request of ``changes``; its answer is checked when it arrives."""
        request = (SetParametersAtomically if atomic else SetParameters).Request(
            parameters=[change.message for change in changes])
        future = client.call_async(request)
        self.pending.append(future)
        self.sent.append((future, changes))
        future.add_done_callback(lambda done: self._answer(done, changes, atomic))

    def _answer(self, future, changes, atomic):
        response = future.result()
        with self._lock:
            if response is None:
                self.problems.append('a parameter request got no response')
                return
            if atomic:
                result = response.result
                must_refuse = [change for change in changes if change.expect == REFUSED]
                if must_refuse and result.successful:
                    self.problems.append(
                        'an atomic request was accepted although it held '
                        + '; '.join(change.describe() for change in must_refuse))
                self._count('atomic ' + ('accepted' if result.successful else 'refused'))
                if result.successful:
                    for change in changes:
                        self._apply(change)
                return
            if len(response.results) != len(changes):
                self.problems.append(f'{len(changes)} changes got {len(response.results)} results')
                return
            for change, result in zip(changes, response.results):
                self._check(change, result)

    def _check(self, change, result):
        if result.successful:
            self._count('accepted')
            if change.expect == REFUSED:
                self.problems.append(f'accepted {change.describe()}')
            else:
                self._apply(change)
            return
        self._count('refused (must)' if change.expect == REFUSED else 'refused (valid value)')
        if not result.reason:
            self.problems.append(f'refused without a reason: {change.describe()}')
        elif change.names_parameter and f"'{change.name}'" not in result.reason:
            self.problems.append(f'refused with a reason that does not name the parameter: '
                                 f'{change.describe()}: {result.reason!r}')

    def _apply(self, change):
        self.fuzzer.accepted(change)
        if change.name in FRAME_NAMES:
            self.invariants.add_frames(self.fuzzer.values)

    def _count(self, what):
        self.counts[what] = self.counts.get(what, 0) + 1

    def done(self) -> bool:
        """Whether every request has been answered."""
        return all(future.done() for future in self.pending)

    def forget_unanswered(self):
        """
        Give up on the requests not answered: their valid changes may or may not hold.

        A value a lost request may have set is allowed for its parameter from now on
        (:meth:`ParameterFuzzer.allow`), and so is its frame tree for the output checks.
        """
        with self._lock:
            for future, changes in self.sent:
                if future.done():
                    continue
                self._count('unanswered')
                for change in changes:
                    if change.expect == EITHER:
                        self.fuzzer.allow(change)
                        if change.name in FRAME_NAMES:
                            self.invariants.add_frames({**self.fuzzer.values,
                                                        change.name: change.value})


def held_value_problems(client, services, fuzzer, timeout: float = DEADLINE) -> List[str]:
    """
    Say which writable parameters do not hold the last value the node accepted.

    A value an unanswered request may have set counts too (:meth:`ParameterFuzzer.allow`).
    """
    expected = fuzzer.checked_values()
    names = sorted(expected)
    answer = client.call(services[GetParameters], GetParameters.Request(names=names), timeout)
    if answer is None:
        return ['no answer to the final get_parameters']
    problems = []
    for name, value in zip(names, answer.values):
        held = python_value(value)
        if not any(_same(held, allowed) for allowed in [expected[name]]
                   + fuzzer.alternatives.get(name, [])):
            problems.append(f'parameter {name} holds {held!r}, not {expected[name]!r}, the last '
                            'value accepted')
    return problems


def _same(a, b) -> bool:
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b
