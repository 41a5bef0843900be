"""The title block (title, input, tables of the asked results, cross-check), panel headings, scale bars.

Blocks of text are measured with the font's widths and flowed left to right, wrapping to a new
row when the page is too narrow, so the block's height follows from its content.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from msgspec import Struct

from kinepoly.geom.tolerances import LOUD_ERROR, NOISE_REL
from kinepoly.present.clean import format_number
from kinepoly.render.layout import HEADING_MM, Panel, round_step
from kinepoly.render.primitives import Item, Path, Stroke, Text
from kinepoly.render.style import SMALL_MM, TERM_COLORS, TERM_NAMES, THIN, TITLE_MM
from kinepoly.render.text import DESCENT_EM, Run, plain_runs, point_runs, text_width, wrap
from kinepoly.solution import Solution

__all__ = ["STEP_TEXT_MM", "Block", "block_items", "fitted_runs", "flow", "flow_height", "heading_items",
           "legend_block", "space_scale_text", "step_block", "title_blocks"]

Point = tuple[float, float]
_GAP_MM = 6.0
_PAD_MM = 2.5
_UNIT_MM = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}


class Block(Struct, frozen=True):
    """Lines of text (each a tuple of runs) in one column of the title block; ``items`` drawn extra."""

    lines: tuple[tuple[tuple[Run, ...], bool, float], ...]
    width: float
    height: float


def _line_height(runs: tuple[Run, ...]) -> float:
    return 1.45 * max(r.size for r in runs)


def _block(lines: Sequence[tuple[tuple[Run, ...], bool]], width: float | None = None) -> Block:
    out = []
    widest = 0.0
    for runs, bold in lines:
        w = max(r.dx + text_width(r.text, r.size, bold) for r in runs)
        widest = max(widest, w)
        out.append((runs, bold, _line_height(runs)))
    return Block(tuple(out), width if width is not None else widest, sum(h for _, _, h in out))


def _numbers(rows: Sequence[Sequence[str | float | None]]) -> list[list[str]]:
    """Format each column; a value below 1e-9 of its column's largest is rounding noise and shows as 0."""
    columns = list(zip(*rows, strict=True))
    out_columns: list[list[str]] = []
    for column in columns:
        numbers = [abs(v) for v in column if isinstance(v, float)]
        top = max(numbers, default=0.0)
        out_columns.append([v if isinstance(v, str) else "" if v is None else
                            format_number(0.0 if abs(v) <= NOISE_REL * top else v) for v in column])
    return [list(row) for row in zip(*out_columns, strict=True)]


def _table(header: Sequence[str], raw_rows: Sequence[Sequence[str | float | None]], title: str) -> Block:
    """A table as lines of runs: the first column left-aligned, the numbers right-aligned; empty columns go."""
    size = SMALL_MM
    rows = _numbers(raw_rows)
    keep = [c for c in range(len(header)) if c == 0 or any(r[c] for r in rows)]
    header = [header[c] for c in keep]
    rows = [[r[c] for c in keep] for r in rows]
    widths = [max(text_width(r[c], size) for r in [header, *rows]) for c in range(len(header))]
    lines: list[tuple[tuple[Run, ...], bool]] = [(plain_runs(title, size), True)]
    for k, row in enumerate([header, *rows]):
        runs: list[Run] = []
        x = 0.0
        for c, cell in enumerate(row):
            if cell:
                dx = x if c == 0 else x + widths[c] - text_width(cell, size)
                runs.extend(Run(r.text, r.dx + dx, r.dy, r.size) for r in
                            (point_runs(cell, size) if c == 0 and k > 0 else plain_runs(cell, size)))
            x += widths[c] + 2.6
        if not runs:
            runs = [Run(" ", 0.0, 0.0, size)]
        lines.append((tuple(runs), False))
    return _block(lines)


def _check_words(solution: Solution, err: float) -> str:
    """The cross-check for people: within the error estimate, the power of ten above the estimate
    (the error's own digits are rounding noise that changes with the machine's arithmetic); beyond
    it, the error itself."""
    verdict = "agrees" if err <= LOUD_ERROR else "DISAGREES"
    estimate = max(solution.accuracy.estimated.values(), default=0.0) if solution.accuracy else 0.0
    if 0.0 < estimate and err <= estimate:
        bound = 10.0 ** math.ceil(math.log10(estimate))
        return f"largest relative error below {bound:.0e}, within its estimate ({verdict})"
    return f"largest relative error {'0' if err == 0.0 else format(err, '.1e')} ({verdict})"


