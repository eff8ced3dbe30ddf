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
Shared fixtures; every test session runs on a private ROS domain, on this machine only.

``pytest_configure`` sets ``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``, a ``ROS_LOG_DIR`` and a
reserved free ``ROS_DOMAIN_ID`` before any test starts rclpy, so neither in-process nodes nor
the node processes the tests start can reach the network or another run.

The executor: ``STEWART_EXECUTOR`` (``events``, the default, or ``single_threaded``) chooses
it for the whole session, as it does for a user's nodes: the node processes inherit it, and
the in-process tests spin on ``create_executor()``, which reads it. So the one suite runs on
either executor (``STEWART_EXECUTOR=single_threaded scripts/run_tests.sh``); the session's
header says which, and an unknown name stops the session before any test.

The multi-process tests share ``start_node`` (console scripts as child processes, stopped at the
end of the test) and ``client`` (the test's own rclpy node, with waits that fail with the
nodes' output: :class:`helpers.TopicClient`). What tests build alike beyond fixtures
(messages, stopping a node cleanly, recording topics) is in test/helpers.py.
"""

import contextlib
import io
from pathlib import Path
import time
from types import SimpleNamespace
from unittest import mock

from helpers import DEADLINE, TopicClient
import pytest

from stewart_kinematics.ros.node_main import create_executor, executor_name
from stewart_kinematics.tools.node_processes import isolated_ros_environment, NodeProcess

CONFIG_DIRECTORY = Path(__file__).resolve().parent.parent / 'config'
#: The test tiers of pytest.ini: each test carries exactly one.
TIERS = ('core', 'node', 'process', 'lint')

_environment = contextlib.ExitStack()


def pytest_configure(config):
    """Isolate ROS before any test runs; refuse an unknown STEWART_EXECUTOR."""
    try:
        executor_name()
    except ValueError as error:
        raise pytest.UsageError(str(error))
    _environment.enter_context(isolated_ros_environment())


def pytest_report_header(config):
    """Say which executor the nodes of this session spin on."""
    return f'executor: {executor_name()} (STEWART_EXECUTOR)'


def pytest_collection_modifyitems(config, items):
    """Refuse a test without exactly one tier marker: `pytest -m core` must mean what it says."""
    wrong = []
    for item in items:
        tiers = {marker.name for marker in item.iter_markers() if marker.name in TIERS}
        if len(tiers) != 1:
            wrong.append(f'{item.nodeid}: {sorted(tiers) or "no tier"}')
    if wrong:
        raise pytest.UsageError(
            f'every test needs exactly one tier marker of {TIERS} (pytestmark = '
            'pytest.mark.<tier> in its module):\n' + '\n'.join(wrong))


#: The failed first attempts of tests run again (``--reruns``, scripts/run_tests.sh), kept to
#: show why: the summary names a rerun test, not its failure.
_first_attempts = []


def pytest_runtest_logreport(report):
    """Keep the failure of a test that is to run again (pytest-rerunfailures' ``rerun``)."""
    if report.outcome == 'rerun':
        _first_attempts.append((report.nodeid, report.when, report.longreprtext))


def pytest_terminal_summary(terminalreporter):
    """Show why each rerun test failed the first time (its last lines), for a flake to mend."""
    if not _first_attempts:
        return
    terminalreporter.section('first attempts of the tests run again')
    for nodeid, when, text in _first_attempts:
        lines = text.splitlines()
        terminalreporter.write_line(f'{nodeid} ({when}):')
        for line in lines[-25:]:
            terminalreporter.write_line(f'    {line}')


def pytest_unconfigure(config):
    """Release the reserved domain."""
    _environment.close()


@pytest.fixture
def config_directory():
    """Return the package's config/ folder."""
    return CONFIG_DIRECTORY


@pytest.fixture
def ros():
    """Initialise rclpy for one test and shut it down afterwards."""
    import rclpy
    rclpy.init(args=[])
    yield rclpy
    rclpy.try_shutdown()


@pytest.fixture
def spin_until():
    """
    Provide a function that spins an executor until a condition holds.

    ``spin_until(executor, condition, timeout=DEADLINE) -> bool`` spins ``executor`` until
    ``condition()`` holds or ``timeout`` seconds pass, and returns whether the condition holds:
    tests wait for data with a deadline, never a fixed sleep.
    """
    def spin(executor, condition, timeout=DEADLINE):
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline:
                return False
            executor.spin_once(timeout_sec=0.05)
        return True
    return spin


@pytest.fixture
def client(ros, spin_until):
    """Create a TopicClient with a fresh node on the session's private domain."""
    node = ros.create_node('stewart_test_client')
    executor = create_executor()
    executor.add_node(node)
    yield TopicClient(node, executor, spin_until)
    executor.shutdown()
    node.destroy_node()


@pytest.fixture
def start_node():
    """
    Provide a function that starts a console script with arguments as a NodeProcess.

    ``start(executable, arguments=(), env=None)``: ``executable`` is a console script's name or
    a path; ``env`` replaces the environment. Every process started is stopped (SIGINT, then
    kill) when the test ends, pass or fail.
    """
    with contextlib.ExitStack() as stack:
        def start(executable, arguments=(), env=None):
            return stack.enter_context(NodeProcess(executable, list(arguments), env))
        yield start


@pytest.fixture(scope='session')
def shipped_cueing_report(tmp_path_factory):
    """
    Run ``stewart_cueing --strict`` once a session: the first four scenarios, shipped tuning.

    Their replay is the longest computation of the core tier, and two modules judge it:
    test/tools/test_cueing_report.py the tool's exit code, output and figures, and
    test/cueing/test_evaluation.py the evaluations the tool computed with the core's ``replay``
    and ``evaluate`` (the same calls on the same files as a direct computation).

    :returns: a namespace of ``exit_code``, ``output`` (stdout), ``folder`` (the outputs) and
        ``evaluations`` (scenario name -> CueEvaluation).
    """
    from stewart_kinematics.tools import cueing_report
    folder = tmp_path_factory.mktemp('cueing_report') / 'out'
    runs = []
    run = cueing_report.run

    def recorded_run(options, stream=None):
        runs.append(run(options, stream))
        return runs[-1]

    arguments = []
    for name in ('paper_platform.yaml', 'example_limits.yaml', 'motion_cueing.yaml'):
        arguments += ['--params-file', str(CONFIG_DIRECTORY / name)]
    with mock.patch.object(cueing_report, 'run', recorded_run), \
            contextlib.redirect_stdout(io.StringIO()) as output:
        code = cueing_report.main(arguments + ['--output', str(folder), '--quiet', '--strict']
                                  + [word for name in ('acceleration_braking', 'slalom',
                                                       'multi_sine', 'lap')
                                     for word in ('--scenario', name)])
    [(results, _)] = runs
    return SimpleNamespace(exit_code=code, output=output.getvalue(), folder=folder,
                           evaluations=dict(results))
