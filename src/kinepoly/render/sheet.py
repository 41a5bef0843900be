"""Solution in, sheet out: layout, scales, arrows and labels decided once for every backend.

``build_sheet`` lays out the page (title block at the foot, the mechanism and the polygons side
by side above it), draws each part on its layer and then places every label clear of what is
drawn. ``step_sheets`` gives one sheet per construction step on the same layout: everything up
to that step, the step's new elements highlighted, the step's text in the title block.
"""

from __future__ import annotations

import math
from typing import Any

from msgspec import Struct, field

from kinepoly.geom.tolerances import FIT_MARGIN_REL, PAPER_ROUNDING_MM, ROUNDING_REL
from kinepoly.present.clean import format_number
from kinepoly.present.phrasing import Context, english, kennedy_sentence, step_sentence
from kinepoly.present.scales import PolygonScales, decide_scales
from kinepoly.render import centers as centers_layer
from kinepoly.render import higher_pairs as higher_pairs_layer
from kinepoly.render.labels import FEW, LabelCache, Request, draft_place, place
from kinepoly.render.layout import (
    Content,
    Panel,
    arrange,
    fit_panel,
    larger_papers,
    nice_floor,
    paper_name,
    paper_size,
)
from kinepoly.render.mechanism import mechanism_box, mechanism_items
from kinepoly.render.polygons import Figure, FigureDrawing, Kind, figure_box, polygon_figure
from kinepoly.render.primitives import LAYERS, Item, Layer, Path, Sheet, Stroke, Text
from kinepoly.render.titleblock import (
    STEP_TEXT_MM,
    Block,
    block_items,
    fitted_runs,
    flow,
    flow_height,
    heading_items,
    legend_block,
    space_scale_text,
    step_block,
    title_blocks,
)
from kinepoly.solution import Solution

__all__ = ["GAIN", "Layout", "build_sheet", "crowded", "layout_sheet", "motion_layout", "readable_values", "roomy",
           "step_count",
           "step_sheets"]

MARGIN_MM = 10.0
_INNER_MM = 3.0
_PADDING_MM = {"mechanism": 12.0, "velocity": 9.0, "acceleration": 9.0}
_NAMES = {"mechanism": "Mechanism", "velocity": "Velocity polygon", "acceleration": "Acceleration polygon",
          "centers": "Circle diagram"}


class Layout(Struct, frozen=True):
    """Where everything goes, shared by a drawing and its step-by-step sheets."""

    width: float
    height: float
    panels: tuple[Panel, ...]
    figures: tuple[Figure, ...]
    title_rect: tuple[float, float, float, float]
    notes: tuple[str, ...]
    reduced: frozenset[str] = frozenset()
    """The polygons (``velocity``, ``acceleration``) drawn at a smaller scale than wanted: their headings say so."""
    blocks: tuple[Block, ...] = ()
    """The title block's columns of the whole drawing (made once: a step's sheet takes its first)."""
    labels: LabelCache = field(default_factory=LabelCache)
    """The labels placed on this layout's sheets so far (``render.labels.LabelCache``): placed once, reused."""

    def panel(self, name: str) -> Panel | None:
        return next((p for p in self.panels if p.name == name), None)


def _title_blocks(solution: Solution, figures: tuple[Figure, ...], notes: tuple[str, ...], width: float,
                  data: dict[str, Any]) -> list[Block]:
    blocks = title_blocks(solution, notes, width, data)
    kinds = _drawn_terms(figures)
    if kinds:
        blocks.append(legend_block(kinds))
    return blocks


def _drawn_terms(figures: tuple[Figure, ...]) -> list[str]:
    order = ("absolute", "relative", "sliding", "normal", "tangential", "coriolis")
    present = {v.term for f in figures for v in f.vectors}
    return [k for k in order if k in present]


