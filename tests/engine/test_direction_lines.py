"""Every direction line a step draws passes through the tip the step finds (issue 24, section 1).

A student draws each line from where the terms laid before it end; the tip is where two such lines
cross, so it lies on both. Checked on every example and every scene the tests ship, for the velocity
and the acceleration polygon, to 1e-9 of the polygon's size. A triad's lines also start at the end of
their normal terms, so the tangential term a step prints (``Also |a^t_D/S| = ...``, the length from the
line's point to the tip) is |alpha| times the segment, as the independent analytic solution gives it.
"""

from __future__ import annotations

import re
import sys
from functools import cache
from pathlib import Path

import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from tests.hardening.support import BASE
from tests.scenes import EXAMPLES, cam_rocker, four_bar, slider_crank, slotted_lever

import kinepoly
from kinepoly.check.analytic import AnalyticSolution, solve_analytic
from kinepoly.engine.steps import Step
from kinepoly.geom.vec import Vec, cross, norm, sub, unit
from kinepoly.present.phrasing import Context, english, step_sentence
from kinepoly.present.scales import polygon_scales
from kinepoly.solution import Solution

TESTS = Path(__file__).resolve().parents[1]
SCENE_FILES = sorted(EXAMPLES.glob("*.toml")) + sorted(TESTS.glob("*/*.toml")) + sorted(TESTS.glob("*/scenes/*.toml"))
BUILT = {
    "four-bar": four_bar(100, 40, 120, 80, 60, 10, 5, guess_b=(110, 80)),
    "slider-crank": slider_crank(40, 120, 10, 60, 10, 3),
    "slotted-lever": slotted_lever(60, 30, 0, 50, 10, 4, guess_f=(0, 150)),
    "cam-knife": cam_rocker("knife"),
    "cam-inside": cam_rocker("inside"),
    "hardening-four-bar": BASE,
}
TRIADS = ("kc0-six-bar", "triad", "triad-slot", "spline-cam-floating-triad")


def _solve_file(path: Path) -> Solution:
    return kinepoly.solve(kinepoly.load_scene(path))


@cache
def _solved(name: str) -> Solution:
    path = next((p for p in SCENE_FILES if p.stem == name), None)
    return _solve_file(path) if path is not None else kinepoly.solve(kinepoly.loads_scene(BUILT[name]))


def _misses(solution: Solution) -> list[tuple[int, Step, float]]:
    """(step number, step, distance of its tip from the line / the polygon's size) for every line of every
    intersection step that misses its tip by more than 1e-9 of the polygon's size."""
    out = []
    for number, step in enumerate(solution.steps, 1):
        if step.kind != "intersection" or len(step.value) != 2:
            continue
        polygon = solution.velocity if step.polygon == "velocity" else solution.acceleration
        assert polygon is not None
        size = max([norm(tip) for tip in polygon.tips.values()] + [norm(step.value)])
        tip: Vec = (step.value[0], step.value[1])
        assert step.lines, f"step {number} ({step.equation}) draws no line"
        for line in step.lines:
            miss = abs(cross(sub(tip, line.through), unit(line.direction)))
            if miss > 1e-9 * size:
                out.append((number, step, miss / size))
    return out


def _report(name: str, solution: Solution) -> str:
    scales = polygon_scales(solution)
    lines = []
    for number, step, relative in _misses(solution):
        polygon = solution.velocity if step.polygon == "velocity" else solution.acceleration
        assert polygon is not None
        size = max(norm(tip) for tip in polygon.tips.values())
        lines.append(f"{name} step {number} ({step.polygon}) {step.equation}: the tip is off a line by "
                     f"{relative:.3g} of the polygon, {relative * size * scales[step.polygon]:.3g} mm on the paper")
    return "\n".join(lines)


@pytest.mark.parametrize("name", [p.stem for p in SCENE_FILES] + sorted(BUILT))
def test_every_intersection_tip_lies_on_each_of_its_lines(name: str) -> None:
    solution = _solved(name)
    if _misses(solution):
        pytest.fail(_report(name, solution))


@settings(max_examples=25, deadline=None)
@example("triad", 0.0, 2.43e-162, 1.0)
@given(st.sampled_from(("triad", "kc0-six-bar")), st.floats(-30.0, 30.0, allow_subnormal=False),
       st.floats(-20, 20, allow_subnormal=False), st.floats(-50, 50, allow_subnormal=False))
