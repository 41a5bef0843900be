"""Instant centers (Aronhold-Kennedy, circle diagram): against the velocity field and the theorem itself.

Independent references: the analytic solution (``solve_analytic``) gives every link's velocity
field, and the center of links i and j is the one point where their velocities agree; the
theorem says the three centers of any three links lie on one line; a parallelogram linkage has
its centers I13 and I24 at infinity in closed form.
"""

from __future__ import annotations

import json
import math
from itertools import combinations
from pathlib import Path

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from tests.cli_support import run
from tests.scenes import EXAMPLES, four_bar, slider_crank, slotted_lever

import kinepoly
from kinepoly.check.analytic import AnalyticSolution, solve_analytic
from kinepoly.engine.centers import InstantCenter
from kinepoly.engine.circle_diagram import edge, pair_name, plan_kennedy
from kinepoly.errors import AssemblyError, SingularityError
from kinepoly.geom.homogeneous import LocalFrame, canonical_direction, wedge

SIX_BAR = (EXAMPLES / "centers-six-bar.toml").read_text()
ALL = '[find]\ninstant_centers = "all"\nomega = ["3", "4"]'

lengths = st.floats(min_value=10.0, max_value=200.0)
angles = st.floats(min_value=-180.0, max_value=180.0)
speeds = st.floats(min_value=-50.0, max_value=50.0).filter(lambda w: abs(w) > 0.1)


def six_bar(a1: float, a2: float, a3: float, a4: float, d: tuple[float, float], a5: float, h: float, theta: float,
            omega: float, slider: bool = True, find: str = '[find]\ninstant_centers = "all"\nomega = ["3", "4", "5"]',
            ) -> str:
    """A Watt six-bar: four-bar 1-2-3-4, link 5 from D on the rocker to E on link 6: a block sliding on the
    frame along y = h, or a rocker of length a6 = 50 + |h| pivoted at F0 = (a1 + a5, h - a6)."""
    a6 = 50.0 + abs(h)
    frame = f"A0 = [0, 0], B0 = [{a1!r}, 0]" + ("" if slider else f", F0 = [{a1 + a5!r}, {h - a6!r}]")
    last = "6 = { points = { E = [0, 0] } }" if slider else f"6 = {{ points = {{ F0 = [0, 0], E = [{a6!r}, 0] }} }}"
    slide = f'\n[[sliders]]\nblock = "6"\nguide = "1"\npoint = "E"\nline = {{ through = [0, {h!r}], angle = 0 }}\n'
    return f"""
title = "random six-bar"
[links]
1 = {{ points = {{ {frame} }} }}
2 = {{ points = {{ A0 = [0, 0], A = [{a2!r}, 0] }} }}
3 = {{ points = {{ A = [0, 0], B = [{a3!r}, 0] }} }}
4 = {{ points = {{ B0 = [0, 0], B = [{a4!r}, 0], D = {{ polar = [{d[0]!r}, {d[1]!r}] }} }} }}
5 = {{ points = {{ D = [0, 0], E = [{a5!r}, 0] }} }}
{last}
{slide if slider else ""}
[input]
link = "2"
angle = {theta!r}
omega = {omega!r}
alpha = 0
[guess]
B = [{a1!r}, {a3 + a4!r}]
E = [{a1 + a5!r}, {h!r}]
{find}
"""


def solve_text(text: str) -> kinepoly.Solution:
    """Solve, leaving out the positions near a singularity (where every method loses digits)."""
    try:
        solution = kinepoly.solve(kinepoly.loads_scene(text))
    except (AssemblyError, SingularityError):
        assume(False)
        raise
    assume(not any(n.code in ("near-singular", "center-ill-conditioned") for n in solution.notices))
    assume(solution.check.condition_number < 1e4)
    return solution


# ----------------------------------------------------------------------------------------------
# Independent references
# ----------------------------------------------------------------------------------------------


