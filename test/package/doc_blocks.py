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
The code blocks of the documentation's pages, and the commands in them, for the tests.

A page's fenced blocks are read from its Markdown source; a ``bash`` block right after a line
``% runnable: ...`` (a MyST comment, not shown on the site) is marked runnable
(doc/documentation.md). A command is one logical line of a block: continuation lines joined,
a trailing ``&`` and comments dropped, split as the shell splits words.
"""

from dataclasses import dataclass
from pathlib import Path
import re
import shlex
from typing import List, Tuple

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / 'doc'
HOW_TO = DOC / 'how-to'
#: The marker of a runnable block: a MyST comment line right before its fence.
RUNNABLE = '% runnable'


@dataclass(frozen=True)
class Block:
    """
    One fenced code block of a page.

    :param page: the page, relative to doc/.
    :param language: the fence's language (``bash``, ``yaml``, ...).
    :param text: the block's text.
    :param runnable: True when a ``% runnable`` line comes right before the fence.
    """

    page: str
    language: str
    text: str
    runnable: bool


def blocks(page: Path, language: str = '') -> List[Block]:
    """Return the fenced blocks of a page (of one language, or all), in order."""
    lines = page.read_text(encoding='utf-8').splitlines()
    found, index = [], 0
    while index < len(lines):
        opening = re.match(r'^(`{3,})(\S*)', lines[index])
        if not opening:
            index += 1
            continue
        fence, info = opening.groups()
        end = next((later for later in range(index + 1, len(lines))
                    if lines[later].strip() == fence), None)
        assert end is not None, f'{page}: line {index + 1}: a fence that is never closed'
        if not language or info == language:
            found.append(Block(str(page.relative_to(DOC)), info,
                               '\n'.join(lines[index + 1:end]) + '\n',
                               index > 0 and lines[index - 1].startswith(RUNNABLE)))
        index = end + 1
    return found


def how_to_pages() -> List[Path]:
    """Every page of doc/how-to/."""
    return sorted(HOW_TO.glob('*.md'))


def commands(block: Block) -> List[Tuple[str, ...]]:
    """
    Return the commands of a shell block, each as its words.

    Continuation lines are joined; a trailing ``&``, a ``$`` prompt and comments are dropped;
    a line that is not a whole command (the inside of a quoted multi-line argument) is read
    with the command it belongs to.
    """
    text = block.text.replace('\\\n', ' ')
    found, pending = [], ''
    for line in text.splitlines():
        pending = f'{pending}\n{line}' if pending else line
        try:
            words = shlex.split(pending, comments=True)
        except ValueError:              # an open quote: the command goes on
            continue
        pending = ''
        if words and words[0] == '$':
            words = words[1:]
        while words and words[-1] == '&':
            words = words[:-1]
        if words:
            found.append(tuple(words))
    assert not pending, f'{block.page}: unclosed quote in a {block.language} block'
    return found


def options(words, flag: str) -> List[str]:
    """Return the values given to ``flag`` (such as ``-p``) in a command's words."""
    return [words[index + 1] for index, word in enumerate(words[:-1]) if word == flag]
