"""A floating flat-faced follower on a spline cam (``examples/spline-cam-floating-flat.toml``).

The coupler of a four-bar rests its flat face on the cam; the follower reaches the frame only through the
rockers. The references are derived apart from the spline's path through the engine, as for the floating
roller (``test_spline_floating``): the same mechanism with the circle the profile's points were sampled
from, solved exactly (a circle cam's flat face is a permanent slider at the circle's centre); finite
differences of the positions over the input (``test_spline_floating``); the analytic check (``check/``, its own face
constraint); and the contact's velocity condition.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.engine.test_spline_floating import (
    CIRCLE,
    COLUMNS,
    FLAT,
    _guess_at,
    _normal_residual,
    _points,
    _scene,
    follows_the_circle_and_keeps_the_contact,
    refused_with_exit_3,
)

import kinepoly
from kinepoly.sweep import sweep

ROCKERS = (("B", "4", -97 + 45j, 71.49), ("C", "5", -42 + 47j, 71.11))
"""The guessed points on the rockers: (point, rocker, pivot, length)."""
GUESS = "[guess]\nW = [13, 47.5]\nB = [-27, 59.5]\nC = [28, 59.5]\n\n[find]"


def _errors(n: int, steps: int = 360) -> tuple[float, float, float]:
    spline = sweep(_scene(FLAT, _points(n)), steps=steps, start=0.0, stop=360.0)
    exact = sweep(_scene(FLAT, CIRCLE), steps=steps, start=0.0, stop=360.0)
    assert (spline.status == 0).all() and (exact.status == 0).all()
    gaps = [np.abs(spline.column(c).values - exact.column(c).values) for c in COLUMNS]
    return tuple(float(np.max(np.hypot(gaps[2 * k], gaps[2 * k + 1]))) for k in range(3))  # type: ignore[return-value]


@pytest.mark.slow  # about 10 s
def test_the_face_follows_the_exact_circle_over_a_turn_at_the_splines_order() -> None:
    # measured over 360 rows, 36 / 72 / 144 points: 1.5e-4 / 9.2e-6 / 5.7e-7 mm, 0.068 / 8.5e-3 / 1.0e-3 mm/s,
    # 94 / 25 / 5.9 mm/s^2 (orders 4.0 4.0, 3.0 3.1, 1.9 2.1)
    coarse, middle, fine = (_errors(n) for n in (36, 72, 144))
    assert coarse[0] < 2e-4 and coarse[1] < 0.08 and coarse[2] < 110.0
    for k, order in enumerate((4, 3, 2)):
        for a, b in ((coarse, middle), (middle, fine)):
            assert math.log2(a[k] / b[k]) == pytest.approx(order, abs=0.4)


def test_every_row_of_a_turn_checks_keeps_the_contact_and_equals_the_sweep() -> None:
    result = sweep(kinepoly.load_scene(FLAT), steps=36, start=0.0, stop=360.0)
    assert (result.status == 0).all()
    worst = 0.0
    for row, degrees in enumerate(result.input.values):
        data = kinepoly.to_json(kinepoly.solve(_scene(FLAT, None, {"angle = 30": f"angle = {float(degrees)!r}",
                                                                   GUESS: _guess_at(ROCKERS, result, row)})))
        assert data["check"]["max_rel_error"] < 1e-12
        worst = max(worst, _normal_residual(data, 20.0))
        point = data["points"]["W"]
        for k, axis in enumerate("xy"):
            for key, q in (("position", "r"), ("velocity", "v"), ("acceleration", "a")):
                assert point[key][k] == pytest.approx(result.column(f"{q}_W_{axis}").values[row], rel=1e-9, abs=1e-7)
        contact = data["contacts"]["23"]
        normal = complex(*contact["normal"])
        face = complex(math.cos(math.radians(data["links"]["3"]["angle"]) + math.pi),
                       math.sin(math.radians(data["links"]["3"]["angle"]) + math.pi))
        assert abs((normal * face.conjugate()).real) < 1e-12  # the common normal is square to the face
    assert worst < 1e-12


def test_the_triads_assur_point_and_the_groups_linear_solve_give_the_same_polygons(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """The third leg is the block pinned at K sliding along the face; forced onto the linear solve (a group of
    another shape), the follower's point under K moving along the face is one more equation: the same tips."""
    from kinepoly.engine import triad

    first = kinepoly.solve(kinepoly.load_scene(FLAT))
    assert any(step.topic == "assur-point" for step in first.steps)
    by_assur = kinepoly.to_json(first)
    monkeypatch.setattr(triad, "triad_of", lambda mechanism, group: None)
    solved = kinepoly.solve(kinepoly.load_scene(FLAT))
    assert any(step.kind == "linear-solve" and step.param("face") for step in solved.steps)
    by_solve = kinepoly.to_json(solved)
    assert by_solve["check"]["max_rel_error"] < 1e-12
    for key in ("velocity", "acceleration"):
        assert by_solve["points"]["W"][key] == pytest.approx(by_assur["points"]["W"][key], rel=1e-12)
    for link in ("3", "4", "5"):
        for key in ("omega", "alpha"):
            assert by_solve["links"][link][key] == pytest.approx(by_assur["links"][link][key], rel=1e-10, abs=1e-12)