class Field:
    """The analytic velocity field of every link, in a frame local to the mechanism (positions / size)."""

    def __init__(self, solution: kinepoly.Solution) -> None:
        self.solution = solution
        self.analytic: AnalyticSolution = solve_analytic(solution.mechanism, dict(solution.pose.links),
                                                         with_acceleration=False)
        pins = [solution.position(j.point) for j in solution.mechanism.revolutes]
        self.origin = (sum(p[0] for p in pins) / len(pins), sum(p[1] for p in pins) / len(pins))
        self.size = max(math.hypot(p[0] - self.origin[0], p[1] - self.origin[1]) for p in pins)
        self.omega_max = max(abs(w) for w in self.analytic.omega.values())

    def velocity(self, link: str, at: tuple[float, float]) -> tuple[float, float]:
        vx, vy = self.analytic.velocity(link, self.analytic.poses[link].to_local(at))
        return (float(vx), float(vy))

    def center(self, i: str, j: str) -> tuple[tuple[float, float, float], float]:
        """I_ij as a homogeneous triple in the local frame, from the velocities (and its unnormalized size).

        v_j - v_i at a point P0 is v_rel + (omega_j - omega_i) J (P - P0): zero at P0 + J v_rel / d_omega,
        so I_ij = (P0 d_omega + J v_rel, d_omega); at infinity when d_omega = 0.
        """
        vi, vj = self.velocity(i, self.origin), self.velocity(j, self.origin)
        rel = ((vj[0] - vi[0]) / self.size, (vj[1] - vi[1]) / self.size)
        d_omega = self.analytic.omega[j] - self.analytic.omega[i]
        h = (-rel[1], rel[0], d_omega)
        return h, math.sqrt(sum(c * c for c in h))

    def local(self, center: InstantCenter) -> tuple[float, float, float]:
        x, y, w = center.homogeneous
        if w == 0.0:
            return (x, y, 0.0)
        return ((x - self.origin[0]) / self.size, (y - self.origin[1]) / self.size, 1.0)


def unit3(v: tuple[float, float, float]) -> tuple[float, float, float]:
    n = math.sqrt(sum(c * c for c in v))
    return (v[0] / n, v[1] / n, v[2] / n)


def sin_between(p: tuple[float, float, float], q: tuple[float, float, float]) -> float:
    a, b = unit3(p), unit3(q)
    c = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
    return math.sqrt(sum(x * x for x in c))


def det3(p: tuple[float, float, float], q: tuple[float, float, float], r: tuple[float, float, float]) -> float:
    a, b, c = unit3(p), unit3(q), unit3(r)
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


def check_all_centers(solution: kinepoly.Solution) -> None:
    """Every pair's center where the two velocity fields agree; every triple collinear; omegas analytic."""
    centers = solution.centers
    assert centers is not None
    links = solution.mechanism.link_names
    assert len(centers.asked) == len(links) * (len(links) - 1) // 2
    field = Field(solution)
    for i, j in combinations(links, 2):
        center = centers.center(pair_name((i, j)))
        reference, size = field.center(i, j)
        if size < 1e-3 * field.omega_max:  # links i and j almost at relative rest: no well-defined center
            continue
        assert sin_between(field.local(center), reference) <= 1e-9, (i, j, center, reference)
        assert center.is_at_infinity == (abs(reference[2]) <= 1e-12 * size) or abs(reference[2]) < 1e-6 * size
    for i, j, k in combinations(links, 3):
        triple = [field.local(centers.center(pair_name(edge(a, b, links)))) for a, b in ((i, j), (i, k), (j, k))]
        assert abs(det3(*triple)) <= 1e-9, (i, j, k)
    for found in centers.omegas:
        assert abs(found.omega - field.analytic.omega[found.link]) <= 1e-9 * field.omega_max, found.link
    assert {o.link for o in centers.omegas} == set(links) - {solution.mechanism.ground, "2"}
    assert solution.check.relative["instant_center"] <= 1e-9


# ----------------------------------------------------------------------------------------------
# Hypothesis: random four-bars, slider-cranks, slotted levers, six-bars
# ----------------------------------------------------------------------------------------------


