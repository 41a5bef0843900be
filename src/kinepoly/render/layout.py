"""Paper sizes, round scales and the arrangement of the panels on the page.

A panel is a rectangle of the page with a scale: paper = origin + scale * physical. The
mechanism gets a round space scale that fills what the polygons leave; the polygons keep
their scales kv and ka when they fit, and otherwise step down the round-number ladder (the
sheet then says so). The round numbers are ``present.scales``' (``nice_floor``), the one rule of them.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

from msgspec import Struct

from kinepoly.geom.tolerances import FIT_MARGIN_REL, PAPER_ROUNDING_MM, PAPER_SAME_MM
from kinepoly.present.scales import nice_floor

__all__ = [
    "PAPER_NAMES",
    "Content",
    "Panel",
    "arrange",
    "fit_panel",
    "larger_papers",
    "nice_floor",
    "paper_name",
    "paper_size",
    "round_step",
]

Point = tuple[float, float]
Box = tuple[float, float, float, float]

_SIZES_MM = {
    "a0": (1189.0, 841.0), "a1": (841.0, 594.0), "a2": (594.0, 420.0), "a3": (420.0, 297.0),
    "a4": (297.0, 210.0), "a5": (210.0, 148.0), "letter": (279.4, 215.9), "legal": (355.6, 215.9),
    "tabloid": (431.8, 279.4),
}
PAPER_NAMES = tuple(_SIZES_MM)
_LABEL_ROOM_MM = 30.0
"""The most a polygon's column is widened beyond its polygon, when the page has room to spare."""
HEADING_MM = 8.5
"""Room at the top of each panel for its heading."""


def paper_size(spec: str) -> tuple[float, float]:
    """Width and height in mm of ``A4`` (landscape), ``A4-portrait``, ``letter``, ``420x297`` ...

    Raises ValueError with what is accepted.
    """
    text = spec.strip().lower()
    m = re.fullmatch(r"(\d+(?:\.\d+)?)\s*x\s*(\d+(?:\.\d+)?)", text)
    if m:
        w, h = float(m.group(1)), float(m.group(2))
        if not (100.0 <= w <= 5000.0 and 100.0 <= h <= 5000.0):
            raise ValueError(f"--paper {spec}: width and height must lie between 100 and 5000 mm")
        return w, h
    name, _, orientation = text.partition("-")
    if name not in _SIZES_MM or orientation not in ("", "landscape", "portrait"):
        raise ValueError(f"--paper {spec}: expected one of "
                         f"{', '.join(n.upper() if n[0] == 'a' else n for n in PAPER_NAMES)}"
                         f", optionally with -portrait or -landscape (default landscape), or WIDTHxHEIGHT in mm")
    long, short = _SIZES_MM[name]
    return (short, long) if orientation == "portrait" else (long, short)


_LARGER = ("a4", "a3", "a2", "a1", "a0")


def paper_name(size: tuple[float, float]) -> str:
    """``A3`` (landscape), ``A4-portrait``, ``letter`` for a named size; else ``WIDTHxHEIGHT``."""
    for name, (long, short) in _SIZES_MM.items():
        shown = name.upper() if name[0] == "a" else name
        if abs(size[0] - long) < PAPER_SAME_MM and abs(size[1] - short) < PAPER_SAME_MM:
            return shown
        if abs(size[0] - short) < PAPER_SAME_MM and abs(size[1] - long) < PAPER_SAME_MM:
            return f"{shown}-portrait"
    return f"{size[0]:g}x{size[1]:g}"


def larger_papers(size: tuple[float, float]) -> list[tuple[str, tuple[float, float]]]:
    """A4, A3, ... A0 in the orientation of ``size``, each larger than ``size`` both ways, smallest first."""
    portrait = size[1] > size[0]
    out = []
    for name in _LARGER:
        w, h = paper_size(name + ("-portrait" if portrait else ""))
        if w > size[0] + PAPER_SAME_MM and h > size[1] + PAPER_SAME_MM:
            out.append((paper_name((w, h)), (w, h)))
    return out


def round_step(target: float) -> float:
    """A round length (1, 2, 2.5, 5 x 10^k) near ``target`` and not above it: for scale bars."""
    return nice_floor(target)


