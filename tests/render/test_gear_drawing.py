"""Pitch circles and a rack's pitch line on the layer higher-pairs, at the gears' centres and radii, the
pitch point marked where the two touch."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import kinepoly
from kinepoly.render.primitives import Circle
from kinepoly.render.primitives import Path as Line
from kinepoly.render.sheet import build_sheet, layout_sheet

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _layer(name: str):  # type: ignore[no-untyped-def]
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    layout = layout_sheet(solution)
    sheet = build_sheet(solution, (layout.width, layout.height), layout=layout)
    return solution, {i.role: i for i in sheet.layer("higher-pairs").items}, layout.panel("mechanism")


def _circle(item: object) -> tuple[complex, float]:
    assert isinstance(item, Line) and item.closed
    z = np.array([complex(*p) for p in item.points])
    center = complex(z.mean())
    assert float(np.ptp(np.abs(z - center))) < 1e-9
    return center, float(np.abs(z - center).mean())


@pytest.mark.parametrize(("name", "circles"), [
    ("gear-pair", {"pitch circle 23 2": ((0.0, 0.0), 40.0), "pitch circle 23 3": ((100.0, 0.0), 60.0)}),
    ("planetary", {"pitch circle 13 1": ((0.0, 0.0), 30.0), "pitch circle 34 4": ((0.0, 0.0), 70.0)}),
])
def test_pitch_circles_at_the_centres_and_radii(name: str,
                                                circles: dict[str, tuple[tuple[float, float], float]]) -> None:
    solution, items, panel = _layer(name)
    for role, (center, radius) in circles.items():
        at, r = _circle(items[role])
        assert abs(at - complex(*panel.paper(center))) < 1e-9
        assert r == pytest.approx(radius * panel.scale, rel=2e-4)  # a polygon of many sides
    for pair, contact in solution.contacts.items():
        dot = items[f"contact P{pair}"]
        assert isinstance(dot, Circle) and dot.center == pytest.approx(panel.paper(contact.point), abs=1e-9)


def test_planet_pitch_circle_turns_round_with_the_arm() -> None:
    solution, items, panel = _layer("planetary")
    c = solution.position("C")  # the planet's centre, 50 from O at the arm's 30 degrees
    assert c == pytest.approx((50 * np.cos(np.radians(30)), 50 * np.sin(np.radians(30))), abs=1e-12)
    for role in ("pitch circle 13 3", "pitch circle 34 3"):
        at, r = _circle(items[role])
        assert abs(at - complex(*panel.paper(c))) < 1e-9 and r == pytest.approx(20.0 * panel.scale, rel=2e-4)


def test_rack_pitch_line_through_the_pitch_point() -> None:
    solution, items, panel = _layer("rack-pinion")
    line = items["pitch line 23 3"]
    assert isinstance(line, Line)
    (ax, ay), (bx, by) = line.points
    p = panel.paper(solution.contacts["23"].point)
    assert ay == pytest.approx(by) == pytest.approx(p[1])  # horizontal, 25 below the pinion's centre
    assert solution.contacts["23"].point[1] == pytest.approx(-25.0, abs=1e-12)
    assert ax < p[0] < bx
