"""Each term a drawing shows is drawn as the kind of term it is (issue 24 sections 1 and 2, issue 25).

A tangential term (``a^t_...``, also the sum of two along a triad's line toward its Assur point) is drawn
and listed in the legend as tangential, a sliding term only where a block slides: a mechanism with no
slider and no flat-faced follower has no sliding term in its polygons or its legend.
"""

from __future__ import annotations

from functools import cache

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.render.polygons import polygon_figure
from kinepoly.render.sheet import _drawn_terms
from kinepoly.solution import Solution

NAMES = sorted(p.stem for p in EXAMPLES.glob("*.toml"))


@cache
def _solved(name: str) -> Solution:
    return kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))


def _slides(solution: Solution) -> bool:
    scene = solution.scene
    return bool(scene.sliders) or any(cam.kind == "flat" for cam in scene.cams)


@pytest.mark.parametrize("name", NAMES)
def test_tangential_terms_are_drawn_as_tangential(name: str) -> None:
    solution = _solved(name)
    if solution.acceleration is None:
        return
    figure = polygon_figure(solution, "acceleration")
    for vector in figure.vectors:
        names = vector.label.split(" = ")[-1].split(" + ")
        if all(part.startswith("a^t_") for part in names):
            assert vector.term == "tangential", (vector.label, vector.term)


@pytest.mark.parametrize("name", NAMES)
def test_nothing_is_sliding_where_nothing_slides(name: str) -> None:
    solution = _solved(name)
    if _slides(solution):
        return
    figures = tuple(polygon_figure(solution, kind) for kind in ("velocity", "acceleration")
                    if getattr(solution, kind) is not None)
    drawn = [(v.label, v.term) for f in figures for v in f.vectors if v.term == "sliding"]
    assert not drawn
    assert "sliding" not in _drawn_terms(figures)


def test_the_triad_sheets_list_no_sliding_term() -> None:
    """The examples the issue names (a triad of rods, a floating follower on a roller): the legend lists the
    terms drawn, tangential among them, and no sliding one."""
    for name in ("kc0-six-bar", "triad", "spline-cam-floating-triad"):
        solution = _solved(name)
        assert not _slides(solution)
        figures = tuple(polygon_figure(solution, kind) for kind in ("velocity", "acceleration"))
        assert _drawn_terms(figures) == ["absolute", "relative", "normal", "tangential"], name


def test_a_rolling_contact_is_drawn_as_relative() -> None:
    """Gear trains: the relative acceleration of the two gears' points at a pitch point (along the common normal)
    and of a planet's centre to the point dividing the known gears' tips are relative terms, nothing slides."""
    for name in ("gear-pair", "planetary", "planetary-free-arm", "differential"):
        figure = polygon_figure(_solved(name), "acceleration")
        rolling = [v for v in figure.vectors if v.label.startswith("a_") and "/" in v.label and "=" not in v.label]
        assert rolling, name
        assert all(v.term == "relative" for v in rolling), (name, [(v.label, v.term) for v in rolling])
