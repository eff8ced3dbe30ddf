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
The documentation's parameter tables, rendered from the parameter specs.

doc/nodes.md shows them, rendered when the site is built, so they cannot drift from the code.
"""

import math


def markdown_table(specs) -> str:
    """
    Render the documentation's table of ``specs``: name, type, default, meaning, allowed values.

    The documentation renders its tables with this when it is built (``{parameter-table}`` in
    doc/nodes.md), so they cannot drift from the code.
    """
    def shown(value):
        if value is None:
            return 'required'
        if isinstance(value, float) and math.isinf(value):
            return '`.inf`' if value > 0 else '`-.inf`'
        if isinstance(value, str):
            return f"`'{value}'`"
        if isinstance(value, bool):
            return f'`{str(value).lower()}`'
        return f'`{value}`'

    lines = ['| Parameter | Type | Default | Meaning | Allowed | Run-time change |',
             '| --- | --- | --- | --- | --- | --- |']
    for spec in specs:
        lines.append(
            f'| `{spec.name}` | {spec.value_type} | {shown(spec.default)} | {spec.description} | '
            f'{spec.constraints or "any"} | {"no (read-only)" if spec.read_only else "yes"} |')
    return '\n'.join(lines)
