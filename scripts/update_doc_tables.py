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
Copy the benchmark tables of benchmarks/results.md into the documentation's pages.

Each benchmark block of a page in ``doc/`` sits between ``<!-- benchmark: NAME -->`` and
``<!-- end benchmark -->`` (NAME: ``machine``, ``results``, ``targets``, in doc/benchmarks.md)
and is copied from the same block of ``benchmarks/results.md``, which
benchmarks/run_benchmarks.py writes. (The parameter tables and the table of refusal codes are
generated from the code when the documentation is built: nothing to copy for them.)

Run after benchmarking: ``.venv/bin/python scripts/update_doc_tables.py``
(``scripts/run_benchmarks.sh --update-docs`` runs it after the benchmark);
test/package/test_benchmark_tables.py fails until the pages match.
"""

from pathlib import Path
import re
import sys

ROOT = Path(__file__).resolve().parent.parent
DOC = ROOT / 'doc'
#: The page that shows the benchmark blocks.
BENCHMARK_PAGE = DOC / 'benchmarks.md'
BENCHMARK_RESULTS = ROOT / 'benchmarks' / 'results.md'

BENCHMARK = re.compile(r'(<!-- benchmark: (\w+) -->\n)(?:.*?\n)??(<!-- end benchmark -->)',
                       re.DOTALL)


def benchmark_blocks(text: str) -> dict:
    """Return ``{name: content}`` of every benchmark block of ``text`` (without markers)."""
    return {match.group(2): match.group(0)[len(match.group(1)):-len(match.group(3))]
            for match in BENCHMARK.finditer(text)}


def render(text: str, results: str = None) -> str:
    """Return ``text`` with every benchmark block replaced by that of ``results``."""
    if results is None:
        results = BENCHMARK_RESULTS.read_text(encoding='utf-8')
    blocks = benchmark_blocks(results)

    def benchmark(match):
        if match.group(2) not in blocks:
            raise KeyError(f'{BENCHMARK_RESULTS} has no block {match.group(2)!r}')
        return match.group(1) + blocks[match.group(2)] + match.group(3)

    return BENCHMARK.sub(benchmark, text)


def main() -> int:
    """Rewrite every page of doc/ that holds a benchmark block; say which changed."""
    for page in sorted(DOC.glob('*.md')):
        text = page.read_text(encoding='utf-8')
        if not BENCHMARK.search(text):
            continue
        updated = render(text)
        if updated != text:
            page.write_text(updated, encoding='utf-8')
        state = 'updated' if updated != text else 'already up to date'
        print(f'{page.relative_to(ROOT)} {state}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
