"""Inputs anywhere (several, relative rotations, cylinders between moving links) and triads by the Assur point.

Each example is checked against values derived here on their own, shared with nothing in kinepoly:
the positions from the examples' own geometry (circle intersections written below), and the
velocities and accelerations as time derivatives of those positions by central differences,
with every input moving at its own rate, v(t) = v0 + rate t + acc t^2 / 2.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.cli_support import run

import kinepoly
from kinepoly.errors import MobilityError

EXAMPLES = Path(__file__).parents[2] / "examples"


def _meet(c1: complex, r1: float, c2: complex, r2: float, near: complex) -> complex:
    """The crossing of two circles nearest ``near``."""
    d = abs(c2 - c1)
    a = (d * d + r1 * r1 - r2 * r2) / (2 * d)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    e = (c2 - c1) / d
    return min((c1 + a * e + s * 1j * h * e for s in (1, -1)), key=lambda p: abs(p - near))


def _derivatives(position: Callable[[float], complex], h: float = 1e-4) -> tuple[complex, complex, complex]:
    """Position, velocity (4th-order central difference) and acceleration at t = 0."""
    p = {k: position(k * h) for k in (-2, -1, 0, 1, 2)}
    v = (p[-2] - 8 * p[-1] + 8 * p[1] - p[2]) / (12 * h)
    a = (-p[-2] + 16 * p[-1] - 30 * p[0] + 16 * p[1] - p[2]) / (12 * h * h)
    return p[0], v, a


def _close(got: tuple[float, float], want: complex, scale: float, rel: float = 1e-6) -> None:
    assert abs(complex(*got) - want) <= rel * scale, (got, want)


def _solved(name: str) -> kinepoly.Solution:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    assert solution.check.max_rel_error <= 1e-9
    return solution


def test_five_bar_with_two_cranks() -> None:
    s = _solved("five-bar")
    a0, e0 = 0j, 150 + 0j

    def b_at(t: float) -> complex:
        th2 = math.radians(70) + 8 * t
        th5 = math.radians(110) - 5 * t + t * t
        a, c = a0 + 50 * cmath.exp(1j * th2), e0 + 60 * cmath.exp(1j * th5)
        return _meet(a, 110, c, 100, complex(90, 140))

    b, v, a = _derivatives(b_at)
    _close(s.position("B"), b, 1e3, 1e-12)
    assert s.velocity is not None and s.acceleration is not None
    _close(s.velocity.tips["B"], v, abs(v))
    _close(s.acceleration.tips["B"], a, abs(a), 1e-5)


def test_a_motor_between_crank_and_coupler() -> None:
    s = _solved("motor-on-coupler")
    b0 = 120 + 0j

    def a_at(t: float) -> complex:
        """theta2 such that B = A + 110 e^(i (theta2 + theta23)) is 90 from B0: the crank's tip A."""
        th23 = math.radians(-50) + 6 * t

        def miss(th2: float) -> float:
            a = 45 * cmath.exp(1j * th2)
            return abs(a + 110 * cmath.exp(1j * (th2 + th23)) - b0) - 90

        low, high = math.radians(60), math.radians(90)  # brackets the example's assembly
        assert miss(low) * miss(high) < 0
        for _ in range(200):
            mid = 0.5 * (low + high)
            low, high = (mid, high) if miss(low) * miss(mid) > 0 else (low, mid)
        return 45 * cmath.exp(1j * 0.5 * (low + high))

    a, v, acc = _derivatives(a_at, 1e-3)
    _close(s.position("A"), a, 100, 1e-12)
    assert s.velocity is not None and s.acceleration is not None
    _close(s.velocity.tips["A"], v, abs(v))
    _close(s.acceleration.tips["A"], acc, abs(acc), 1e-4)
    assert s.velocity.omega["3"] - s.velocity.omega["2"] == pytest.approx(6.0, rel=1e-12)  # omega_23, the motor


