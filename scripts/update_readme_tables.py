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
Rewrite the parameter tables of README.md from the parameter specs.

Each table sits between ``<!-- parameters: GROUP -->`` and ``<!-- end parameters -->``, where
GROUP names a tuple of :mod:`stewart_kinematics.parameter_spec` (``GEOMETRY``, ``SOLVER``,
``QUEUE``, ``RAMP``). Run after changing a parameter: ``.venv/bin/python
scripts/update_readme_tables.py``; test/test_readme.py fails until the README matches.
"""

from pathlib import Path
import re
import sys

from stewart_kinematics import parameter_spec

README = Path(__file__).resolve().parent.parent / 'README.md'
# The table between the markers may be empty (a new group): `.*?` then matches nothing.
TABLE = re.compile(r'(<!-- parameters: (\w+) -->\n)(?:.*?\n)??(<!-- end parameters -->)',
                   re.DOTALL)


def render(text: str) -> str:
    """Return ``text`` with every marked table regenerated."""
    def table(match):
        specs = getattr(parameter_spec, f'{match.group(2)}_PARAMETERS')
        return match.group(1) + parameter_spec.markdown_table(specs) + '\n' + match.group(3)
    return TABLE.sub(table, text)


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