class Content(Struct, frozen=True):
    """What a panel must show: its physical bounding box, the scale it wants (None: free), padding."""

    name: str
    box: Box
    wanted: float | None
    padding: float

    def size(self, scale: float) -> tuple[float, float]:
        w = max(self.box[2] - self.box[0], 0.0) * scale + 2 * self.padding
        h = max(self.box[3] - self.box[1], 0.0) * scale + 2 * self.padding + HEADING_MM
        return w, h

    def fit(self, width: float, height: float) -> float:
        """The largest scale at which the content fits ``width`` x ``height`` (inf when it has no size)."""
        w = max(self.box[2] - self.box[0], 0.0)
        h = max(self.box[3] - self.box[1], 0.0)
        room_w, room_h = width - 2 * self.padding, height - 2 * self.padding - HEADING_MM
        scales = [room_w / w if w > 0 else math.inf, room_h / h if h > 0 else math.inf]
        return max(min(scales), 0.0)


class Panel(Struct, frozen=True):
    """A panel of the page: ``rect`` (x0, y0, x1, y1) in paper mm, ``scale`` paper mm per unit."""

    name: str
    rect: Box
    scale: float
    wanted: float | None
    origin: Point

    def paper(self, p: Point) -> Point:
        return (self.origin[0] + self.scale * p[0], self.origin[1] + self.scale * p[1])

    @property
    def drawing_rect(self) -> Box:
        """The panel without its heading strip."""
        return (self.rect[0], self.rect[1], self.rect[2], self.rect[3] - HEADING_MM)


def fit_panel(content: Content, rect: Box, scale: float) -> Panel:
    """The panel ``rect`` drawing ``content`` at ``scale``, its box centred below the heading strip."""
    return _panel(content, rect, scale)


def _panel(content: Content, rect: Box, scale: float) -> Panel:
    x0, y0, x1, y1 = rect
    cx = (content.box[0] + content.box[2]) / 2
    cy = (content.box[1] + content.box[3]) / 2
    mid = ((x0 + x1) / 2, (y0 + y1 - HEADING_MM) / 2)
    return Panel(content.name, rect, scale, content.wanted, (mid[0] - scale * cx, mid[1] - scale * cy))


def _step_down(scale: float, steps: int) -> float:
    for _ in range(steps):
        scale = nice_floor(scale * (1.0 - FIT_MARGIN_REL))
    return scale


def _ladder(scale: float, steps: int) -> list[float]:
    """``scale`` and its first ``steps`` round steps down: ``_step_down(scale, n)`` for n = 0 .. steps."""
    out = [scale]
    for _ in range(steps):
        out.append(_step_down(out[-1], 1))
    return out


def _columns(count: int) -> list[list[list[int]]]:
    """Ways to put contents 0..count-1 into contiguous columns, the mechanism (0) in the first."""
    out: list[list[list[int]]] = [[[k] for k in range(count)]]
    if count >= 2:
        out.append([list(range(count))] if count == 2 else [[0, 1], *[[k] for k in range(2, count)]])
    if count >= 3:
        out.append([[0], list(range(1, count))])
        out.append([[0, 2], [1], *[[k] for k in range(3, count)]])
    return out


def _try(contents: Sequence[Content], area: Box, columns: list[list[int]],
         scales: dict[int, float]) -> list[Panel] | None:
    """Panels for one arrangement with the given polygon scales, or None when it does not fit."""
    x0, y0, x1, y1 = area
    width, height = x1 - x0, y1 - y0
    need = {k: contents[k].size(s) for k, s in scales.items()}
    widths = []
    for column in columns:
        fixed = [need[k] for k in column if k in need]
        if sum(h for _, h in fixed) > height + PAPER_ROUNDING_MM:
            return None
        widths.append(max((w for w, _ in fixed), default=0.0))
    spare = width - sum(widths)
    if spare < 0.0:
        return None
    # each polygon's column gets some of what is left for labels set further out; the mechanism's the rest
    share = min(spare / len(columns), _LABEL_ROOM_MM) if len(columns) > 1 else 0.0
    widths = [w + share for w in widths]
    widths[0] += spare - share * len(columns)
    panels: dict[int, Panel] = {}
    x = x0
    for column, col_w in zip(columns, widths, strict=True):
        free = [k for k in column if k not in need]
        rest = height - sum(need[k][1] for k in column if k in need)
        extra = 0.0 if free else rest / len(column)
        y = y1
        for k in column:
            cell_h = rest if k not in need else need[k][1] + extra
            rect = (x, y - cell_h, x + col_w, y)
            if k in need:
                panels[k] = _panel(contents[k], rect, scales[k])
            else:
                fit = contents[k].fit(col_w, cell_h)
                if not (fit > 0.0):
                    return None
                scale = nice_floor(fit) if math.isfinite(fit) else 1.0
                panels[k] = _panel(contents[k], rect, scale)
            y -= cell_h
        x += col_w
    return [panels[k] for k in range(len(contents))]