def layout_sheet(solution: Solution, paper: str | tuple[float, float] = "A4", *, grow: bool = True,
                 scales_paper: tuple[float, float] | None = None, readable: dict[str, Any] | None = None) -> Layout:
    """Decide the page: its paper, the title block's height, the panels and their scales.

    Each polygon is drawn at the scale decided for the paper asked (``present.scales.decide_scales``;
    for ``scales_paper`` when given) and the mechanism large enough to read (``roomy``), every
    label in a free place (``crowded``). When the paper asked cannot hold them, the next larger A
    paper that can (A3, A2 ... A0, in the paper's orientation) is taken and the title block says
    so; a larger paper is tried for the labels only while it gives them more room (fewer
    crowded). When no paper is roomy, the first that keeps the scales, else the paper asked with
    the polygons' scales reduced (said too). ``grow=False`` keeps the paper as given (a handout
    chooses its own). ``readable`` the solution's readable values at those scales (``readable_values``), when
    the caller has them already.
    """
    size = paper_size(paper) if isinstance(paper, str) else paper
    decided = decide_scales(solution, scales_paper or size)
    if readable is None:
        from kinepoly.present.report import readable_json

        readable = readable_json(solution, scales=decided)
    data = readable
    first = _layout_on(solution, size, (), decided, data)
    if not grow:
        return first
    best: Layout | None = None
    kept: Layout | None = None
    counted: dict[int, int] = {}

    def crowded_on(layout: Layout) -> int:  # each paper's sheet built once to count its crowded labels
        if id(layout) not in counted:
            counted[id(layout)] = crowded(solution, layout)
        return counted[id(layout)]

    for name, candidate in [("", size), *larger_papers(size)]:
        note = (f"drawn on {name}: the polygons at their scales, the mechanism and their labels need more room "
                f"than {paper_name(size)} has")
        layout = first if not name else _layout_on(solution, candidate, (note,), decided, data)
        kept = kept or (layout if _keeps_scales(layout) else None)
        if not roomy(solution, layout):
            if best is None:
                continue
            break
        if best is not None and crowded_on(layout) > GAIN * crowded_on(best):
            break  # little room gained for the labels: they crowd where the polygon does, at any paper
        best = layout
        if not 0 < crowded_on(layout) <= FEW:
            break  # every label free, or so many crowded that their polygon's points crowd, at any paper
    return best or kept or first


def readable_values(solution: Solution, scales_paper: str | tuple[float, float]) -> dict[str, Any]:
    """The solution's readable values (``present.report.readable_json``) at the scales decided for
    ``scales_paper``, which the title block shows: made once by a caller that lays out many sheets at the
    same scales (a handout) and passed to ``layout_sheet``."""
    from kinepoly.present.report import readable_json

    size = paper_size(scales_paper) if isinstance(scales_paper, str) else scales_paper
    return readable_json(solution, scales=decide_scales(solution, size))


GAIN = 0.75
"""A larger paper is taken for the labels only when it leaves at most this share of them crowded."""


def _keeps_scales(layout: Layout) -> bool:
    return not any(p.wanted is not None and p.scale < p.wanted * (1 - ROUNDING_REL) for p in layout.panels)


def crowded(solution: Solution, layout: Layout) -> int:
    """How many labels of the whole drawing on ``layout`` find no free place near their point (they stay placed
    for its sheets): set out further with a leader, or crowded (``render.labels.LabelCache.set_out``)."""
    build_sheet(solution, (layout.width, layout.height), layout=layout)
    return len(layout.labels.set_out)


def roomy(solution: Solution, layout: Layout) -> bool:
    """Whether every panel keeps the scale it wants and the mechanism is drawn at least a third of the area large."""
    if not _keeps_scales(layout):
        return False
    mech = layout.panel("mechanism")
    if mech is None:
        return True
    box = _mechanism_box(solution)
    size = max(box[2] - box[0], box[3] - box[1]) * mech.scale
    area = _drawing_area(layout.width, layout.height, layout.title_rect[3] - layout.title_rect[1])
    return size >= _LEAST_MECHANISM * min(area[2] - area[0], area[3] - area[1]) - PAPER_ROUNDING_MM


