"""A handout builds its drawing once: the whole drawing's labels placed once on the paper chosen (the sheet built
to count its crowded labels is the answers page's drawing), each other page built once; a frame with a band of
text laid out from the frame without one; a paper too small for the text told by the first page too long."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from tests.render.builds import chain, counted, four_bar

import kinepoly.handout.build as build_module
from kinepoly.handout.band import band_height
from kinepoly.handout.build import handout_sheets
from kinepoly.handout.drawing import GAP_MM, band_frame, scales_of
from kinepoly.handout.html import handout_html
from kinepoly.present.catalogue import load_catalogue
from kinepoly.render.sheet import MARGIN_MM, readable_values
from kinepoly.solution import Solution


@pytest.mark.parametrize(("make", "layouts"), [(lambda: chain(7), 3), (four_bar, 5)], ids=["chain-7", "four-bar"])
def test_a_handout_builds_its_drawing_once(monkeypatch: pytest.MonkeyPatch, make: Callable[[], Solution],
                                           layouts: int) -> None:
    """The PDF's drawing of the chain on A4 (its text does not fit there), on A3 and on A3 shortened for the band
    of text (the four-bar's on A4, twice shortened until its band settles, on A3 and on A3 shortened)."""
    solution = make()
    say = load_catalogue("en")
    counts = counted(monkeypatch)
    _, sheets = handout_sheets(solution, say, "A4")
    assert counts == {"placed": len(sheets), "layouts": layouts}
    counts.update(placed=0, layouts=0)
    handout, _ = handout_html(solution, say, "A4")  # its drawing on A4 without a band: one layout
    assert counts == {"placed": len(handout.pages), "layouts": 1}


def test_a_page_too_small_for_the_text_is_told_by_the_first_page_too_long(monkeypatch: pytest.MonkeyPatch) -> None:
    """A4 cannot hold the text of the chain's problem page (its first): the other pages' text is not set on A4
    to find that out; the reason, when asked, names the longest text (every page's measured then)."""
    solution = chain(7)
    say = load_catalogue("en")
    a4 = (297.0, 210.0)
    readable = readable_values(solution, a4)
    measured: list[object] = []

    def measuring(page: object, *args: object) -> float:
        measured.append(page)
        return band_height(page, *args)  # type: ignore[arg-type]

    monkeypatch.setattr(build_module, "band_height", measuring)
    why = build_module._frame_for(solution, say, a4, a4, readable)
    assert callable(why)
    assert len(measured) == 1
    frame = band_frame(solution, a4, 0.0, a4, readable)
    pages = build_module.handout_content(solution, say, scales_of(frame.layout)).pages
    assert measured[0] == pages[0]
    inner = a4[0] - 2 * (MARGIN_MM + GAP_MM)
    longest = max(band_height(page, inner, build_module.drawn_kinds(frame), say) for page in pages)
    assert longest > build_module._MOST_BAND * (a4[1] - 2 * MARGIN_MM)
    assert why() == f"the handout's text needs {longest:.0f} mm of the page's 210"
    assert len(measured) == len(pages)
