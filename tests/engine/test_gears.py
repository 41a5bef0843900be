"""Gears by their pitch curves: closed forms derived here, against the construction and the sweep."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import kinepoly
from kinepoly.errors import SceneError
from kinepoly.sweep import sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _solve(name: str) -> kinepoly.Solution:
    return kinepoly.solve(kinepoly.load_scene(EXAMPLES / name))


def test_gear_pair_ratio_is_minus_r2_over_r3() -> None:
    # external pair, r2 = 40, r3 = 60: omega3 = -(r2/r3) omega2, alpha3 = -(r2/r3) alpha2; phases 0:
    # at the reference theta2 = 0, theta3 = 180 deg; rolled 20 deg: theta3 = 180 - 20 r2/r3
    sol = _solve("gear-pair.toml")
    data = kinepoly.to_json(sol)
    ratio = 40.0 / 60.0
    assert data["links"]["3"]["omega"] == pytest.approx(-12.0 * ratio, rel=1e-15)
    assert data["links"]["3"]["alpha"] == pytest.approx(-1.0 * ratio, rel=1e-14)
    assert data["links"]["3"]["angle"] == pytest.approx(180.0 - 20.0 * ratio, rel=1e-14)
    assert data["contacts"]["23"] == {"point": [40.0, 0.0], "normal": [1.0, 0.0], "sliding_velocity": [0.0, 0.0]}
    assert data["instant_centers"]["23"]["position"] == pytest.approx([40.0, 0.0], abs=1e-12)
    assert sol.check.max_rel_error < 1e-12
    # the pin E on gear 3 (45 from O3 = (100, 0)): closed form
    theta3 = math.radians(180.0 - 20.0 * ratio)
    w3, a3 = -12.0 * ratio, -ratio
    arm = 45.0 * complex(math.cos(theta3), math.sin(theta3))
    v = w3 * 1j * arm
    a = a3 * 1j * arm - w3 * w3 * arm
    assert data["points"]["E"]["velocity"] == pytest.approx([v.real, v.imag], rel=1e-13, abs=1e-11)
    assert data["points"]["E"]["acceleration"] == pytest.approx([a.real, a.imag], rel=1e-13, abs=1e-10)


def test_gear_pair_sweep_keeps_the_ratio_and_continues_the_phase() -> None:
    result = sweep(kinepoly.load_scene(EXAMPLES / "gear-pair.toml"), steps=36)
    omega = result.column("omega_3").values
    assert np.max(np.abs(omega / 12.0 + 40.0 / 60.0)) < 1e-14
    assert (result.status == 0).all()


def test_planetary_train_by_willis() -> None:
    # sun 1 fixed (r 30), planet 3 (r 20) on arm 2, ring 4 (r 70): planet (w3 - w2)/(0 - w2) = -30/20,
    # ring (w4 - w2)/(0 - w2) = -30/70; the same for the alphas
    data = kinepoly.to_json(_solve("planetary.toml"))
    w2, a2 = 10.0, 2.0
    assert data["links"]["3"]["omega"] == pytest.approx(w2 + 1.5 * w2, rel=1e-14)
    assert data["links"]["4"]["omega"] == pytest.approx(w2 + (3.0 / 7.0) * w2, rel=1e-14)
    assert data["links"]["3"]["alpha"] == pytest.approx(a2 + 1.5 * a2, rel=1e-13)
    assert data["links"]["4"]["alpha"] == pytest.approx(a2 + (3.0 / 7.0) * a2, rel=1e-13)
    assert set(data["contacts"]) == {"13", "34"}
    assert data["check"]["max_rel_error"] < 1e-12


def test_rack_and_pinion() -> None:
    # pinion r = 25 at O, rack below on a horizontal guide: s = r theta2 (phase -90: at theta2 = 0 the
    # pitch point is the rack's through point), s_dot = r omega2, s_ddot = r alpha2
    data = kinepoly.to_json(_solve("rack-pinion.toml"))
    slider = data["sliders"]["13"]
    assert slider["s"] == pytest.approx(25.0 * math.radians(30.0), rel=1e-14)
    assert slider["s_dot"] == pytest.approx(25.0 * 4.0, rel=1e-14)
    assert slider["s_ddot"] == pytest.approx(25.0 * -3.0, rel=1e-14)
    assert data["contacts"]["23"]["point"] == pytest.approx([0.0, -25.0], abs=1e-12)
    assert data["check"]["max_rel_error"] < 1e-12


def _text(name: str) -> str:
    return (EXAMPLES / name).read_text()


def test_centres_too_far_apart_is_an_error_naming_the_distance() -> None:
    text = _text("gear-pair.toml").replace("O3 = [100, 0]", "O3 = [104, 0]")
    with pytest.raises(SceneError, match=r"gears\.23: the centres O2 and O3 are 104 mm apart.*expected 100"):
        kinepoly.solve(kinepoly.loads_scene(text, "pair.toml"))


def test_gear_tables_are_checked_with_line_and_key() -> None:
    text = _text("gear-pair.toml").replace('{ center = "O3", radius = 60 }', '{ center = "Q", radius = -1 }')
    with pytest.raises(SceneError) as error:
        kinepoly.loads_scene(text, "pair.toml")
    message = str(error.value)
    assert "gears.1.pitch.2.center" in message and 'no point "Q"' in message
    assert "gears.1.pitch.2.radius" in message and "pair.toml:" in message
