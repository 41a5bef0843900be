"""The band of text under a page's drawing: the page's columns as blocks of lines, flowed left to right.

Blocks, their flow and the legend's swatches are the title block's (``render.titleblock``); the
lines are typeset here, the course's notation with its sub- and superscripts
(``handout.notation``). Every line is a Text whose role says what it is (``handout equation``,
``handout heading``, ``handout table 2 row 3``), so tests find them.
"""

from __future__ import annotations

from collections.abc import Sequence

from kinepoly.geom.tolerances import PAPER_SAME_MM
from kinepoly.handout.content import Column, Page, Paragraph, Table
from kinepoly.handout.notation import runs_of, text_width, wrap
from kinepoly.present.catalogue import Catalogue
from kinepoly.render.primitives import Item, Text
from kinepoly.render.style import INK, SMALL_MM
from kinepoly.render.text import Run, plain_runs, runs_box
from kinepoly.render.titleblock import Block, block_items, flow, flow_height

__all__ = ["band_height", "band_items"]

_SIZES = {"title": (4.2, True), "heading": (3.1, True), "equation": (3.1, True), "body": (2.6, False),
          "result": (2.6, True), "note": (2.3, False)}
_TABLE_MM = 2.3
_ROWS_MAX = 9
"""A table with more rows is set in side-by-side parts."""
_CELL_GAP_MM = 3.0
_FIT_MAX_MM = 105.0
_FILL_MIN_MM = 45.0
_GAP_MM = 6.0
_PAD_MM = 2.5
_LEAD_MM = 0.6
"""The least gap between the boxes of two lines of the band."""
_LEGEND_ORDER = ("absolute", "relative", "sliding", "normal", "tangential", "coriolis")

Line = tuple[tuple[Run, ...], bool, float]


def _line(runs: tuple[Run, ...], bold: bool, size: float, spacing: float = 1.45) -> Line:
    """A line ``spacing`` times its size high, or higher where its sub- and superscripts need it."""
    _, y0, _, y1 = runs_box(runs, bold)
    return (runs, bold, max(spacing * size, y1 - y0 + _LEAD_MM))


def _baseline(runs: tuple[Run, ...], bold: bool, top: float, height: float) -> float:
    """The baseline that centres the runs' box in a line from ``top`` down ``height``."""
    _, y0, _, y1 = runs_box(runs, bold)
    return top - (height - (y1 - y0)) / 2 - y1


def _paragraph_lines(paragraph: Paragraph, width: float) -> list[tuple[Line, str]]:
    size, bold = _SIZES[paragraph.style]
    out = []
    for k, text in enumerate(wrap(paragraph.text, size, width, bold)):
        out.append((_line(runs_of(text, size, bold), bold, size), f"handout {paragraph.style} line {k}"))
    return out


def _runs_width(runs: tuple[Run, ...], bold: bool) -> float:
    return max(r.dx + text_width(r.text, r.size, bold) for r in runs)


def _is_number(cell: str) -> bool:
    return bool(cell) and (cell[0].isdigit() or cell[0] == "−" and cell[1:2].isdigit())


def _table_lines(table: Table, number: int) -> list[tuple[Line, str]]:
    size = _TABLE_MM
    cells = [[runs_of(cell, size) if cell else () for cell in row] for row in (table.header, *table.rows)]
    columns = len(table.header)
    widths = [max((_runs_width(row[c], k == 0) for k, row in enumerate(cells) if row[c]), default=0.0)
              for c in range(columns)]
    numeric = [c > 0 and all(_is_number(row[c]) for row in table.rows if row[c]) and any(row[c] for row in table.rows)
               for c in range(columns)]
    out: list[tuple[Line, str]] = []
    if table.title:
        out.append((_line(plain_runs(table.title, size), True, size), f"handout table {number} title"))
    for k, row in enumerate(cells):
        runs: list[Run] = []
        x = 0.0
        for c, cell in enumerate(row):
            if cell:
                dx = x + (widths[c] - _runs_width(cell, k == 0) if numeric[c] else 0.0)
                runs += [Run(r.text, r.dx + dx, r.dy, r.size) for r in cell]
            x += widths[c] + _CELL_GAP_MM
        what = "header" if k == 0 else f"row {k - 1}"
        out.append((_line(tuple(runs) or (Run(" ", 0.0, 0.0, size),), k == 0, size, 1.38),
                    f"handout table {number} {what}"))
    return out


def _natural_width(column: Column) -> float:
    """A paragraph wraps at ``_FIT_MAX_MM``; a table cannot, and is as wide as its widest line."""
    widest = tables = 0.0
    for part in column.parts:
        if isinstance(part, Paragraph):
            size, bold = _SIZES[part.style]
            widest = max(widest, _runs_width(runs_of(part.text, size, bold), bold))
        else:
            tables = max(tables, max(_runs_width(runs, bold) for (runs, bold, _), _ in _table_lines(part, 0)))
    return max(min(widest, _FIT_MAX_MM), tables)


