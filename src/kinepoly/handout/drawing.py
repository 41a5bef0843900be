"""The drawing of each handout page, from the render package's sheets, with the words of the handout.

A page is the drawing of ``kinepoly draw`` (``render.sheet.build_sheet``: the same layout, scales,
arrows and labels; a construction step highlighted on the growing polygons) with its English
title block taken off and a band of text in the handout's language put in its place. The drawing
is laid out once for all pages (``Frame``), on a paper short enough that the band fits below it,
so that nothing moves from page to page. The panel headings and scale texts are written anew in
the handout's language (``render.titleblock.heading_items``); the instant centers are shown as
far as the Kennedy steps have found them, the current step's lines and center highlighted.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from msgspec import Struct, field
from msgspec.structs import replace

from kinepoly.geom.tolerances import PAPER_SAME_MM
from kinepoly.handout.content import Drawing
from kinepoly.present.catalogue import Catalogue
from kinepoly.render.labels import LabelCache
from kinepoly.render.layout import Panel
from kinepoly.render.primitives import LAYERS, Arrow, Circle, Item, Layer, Path, Sheet, Stroke, Text
from kinepoly.render.sheet import MARGIN_MM, Layout, build_sheet, layout_sheet
from kinepoly.render.style import BORDER, HALO, INK, RULE
from kinepoly.render.text import Run
from kinepoly.render.titleblock import fitted_runs, heading_items, space_scale_text
from kinepoly.solution import Solution

__all__ = ["GAP_MM", "Frame", "band_frame", "blank_sheet", "drawing_layers", "moved", "page_frame_items", "scales_of"]

GAP_MM = 3.0
"""Between the band of text and the drawing's panels, and inside the border."""


class Frame(Struct, frozen=True):
    """The drawing laid out on ``paper`` and moved up by ``shift`` on a page ``width`` x ``height``.

    The band of text is the strip ``band`` mm high above the page's bottom margin (0: no band).
    """

    layout: Layout
    paper: tuple[float, float]
    shift: float
    width: float
    height: float
    band: float
    labels: LabelCache = field(default_factory=LabelCache)
    """Shared by the frame's pages: the labels of the fixed parts are placed once."""
    placed: dict[Item, Item] = field(default_factory=dict)
    """Each item drawn on the frame's pages, moved to its place on the page once (``moved``): equal items are
    one object on every page."""


def scales_of(layout: Layout) -> dict[str, float]:
    """The scales as drawn: the mechanism's (paper mm per length unit), kv and ka."""
    return {panel.name: panel.scale for panel in layout.panels if panel.name != "centers"}


def _bottom(layout: Layout) -> float:
    """Where the English title block ends, the panels start (paper mm from the paper's bottom)."""
    return layout.title_rect[3]


def band_frame(solution: Solution, page: tuple[float, float], band: float,
               scales_paper: tuple[float, float] | None = None, readable: dict[str, Any] | None = None,
               whole: Layout | None = None) -> Frame:
    """The drawing for a page of size ``page`` with ``band`` mm of text at its foot (0: none).

    With a band the page keeps its size and the drawing's paper is made shorter until the band
    fits (the layout's notes may change its title block, so a few rounds settle it); without
    one the drawing keeps the whole paper and the page loses the title block's strip. The polygons'
    scales are those decided for ``scales_paper`` (the paper asked for; ``page`` when None); ``readable``
    the solution's readable values at them (``render.sheet.readable_values``), made once per handout;
    ``whole`` the layout on the whole page at those scales when the caller has it (a frame without a band's).
    """
    asked = scales_paper or page
    width, height = page
    if band <= 0.0:
        layout = layout_sheet(solution, page, grow=False, scales_paper=asked, readable=readable)
        shift = MARGIN_MM - _bottom(layout)
        return Frame(layout, page, shift, width, height + shift, 0.0)
    paper_height = height
    layout = whole or layout_sheet(solution, (width, paper_height), grow=False, scales_paper=asked, readable=readable)
    for _ in range(4):
        shift = MARGIN_MM + band + GAP_MM - _bottom(layout)
        wanted = height - shift
        if abs(wanted - paper_height) < PAPER_SAME_MM:
            break
        paper_height = wanted
        layout = layout_sheet(solution, (width, paper_height), grow=False, scales_paper=asked, readable=readable)
    shift = height - paper_height
    return Frame(layout, (width, paper_height), shift, width, height, band)