def _unit_text(solution: Solution) -> tuple[str, str, str]:
    u = solution.scene.units.length
    return u, f"{u}/s", f"{u}/s²"


def _angle_of(v: Sequence[float]) -> str | float | None:
    """Direction of a vector in degrees; none for the zero vector."""
    if math.hypot(v[0], v[1]) == 0.0:
        return None
    return format_number(math.degrees(math.atan2(v[1], v[0])))


def title_blocks(solution: Solution, notes: Sequence[str], width: float,
                 data: dict[str, Any] | None = None) -> list[Block]:
    """The title block's columns: title and input, the tables of asked results, notes and legend.

    ``data`` is ``present.report.readable_json(solution)`` when the caller has it already.
    """
    from kinepoly.present.report import input_text, readable_json

    data = data if data is not None else readable_json(solution)  # values below their error estimate are 0
    u, uv, ua = _unit_text(solution)
    au = "°" if solution.scene.units.angle == "deg" else "rad"
    left_w = min(width * 0.42, 110.0)
    head: list[tuple[tuple[Run, ...], bool]] = []
    for line in wrap(solution.scene.title, TITLE_MM, left_w, bold=True):
        head.append((plain_runs(line, TITLE_MM), True))
    text = readable(input_text(solution).replace("s_ddot", "s̈").replace("s_dot", "ṡ"))
    head += [(plain_runs(line, SMALL_MM), False) for line in wrap("input: " + text, SMALL_MM, left_w)]
    check = "cross-check against the analytic solution: " + _check_words(solution, data["check"]["max_rel_error"])
    head += [(plain_runs(line, SMALL_MM), False) for line in wrap(check, SMALL_MM, left_w)]
    for note in notes:
        head += [(plain_runs(line, SMALL_MM), False) for line in wrap(note, SMALL_MM, left_w)]
    blocks = [_block(head, left_w)]
    if "links" in data:
        rows: list[list[str | float | None]] = [
            [f"link {name} ({v['line']['name']})" if "line" in v else f"link {name}",
             v["line"]["angle"] if "line" in v else v["angle"], v.get("omega"), v.get("alpha")]
            for name, v in data["links"].items()]
        blocks.append(_table(["", f"θ ({au})", "ω (rad/s)", "α (rad/s²)"], rows, "links"))
    if "points" in data:
        rows = []
        for label, v in data["points"].items():
            vel, acc = v.get("velocity"), v.get("acceleration")
            rows.append([label, math.hypot(*vel) if vel else None, _angle_of(vel) if vel else None,
                         math.hypot(*acc) if acc else None, _angle_of(acc) if acc else None])
        blocks.append(_table(["", f"|v| ({uv})", "∠v (°)", f"|a| ({ua})", "∠a (°)"], rows, "points"))
    if "sliders" in data:
        rows = [[f"slider {name}", v["s"], v.get("s_dot"), v.get("s_ddot"),
                 math.hypot(*v["coriolis"]) if "coriolis" in v else None] for name, v in data["sliders"].items()]
        blocks.append(_table(["", f"s ({u})", f"ṡ ({uv})", f"s̈ ({ua})", f"|aᶜ| ({ua})"], rows, "sliders"))
    return blocks


def legend_block(kinds: Sequence[str]) -> Block:
    """Which colour is which kind of term (only the kinds drawn)."""
    lines: list[tuple[tuple[Run, ...], bool]] = [(plain_runs("vectors", SMALL_MM), True)]
    for kind in kinds:
        lines.append(((Run(TERM_NAMES[kind], 7.0, 0.0, SMALL_MM),), False))
    return _block(lines)


def readable(text: str) -> str:
    """Plain-text notation of the steps made typographic: omega -> ω, ^2 -> ², deg -> °."""
    for plain, nice in (("omega", "ω"), ("alpha", "α"), ("theta", "θ"), ("^2", "²"), (" deg", "°")):
        text = text.replace(plain, nice)
    return text


STEP_TEXT_MM = SMALL_MM * 1.1
"""The size of a step's equation and sentence in its block (``step_block``), unless it must shrink to fit."""


def step_block(number: int, total: int, equation: str, text: str, width: float, size: float = STEP_TEXT_MM) -> Block:
    lines: list[tuple[tuple[Run, ...], bool]] = [(plain_runs(f"Step {number} of {total}", TITLE_MM * 0.8), True)]
    lines += [(plain_runs(line, size), True) for line in wrap(readable(equation), size, width, bold=True)]
    lines += [(plain_runs(line, size), False) for line in wrap(readable(text), size, width)]
    return _block(lines, width)


