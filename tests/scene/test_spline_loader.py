"""A cam's ``profile = { points = ... }`` read and checked: each problem named by file, line and key."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import kinepoly
from kinepoly.errors import SceneError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
CIRCLE = "profile = { circle = { center = [15, 0], radius = 40 } }"
_PROFILE_LINE = 1 + (EXAMPLES / "cam-roller-rocker.toml").read_text().splitlines().index(CIRCLE)
"""The line of the example's profile, which the loader's messages name."""


def _load(points: str) -> None:
    text = (EXAMPLES / "cam-roller-rocker.toml").read_text()
    assert CIRCLE in text
    kinepoly.loads_scene(text.replace(CIRCLE, f"profile = {{ points = {points} }}"), "cam.toml")


def _problems(points: str) -> str:
    with pytest.raises(SceneError) as caught:
        _load(points)
    return str(caught.value)


def _ellipse(n: int) -> str:
    return str([[round(40.0 * math.cos(2 * math.pi * k / n), 9), round(25.0 * math.sin(2 * math.pi * k / n), 9)]
                 for k in range(n)])


def test_a_valid_spline_profile_is_read_onto_the_cam() -> None:
    text = (EXAMPLES / "cam-roller-rocker.toml").read_text().replace(CIRCLE, f"profile = {{ points = {_ellipse(12)} }}")
    cam = kinepoly.loads_scene(text, "cam.toml").cams[0]
    assert cam.is_spline and len(cam.profile_points) == 12
    assert cam.profile_points[3] == pytest.approx((0.0, 25.0), abs=1e-9)
    assert cam.equivalent == ""  # no permanent equivalent link: it is found row by row


@pytest.mark.parametrize(("points", "expected"), [
    ("[[40, 0], [0, 30], [-40, 0]]", "expected at least 4 points [x, y] of a closed curve, got 3 points"),
    ('"round"', 'expected at least 4 points [x, y] of a closed curve, got "round"'),
    ("[[40, 0], [0, 30], [-40, 0], [0, -30], [40, 0]]",
     "cams.1.profile.points.5: the last point repeats the first [40.0, 0.0]; the curve closes by itself"),
    ("[[40, 0], [0, 30], [0, 30], [-40, 0], [0, -30]]", "cams.1.profile.points.3: repeats point 2 [0.0, 30.0]"),
    ("[[40, 0], [0, -30], [-40, 0], [0, 30]]", "the points run clockwise (or enclose no area)"),
    ("[[40, 0], [0, 30], [-40, 0], [0, 30]]", "the points run clockwise (or enclose no area)"),
    ("[[40, 0], [0, 30], [-40, 0], [0]]", "cams.1.profile.points.4: expected [x, y], each a length"),
    ("[[40, 0], [0, 30], [-40, 0], [0, \"x\"]]", "cams.1.profile.points.4.y:"),
])
def test_bad_points_are_named(points: str, expected: str) -> None:
    problems = _problems(points)
    assert expected in problems
    assert f"cam.toml:{_PROFILE_LINE}:" in problems


def test_a_spline_that_crosses_itself_is_refused() -> None:
    # a pentagram: the points of a regular pentagon taken every second one (positive area, but two turns)
    star = [[round(40 * math.cos(math.pi / 2 + 4 * math.pi * k / 5), 9),
             round(40 * math.sin(math.pi / 2 + 4 * math.pi * k / 5), 9)]
            for k in range(5)]
    assert "the spline through these points turns 2 times round instead of once" in _problems(str(star))


def test_circle_and_points_together_are_refused() -> None:
    text = (EXAMPLES / "cam-roller-rocker.toml").read_text().replace(
        CIRCLE, "profile = { circle = { center = [15, 0], radius = 40 }, points = [[1, 0], [0, 1], [-1, 0], [0, -1]] }")
    with pytest.raises(SceneError, match=r"cams\.1\.profile: a profile is a circle or points; expected one of them"):
        kinepoly.loads_scene(text, "cam.toml")