@settings(max_examples=40, deadline=None)
@given(lengths, lengths, lengths, lengths, angles, speeds)
def test_four_bar_centers(a1: float, a2: float, a3: float, a4: float, th: float, w: float) -> None:
    d = abs(a1 - a2 * complex(math.cos(math.radians(th)), math.sin(math.radians(th))))  # |A B0|
    assume(abs(a3 - a4) + 1e-3 * d < d < a3 + a4 - 1e-3 * d)  # assembles, away from the dead and change points
    assume(abs((a3 * a3 + a4 * a4 - d * d) / (2 * a3 * a4)) < 0.95)  # transmission angle away from 0 and 180 deg
    check_all_centers(solve_text(four_bar(a1, a2, a3, a4, th, w, 0.0, guess_b=(a1, a3 + a4), find=ALL)))


@settings(max_examples=40, deadline=None)
@given(st.floats(min_value=5.0, max_value=50.0), st.floats(min_value=1.5, max_value=8.0),
       st.floats(min_value=-0.9, max_value=0.9), angles, speeds)
def test_slider_crank_centers(a2: float, ratio: float, offset: float, th: float, w: float) -> None:
    text = slider_crank(a2, ratio * a2, offset * a2, th, w, 0.0, find='[find]\ninstant_centers = "all"\nomega = ["3"]')
    solution = solve_text(text)
    check_all_centers(solution)
    assert solution.centers is not None
    assert solution.centers.center("14").direction == pytest.approx((0.0, 1.0), abs=1e-12)  # perpendicular to the slide


@settings(max_examples=40, deadline=None)
@given(st.floats(min_value=40.0, max_value=200.0), st.floats(min_value=0.1, max_value=0.9),
       st.floats(min_value=-0.3, max_value=0.3), angles, speeds)
def test_slotted_lever_centers(a1: float, crank_ratio: float, offset: float, th: float, w: float) -> None:
    a2 = crank_ratio * a1
    text = slotted_lever(a1, a2, offset * a2, th, w, 0.0, guess_f=(a1, a1), find='instant_centers = "all"')
    solution = solve_text(text)
    check_all_centers(solution)
    assert solution.centers is not None
    # block 3 turns with lever 4: I34 is at infinity, and omega13 = omega14
    assert solution.centers.center("34").is_at_infinity
    omegas = {o.link: o.omega for o in solution.centers.omegas}
    assert omegas["3"] == pytest.approx(omegas["4"], rel=1e-12, abs=1e-12)


@settings(max_examples=30, deadline=None)
@given(st.floats(min_value=80.0, max_value=140.0), st.floats(min_value=20.0, max_value=50.0),
       st.floats(min_value=80.0, max_value=150.0), st.floats(min_value=60.0, max_value=120.0),
       st.tuples(st.floats(min_value=30.0, max_value=90.0), st.floats(min_value=20.0, max_value=160.0)),
       st.floats(min_value=80.0, max_value=160.0), st.floats(min_value=-60.0, max_value=60.0), angles, speeds,
       st.booleans())
def test_six_bar_centers(a1: float, a2: float, a3: float, a4: float, d: tuple[float, float], a5: float, h: float,
                         th: float, w: float, slider: bool) -> None:
    solution = solve_text(six_bar(a1, a2, a3, a4, d, a5, h, th, w, slider=slider))
    check_all_centers(solution)
    assert solution.centers is not None
    assert len(solution.centers.steps) == 15 - 7  # every center not at a joint is derived, once


# ----------------------------------------------------------------------------------------------
# Fixed cases
# ----------------------------------------------------------------------------------------------