def flow(blocks: Sequence[Block], width: float) -> list[tuple[Block, Point]]:
    """Top-left positions of the blocks (relative to the title block's top-left), wrapping rows."""
    out: list[tuple[Block, Point]] = []
    x = y = row_h = 0.0
    for block in blocks:
        if x > 0.0 and x + block.width > width:
            x, y, row_h = 0.0, y + row_h + _PAD_MM, 0.0
        out.append((block, (x, -y)))
        x += block.width + _GAP_MM
        row_h = max(row_h, block.height)
    return out


def flow_height(blocks: Sequence[Block], width: float) -> float:
    placed = flow(blocks, width)
    return max(-pos[1] + block.height for block, pos in placed) + 2 * _PAD_MM


def block_items(block: Block, top_left: Point, role: str, legend: Sequence[str] = ()) -> list[Item]:
    """The block's texts, each line's baseline below its top; legend swatches where a legend asks."""
    items: list[Item] = []
    y = top_left[1]
    for k, (runs, bold, h) in enumerate(block.lines):
        size = max(r.size for r in runs)
        baseline = y - h + (h - size) / 2 + DESCENT_EM * size
        items.append(Text(top_left[0], baseline, runs, "#000000", f"{role} line {k}", None, bold))
        if legend and k >= 1:
            kind = legend[k - 1]
            mid = baseline + 0.3 * size
            items.append(Path(((top_left[0], mid), (top_left[0] + 5.5, mid)), Stroke(TERM_COLORS[kind], 0.6),
                              role=f"legend {kind}"))
        y -= h
    return items


def heading_items(panel: Panel, title: str, scale_text: str, bar_unit: str) -> tuple[list[Item], list[Item]]:
    """A panel's heading (title layer) and its scale text and bar (scales layer), in the heading strip."""
    x0, _, x1, y1 = panel.rect
    room = x1 - x0 - 2.0
    title_items: list[Item] = [Text(x0 + 1.0, y1 - 3.2, fitted_runs(title, 2.8, room, True), "#000000",
                                    f"heading {panel.name}", None, True)]
    baseline = y1 - HEADING_MM + 1.2
    text = Text(x0 + 1.0, baseline, fitted_runs(scale_text, SMALL_MM, room), "#000000", f"scale {panel.name}")
    scale_items: list[Item] = [text]
    label_room = text_width(f"{format_number(25.0 / panel.scale)} {bar_unit}", SMALL_MM) + 2.0
    start = text.box[2] + 3.0
    if x1 - start - 2.0 - label_room < 8.0:  # no room beside the scale: beside the heading
        start, baseline = title_items[0].box[2] + 4.0, y1 - 3.2  # type: ignore[union-attr]
    if x1 - start - 2.0 - label_room < 8.0:  # nor there: on its own line, under the heading strip
        start, baseline = x0 + 1.0, y1 - HEADING_MM - 2.6
    target = min(25.0, x1 - start - 2.0 - label_room)
    if target >= 6.0 and panel.scale > 0:
        value = round_step(target / panel.scale)
        length = value * panel.scale
        y = baseline + 0.2
        scale_items.append(Path(((start, y), (start + length, y)), Stroke("#000000", 0.35),
                                role=f"scale bar {panel.name}"))
        for k in range(3):
            x = start + length * k / 2
            tick = 1.2 if k != 1 else 0.7
            scale_items.append(Path(((x, y), (x, y + tick)), THIN, role=f"scale tick {panel.name}"))
        scale_items.append(Text(start + length + 1.5, baseline,
                                plain_runs(f"{format_number(value)} {bar_unit}", SMALL_MM),
                                "#000000",
                                f"scale label {panel.name}"))
    return title_items, scale_items


def fitted_runs(text: str, size: float, room: float, bold: bool = False) -> tuple[Run, ...]:
    """``text`` at ``size``, or smaller where it would be wider than ``room`` (a heading in a narrow panel)."""
    width = text_width(text, size, bold)
    return plain_runs(text, size if width <= room else size * max(room, 1.0) / width)


def space_scale_text(scale: float, unit: str) -> str:
    """``scale 1:2.5`` for a mechanism drawn 0.4 mm of paper per mm."""
    ratio = scale / _UNIT_MM[unit]
    if ratio >= 1.0:
        return f"scale {format_number(ratio)}:1"
    return f"scale 1:{format_number(1.0 / ratio)}"
