"""The loop-closure method against the polygons: every example it covers, random four-bars, slider-cranks
and slotted levers (hypothesis), its loop count, its derivation and ``solve --method loops``."""

from __future__ import annotations

import json
import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from tests.cli_support import run
from tests.scenes import EXAMPLES, four_bar, slider_crank, slotted_lever

import kinepoly
from kinepoly.errors import AssemblyError, SingularityError
from kinepoly.loops import LoopMethodError, loop_count, loop_method_solution
from kinepoly.loops.contours import uncovered
from kinepoly.loops.text import derivation_lines
from kinepoly.present.catalogue import load_catalogue

COVERED = sorted(p.stem for p in EXAMPLES.glob("*.toml")
                 if uncovered(kinepoly.solve(kinepoly.load_scene(p)).mechanism) is None)
NOT_COVERED = sorted(p.stem for p in EXAMPLES.glob("*.toml") if p.stem not in COVERED)


def _c(v: tuple[float, float]) -> complex:
    return complex(*v)


def assert_loops_equal_polygons(solution: kinepoly.Solution, rel: float) -> None:
    """Every tip, omega, alpha and slider value of the loop method equals the polygons' to ``rel`` of its scale."""
    loops_solution, loops = loop_method_solution(solution)
    v, a = solution.velocity, solution.acceleration
    lv, la = loops_solution.velocity, loops_solution.acceleration
    size = max(abs(_c(solution.position(p.name))) for link in solution.scene.links for p in link.points
               if link.name in solution.pose.links) + 1.0
    if v is not None:
        assert lv is not None
        speed = max([abs(_c(t)) for t in v.tips.values()] + [1e-300])
        omega = max([abs(w) for w in v.omega.values()] + [1e-300])
        assert set(lv.tips) == set(v.tips) - set(solution.pose.marks)
        for label, tip in lv.tips.items():
            assert abs(_c(tip) - _c(v.tips[label])) <= rel * speed, label
        for link, w in v.omega.items():
            assert abs(lv.omega[link] - w) <= rel * omega, link
    if a is not None:
        assert la is not None
        accel = max([abs(_c(t)) for t in a.tips.values()] + [1e-300])
        for label, tip in la.tips.items():
            assert abs(_c(tip) - _c(a.tips[label])) <= rel * accel, label
        for link, al in a.alpha.items():
            assert abs(la.alpha[link] - al) <= rel * (accel / size), link
    for name, got in loops_solution.sliders.items():
        ref = solution.sliders[name]
        assert got.s == pytest.approx(ref.s, rel=rel, abs=rel * size)
        if ref.s_dot is not None:
            assert got.s_dot == pytest.approx(ref.s_dot, rel=rel, abs=rel * max(speed, 1.0))
        if ref.s_ddot is not None and ref.coriolis is not None:
            assert got.s_ddot == pytest.approx(ref.s_ddot, rel=rel, abs=rel * accel)
            assert got.coriolis is not None
            assert abs(_c(got.coriolis) - _c(ref.coriolis)) <= rel * accel
    for loop in loops.loops:  # the loop equations hold at the engine's positions
        assert abs(loop.closure()) <= 1e-12 * size * len(loop.terms)


def test_the_examples_covered_are_the_lower_pair_ones() -> None:
    assert {"four-bar", "slider-crank", "slotted-lever", "shaper", "kc0-six-bar", "triad", "triad-slot",
            "centers-six-bar", "toggle-press", "motor-on-coupler", "five-bar", "scotch-yoke"} <= set(COVERED)
    assert {"gear-pair", "metu-cam", "planetary", "image-point"} <= set(NOT_COVERED)


