"""A circle cam's flat face: which side the disc touches is an assembly, told by the [guess].

Closed forms derived here. Translating follower on the vertical guide x = 0, its face square to the
guide through T; the disc (centre K = e (cos t, sin t), radius R) under the face (the default, left
side) or above it (the right side):  y_T = e sin t +- R,  v_T = e (w cos t - ... ) by differentiation:
v_T = e w cos t,  a_T = e (alpha cos t - w^2 sin t), the same on both sides.
Pivoted follower (face through its pivot P along its x-axis at angle phi): the disc's centre at
signed height -R (right) from the face, so with K - P = rho e^{i beta}, sin(beta - phi) = -R / rho.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinepoly
from kinepoly.sweep import sweep


def _translating(e: float, r: float, theta_deg: float, omega: float, alpha: float, guess: str) -> str:
    return f"""
title = "flat face, side by guess"
[links]
1 = {{ points = {{ O = [0, 0] }} }}
2 = {{ points = {{ O = [0, 0] }} }}
3 = {{ points = {{ T = [0, 0], S = [0, 40] }} }}
[[sliders]]
block = "3"
guide = "1"
point = "T"
line = {{ through = [0, 0], angle = 90 }}
[[cams]]
cam = "2"
follower = "3"
profile = {{ circle = {{ center = [{e!r}, 0], radius = {r!r} }} }}
flat = {{ through = [0, 0], angle = 90 }}
[input]
link = "2"
angle = {theta_deg!r}
omega = {omega!r}
alpha = {alpha!r}
{guess}
[find]
velocity = ["T"]
acceleration = ["T"]
"""


def _warnings(data: dict[str, object]) -> str:
    return repr(data.get("warnings", []))


def _point(data: dict[str, object], name: str, key: str) -> complex:
    points = data["points"]
    assert isinstance(points, dict)
    x, y = points[name][key]
    return complex(x, y)


def _check_translating(e: float, r: float, theta_deg: float, w: float, alpha: float, below: bool) -> None:
    t = math.radians(theta_deg)
    k = e * complex(math.cos(t), math.sin(t))
    sign = -1.0 if below else 1.0  # T below the disc: the disc on the face's right
    guess = f"[guess]\nT = [0, {k.imag + sign * 1.5 * r!r}]"
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(_translating(e, r, theta_deg, w, alpha, guess))))
    scale = e + r
    assert "default-assembly" not in _warnings(data)
    assert _point(data, "T", "position") == pytest.approx(complex(0.0, k.imag + sign * r), abs=1e-12 * scale)
    assert _point(data, "T", "velocity") == pytest.approx(complex(0.0, e * w * math.cos(t)), abs=1e-11 * scale * abs(w))
    a = e * (alpha * math.cos(t) - w * w * math.sin(t))
    assert _point(data, "T", "acceleration") == pytest.approx(complex(0.0, a), abs=1e-10 * scale * (w * w + abs(alpha)))
    contact = data["contacts"]["23"]
    q = complex(k.real, k.imag + sign * r)
    assert complex(*contact["point"]) == pytest.approx(q, abs=1e-12 * scale)
    assert complex(*contact["normal"]) == pytest.approx(complex(0.0, sign), abs=1e-14)
    # the follower's point at Q moves straight up (e w cos t); the cam's turns: w i Q
    sliding = complex(0.0, e * w * math.cos(t)) - w * 1j * q
    assert complex(*contact["sliding_velocity"]) == pytest.approx(sliding, abs=1e-11 * scale * abs(w))


def test_disc_above_the_face_fixed_case() -> None:
    _check_translating(12.0, 35.0, 40.0, 15.0, 0.0, below=True)


def test_disc_below_the_face_is_the_old_behaviour() -> None:
    _check_translating(12.0, 35.0, 40.0, 15.0, 0.0, below=False)


@settings(max_examples=40, deadline=None)
@given(e=st.floats(1.0, 30.0), r=st.floats(31.0, 80.0), theta=st.floats(-180.0, 180.0),
       w=st.floats(-20.0, 20.0).filter(lambda x: abs(x) > 0.1), alpha=st.floats(-50.0, 50.0), below=st.booleans())
def test_either_side_against_the_closed_form(e: float, r: float, theta: float, w: float, alpha: float,
                                             below: bool) -> None:
    _check_translating(e, r, theta, w, alpha, below)


def test_sweep_with_the_disc_above_the_face_over_a_turn() -> None:
    e, r, w = 12.0, 35.0, 15.0
    scene = kinepoly.loads_scene(_translating(e, r, 40.0, w, 0.0, "[guess]\nT = [0, -30]"))
    result = sweep(scene, steps=360)
    t = np.radians(result.input.values)
    assert (result.status == 0).all()
    y, v, a = (result.column(f"{q}_T_y").values for q in ("r", "v", "a"))
    assert np.max(np.abs(y - (e * np.sin(t) - r))) < 1e-9 * (e + r)
    assert np.max(np.abs(v - e * w * np.cos(t))) < 1e-9 * e * w
    assert np.max(np.abs(a + e * w * w * np.sin(t))) < 1e-9 * e * w * w


def test_without_a_telling_guess_the_left_is_taken_with_a_warning() -> None:
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(_translating(12.0, 35.0, 40.0, 15.0, 0.0, ""))))
    warnings = _warnings(data)
    assert "default-assembly" in warnings and "cam 23" in warnings and "left" in warnings
    assert _point(data, "T", "position").imag == pytest.approx(12.0 * math.sin(math.radians(40.0)) + 35.0,
                                                                rel=1e-13)


def _rocker_text(theta_deg: float, guess: complex) -> str:
    return f"""