def test_six_bar_example_all_fifteen_centers() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "centers-six-bar.toml"))
    check_all_centers(solution)
    centers = solution.centers
    assert centers is not None
    assert len(centers.centers) == 15 and len(centers.steps) == 8
    assert centers.center("16").direction == pytest.approx((0.0, 1.0))
    # the slider's block 6 translates: omega16 = 0, and the polygon agrees with the centers on every link
    omegas = {o.link: o.omega for o in centers.omegas}
    assert omegas["6"] == 0.0
    for link in ("3", "4", "5"):
        assert solution.velocity is not None
        assert omegas[link] == pytest.approx(solution.velocity.omega[link], rel=1e-12)
    # the textbook's example: edge 24 closes triangles 124 and 234
    step24 = next(s for s in centers.steps if s.center == "24")
    assert set(step24.triangles) == {"124", "234"}
    assert {line.label for line in step24.lines} == {"I12 I14", "I23 I34"}


def test_six_bar_asking_one_center_derives_only_its_path() -> None:
    every = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "centers-six-bar.toml"))
    one = kinepoly.solve(kinepoly.loads_scene(SIX_BAR.replace('instant_centers = "all"', 'instant_centers = ["13"]')))
    assert one.centers is not None and every.centers is not None
    assert [s.center for s in one.centers.steps] == ["13"]
    assert len(one.centers.steps) < len(every.centers.steps)
    assert one.centers.center("13").position == pytest.approx(every.centers.center("13").position, rel=1e-12)
    # I36 needs I46 and I13 (triangles 346 and 136), not the six other derived centers
    far = kinepoly.solve(kinepoly.loads_scene(SIX_BAR.replace('instant_centers = "all"', 'instant_centers = ["36"]')))
    assert far.centers is not None
    assert sorted(s.center for s in far.centers.steps) == ["13", "36", "46"]
    assert far.centers.center("36").position == pytest.approx(every.centers.center("36").position, rel=1e-12)


def test_asking_a_joint_center_solves_no_group() -> None:
    text = SIX_BAR.split("[find]")[0] + '[find]\ninstant_centers = ["21"]\n'
    solution = kinepoly.solve(kinepoly.loads_scene(text))
    assert solution.plan.groups == () and set(solution.pose.links) == {"1", "2"}
    assert solution.centers is not None and solution.centers.steps == ()
    assert solution.centers.center("21").position == pytest.approx((0.0, 0.0))
    # asking I24 needs the four-bar 1-2-3-4 only, not the group 5-6
    text = SIX_BAR.split("[find]")[0] + '[find]\ninstant_centers = ["24"]\n'
    solution = kinepoly.solve(kinepoly.loads_scene(text))
    assert [set(g.links) for g in solution.plan.groups] == [{"3", "4"}]


def test_plan_kennedy_is_the_circle_diagram() -> None:
    links = ("1", "2", "3", "4")
    joints = frozenset({("1", "2"), ("2", "3"), ("3", "4"), ("1", "4")})
    plan = plan_kennedy(links, joints, (("2", "4"),))
    assert plan.order == (("2", "4"),) and plan.chosen[("2", "4")] == ("1", "3") and not plan.unreachable
    # a chain with too few joints: nothing closes two triangles
    plan = plan_kennedy(links, frozenset({("1", "2"), ("2", "3"), ("3", "4")}), (("1", "3"),))
    assert plan.order == () and plan.unreachable == (("1", "3"),)


@settings(max_examples=30, deadline=None)
@given(st.floats(min_value=20.0, max_value=200.0), st.floats(min_value=10.0, max_value=150.0),
       st.floats(min_value=-170.0, max_value=170.0).filter(lambda t: abs(t) > 1.0), speeds)