def test_a_cylinder_tips_the_dump_body() -> None:
    s = _solved("dump-body")
    h, c0 = 0j, complex(-900, -300)
    hd = abs(complex(-700, 150))

    def d_at(t: float) -> complex:
        stroke = 520 + 40 * t  # the rod's point D runs along the barrel's axis from C0
        return _meet(c0, stroke, h, hd, complex(-640, 180))

    d, v, a = _derivatives(d_at, 1e-2)
    _close(s.position("D"), d, 1e3, 1e-12)
    assert s.velocity is not None and s.acceleration is not None
    _close(s.velocity.tips["D"], v, abs(v))
    _close(s.acceleration.tips["D"], a, abs(a), 1e-4)
    # the barrel's point under D moves perpendicular to C0D; the rod slides out of it at s_dot along C0D
    e = (d - c0) / abs(d - c0)
    rel = complex(*s.velocity.tips["D"]) - complex(*s.velocity.tips["D@3"])
    assert abs(rel - 40 * e) <= 1e-12 * 40
    assert s.slider("34").s == pytest.approx(520, rel=1e-12)


def test_the_triad_is_built_through_its_assur_point() -> None:
    s = _solved("triad")
    assert not [step for step in s.steps if step.kind == "linear-solve"]
    assur = [step for step in s.steps if step.topic == "assur-point"]
    assert {step.polygon for step in assur} == {"velocity", "acceleration"}
    # S is where the lines of two legs cross: on both lines, as the step names them
    at = complex(*s.position("S"))
    for step in assur:
        for name in ("first", "second"):
            leg = str(step.param(name))
            pivot, pin = {"4": ("E", "B"), "5": ("F", "C"), "6": ("A", "D")}[leg]
            p, q = complex(*s.position(pivot)), complex(*s.position(pin))
            assert abs(((at - p) / (q - p)).imag) <= 1e-12 * abs(at - p) / abs(q - p) + 1e-15
    tips = [step.result for step in s.steps if step.kind == "intersection" and step.polygon == "velocity"]
    assert set(tips) >= {"s", "b", "c", "d"}


@settings(max_examples=40, deadline=None)
@given(st.floats(20, 160), st.floats(-20, 20).filter(lambda w: w == 0 or abs(w) > 1e-6), st.floats(-5, 5))
def test_random_triads_agree_with_the_analytic_solution(angle: float, omega: float, alpha: float) -> None:
    """The crank of the triad six-bar at random angles and rates: the construction agrees with the analytic
    check, and the error estimate bounds the error actually made, wherever the group assembles."""
    text = (EXAMPLES / "triad.toml").read_text()
    text = text.replace("angle = 60", f"angle = {angle!r}").replace("omega = 5", f"omega = {omega!r}")
    text = text.replace("alpha = 2", f"alpha = {alpha!r}")
    try:
        solution = kinepoly.solve(kinepoly.loads_scene(text))
    except kinepoly.KinepolyError:
        return  # the group does not assemble at this angle from the guess
    assert not [step for step in solution.steps if step.kind == "linear-solve"]
    accuracy = solution.accuracy
    assert accuracy is not None and solution.check.max_rel_error <= 1e-9
    for kind, error in accuracy.normwise.items():
        assert error <= accuracy.estimated[kind], (kind, error, accuracy.estimated[kind])


def test_the_wrong_number_of_inputs_says_which_link_hangs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = (EXAMPLES / "five-bar.toml").read_text()
    second = text.index("\n[[input]]", text.index("\n[[input]]") + 1)
    one_input = text[:second] + "[guess]" + text.split("[guess]")[1]
    path = tmp_path / "one.toml"
    path.write_text(one_input)
    code, _, err = run(capsys, "solve", str(path))
    assert code == 2 and "mobility" in err and "one input" in err, err
    # the four-bar without B0 on the frame: link 4 hangs from B
    four = (EXAMPLES / "four-bar.toml").read_text().replace("B0 = [", "Q0 = [", 1)
    with pytest.raises(MobilityError, match=r"link 4 is joined only at B; its point\(s\) B0 are on no other link"):
        kinepoly.solve(kinepoly.loads_scene(four))


def test_a_sweep_row_equals_the_solve_for_a_relative_input() -> None:
    from kinepoly.sweep import prepare_sweep, run_sweep

    scene = kinepoly.load_scene(EXAMPLES / "motor-on-coupler.toml")
    solution = kinepoly.solve(scene)
    result = run_sweep(prepare_sweep(scene), start=-50.0, stop=-40.0, steps=10)
    assert solution.velocity is not None
    assert result.input.name == "theta_23"
    assert float(result.column("omega_2").values[0]) == pytest.approx(solution.velocity.omega["2"], rel=1e-12)


