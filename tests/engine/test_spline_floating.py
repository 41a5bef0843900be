"""Floating followers on spline cams: the follower reaches the frame only through other unknown links.

The references are derived apart from the spline's path through the engine: the same mechanisms with the
circle the profile's points were sampled from, solved exactly (a circle cam's pair is a permanent link, closed
by the triad's construction or the group's own equations with no contact unknown); finite differences of the
positions over the input; the analytic check (``check/``); and the contact's velocity condition (the normal
components of both contact points' velocities equal).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinepoly
from kinepoly.errors import AssemblyError
from kinepoly.sweep import sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
TRIAD = EXAMPLES / "spline-cam-floating-triad.toml"
SLEEVE = EXAMPLES / "spline-cam-floating-sleeve.toml"
FLAT = EXAMPLES / "spline-cam-floating-flat.toml"
PROFILE = re.compile(r"profile = \{ points = \[.*?\] \}", re.DOTALL)
CIRCLE = "profile = { circle = { center = [15, 0], radius = 40 } }"
E, R = 15.0, 40.0


def _scene(path: Path, profile: str | None = None, replace: dict[str, str] | None = None) -> kinepoly.Scene:
    text = path.read_text()
    if profile is not None:
        text = PROFILE.sub(profile, text)
    for old, new in (replace or {}).items():
        assert old in text
        text = text.replace(old, new)
    return kinepoly.loads_scene(text, path.name)


def _points(n: int) -> str:
    points = [[E + R * math.cos(2 * math.pi * k / n), R * math.sin(2 * math.pi * k / n)] for k in range(n)]
    return f"profile = {{ points = {points!r} }}"


COLUMNS = ("r_W_x", "r_W_y", "v_W_x", "v_W_y", "a_W_x", "a_W_y")


def _errors(path: Path, n: int, steps: int = 360) -> tuple[float, float, float]:
    """The worst position, velocity and acceleration error of W over a turn, spline of n points against the
    circle solved exactly."""
    spline = sweep(_scene(path, _points(n)), steps=steps, start=0.0, stop=360.0)
    exact = sweep(_scene(path, CIRCLE), steps=steps, start=0.0, stop=360.0)
    assert (spline.status == 0).all() and (exact.status == 0).all()
    gaps = [np.abs(spline.column(c).values - exact.column(c).values) for c in COLUMNS]
    return tuple(float(np.max(np.hypot(gaps[2 * k], gaps[2 * k + 1]))) for k in range(3))  # type: ignore[return-value]


@pytest.mark.slow  # about 11 to 15 s each
@pytest.mark.parametrize("path", [TRIAD, SLEEVE])
def test_the_examples_follow_the_exact_circle_over_a_turn_at_the_splines_order(path: Path) -> None:
    # measured over 360 rows, 36 / 72 / 144 points: triad 1.4e-4 / 8.4e-6 / 5.3e-7 mm, 0.067 / 8.2e-3 / 1.0e-3
    # mm/s, 98 / 26 / 6.1 mm/s^2; sleeve 1.7e-4 / 1.0e-5 / 6.5e-7, 0.055 / 6.8e-3 / 8.5e-4, 83 / 21 / 5.1
    coarse, middle, fine = (_errors(path, n) for n in (36, 72, 144))
    assert coarse[0] < 2e-4 and coarse[1] < 0.08 and coarse[2] < 110.0
    for k, order in enumerate((4, 3, 2)):
        for a, b in ((coarse, middle), (middle, fine)):
            assert math.log2(a[k] / b[k]) == pytest.approx(order, abs=0.35)


@pytest.mark.slow  # about 25 to 34 s each: the slowest of the suite
@pytest.mark.parametrize("path", [TRIAD, SLEEVE, FLAT])
def test_velocity_and_acceleration_are_the_positions_finite_differences(path: Path) -> None:
    steps = 3600
    result = sweep(kinepoly.load_scene(path), steps=steps, start=0.0, stop=360.0)
    assert (result.status == 0).all()
    dt = math.radians(360.0 / steps) / 20.0  # the cam turns at 20 rad/s, steadily
    for axis in ("x", "y"):
        r, v, a = (result.column(f"{q}_W_{axis}").values for q in ("r", "v", "a"))
        central_v = (np.roll(r, -1) - np.roll(r, 1)) / (2 * dt)
        central_a = (np.roll(v, -1) - np.roll(v, 1)) / (2 * dt)
        assert np.max(np.abs(central_v - v)) < 2e-3 * np.max(np.abs(v))
        assert np.max(np.abs(central_a - a)) < 2e-3 * np.max(np.abs(a))


def _normal_residual(data: dict[str, object], omega_cam: float) -> float:
    """|(v_follower(Q) - v_cam(Q)) . n| / |v_cam(Q)| at the contact Q (the cam turns about O = 0)."""
    contact = data["contacts"]["23"]  # type: ignore[index]
    q, n = complex(*contact["point"]), complex(*contact["normal"])
    w = data["points"]["W"]  # type: ignore[index]
    omega = data["links"]["3"]["omega"]  # type: ignore[index]
    on_follower = complex(*w["velocity"]) + omega * 1j * (q - complex(*w["position"]))
    on_cam = omega_cam * 1j * q
    return abs(((on_follower - on_cam) * n.conjugate()).real) / abs(on_cam)


ROCKERS = {TRIAD: (("B", "4", -90 + 45j, 67.6), ("C", "5", -5 + 50j, 61.2)),
           SLEEVE: (("B", "4", -150 + 120.5j, 163.3),)}
"""The guessed points on the rockers: (point, rocker, pivot, length)."""


def _guess_at(rockers: tuple[tuple[str, str, complex, float], ...], result: object, row: int) -> str:
    """A [guess] at the sweep's row: W and the rockers' pins where the sweep has them (so that the solve
    takes the assembly the sweep followed: the group has others, which a guess far off may reach)."""
    def value(name: str) -> float:
        return float(result.column(name).values[row])  # type: ignore[attr-defined]

    lines = [f"W = [{value('r_W_x')!r}, {value('r_W_y')!r}]"]
    for point, rocker, pivot, length in rockers:
        at = pivot + length * complex(math.cos(math.radians(value(f"theta_{rocker}"))),
                                      math.sin(math.radians(value(f"theta_{rocker}"))))
        lines.append(f"{point} = [{at.real!r}, {at.imag!r}]")
    return "[guess]\n" + "\n".join(lines) + "\n\n[find]"


@pytest.mark.parametrize("path", [TRIAD, SLEEVE])
def test_every_row_of_a_turn_checks_and_keeps_the_contacts_normal_velocities_equal(path: Path) -> None:
    result = sweep(kinepoly.load_scene(path), steps=36, start=0.0, stop=360.0)
    worst = 0.0
    text = path.read_text()
    guess = text[text.index("[guess]"):text.index("[find]") + len("[find]")]
    for row, degrees in enumerate(result.input.values):
        solved = kinepoly.solve(_scene(path, None, {"angle = 30": f"angle = {float(degrees)!r}",
                                                    guess: _guess_at(ROCKERS[path], result, row)}))
        data = kinepoly.to_json(solved)
        assert data["check"]["max_rel_error"] < 1e-12
        worst = max(worst, _normal_residual(data, 20.0))
        point = data["points"]["W"]
        for k, axis in enumerate("xy"):  # solve at any row equals the sweep row
            for key, q in (("position", "r"), ("velocity", "v"), ("acceleration", "a")):
                assert point[key][k] == pytest.approx(result.column(f"{q}_W_{axis}").values[row], rel=1e-9, abs=1e-7)
    assert worst < 1e-12


def test_a_follower_that_cannot_reach_the_profile_exits_3_with_the_reason(tmp_path: Path) -> None:
    # the rockers hung 150 mm higher: W stays above y = 115, the offset profile below y = 65
    far = {"B0 = [-90, 45], C0 = [-5, 50]": "B0 = [-90, 195], C0 = [-5, 200]",
           "B = [-27, 69.5]\nC = [53, 69.5]": "B = [-27, 219.5]\nC = [53, 219.5]"}
    refused_with_exit_3(TRIAD, far, r"does not close at theta12 = 30 deg.*; or follower 3 cannot touch cam 2: with "
                        r"the group's joints held, the roller's centre W cannot reach the profile offset by the roller",
                        tmp_path)


def refused_with_exit_3(path: Path, far: dict[str, str], message: str, tmp_path: Path) -> None:
    """The scene at ``path`` changed by ``far`` raises ``AssemblyError`` matching ``message``; its solve exits 3."""
    from kinepoly.cli import main

    with pytest.raises(AssemblyError, match=message):
        kinepoly.solve(_scene(path, None, far))
    text = path.read_text()
    for old, new in far.items():
        text = text.replace(old, new)
    scene = tmp_path / "far.toml"
    scene.write_text(text)
    assert main(["solve", str(scene)]) == 3


@settings(max_examples=12, deadline=None)
@given(st.floats(-8, 8), st.floats(-8, 8), st.floats(5.0, 13.0), st.floats(5.0, 355.0))
def test_random_pivots_and_rollers_follow_the_exact_circle_and_keep_the_contact(dx: float, dy: float, radius: float,
                                                                                angle: float) -> None:
    """The triad with its rockers' pivots moved and another roller, swept from 30 degrees to a random cam angle:
    the same rows assemble as with the exact circle, W follows it to the spline's accuracy, and the last row's
    solve agrees with the analytic check and keeps the contact's normal velocities equal."""
    b0, c0 = complex(-90 + dx, 45 + dy), complex(-5 - dy, 50 + dx)
    lift = radius - 10.0
    b, c = complex(-27, 69.5 + lift), complex(53, 69.5 + lift)
    text = {"B0 = [-90, 45], C0 = [-5, 50]": f"B0 = [{b0.real!r}, {b0.imag!r}], C0 = [{c0.real!r}, {c0.imag!r}]",
            "B = [67.6, 0]": f"B = [{abs(b - b0)!r}, 0]", "C = [61.2, 0]": f"C = [{abs(c - c0)!r}, 0]",
            "radius = 10": f"radius = {radius!r}",
            "W = [13, 57.5]\nB = [-27, 69.5]\nC = [53, 69.5]":
                f"W = [13, {57.5 + lift!r}]\nB = [-27, {b.imag!r}]\nC = [53, {c.imag!r}]"}
    rockers = (("B", "4", b0, abs(b - b0)), ("C", "5", c0, abs(c - c0)))
    original = "W = [13, 57.5]\nB = [-27, 69.5]\nC = [53, 69.5]"
    guess = "[guess]\n" + original + "\n\n[find]"
    moved = {old: new for old, new in text.items() if old != original}
    follows_the_circle_and_keeps_the_contact(TRIAD, text, moved, rockers, guess, angle)


