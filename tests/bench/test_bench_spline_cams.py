"""``kinepoly bench`` on spline cams (``points`` profiles): the 50-digit reference of the spline's own motion.

The reference rebuilds the periodic cubic in mpmath (``bench.spline_pairs``) and makes the contact parameter
an unknown. Checked here apart from it:

* its spline against the definition (through every point, the point, tangent and second derivative
  continuous at every knot, to 70 digits) and against the double-precision ``geom.spline``;
* its motion is the spline's, not the circle's the points were sampled from (a small but real gap);
* its velocities are the central differences of its own positions;
* the construction agrees with it to ~1e-13 on the examples and on random convex profiles.
"""

from __future__ import annotations

import json
import math

import mpmath  # type: ignore[import-untyped]
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.bench.methods import construction_values
from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import kind_errors
from kinepoly.bench.spline_pairs import mp_spline
from kinepoly.cli import main
from kinepoly.geom.spline import periodic_spline
from kinepoly.scene.loader import loads_scene

SPLINE_EXAMPLES = ("spline-cam-knife", "spline-cam-roller-rocker", "spline-cam-flat-rocker", "spline-on-spline")
KNIFE = EXAMPLES / "spline-cam-knife.toml"


def _keys(solution: kinepoly.Solution) -> list[str]:
    return [q.key for q in solution.check.quantities if not q.key.startswith("instant_centers.")]


def _reference(solution: kinepoly.Solution, t: float | None = None) -> dict[str, object]:
    assert solution.inside is not None
    return reference_values(solution.inside.mechanism, solution.inside.pose, _keys(solution), t=t,
                            origin=solution.inside.frame.origin).values


def _construction_error(solution: kinepoly.Solution) -> dict[str, float]:
    assert solution.inside is not None
    keys = tuple(_keys(solution))
    reference = reference_values(solution.inside.mechanism, solution.inside.pose, list(keys),
                                 origin=solution.inside.frame.origin)
    return kind_errors(construction_values(solution, keys, solution.inside.frame.origin), reference,
                       dict(solution.check.scales))


def _ellipse(n: int, a: float, b: float, turn: float, shift: float) -> list[tuple[float, float]]:
    """n points of an ellipse (semi-axes a, b, turned by ``turn``, its centre ``shift`` along x), unevenly spaced."""
    out = []
    for k in range(n):
        phi = 2 * math.pi * k / n + 0.2 * math.sin(2 * math.pi * k / n)
        x, y = a * math.cos(phi), b * math.sin(phi)
        out.append((shift + x * math.cos(turn) - y * math.sin(turn), x * math.sin(turn) + y * math.cos(turn)))
    return out


def test_the_reference_spline_meets_its_definition_to_seventy_digits() -> None:
    points = tuple(_ellipse(11, 40.0, 25.0, 0.4, 7.0))
    mp = mpmath.mp
    with mp.workdps(80):
        spline = mp_spline(mp, points)
        n = len(points)
        tiny = mp.mpf(10) ** -70
        for k in range(n):
            a, b, c, d = spline.stretches[k]
            h = spline.knots[k + 1] - spline.knots[k]
            assert abs(h - mp.sqrt(sum((mp.mpf(points[(k + 1) % n][i]) - mp.mpf(points[k][i])) ** 2
                                       for i in (0, 1)))) < tiny
            end = [a[i] + h * (b[i] + h * (c[i] + h * d[i])) for i in (0, 1)]
            slope = [b[i] + h * (2 * c[i] + 3 * h * d[i]) for i in (0, 1)]
            bend = [2 * c[i] + 6 * h * d[i] for i in (0, 1)]
            a1, b1, c1, _ = spline.stretches[(k + 1) % n]
            for i in (0, 1):
                assert abs(a[i] - mp.mpf(points[k][i])) < tiny
                assert abs(end[i] - a1[i]) < tiny * 100  # the next point
                assert abs(slope[i] - b1[i]) < tiny * 100  # the tangent
                assert abs(bend[i] - 2 * c1[i]) < tiny * 100  # the second derivative


@settings(max_examples=10, deadline=None)
@given(n=st.integers(5, 30), a=st.floats(10.0, 60.0), ratio=st.floats(0.4, 1.0), turn=st.floats(0.0, 6.28),
       u=st.floats(-1.0, 2.0))
def test_the_reference_spline_is_the_engines_spline(n: int, a: float, ratio: float, turn: float, u: float) -> None:
    points = tuple(_ellipse(n, a, a * ratio, turn, 3.0))
    ours = periodic_spline(points)
    mp = mpmath.mp
    with mp.workdps(30):
        theirs = mp_spline(mp, points)
        period = float(theirs.period)
        assert abs(period - ours.period) < 1e-12 * period
        at = u * period
        point, tangent = theirs.point_and_tangent(mp, mp.mpf(at))
    p, t, _ = ours.derivatives(np.array([at]))
    assert abs(complex(float(point[0]), float(point[1])) - p[0]) < 1e-12 * a
    assert abs(complex(float(tangent[0]), float(tangent[1])) - t[0]) < 1e-11