def test_an_excavator_with_two_cylinders() -> None:
    s = _solved("excavator")
    o, c0 = 0j, complex(300, -300)
    d0, e0, k0, g0, t0 = (complex(600, 300), complex(2000, 800), complex(900, 700), complex(1900, 1100),
                          complex(2600, -200))

    def tip_at(t: float) -> complex:
        d = _meet(o, abs(d0), c0, 680 + 50 * t, d0)  # the boom turns about O; its cylinder spans C0 D
        boom = (d - o) / (d0 - o)
        e, k = o + boom * (e0 - o), o + boom * (k0 - o)
        g = _meet(e, abs(g0 - e0), k, 1070 - 30 * t + 2.5 * t * t, e + boom * (g0 - e0))
        arm = (g - e) / (g0 - e0)
        return e + arm * (t0 - e0)

    tip, v, a = _derivatives(tip_at, 1e-3)
    _close(s.position("T"), tip, 3e3, 1e-12)
    assert s.velocity is not None and s.acceleration is not None
    _close(s.velocity.tips["T"], v, abs(v))
    _close(s.acceleration.tips["T"], a, abs(a), 1e-4)
    assert not [step for step in s.steps if step.kind == "linear-solve"]


def _rates(rows: list[tuple[complex, ...]], right: list[complex]) -> list[float]:
    """The real unknowns of vector equations sum_k x_k c_k = r (each complex equation two real rows)."""
    import numpy as np

    matrix = np.array([[c.real for c in row] for row in rows] + [[c.imag for c in row] for row in rows])
    rhs = np.array([r.real for r in right] + [r.imag for r in right])
    return [float(x) for x in np.linalg.solve(matrix, rhs)]


def test_the_romanian_kc0_group_by_the_texts_equations() -> None:
    """v_B = v_A + w1 x AB; v_D = v_B + w2 x BD = v_C + w3 x CD; v_H = v_B + w2 x BH = v_G + w4 x GH
    (section 2.2.2.6), then the same with the normal terms for the accelerations."""
    s = _solved("kc0-six-bar")
    p = {name: complex(*s.position(name)) for name in ("O", "A", "B", "C", "D", "G", "H")}
    w5, al5 = 10.0, -4.0
    va = w5 * 1j * (p["A"] - p["O"])
    aa = (al5 * 1j - w5 * w5) * (p["A"] - p["O"])
    ab, bd, cd, bh, gh = (p["B"] - p["A"], p["D"] - p["B"], p["D"] - p["C"], p["H"] - p["B"], p["H"] - p["G"])
    # unknowns w1, w2, w3, w4: (v_A + w1 k AB + w2 k BD) - w3 k CD = 0; (v_A + w1 k AB + w2 k BH) - w4 k GH = 0
    rows = [(1j * ab, 1j * bd, -1j * cd, 0j), (1j * ab, 1j * bh, 0j, -1j * gh)]
    w1, w2, w3, w4 = _rates(rows, [-va, -va])
    n = -(aa - w1 * w1 * ab - w2 * w2 * bd + w3 * w3 * cd)
    m = -(aa - w1 * w1 * ab - w2 * w2 * bh + w4 * w4 * gh)
    e1, e2, e3, e4 = _rates(rows, [n, m])
    assert s.velocity is not None and s.acceleration is not None
    for link, want in (("1", w1), ("2", w2), ("3", w3), ("4", w4)):
        assert s.velocity.omega[link] == pytest.approx(want, rel=1e-10)
    for link, want in (("1", e1), ("2", e2), ("3", e3), ("4", e4)):
        assert s.acceleration.alpha[link] == pytest.approx(want, rel=1e-9)
    vh = va + w1 * 1j * ab + w2 * 1j * bh
    _close(s.velocity.tips["H"], vh, abs(vh), 1e-10)
    # S lies on AB and on CD, as the text finds it
    at = complex(*s.position("S"))
    for first, second in (("A", "B"), ("C", "D")):
        u = p[second] - p[first]
        assert abs(((at - p[first]) / u).imag) <= 1e-9


