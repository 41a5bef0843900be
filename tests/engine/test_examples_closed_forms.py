"""Each example against closed forms derived on their own from the course texts' loop equations."""

from __future__ import annotations

import cmath
import math

import pytest
from tests.scenes import EXAMPLES

import kinepoly

REL = 1e-10


def close(a: complex, b: complex, scale: float) -> bool:
    return abs(a - b) <= REL * scale


def vec(pair: list[float]) -> complex:
    return complex(pair[0], pair[1])


def solved(name: str) -> dict:
    return kinepoly.to_json(kinepoly.solve(kinepoly.load_scene(EXAMPLES / name)))


def test_slider_crank_against_loop_closure() -> None:
    # s14 + i c1 + a3 e^{i th13} = a2 e^{i th12}, th13 the angle of BA (B to A)
    a2, a3, c1, th2, w2, al2 = 40.0, 120.0, 10.0, math.radians(60), 10.0, 0.0
    th3 = math.pi - math.asin((a2 * math.sin(th2) - c1) / a3)  # B to the right of A: cos th13 < 0
    s = a2 * math.cos(th2) - a3 * math.cos(th3)
    w3 = a2 * math.cos(th2) / (a3 * math.cos(th3)) * w2                     # seed eq. (5)
    s_dot = -a2 * math.sin(th2 - th3) / math.cos(th3) * w2                  # seed eq. (4)
    al3 = (a2 * al2 * math.cos(th2) - a2 * w2**2 * math.sin(th2) + a3 * w3**2 * math.sin(th3)) / (
        a3 * math.cos(th3))                                                  # seed eq. (9)
    s_ddot = (a3 * al3 * math.sin(th3) + a3 * w3**2 * math.cos(th3)      # real part of (8a), derived here
              - a2 * al2 * math.sin(th2) - a2 * w2**2 * math.cos(th2))
    # C: polar (50, -30 deg) from B on link 3: r_C = s14 + i c1 + b3 e^{i(th13 - 30 deg)}
    b3, g3 = 50.0, math.radians(30)
    e = cmath.exp(1j * (th3 - g3))
    v_c = s_dot + 1j * b3 * w3 * e                                          # seed eq. (12)
    a_c = s_ddot + 1j * b3 * al3 * e - b3 * w3**2 * e                       # seed eq. (13)
    out = solved("slider-crank.toml")
    assert close(out["links"]["3"]["omega"], w3, abs(w3))
    assert close(out["links"]["3"]["alpha"], al3, abs(al3))
    assert close(math.radians(out["links"]["3"]["angle"]) % (2 * math.pi), th3 % (2 * math.pi), 1.0)
    assert close(vec(out["points"]["B"]["velocity"]), s_dot, abs(s_dot))
    assert close(vec(out["points"]["B"]["acceleration"]), s_ddot, abs(s_ddot))
    assert close(vec(out["points"]["B"]["position"]), s + 1j * c1, abs(s))
    assert close(vec(out["points"]["C"]["velocity"]), v_c, abs(v_c))
    assert close(vec(out["points"]["C"]["acceleration"]), a_c, abs(a_c))
    assert out["links"]["3"]["omega"] == pytest.approx(-1.70, abs=0.005)  # the homework figure