def _score(panels: list[Panel], contents: Sequence[Content], area: Box) -> tuple[bool, float, float, float]:
    ratios = [p.scale / p.wanted for p in panels if p.wanted]
    c = contents[0]
    size = max(c.box[2] - c.box[0], c.box[3] - c.box[1]) * panels[0].scale
    least = 0.3 * min(area[2] - area[0], area[3] - area[1])
    return (size >= least, min(ratios, default=1.0), sum(ratios), size)


def arrange(contents: Sequence[Content], area: Box) -> list[Panel]:
    """Panels for ``contents`` (the mechanism first, then panels with a wanted scale) in ``area``.

    Tries the arrangements in columns and, for each, the wanted scales and a few round steps
    below them; keeps the one that draws the mechanism at least a third of the area large,
    then keeps the wanted scales best (the least kept first, then all together), then draws the
    mechanism largest.
    """
    fixed = [k for k, c in enumerate(contents) if c.wanted is not None]
    levels_tried = _levels(len(fixed))
    deepest = max((max(levels, default=0) for levels in levels_tried), default=0)
    # each wanted scale's round steps down, made once for every arrangement and level that takes them
    ladders = {k: _ladder(contents[k].wanted or 1.0, deepest) for k in fixed}
    # Where levels fit with the mechanism large enough, every level as low or lower in each panel scores less
    # (the same first term, smaller scale ratios): it cannot be the best, and is not tried.
    prune = all(contents[k].wanted for k in fixed)
    best: list[Panel] | None = None
    best_score: tuple[bool, float, float, float] | None = None
    for columns in _columns(len(contents)):
        settled: list[tuple[int, ...]] = []
        for levels in levels_tried:
            if any(all(n >= m for n, m in zip(levels, done, strict=True)) for done in settled):
                continue
            scales = {k: ladders[k][n] for k, n in zip(fixed, levels, strict=True)}
            panels = _try(contents, area, columns, scales)
            if panels is None:
                continue
            score = _score(panels, contents, area)
            if prune and score[0]:
                settled.append(levels)
            if best_score is None or score > best_score:
                best, best_score = panels, score
    if best is None:  # nothing fits a few steps down: everything in one row, each polygon at the scale that fits
        best = _one_row(contents, area, fixed)
    return best


def _one_row(contents: Sequence[Content], area: Box, fixed: Sequence[int]) -> list[Panel]:
    """Every content in a cell of its own, side by side, the polygons at the round scale that fits their cell.

    Never fails: where even that does not fit (a page smaller than the paddings), the cells are
    laid out as they are and the drawing overflows them rather than the command failing.
    """
    x0, y0, x1, y1 = area
    cell_w, cell_h = max(x1 - x0, 0.0) / len(contents), max(y1 - y0, 0.0)
    scales = {}
    for k in fixed:
        fit = contents[k].fit(cell_w, cell_h) * (1.0 - FIT_MARGIN_REL)
        scales[k] = nice_floor(fit) if math.isfinite(fit) else (contents[k].wanted or 1.0)
    panels = _try(contents, area, [[k] for k in range(len(contents))], scales)
    if panels is not None:
        return panels
    out = []
    for k, content in enumerate(contents):
        rect = (x0 + k * cell_w, y0, x0 + (k + 1) * cell_w, max(y1, y0))
        fit = content.fit(cell_w, cell_h) * (1.0 - FIT_MARGIN_REL)
        scale = scales.get(k, nice_floor(fit) if math.isfinite(fit) else 1.0)
        out.append(_panel(content, rect, scale))
    return out


def _levels(count: int) -> list[tuple[int, ...]]:
    """Round steps below the wanted scales to try, for ``count`` panels (0 = as wanted)."""
    steps = range(7)
    if count == 0:
        return [()]
    if count == 1:
        return [(a,) for a in steps]
    return [(a, b) for a in steps for b in steps] if count == 2 else [tuple([a] * count) for a in steps]