def follows_the_circle_and_keeps_the_contact(path: Path, text: dict[str, str], moved: dict[str, str],
                                            rockers: tuple[tuple[str, str, complex, float], ...], guess: str,
                                            angle: float) -> None:
    """Swept with ``text`` from 30 degrees on by ``angle``: the same rows assemble as with the exact circle and W
    follows it to the spline's accuracy; where the last row closes, its solve (``moved``, guessed from the sweep)
    agrees with the analytic check and keeps the contact's normal velocities equal."""
    steps = max(2, math.ceil(angle / 5.0))
    spline = sweep(_scene(path, None, text), steps=steps, start=30.0, stop=30.0 + angle)
    exact = sweep(_scene(path, CIRCLE, text), steps=steps, start=30.0, stop=30.0 + angle)
    assert ((spline.status == 0) == (exact.status == 0)).all()
    ok = spline.status == 0
    for column in ("r_W_x", "r_W_y"):
        gap = np.abs(spline.column(column).values[ok] - exact.column(column).values[ok])
        assert np.max(gap, initial=0.0) < 5e-3
    if not ok[-1]:
        return
    last = {**moved, "angle = 30": f"angle = {30.0 + angle!r}", guess: _guess_at(rockers, spline, steps)}
    data = kinepoly.to_json(kinepoly.solve(_scene(path, None, last)))
    assert data["check"]["max_rel_error"] < 1e-10
    assert _normal_residual(data, 20.0) < 1e-11


