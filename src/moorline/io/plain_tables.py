"""The summary's blocks (:mod:`moorline.io.summary_render`) as plain text, without rich.

The layout is rich's, character for character, for what a summary holds: a paragraph is
wrapped at the width as rich wraps words (a word longer than the width cut into pieces); a
table has rich's default box (``HEAVY_HEAD``), one space of padding, each column as wide as
its widest cell or header, its title centred over it (wrapped to the table's width). What
rich lays out otherwise is left to rich: :func:`plain_text` returns ``None`` for a table
wider than the width (rich shrinks its columns), and for text that is not printable ASCII or
holds ``:name:`` (rich measures wide characters, replaces emoji codes). Importing rich costs
about 20 ms and rendering a run's tables through it about 30 ms, twice (``summary.txt`` and
stdout): the command line pays neither unless it prints to a terminal.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from .summary_render import Block, Grid, Para

__all__ = ["plain_text", "wrap"]

_WORD = re.compile(r"\s*\S+\s*")
_TRAILING = re.compile(r"\s+$")
_EMOJI = re.compile(r":\S*?:")
_PRINTABLE = re.compile(r"[ -~\n]*")


def plain_text(blocks: Iterable[Block], width: int) -> str | None:
    """The blocks laid out as rich's console would at ``width`` columns, with no styles;
    ``None`` when that layout needs rich (see the module docstring)."""
    out: list[str] = []
    for block in blocks:
        lines = _table(block, width) if isinstance(block, Grid) else _paragraph(block, width)
        if lines is None:
            return None
        out.extend(line + "\n" for line in lines)
    return "".join(out)


def _plain(text: str) -> bool:
    """Whether rich prints ``text`` as it is (printable ASCII, no emoji code)."""
    return _PRINTABLE.fullmatch(text) is not None and _EMOJI.search(text) is None


def wrap(text: str, width: int) -> list[str]:
    """``text`` wrapped as rich wraps a paragraph (``overflow="fold"``): each line of it cut
    at word starts so that no line is wider than ``width``, a word longer than ``width`` cut
    into pieces; whitespace at a line's end kept as far as it fits."""
    out: list[str] = []
    for line in text.split("\n"):
        breaks, offset = [], 0
        for match in _WORD.finditer(line):
            start, word = match.start(), match.group(0)
            size = len(word.rstrip())
            if width - offset >= size:
                offset += len(word)
            elif size > width:
                pieces = [word[k:k + width] for k in range(0, len(word), width)]
                for k, piece in enumerate(pieces):
                    if start:
                        breaks.append(start)
                    if k == len(pieces) - 1:
                        offset = len(piece)
                    else:
                        start += len(piece)
            elif offset and start:
                breaks.append(start)
                offset = len(word)
        cuts = [0, *breaks, len(line)]
        for a, b in zip(cuts[:-1], cuts[1:], strict=True):
            out.append(_strip_end(line[a:b], width))
    return out


def _strip_end(line: str, width: int) -> str:
    """Trailing whitespace dropped as far as the line is wider than ``width``."""
    excess = len(line) - width
    space = _TRAILING.search(line)
    if excess > 0 and space is not None:
        return line[:len(line) - min(len(space.group(0)), excess)]
    return line


def _paragraph(block: Para, width: int) -> list[str] | None:
    return wrap(block.text, width) if _plain(block.text) else None


def _table(grid: Grid, width: int) -> list[str] | None:
    """rich's ``Table`` with its defaults (``box.HEAVY_HEAD``, padding 0 1)."""
    cells = [[name for name, _ in grid.columns], *grid.rows]
    if not all(_plain(c) for row in cells for c in row) or not _plain(grid.title):
        return None
    n = len(grid.columns)
    widths = [2 + max((len(line) for row in cells for line in row[k].split("\n")), default=0)
              for k in range(n)]
    if sum(widths) > width - (n + 1):
        return None
    total = sum(widths) + n + 1
    out = [_centre(line, total) for line in wrap(grid.title, total)] if grid.title else []
    out.append(_rule("┏", "━", "┳", "┓", widths))
    out.extend(_row(cells[0], grid, widths, "┃"))
    out.append(_rule("┡", "━", "╇", "┩", widths))
    for row in cells[1:]:
        out.extend(_row(row, grid, widths, "│"))
    out.append(_rule("└", "─", "┴", "┘", widths))
    return out


def _centre(line: str, width: int) -> str:
    line = line.rstrip()
    left = (width - len(line)) // 2
    return " " * left + line + " " * (width - len(line) - left)


def _rule(left: str, fill: str, cross: str, right: str, widths: list[int]) -> str:
    return left + cross.join(fill * w for w in widths) + right


def _row(row: list[str], grid: Grid, widths: list[int], bar: str) -> list[str]:
    """The lines of one table row (a cell of several lines makes the row as tall)."""
    parts = [cell.split("\n") for cell in row]
    height = max(len(p) for p in parts)
    lines = []
    for i in range(height):
        fields = []
        for (_, justify), part, w in zip(grid.columns, parts, widths, strict=True):
            text = part[i] if i < len(part) else ""
            inner = w - 2
            fields.append(" " + (text.rstrip().rjust(inner) if justify == "right"
                                 else text.ljust(inner)) + " ")
        lines.append(bar + bar.join(fields) + bar)
    return lines
