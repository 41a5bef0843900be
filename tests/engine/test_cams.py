"""Circle cams by their permanent equivalent linkage: closed forms derived here, over whole sweeps."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import kinepoly
from kinepoly.errors import SceneError
from kinepoly.sweep import SweepResult, sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _radians(result: SweepResult) -> np.ndarray:
    return np.radians(result.input.values)


def test_flat_faced_follower_is_simple_harmonic_motion_over_a_turn() -> None:
    # disc centre K at e = 12 from the pivot, radius R = 35, face square to the guide through O:
    # y_T = e sin(theta) + R, v = e omega cos(theta), a = -e omega^2 sin(theta) (alpha = 0)
    result = sweep(kinepoly.load_scene(EXAMPLES / "eccentric-cam-flat.toml"), steps=360)
    theta = _radians(result)
    e, r, w = 12.0, 35.0, 15.0
    y = result.column("r_T_y").values
    v = result.column("v_T_y").values
    a = result.column("a_T_y").values
    assert np.max(np.abs(y - (e * np.sin(theta) + r))) < 1e-9 * (e + r)
    assert np.max(np.abs(v - e * w * np.cos(theta))) < 1e-9 * e * w
    assert np.max(np.abs(a + e * w * w * np.sin(theta))) < 1e-9 * e * w * w
    assert (result.status == 0).all()


def test_flat_follower_solve_contact_and_steps() -> None:
    sol = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "eccentric-cam-flat.toml"))
    data = kinepoly.to_json(sol)
    theta = math.radians(40.0)
    contact = data["contacts"]["23"]
    assert contact["point"] == pytest.approx([12 * math.cos(theta), 12 * math.sin(theta) + 35.0], rel=1e-14)
    assert contact["normal"] == pytest.approx([0.0, 1.0], abs=1e-15)
    # the face slides over the disc: the follower translates up, the disc point turns with 15 rad/s
    v_cam = 15.0 * 1j * complex(*contact["point"])
    assert contact["sliding_velocity"] == pytest.approx([-v_cam.real, 0.0], rel=1e-13, abs=1e-12)
    assert any(step.topic == "equivalent-link" for step in sol.steps)
    assert sol.scene.cams[0].equivalent == "4"  # the block a textbook numbers 4
    assert "links" not in data or "4" not in data["links"]


def _rocker(theta: float, sign: float) -> tuple[complex, float, float]:
    """The four-bar O K W P equivalent to the cam: W, omega3, alpha3 (omega2 = 20, alpha2 = 0)."""
    w2 = 20.0
    k = 15.0 * complex(math.cos(theta), math.sin(theta))
    p = complex(75.0, 35.0)
    d = abs(p - k)
    a = (50.0**2 - 60.0**2 + d * d) / (2 * d)
    h = math.sqrt(50.0**2 - a * a)
    unit = (p - k) / d
    w = k + a * unit + sign * h * 1j * unit
    u = w - k
    v_k = w2 * 1j * k

    def dot(x: complex, y: complex) -> float:
        return (x * y.conjugate()).real

    w3 = dot(v_k, u) / dot(1j * (w - p), u)
    v_w = w3 * 1j * (w - p)
    a_k = -w2 * w2 * k
    alpha3 = (dot(a_k, u) + w3 * w3 * dot(w - p, u) - abs(v_w - v_k) ** 2) / dot(1j * (w - p), u)
    return w, w3, alpha3


def test_roller_on_a_rocker_against_its_four_bar_over_a_turn() -> None:
    result = sweep(kinepoly.load_scene(EXAMPLES / "cam-roller-rocker.toml"), steps=180)
    theta = _radians(result)
    wx, wy = result.column("r_W_x").values, result.column("r_W_y").values
    omega, alpha = result.column("omega_3").values, result.column("alpha_3").values
    first = complex(wx[0], wy[0])
    sign = min((1.0, -1.0), key=lambda s: abs(_rocker(float(theta[0]), s)[0] - first))
    worst_n = 0.0
    for k, t in enumerate(theta):
        w, w3, a3 = _rocker(float(t), sign)
        assert abs(complex(wx[k], wy[k]) - w) < 1e-9 * 90.0
        assert omega[k] == pytest.approx(w3, rel=1e-9, abs=1e-9 * 20.0)
        assert alpha[k] == pytest.approx(a3, rel=1e-9, abs=1e-9 * 400.0)
        # the contact's velocity condition: the normal components of the two contact points agree
        kk = 15.0 * complex(math.cos(t), math.sin(t))
        n = (w - kk) / abs(w - kk)
        c = kk + 40.0 * n
        v_cam = 20.0 * 1j * c
        v_follower = omega[k] * 1j * (c - complex(75.0, 35.0))
        residual = abs(((v_cam - v_follower) * n.conjugate()).real) / abs(v_cam)
        worst_n = max(worst_n, residual)
    assert worst_n < 1e-12


def test_roller_solve_matches_the_sweep_row_and_the_check() -> None:
    sol = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "cam-roller-rocker.toml"))
    data = kinepoly.to_json(sol)
    _w, w3, a3 = _rocker(math.radians(30.0), 1.0 if data["points"]["W"]["position"][1] > 0 else -1.0)
    assert data["links"]["3"]["omega"] == pytest.approx(w3, rel=1e-12)
    assert data["links"]["3"]["alpha"] == pytest.approx(a3, rel=1e-12)
    contact = data["contacts"]["23"]
    assert math.hypot(*contact["normal"]) == pytest.approx(1.0, rel=1e-15)
    # I23 lies on the common normal through K
    k = 15.0 * complex(math.cos(math.radians(30.0)), math.sin(math.radians(30.0)))
    i23 = complex(*data["instant_centers"]["23"]["position"])
    n = complex(*contact["normal"])
    assert abs(((i23 - k) * n.conjugate()).imag) < 1e-9 * 100.0
    assert data["check"]["max_rel_error"] < 1e-12



def test_a_circle_cams_centre_takes_polar_like_every_point() -> None:
    # the disc's centre 15 from the pivot at 30 degrees, written both ways; the bad form named by its key
    text = (EXAMPLES / "cam-roller-rocker.toml").read_text(encoding="utf-8")
    assert "center = [15, 0]" in text
    x, y = 15.0 * math.cos(math.radians(30.0)), 15.0 * math.sin(math.radians(30.0))
    as_pair = kinepoly.loads_scene(text.replace("center = [15, 0]", f"center = [{x!r}, {y!r}]"))
    as_polar = kinepoly.loads_scene(text.replace("center = [15, 0]", "center = { polar = [15, 30] }"))
    assert as_polar.cams[0].center == pytest.approx(as_pair.cams[0].center, rel=1e-15, abs=1e-15)
    one, two = (kinepoly.to_json(kinepoly.solve(scene)) for scene in (as_pair, as_polar))
    assert one["links"]["3"]["angle"] != pytest.approx(
        kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text)))["links"]["3"]["angle"])
    for name, link in one["links"].items():
        other = two["links"][name]
        assert ("line" in other) == ("line" in link)
        if "line" in link:  # the named line a reader knows the link by
            assert other["line"]["name"] == link["line"]["name"]
            assert other["line"]["angle"] == pytest.approx(link["line"]["angle"], rel=1e-13)
        numbers = {key: value for key, value in link.items() if key != "line"}
        assert {key: other[key] for key in numbers} == pytest.approx(numbers, rel=1e-13, abs=1e-12)
    with pytest.raises(SceneError, match=r"cams\.1\.profile\.circle\.center\.polar: expected \[r, angle\]"):
        kinepoly.loads_scene(text.replace("center = [15, 0]", "center = { polar = [15] }"), "cam.toml")