def test_the_reference_follows_the_spline_not_the_circle_it_was_sampled_from() -> None:
    # the points are on the circle centre [15, 0], radius 40: the exact rise of the circle is
    # 15 sin(theta) + sqrt(40^2 - 15^2 cos(theta)^2); the spline is within its accuracy of it, not on it
    solution = kinepoly.solve(kinepoly.load_scene(KNIFE))
    theta = math.radians(30.0)
    ref = _reference(solution)
    position = ref["points.W.position"]
    assert isinstance(position, tuple)
    circle = 15 * mpmath.sin(theta) + mpmath.sqrt(40 ** 2 - 15 ** 2 * mpmath.cos(theta) ** 2)
    gap = abs(position[1] - circle)
    assert 1e-9 < gap < 1e-4 * 55  # the spline's error at 36 points, far above the reference's


def test_the_references_velocity_is_the_central_difference_of_its_positions() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(KNIFE))
    assert solution.inside is not None
    theta, omega = math.radians(30.0), 10.0
    mid, ahead, behind = (reference_values(solution.inside.mechanism, solution.inside.pose,
                                           ["points.W.position", "points.W.velocity"], t=theta + d)
                          for d in (0.0, 1e-12, -1e-12))
    rise = [v.values["points.W.position"][1] for v in (ahead, behind)]
    velocity = mid.values["points.W.velocity"]
    with mpmath.mp.workdps(50):  # the inputs as the reference took them; the gap of two close rises in full
        slope = (rise[0] - rise[1]) / (ahead.t - behind.t) * omega
        assert abs(slope - velocity[1]) < 1e-18 * abs(velocity[1])  # delta^2 times the third derivative
    assert abs(velocity[0]) < 1e-16 * abs(velocity[1])  # along the guide at radians(90), cos of it ~6e-17


@pytest.mark.parametrize("name", SPLINE_EXAMPLES)
def test_the_construction_agrees_with_the_reference_on_every_spline_example(name: str) -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    assert solution.accuracy is not None
    errors = _construction_error(solution)
    assert all(err <= solution.accuracy.estimate.relative[kind] for kind, err in errors.items()), errors
    assert max(errors.values()) < 1e-13


@pytest.mark.parametrize("name", SPLINE_EXAMPLES)
def test_bench_prints_its_table_on_every_spline_example(name: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", str(EXAMPLES / f"{name}.toml"), "--budget", "0.002"]) == 0
    out = capsys.readouterr().out
    assert "reference: mpmath, 50 digits" in out and "not built yet" not in out
    assert main(["bench", str(EXAMPLES / f"{name}.toml"), "--json", "--budget", "0.002"]) == 0
    methods = json.loads(capsys.readouterr().out)["methods"]
    errors = {family: [m["error"] for m in methods if m["family"] == family]
              for family in ("construction", "finite differences")}
    assert errors["construction"][0] < 1e-12
    assert 1e-12 < min(errors["finite differences"]) < 1e-7  # their best step, at the rounding's limit


def _scene(points: list[tuple[float, float]], touch: str, angle: float, omega: float, alpha: float) -> str:
    text = KNIFE.read_text()
    start, end = text.index("profile = {"), text.index("] }", text.index("profile = {")) + 3
    follower = {"knife": 'knife = "W"', "roller": 'roller = { center = "W", radius = 5 }',
                "inside": 'roller = { center = "W", radius = 5 }\ncontact = "inside"',
                "flat": "flat = { through = [0, 0], angle = 90 }"}[touch]
    swaps = {'knife = "W"': follower, "angle = 30": f"angle = {angle!r}", "omega = 10": f"omega = {omega!r}",
             "alpha = 5": f"alpha = {alpha!r}", "W = [0, 50]": "W = [0, 80]"}
    text = text[:start] + f"profile = {{ points = {[list(p) for p in points]!r} }}" + text[end:]
    for old, new in swaps.items():
        assert old in text
        text = text.replace(old, new)
    return text


@settings(max_examples=8, deadline=None)
@given(n=st.integers(8, 24), a=st.floats(30.0, 50.0), ratio=st.floats(0.6, 1.0), turn=st.floats(0.0, 6.28),
       shift=st.floats(-8.0, 8.0), angle=st.floats(0.0, 360.0), omega=st.floats(1.0, 20.0),
       alpha=st.floats(-10.0, 10.0), touch=st.sampled_from(["knife", "roller", "inside", "flat"]))
def test_the_construction_agrees_with_the_reference_on_random_convex_profiles(
        n: int, a: float, ratio: float, turn: float, shift: float, angle: float, omega: float, alpha: float,
        touch: str) -> None:
    # an ellipse's points round the pivot (the shift is below the least semi-axis): the guide always crosses it;
    # its least radius of curvature b^2 / a >= 10.8 holds a roller of 5 inside
    text = _scene(_ellipse(n, a, a * ratio, turn, shift), touch, angle, omega, alpha)
    errors = _construction_error(kinepoly.solve(loads_scene(text, "random.toml")))
    assert max(errors.values()) < 1e-12, errors



def test_a_bench_sweep_of_a_spline_cam_is_exact_at_every_input(capsys: pytest.CaptureFixture[str]) -> None:
    # each input's reference starts its contact parameter afresh, across every stretch of the spline
    assert main(["bench", str(EXAMPLES / "spline-cam-flat-rocker.toml"), "--sweep", "7", "--json",
                 "--budget", "0.002"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [p["status"] for p in data["sweep"]["points"]] == ["ok"] * 7
    construction = data["methods"][0]
    assert construction["name"].startswith("construction") and construction["error"] < 1e-12
