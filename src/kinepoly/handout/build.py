"""A solution in, the handout out: its pages' content, then the sheets of the PDF or the HTML page.

The content (``content.Handout``) is the same for both: the problem, a page per construction
step (and per Kennedy step), the answers. The PDF puts each page's text in a band under its
drawing; the scales the text quotes are the ones drawn, so the content is written again if
making room for the band changed a scale.
"""

from __future__ import annotations

from collections.abc import Mapping

from kinepoly.errors import HandoutError
from kinepoly.handout.answers import answers_page
from kinepoly.handout.band import band_height, band_items
from kinepoly.handout.content import Handout
from kinepoly.handout.drawing import GAP_MM, Frame, band_frame, blank_sheet, drawing_layers, page_frame_items, scales_of
from kinepoly.handout.problem import problem_page
from kinepoly.handout.step_pages import construction_pages
from kinepoly.present.catalogue import Catalogue
from kinepoly.render.layout import paper_size
from kinepoly.render.primitives import Sheet
from kinepoly.render.sheet import MARGIN_MM
from kinepoly.solution import Solution

__all__ = ["drawn_kinds", "handout_content", "handout_sheets"]

_MOST_BAND = 0.55
"""The band of text may take at most this share of the page's height."""


def handout_content(solution: Solution, say: Catalogue, scales: Mapping[str, float]) -> Handout:
    """Every page's content; ``scales`` as drawn (``mechanism``, ``velocity``, ``acceleration``)."""
    pages = (problem_page(solution, say, scales), *construction_pages(solution, say, scales),
             answers_page(solution, say, scales))
    return Handout(solution.scene.title, say.code, pages)


def drawn_kinds(frame: Frame) -> list[str]:
    """The kinds of vector the polygons draw (for the legend)."""
    return sorted({v.term for figure in frame.layout.figures for v in figure.vectors})


def _paper(paper: str | tuple[float, float]) -> tuple[float, float]:
    if isinstance(paper, tuple):
        return paper
    try:
        return paper_size(paper)
    except ValueError as error:
        raise HandoutError(str(error)) from None


def handout_sheets(solution: Solution, say: Catalogue,
                   paper: str | tuple[float, float] = "A4") -> tuple[Handout, list[Sheet]]:
    """The handout's content and a sheet per page, the text in a band under the drawing."""
    width, height = _paper(paper)
    inner = width - 2 * (MARGIN_MM + GAP_MM)
    frame = band_frame(solution, (width, height), 0.0)
    scales = scales_of(frame.layout)
    handout = handout_content(solution, say, scales)
    for _ in range(6):
        need = max(band_height(page, inner, drawn_kinds(frame), say) for page in handout.pages)
        if need > _MOST_BAND * (height - 2 * MARGIN_MM):
            raise HandoutError(f"the handout's text needs {need:.0f} mm of the page's {height:.0f}; choose a larger "
                               f"--paper (e.g. A3)")
        if frame.band < need or scales_of(frame.layout) != scales:
            frame = band_frame(solution, (width, height), max(need, frame.band))
            if scales_of(frame.layout) != scales:
                scales = scales_of(frame.layout)
                handout = handout_content(solution, say, scales)
            continue
        break
    else:
        raise HandoutError("the handout's layout does not settle on this paper; choose another --paper")
    kinds = drawn_kinds(frame)
    rect = (MARGIN_MM + GAP_MM, MARGIN_MM, width - MARGIN_MM - GAP_MM, MARGIN_MM + frame.band)
    sheets = []
    for page in handout.pages:
        layers = drawing_layers(solution, frame, page.drawing, say)
        layers["title"] += page_frame_items(frame) + band_items(page, rect, kinds, say)
        sheets.append(blank_sheet(frame, f"{solution.scene.title}: {page.heading}", layers))
    return handout, sheets