title = "pivoted flat face, disc on its right"
[links]
1 = {{ points = {{ O2 = [0, 0], O3 = [110, 70] }} }}
2 = {{ points = {{ O2 = [0, 0] }} }}
3 = {{ points = {{ O3 = [0, 0], F = [130, 0] }} }}
[[cams]]
cam = "2"
follower = "3"
profile = {{ circle = {{ center = [20, 0], radius = 40 }} }}
flat = {{ through = [0, 0], angle = 0 }}
[input]
link = "2"
angle = {theta_deg!r}
omega = 10
alpha = 0
[guess]
F = [{guess.real!r}, {guess.imag!r}]
[find]
omega = ["3"]
alpha = ["3"]
velocity = ["F"]
"""


def _face_angle(theta: float, branch: float) -> float:
    """phi with the disc's centre at height -R from the face through P (the right side)."""
    p, k = complex(110.0, 70.0), 20.0 * complex(math.cos(theta), math.sin(theta))
    rho, beta = abs(k - p), math.atan2((k - p).imag, (k - p).real)
    return beta + math.asin(40.0 / rho) if branch > 0 else beta - math.pi - math.asin(40.0 / rho)


@pytest.mark.parametrize("branch", [1.0, -1.0])
def test_pivoted_face_with_the_disc_on_its_right_against_the_closed_form(branch: float) -> None:
    theta, h, p = math.radians(50.0), 1e-4, complex(110.0, 70.0)
    phi = _face_angle(theta, branch)
    f = p + 130.0 * complex(math.cos(phi), math.sin(phi))
    sol = kinepoly.solve(kinepoly.loads_scene(_rocker_text(50.0, f + 3.0)))
    data = kinepoly.to_json(sol)
    assert "default-assembly" not in _warnings(data)
    assert _point(data, "F", "position") == pytest.approx(f, abs=1e-10)
    # omega3 = dphi/dt = 10 dphi/dtheta, alpha3 = 100 d2phi/dtheta2 (central differences, h^2 ~ 1e-8)
    values = [_face_angle(theta + s * h, branch) for s in (-1.0, 0.0, 1.0)]
    omega3 = 10.0 * (values[2] - values[0]) / (2 * h)
    alpha3 = 100.0 * (values[2] - 2 * values[1] + values[0]) / (h * h)
    links = data["links"]
    assert isinstance(links, dict)
    assert links["3"]["omega"] == pytest.approx(omega3, rel=1e-7)
    assert links["3"]["alpha"] == pytest.approx(alpha3, rel=1e-4, abs=1e-3)


@pytest.mark.parametrize("guess_x", [-60.0, 60.0])
def test_a_follower_that_is_the_guide_of_a_frame_block(guess_x: float) -> None:
    # the follower slides along the frame's x-axis (its rotation read from the slider, not from two points);
    # its face is vertical through T: x_T = e cos t + R (disc on the face's left) or - R (on its right)
    text = _translating(12.0, 35.0, 40.0, 15.0, 0.0, f"[guess]\nT = [{guess_x!r}, 0]")
    text = text.replace('block = "3"\nguide = "1"\npoint = "T"\nline = { through = [0, 0], angle = 90 }',
                        'block = "1"\nguide = "3"\npoint = "O"\nline = { through = [0, 0], angle = 0 }')
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text)))
    t = math.radians(40.0)
    assert "default-assembly" not in _warnings(data)
    assert _point(data, "T", "position") == pytest.approx(
        complex(12.0 * math.cos(t) + math.copysign(35.0, guess_x), 0.0), abs=1e-12)
    assert _point(data, "T", "velocity") == pytest.approx(complex(-12.0 * 15.0 * math.sin(t), 0.0), abs=1e-11)
