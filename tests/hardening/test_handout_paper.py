"""Issue 15's drawing and handout part: a handout never fails for want of room, and its labels are placed once.

A chain too long for A4 gets the next larger A paper, said on every page and on stderr; the
labels of the parts that do not change from page to page (the mechanism, the circle diagram)
are placed once per handout (``render.labels.LabelCache``) with the same result as placing
them anew on each page. The times are the benchmark's (benchmarks/scaling.py), not asserted here.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from msgspec.structs import replace
from tests.scenes import EXAMPLES

from kinepoly.bench.chain import chain_text
from kinepoly.cli import main
from kinepoly.handout import handout_sheets, load_catalogue
from kinepoly.handout.build import handout_content
from kinepoly.handout.drawing import band_frame, drawing_layers
from kinepoly.render.labels import LabelCache
from kinepoly.render.layout import paper_size
from kinepoly.render.primitives import Sheet, Text
from kinepoly.render.sheet import build_sheet, layout_sheet, step_count, step_sheets
from kinepoly.scene.loader import load_scene, loads_scene
from kinepoly.solution import solve


def _notes(sheet: Sheet) -> list[str]:
    return ["".join(r.text for r in item.runs) for layer in sheet.layers for item in layer.items
            if isinstance(item, Text) and item.role == "paper note"]


def test_the_10_loop_handout_on_a4_takes_a_larger_paper_and_says_so() -> None:
    solution = solve(loads_scene(chain_text(10), "chain-10.toml"))
    handout, sheets = handout_sheets(solution, load_catalogue("en"), "A4")
    assert handout.paper in ("A3", "A2", "A1", "A0")
    assert (sheets[0].width, sheets[0].height) == paper_size(handout.paper)
    assert len(handout.notes) == 1 and handout.paper in handout.notes[0] and "A4" in handout.notes[0]
    assert all(_notes(sheet) == list(handout.notes) for sheet in sheets)


def test_a_handout_that_fits_keeps_its_paper_and_says_nothing() -> None:
    solution = solve(load_scene(EXAMPLES / "slider-crank.toml"))  # the four-bar's polygons at their scales need A3
    handout, sheets = handout_sheets(solution, load_catalogue("en"), "A4")
    assert handout.paper == "A4" and handout.notes == ()
    assert not any(_notes(sheet) for sheet in sheets)


def test_kinepoly_handout_of_a_long_chain_on_a4_exits_0_and_reports_the_paper(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    scene = tmp_path / "chain.toml"
    scene.write_text(chain_text(5), encoding="utf-8")
    assert main(["handout", str(scene), "--html", str(tmp_path / "h.html"), "-o", str(tmp_path / "h.pdf"),
                 "--paper", "A4"]) == 0
    err = capsys.readouterr().err
    assert "A4" in err and any(f"Printed on {name}" in err for name in ("A3", "A2", "A1", "A0"))
    assert (tmp_path / "h.pdf").stat().st_size > 0 and (tmp_path / "h.html").stat().st_size > 0


@pytest.mark.parametrize("name", ["centers-six-bar", "slider-crank"])
def test_labels_placed_once_per_handout_are_those_placed_anew_on_each_page(name: str) -> None:
    """The shared cache changes nothing on the fixed parts (the mechanism, the circle diagram): every page's as
    with a cache of its own. (A polygon's labels are kept from the page before:
    tests/render/test_render_labels_once.py.)"""
    solution = solve(load_scene(EXAMPLES / f"{name}.toml"))
    say = load_catalogue("en")
    frame = band_frame(solution, paper_size("A4"), 20.0)
    pages = handout_content(solution, say, {p.name: p.scale for p in frame.layout.panels}).pages
    shared = [drawing_layers(solution, frame, page.drawing, say) for page in pages]
    alone = [drawing_layers(solution, replace(frame, labels=LabelCache()), page.drawing, say) for page in pages]
    fixed = ("mechanism", "instant-centers", "title", "scales")
    assert [{k: p[k] for k in fixed} for p in shared] == [{k: p[k] for k in fixed} for p in alone]


def test_step_sheets_with_the_shared_cache_are_the_sheets_built_alone() -> None:
    solution = solve(load_scene(EXAMPLES / "centers-six-bar.toml"))
    layout = layout_sheet(solution, "A4")
    alone = [build_sheet(solution, "A4", step=n, layout=layout) for n in range(1, step_count(solution) + 1)]
    assert step_sheets(solution, "A4") == alone