_LEAST_MECHANISM = 0.3
"""The mechanism's drawn size, as a share of the drawing area's shorter side, below which a larger paper is taken."""


def _drawing_area(width: float, height: float, title_h: float) -> tuple[float, float, float, float]:
    inner = (MARGIN_MM + _INNER_MM, MARGIN_MM + _INNER_MM, width - MARGIN_MM - _INNER_MM,
             height - MARGIN_MM - _INNER_MM)
    return (inner[0], inner[1] + title_h + _INNER_MM, inner[2], inner[3])


def _layout_on(solution: Solution, size: tuple[float, float], fixed: tuple[str, ...],
               decided: PolygonScales, data: dict[str, Any]) -> Layout:
    """The layout on a paper of ``size`` at the ``decided`` scales; ``fixed`` notes first in the title block;
    ``data`` the solution's readable values (``present.report.readable_json``)."""
    width, height = size
    figures = tuple(polygon_figure(solution, kind) for kind in ("velocity", "acceleration")
                    if (solution.velocity if kind == "velocity" else solution.acceleration) is not None)
    inner_w = width - 2 * (MARGIN_MM + _INNER_MM)
    # the notes depend on the scales, the scales on the title block's height: two passes settle it
    fixed = fixed + tuple(f"{p.symbol} reduced from {format_number(p.wanted)} to {format_number(p.value)} so that "
                          f"the {p.kind} polygon fits the paper" for p in decided.reduced)
    notes: tuple[str, ...] = fixed
    panels: list[Panel] = []
    title_h = 0.0
    scales = decided.as_dict()
    blocks: list[Block] = []
    used = notes
    for _ in range(2):
        blocks, used = _title_blocks(solution, figures, notes, inner_w, data), notes
        title_h = flow_height(blocks, inner_w)
        area = _drawing_area(width, height, title_h)
        contents = [Content("mechanism", _mechanism_box(solution), None, _PADDING_MM["mechanism"])]
        diagram = centers_layer.centers_content(solution)
        if diagram is not None:
            contents.append(diagram)
        contents += [Content(f.kind, figure_box(f), scales[f.kind], _PADDING_MM[f.kind]) for f in figures]
        panels = arrange(contents, area)
        notes = fixed + tuple(_scale_note(p) for p in panels if p.name in ("velocity", "acceleration")
                              and p.wanted is not None and p.scale < p.wanted * (1 - ROUNDING_REL))
        if notes == used:
            break  # the notes the title block was made with: a second pass would make the same blocks and panels
    if notes != used:
        blocks = _title_blocks(solution, figures, notes, inner_w, data)
    title_rect = (MARGIN_MM, MARGIN_MM, width - MARGIN_MM, MARGIN_MM + title_h)
    reduced = frozenset({p.kind for p in decided.reduced} | {p.name for p in panels if p.wanted is not None
                                                             and p.scale < p.wanted * (1 - ROUNDING_REL)})
    return Layout(width, height, tuple(panels), figures, title_rect, notes, reduced, tuple(blocks))


def _union(boxes: list[tuple[float, float, float, float]]) -> tuple[float, float, float, float]:
    return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes), max(b[3] for b in boxes))


