"""``kinepoly bench SCENE --family N``: the family sweep against one sweep per member and the 50-digit reference."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from tests.cli_support import run

import kinepoly
from kinepoly.bench.family import family_points, run_family

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_the_members_are_each_link_times_a_factor_of_its_own() -> None:
    scene = kinepoly.load_scene(EXAMPLES / "four-bar.toml")
    points, slides = family_points(scene, 5, 0.1, 3)
    assert points.keys() == {f"{p.name}@{link.name}" for link in scene.links for p in link.points}
    for link in scene.links:
        factors = None
        for p in link.points:
            if p.local == (0.0, 0.0):
                assert np.array_equal(points[f"{p.name}@{link.name}"], np.zeros((5, 2)))
                continue
            k = np.abs(points[f"{p.name}@{link.name}"]).max(axis=1) / max(abs(p.local[0]), abs(p.local[1]))
            assert ((0.9 <= k) & (k <= 1.1)).all() and np.ptp(k) > 0.0
            assert factors is None or np.allclose(k, factors, rtol=1e-15)
            factors = k
    again, _ = family_points(scene, 5, 0.1, 3)
    assert all(np.array_equal(points[key], again[key]) for key in points)
    assert slides == {}


def test_a_slide_line_takes_its_guides_factor() -> None:
    """The shaper's ram slides on the frame along y = 430: its line moves with the frame's points (A0 = [0, 150])."""
    scene = kinepoly.load_scene(EXAMPLES / "shaper.toml")
    points, slides = family_points(scene, 4, 0.1, 1)
    frame = points["A0@1"][:, 1] / 150.0
    assert np.allclose(slides["16"][:, 1] / 430.0, frame, rtol=1e-15) and np.ptp(frame) > 0.0
    assert np.array_equal(slides["43"], np.zeros((4, 2)))  # the slot's line through the lever's pivot


@pytest.mark.parametrize("name", ["four-bar", "shaper"])
def test_the_family_agrees_with_the_loop_and_the_reference(name: str) -> None:
    result = run_family(kinepoly.load_scene(EXAMPLES / f"{name}.toml"), 6, 24, rounds=1)
    assert result.batched and result.members == 6 and result.rows == 24
    assert result.agreement <= 1e-12
    assert result.checked >= 10
    assert set(result.errors) >= {"position", "velocity", "acceleration", "omega", "alpha", "angle"}
    assert max(result.errors.values()) <= 1e-13
    assert result.family_s > 0.0 and result.loop_s > 0.0


def test_the_command_prints_json(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "bench", str(EXAMPLES / "slider-crank.toml"), "--family", "3", "--positions", "12",
                       "--json")
    assert code == 0
    data = json.loads(out)
    assert data["members"] == 3 and data["rows"] == 12 and data["batched"] is True
    assert data["agreement"] <= 1e-12 and max(data["errors"].values()) <= 1e-13


def test_the_command_prints_its_lines(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "bench", str(EXAMPLES / "four-bar.toml"), "--family", "2", "--positions", "8")
    assert code == 0
    lines = out.splitlines()
    assert "a family of 2 members" in lines[0] and "kinepoly.sweep_family" in lines[1]
    assert "one sweep per member" in lines[2] and "50-digit reference" in lines[4]


@pytest.mark.parametrize(("argv", "message"), [
    (["--family", "0"], "--family 0: expected at least 1 member"),
    (["--family", "2", "--spread", "1.5"], "--spread 1.5: expected a fraction"),
    (["--family", "2", "--sweep", "5"], "--family: measured on its own; leave out --sweep and --plot"),
])
def test_bad_family_options_say_what_to_change(capsys: pytest.CaptureFixture[str], argv: list[str],
                                               message: str) -> None:
    code, _, err = run(capsys, "bench", str(EXAMPLES / "four-bar.toml"), *argv)
    assert code == 2 and message in err
