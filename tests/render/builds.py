"""Counting a sheet's builds: the label placements (``render.labels.place``, once per sheet built) and the layouts
(``render.sheet._layout_on``) made while a drawing, its step sheets or a handout are made; the scenes counted."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from tests.scenes import EXAMPLES

import kinepoly.render.sheet as sheet_module
from kinepoly.bench.chain import chain_text
from kinepoly.render.labels import place
from kinepoly.scene.loader import load_scene, loads_scene
from kinepoly.solution import Solution, solve

__all__ = ["chain", "counted", "four_bar"]


def counted(monkeypatch: pytest.MonkeyPatch) -> dict[str, int]:
    """Counters of the label placements (sheets built) and the layouts made, from now on."""
    counts = {"placed": 0, "layouts": 0}

    def counter(name: str, work: Callable[..., object]) -> Callable[..., object]:
        def counting(*args: object, **kwargs: object) -> object:
            counts[name] += 1
            return work(*args, **kwargs)
        return counting

    monkeypatch.setattr(sheet_module, "place", counter("placed", place))
    monkeypatch.setattr(sheet_module, "_layout_on", counter("layouts", sheet_module._layout_on))
    return counts


def chain(loops: int, find: str | None = None) -> Solution:
    """A chain of ``loops`` four-bar loops (``kinepoly.bench.chain``), solved."""
    return solve(loads_scene(chain_text(loops, find=find), f"chain-{loops}.toml"))


def four_bar() -> Solution:
    """The example four-bar, solved."""
    return solve(load_scene(EXAMPLES / "four-bar.toml"))