def motion_layout(solutions: list[Solution], size: tuple[float, float], foot_mm: float) -> Layout:
    """One layout for every drawing of a motion (``solutions``, one per position shown): the mechanism and each
    polygon at one scale for all of them, so that sizes compare from frame to frame; each panel holds what any
    of them draws there, at the largest round scale that fits it. The mechanism takes the left part of the
    page (the circle diagram, when asked, below it), the polygons a column each. A strip ``foot_mm`` high at
    the foot takes the place of the title block (the frame's caption). Each frame's sheet is this layout with
    that frame's figures (``replace(layout, figures=..., labels=LabelCache())``)."""
    width, height = size
    x0, y0, x1, y1 = _drawing_area(width, height, foot_mm)
    mech = _union([mechanism_box(s) for s in solutions] +
                  [(x, y, x, y) for s in solutions for x, y in higher_pairs_layer.higher_pair_points(s)])
    both: tuple[Kind, Kind] = ("velocity", "acceleration")
    kinds = [k for k in both if any((s.velocity if k == "velocity" else s.acceleration) is not None
                                    for s in solutions)]
    split = x0 + (x1 - x0) * (_MOTION_MECHANISM if kinds else 1.0)
    diagram = centers_layer.centers_content(solutions[0])
    low = y0 + (y1 - y0) * 0.3 if diagram is not None else y0
    panels = [_fitted(Content("mechanism", mech, None, _PADDING_MM["mechanism"]), (x0, low, split, y1))]
    if diagram is not None:
        panels.append(_fitted(diagram, (x0, y0, split, low), diagram.wanted))
    column = (x1 - split) / max(len(kinds), 1)
    for n, kind in enumerate(kinds):
        box = _union([figure_box(polygon_figure(s, kind)) for s in solutions
                      if (s.velocity if kind == "velocity" else s.acceleration) is not None])
        rect = (split + n * column, y0, split + (n + 1) * column, y1)
        panels.append(_fitted(Content(kind, box, 1.0, _PADDING_MM[kind]), rect))
    title_rect = (MARGIN_MM, MARGIN_MM, width - MARGIN_MM, MARGIN_MM + foot_mm)
    return Layout(width, height, tuple(panels), (), title_rect, ())


_MOTION_MECHANISM = 0.44
"""The mechanism's share of a motion's page width (the polygons share the rest)."""


def _fitted(content: Content, rect: tuple[float, float, float, float], scale: float | None = None) -> Panel:
    """``content`` in ``rect`` at ``scale``, or at the largest round scale that fits."""
    if scale is None:
        fit = content.fit(rect[2] - rect[0], rect[3] - rect[1])
        scale = nice_floor(fit * (1.0 - FIT_MARGIN_REL)) if 0.0 < fit < math.inf else 1.0
    panel = fit_panel(content, rect, scale)
    return Panel(panel.name, panel.rect, panel.scale, scale if content.wanted is not None else None, panel.origin)


def _mechanism_box(solution: Solution) -> tuple[float, float, float, float]:
    """The mechanism's box, grown to hold the instant centers near it."""
    box = mechanism_box(solution)
    points = centers_layer.near_centers(solution, box) + higher_pairs_layer.higher_pair_points(solution)
    xs = [box[0], box[2], *(p[0] for p in points)]
    ys = [box[1], box[3], *(p[1] for p in points)]
    return (min(xs), min(ys), max(xs), max(ys))


def _scale_note(panel: Panel) -> str:
    symbol = "kv" if panel.name == "velocity" else "ka"
    return (f"{symbol} reduced from {format_number(panel.wanted or 0.0)} to {format_number(panel.scale)} "
            f"so that the {panel.name} polygon fits the page (a larger --paper keeps it)")


def _frame_items(layout: Layout) -> list[Item]:
    w, h, m = layout.width, layout.height, MARGIN_MM
    border = Path(((m, m), (w - m, m), (w - m, h - m), (m, h - m)), Stroke("#000000", 0.5), closed=True,
                  role="border")
    x0, _, x1, y1 = layout.title_rect
    rule = Path(((x0, y1), (x1, y1)), Stroke("#000000", 0.35), role="title rule")
    return [border, rule]