def test_random_triad_tips_lie_on_their_lines(name: str, turn: float, omega: float, alpha: float) -> None:
    """The triad examples at other crank angles and rates: the same, wherever the group assembles. An acceleration
    polygon made of subnormal numbers is left out: at omega = 0 and alpha = 5e-324, or at omega = 2.4e-162 (its
    square 5.9e-324) and alpha = 0, its terms have one significant bit, so no tip can lie within 1e-9 of it on a
    line. A rate whose square is subnormal beside a normal one still counts (the pinned example)."""
    assume(omega * omega >= sys.float_info.min or abs(alpha) >= sys.float_info.min)
    text = (EXAMPLES / f"{name}.toml").read_text()
    angle, w, al = {"triad": (60, 5, 2), "kc0-six-bar": (60, 10, -4)}[name]
    text = text.replace(f"angle = {angle}\n", f"angle = {angle + turn!r}\n", 1)
    text = (text.replace(f"omega = {w}\n", f"omega = {omega!r}\n", 1)
            .replace(f"alpha = {al}\n", f"alpha = {alpha!r}\n", 1))
    try:
        solution = kinepoly.solve(kinepoly.loads_scene(text))
    except kinepoly.KinepolyError:
        return  # the group does not assemble there from the guess
    if _misses(solution):
        pytest.fail(_report(name, solution))


# -- the tangential terms a triad's steps print ---------------------------------------------------------


def _analytic(solution: Solution) -> AnalyticSolution:
    return solve_analytic(solution.mechanism, dict(solution.pose.links), with_acceleration=True)


_ALSO = re.compile(r"\|([av](?:\^t)?_[^|]+)\| = ([−-]?[\d.]+(?:e[+-]?\d+)?)")


def _c(v: Vec) -> complex:
    return complex(v[0], v[1])


def _tangential(solution: Solution, exact: AnalyticSolution, term: str, ternary: str) -> complex | None:
    """The analytic tangential term ``a^t_P/R`` (alpha x RP of the link carrying both points, the ternary where
    both are its points, its Assur point included), or a sum of two such terms (``a^t_B/E + a^t_S/B``); None for
    a term of another kind (a sliding term)."""
    assur = {str(step.param("point")) for step in solution.steps if step.topic == "assur-point"}
    total = 0j
    for part in term.split(" + "):
        m = re.fullmatch(r"a\^t_([^/@]+)(?:@\w+)?/([^/@]+)", part.strip())
        if m is None:
            return None
        point, reference = m.groups()
        mech = solution.mechanism
        links = [k for k in mech.link_names if (mech.has_point(k, point) or point in assur)
                 and (mech.has_point(k, reference) or reference in assur)]
        link = ternary if ternary in links else links[0] if len(links) == 1 else None
        if link is None:
            return None
        assert exact.alpha is not None
        total += exact.alpha[link] * 1j * (_c(solution.position(point)) - _c(solution.position(reference)))
    return total


@pytest.mark.parametrize("name", TRIADS)
def test_a_triad_prints_each_tangential_term_alone(name: str) -> None:
    """|a^t| from the line's point to the tip, and as the step's text prints it, equals |alpha| x the segment
    (for the Assur point's line, the sum of the leg's and the ternary's terms along it)."""
    solution = _solved(name)
    exact = _analytic(solution)
    context = Context(solution, polygon_scales(solution))
    checked = 0
    for step in solution.steps:
        triad = step.topic == "assur-tip" or any(k == "triad" for k, _ in step.params)
        if not triad or step.polygon != "acceleration" or step.kind != "intersection":
            continue
        ternary = str(step.param("ternary")) if step.topic == "assur-tip" else str(step.param("triad")).split("-")[0]
        printed = dict(_ALSO.findall(step_sentence(step, english(), context)))
        for direction, line in zip(step.directions, step.lines, strict=True):
            want = _tangential(solution, exact, direction.term, ternary)
            if want is None:
                continue
            drawn = norm(sub((step.value[0], step.value[1]), line.through))
            size = max(norm(t) for t in solution.acceleration.tips.values()) if solution.acceleration else 1.0
            assert drawn == pytest.approx(abs(want), rel=1e-9, abs=1e-9 * size), (step.equation, direction.term)
            if direction.term in printed:
                shown = float(printed[direction.term].replace("−", "-"))
                assert shown == pytest.approx(abs(want), rel=1e-4, abs=1e-9 * size), (direction.term, shown)
            checked += 1
    assert checked >= 4