@pytest.mark.parametrize("name", COVERED)
def test_loop_equations_equal_the_polygons_on_every_example(name: str) -> None:
    assert_loops_equal_polygons(kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml")), 1e-9)


@pytest.mark.parametrize("name", COVERED)
def test_the_loops_are_independent_and_counted_by_the_formula(name: str) -> None:
    """N = j - n + 1 loops, each holding a joint no other loop holds (RO 2.2.1's criterion), each closing."""
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    _, loops = loop_method_solution(solution)
    mech = solution.mechanism
    assert len(loops.loops) == loop_count(mech) == len(mech.joints) - len(mech.link_names) + 1
    closings = [loop.closing for loop in loops.loops]
    assert len(set(closings)) == len(closings)
    for loop in loops.loops:
        assert loop.members[0] == mech.ground or mech.ground not in loop.members
        assert loop.closing in loop.joints and len(loop.joints) == len(loop.members)
        assert all(loop.closing not in other.joints for other in loops.loops if other is not loop)


@pytest.mark.parametrize("name", NOT_COVERED)
def test_scenes_with_higher_pairs_are_refused_by_name(name: str) -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    with pytest.raises(LoopMethodError, match="does not cover"):
        loop_method_solution(solution)


def _solve(text: str) -> kinepoly.Solution:
    try:
        solution = kinepoly.solve(kinepoly.loads_scene(text))
    except (AssemblyError, SingularityError):
        assume(False)
        raise
    assume(solution.check.condition_number < 1e4)
    assume(not any(n.code == "near-singular" for n in solution.notices))
    return solution


lengths = st.floats(min_value=10.0, max_value=200.0)
angles = st.floats(min_value=-180.0, max_value=180.0)
speeds = st.floats(min_value=-50.0, max_value=50.0).filter(lambda w: abs(w) > 0.1)
accels = st.floats(min_value=-500.0, max_value=500.0)


@settings(max_examples=40, deadline=None)
@given(lengths, lengths, lengths, lengths, angles, speeds, accels)
def test_random_four_bars(a1: float, a2: float, a3: float, a4: float, th: float, w: float, al: float) -> None:
    d = abs(a1 - a2 * complex(math.cos(math.radians(th)), math.sin(math.radians(th))))
    assume(abs(a3 - a4) + 1e-3 * d < d < a3 + a4 - 1e-3 * d)
    assert_loops_equal_polygons(_solve(four_bar(a1, a2, a3, a4, th, w, al, guess_b=(a1, a3 + a4))), 1e-8)


CRANK_FIND = ('[find]\nsliders = ["14"]\nvelocity = ["B", "C"]\nacceleration = ["B", "C"]\nomega = ["3"]\n'
              'alpha = ["3"]')


@settings(max_examples=40, deadline=None)
@given(lengths, lengths, st.floats(-60.0, 60.0), angles, speeds, accels)
def test_random_slider_cranks(a2: float, a3: float, offset: float, th: float, w: float, al: float) -> None:
    assert_loops_equal_polygons(_solve(slider_crank(a2, a3, offset, th, w, al, find=CRANK_FIND)), 1e-8)


@settings(max_examples=30, deadline=None)
@given(lengths, lengths, st.floats(-40.0, 40.0), angles, speeds, accels)
def test_random_slotted_levers(a1: float, a2: float, offset: float, th: float, w: float, al: float) -> None:
    assume(abs(a1 - a2) > 5.0)
    assert_loops_equal_polygons(_solve(slotted_lever(a1, a2, offset, th, w, al, guess_f=(a1, 0.0))), 1e-8)


def test_a_four_bar_by_hand() -> None:
    """The four-bar example's omega_13 and omega_14 by Cramer's rule written out here from its loop equation."""
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "four-bar.toml"))
    t2, t3, t4 = (solution.angle(k) for k in "234")
    # i w2 a2 e^{it2} + i w3 a3 e^{it3} - i w4 a4 e^{it4} = 0, real and imaginary parts
    a11, a12, b1 = -120 * math.sin(t3), 80 * math.sin(t4), 10 * 40 * math.sin(t2)
    a21, a22, b2 = 120 * math.cos(t3), -80 * math.cos(t4), -10 * 40 * math.cos(t2)
    det = a11 * a22 - a12 * a21
    _, loops = loop_method_solution(solution)
    assert loops.omega["3"] == pytest.approx((b1 * a22 - a12 * b2) / det, rel=1e-12)
    assert loops.omega["4"] == pytest.approx((a11 * b2 - b1 * a21) / det, rel=1e-12)
    block = next(b for b in loops.velocity_blocks if b.kind == "cramer")
    assert block.unknowns == ("3", "4")


