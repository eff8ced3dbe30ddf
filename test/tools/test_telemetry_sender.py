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

"""``telemetry_sender``'s options, through its ``main()``: a bad one exits 2 naming it."""

import pytest
from stewart_kinematics.tools.telemetry_sender import main

pytestmark = pytest.mark.core


@pytest.mark.parametrize('arguments, fragment', [
    (['--port', '70000'], 'argument --port: must be at most 65535, got 70000'),
    (['--port', '0'], 'argument --port: must be at least 1'),
    (['--rate', 'nan'], 'argument --rate: must be finite'),
    (['--speed', '1e308'], 'argument --speed: must be in [0.01, 1000]'),
    (['--duration', '-1'], 'argument --duration: must be positive'),
    (['--loops', '1e9'], 'argument --loops: must be an integer'),
    (['--scenario', 'drift'], 'argument --scenario: invalid choice'),
])
def test_bad_options_exit_2_naming_the_option(capsys, arguments, fragment):
    """Refused before a packet is sent, in argparse's words for every option."""
    with pytest.raises(SystemExit) as raised:
        main(arguments)
    assert raised.value.code == 2
    assert fragment in capsys.readouterr().err


def test_an_address_that_does_not_resolve_exits_1_naming_it(capsys):
    """No traceback: the address and the resolver's reason, in one line."""
    assert main(['--address', 'nohost.invalid', '--duration', '0.02']) == 1
    assert capsys.readouterr().err.startswith(
        'telemetry_sender: cannot send to nohost.invalid:47800: ')