@pytest.mark.parametrize("path", [TRIAD, SLEEVE])
def test_the_construction_agrees_with_the_50_digit_reference_of_the_same_spline(path: Path) -> None:
    """``kinepoly bench``'s reference (the spline rebuilt in mpmath, the contact's parameter an unknown of its
    own closure): measured 1.1e-15 (triad), 3.1e-16 (sleeve)."""
    from tests.bench.test_bench_spline_cams import _construction_error

    solution = kinepoly.solve(kinepoly.load_scene(path))
    errors = _construction_error(solution)
    assert all(err <= solution.accuracy.estimate.relative[kind] for kind, err in errors.items()), errors
    assert max(errors.values()) < 1e-13


def test_a_sweep_marks_the_rows_where_the_follower_cannot_follow_the_cam() -> None:
    # rockers hung to the sides: the coupler cannot carry W round the whole turn (with the exact circle too)
    apart = {"B0 = [-90, 45], C0 = [-5, 50]": "B0 = [-65, 60], C0 = [95, 85]",
             "B = [67.6, 0]": "B = [39.1695, 0]", "C = [61.2, 0]": "C = [44.7689, 0]"}
    spline = sweep(_scene(TRIAD, None, apart), steps=72, start=0.0, stop=360.0)
    exact = sweep(_scene(TRIAD, CIRCLE, apart), steps=72, start=0.0, stop=360.0)
    marked = spline.status != 0
    assert 10 < marked.sum() < 62  # measured: 42 of 72
    assert (exact.status != 0).sum() == marked.sum()
    for row in np.flatnonzero(marked):
        assert "follower 3 cannot touch cam 2" in spline.warnings[row]


@pytest.mark.parametrize("path", [TRIAD, SLEEVE])
def test_the_triads_assur_point_and_the_groups_linear_solve_give_the_same_polygons(
        path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Both examples are triads whose third leg is the pair's equivalent link; a floating group of another
    shape takes the linear solve with the link as one more equation (``engine.group``): forced here, it gives
    the same tips and rates, and the check agrees."""
    from kinepoly.engine import triad

    by_assur = kinepoly.to_json(kinepoly.solve(kinepoly.load_scene(path)))
    monkeypatch.setattr(triad, "triad_of", lambda mechanism, group: None)
    solved = kinepoly.solve(kinepoly.load_scene(path))
    assert any(step.kind == "linear-solve" for step in solved.steps)
    by_solve = kinepoly.to_json(solved)
    assert by_solve["check"]["max_rel_error"] < 1e-12
    for key in ("velocity", "acceleration"):
        assert by_solve["points"]["W"][key] == pytest.approx(by_assur["points"]["W"][key], rel=1e-12)
    for link in ("3", "4"):
        for key in ("omega", "alpha"):
            assert by_solve["links"][link][key] == pytest.approx(by_assur["links"][link][key], rel=1e-11)
