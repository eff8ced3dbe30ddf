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
Rewrite the generated tables of README.md: parameters from the specs, benchmarks from results.

Each parameter table sits between ``<!-- parameters: GROUP -->`` and
``<!-- end parameters -->``, where GROUP names a tuple of
:mod:`stewart_kinematics.parameters` (``GEOMETRY``, ``SOLVER``, ``QUEUE``, ``RAMP``). Each
benchmark block sits between ``<!-- benchmark: NAME -->`` and ``<!-- end benchmark -->`` (NAME:
``machine``, ``results``, ``targets``) and is copied from the same block of
``benchmarks/results.md``, which benchmarks/run_benchmarks.py writes.

Run after changing a parameter or benchmarking: ``.venv/bin/python
scripts/update_readme_tables.py`` (``scripts/run_benchmarks.sh --update-readme`` runs it after
the benchmark); test/test_readme.py and test/test_benchmark_tables.py fail until the README
matches.
"""

from pathlib import Path
import re
import sys

from stewart_kinematics import parameters

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / 'README.md'
BENCHMARK_RESULTS = ROOT / 'benchmarks' / 'results.md'
# The table between the markers may be empty (a new group): `.*?` then matches nothing.
TABLE = re.compile(r'(<!-- parameters: (\w+) -->\n)(?:.*?\n)??(<!-- end parameters -->)',
                   re.DOTALL)

BENCHMARK = re.compile(r'(<!-- benchmark: (\w+) -->\n)(?:.*?\n)??(<!-- end benchmark -->)',
                       re.DOTALL)


def benchmark_blocks(text: str) -> dict:
    """Return ``{name: content}`` of every benchmark block of ``text`` (without markers)."""
    return {match.group(2): match.group(0)[len(match.group(1)):-len(match.group(3))]
            for match in BENCHMARK.finditer(text)}


def render(text: str, results: str = None) -> str:
    """Return ``text`` with every marked table regenerated (benchmarks from ``results``)."""
    def table(match):
        specs = getattr(parameters, f'{match.group(2)}_PARAMETERS')
        return match.group(1) + parameters.markdown_table(specs) + '\n' + match.group(3)

    if results is None:
        results = BENCHMARK_RESULTS.read_text(encoding='utf-8')
    blocks = benchmark_blocks(results)

    def benchmark(match):
        if match.group(2) not in blocks:
            raise KeyError(f'{BENCHMARK_RESULTS} has no block {match.group(2)!r}')
        return match.group(1) + blocks[match.group(2)] + match.group(3)

    return BENCHMARK.sub(benchmark, TABLE.sub(table, text))


def main() -> int:
    """Rewrite README.md in place; say whether it changed."""
    text = README.read_text(encoding='utf-8')
    updated = render(text)
    if updated != text:
        README.write_text(updated, encoding='utf-8')
    print('README.md ' + ('updated' if updated != text else 'already up to date'))
    return 0


if __name__ == '__main__':
    sys.exit(main())
