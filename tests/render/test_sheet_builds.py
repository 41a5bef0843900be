"""Laying out a sheet builds it once per paper tried, to count its crowded labels (a chain of five loops tries
A4 then A3, and keeps A4): the count of a paper is not built again when the next paper is compared with it."""

from __future__ import annotations

import pytest

import kinepoly.render.sheet as sheet_module
from kinepoly.bench.chain import chain_text
from kinepoly.scene.loader import loads_scene
from kinepoly.solution import solve


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