def test_the_derivation_names_the_texts_terms() -> None:
    """The slotted lever's derivation: its loop, the Coriolis term, Cramer's rule, in en, tr and ro."""
    _, loops = loop_method_solution(kinepoly.solve(kinepoly.load_scene(EXAMPLES / "slotted-lever.toml")))
    for code in ("en", "tr", "ro"):
        text = "\n".join(derivation_lines(loops, load_catalogue(code)))
        assert "N = j − n + 1 = 4 − 4 + 1 = 1" in text
        assert "s_43 e^{i(θ_14 + 90°)}" in text
        assert "2 i ω_14 ṡ_43" in text
        assert "a^c" in text
        assert "Δ =" in text and "ω_14 = " in text and "s̈_43 = " in text
    triad = "\n".join(derivation_lines(loop_method_solution(
        kinepoly.solve(kinepoly.load_scene(EXAMPLES / "triad.toml")))[1]))
    assert "coupled" in triad and "Cramer" not in triad


def test_solve_method_loops_json_and_steps(capsys: pytest.CaptureFixture[str]) -> None:
    path = str(EXAMPLES / "shaper.toml")
    code, polygons, _ = run(capsys, "solve", path, "--json")
    assert code == 0
    code, out, _ = run(capsys, "solve", path, "--json", "--method", "loops")
    assert code == 0
    loops, ref = json.loads(out), json.loads(polygons)
    assert loops["method"] == "loops" and "method" not in ref
    assert [loop["members"] for loop in loops["loops"]] == [["1", "2", "3", "4"], ["1", "4", "5", "6"]]
    assert loops["loops"][0]["unknowns"] == ["θ_14", "s_43"]
    assert loops["loops"][1]["unknowns"] == ["θ_14", "θ_15", "s_16"]
    assert loops["loops"][0]["equation"] == "150 e^{i 90°} + 60 e^{i θ_12} − s_43 e^{i θ_14} = 0"
    assert set(loops) - {"method", "loops"} == set(ref)
    for part in ("links", "points"):
        for name, entry in ref[part].items():
            for key, value in entry.items():
                assert loops[part][name][key] == pytest.approx(value, rel=1e-9, abs=1e-9), (name, key)
    code, out, _ = run(capsys, "solve", path, "--steps", "--method", "loops")
    assert code == 0 and "Cramer's rule" in out and "Loop 2" in out


def test_solve_method_loops_refuses_a_gear_train(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "solve", str(EXAMPLES / "gear-pair.toml"), "--method", "loops")
    assert code == 2 and not out
    assert "--method loops" in err and "gears" in err and "Traceback" not in err


def test_a_coefficient_that_is_zero_is_written_as_zero() -> None:
    """The toggle press's block slides square to link 5's loop term: its coefficient is zero to rounding, and is
    written 0, never −0 or (0)."""
    _, loops = loop_method_solution(kinepoly.solve(kinepoly.load_scene(EXAMPLES / "toggle-press.toml")))
    text = "\n".join(derivation_lines(loops))
    assert "+ 0 ṡ_16" in text
    assert "− 0 " not in text and "(0)" not in text and "(−0)" not in text


def test_a_motor_between_moving_links_is_said_so() -> None:
    """motor-on-coupler: the input gives omega_13 - omega_12, so its equation is solved with the loop's."""
    _, loops = loop_method_solution(kinepoly.solve(kinepoly.load_scene(EXAMPLES / "motor-on-coupler.toml")))
    text = "\n".join(derivation_lines(loops))
    assert "loop 1 and the input's equation (a motor between moving links" in text
    assert "−1 ω_12 + 1 ω_13 + 0 ω_14 = 6" in text
