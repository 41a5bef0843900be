"""A solution in, the handout out: its pages' content, then the sheets of the PDF or the HTML page.

The content (``content.Handout``) is the same for both: the problem, a page per construction
step (and per Kennedy step), the answers. The PDF puts each page's text in a band under its
drawing; the scales the text quotes are the ones drawn, so the content is written again if
making room for the band changed a scale.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from msgspec.structs import replace

from kinepoly.errors import HandoutError
from kinepoly.handout.answers import answers_page
from kinepoly.handout.band import band_height, band_items
from kinepoly.handout.content import Handout, Page
from kinepoly.handout.drawing import GAP_MM, Frame, band_frame, blank_sheet, drawing_layers, page_frame_items, scales_of
from kinepoly.handout.problem import problem_page
from kinepoly.handout.step_pages import construction_pages
from kinepoly.present.catalogue import Catalogue
from kinepoly.render.labels import FEW
from kinepoly.render.layout import larger_papers, paper_name, paper_size
from kinepoly.render.primitives import Item, Sheet, Text
from kinepoly.render.sheet import GAIN as _GAIN
from kinepoly.render.sheet import MARGIN_MM, build_sheet, readable_values, roomy
from kinepoly.render.style import NOTE_INK
from kinepoly.render.text import plain_runs, runs_box
from kinepoly.solution import Solution

if TYPE_CHECKING:
    from kinepoly.loops.rates import LoopSolution

__all__ = ["crowded_labels", "drawn_kinds", "handout_content", "handout_sheets"]

_MOST_BAND = 0.55
"""The band of text may take at most this share of the page's height."""


def handout_content(solution: Solution, say: Catalogue, scales: Mapping[str, float],
                    loops: LoopSolution | None = None) -> Handout:
    """Every page's content; ``scales`` as drawn (``mechanism``, ``velocity``, ``acceleration``); with ``loops``
    the loop-closure method's pages after the answers."""
    from kinepoly.handout.loop_pages import loop_pages

    pages = (problem_page(solution, say, scales), *construction_pages(solution, say, scales),
             answers_page(solution, say, scales), *(loop_pages(loops, say) if loops is not None else ()))
    return Handout(solution.scene.title, say.code, pages)


def drawn_kinds(frame: Frame) -> list[str]:
    """The kinds of vector the polygons draw (for the legend)."""
    return sorted({v.term for figure in frame.layout.figures for v in figure.vectors})


_PAPER_NOTE = ("Printed on {paper}: the handout does not fit the {asked} asked for (its text and drawing need more "
               "room).")
"""The note on every page when a larger paper was chosen (the catalogue's ``page.larger_paper`` when it has one)."""


def _paper(paper: str | tuple[float, float]) -> tuple[float, float]:
    if isinstance(paper, tuple):
        return paper
    try:
        return paper_size(paper)
    except ValueError as error:
        raise HandoutError(str(error)) from None


def _paper_name(paper: str | tuple[float, float]) -> str:
    if isinstance(paper, tuple):
        return paper_name(paper)
    return paper.strip().upper() if paper.strip().lower()[:1] == "a" else paper.strip()


def _frame_for(solution: Solution, say: Catalogue, size: tuple[float, float], asked: tuple[float, float],
               readable: dict[str, Any],
               loops: LoopSolution | None = None) -> tuple[Frame, Handout] | Callable[[], str]:
    """The frame and the content on a page of ``size`` at the scales of the paper ``asked``, or why they do not fit
    (told when asked: a page whose text is too long decides it, the longest is measured only for the message)."""
    width, height = size
    inner = width - 2 * (MARGIN_MM + GAP_MM)
    frame = band_frame(solution, (width, height), 0.0, asked, readable)
    whole = frame.layout  # the drawing on the whole page, where each frame with a band starts
    scales = scales_of(frame.layout)
    handout = handout_content(solution, say, scales, loops)
    heights: dict[Page, float] = {}  # a page's text is set once per paper, however often the scales settle

    def height_of(page: Page) -> float:
        if page not in heights:
            heights[page] = band_height(page, inner, drawn_kinds(frame), say)
        return heights[page]

    most = _MOST_BAND * (height - 2 * MARGIN_MM)
    for _ in range(6):
        if any(height_of(page) > most for page in handout.pages):  # the problem page's, first, on a long chain
            pages = handout.pages
            return lambda: f"the handout's text needs {max(map(height_of, pages)):.0f} mm of the page's {height:.0f}"
        need = max(height_of(page) for page in handout.pages)
        grown = frame.band < need  # else the frame is the one a band of its height makes: laid out once
        if grown:
            frame = band_frame(solution, (width, height), need, asked, readable, whole)
        if scales_of(frame.layout) != scales:
            scales = scales_of(frame.layout)
            handout = handout_content(solution, say, scales, loops)
            continue
        if grown:
            continue
        return frame, handout
    return lambda: "the handout's layout does not settle on this paper"


