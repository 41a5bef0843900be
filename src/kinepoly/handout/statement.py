"""The problem as a quiz question states it: the handout's problem page as HTML, its drawing as a PNG.

The words are the problem page's (``handout.problem.problem_page``, written as the web handout
writes them, ``handout.html.text_html``); the figure is the web handout's drawing of that page
(the mechanism and the empty polygon panels with their poles and scale bars), on the same paper,
at the same scales. A learning platform shows the text and the picture; nothing else is needed.
"""

from __future__ import annotations

import io
from collections.abc import Mapping

from msgspec import Struct

from kinepoly.handout.build import crowded_labels, drawn_kinds
from kinepoly.handout.drawing import blank_sheet, drawing_layers, page_frame_items, scales_of
from kinepoly.handout.html import drawing_frame, text_html
from kinepoly.handout.problem import problem_page
from kinepoly.present.catalogue import Catalogue
from kinepoly.present.scales import A4
from kinepoly.solution import Solution

__all__ = ["FIGURE_DPI", "Statement", "problem_statement"]

FIGURE_DPI = 110
"""The figure's resolution: an A4 drawing is about 1300 pixels wide, readable on a screen, small in a quiz file."""


class Statement(Struct, frozen=True):
    """The problem page's text (HTML), its drawing (PNG bytes) and the scales the text quotes
    (``mechanism``: paper mm per length unit; ``velocity``: kv; ``acceleration``: ka)."""

    html: str
    png: bytes
    scales: Mapping[str, float]


def problem_statement(solution: Solution, say: Catalogue, paper: tuple[float, float] = A4,
                      dpi: int = FIGURE_DPI) -> Statement:
    """The problem of ``solution`` as the handout's problem page gives it, in the catalogue's language."""
    from kinepoly.render.mpl import write_png

    frame = drawing_frame(solution, paper)
    scales = scales_of(frame.layout)
    page = problem_page(solution, say, scales)
    crowded_labels(solution, frame)  # the whole drawing's labels first, as the handout places them
    layers = drawing_layers(solution, frame, page.drawing, say)
    layers["title"] += page_frame_items(frame)
    sheet = blank_sheet(frame, f"{solution.scene.title}: {page.heading}", layers)
    buffer = io.BytesIO()
    write_png(sheet, buffer, dpi)
    return Statement(text_html(page, drawn_kinds(frame), say), buffer.getvalue(), scales)
