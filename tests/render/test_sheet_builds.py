"""Laying out a sheet builds it once per paper tried, to count its crowded labels (a chain of five loops tries
A4 then A3, and keeps A4): the count of a paper is not built again when the next paper is compared with it.

The whole drawing is built once per layout: the sheet built to count its crowded labels is the one drawn (``kinepoly
draw``) or shown on a handout's answers page, and a handout's frame with a band is laid out from the frame without
one it has already. The builds are counted as label placements (``render.labels.place``, once per sheet built) and
the layouts as ``render.sheet._layout_on`` calls."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

import kinepoly.render.sheet as sheet_module
from kinepoly.bench.chain import chain_text
from kinepoly.handout.build import handout_sheets
from kinepoly.handout.html import handout_html
from kinepoly.present.catalogue import load_catalogue
from kinepoly.render.labels import place
from kinepoly.scene.loader import load_scene, loads_scene
from kinepoly.solution import Solution, solve

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_each_paper_tried_is_built_once(monkeypatch: pytest.MonkeyPatch) -> None:
    solution = solve(loads_scene(chain_text(5), "chain-5.toml"))
    built: list[tuple[float, float]] = []
    build = sheet_module.build_sheet

    def counting(*args: object, **kwargs: object) -> object:
        built.append(args[1])  # type: ignore[arg-type]
        return build(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(sheet_module, "build_sheet", counting)
    sheet_module.layout_sheet(solution, "A4")
    assert len(built) == len(set(built)) == 2  # A4 and A3, each built once


def _counted(monkeypatch: pytest.MonkeyPatch) -> dict[str, int]:
    """Counters of the label placements and the layouts made, from now on."""
    counts = {"placed": 0, "layouts": 0}

    def counter(name: str, work: Callable[..., object]) -> Callable[..., object]:
        def counting(*args: object, **kwargs: object) -> object:
            counts[name] += 1
            return work(*args, **kwargs)
        return counting

    monkeypatch.setattr(sheet_module, "place", counter("placed", place))
    monkeypatch.setattr(sheet_module, "_layout_on", counter("layouts", sheet_module._layout_on))
    return counts


def _chain(loops: int, find: str | None = None) -> Solution:
    return solve(loads_scene(chain_text(loops, find=find), f"chain-{loops}.toml"))


def _four_bar() -> Solution:
    return solve(load_scene(EXAMPLES / "four-bar.toml"))


@pytest.mark.parametrize(("make", "papers"), [(lambda: _chain(7, find=""), 2), (_four_bar, 1)],
                         ids=["chain-7", "four-bar"])
def test_the_drawing_is_built_once(monkeypatch: pytest.MonkeyPatch, make: Callable[[], Solution],
                                   papers: int) -> None:
    solution = make()
    counts = _counted(monkeypatch)
    sheet = sheet_module.build_sheet(solution, "A4")  # a chain of seven loops, every point asked: A3, not A4
    assert counts == {"placed": 1, "layouts": papers}  # built on A3 to count its crowded labels, then drawn
    assert sheet_module.build_sheet(solution, "A4", layout=sheet_module.layout_sheet(solution, "A4")) == sheet


@pytest.mark.parametrize(("make", "layouts"), [(lambda: _chain(7), 3), (_four_bar, 5)], ids=["chain-7", "four-bar"])
def test_a_handout_builds_its_drawing_once(monkeypatch: pytest.MonkeyPatch, make: Callable[[], Solution],
                                           layouts: int) -> None:
    """The PDF's drawing of the chain on A4 (its text does not fit there), on A3 and on A3 shortened for the band
    of text (the four-bar's on A4, twice shortened until its band settles, on A3 and on A3 shortened), its labels
    placed once on the paper chosen, then each page but the answers page (the whole drawing, built already)."""
    solution = make()
    say = load_catalogue("en")
    counts = _counted(monkeypatch)
    _, sheets = handout_sheets(solution, say, "A4")
    assert counts == {"placed": len(sheets), "layouts": layouts}
    counts.update(placed=0, layouts=0)
    handout, _ = handout_html(solution, say, "A4")  # its drawing on A4 without a band: one layout
    assert counts == {"placed": len(handout.pages), "layouts": 1}