def test_four_bar_by_cramers_rule() -> None:
    a1, a2, a3, a4, th2, w2, al2 = 100.0, 40.0, 120.0, 80.0, math.radians(60), 10.0, 5.0
    # position: B on circles about A (a3) and B0 (a4), the upper assembly
    A = a2 * cmath.exp(1j * th2)
    d = abs(a1 - A)
    u = (a1 - A) / d
    x = (d * d + a3 * a3 - a4 * a4) / (2 * d)
    B = A + x * u + math.sqrt(a3 * a3 - x * x) * 1j * u
    th3, th4 = cmath.phase(B - A), cmath.phase(B - a1)
    # velocity loop i a2 w2 e2 + i a3 w3 e3 = i a4 w4 e4, by Cramer's rule
    w3 = a2 / a3 * math.sin(th2 - th4) / math.sin(th4 - th3) * w2
    w4 = a2 / a4 * math.sin(th2 - th3) / math.sin(th4 - th3) * w2
    e2, e3, e4 = (cmath.exp(1j * t) for t in (th2, th3, th4))
    # acceleration loop: i a3 al3 e3 - i a4 al4 e4 = R; multiply by e^{-i th4} (or e^{-i th3}), real part
    R = -1j * a2 * al2 * e2 + a2 * w2**2 * e2 + a3 * w3**2 * e3 - a4 * w4**2 * e4
    al3 = -(R * cmath.exp(-1j * th4)).real / (a3 * math.sin(th3 - th4))
    al4 = (R * cmath.exp(-1j * th3)).real / (a4 * math.sin(th4 - th3))
    b3, beta = 60.0, math.radians(30)
    ec = cmath.exp(1j * (th3 + beta))
    v_c = 1j * a2 * w2 * e2 + 1j * b3 * w3 * ec
    a_c = (1j * a2 * al2 - a2 * w2**2) * e2 + (1j * b3 * al3 - b3 * w3**2) * ec
    out = solved("four-bar.toml")
    for got, want in ((out["links"]["3"]["omega"], w3), (out["links"]["4"]["omega"], w4),
                      (out["links"]["3"]["alpha"], al3), (out["links"]["4"]["alpha"], al4)):
        assert close(got, want, abs(want))
    assert close(vec(out["points"]["B"]["position"]), B, abs(B))
    assert close(vec(out["points"]["B"]["velocity"]), 1j * a4 * w4 * e4, a4 * abs(w4))
    assert close(vec(out["points"]["C"]["velocity"]), v_c, abs(v_c))
    assert close(vec(out["points"]["C"]["acceleration"]), a_c, abs(a_c))


def test_slotted_lever_with_its_coriolis_term() -> None:
    # a2 e^{i th12} = a1 + e^{i th14} (a4 + i s43): lever 4 about B0, slot at offset a4 along its local y
    a1, a2, a4, th2, w2, al2 = 80.0, 40.0, 15.0, math.radians(60), 10.0, 0.0
    rel = a2 * cmath.exp(1j * th2) - a1
    s = -math.sqrt(abs(rel) ** 2 - a4 * a4)           # the assembly of the guess F = (70, -11)
    th4 = cmath.phase(rel) - math.atan2(s, a4)
    phi = th2 - th4
    w4 = a2 * w2 * math.sin(phi) / s
    s_dot = a2 * w2 * math.cos(phi) - w4 * a4
    lhs = (1j * a2 * al2 - a2 * w2**2) * cmath.exp(1j * phi)
    al4 = -(lhs.real + w4**2 * a4 + 2 * s_dot * w4) / s
    s_ddot = lhs.imag - al4 * a4 + w4**2 * s
    e4 = cmath.exp(1j * th4)
    coriolis = -2 * w4 * s_dot * e4
    point = a1 + e4 * (a4 + 1j * s)
    v_a4 = 1j * w4 * (point - a1)
    a_a4 = (1j * al4 - w4**2) * (point - a1)
    text = (EXAMPLES / "slotted-lever.toml").read_text() + '\nsliders = ["43"]\n'
    out = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text, "slotted-lever.toml")))
    assert close(out["links"]["4"]["omega"], w4, abs(w4))
    assert close(out["links"]["4"]["alpha"], al4, abs(al4))
    assert close(out["sliders"]["43"]["s"], s, abs(s))
    assert close(out["sliders"]["43"]["s_dot"], s_dot, abs(s_dot))
    assert close(out["sliders"]["43"]["s_ddot"], s_ddot, abs(a2 * w2**2))
    assert close(vec(out["sliders"]["43"]["coriolis"]), coriolis, abs(coriolis))
    assert close(vec(out["points"]["A@4"]["velocity"]), v_a4, abs(v_a4))
    assert close(vec(out["points"]["A@4"]["acceleration"]), a_a4, abs(a_a4))
    assert [round(c, 1) for c in out["points"]["A@4"]["velocity"]] == [-44.4, -76.8]  # the homework figure
    assert any(step["kind"] == "coriolis" for step in out["steps"])