def _headings(solution: Solution, layout: Layout) -> tuple[list[Item], list[Item]]:
    unit: str = solution.scene.units.length
    title_items: list[Item] = []
    scale_items: list[Item] = []
    for panel in layout.panels:
        if panel.name == "mechanism":
            text, bar_unit = space_scale_text(panel.scale, unit), unit
        elif panel.name == "velocity":
            text, bar_unit = f"kv = {format_number(panel.scale)} mm per {unit}/s", f"{unit}/s"
        elif panel.name == "acceleration":
            text, bar_unit = f"ka = {format_number(panel.scale)} mm per {unit}/s²", f"{unit}/s²"
        else:
            title_items.append(Text(panel.rect[0] + 1.0, panel.rect[3] - 3.2,
                                    fitted_runs(_NAMES[panel.name], 2.8, panel.rect[2] - panel.rect[0] - 2.0, True),
                                    "#000000", f"heading {panel.name}", None, True))
            continue
        if panel.name in layout.reduced:
            text += " (reduced)"
        t, s = heading_items(panel, _NAMES[panel.name], text, bar_unit)
        title_items += t
        scale_items += s
    return title_items, scale_items


def _title_items(solution: Solution, layout: Layout, step: int | None) -> list[Item]:
    x0, _, x1, y1 = layout.title_rect
    width = x1 - x0 - 2 * _INNER_MM
    blocks = list(layout.blocks) if step is None else _step_blocks(solution, layout, step, width)
    items: list[Item] = []
    kinds = _drawn_terms(layout.figures)
    for k, (block, (bx, by)) in enumerate(flow(blocks, width)):
        legend = kinds if block.lines and block.lines[0][0][0].text == "vectors" else []
        items += block_items(block, (x0 + _INNER_MM + bx, y1 - 2.5 + by), f"title block {k}", legend)
    return items


def _step_blocks(solution: Solution, layout: Layout, step: int, width: float) -> list[Block]:
    """The title block of a step's sheet: the title, the step (its equation and sentence), the legend.

    The sheet keeps the drawing's layout, so the step's block fits the drawing's title block: as
    wide as the row leaves it, in smaller type where its sentence is long.
    """
    kinds = _drawn_terms(layout.figures)
    head = layout.blocks[0]
    legend = [legend_block(kinds)] if kinds else []
    context = Context(solution, {p.name: p.scale for p in layout.panels})
    if step <= len(solution.steps):
        s = solution.steps[step - 1]
        words = step_sentence(s, english(), context)
        heading = f"[{s.polygon}, {s.kind}] {s.equation}"
    else:  # a Kennedy step, numbered after the polygons' as kinepoly solve --steps numbers it
        assert solution.centers is not None
        kennedy = solution.centers.steps[step - len(solution.steps) - 1]
        words = kennedy_sentence(kennedy, english(), context)
        heading = f"[instant centers, kennedy] {kennedy.equation}"
    room = layout.title_rect[3] - layout.title_rect[1]

    def blocks(text_w: float, size: float) -> list[Block]:
        return [head, step_block(step, step_count(solution), heading, words, text_w, size), *legend]

    def one_row(text_w: float) -> bool:
        return all(y == 0.0 for _, (_, y) in flow(blocks(text_w, STEP_TEXT_MM), width))

    narrow = max(width - head.width - 40.0, 60.0)
    wide = max(width - head.width - sum(b.width for b in legend), narrow)
    while wide > narrow and not one_row(wide):
        wide -= 2.0
    tries = [(narrow, STEP_TEXT_MM)] + [(wide, STEP_TEXT_MM * k / 10) for k in range(10, 5, -1)]
    for text_w, size in tries:
        if flow_height(blocks(text_w, size), width) <= room:
            break
    return blocks(text_w, size)