def moved(item: Item, dy: float) -> Item:
    """The item moved up by ``dy`` mm."""
    def up(p: tuple[float, float]) -> tuple[float, float]:
        return (p[0], p[1] + dy)

    if isinstance(item, Path):
        return replace(item, points=tuple(up(p) for p in item.points))
    if isinstance(item, Circle):
        return replace(item, center=up(item.center))
    if isinstance(item, Arrow):
        return replace(item, start=up(item.start), end=up(item.end))
    return replace(item, y=item.y + dy, anchor=up(item.anchor) if item.anchor else None)


def _scale_text(panel: Panel, say: Catalogue, unit: str, reduced: bool) -> tuple[str, str]:
    if panel.name == "mechanism":
        ratio = space_scale_text(panel.scale, unit).partition(" ")[2]
        text, bar_unit = say.say("panel.space_scale", ratio=ratio.replace(".", say.decimal)), unit
    elif panel.name == "velocity":
        text, bar_unit = say.say("panel.kv", scale=say.number(panel.scale), unit=f"{unit}/s"), f"{unit}/s"
    else:
        text, bar_unit = say.say("panel.ka", scale=say.number(panel.scale), unit=f"{unit}/s²"), f"{unit}/s²"
    if reduced:
        text += " " + say.say("panel.reduced")
    return text, bar_unit


def _headings(solution: Solution, layout: Layout, say: Catalogue) -> tuple[list[Item], list[Item]]:
    """Panel headings and scale bars in the handout's language (the render's own, re-worded)."""
    unit = solution.scene.units.length
    titles: list[Item] = []
    bars: list[Item] = []
    for panel in layout.panels:
        name = say.say(f"panel.{panel.name}")
        if panel.name == "centers":
            titles.append(Text(panel.rect[0] + 1.0, panel.rect[3] - 3.2,
                               fitted_runs(name, 2.8, panel.rect[2] - panel.rect[0] - 2.0, True), INK,
                               f"heading {panel.name}", None, True))
            continue
        text, bar_unit = _scale_text(panel, say, unit, panel.name in layout.reduced)
        heading, scale = heading_items(panel, name, text, bar_unit)
        titles += heading
        bars += [_decimal(item, say) for item in scale]
    return titles, bars


def _decimal(item: Item, say: Catalogue) -> Item:
    """A number drawn by the render package (a scale bar's value, a far center's place) with the handout's mark."""
    if say.decimal == "." or not isinstance(item, Text):
        return item
    runs = tuple(Run(re.sub(r"(?<=\d)\.(?=\d)", say.decimal, r.text), r.dx, r.dy, r.size) for r in item.runs)
    runs = tuple(Run(r.text.replace(", ", "; ") if "(" in r.text else r.text, r.dx, r.dy, r.size) for r in runs)
    return replace(item, runs=runs)


_CENTER_ROLE = re.compile(r"^(?:leader |ring )?center I(?:\((\S+)\)|(\S+?))(?: toward)?$")
_DIAGRAM_ROLE = re.compile(r"^(?:leader |ring )?diagram (?:edge|number) (\S+)$")


