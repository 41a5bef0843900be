"""Tests of the independent analytic solution (kinepoly.check.analytic).

Every reference value here is a closed form derived from a complex loop equation, a finite
difference of the solver's own positions, or a 50-digit mpmath solution; none uses the
graphical construction.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable

import mpmath as mp
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from msgspec.structs import replace

from kinepoly.check.analytic import AnalyticSolution, solve_analytic
from kinepoly.errors import AssemblyError, SceneError, SingularityError
from kinepoly.model.mechanism import build_mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.scene.spec import (
    GivenInput,
    GivenPoint,
    LinkInput,
    LinkSpec,
    PointSpec,
    Scene,
    SliderInput,
    SliderSpec,
    Units,
)

RAD = math.radians



def _expj(x: object) -> object:
    """e^{ix} in mpmath, written out (mpmath 1.4's expj no longer takes a real mpf)."""
    return mp.mpc(mp.cos(x), mp.sin(x))

def link(name: str, **points: tuple[float, float]) -> LinkSpec:
    return LinkSpec(name, tuple(PointSpec(k, v) for k, v in points.items()))


def polar(r: float, deg: float) -> tuple[float, float]:
    return (r * math.cos(RAD(deg)), r * math.sin(RAD(deg)))


def cvec(v: tuple[float, float]) -> complex:
    return complex(v[0], v[1])


def close(actual: complex, expected: complex, scale: float, rel: float = 1e-10) -> bool:
    return abs(complex(actual) - complex(expected)) <= rel * max(abs(expected), scale)


def with_input(scene: Scene, **changes: float) -> Scene:
    return replace(scene, input=replace(scene.input, **changes))


# --------------------------------------------------------------------------------------------
# Slider-crank (section 4.2, first example): s14 + i c1 + a3 e^{i th13} = a2 e^{i th12}
# --------------------------------------------------------------------------------------------


def slider_crank(
    a2: float, a3: float, c1: float, th12: float, w12: float, al12: float, b3: float = 50.0, gamma3_deg: float = 30.0
) -> Scene:
    return Scene(
        title="slider-crank",
        units=Units(),
        ground="1",
        links=(
            link("1", A0=(0.0, 0.0)),
            link("2", A0=(0.0, 0.0), A=(a2, 0.0)),
            link("3", B=(0.0, 0.0), A=(a3, 0.0), C=polar(b3, -gamma3_deg)),
            link("4", B=(0.0, 0.0)),
        ),
        sliders=(SliderSpec("14", "4", "1", "B", (0.0, c1), 0.0),),
        input=LinkInput("2", th12, w12, al12),
    )


def slider_crank_position(a2: float, a3: float, c1: float, th12: float) -> tuple[float, float]:
    """theta13 (angle of BA) and s14, B to the right of A: a3 sin th13 = a2 sin th12 - c1."""
    th13 = math.pi - math.asin((a2 * math.sin(th12) - c1) / a3)
    s14 = a2 * math.cos(th12) - a3 * math.cos(th13)
    return th13, s14


def slider_crank_start(a2: float, a3: float, c1: float, th12: float, jitter: float = 0.0) -> dict[str, LinkPose]:
    th13, s14 = slider_crank_position(a2, a3, c1, th12)
    return {
        "2": LinkPose(0.0, 0.0, th12 + jitter),
        "3": LinkPose(s14 + 40 * jitter, c1 - 20 * jitter, th13 - jitter),
        "4": LinkPose(s14 - 30 * jitter, c1 + 10 * jitter, 2 * jitter),
    }


SLIDER_CRANK_CASES = [
    (60.0, 10.0, 0.0),
    (60.0, 10.0, 7.5),
    (135.0, -7.0, 25.0),
    (250.0, 3.0, -40.0),
    (-20.0, 12.5, 100.0),
    (0.0, 1.0, 0.0),
]


@pytest.mark.parametrize(("deg", "w12", "al12"), SLIDER_CRANK_CASES)
def test_slider_crank_closed_forms(deg: float, w12: float, al12: float) -> None:
    a2, a3, c1, b3, g3 = 40.0, 120.0, 10.0, 50.0, RAD(30.0)
    th12 = RAD(deg)
    scene = slider_crank(a2, a3, c1, th12, w12, al12)
    mech = build_mechanism(scene)
    sol = solve_analytic(mech, slider_crank_start(a2, a3, c1, th12, jitter=0.03), with_acceleration=True)
    th13, s14 = slider_crank_position(a2, a3, c1, th12)

    # (4), (5)
    s14_dot = -a2 * math.sin(th12 - th13) / math.cos(th13) * w12
    w13 = a2 / a3 * math.cos(th12) / math.cos(th13) * w12
    # (9)
    al13 = (a2 * al12 * math.cos(th12) - a2 * w12**2 * math.sin(th12) + a3 * w13**2 * math.sin(th13)) / (
        a3 * math.cos(th13)
    )
    # (10) re-derived: the real part of (8a) is
    # s14_ddot - a3 al13 sin th13 - a3 w13^2 cos th13 = -a2 al12 sin th12 - a2 w12^2 cos th12
    # (the seed prints "+ i a3 al13 sin th13"; there is no i).
    s14_ddot = (
        -a2 * al12 * math.sin(th12)
        - a2 * w12**2 * math.cos(th12)
        + a3 * al13 * math.sin(th13)
        + a3 * w13**2 * math.cos(th13)
    )

    vscale, ascale = a2 * abs(w12), a2 * (w12**2 + abs(al12))
    assert sol.poses["3"].theta == pytest.approx(th13, rel=1e-12)
    assert close(sol.omega["3"], w13, vscale / a3)
    assert close(sol.alpha["3"], al13, ascale / a3)
    assert sol.omega["4"] == 0.0 and sol.alpha["4"] == 0.0
    sv = sol.slider_values(mech, "14")
    assert close(sv["s"], s14, a3)
    assert close(sv["s_dot"], s14_dot, vscale)
    assert close(sv["s_ddot"], s14_ddot, ascale)
    assert sv["coriolis"] == (0.0, 0.0)
    assert close(cvec(sol.point_velocity(mech, "B")), s14_dot, vscale)
    assert close(cvec(sol.point_acceleration(mech, "B")), s14_ddot, ascale)

    # (11), (12), (13): C at b3 e^{i(th13 - gamma3)} from B
    eC = cmath.exp(1j * (th13 - g3))
    assert close(cvec(sol.point_position(mech, "C")), s14 + 1j * c1 + b3 * eC, a3)
    assert close(cvec(sol.point_velocity(mech, "C")), s14_dot + 1j * b3 * w13 * eC, vscale)
    assert close(cvec(sol.point_acceleration(mech, "C")), s14_ddot + 1j * b3 * al13 * eC - b3 * w13**2 * eC, ascale)
    # A as a point of the crank
    eA = cmath.exp(1j * th12)
    assert close(cvec(sol.point_velocity(mech, "A")), 1j * a2 * w12 * eA, vscale)
    assert close(cvec(sol.point_acceleration(mech, "A")), (1j * al12 - w12**2) * a2 * eA, ascale)
    assert sol.position_residual <= 1e-12 * a3
    assert 1.0 <= sol.condition_number < 1e3


def test_slider_crank_without_acceleration() -> None:
    th12 = RAD(60.0)
    mech = build_mechanism(slider_crank(40.0, 120.0, 10.0, th12, 10.0, 0.0))
    sol = solve_analytic(mech, slider_crank_start(40.0, 120.0, 10.0, th12), with_acceleration=False)
    assert sol.alpha is None and sol.linear_acceleration is None
    assert set(sol.slider_values(mech, "14")) == {"s", "s_dot"}
    with pytest.raises(ValueError, match="accelerations were not solved"):
        sol.point_acceleration(mech, "C")
    assert sol.poses["1"] == LinkPose(0.0, 0.0, 0.0)
    assert set(sol.poses) == {"1", "2", "3", "4"}


def test_slider_driven_slider_crank_inverts_crank_driven() -> None:
    """Drive the slider with the crank-driven s, s_dot, s_ddot: the crank gets back omega, alpha."""
    a2, a3, c1, th12, w12, al12 = 40.0, 120.0, 10.0, RAD(60.0), 10.0, 7.5
    mech = build_mechanism(slider_crank(a2, a3, c1, th12, w12, al12))
    ref = solve_analytic(mech, slider_crank_start(a2, a3, c1, th12), with_acceleration=True)
    sv = ref.slider_values(mech, "14")
    driven = build_mechanism(
        replace(slider_crank(a2, a3, c1, th12, w12, al12), input=SliderInput("14", sv["s"], sv["s_dot"], sv["s_ddot"]))
    )
    sol = solve_analytic(driven, slider_crank_start(a2, a3, c1, th12, jitter=0.02), with_acceleration=True)
    assert sol.poses["2"].theta == pytest.approx(th12, rel=1e-12)
    assert sol.omega["2"] == pytest.approx(w12, rel=1e-10)
    assert sol.alpha["2"] == pytest.approx(al12, rel=1e-9)
    assert sol.omega["3"] == pytest.approx(ref.omega["3"], rel=1e-10)
    assert sol.alpha["3"] == pytest.approx(ref.alpha["3"], rel=1e-9)


def test_missing_start_links_are_guessed() -> None:
    """Only the crank is given: the rest is placed from the joints and Newton closes some assembly."""
    a2, a3, c1, th12 = 40.0, 120.0, 10.0, RAD(60.0)
    mech = build_mechanism(slider_crank(a2, a3, c1, th12, 10.0, 0.0))
    sol = solve_analytic(mech, {"2": LinkPose(0.0, 0.0, th12)}, with_acceleration=False)
    s = sol.slider_values(mech, "14")["s"]
    root = math.sqrt(a3**2 - (a2 * math.sin(th12) - c1) ** 2)
    assert min(abs(s - (a2 * math.cos(th12) + root)), abs(s - (a2 * math.cos(th12) - root))) < 1e-9
    assert sol.position_residual <= 1e-12 * a3


# --------------------------------------------------------------------------------------------
# Four-bar (section 4.2, second example): a2 e^{i th12} + a3 e^{i th13} = a1 + a4 e^{i th14}
# --------------------------------------------------------------------------------------------


def four_bar(
    a1: float,
    a2: float,
    a3: float,
    a4: float,
    th12: float,
    w12: float,
    al12: float,
    b3: float = 60.0,
    beta_deg: float = 30.0,
) -> Scene:
    return Scene(
        title="four-bar",
        units=Units(),
        ground="1",
        links=(
            link("1", A0=(0.0, 0.0), B0=(a1, 0.0)),
            link("2", A0=(0.0, 0.0), A=(a2, 0.0)),
            link("3", A=(0.0, 0.0), B=(a3, 0.0), C=polar(b3, beta_deg)),
            link("4", B0=(0.0, 0.0), B=(a4, 0.0)),
        ),
        sliders=(),
        input=LinkInput("2", th12, w12, al12),
    )


def four_bar_position(
    a1: float, a2: float, a3: float, a4: float, th12: float, branch: int = 1
) -> tuple[float, float] | None:
    """theta13, theta14 by intersecting circle(A, a3) and circle(B0, a4); branch +1 is left of A->B0."""
    A = a2 * cmath.exp(1j * th12)
    d = abs(a1 - A)
    if d < 1e-3:
        return None
    along = (a3**2 - a4**2 + d**2) / (2 * d)
    h2 = a3**2 - along**2
    if h2 < 0:
        return None
    u = (a1 - A) / d
    B = A + along * u + branch * math.sqrt(h2) * 1j * u
    return cmath.phase(B - A), cmath.phase(B - a1)


def four_bar_start(
    a1: float, a2: float, a3: float, a4: float, th12: float, jitter: float = 0.0, branch: int = 1
) -> dict[str, LinkPose]:
    pos = four_bar_position(a1, a2, a3, a4, th12, branch)
    assert pos is not None
    th13, th14 = pos
    A = a2 * cmath.exp(1j * th12)
    return {
        "2": LinkPose(0.0, 0.0, th12 - jitter),
        "3": LinkPose(A.real + 50 * jitter, A.imag - 30 * jitter, th13 + jitter),
        "4": LinkPose(a1 - 20 * jitter, 40 * jitter, th14 - 2 * jitter),
    }


def four_bar_closed_forms(
    a1: float, a2: float, a3: float, a4: float, th12: float, w12: float, al12: float
) -> dict[str, float]:
    """omega13, omega14, alpha13, alpha14 by Cramer's rule, re-derived here (own derivation).

    Velocity loop: i a2 w12 e^{i th12} + i a3 w13 e^{i th13} = i a4 w14 e^{i th14}.
    Times e^{-i th14}, real part:  a2 w12 sin(th12 - th14) = a3 w13 sin(th14 - th13)
    Times e^{-i th13}, real part:  a2 w12 sin(th12 - th13) = a4 w14 sin(th14 - th13)
    Acceleration loop:
      (i al12 - w12^2) a2 e^{i th12} + (i al13 - w13^2) a3 e^{i th13} = (i al14 - w14^2) a4 e^{i th14}.
    Times e^{-i th14}, real part:
      a3 al13 sin(th14 - th13) = a2 al12 sin(th12 - th14) + a2 w12^2 cos(th12 - th14)
                                 + a3 w13^2 cos(th14 - th13) - a4 w14^2
    Times e^{-i th13}, real part:
      a4 al14 sin(th14 - th13) = a2 al12 sin(th12 - th13) + a2 w12^2 cos(th12 - th13)
                                 + a3 w13^2 - a4 w14^2 cos(th14 - th13)
    (The Turkish text prints "- a4 w12^2" and "- a3 w12^2 cos(th14 - th13)" in these two: typos.)
    """
    pos = four_bar_position(a1, a2, a3, a4, th12)
    assert pos is not None
    th13, th14 = pos
    den = math.sin(th14 - th13)
    w13 = a2 * w12 * math.sin(th12 - th14) / (a3 * den)
    w14 = a2 * w12 * math.sin(th12 - th13) / (a4 * den)
    al13 = (
        a2 * al12 * math.sin(th12 - th14)
        + a2 * w12**2 * math.cos(th12 - th14)
        + a3 * w13**2 * math.cos(th14 - th13)
        - a4 * w14**2
    ) / (a3 * den)
    al14 = (
        a2 * al12 * math.sin(th12 - th13)
        + a2 * w12**2 * math.cos(th12 - th13)
        + a3 * w13**2
        - a4 * w14**2 * math.cos(th14 - th13)
    ) / (a4 * den)
    return {"th13": th13, "th14": th14, "w13": w13, "w14": w14, "al13": al13, "al14": al14}


@pytest.mark.parametrize(
    ("deg", "w12", "al12"),
    [(60.0, 10.0, 5.0), (60.0, 10.0, 0.0), (200.0, -4.0, 30.0), (300.0, 2.5, -12.0), (100.0, 20.0, 0.0)],
)
def test_four_bar_closed_forms(deg: float, w12: float, al12: float) -> None:
    a1, a2, a3, a4, b3, beta = 100.0, 40.0, 120.0, 80.0, 60.0, RAD(30.0)
    th12 = RAD(deg)
    mech = build_mechanism(four_bar(a1, a2, a3, a4, th12, w12, al12))
    sol = solve_analytic(mech, four_bar_start(a1, a2, a3, a4, th12, jitter=0.02), with_acceleration=True)
    ref = four_bar_closed_forms(a1, a2, a3, a4, th12, w12, al12)
    ws, als = a2 * abs(w12) / a3, a2 * (w12**2 + abs(al12)) / a3
    assert math.remainder(sol.poses["3"].theta - ref["th13"], 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    assert math.remainder(sol.poses["4"].theta - ref["th14"], 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    assert close(sol.omega["3"], ref["w13"], ws)
    assert close(sol.omega["4"], ref["w14"], ws)
    assert close(sol.alpha["3"], ref["al13"], als)
    assert close(sol.alpha["4"], ref["al14"], als)
    # C: r_C = a2 e^{i th12} + b3 e^{i(th13 + beta)}, differentiated
    e2, eC = cmath.exp(1j * th12), cmath.exp(1j * (ref["th13"] + beta))
    vC = 1j * a2 * w12 * e2 + 1j * b3 * ref["w13"] * eC
    aC = (1j * al12 - w12**2) * a2 * e2 + (1j * ref["al13"] - ref["w13"] ** 2) * b3 * eC
    assert close(cvec(sol.point_position(mech, "C")), a2 * e2 + b3 * eC, a3)
    assert close(cvec(sol.point_velocity(mech, "C")), vC, a2 * abs(w12))
    assert close(cvec(sol.point_acceleration(mech, "C")), aC, a2 * (w12**2 + abs(al12)))
    # B as a point of the rocker and of the coupler agree
    assert close(cvec(sol.point_velocity(mech, "B")), cvec(sol.point_velocity(mech, "B@4")), a2 * abs(w12))
    assert close(cvec(sol.point_velocity(mech, "B")), 1j * a4 * ref["w14"] * cmath.exp(1j * ref["th14"]), a2 * abs(w12))


def test_four_bar_mpmath_reference() -> None:
    """The four-bar loop solved with 50 digits (findroot, then the linear velocity/acceleration loops)."""
    a1, a2, a3, a4, b3, beta_deg = 100, 40, 120, 80, 60, 30
    th12f, w12f, al12f = RAD(60.0), 10.0, 5.0
    mech = build_mechanism(four_bar(a1, a2, a3, a4, th12f, w12f, al12f))
    sol = solve_analytic(mech, four_bar_start(a1, a2, a3, a4, th12f, jitter=0.05), with_acceleration=True)

    with mp.workdps(50):
        th12, w12, al12 = mp.mpf(th12f), mp.mpf(w12f), mp.mpf(al12f)
        beta = mp.radians(beta_deg)

        def loop(t13: mp.mpf, t14: mp.mpf) -> list[mp.mpf]:
            z = a2 * _expj(th12) + a3 * _expj(t13) - a1 - a4 * _expj(t14)
            return [mp.re(z), mp.im(z)]

        t13, t14 = mp.findroot(
            loop, (mp.mpf(sol.poses["3"].theta) + mp.mpf("0.01"), mp.mpf(sol.poses["4"].theta) - mp.mpf("0.01"))
        )
        # real and imaginary parts of i a3 w13 e^{i t13} - i a4 w14 e^{i t14} = -i a2 w12 e^{i th12}
        M = mp.matrix([[-a3 * mp.sin(t13), a4 * mp.sin(t14)], [a3 * mp.cos(t13), -a4 * mp.cos(t14)]])
        rv = -1j * a2 * w12 * _expj(th12)
        w13, w14 = mp.lu_solve(M, mp.matrix([mp.re(rv), mp.im(rv)]))
        # i a3 al13 e^{i t13} - i a4 al14 e^{i t14}
        #   = -(i al12 - w12^2) a2 e^{i th12} + a3 w13^2 e^{i t13} - a4 w14^2 e^{i t14}
        ra = -(1j * al12 - w12**2) * a2 * _expj(th12) + a3 * w13**2 * _expj(t13) - a4 * w14**2 * _expj(t14)
        al13, al14 = mp.lu_solve(M, mp.matrix([mp.re(ra), mp.im(ra)]))
        eC = _expj(t13 + beta)
        vC = 1j * a2 * w12 * _expj(th12) + 1j * b3 * w13 * eC
        aC = (1j * al12 - w12**2) * a2 * _expj(th12) + (1j * al13 - w13**2) * b3 * eC
        ref = {
            k: complex(v)
            for k, v in {
                "t13": t13,
                "t14": t14,
                "w13": w13,
                "w14": w14,
                "al13": al13,
                "al14": al14,
                "vC": vC,
                "aC": aC,
            }.items()
        }

    rel = 1e-12
    assert sol.poses["3"].theta == pytest.approx(ref["t13"].real, rel=rel)
    assert sol.poses["4"].theta == pytest.approx(ref["t14"].real, rel=rel)
    for got, key in (
        (sol.omega["3"], "w13"),
        (sol.omega["4"], "w14"),
        (sol.alpha["3"], "al13"),
        (sol.alpha["4"], "al14"),
    ):
        assert got == pytest.approx(ref[key].real, rel=rel)
    assert close(cvec(sol.point_velocity(mech, "C")), ref["vC"], 0.0, rel)
    assert close(cvec(sol.point_acceleration(mech, "C")), ref["aC"], 0.0, rel)


def test_dead_centre_is_singular() -> None:
    """A double-rocker at its input limit: coupler 3 and rocker 4 stretched in one line."""
    a1, a2, a3, a4 = 100.0, 40.0, 50.0, 80.0
    th12 = math.acos((a1**2 + a2**2 - (a3 + a4) ** 2) / (2 * a1 * a2))
    mech = build_mechanism(four_bar(a1, a2, a3, a4, th12, 10.0, 0.0, b3=20.0))
    A = a2 * cmath.exp(1j * th12)
    phase = cmath.phase(A - a1)
    start = {
        "2": LinkPose(0.0, 0.0, th12),
        "3": LinkPose(A.real, A.imag, phase + math.pi + 0.01),
        "4": LinkPose(a1, 0.0, phase - 0.01),
    }
    with pytest.raises(SingularityError, match=r"velocity equations are singular at input link 2 at angle 131\.49"):
        solve_analytic(mech, start, with_acceleration=True)
    # well away from it, the same start works
    ok = build_mechanism(four_bar(a1, a2, a3, a4, th12 - 0.05, 10.0, 0.0, b3=20.0))
    assert solve_analytic(ok, start, with_acceleration=True).condition_number < 1e4
    # beyond it, the linkage does not close
    beyond = build_mechanism(four_bar(a1, a2, a3, a4, th12 + 0.05, 10.0, 0.0, b3=20.0))
    with pytest.raises(AssemblyError, match="does not close"):
        solve_analytic(beyond, start, with_acceleration=False)


# --------------------------------------------------------------------------------------------
# Crank and slotted lever with offset: a2 e^{i th12} = a1 + a4 e^{i th14} + i s43 e^{i th14}
# --------------------------------------------------------------------------------------------


def slotted_lever(a1: float, a2: float, a4: float, th12: float, w12: float, al12: float) -> Scene:
    return Scene(
        title="slotted lever",
        units=Units(),
        ground="1",
        links=(
            link("1", A0=(0.0, 0.0), B0=(a1, 0.0)),
            link("2", A0=(0.0, 0.0), A=(a2, 0.0)),
            link("3", A=(0.0, 0.0)),
            link("4", B0=(0.0, 0.0), F=(a4, 0.0)),
        ),
        sliders=(SliderSpec("43", "3", "4", "A", (a4, 0.0), RAD(90.0)),),
        input=LinkInput("2", th12, w12, al12),
    )


def slotted_lever_position(a1: float, a2: float, a4: float, th12: float, sign: float = -1.0) -> tuple[float, float]:
    """th14 and s43: A - a1 = (a4 + i s43) e^{i th14}, |s43| = sqrt(|A - a1|^2 - a4^2)."""
    rel = a2 * cmath.exp(1j * th12) - a1
    s43 = sign * math.sqrt(abs(rel) ** 2 - a4**2)
    return cmath.phase(rel) - cmath.phase(complex(a4, s43)), s43


def slotted_lever_start(a1: float, a2: float, a4: float, th12: float, jitter: float = 0.0) -> dict[str, LinkPose]:
    th14, _ = slotted_lever_position(a1, a2, a4, th12)
    A = a2 * cmath.exp(1j * th12)
    return {
        "2": LinkPose(0.0, 0.0, th12 + jitter),
        "3": LinkPose(A.real - 30 * jitter, A.imag + 20 * jitter, th14 + math.pi / 2 + jitter),
        "4": LinkPose(a1 + 10 * jitter, -10 * jitter, th14 - jitter),
    }


@pytest.mark.parametrize(
    ("deg", "w12", "al12"), [(60.0, 10.0, 0.0), (60.0, 10.0, 20.0), (170.0, -6.0, 3.0), (290.0, 4.0, -15.0)]
)
def test_slotted_lever_closed_forms(deg: float, w12: float, al12: float) -> None:
    a1, a2, a4 = 80.0, 40.0, 15.0
    th12 = RAD(deg)
    mech = build_mechanism(slotted_lever(a1, a2, a4, th12, w12, al12))
    sol = solve_analytic(mech, slotted_lever_start(a1, a2, a4, th12, jitter=0.02), with_acceleration=True)
    th14, s = slotted_lever_position(a1, a2, a4, th12)
    # Own derivation. Velocity loop, divided by i e^{i th14}, phi = th12 - th14:
    #   a2 w12 e^{i phi} = w14 (a4 + i s) + s_dot
    #   imag: a2 w12 sin phi = w14 s;   real: a2 w12 cos phi = w14 a4 + s_dot
    # Acceleration loop: (i al12 - w12^2) a2 e^{i th12}
    #   = (i al14 - w14^2)(a4 + i s) e^{i th14} + i s_ddot e^{i th14} - 2 w14 s_dot e^{i th14},
    # divided by i e^{i th14}:
    #   a2 (al12 + i w12^2) e^{i phi} = al14 (a4 + i s) + i w14^2 (a4 + i s) + s_ddot + 2 i w14 s_dot
    #   imag: a2 (al12 sin phi + w12^2 cos phi) = al14 s + w14^2 a4 + 2 w14 s_dot
    #   real: a2 (al12 cos phi - w12^2 sin phi) = al14 a4 - w14^2 s + s_ddot
    phi = th12 - th14
    w14 = a2 * w12 * math.sin(phi) / s
    s_dot = a2 * w12 * math.cos(phi) - w14 * a4
    al14 = (a2 * (al12 * math.sin(phi) + w12**2 * math.cos(phi)) - w14**2 * a4 - 2 * w14 * s_dot) / s
    s_ddot = a2 * (al12 * math.cos(phi) - w12**2 * math.sin(phi)) - al14 * a4 + w14**2 * s
    e14 = cmath.exp(1j * th14)
    coriolis = -2 * w14 * s_dot * e14  # 2 w14 x (s_dot i e^{i th14})

    vs, acs = a2 * abs(w12), a2 * (w12**2 + abs(al12))
    assert close(sol.omega["4"], w14, vs / a1)
    assert close(sol.omega["3"], w14, vs / a1)
    assert close(sol.alpha["4"], al14, acs / a1)
    assert close(sol.alpha["3"], al14, acs / a1)
    sv = sol.slider_values(mech, "43")
    assert close(sv["s"], s, a1)
    assert close(sv["s_dot"], s_dot, vs)
    assert close(sv["s_ddot"], s_ddot, acs)
    assert close(cvec(sv["coriolis"]), coriolis, acs)
    # A@4, the lever's point under A: v = i w14 (a4 + i s) e^{i th14}, a = (i al14 - w14^2)(a4 + i s) e^{i th14}
    arm = complex(a4, s) * e14
    assert close(cvec(sol.point_position(mech, "A@4")), a1 + arm, a1)
    assert close(cvec(sol.point_velocity(mech, "A@4")), 1j * w14 * arm, vs)
    assert close(cvec(sol.point_acceleration(mech, "A@4")), (1j * al14 - w14**2) * arm, acs)
    # and a_A = a_A@4 + s_ddot (i e^{i th14}) + coriolis
    aA = (1j * al12 - w12**2) * a2 * cmath.exp(1j * th12)
    assert close(cvec(sol.point_acceleration(mech, "A")), aA, acs)
    assert close((1j * al14 - w14**2) * arm + s_ddot * 1j * e14 + coriolis, aA, acs)


def test_slider_driven_on_a_turning_guide() -> None:
    """Drive the slotted lever by its slider 43 (turning guide): the crank gets back omega, alpha."""
    a1, a2, a4, th12, w12, al12 = 80.0, 40.0, 15.0, RAD(60.0), 10.0, 20.0
    scene = slotted_lever(a1, a2, a4, th12, w12, al12)
    ref = solve_analytic(build_mechanism(scene), slotted_lever_start(a1, a2, a4, th12), with_acceleration=True)
    sv = ref.slider_values(build_mechanism(scene), "43")
    driven = build_mechanism(replace(scene, input=SliderInput("43", sv["s"], sv["s_dot"], sv["s_ddot"])))
    sol = solve_analytic(driven, slotted_lever_start(a1, a2, a4, th12, jitter=0.01), with_acceleration=True)
    assert math.remainder(sol.poses["2"].theta - th12, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    for name in ("2", "3", "4"):
        assert sol.omega[name] == pytest.approx(ref.omega[name], rel=1e-9)
        assert sol.alpha[name] == pytest.approx(ref.alpha[name], rel=1e-9)


# --------------------------------------------------------------------------------------------
# Finite differences: velocities are d(position)/dt, accelerations d(velocity)/dt
# --------------------------------------------------------------------------------------------


def check_by_finite_differences(
    scene: Scene,
    start: dict[str, LinkPose],
    labels: tuple[str, ...],
    sliders: tuple[str, ...] = (),
    h: float = 1e-5,
    rtol: float = 1e-6,
) -> None:
    """Compare with central differences in the input angle (omega, alpha of the input given).

    x(th): v = w x', a = w^2 x'' + al x'; with v(th) the solved velocity (at the same w),
    dv/dth = w x'', so a = w dv/dth + (al / w) v.
    """
    inp = scene.input
    assert isinstance(inp, LinkInput) and inp.omega != 0.0
    w, al = inp.omega, inp.alpha
    mech = build_mechanism(scene)
    sol = solve_analytic(mech, start, with_acceleration=True)
    near = dict(sol.poses)
    plus = solve_analytic(
        build_mechanism(with_input(scene, angle_rad=inp.angle_rad + h)), near, with_acceleration=False
    )
    minus = solve_analytic(
        build_mechanism(with_input(scene, angle_rad=inp.angle_rad - h)), near, with_acceleration=False
    )
    plus2 = solve_analytic(
        build_mechanism(with_input(scene, angle_rad=inp.angle_rad + 2 * h)), near, with_acceleration=False
    )
    minus2 = solve_analytic(
        build_mechanism(with_input(scene, angle_rad=inp.angle_rad - 2 * h)), near, with_acceleration=False
    )
    size = max(math.hypot(*p.local) for lk in scene.links for p in lk.points)
    vscale, ascale = size * abs(w), size * (w * w + abs(al))

    def d(f: Callable[[AnalyticSolution], complex]) -> complex:
        """Central differences at h and 2h, Richardson-extrapolated: truncation O(h^4), so that a
        short link's large third derivative (a coupler of 15 beside links of 110) does not show."""
        at_h = (f(plus) - f(minus)) / (2 * h)
        at_2h = (f(plus2) - f(minus2)) / (4 * h)
        return at_h + (at_h - at_2h) / 3.0

    def check(got: complex, expected: complex, scale: float, what: str) -> None:
        assert abs(got - expected) <= rtol * max(scale, abs(expected)), (what, got, expected)

    for name in mech.link_names:
        check(sol.omega[name], w * d(lambda s, n=name: s.poses[n].theta), abs(w), f"omega {name}")
        check(
            sol.alpha[name],
            w * d(lambda s, n=name: s.omega[n]) + al / w * sol.omega[name],
            w * w + abs(al),
            f"alpha {name}",
        )
        check(
            cvec(sol.linear_velocity[name]),
            w * d(lambda s, n=name: complex(s.poses[n].x, s.poses[n].y)),
            vscale,
            f"v {name}",
        )
        check(
            cvec(sol.linear_acceleration[name]),
            w * d(lambda s, n=name: cvec(s.linear_velocity[n])) + al / w * cvec(sol.linear_velocity[name]),
            ascale,
            f"a {name}",
        )
    for label in labels:
        # the material point the label names now, followed as a fixed point of its link
        lk, local = sol.material_point(mech, label)
        v = cvec(sol.point_velocity(mech, label))
        check(v, w * d(lambda s, k=lk, p=local: cvec(s.position(k, p))), vscale, f"v {label}")
        check(
            cvec(sol.point_acceleration(mech, label)),
            w * d(lambda s, k=lk, p=local: cvec(s.velocity(k, p))) + al / w * v,
            ascale,
            f"a {label}",
        )
    for name in sliders:
        sv = sol.slider_values(mech, name)
        check(sv["s_dot"], w * d(lambda s, n=name: s.slider_values(mech, n)["s"]), vscale, f"s_dot {name}")
        check(
            sv["s_ddot"],
            w * d(lambda s, n=name: s.slider_values(mech, n)["s_dot"]) + al / w * sv["s_dot"],
            ascale,
            f"s_ddot {name}",
        )


def shaper(th12: float, w12: float, al12: float) -> tuple[Scene, dict[str, LinkPose]]:
    """The crank-shaper six-bar of the examples, with a start pose from its own geometry."""
    scene = Scene(
        title="shaper",
        units=Units(),
        ground="1",
        links=(
            link("1", B0=(0.0, 0.0), A0=(0.0, 150.0)),
            link("2", A0=(0.0, 0.0), A=(60.0, 0.0)),
            link("3", A=(0.0, 0.0)),
            link("4", B0=(0.0, 0.0), C=(400.0, 0.0)),
            link("5", C=(0.0, 0.0), D=(150.0, 0.0)),
            link("6", D=(0.0, 0.0)),
        ),
        sliders=(SliderSpec("43", "3", "4", "A", (0.0, 0.0), 0.0), SliderSpec("16", "6", "1", "D", (0.0, 430.0), 0.0)),
        input=LinkInput("2", th12, w12, al12),
    )
    A = 150j + 60 * cmath.exp(1j * th12)
    th4 = cmath.phase(A)
    C = 400 * cmath.exp(1j * th4)
    D = complex(C.real + math.sqrt(150**2 - (430 - C.imag) ** 2), 430)
    start = {
        "2": LinkPose(0.0, 150.0, th12),
        "3": LinkPose(A.real + 1, A.imag - 1, th4 + 0.01),
        "4": LinkPose(0.5, -0.5, th4 - 0.01),
        "5": LinkPose(C.real, C.imag + 1, cmath.phase(D - C) + 0.02),
        "6": LinkPose(D.real - 2, D.imag, 0.01),
    }
    return scene, start


@pytest.mark.parametrize(("deg", "w12", "al12"), [(30.0, 6.0, 0.0), (30.0, 6.0, 40.0), (200.0, -3.0, 10.0)])
def test_shaper_by_finite_differences(deg: float, w12: float, al12: float) -> None:
    """Two sliders, one on a turning guide: A@4 (the lever under the block) followed as a lever point."""
    scene, start = shaper(RAD(deg), w12, al12)
    check_by_finite_differences(scene, start, ("A", "A@4", "C", "D"), sliders=("43", "16"))
    mech = build_mechanism(scene)
    sol = solve_analytic(mech, start, with_acceleration=True)
    sv = sol.slider_values(mech, "43")
    th4 = sol.poses["4"].theta
    # coriolis = 2 w4 x (s_dot e), e along the lever
    expected = 2 * sol.omega["4"] * 1j * sv["s_dot"] * cmath.exp(1j * th4)
    assert abs(cvec(sv["coriolis"]) - expected) <= 1e-10 * abs(expected)
    assert sol.slider_values(mech, "16")["coriolis"] == (0.0, 0.0)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(
    a1=st.floats(50, 150),
    a2=st.floats(15, 150),
    a3=st.floats(15, 150),
    a4=st.floats(15, 150),
    th12=st.floats(0, 2 * math.pi),
    w12=st.floats(0.5, 20),
    al12=st.floats(-50, 50),
    branch=st.sampled_from([1, -1]),
    flip=st.booleans(),
)
def test_four_bar_finite_differences(
    a1: float, a2: float, a3: float, a4: float, th12: float, w12: float, al12: float, branch: int, flip: bool
) -> None:
    pos = four_bar_position(a1, a2, a3, a4, th12, branch)
    assume(pos is not None)
    assert pos is not None
    assume(abs(math.sin(pos[1] - pos[0])) > 0.2)  # transmission well away from a dead-centre
    w = -w12 if flip else w12
    scene = four_bar(a1, a2, a3, a4, th12, w, al12)
    check_by_finite_differences(
        scene, four_bar_start(a1, a2, a3, a4, th12, jitter=0.005, branch=branch), ("A", "B", "C", "B@4", "A@3")
    )


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(
    a2=st.floats(10, 80),
    ratio=st.floats(1.2, 5),
    c1=st.floats(-50, 50),
    th12=st.floats(0, 2 * math.pi),
    w12=st.floats(-20, 20).filter(lambda x: abs(x) > 0.5),
    al12=st.floats(-50, 50),
)
def test_slider_crank_finite_differences(
    a2: float, ratio: float, c1: float, th12: float, w12: float, al12: float
) -> None:
    a3 = ratio * a2
    assume(abs(a2 * math.sin(th12) - c1) < 0.9 * a3)  # the coupler well away from perpendicular
    scene = slider_crank(a2, a3, c1, th12, w12, al12)
    check_by_finite_differences(
        scene, slider_crank_start(a2, a3, c1, th12, jitter=0.005), ("A", "B", "C"), sliders=("14",)
    )


# --------------------------------------------------------------------------------------------
# [given]: one body, the motion of two points known (the image-point example)
# --------------------------------------------------------------------------------------------


def image_point(vB: tuple[float, float] = (0.0, -100.0), aB: tuple[float, float] | None = (-2050.0, 120.0)) -> Scene:
    return Scene(
        title="image point",
        units=Units(),
        ground=None,
        links=(link("3", A=(0.0, 0.0), B=(80.0, 0.0), S=(30.0, 40.0)),),
        sliders=(),
        input=GivenInput((GivenPoint("A", (0.0, 300.0), (-50.0, 0.0), line=9), GivenPoint("B", vB, aB, line=12))),
        source="image.toml",
    )


def test_given_image_point() -> None:
    mech = build_mechanism(image_point())
    sol = solve_analytic(mech, {}, with_acceleration=True)
    assert sol.poses == {"3": LinkPose(0.0, 0.0, 0.0)}
    assert sol.omega["3"] == pytest.approx(-5.0, rel=1e-14)
    assert sol.alpha["3"] == pytest.approx(1.5, rel=1e-14)
    # By hand: v_S = v_A + w k x AS = (0, 300) - 5 (-40, 30) = (200, 150)
    #          a_S = a_A + al k x AS - w^2 AS = (-50, 0) + 1.5 (-40, 30) - 25 (30, 40) = (-860, -955)
    assert sol.point_velocity(mech, "S") == pytest.approx((200.0, 150.0), rel=1e-13, abs=1e-12)
    assert sol.point_acceleration(mech, "S") == pytest.approx((-860.0, -955.0), rel=1e-13, abs=1e-12)
    assert sol.point_velocity(mech, "B") == pytest.approx((0.0, -100.0), abs=1e-12)
    assert sol.point_acceleration(mech, "B") == pytest.approx((-2050.0, 120.0), abs=1e-11)
    assert sol.position_residual == 0.0
    assert sol.condition_number >= 1.0


def test_given_without_acceleration() -> None:
    mech = build_mechanism(image_point(aB=None))
    sol = solve_analytic(mech, {}, with_acceleration=False)
    assert sol.alpha is None and sol.omega["3"] == pytest.approx(-5.0)
    with pytest.raises(SceneError, match=r"given\.B\.acceleration: missing"):
        solve_analytic(mech, {}, with_acceleration=True)


def test_given_velocities_not_rigid() -> None:
    mech = build_mechanism(image_point(vB=(12.5, -100.0)))
    with pytest.raises(SceneError) as info:
        solve_analytic(mech, {}, with_acceleration=False)
    message = str(info.value)
    assert message.startswith("image.toml:12: given.B.velocity: the velocities of A and B differ by 12.5 mm/s along AB")
    assert "a rigid body allows none" in message


def test_given_accelerations_not_rigid() -> None:
    mech = build_mechanism(image_point(aB=(-2040.0, 120.0)))
    with pytest.raises(SceneError, match=r"given\.B\.acceleration: .* -2000 mm/s\^2: off by 10 mm/s\^2"):
        solve_analytic(mech, {}, with_acceleration=True)
    # a tiny, rounding-sized departure is accepted
    ok = build_mechanism(image_point(vB=(1e-12, -100.0), aB=(-2050.0 + 1e-9, 120.0)))
    assert solve_analytic(ok, {}, with_acceleration=True).alpha["3"] == pytest.approx(1.5)
