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
The documentation's benchmark tables are the benchmark's own output, with every target it defines.

No benchmark runs here: benchmarks/run_benchmarks.py writes benchmarks/results.md,
scripts/update_doc_tables.py copies its blocks into doc/benchmarks.md, and these tests check that
chain and that no target row can be dropped, so a missed target stays in the documentation. The
README's headline accuracy claim is checked against the results too.
"""

import importlib.util
from pathlib import Path
import re

import pytest

pytestmark = pytest.mark.core

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / 'README.md').read_text(encoding='utf-8')
#: The page that shows the benchmark's tables.
PAGE = (ROOT / 'doc' / 'benchmarks.md').read_text(encoding='utf-8')
RESULTS = (ROOT / 'benchmarks' / 'results.md').read_text(encoding='utf-8')
BLOCKS = ('machine', 'results', 'targets')


def load_script(relative_path):
    """Import a script of the repository (not a package) as a module."""
    path = ROOT / relative_path
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope='module')
def benchmark():
    """benchmarks/run_benchmarks.py, imported (nothing runs)."""
    return load_script('benchmarks/run_benchmarks.py')


@pytest.fixture(scope='module')
def updater():
    """scripts/update_doc_tables.py, imported."""
    return load_script('scripts/update_doc_tables.py')


def target_names(markdown):
    """Target names of the targets table in ``markdown``, in order."""
    return re.findall(r'^\| (?!Target \|)(?!---)(.+?) \| (?:yes|\*\*no\*\*) \|', markdown,
                      re.MULTILINE)


def test_doc_benchmark_blocks_are_the_latest_results(updater):
    """Every benchmark block of doc/benchmarks.md is the one benchmarks/results.md holds."""
    page_blocks = updater.benchmark_blocks(PAGE)
    results_blocks = updater.benchmark_blocks(RESULTS)
    assert sorted(page_blocks) == sorted(BLOCKS) == sorted(results_blocks)
    for name in BLOCKS:
        assert page_blocks[name] == results_blocks[name], (
            f'doc/benchmarks.md block {name!r} differs from benchmarks/results.md: run '
            '.venv/bin/python scripts/update_doc_tables.py')
    assert updater.render(PAGE, RESULTS) == updater.render(PAGE)
    assert updater.BENCHMARK_PAGE == ROOT / 'doc' / 'benchmarks.md'


def test_doc_target_rows_are_exactly_the_benchmark_targets(benchmark, updater):
    """The docs' target table lists every target of TARGETS, in order, none dropped."""
    targets = updater.benchmark_blocks(PAGE)['targets']
    rows = [line for line in targets.splitlines()[2:] if line.strip()]
    names = target_names(targets)
    missing = [name for name in benchmark.TARGETS if name not in names]
    extra = [name for name in names if name not in benchmark.TARGETS]
    assert not missing and not extra, f'missing target rows: {missing}; unknown: {extra}'
    assert names == list(benchmark.TARGETS)
    assert len(rows) == len(benchmark.TARGETS), 'a target row without a yes/**no** verdict'


def test_a_target_never_measured_is_printed_as_not_met(benchmark):
    """A run that skips a target (no nodes, no peer) still prints its row, as not met."""
    table = benchmark.Table(rounds=3)
    table.target(benchmark.TARGETS[0], True, '12.0x (11.0-13.0)')
    printed = table.targets_markdown()
    assert target_names(printed) == list(benchmark.TARGETS)
    for name in benchmark.TARGETS[1:]:
        assert f'| {name} | **no** | not measured in this run |' in printed
    with pytest.raises(KeyError):
        table.target('a target nobody defined', True, '')


def test_series_reports_median_and_range(benchmark):
    """A ratio over three rounds reads as its median with the lowest and highest value."""
    series = benchmark.Series([1.9, 2.4, 2.1])
    assert series.median == 2.1
    assert series.text('.2f') == '2.10x (1.90-2.40)'


def test_accuracy_claim_covers_the_measured_error():
    """The README's FK pose accuracy is no better than the benchmark's worst measured error."""
    claim = re.search(r'poses within about ([0-9.e+-]+) m and rad', README)
    assert claim, 'the FK accuracy claim ("poses within about ... m and rad") is missing'
    worst = [float(error) for error in re.findall(
        r'^\| FK [^|]+ \| stewart_kinematics[^|]* \|[^|]+\|[^|]+\|[^|]+\| ([0-9.e+-]+) \|$',
        RESULTS, re.MULTILINE)]
    assert len(worst) >= 3, 'no FK error of ours found in benchmarks/results.md'
    assert max(worst) <= float(claim.group(1))
