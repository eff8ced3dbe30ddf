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
What the property tests share: hypothesis profiles, strategies, and the checks of a refusal.

Profiles (``HYPOTHESIS_PROFILE``, default ``ci``): ``ci`` runs a bounded number of examples
(the whole property suite in well under a minute), ``long`` fifty times as many, ``replay``
only the examples stored in the database. The database is ``.hypothesis/examples`` under the
repository (git-ignored): a failing example is stored there and tried first by the next run,
and hypothesis prints the ``@reproduce_failure`` line that replays it anywhere. See
doc/testing_adversarial.md.

:func:`covers` records which public names a property test exercises; test_properties_api.py
fails for a name of ``stewart_kinematics.__all__`` that no property test covers.
"""

import math
import os
from pathlib import Path

from hypothesis import HealthCheck, Phase, settings, strategies as st
from hypothesis.database import DirectoryBasedExampleDatabase
import numpy as np
import pytest
from reference import HOME, paper_geometry

ROOT = Path(__file__).resolve().parent.parent
DATABASE = DirectoryBasedExampleDatabase(str(ROOT / '.hypothesis' / 'examples'))
PROFILE = os.environ.get('HYPOTHESIS_PROFILE', 'ci')
#: Examples per test in the ``long`` profile, as a multiple of the ``ci`` count.
LONG_FACTOR = 50

_COMMON = {'database': DATABASE, 'deadline': None, 'print_blob': True,
           'suppress_health_check': [HealthCheck.too_slow, HealthCheck.data_too_large,
                                     HealthCheck.filter_too_much]}
settings.register_profile('ci', max_examples=25, derandomize=False, **_COMMON)
settings.register_profile('long', max_examples=25 * LONG_FACTOR, **_COMMON)
settings.register_profile('replay', max_examples=25, phases=[Phase.explicit, Phase.reuse],
                          **_COMMON)
settings.load_profile(PROFILE)


def budget(examples: int):
    """Return settings for ``examples`` examples in ``ci`` (``LONG_FACTOR`` times in ``long``)."""
    return settings(max_examples=examples * (LONG_FACTOR if PROFILE == 'long' else 1))


def covers(*names):
    """Mark a property test as exercising these public names (see test_properties_api.py)."""
    def mark(test):
        test.covers = tuple(names)
        return test
    return mark


# Geometries: the paper's platform, with and without the example limits.
PAPER = paper_geometry()
EXAMPLE_LIMITS = {'leg_length_min': 0.65, 'leg_length_max': 0.90,
                  'base_joint_max_angle': math.radians(30.0),
                  'platform_joint_max_angle': math.radians(35.0), 'max_jacobian_condition': 50.0}
LIMITED = paper_geometry(**EXAMPLE_LIMITS)
HOME_POSE = np.array(HOME)

# Numbers.
#: Values that must never pass as a finite number.
NON_FINITE = st.sampled_from([math.nan, math.inf, -math.inf])
#: Finite values too large for any platform, whose products overflow.
HUGE = st.sampled_from([1e308, -1e308, 1.7e308, 1e200, -1e155])
#: Words of numpy's own errors, which name no argument: never the message of a refusal.
NUMPY_WORDS = ('setting an array element', 'could not convert', 'float() argument',
               'zero-size array', 'could not be broadcast', 'inhomogeneous', 'index ',
               'object of type', 'unsupported operand', 'not subscriptable',
               'has no len', 'object is not iterable')


def floats(low, high):
    """Finite floats in [low, high]."""
    return st.floats(low, high, allow_nan=False, allow_infinity=False)


def small_angles(limit=math.radians(12.0)):
    """Three Euler angles within +-limit radians."""
    return st.tuples(*[floats(-limit, limit)] * 3).map(np.array)


def any_angles():
    """Euler angles anywhere: alpha, gamma in [-pi, pi], beta within 1e-6 of +-pi/2."""
    half = math.pi / 2 - 1e-6
    return st.tuples(floats(-math.pi, math.pi), floats(-half, half),
                     floats(-math.pi, math.pi)).map(np.array)


def poses_near_home(position=0.06, angle=math.radians(10.0)):
    """Poses within +-position metres and +-angle radians of the paper's home pose."""
    return st.tuples(*[floats(-position, position)] * 3, *[floats(-angle, angle)] * 3).map(
        lambda offsets: HOME_POSE + np.array(offsets))


def pose_batches(max_size=8, **ranges):
    """Batches (N, 6) of poses near home, N from 0 to ``max_size``."""
    return st.lists(poses_near_home(**ranges), min_size=0, max_size=max_size).map(
        lambda rows: np.array(rows, dtype=float).reshape(-1, 6))


def unit_quaternions():
    """Draw unit quaternions (x, y, z, w), from random 4-vectors well away from zero."""
    return st.tuples(*[floats(-1.0, 1.0)] * 4).filter(
        lambda q: sum(v * v for v in q) > 1e-2).map(lambda q: np.array(q) / np.linalg.norm(q))


def with_bad_entry(values, bad):
    """Return ``values`` (an array) with one entry replaced by ``bad``, chosen by hypothesis."""
    return st.integers(0, values.size - 1).map(
        lambda index: np.where(np.arange(values.size) == index, bad, values.ravel()).reshape(
            values.shape))


#: Arguments that are not numbers at all.
NOT_NUMBERS = st.sampled_from(['abc', None, {'x': 1.0}, [[1.0, 2.0], [3.0]], object(),
                               [1 + 2j] * 6, ['0.1'] * 6, [True] * 6, b'bytes', 'nan'])


def wrong_shapes(*good_shapes):
    """Float arrays whose shape is none of ``good_shapes`` (empty ones included)."""
    shapes = st.lists(st.integers(0, 7), min_size=0, max_size=3).map(tuple).filter(
        lambda shape: shape not in good_shapes)
    return shapes.map(lambda shape: np.full(shape, 0.1))


def assert_refused(call, names, error=ValueError):
    """
    Check that ``call()`` raises ``error`` naming one of ``names``, in the package's words.

    :param names: words of which the message must contain at least one (the argument's name).
    """
    with pytest.raises(error) as raised:
        call()
    message = str(raised.value)
    assert any(name in message for name in names), f'{names} not named in: {message}'
    assert not any(words in message for words in NUMPY_WORDS), f"numpy's words: {message}"
    return raised.value


def assert_refusal(decision, codes):
    """Check that a decision (LegCommand, PoseEstimate, ...) is a refusal with one of codes."""
    assert not decision.accepted, decision
    assert decision.refusal.code in codes, decision.refusal
    assert not any(words in decision.reason for words in NUMPY_WORDS), decision.reason


def pose_distance(pose, other):
    """Return the larger of the position distance (m) and rotation angle (rad) of two poses."""
    from reference import rotation_angle, rotation_zyx
    return max(float(np.linalg.norm(np.asarray(pose[:3]) - other[:3])),
               rotation_angle(rotation_zyx(*pose[3:]), rotation_zyx(*other[3:])))