def test_parallelogram_centers_at_infinity(a1: float, a2: float, th: float, w: float) -> None:
    t = math.radians(th)
    guess = (a2 * math.cos(t) + a1, a2 * math.sin(t))
    solution = solve_text(four_bar(a1, a2, a1, a2, th, w, 0.0, guess_b=guess, find=ALL))
    centers = solution.centers
    assert centers is not None
    i13, i24 = centers.center("13"), centers.center("24")
    assert i13.is_at_infinity and i24.is_at_infinity
    assert i13.direction is not None and i24.direction is not None
    # I13 runs along the crank (parallel to the rocker), I24 along the frame (parallel to the coupler)
    assert abs(i13.direction[0] * math.sin(t) - i13.direction[1] * math.cos(t)) <= 1e-12
    assert i24.direction == pytest.approx(canonical_direction((1.0, 0.0)), abs=1e-12)
    omegas = {o.link: o.omega for o in centers.omegas}
    assert omegas["3"] == 0.0 and omegas["4"] == pytest.approx(w, rel=1e-12)  # the coupler translates
    out = kinepoly.to_json(solution)["instant_centers"]
    assert set(out["13"]) == {"direction"} and set(out["24"]) == {"direction"}
    assert set(out["12"]) == {"position"}


def test_nearly_parallel_kennedy_lines_warn_with_their_error() -> None:
    solution = kinepoly.solve(kinepoly.loads_scene(four_bar(100, 40, 100, 40 * (1 + 1e-8), 60, 10, 0,
                                                            guess_b=(120, 35), find=ALL)))
    assert solution.centers is not None
    far = solution.centers.center("13")
    assert far.position is not None and math.hypot(*far.position) > 1e9
    warnings = [n.message for n in solution.notices if n.code == "center-ill-conditioned"]
    assert any("I13" in m and "nearly parallel" in m and "relative error of about" in m for m in warnings)
    # the ratio of distances stays accurate however far the center
    assert solution.check.relative["instant_center"] <= 1e-12


def test_far_from_the_origin_nothing_is_lost() -> None:
    near = kinepoly.solve(kinepoly.loads_scene(four_bar(100, 40, 120, 80, 60, 10, 0, guess_b=(120, 80), find=ALL)))
    shift = 1e6
    text = four_bar(100, 40, 120, 80, 60, 10, 0, guess_b=(120 + shift, 80 + shift), find=ALL)
    frame = "A0 = [0, 0], B0 = [100, 0]"
    assert frame in text
    text = text.replace(frame, f"A0 = [{shift}, {shift}], B0 = [{100 + shift}, {shift}]", 1)
    far = kinepoly.solve(kinepoly.loads_scene(text))
    assert near.centers is not None and far.centers is not None
    for name in ("13", "24"):
        a, b = near.centers.center(name).position, far.centers.center(name).position
        assert a is not None and b is not None
        assert math.hypot(b[0] - shift - a[0], b[1] - shift - a[1]) <= 1e-9 * math.hypot(*a)


# ----------------------------------------------------------------------------------------------
# The homogeneous kernel
# ----------------------------------------------------------------------------------------------


def test_wedge_joins_and_crosses_with_points_at_infinity() -> None:
    frame = LocalFrame((10.0, 20.0), 50.0)
    a, b = frame.point((0.0, 0.0)), frame.point((100.0, 50.0))
    up = frame.point_at_infinity((0.0, 1.0))
    line_ab = wedge(a, b).value
    vertical = wedge(frame.point((40.0, -7.0)), up).value
    assert line_ab is not None and vertical is not None
    crossing = wedge(line_ab, vertical).value
    assert crossing is not None
    assert frame.place(crossing).position == pytest.approx((40.0, 20.0), rel=1e-14)
    parallel = wedge(frame.point((0.0, 5.0)), frame.point((100.0, 55.0))).value
    assert parallel is not None
    at_infinity = wedge(line_ab, parallel).value
    assert at_infinity is not None
    place = frame.place(at_infinity)
    assert place.is_at_infinity and place.direction == pytest.approx(canonical_direction((2.0, 1.0)))
    assert place.homogeneous[2] == 0.0
    # one point twice, or one line twice: no value, never NaN
    assert wedge(a, frame.point((0.0, 0.0))).value is None
    assert wedge(line_ab, line_ab).value is None
    # two points at infinity: the line at infinity; it crosses a finite line at that line's direction
    at_inf_line = wedge(up, frame.point_at_infinity((1.0, 0.0))).value
    assert at_inf_line is not None and frame.line(at_inf_line) is None
    meet = wedge(at_inf_line, line_ab).value
    assert meet is not None and frame.place(meet).direction == pytest.approx(canonical_direction((2.0, 1.0)))