def _centers_filter(solution: Solution, drawing: Drawing) -> tuple[Callable[[Item], bool], set[str], str]:
    """Which items of the instant-centers layer a page shows; the current step's lines and center."""
    centers = solution.centers
    if centers is None or drawing.kind == "answers":
        return (lambda item: True), set(), ""
    upto = drawing.number if drawing.kind == "kennedy" else 0
    steps = [s for s in centers.steps if s.number <= upto]
    lines = {line.label for s in steps for line in s.lines}
    found = {name for name, c in centers.centers.items() if c.number == 0 or c.number <= upto}
    if upto == 0:
        found = set()  # before the Kennedy steps the student marks the joints' centers too
    edges = {e.name: e for e in centers.diagram.edges}
    current = next((s for s in centers.steps if s.number == upto), None)

    def keep(item: Item) -> bool:
        role = item.role
        if role.startswith("kennedy "):
            return role[len("kennedy "):] in lines
        m = _CENTER_ROLE.match(role)
        if m:
            return (m.group(1) or m.group(2)) in found
        m = _DIAGRAM_ROLE.match(role)
        if m and m.group(1) in edges:
            edge = edges[m.group(1)]
            # a cam pair's line edge is known from the start as a line; its number once its point is found
            return edge.kind == "joint" or edge.number <= upto or (edge.kind == "line" and "number" not in role)
        return True

    return keep, ({line.label for line in current.lines} if current else set()), (current.center if current else "")


def _highlighted(items: list[Item], lines: set[str], center: str) -> list[Item]:
    """The items, with a halo under the current Kennedy step's lines and its center."""
    out: list[Item] = []
    for item in items:
        role = item.role
        m = _CENTER_ROLE.match(role)
        if isinstance(item, Path) and role.startswith("kennedy ") and role[len("kennedy "):] in lines:
            out.append(Path(item.points, HALO, role="highlight"))
        elif m and (m.group(1) or m.group(2)) == center and not role.startswith(("leader", "ring")):
            if isinstance(item, Circle):
                out.append(Circle(item.center, 2.0, None, fill=HALO.color, role="highlight"))
            elif isinstance(item, Arrow):
                out.append(Path((item.start, item.end), Stroke(HALO.color, 2.2), role="highlight"))
        out.append(item)
    return out


def drawing_layers(solution: Solution, frame: Frame, drawing: Drawing, say: Catalogue) -> dict[str, list[Item]]:
    """The drawing of a page, layer by layer, moved to its place on the page; no border, no text band."""
    step: int | None = None
    if drawing.kind == "problem":
        step = 0 if solution.steps else None
    elif drawing.kind == "step":
        step = drawing.number
    base = build_sheet(solution, frame.paper, step=step, layout=frame.layout, labels=frame.labels, title_block=False)
    layers = {layer.name: list(layer.items) for layer in base.layers}
    titles, bars = _headings(solution, frame.layout, say)
    layers["title"], layers["scales"] = titles, bars
    keep, lines, center = _centers_filter(solution, drawing)
    layers["instant-centers"] = _highlighted([_decimal(i, say) for i in layers["instant-centers"] if keep(i)],
                                             lines, center)
    placed = frame.placed
    out: dict[str, list[Item]] = {}
    for name in LAYERS:
        out[name] = []
        for item in layers[name]:
            shown = placed.get(item)
            if shown is None:
                shown = placed[item] = moved(item, frame.shift)
            out[name].append(shown)
    return out


def page_frame_items(frame: Frame) -> list[Item]:
    """The page's border, and the rule over the band of text."""
    w, h, m = frame.width, frame.height, MARGIN_MM
    items: list[Item] = [Path(((m, m), (w - m, m), (w - m, h - m), (m, h - m)), BORDER, closed=True,
                              role="border")]
    if frame.band > 0.0:
        y = m + frame.band
        items.append(Path(((m, y), (w - m, y)), RULE, role="band rule"))
    return items


def blank_sheet(frame: Frame, title: str, layers: dict[str, list[Item]]) -> Sheet:
    """A sheet of the page's size holding ``layers`` (every layer of ``LAYERS``)."""
    return Sheet(frame.width, frame.height, title, tuple(Layer(name, tuple(layers[name])) for name in LAYERS))