def test_image_point_of_one_body() -> None:
    # v_S = v_A + w k x AS with w from v_B - v_A = w k x AB; likewise a_S
    A, B, S = 0j, 80 + 0j, 30 + 40j
    vA, vB, aA, aB = 300j, -100j, -50 + 0j, -2050 + 120j
    w = ((vB - vA) / (1j * (B - A))).real
    al = ((aB - aA + w * w * (B - A)) / (1j * (B - A))).real
    out = solved("image-point.toml")
    assert (w, al) == (pytest.approx(-5.0), pytest.approx(1.5))
    assert close(out["links"]["3"]["omega"], w, 5)
    assert close(out["links"]["3"]["alpha"], al, 1.5)
    assert close(vec(out["points"]["S"]["velocity"]), vA + 1j * w * (S - A), 300)
    assert close(vec(out["points"]["S"]["acceleration"]), aA + (1j * al - w * w) * (S - A), 2000)
    assert vec(out["points"]["S"]["velocity"]) == pytest.approx(200 + 150j)
    assert [s["kind"] for s in out["steps"] if s["polygon"] == "velocity"][-1] == "image"


@pytest.mark.parametrize("name", sorted(p.name for p in EXAMPLES.glob("*.toml")))
def test_every_example_solves_and_agrees_with_the_analytic_check(name: str) -> None:
    out = solved(name)
    assert out["check"]["max_rel_error"] <= 1e-12
    assert out["timing"]["total_s"] > 0


def test_scotch_yoke_rpp_group() -> None:
    # x_Y = a2 cos(th) - 60 on the frame's x-axis; the block rides the vertical slot: y_A = a2 sin(th)
    a2, th, w, al = 40.0, math.radians(50), 12.0, 3.0
    x_dot = -a2 * w * math.sin(th)
    x_ddot = -a2 * (al * math.sin(th) + w * w * math.cos(th))
    y_dot = a2 * w * math.cos(th)
    y_ddot = a2 * (al * math.cos(th) - w * w * math.sin(th))
    out = solved("scotch-yoke.toml")
    assert close(vec(out["points"]["Y"]["velocity"]), x_dot, a2 * w)
    assert close(vec(out["points"]["Y"]["acceleration"]), x_ddot, a2 * w * w)
    assert close(vec(out["points"]["A@4"]["acceleration"]), x_ddot, a2 * w * w)
    assert close(out["sliders"]["43"]["s_dot"], y_dot, a2 * w)
    assert close(out["sliders"]["43"]["s_ddot"], y_ddot, a2 * w * w)
    assert out["sliders"]["43"]["coriolis"] == [0.0, 0.0]  # the yoke translates: no Coriolis step
    assert not any(step["kind"] == "coriolis" for step in out["steps"])
    assert "group 3-4 (RPP)" in out["plan"]


def test_slotted_crank_driving_a_slider_prp_group() -> None:
    # P = (h cot(th), h) on y = h; along the slot r = h / sin(th)
    h, th, w, al = 30.0, math.radians(60), 4.0, 10.0
    s, c = math.sin(th), math.cos(th)
    x_dot = -h * w / s**2
    x_ddot = -h * (al / s**2 - 2 * w * w * c / s**3)
    r_dot = -h * c * w / s**2
    r_ddot = -h * ((al * c - w * w * s) / s**2 - 2 * c * c * w * w / s**3)
    e = complex(c, s)
    coriolis = 2 * w * 1j * (r_dot * e)  # 2 omega12 x v_rel, v_rel along the slot
    out = solved("slotted-crank-slider.toml")
    assert close(vec(out["points"]["P"]["velocity"]), x_dot, abs(x_dot))
    assert close(vec(out["points"]["P"]["acceleration"]), x_ddot, abs(x_ddot))
    assert close(out["sliders"]["23"]["s_dot"], r_dot, abs(r_dot))
    assert close(out["sliders"]["23"]["s_ddot"], r_ddot, abs(r_ddot) + abs(coriolis))
    assert close(vec(out["sliders"]["23"]["coriolis"]), coriolis, abs(coriolis))
    assert sum(step["kind"] == "coriolis" for step in out["steps"]) == 1
    assert "group 3-4 (PRP)" in out["plan"]