def test_a_triad_with_a_slot_and_its_coriolis_term() -> None:
    """v_B = v_A + w3 x AB; v_D = v_B + w4 x BD = v_C + w5 x CD; v_K@4 = v_B + w4 x BK = v_K - u e;
    and a_K@4 = a_K - a_rel e - 2 w4 x u e (the block at K turns with link 4)."""
    s = _solved("triad-slot")
    p = {name: complex(*s.position(name)) for name in ("O", "A", "B", "C", "D", "K")}
    w2 = 10.0
    va, aa = w2 * 1j * (p["A"] - p["O"]), -w2 * w2 * (p["A"] - p["O"])
    ab, bd, cd, bk = p["B"] - p["A"], p["D"] - p["B"], p["D"] - p["C"], p["K"] - p["B"]
    e = cmath.exp(1j * (math.radians(63.43494882292201) + math.radians(float(s.angle("4")) * 180 / math.pi)))
    rows = [(1j * ab, 1j * bd, -1j * cd, 0j), (1j * ab, 1j * bk, 0j, e)]
    w3, w4, w5, u = _rates(rows, [-va, -va])
    n = -(aa - w3 * w3 * ab - w4 * w4 * bd + w5 * w5 * cd)
    m = -(aa - w3 * w3 * ab - w4 * w4 * bk + 2 * w4 * 1j * u * e)
    e3, e4, e5, _ = _rates(rows, [n, m])
    assert s.velocity is not None and s.acceleration is not None
    for link, want in (("3", w3), ("4", w4), ("5", w5)):
        assert s.velocity.omega[link] == pytest.approx(want, rel=1e-10)
    for link, want in (("3", e3), ("4", e4), ("5", e5)):
        assert s.acceleration.alpha[link] == pytest.approx(want, rel=1e-9)
    assert s.slider("46").s_dot == pytest.approx(u, rel=1e-10)
    assert s.slider("46").coriolis is not None and abs(complex(*s.slider("46").coriolis)) > 0


def test_a_stroke_the_body_cannot_reach_exits_3_with_the_inequality(tmp_path: Path,
                                                                   capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "long.toml"
    path.write_text((EXAMPLES / "dump-body.toml").read_text().replace("s = 520", "s = 2000"))
    code, _, err = run(capsys, "solve", str(path))
    assert code == 3, err
    assert "group 3+4-2" in err and "s34 driven" in err
    assert "|C0 H| = 948.683 < | |C0D| - |DH| | = | 2000 - 715.891 | = 1284.11" in err, err
    assert "held by s34" in err, err


def test_a_cylinder_sweep_runs_over_the_strokes_the_body_reaches() -> None:
    """With no range given, the stroke runs between | |C0H| - |HD| | and |C0H| + |HD|, where D is in line."""
    from kinepoly.sweep import prepare_sweep, run_sweep

    result = run_sweep(prepare_sweep(kinepoly.load_scene(EXAMPLES / "dump-body.toml")), steps=100)
    c0h, hd = abs(complex(-900, -300)), abs(complex(-700, 150))
    values = result.input.values
    assert float(values[0]) == pytest.approx(abs(c0h - hd), rel=1e-6)
    assert float(values[-1]) == pytest.approx(c0h + hd, rel=1e-6)


BLOCK_BY_CYLINDER = """
title = "A block pushed along the frame by a cylinder from a frame pin"
[links]
1 = { points = { C0 = [0, 0] } }
2 = { points = { D = [0, 0] } }
3 = { points = { C0 = [0, 0] } }
4 = { points = { D = [0, 0] } }
[[sliders]]
block = "2"
guide = "1"
point = "D"
line = { through = [0, 80], angle = 0 }
[[sliders]]
block = "4"
guide = "3"
point = "D"
line = { through = [0, 0], angle = 0 }
[input]
slider = "34"
s = 150
s_dot = 20
s_ddot = 3
[guess]
D = [126, 80]
"""


def test_a_cylinder_in_a_group_that_is_no_dyad_is_solved_with_its_stroke_as_an_equation() -> None:
    """The cylinder from C0 pushes the block D along y = 80: x = sqrt(s^2 - 80^2), x_dot = s s_dot / x,
    x_ddot = (s_dot^2 + s s_ddot - x_dot^2) / x."""
    s = kinepoly.solve(kinepoly.loads_scene(BLOCK_BY_CYLINDER))
    assert s.check.max_rel_error <= 1e-9
    x = math.sqrt(150**2 - 80**2)
    x_dot = 150 * 20 / x
    x_ddot = (20**2 + 150 * 3 - x_dot**2) / x
    assert s.velocity is not None and s.acceleration is not None
    _close(s.velocity.tips["D"], complex(x_dot, 0), x_dot, 1e-12)
    _close(s.acceleration.tips["D"], complex(x_ddot, 0), x_ddot, 1e-12)
    assert [step.kind for step in s.steps if step.kind == "linear-solve"] == ["linear-solve", "linear-solve"]