def _choose(solution: Solution, say: Catalogue, size: tuple[float, float],
            asked: str, loops: LoopSolution | None = None) -> tuple[Frame, Handout, str]:
    """The frame and content on the paper asked or the smallest larger A paper that holds them, and its name.

    A paper holds the handout when its text's band fits, the drawing is ``roomy`` (each polygon
    at its scale, the mechanism large enough) and every label of the whole drawing finds a free
    place; a larger paper is tried only while it gives crowded labels more room (fewer of them
    without a free place). When no paper up to A0 is roomy, the first whose band fits (the
    polygons' scales reduced there, as the drawing says).
    """
    papers = [(asked, size), *larger_papers(size)]
    readable = readable_values(solution, size)  # the scales are the paper asked's on every paper tried
    fallback: tuple[Frame, Handout, str] | None = None
    best: tuple[Frame, Handout, str] | None = None
    why: Callable[[], str] = str
    for name, paper in papers:
        chosen = _frame_for(solution, say, paper, size, readable, loops)
        if callable(chosen):
            why = chosen
            if best is None:
                continue
            break
        fallback = fallback or (*chosen, name)
        if not roomy(solution, chosen[0].layout):
            if best is None:
                continue
            break
        if best is not None and crowded_labels(solution, chosen[0]) > _GAIN * crowded_labels(solution, best[0]):
            break  # little room gained for the labels: they crowd where the polygon does, at any paper
        best = (*chosen, name)
        if not 0 < crowded_labels(solution, chosen[0]) <= FEW:
            break  # every label free, or so many crowded that their polygon's points crowd, at any paper
    fallback = best or fallback
    if fallback is None:
        raise HandoutError(f"{why()} even on A0; the handout cannot be laid out")  # a text longer than A0
    return fallback


def crowded_labels(solution: Solution, frame: Frame) -> int:
    """How many labels of the whole drawing find no free place near their point on ``frame`` (set out further with
    a leader, or crowded: ``render.labels.LabelCache.set_out``). They stay placed for its pages: each page shows a
    label where the whole drawing has it and places only those that differ."""
    build_sheet(solution, frame.paper, layout=frame.layout, labels=frame.labels, title_block=False)
    return len(frame.labels.set_out)


def _note_items(frame: Frame, notes: tuple[str, ...]) -> list[Item]:
    """The notes in small type in the top margin, at the border's right end."""
    items: list[Item] = []
    y = frame.height - MARGIN_MM + 1.6
    for note in notes:
        runs = plain_runs(note, 2.4)
        x1 = runs_box(runs)[2]
        items.append(Text(frame.width - MARGIN_MM - x1, y, runs, NOTE_INK, "paper note"))
        y += 3.2
    return items


def handout_sheets(solution: Solution, say: Catalogue, paper: str | tuple[float, float] = "A4",
                   loops: LoopSolution | None = None) -> tuple[Handout, list[Sheet]]:
    """The handout's content and a sheet per page, the text in a band under the drawing.

    When the page asked for is too small (the text's band and the drawing do not both fit), the
    next larger A paper that holds them is taken (A3, A2, ... A0, in the page's orientation), and
    every page and ``Handout.notes`` say so; the drawing reduces its polygons' scales or puts them
    in cells of their own (``render.layout``) before that. Never fails for want of room. With ``loops``
    (``kinepoly.loops.solve_loops``) a page per loop of the loop-closure method follows the answers.
    """
    size = _paper(paper)
    asked = _paper_name(paper)
    frame, handout, name = _choose(solution, say, size, asked, loops)
    notes: tuple[str, ...] = ()
    if name != asked:
        template = say.messages.get("page.larger_paper", _PAPER_NOTE)
        notes = (template.format(paper=name, asked=asked),)
    handout = replace(handout, paper=name, notes=notes)
    width = frame.width
    kinds = drawn_kinds(frame)
    rect = (MARGIN_MM + GAP_MM, MARGIN_MM, width - MARGIN_MM - GAP_MM, MARGIN_MM + frame.band)
    crowded_labels(solution, frame)  # the whole drawing's labels first (done already when the paper was chosen)
    sheets = []
    for page in handout.pages:
        layers = drawing_layers(solution, frame, page.drawing, say)
        layers["title"] += page_frame_items(frame) + band_items(page, rect, kinds, say) + _note_items(frame, notes)
        sheets.append(blank_sheet(frame, f"{solution.scene.title}: {page.heading}", layers))
    return handout, sheets
