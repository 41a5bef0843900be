"""Gear ratio columns of a sweep: -r2/r3 for an external pair, +r2/r3 inside a ring, Willis' formula
for a planetary train, derived here; and every row against ``kinepoly.solve`` at its input."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.sweep_support import compare_row, row_scene

import kinepoly
from kinepoly.sweep import sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _pair(r2: float, r3: float, internal: bool, angle: float, omega: float, alpha: float) -> str:
    distance = abs(r2 - r3) if internal else r2 + r3
    return f"""
title = "gears"
input = {{ link = "2", angle = {angle!r}, omega = {omega!r}, alpha = {alpha!r} }}
[links]
1 = {{ points = {{ O2 = [0, 0], O3 = [{distance!r}, 0] }} }}
2 = {{ points = {{ O2 = [0, 0] }} }}
3 = {{ points = {{ O3 = [0, 0], E = [{r3 / 2!r}, 0] }} }}
[[gears]]
links = ["2", "3"]
pitch = [{{ center = "O2", radius = {r2!r} }}, {{ center = "O3", radius = {r3!r} }}]
internal = {"true" if internal else "false"}
[find]
velocity = ["E"]
"""


def test_gear_pair_ratio_is_minus_r2_over_r3_at_every_row() -> None:
    result = sweep(kinepoly.load_scene(EXAMPLES / "gear-pair.toml"), steps=360)
    ratio = result.column("ratio_3_2")
    assert ratio.valid.all()
    assert np.max(np.abs(ratio.values + 40.0 / 60.0)) <= 4e-16


@settings(max_examples=40, deadline=None)
@given(st.floats(5.0, 80.0), st.floats(5.0, 80.0), st.booleans(), st.floats(-180.0, 180.0),
       st.floats(-50.0, 50.0).filter(lambda w: abs(w) > 1e-3), st.floats(-20.0, 20.0))
def test_gear_ratio_random(r2: float, r3: float, internal: bool, angle: float, omega: float, alpha: float) -> None:
    if internal and abs(r2 - r3) < 1.0:
        r3 = r2 + 5.0
    result = sweep(kinepoly.loads_scene(_pair(r2, r3, internal, angle, omega, alpha)), steps=12)
    want = (r2 / r3) if internal else -(r2 / r3)
    assert np.max(np.abs(result.column("ratio_3_2").values - want)) <= 1e-14 * abs(want)


def test_planetary_ratios_by_willis() -> None:
    # arm 2 carries the planet 3 (r = 20) round the fixed sun (r = 30) and inside the ring 4 (r = 70);
    # relative to the arm the train is an ordinary one: (w3 - w2) / (0 - w2) = -30 / 20 and
    # (w4 - w2) / (w3 - w2) = +20 / 70, so w3 / w2 = 1 + 30/20 and w4 / w2 = 1 + 30/70
    result = sweep(kinepoly.load_scene(EXAMPLES / "planetary.toml"), steps=360)
    assert np.max(np.abs(result.column("ratio_3_2").values - 2.5)) <= 1e-14
    assert np.max(np.abs(result.column("ratio_4_2").values - (1.0 + 30.0 / 70.0))) <= 1e-14
    assert np.max(np.abs(result.column("ratio_4_3").values - (1.0 + 30.0 / 70.0) / 2.5)) <= 1e-14
    assert not any(c.name.startswith("ratio_") and "1" in c.name.split("_")[1:] for c in result.columns)


def test_a_gear_standing_still_leaves_its_ratios_empty() -> None:
    result = sweep(kinepoly.loads_scene(_pair(30.0, 45.0, False, 10.0, 0.0, 0.0)), steps=8)
    assert not result.column("ratio_3_2").valid.any()


def test_every_gear_row_equals_the_solve_at_its_input() -> None:
    # a solve rolls the gears from their reference mesh the shorter way, a sweep on from the scene's
    # input: they place the gears alike within half a turn of the input from the reference
    for name in ("gear-pair", "planetary", "rack-pinion"):
        text = (EXAMPLES / f"{name}.toml").read_text()
        result = sweep(kinepoly.loads_scene(text), steps=24)
        rows = [row for row in range(result.rows) if result.input.values[row] < 180.0]
        worst = max(compare_row(text, result, row) for row in rows)
        assert worst <= 1e-10, (name, worst)
        for row in rows:
            scene = kinepoly.loads_scene(row_scene(text, result, row))
            solved = kinepoly.to_json(kinepoly.solve(scene)).get("links", {})
            solved["2"] = {"omega": scene.input.omega}  # type: ignore[union-attr]  # the input (link 2 in each)
            for col in result.columns:
                if col.kind == "ratio":
                    gear, over = col.name.split("_")[1:]
                    want = solved[gear]["omega"] / solved[over]["omega"]
                    assert abs(col.values[row] - want) <= 1e-13 * abs(want), (name, col.name, row)
