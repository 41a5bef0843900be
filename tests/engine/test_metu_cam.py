"""The METU instant-center text's cam (examples/metu-cam.toml): its three instant centers derived here.

The text: I12 and I13 are the pivots; by Kennedy I23 lies on the line I12 I13; the relative motion of
3 on 2 turns about a point of the common normal at the contact; so I23 is where the two lines cross.

Derived apart from the engine: the disc's centre K = e (cos t, sin t); the follower's face is the line
y' = f in its own frame (x' along its axis at the angle phi, from the pivot O3); the disc of radius R
touches it from the face's left, so K sits at y' = f + R: with rho, beta the distance and direction of
K from O3, rho sin(beta - phi) = f + R, phi = beta - asin((f + R) / rho) (K ahead of the pivot along
the axis). The common normal is the face's left normal n = (-sin phi, cos phi) through K; the contact
C = K - R n. With I23 on both lines, omega3 / omega2 = (I12 I23) / (I13 I23), the distances signed along
the line (I23 has one velocity as a point of 2 and of 3). phi(t) differentiated by mpmath gives omega3
and alpha3 a second way.
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath  # type: ignore[import-untyped]
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.cli_support import run

import kinepoly
from kinepoly.scene.loader import loads_scene

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "metu-cam.toml"
E, R, FACE, O3 = 20.0, 40.0, 0.0, complex(110.0, 70.0)  # read off examples/metu-cam.toml


def _phi(t: float) -> float:
    k = E * complex(math.cos(t), math.sin(t))
    rho, beta = abs(k - O3), math.atan2((k - O3).imag, (k - O3).real)
    return beta - math.asin((FACE + R) / rho)


def _phi_mp(t: object) -> object:
    k = (E * mpmath.cos(t) - O3.real, E * mpmath.sin(t) - O3.imag)
    return mpmath.atan2(k[1], k[0]) - mpmath.asin((FACE + R) / mpmath.hypot(*k))


def _cross(p1: complex, d1: complex, p2: complex, d2: complex) -> complex:
    """The crossing of the line through p1 along d1 with the line through p2 along d2."""
    s = ((p2 - p1).real * d2.imag - (p2 - p1).imag * d2.real) / (d1.real * d2.imag - d1.imag * d2.real)
    return p1 + s * d1


def _derived(theta_deg: float) -> dict[str, complex | float]:
    t = math.radians(theta_deg)
    phi = _phi(t)
    k = E * complex(math.cos(t), math.sin(t))
    normal = complex(-math.sin(phi), math.cos(phi))
    i12, i13 = 0j, O3
    i23 = _cross(i12, i13 - i12, k, normal)
    along = (i13 - i12) / abs(i13 - i12)
    ratio = ((i23 - i12) / along).real / ((i23 - i13) / along).real
    return {"I12": i12, "I13": i13, "I23": i23, "contact": k - R * normal, "normal": normal, "ratio": ratio,
            "phi": phi}


def _scene_at(theta_deg: float) -> str:
    """The example at another input angle, its [guess] the face's end F where the derivation puts it."""
    phi = _phi(math.radians(theta_deg))
    f = O3 + complex(math.cos(phi), math.sin(phi)) * complex(130.0, FACE)
    text = EXAMPLE.read_text().replace("angle = 50\n", f"angle = {theta_deg!r}\n")
    return text.replace("F = [-18.6, 51.1]", f"F = [{f.real!r}, {f.imag!r}]")


def _check(data: dict, theta_deg: float, omega2: float) -> None:  # type: ignore[type-arg]
    want = _derived(theta_deg)
    centers = data["instant_centers"]
    for name in ("12", "13", "23"):
        got = complex(*centers[name]["position"])
        assert abs(got - want[f"I{name}"]) < 1e-11 * abs(O3), name  # type: ignore[operator]
    contact = data["contacts"]["23"]
    assert abs(complex(*contact["point"]) - want["contact"]) < 1e-11 * abs(O3)  # type: ignore[operator]
    # the contract's normal runs from the cam's side to the follower's: against n (the face toward K)
    assert abs(complex(*contact["normal"]) + want["normal"]) < 1e-13  # type: ignore[operator]
    omega3 = data["links"]["3"]["omega"]
    assert omega3 == pytest.approx(omega2 * want["ratio"], rel=1e-11)  # I12 I23 / I13 I23, with its sign
    t = mpmath.mpf(math.radians(theta_deg))
    with mpmath.workdps(30):
        assert omega3 == pytest.approx(float(mpmath.diff(_phi_mp, t) * omega2), rel=1e-11)
        assert data["links"]["3"]["alpha"] == pytest.approx(float(mpmath.diff(_phi_mp, t, 2) * omega2**2),
                                                            rel=1e-10)


def test_the_three_instant_centers_of_the_metu_cam() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLE))
    data = kinepoly.to_json(solution)
    turn = math.remainder(math.radians(data["links"]["3"]["angle"]) - _derived(50.0)["phi"], math.tau)  # type: ignore[operator]
    assert abs(turn) < 1e-13
    _check(data, 50.0, 10.0)
    assert _derived(50.0)["ratio"] < 0  # I23 between I12 and I13: the follower turns against the cam
    assert data["links"]["3"]["omega"] < 0
    assert solution.check.max_rel_error < 1e-12


@settings(max_examples=20, deadline=None)
@given(theta=st.floats(-180.0, 180.0).map(lambda x: round(x, 2)))
def test_the_metu_cams_centers_at_any_cam_angle(theta: float) -> None:
    data = kinepoly.to_json(kinepoly.solve(loads_scene(_scene_at(theta))))
    _check(data, theta, 10.0)


def test_solve_steps_find_i23_on_the_line_i12_i13(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "solve", str(EXAMPLE), "--steps")
    assert code == 0, err
    assert "equivalent block at K on the face of 3" in out and "I23 = (I12 I13) x" in out
    assert "Links 1, 2, 3: I23 lies on the line I12 I13." in out
    shown = format(10.0 * _derived(50.0)["ratio"], ".5g").replace("-", "\u2212")  # type: ignore[arg-type]
    assert "(I12 I23)/(I13 I23) = 10 × (" in out and f") = {shown} rad/s, clockwise" in out
