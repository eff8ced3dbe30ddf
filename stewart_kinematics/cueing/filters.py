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
Linear filters of the washout, discretised exactly for the time step each sample brings.

A filter is a continuous transfer function ``N(s) / D(s)`` (coefficients highest power first,
``D`` monic); :func:`high_pass`, :func:`low_pass` and :func:`integrated` build the ones of the
classical washout. A :class:`FilterBank` stacks several of them, each driven by one input and
read through any of its derivatives, into one block-diagonal state-space system
``x' = A x + B u``, ``y = C x + D u`` (controllable canonical form of each block).

Discretisation: the newest sample is held over the interval that ends with it, and the state is
advanced with the exact solution for that held input, ``x+ = Phi x + Gamma u`` with
``[[Phi, Gamma], [0, I]] = expm([[A, B], [0, 0]] dt)`` (zero-order hold, Franklin, Powell and
Workman, *Digital Control of Dynamic Systems*, 3rd ed., section 4.3.3). A step of the input
therefore gives, at every sample, the continuous filter's step response to rounding; tests check
it against the closed forms. The pair ``(Phi, Gamma)`` is computed for each distinct step
(rounded to :data:`TIME_QUANTUM`, the rounding carried into the next step so that the filter's
clock never drifts from the samples' stamps) and kept in a small cache, so that a jittered
stream costs one matrix exponential per new step length, not one per sample.

Nothing here imports ROS.
"""

from collections import OrderedDict
import math
from typing import Sequence

import numpy as np

#: Steps are rounded to a multiple of this, seconds; the remainder goes into the next step.
TIME_QUANTUM = 1e-6
#: Distinct step lengths whose discretisation is kept.
CACHE_SIZE = 1024
#: Pade degree of the matrix exponential, exact to rounding once the norm is scaled to 1/2.
_PADE_DEGREE = 6


def second_order(frequency: float, damping: float) -> np.ndarray:
    """Return ``s^2 + 2 zeta omega s + omega^2`` (``frequency`` omega, rad/s; ``damping`` zeta)."""
    return np.array([1.0, 2.0 * damping * frequency, frequency * frequency])


def first_order(frequency: float) -> np.ndarray:
    """Return ``s + omega`` (``frequency`` omega, rad/s)."""
    return np.array([1.0, frequency])


def high_pass(order: int, frequency: float, damping: float, break_frequency: float = 0.0):
    """
    Return the high-pass filter of the classical washout as ``(numerator, denominator)``.

    - order 1: ``s / (s + omega)``;
    - order 2: ``s^2 / (s^2 + 2 zeta omega s + omega^2)``;
    - order 3: the order-2 filter times ``s / (s + omega_b)`` (``break_frequency``), Reid and
      Nahon's translational channel.

    :raises ValueError: for another order.
    """
    if order == 1:
        return np.array([1.0, 0.0]), first_order(frequency)
    if order == 2:
        return np.array([1.0, 0.0, 0.0]), second_order(frequency, damping)
    if order == 3:
        return (np.array([1.0, 0.0, 0.0, 0.0]),
                np.polymul(second_order(frequency, damping), first_order(break_frequency)))
    raise ValueError(f'high-pass order must be 1, 2 or 3, got {order!r}')


def low_pass(order: int, frequency: float, damping: float):
    """
    Return a unit-gain low-pass filter as ``(numerator, denominator)``.

    Order 1: ``omega / (s + omega)``; order 2: ``omega^2 / (s^2 + 2 zeta omega s + omega^2)``.

    :raises ValueError: for another order.
    """
    if order == 1:
        return np.array([frequency]), first_order(frequency)
    if order == 2:
        return np.array([frequency * frequency]), second_order(frequency, damping)
    raise ValueError(f'low-pass order must be 1 or 2, got {order!r}')


def complement(filter_pair):
    """
    Return ``1 - N / D`` as ``(numerator, denominator)``: the low-pass that completes a high-pass.

    :raises ValueError: unless ``N / D`` has unit gain at high frequency (numerator of the
        denominator's degree and leading coefficient), as a high-pass has.
    """
    numerator, denominator = filter_pair
    if numerator.size != denominator.size or numerator[0] != denominator[0]:
        raise ValueError('only a high-pass of unit gain at high frequency has a complement')
    remainder = np.trim_zeros(denominator - numerator, 'f')
    return remainder, denominator


def integrated(filter_pair, times: int):
    """
    Return ``filter / s^times``, cancelling the numerator's zeros at the origin.

    The position of the translational channel is its high-passed acceleration integrated twice;
    with a high-pass of order ``times`` or more the zeros cancel and the result has no pole at
    the origin, so the position returns to zero after a step of the input.

    :raises ValueError: when the numerator has fewer than ``times`` zeros at the origin.
    """
    numerator, denominator = filter_pair
    for _ in range(times):
        if numerator.size < 2 or numerator[-1] != 0.0:
            raise ValueError('the filter has too few zeros at s = 0 to be integrated '
                             f'{times} time(s): it would drift')
        numerator = numerator[:-1]
    return numerator, denominator


def expm(matrix: np.ndarray) -> np.ndarray:
    """
    Matrix exponential of a small square matrix: Pade approximant with scaling and squaring.

    The matrix is scaled by ``2^-k`` to an infinity norm of at most 1/2, where the degree-6
    diagonal Pade approximant is exact to rounding (Golub and Van Loan, *Matrix Computations*,
    algorithm 11.3.1), then squared ``k`` times.
    """
    norm = float(np.max(np.sum(np.abs(matrix), axis=1))) if matrix.size else 0.0
    squarings = max(0, int(math.ceil(math.log2(norm / 0.5)))) if norm > 0.5 else 0
    scaled = matrix / (2.0 ** squarings)
    identity = np.eye(matrix.shape[0])
    numerator, denominator = identity.copy(), identity.copy()
    power = identity
    coefficient = 1.0
    for k in range(1, _PADE_DEGREE + 1):
        coefficient *= (_PADE_DEGREE - k + 1) / (k * (2 * _PADE_DEGREE - k + 1))
        power = power @ scaled
        numerator = numerator + coefficient * power
        denominator = denominator + (-1.0) ** k * coefficient * power
    result = np.linalg.solve(denominator, numerator)
    for _ in range(squarings):
        result = result @ result
    return result


class FilterBank:
    """
    Several transfer functions as one state-space system, stepped at the samples' times.

    :param inputs: number of inputs ``u`` (a vector).
    :param blocks: ``(numerator, denominator, input_index, outputs)`` per filter, where
        ``outputs`` lists the derivatives to read: 0 for the filter's output, 1 for its time
        derivative, and so on (each must stay proper). The bank's outputs are every block's
        outputs, in order.
    :raises ValueError: if a denominator is not monic with a non-zero constant term (a pole at
        the origin would never settle), or an output is improper.
    """

    def __init__(self, inputs: int, blocks: Sequence):
        sizes = [len(denominator) - 1 for _, denominator, _, _ in blocks]
        states = sum(sizes)
        outputs = sum(len(block[3]) for block in blocks)
        a = np.zeros((states, states))
        b = np.zeros((states, inputs))
        c = np.zeros((outputs, states))
        d = np.zeros((outputs, inputs))
        start = row = 0
        for (numerator, denominator, input_index, derivatives), size in zip(blocks, sizes):
            denominator = np.asarray(denominator, dtype=float)
            if denominator[0] != 1.0 or denominator[-1] == 0.0 or size < 1:
                raise ValueError('a filter denominator must be monic, of degree >= 1, without a '
                                 f'root at s = 0; got {denominator.tolist()}')
            # Companion form of 1 / D(s): states z, z', ..., z^(n-1); z^(n) = u - sum a_i z^(i).
            ascending = denominator[::-1][:-1]  # a_0 .. a_(n-1)
            block = slice(start, start + size)
            a[block, block] = np.eye(size, k=1)
            a[start + size - 1, block] = -ascending
            b[start + size - 1, input_index] = 1.0
            for derivative in derivatives:
                # y = s^derivative N(s) z: coefficients of z, z', ..., z^(n) (ascending).
                polynomial = np.polymul(np.asarray(numerator, dtype=float),
                                        np.r_[1.0, np.zeros(derivative)])[::-1]
                if polynomial.size > size + 1:
                    raise ValueError(f'derivative {derivative} of a filter of order {size} is '
                                     'improper')
                polynomial = np.r_[polynomial, np.zeros(size + 1 - polynomial.size)]
                c[row, block] = polynomial[:size] - polynomial[size] * ascending
                d[row, input_index] = polynomial[size]
                row += 1
            start += size
        self.a, self.b, self.c, self.d = a, b, c, d
        self.state = np.zeros(states)
        self._carry = 0.0
        self._cache = OrderedDict()

    @property
    def order(self) -> int:
        """Return the number of states."""
        return self.state.size

    def settle(self, u) -> np.ndarray:
        """
        Put the bank at the steady state of a constant input ``u`` and return its outputs.

        High-pass outputs are then zero and low-pass outputs equal their input: a stream that
        starts in a sustained turn starts without a step cue.
        """
        u = np.asarray(u, dtype=float)
        self.state = -np.linalg.solve(self.a, self.b @ u)
        self._carry = 0.0
        return self.output(u)

    def step(self, u, dt: float) -> np.ndarray:
        """
        Advance by ``dt`` seconds with ``u`` held over the interval, and return the outputs.

        :param u: the newest input sample, shape (inputs,).
        :param dt: seconds since the previous sample, >= 0 (the caller checks it).
        """
        u = np.asarray(u, dtype=float)
        quanta = round((dt + self._carry) / TIME_QUANTUM)
        self._carry += dt - quanta * TIME_QUANTUM
        if quanta > 0:
            phi, gamma = self.discretised(quanta)
            self.state = phi @ self.state + gamma @ u
        return self.output(u)

    def output(self, u) -> np.ndarray:
        """Return the outputs for the current state and the input ``u``."""
        return self.c @ self.state + self.d @ np.asarray(u, dtype=float)

    def discretised(self, quanta: int):
        """
        Return ``(Phi, Gamma)`` for a step of ``quanta`` * :data:`TIME_QUANTUM` seconds.

        Exact zero-order-hold discretisation, cached by step length.
        """
        cached = self._cache.get(quanta)
        if cached is not None:
            self._cache.move_to_end(quanta)
            return cached
        states, inputs = self.b.shape
        augmented = np.zeros((states + inputs, states + inputs))
        augmented[:states, :states] = self.a
        augmented[:states, states:] = self.b
        exponential = expm(augmented * (quanta * TIME_QUANTUM))
        pair = (exponential[:states, :states].copy(), exponential[:states, states:].copy())
        self._cache[quanta] = pair
        if len(self._cache) > CACHE_SIZE:
            self._cache.popitem(last=False)
        return pair