def _column_lines(column: Column, width: float, first_table: int) -> list[tuple[Line, str]]:
    lines: list[tuple[Line, str]] = []
    table = first_table
    for part in column.parts:
        if isinstance(part, Paragraph):
            if lines and part.style in ("heading", "result"):
                lines.append((_line((Run(" ", 0.0, 0.0, 1.2),), False, 1.2), "handout space"))
            lines += _paragraph_lines(part, width)
        else:
            if lines:
                lines.append((_line((Run(" ", 0.0, 0.0, 1.2),), False, 1.2), "handout space"))
            lines += _table_lines(part, table)
            table += 1
    return lines


def _split(column: Column) -> list[Column]:
    """A column that is one long table, as several columns of at most ``_ROWS_MAX`` rows each."""
    if column.fill or len(column.parts) != 1 or not isinstance(column.parts[0], Table):
        return [column]
    table = column.parts[0]
    count = -(-len(table.rows) // _ROWS_MAX)
    if count <= 1:
        return [column]
    per = -(-len(table.rows) // count)
    return [Column((Table(table.title if k == 0 else " ", table.header, table.rows[k * per:(k + 1) * per]),))
            for k in range(count)]


def _legend(kinds: Sequence[str], say: Catalogue) -> Block:
    lines: list[Line] = [_line(plain_runs(say.say("legend.title"), SMALL_MM * 1.1), True, SMALL_MM * 1.1)]
    for kind in kinds:
        lines.append(_line((Run(say.say(f"legend.{kind}"), 7.0, 0.0, SMALL_MM * 1.1),), False, SMALL_MM * 1.1))
    width = max(_runs_width(runs, bold) for runs, bold, _ in lines)
    return Block(tuple(lines), width, sum(h for _, _, h in lines))


def _blocks(page: Page, width: float, kinds: Sequence[str], say: Catalogue) -> list[tuple[Block, list[str], bool]]:
    """The page's columns as blocks (with each line's role), widths decided: fits first, fills share the rest."""
    kinds = [k for k in _LEGEND_ORDER if k in kinds]
    shown = [part for c in page.columns if c.parts or (c.legend and kinds) for part in _split(c)]
    fits = {id(c): _natural_width(c) for c in shown if not c.fill and not c.legend}
    legend = _legend(kinds, say) if kinds else None
    taken = sum(fits.values()) + (legend.width if legend and any(c.legend for c in shown) else 0.0)
    fills = [c for c in shown if c.fill]
    spare = width - taken - _GAP_MM * (len(shown) - 1)
    fill_width = max(spare / len(fills) - PAPER_SAME_MM, _FILL_MIN_MM) if fills else 0.0
    out: list[tuple[Block, list[str], bool]] = []
    tables = 0
    for column in shown:
        if column.legend:
            assert legend is not None
            out.append((legend, ["handout legend"] * len(legend.lines), True))
            continue
        column_width = fill_width if column.fill else fits[id(column)]
        lines = _column_lines(column, column_width, tables)
        tables += sum(1 for part in column.parts if isinstance(part, Table))
        out.append((Block(tuple(line for line, _ in lines), column_width, sum(line[2] for line, _ in lines)),
                    [role for _, role in lines], False))
    return out


def band_height(page: Page, width: float, kinds: Sequence[str], say: Catalogue) -> float:
    """The height the page's text needs in a band ``width`` mm wide."""
    blocks = [block for block, _, _ in _blocks(page, width, kinds, say)]
    return flow_height(blocks, width) if blocks else 0.0


def band_items(page: Page, rect: tuple[float, float, float, float], kinds: Sequence[str],
               say: Catalogue) -> list[Item]:
    """The page's text laid out in ``rect`` (x0, y0, x1, y1), from its top left."""
    x0, _, x1, y1 = rect
    width = x1 - x0
    blocks = _blocks(page, width, kinds, say)
    items: list[Item] = []
    for (block, (bx, by)), (_, roles, is_legend) in zip(flow([b for b, _, _ in blocks], width), blocks, strict=True):
        top = (x0 + bx, y1 - _PAD_MM + by)
        if is_legend:
            items += block_items(block, top, "handout legend", [k for k in _LEGEND_ORDER if k in kinds])
            continue
        y = top[1]
        for (runs, bold, h), role in zip(block.lines, roles, strict=True):
            baseline = _baseline(runs, bold, y, h)
            if role != "handout space":
                items.append(Text(top[0], baseline, runs, INK, role, None, bold))
            y -= h
    return items

