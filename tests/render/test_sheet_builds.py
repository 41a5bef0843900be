"""Laying out a sheet builds it once per paper tried, to count its crowded labels (a chain of five loops tries
A4 then A3, and keeps A4): the count of a paper is not built again when the next paper is compared with it.

The whole drawing is built once per layout: the sheet built to count its crowded labels is the one drawn. The
builds are counted as label placements (``render.labels.place``, once per sheet built), the layouts as
``render.sheet._layout_on`` calls (``tests.render.builds``)."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from tests.render.builds import chain, counted, four_bar

import kinepoly.render.sheet as sheet_module
from kinepoly.bench.chain import chain_text
from kinepoly.scene.loader import loads_scene
from kinepoly.solution import Solution, solve


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


@pytest.mark.parametrize(("make", "papers"), [(lambda: chain(7, find=""), 2), (four_bar, 1)],
                         ids=["chain-7", "four-bar"])
def test_the_drawing_is_built_once(monkeypatch: pytest.MonkeyPatch, make: Callable[[], Solution],
                                   papers: int) -> None:
    solution = make()
    counts = counted(monkeypatch)
    sheet = sheet_module.build_sheet(solution, "A4")  # a chain of seven loops, every point asked: A3, not A4
    assert counts == {"placed": 1, "layouts": papers}  # built on the paper kept to count its crowded labels, drawn
    layout = sheet_module.layout_sheet(solution, "A4")
    assert sheet_module.build_sheet(solution, "A4", layout=layout) is sheet_module.build_sheet(solution, "A4",
                                                                                             layout=layout)
    assert sheet_module.build_sheet(solution, "A4", layout=layout) == sheet