def test_the_steps_say_the_block_at_k_is_the_third_leg_with_its_coriolis_term() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(FLAT))
    assur = next(step for step in solution.steps if step.topic == "assur-point")
    params = dict(assur.params)
    assert "K23" in (params["first"], params["second"], params["third"])
    acceleration = [step for step in solution.steps if step.polygon == "acceleration" and step.kind == "intersection"]
    coriolis = [v for step in acceleration for v in step.vectors if v.term == "coriolis"]
    assert coriolis and all(v.label.startswith("a^c_K23@3/") for v in coriolis)
    data = kinepoly.to_json(solution)
    omega3 = data["links"]["3"]["omega"]
    tips, kv = data["polygons"]["velocity"]["points"], data["polygons"]["velocity"]["scale"]  # paper mm, kv
    block = (complex(*tips["k23@2"]) - complex(*tips["k23@3"])) / kv  # the block's velocity over the face
    start, end = (complex(*p) for p in (coriolis[0].start, coriolis[0].end))
    assert abs(end - start) == pytest.approx(2.0 * abs(omega3) * abs(block), rel=1e-9)  # 2 |omega3| |v_rel|
    assert abs(((end - start) * block.conjugate()).real) < 1e-9 * abs(end - start) * abs(block)  # square to it


def test_a_face_that_cannot_reach_the_profile_exits_3_with_the_reason(tmp_path: Path) -> None:
    # the rockers hung 100 mm higher: the face stays above y = 60, the profile's top below 55
    far = {"B0 = [-97, 45], C0 = [-42, 47]": "B0 = [-97, 145], C0 = [-42, 147]",
           GUESS: GUESS.replace("47.5", "147.5").replace("59.5", "159.5")}
    refused_with_exit_3(FLAT, far, r"; or follower 3 cannot touch cam 2: with the group's joints held, its flat face "
                                   r"cannot be laid along a tangent of the profile", tmp_path)


@settings(max_examples=10, deadline=None)
@given(st.floats(-1, 2), st.floats(-2, 1), st.floats(5.0, 355.0))
def test_random_pivots_follow_the_exact_circle_and_keep_the_contact(dx: float, dy: float, angle: float) -> None:
    """The example with its rockers' pivots moved (within the box where the exact circle's mechanism closes over
    the whole turn), swept from 30 degrees to a random cam angle: every row assembles, W follows the exact
    circle to the spline's accuracy, and the last row's solve agrees with the analytic check and keeps the
    contact's normal velocities equal. (Beyond that box the floating four-bar meets dead points within the
    turn, where the exact circle's group may jump to its other assembly: see the docs.)"""
    b0, c0 = complex(-97 + dx, 45 + dy), complex(-42 - dy, 47 + dx)
    b, c = complex(-27, 59.5), complex(28, 59.5)
    text = {"B0 = [-97, 45], C0 = [-42, 47]": f"B0 = [{b0.real!r}, {b0.imag!r}], C0 = [{c0.real!r}, {c0.imag!r}]",
            "B = [71.49, 0]": f"B = [{abs(b - b0)!r}, 0]", "C = [71.11, 0]": f"C = [{abs(c - c0)!r}, 0]"}
    rockers = (("B", "4", b0, abs(b - b0)), ("C", "5", c0, abs(c - c0)))
    follows_the_circle_and_keeps_the_contact(FLAT, text, text, rockers, GUESS, angle)
