"""Properties of the construction over random assemblable mechanisms (hypothesis).

Construction equals analytic; image triangles similar and of the same sense; polygons close;
accelerations equal central differences of the constructed velocities; results scale exactly.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from tests.scenes import four_bar, slider_crank, slotted_lever

import kinepoly
from kinepoly.errors import AssemblyError, SingularityError

lengths = st.floats(min_value=10.0, max_value=200.0)
angles = st.floats(min_value=-180.0, max_value=180.0)
speeds = st.floats(min_value=-50.0, max_value=50.0).filter(lambda w: abs(w) > 0.1)
accels = st.floats(min_value=-500.0, max_value=500.0)


def solve_text(text: str) -> kinepoly.Solution:
    try:
        solution = kinepoly.solve(kinepoly.loads_scene(text))
    except (AssemblyError, SingularityError):
        assume(False)
        raise
    assume(not any(n.code == "near-singular" for n in solution.notices))
    assume(solution.check.condition_number < 1e4)
    return solution


def c(v: tuple[float, float]) -> complex:
    return complex(v[0], v[1])


def well_conditioned_four_bar(a1, a2, a3, a4, th) -> None:  # type: ignore[no-untyped-def]
    A = a2 * complex(math.cos(math.radians(th)), math.sin(math.radians(th)))
    d = abs(a1 - A)
    assume(abs(a3 - a4) + 1e-3 * d < d < a3 + a4 - 1e-3 * d)
    # transmission angle away from 0 and 180 degrees
    cos_mu = (a3 * a3 + a4 * a4 - d * d) / (2 * a3 * a4)
    assume(abs(cos_mu) < 0.95)


@settings(max_examples=60, deadline=None)
@given(lengths, lengths, lengths, lengths, angles, speeds, accels)
def test_four_bar_construction_equals_analytic_and_closes(a1, a2, a3, a4, th, w, al) -> None:  # type: ignore[no-untyped-def]
    well_conditioned_four_bar(a1, a2, a3, a4, th)
    sol = solve_text(four_bar(a1, a2, a3, a4, th, w, al, guess_b=(a1, a3 + a4)))
    assert sol.check.max_rel_error < 1e-10
    v, a = sol.velocity, sol.acceleration
    assert v is not None and a is not None
    P = {name: c(sol.position(name)) for name in ("A", "B", "B0", "C")}
    # the loops close with the omegas and alphas read off the polygon
    for link, first in (("3", "A"), ("4", "B0")):
        w3, al3 = v.omega[link], a.alpha[link]
        r = P["B"] - P[first]
        vel_scale = max(abs(c(t)) for t in v.tips.values())
        acc_scale = max(abs(c(t)) for t in a.tips.values())
        assert abs(c(v.tips.get(first, (0.0, 0.0))) + 1j * w3 * r - c(v.tips["B"])) <= 1e-10 * vel_scale
        assert abs(c(a.tips.get(first, (0.0, 0.0))) + (1j * al3 - w3 * w3) * r - c(a.tips["B"])) <= 1e-10 * acc_scale
    # Mehmke: abc similar to ABC and of the same sense: the complex ratios agree
    for tips in (v.tips, a.tips):
        ab = c(tips["B"]) - c(tips["A"])
        assume(abs(ab) > 1e-6 * max(abs(c(t)) for t in tips.values()))
        ratio_polygon = (c(tips["C"]) - c(tips["A"])) / ab
        ratio_link = (P["C"] - P["A"]) / (P["B"] - P["A"])
        assert abs(ratio_polygon - ratio_link) <= 1e-9 * abs(ratio_link)


@settings(max_examples=60, deadline=None)
@given(st.floats(min_value=5.0, max_value=50.0), st.floats(min_value=2.5, max_value=8.0),
       st.floats(min_value=-0.5, max_value=0.5), angles, speeds, accels)
def test_slider_crank_construction_equals_analytic(a2, ratio, offset, th, w, al) -> None:  # type: ignore[no-untyped-def]
    a3 = ratio * a2
    sol = solve_text(slider_crank(a2, a3, offset * a2, th, w, al,
                                  find='[find]\nsliders = ["14"]\nvelocity = ["B", "C"]\n'
                                       'acceleration = ["B", "C"]\nomega = ["3"]\nalpha = ["3"]'))
    assert sol.check.max_rel_error < 1e-10
    assert sol.acceleration is not None
    assert sol.acceleration.coriolis["14"] == (0.0, 0.0)
    assert not any(step.kind == "coriolis" for step in sol.steps)  # the guide is the frame


@settings(max_examples=60, deadline=None)
@given(lengths, st.floats(min_value=0.1, max_value=0.9), st.floats(min_value=-0.3, max_value=0.3), angles, speeds,
       accels)
def test_slotted_lever_construction_equals_analytic(a1, crank_ratio, offset_ratio, th, w, al) -> None:  # type: ignore[no-untyped-def]
    a2 = crank_ratio * a1
    sol = solve_text(slotted_lever(a1, a2, offset_ratio * a2, th, w, al, guess_f=(a1, -a1)))
    assert sol.check.max_rel_error < 1e-10
    assert any(step.kind == "coriolis" for step in sol.steps)


@settings(max_examples=25, deadline=None)
@given(lengths, lengths, lengths, lengths, angles, speeds, accels)
def test_acceleration_is_the_time_derivative_of_the_constructed_velocity(a1, a2, a3, a4, th, w, al) -> None:  # type: ignore[no-untyped-def]
    well_conditioned_four_bar(a1, a2, a3, a4, th)
    base = solve_text(four_bar(a1, a2, a3, a4, th, w, al, guess_b=(a1, a3 + a4)))
    guess = base.position("B")
    h = 1e-5 / max(abs(w), 1.0)

    def at(t: float) -> kinepoly.Solution:
        theta = th + math.degrees(w * t + 0.5 * al * t * t)
        return kinepoly.solve(kinepoly.loads_scene(four_bar(a1, a2, a3, a4, theta, w + al * t, al, guess_b=guess)))

    ahead, behind = at(h), at(-h)
    assert base.acceleration is not None and ahead.velocity is not None and behind.velocity is not None
    scale = max(abs(c(t)) for t in base.acceleration.tips.values())
    for point in ("B", "C"):
        fd = (c(ahead.velocity.tips[point]) - c(behind.velocity.tips[point])) / (2 * h)
        assert abs(fd - c(base.acceleration.tips[point])) <= 1e-5 * scale
    fd_omega = (ahead.velocity.omega["3"] - behind.velocity.omega["3"]) / (2 * h)
    assert base.acceleration.alpha["3"] == pytest.approx(fd_omega, rel=1e-5, abs=1e-5 * abs(al) + 1e-5 * w * w)


@pytest.mark.parametrize("k", [-6, -3, 0, 3, 6])
def test_results_scale_exactly_with_the_lengths(k: int) -> None:
    f = 10.0**k
    base = kinepoly.solve(kinepoly.loads_scene(four_bar(100, 40, 120, 80, 60, 10, 5, guess_b=(110, 80))))
    scaled = kinepoly.solve(kinepoly.loads_scene(four_bar(100 * f, 40 * f, 120 * f, 80 * f, 60, 10, 5,
                                                          guess_b=(110 * f, 80 * f), coupler=(60 * f, 30))))
    assert base.velocity and scaled.velocity and base.acceleration and scaled.acceleration
    for link in ("3", "4"):
        assert scaled.velocity.omega[link] == pytest.approx(base.velocity.omega[link], rel=1e-12)
        assert scaled.acceleration.alpha[link] == pytest.approx(base.acceleration.alpha[link], rel=1e-12)
    for point in ("B", "C"):
        assert c(scaled.velocity.tips[point]) == pytest.approx(f * c(base.velocity.tips[point]), rel=1e-12)
        assert c(scaled.acceleration.tips[point]) == pytest.approx(f * c(base.acceleration.tips[point]), rel=1e-12)
    assert scaled.check.max_rel_error < 1e-12