def test_canonical_direction_and_offset() -> None:
    assert canonical_direction((0.0, -2.0)) == (0.0, 1.0)
    assert canonical_direction((-3.0, 0.0)) == (1.0, 0.0)
    assert canonical_direction((-0.0, 1.0)) == (0.0, 1.0)
    frame = LocalFrame((1.0, 2.0), 3.0, offset=(1e6, -1e6))
    assert frame.place(frame.point((4.0, 5.0))).position == pytest.approx((1e6 + 4.0, -1e6 + 5.0), abs=1e-9)


# ----------------------------------------------------------------------------------------------
# What the user sees: JSON, table, steps, errors
# ----------------------------------------------------------------------------------------------


def test_json_keys_as_asked_and_kennedy_steps(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = tmp_path / "scene.toml"
    path.write_text(SIX_BAR.replace('instant_centers = "all"', 'instant_centers = ["31", "1-6", "36"]'))
    code, out, err = run(capsys, "solve", str(path), "--json")
    assert code == 0, err
    data = json.loads(out)
    centers = data["instant_centers"]
    assert list(centers) == ["31", "16", "36"]  # the loader writes "1-6" as "16"
    assert set(centers["31"]) == {"position"} and set(centers["16"]) == {"direction"}
    assert centers["16"]["direction"] == [0.0, 1.0]
    kennedy = [s for s in data["steps"] if s["kind"] == "kennedy"]
    assert [s["result"] for s in kennedy] == ["I13", "I46", "I36"]
    for step in kennedy:
        assert step["polygon"] == "instant-centers" and len(step["lines"]) == 2
        assert all(line["label"] in step["equation"] for line in step["lines"])
        assert all(f"I{name}" in step["text"] for line in step["lines"] for name in line["centers"])
    assert {k for k in data["check"]["differences"] if k.startswith("instant_centers.")} >= {
        "instant_centers.omega13.analytic", "instant_centers.omega14.analytic"}
    assert data["check"]["relative"]["instant_center"] <= 1e-12


def test_table_and_steps_print_the_centers(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "solve", str(EXAMPLES / "centers-six-bar.toml"))
    assert code == 0
    assert "I16     at infinity, direction (0, 1)" in out and "Kennedy step 3: triangles 124 and 234" in out
    assert "omega from the instant centers" in out
    code, out, _ = run(capsys, "solve", str(EXAMPLES / "centers-six-bar.toml"), "--steps")
    assert code == 0
    assert out.count("[instant centers, kennedy]") == 8
    assert "omega13 = omega12 (I12 I23)/(I13 I23)" in out


def test_no_centers_unless_asked() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "four-bar.toml"))
    assert solution.centers is None
    data = kinepoly.to_json(solution)
    assert "instant_centers" not in data and all(s["kind"] != "kennedy" for s in data["steps"])


def test_a_given_scene_has_no_pair_of_links(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = tmp_path / "given.toml"
    path.write_text((EXAMPLES / "image-point.toml").read_text().replace("[find]", '[find]\ninstant_centers = "all"'))
    code, _, err = run(capsys, "solve", str(path))
    assert code == 2
    assert "find.instant_centers" in err and "no frame link" in err and "Traceback" not in err


def test_degenerate_position_says_which_lines(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    # crank, coupler and rocker folded onto the frame line: both Kennedy lines of I13 are that line
    path = tmp_path / "folded.toml"
    path.write_text(four_bar(100, 40, 20, 80, 0.0, 10, 0, guess_b=(60, 1), find='[find]\ninstant_centers = ["13"]'))
    code, _, err = run(capsys, "solve", str(path))
    assert code == 3
    assert "I13" in err and "I12 I23 and I14 I34 are one line" in err and "Traceback" not in err