def build_sheet(solution: Solution, paper: str | tuple[float, float] = "A4", *, step: int | None = None,
                layout: Layout | None = None, labels: LabelCache | None = None, title_block: bool = True,
                draft: bool = False) -> Sheet:
    """The drawing of ``solution``; with ``step``, the sheet of that construction step (1-based).

    ``labels``, shared by the sheets of one layout, places the labels of the parts that do not
    change from sheet to sheet once (``render.labels.LabelCache``); ``title_block=False`` leaves the
    title block's text out (a handout writes its own). ``draft``: every label at the first place the
    search tries, not searched clear of the rest (``render.labels.draft_place``): the same sheet but
    for where its labels sit, made in a fraction of the time (the editor's, while the user drags).
    The whole drawing (no ``step``, not a draft) is built once per ``labels``: asked again, it is the same sheet.
    """
    layout = layout if layout is not None else layout_sheet(solution, paper)
    labels = labels if labels is not None else layout.labels
    whole = (_WHOLE, title_block) if step is None and not draft else None
    kept = labels.parts.get(whole) if whole is not None else None
    if isinstance(kept, Sheet):
        return kept  # built already on this layout (to count its crowded labels, or for an earlier page)
    layers: dict[str, list[Item]] = {name: [] for name in LAYERS}
    requests: list[Request] = []
    mech_panel = layout.panel("mechanism")
    assert mech_panel is not None
    parts = labels.parts
    if "mechanism" not in parts:  # the parts every sheet of the layout draws alike, made once
        parts["mechanism"] = mechanism_items(solution, mech_panel)
        parts[higher_pairs_layer.LAYER] = higher_pairs_layer.higher_pair_items(solution, mech_panel)
        parts[centers_layer.LAYER] = centers_layer.centers_items(solution, mech_panel, layout.panel("centers"))
        parts["headings"] = _headings(solution, layout)
    for name in ("mechanism", higher_pairs_layer.LAYER):
        items, reqs = parts[name]
        layers[name] += items
        requests += reqs
    for figure in layout.figures:
        panel = layout.panel(figure.kind)
        assert panel is not None
        drawing = parts.get(figure.kind)
        if drawing is None:
            drawing = parts[figure.kind] = FigureDrawing(figure, panel)
        key = (figure.kind, drawing.stage(step))
        if key not in parts:
            parts[key] = drawing.at(step)
        items, reqs = parts[key]
        layers[f"{figure.kind}-polygon"] += items
        requests += reqs
    items, reqs = parts[centers_layer.LAYER]
    layers[centers_layer.LAYER] += items
    requests += reqs
    headings, bars = parts["headings"]
    layers["title"] += _frame_items(layout) + headings + (_title_items(solution, layout, step) if title_block else [])
    layers["scales"] += bars
    if draft:
        labelled = draft_place(requests, labels)
    else:
        labelled = place(requests, [item for name in LAYERS for item in layers[name]], labels)
    for name, placed in labelled.items():
        layers[name] += placed
    title = solution.scene.title if step is None else f"{solution.scene.title}: step {step}"
    sheet = Sheet(layout.width, layout.height, title, tuple(Layer(name, tuple(layers[name])) for name in LAYERS))
    if whole is not None:
        labels.parts[whole] = sheet
    return sheet


_WHOLE = "whole sheet"
"""The key in ``LabelCache.parts`` of the whole drawing's sheet (with and without its title block's text): built
once per layout, whether to count its crowded labels (``crowded``), to draw it or to show it on a handout's page."""


def step_count(solution: Solution) -> int:
    """The steps ``kinepoly solve --steps`` numbers: the polygons' construction, then the Kennedy steps."""
    return len(solution.steps) + (len(solution.centers.steps) if solution.centers is not None else 0)


def step_sheets(solution: Solution, paper: str | tuple[float, float] = "A4") -> list[Sheet]:
    """One sheet per step (``step_count``), all on the layout of the whole drawing; a Kennedy step's sheet shows
    the whole construction with that step in its title block."""
    layout = layout_sheet(solution, paper)
    return [build_sheet(solution, paper, step=n, layout=layout) for n in range(1, step_count(solution) + 1)]
