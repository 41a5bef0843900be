"""Spline cams solved through their equivalent link, against exact solutions derived here.

The profiles are splines through samples of an eccentric circle (centre [15, 0], radius 40, in the cam's
frame), whose exact follower motion has a closed form: for a knife edge on a vertical guide through the
cam's pivot, y = e sin(theta) + sqrt(R^2 - e^2 cos(theta)^2) (its derivatives by mpmath, apart from any
code of kinepoly); for the roller on a rocker, the two-circle closure of the four-bar O K W P
(``test_cams._rocker``); for a flat face, simple harmonic motion (translating) and the face tangent to the
disc (a rocker). The spline's error falls at its order as the points double; every solve is also checked
against the analytic solution, and the contact's normal velocities are compared at every row.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.engine.test_cams import _rocker

import kinepoly
from kinepoly.errors import AssemblyError
from kinepoly.sweep import sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
KNIFE = EXAMPLES / "spline-cam-knife.toml"
ROCKER = EXAMPLES / "spline-cam-roller-rocker.toml"
E, R = 15.0, 40.0
PROFILE = re.compile(r"profile = \{ points = \[.*?\] \}", re.DOTALL)


def _with_points(path: Path, points: list[list[float]] | None, replace: dict[str, str] | None = None) -> kinepoly.Scene:
    """The example at ``path`` with its profile's points (None: its own) and texts replaced."""
    text = path.read_text()
    if points is not None:
        text = PROFILE.sub(f"profile = {{ points = {points!r} }}", text)
    for old, new in (replace or {}).items():
        assert old in text
        text = text.replace(old, new)
    return kinepoly.loads_scene(text, path.name)


def _circle(n: int) -> list[list[float]]:
    return [[E + R * math.cos(2 * math.pi * k / n), R * math.sin(2 * math.pi * k / n)] for k in range(n)]


def _knife_exact(theta: float, omega: float = 10.0, alpha: float = 5.0) -> tuple[float, float, float]:
    """y, y_dot, y_ddot of the knife edge on the exact circle (mpmath, 30 digits)."""
    with mp.workdps(30):
        def y(t: mp.mpf) -> mp.mpf:
            return E * mp.sin(t) + mp.sqrt(R**2 - E**2 * mp.cos(t) ** 2)

        first, second = mp.diff(y, theta, 1), mp.diff(y, theta, 2)
        return float(y(theta)), float(omega * first), float(omega**2 * second + alpha * first)


def _knife_errors(n: int, steps: int = 72) -> tuple[float, float, float]:
    result = sweep(_with_points(KNIFE, _circle(n)), steps=steps)
    assert (result.status == 0).all()
    exact = np.array([_knife_exact(t) for t in np.radians(result.input.values)])
    return tuple(float(np.max(np.abs(result.column(c).values - exact[:, k])))  # type: ignore[return-value]
                 for k, c in enumerate(("r_W_y", "v_W_y", "a_W_y")))


def test_knife_example_agrees_with_the_exact_rise_over_a_turn() -> None:
    result = sweep(kinepoly.load_scene(KNIFE), steps=360)
    assert (result.status == 0).all()
    exact = np.array([_knife_exact(t) for t in np.radians(result.input.values)])
    # 36 points of a circle of radius 40: the documented accuracy (h^4, h^3, h^2) measured here
    assert np.max(np.abs(result.column("r_W_y").values - exact[:, 0])) < 2e-4
    assert np.max(np.abs(result.column("v_W_y").values - exact[:, 1])) < 0.03
    assert np.max(np.abs(result.column("a_W_y").values - exact[:, 2])) < 25.0


def test_error_falls_at_the_splines_order_as_the_points_double() -> None:
    # measured: 36 -> 72 -> 144 points divide the errors by 16.7 and 15.3 (position), 7.9 and 7.8 (velocity),
    # 4.0 and 4.0 (acceleration)
    coarse, middle, fine = (_knife_errors(n) for n in (36, 72, 144))
    for k, order in enumerate((4, 3, 2)):
        for a, b in ((coarse, middle), (middle, fine)):
            assert math.log2(a[k] / b[k]) == pytest.approx(order, abs=0.35)


def test_solve_at_any_row_equals_the_sweep_row() -> None:
    result = sweep(kinepoly.load_scene(KNIFE), steps=24)
    for row in (0, 5, 11, 17, 23):
        angle = float(result.input.values[row])
        data = kinepoly.to_json(kinepoly.solve(_with_points(KNIFE, None, {"angle = 30": f"angle = {angle!r}"})))
        point = data["points"]["W"]
        assert point["position"][1] == pytest.approx(result.column("r_W_y").values[row], rel=1e-12)
        assert point["velocity"][1] == pytest.approx(result.column("v_W_y").values[row], rel=1e-12, abs=1e-9)
        assert point["acceleration"][1] == pytest.approx(result.column("a_W_y").values[row], rel=1e-12, abs=1e-9)
        assert data["check"]["max_rel_error"] < 1e-12


def _normal_residual(data: dict[str, object], omega_cam: float, point: str = "W") -> float:
    """|(v_follower(Q) - v_cam(Q)) . n| / |v_cam(Q)| at the contact Q (the cam turns about O = 0), the
    follower's velocity there from its ``point``'s."""
    contact = data["contacts"]["23"]  # type: ignore[index]
    q, n = complex(*contact["point"]), complex(*contact["normal"])
    w = data["points"][point]  # type: ignore[index]
    omega = data.get("links", {}).get("3", {}).get("omega", 0.0)  # type: ignore[attr-defined]
    on_follower = complex(*w["velocity"]) + omega * 1j * (q - complex(*w["position"]))
    on_cam = omega_cam * 1j * q
    return abs(((on_follower - on_cam) * n.conjugate()).real) / abs(on_cam)


@pytest.mark.parametrize(("name", "omega", "point"), [("spline-cam-knife.toml", 10.0, "W"),
                                                      ("spline-cam-roller-rocker.toml", 20.0, "W"),
                                                      ("spline-cam-flat-rocker.toml", 10.0, "S")])
def test_the_contacts_normal_velocities_are_equal_at_every_row_of_a_turn(name: str, omega: float, point: str) -> None:
    path = EXAMPLES / name
    worst = 0.0
    for degrees in range(0, 360, 10):
        data = kinepoly.to_json(kinepoly.solve(_with_points(path, None, {"angle = 30": f"angle = {degrees}"})))
        contact = data["contacts"]["23"]
        assert math.hypot(*contact["normal"]) == pytest.approx(1.0, rel=1e-14)
        assert (complex(*contact["sliding_velocity"]) * complex(*contact["normal"]).conjugate()).real == (
            pytest.approx(0.0, abs=1e-9))
        worst = max(worst, _normal_residual(data, omega, point))
        assert data["check"]["max_rel_error"] < 1e-12  # measured at most 6.9e-16, 2.4e-14, 1.1e-15
    assert worst < 1e-13  # measured: 4.0e-16 (knife), 5.7e-16 (roller on a rocker), 2.0e-16 (flat rocker)


def test_rocker_example_agrees_with_the_exact_four_bar() -> None:
    result = sweep(kinepoly.load_scene(ROCKER), steps=180)
    assert (result.status == 0).all()
    theta = np.radians(result.input.values)
    exact = [_rocker(float(t), 1.0) for t in theta]
    w = result.column("r_W_x").values + 1j * result.column("r_W_y").values
    # measured with 36 points: 9.5e-4 mm, 5.6e-3 rad/s (the cam turns at 20), 4.8 rad/s^2 (of 875)
    assert np.max(np.abs(w - np.array([e[0] for e in exact]))) < 1.5e-3
    assert np.max(np.abs(result.column("omega_3").values - [e[1] for e in exact])) < 8e-3
    assert np.max(np.abs(result.column("alpha_3").values - [e[2] for e in exact])) < 7.0


def test_a_follower_that_cannot_reach_the_profile_exits_3_naming_the_pair() -> None:
    scene = _with_points(KNIFE, _circle(36), {"line = { through = [0, 0], angle = 90 }":
                                              "line = { through = [80, 0], angle = 90 }"})
    with pytest.raises(AssemblyError, match=r"spline-cam-knife\.toml:\d+: cams\.23: at theta12 = 30 deg, follower 3 "
                       r"cannot touch cam 2: the line W slides along on 1 misses the profile"):
        kinepoly.solve(scene)
    # a guide at x = 50 reaches the profile (x in 15 cos(theta) -+ 40) only while cos(theta) >= 2/3: a sweep
    # marks the other rows instead
    near = _with_points(KNIFE, None, {"line = { through = [0, 0], angle = 90 }":
                                      "line = { through = [50, 0], angle = 90 }"})
    result = sweep(near, steps=72, start=0.0, stop=360.0)
    reaches = np.cos(np.radians(result.input.values)) > 2.0 / 3.0
    assert reaches.any() and not reaches.all()
    assert ((result.status == 0) == reaches).all()
    row = int(np.flatnonzero(~reaches)[0])
    assert "follower 3 cannot touch cam 2: the line W slides along on 1 misses the profile" in result.warnings[row]
    # without a range, the sweep runs where the follower reaches: |theta| <= acos(2/3) = 48.19 deg on the
    # circle, 48.18 on the spline (the edge is a grazing contact: the spline's 1e-4 mm moves it 0.01 deg)
    ends = sweep(near, steps=12).input.values
    assert (ends[0], ends[-1]) == pytest.approx((-math.degrees(math.acos(2 / 3)), math.degrees(math.acos(2 / 3))),
                                                abs=0.02)


def _bean(n: int) -> list[list[float]]:
    """r = 40 + 8 cos(3 phi): concave near phi = 60, 180, 300 deg (radius of curvature 25.6 there)."""
    out = []
    for k in range(n):
        phi = 2 * math.pi * k / n
        r = 40.0 + 8.0 * math.cos(3 * phi)
        out.append([r * math.cos(phi), r * math.sin(phi)])
    return out


def _roller_on_the_bean(radius: int) -> kinepoly.Scene:
    # at theta = 30 deg the bean's hollow at phi = 60 deg is on top, under the guide through O
    return _with_points(KNIFE, _bean(90), {'knife = "W"': f'roller = {{ center = "W", radius = {radius} }}',
                                           "W = [0, 50]": f"W = [0, {32 + radius}]"})


def test_a_roller_larger_than_the_concave_radius_is_refused_with_the_radius() -> None:
    data = kinepoly.to_json(kinepoly.solve(_roller_on_the_bean(20)))  # 20 < 25.6: it touches the hollow
    assert data["contacts"]["23"]["point"] == pytest.approx([0.0, 32.0], abs=1e-9)
    assert data["points"]["W"]["position"] == pytest.approx([0.0, 52.0], abs=1e-9)
    assert data["check"]["max_rel_error"] < 1e-12
    with pytest.raises(AssemblyError, match=r"cams\.23: at theta12 = 30 deg, the roller of radius 30 mm is larger "
                       r"than the profile's concave radius 2\d\.\d+ mm at the contact"):
        kinepoly.solve(_roller_on_the_bean(30))


def _polar_profile(n: int, a2: float, p2: float, a3: float, p3: float) -> list[list[float]]:
    out = []
    for k in range(n):
        phi = 2 * math.pi * k / n
        r = 40.0 + a2 * math.cos(2 * phi + p2) + a3 * math.cos(3 * phi + p3)
        out.append([r * math.cos(phi), r * math.sin(phi)])
    return out


@settings(max_examples=25, deadline=None)
@given(a2=st.floats(0.0, 2.0), p2=st.floats(0.0, 6.28), a3=st.floats(0.0, 1.0), p3=st.floats(0.0, 6.28),
       offset=st.floats(-15.0, 15.0), angle=st.floats(0.0, 360.0),
       omega=st.one_of(st.floats(-20.0, -1.0), st.floats(1.0, 20.0)),
       alpha=st.one_of(st.just(0.0), st.floats(-50.0, -0.5), st.floats(0.5, 50.0)), rocker=st.booleans(),
       touch=st.sampled_from(["knife", "roller", "flat"]))
def test_random_convex_profiles_solve_and_check(a2: float, p2: float, a3: float, p3: float, offset: float,
                                                angle: float, omega: float, alpha: float, rocker: bool,
                                                touch: str) -> None:
    # r'' <= 4 a2 + 9 a3 <= 17 and r >= 37, so r^2 + 2 r'^2 - r r'' > 0: every profile is convex
    path = ROCKER if rocker else KNIFE
    swaps = {"angle = 30": f"angle = {angle!r}", f"omega = {20 if rocker else 10}": f"omega = {omega!r}",
             "alpha = 0" if rocker else "alpha = 5": f"alpha = {alpha!r}"}
    if not rocker:
        swaps["line = { through = [0, 0], angle = 90 }"] = f"line = {{ through = [{offset!r}, 0], angle = 90 }}"
        if touch == "flat":  # a face through W, square to the guide turned by up to 15 deg, the cam below it
            swaps['knife = "W"'] = f"flat = {{ through = [0, 0], angle = {90.0 + offset!r} }}"
        elif touch == "roller":
            swaps['knife = "W"'] = 'roller = { center = "W", radius = 6 }'
            swaps["W = [0, 50]"] = "W = [0, 56]"
    data = kinepoly.to_json(kinepoly.solve(_with_points(path, _polar_profile(48, a2, p2, a3, p3), swaps)))
    assert data["check"]["max_rel_error"] < 1e-9
    assert _normal_residual(data, omega) < 1e-11


def test_without_a_guess_the_first_contact_is_taken_with_a_warning_naming_the_other() -> None:
    text = KNIFE.read_text().replace("[guess]\nW = [0, 50]\n", "")
    warnings = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text, "knife.toml")))["warnings"]
    assert any("no [guess] tells its contacts with the cam apart" in str(w) and "-30.3319" in str(w) for w in warnings)


@pytest.mark.parametrize(("path", "omega", "find"), [
    (KNIFE, 10.0, ('sliders = ["13"]', 'sliders = ["13"]\ninstant_centers = ["23"]')),
    (ROCKER, 20.0, ('alpha = ["3"]', 'alpha = ["3"]\ninstant_centers = ["23", "13"]'))])
def test_the_pairs_instant_center_is_on_the_common_normal_and_moves_with_both(path: Path, omega: float,
                                                                               find: tuple[str, str]) -> None:
    for degrees in (0, 75, 200, 310):
        data = kinepoly.to_json(kinepoly.solve(_with_points(path, None, {"angle = 30": f"angle = {degrees}",
                                                                          find[0]: find[1]})))
        center = complex(*data["instant_centers"]["23"]["position"])
        contact = data["contacts"]["23"]
        q, n = complex(*contact["point"]), complex(*contact["normal"])
        assert abs(((center - q) * n.conjugate()).imag) < 1e-9 * abs(center - q)  # on the common normal
        w = data["points"]["W"]
        omega3 = data.get("links", {}).get("3", {}).get("omega", 0.0)
        on_follower = complex(*w["velocity"]) + omega3 * 1j * (center - complex(*w["position"]))
        assert abs(on_follower - omega * 1j * center) < 1e-9 * abs(omega * center)  # one velocity on both links


FLOATING = """title = "a follower held by two links, not one joint"
[links]
1 = { points = { O = [0, 0], B = [90, 30], D = [90, -30] } }
2 = { points = { O = [0, 0] } }
3 = { points = { A = [0, 0], C = [0, -40], W = [-40, 0] } }
4 = { points = { B = [0, 0], A = [0, 20] } }
5 = { points = { D = [0, 0], C = [0, 20] } }
[[cams]]
cam = "2"
follower = "3"
knife = "W"
profile = { points = [[40, 0], [0, 40], [-40, 0], [0, -40]] }
[input]
link = "2"
angle = 30
omega = 1
"""


@pytest.mark.parametrize(("replace", "message"), [
    ({"angle = 30": "angle = 30\nrelative_to = \"1\"", 'link = "2"': 'link = "4"'},
     r"floating\.toml:8: cams\.23: the cam 2 is not known before its follower 3 \(the follower drives the cam\)"),
])
def test_what_is_not_built_for_a_floating_follower_is_refused_by_name_with_exit_2(
        tmp_path: Path, replace: dict[str, str], message: str) -> None:
    from kinepoly.cli import main

    text = FLOATING
    for old, new in replace.items():
        text = text.replace(old, new)
    scene = tmp_path / "floating.toml"
    scene.write_text(text)
    with pytest.raises(kinepoly.SceneError, match=message):
        kinepoly.solve(kinepoly.load_scene(scene))
    assert main(["solve", str(scene)]) == 2


FLAT = EXAMPLES / "eccentric-cam-flat.toml"
FLAT_CIRCLE = "profile = { circle = { center = [12, 0], radius = 35 } }"


def _flat_follower(n: int) -> kinepoly.Scene:
    """The eccentric-cam-flat example with its disc (centre [12, 0], radius 35) as a spline through n points."""
    points = [[12.0 + 35.0 * math.cos(2 * math.pi * k / n), 35.0 * math.sin(2 * math.pi * k / n)] for k in range(n)]
    text = FLAT.read_text()
    assert FLAT_CIRCLE in text
    return kinepoly.loads_scene(text.replace(FLAT_CIRCLE, f"profile = {{ points = {points!r} }}"), "flat.toml")


def test_a_flat_faced_translating_follower_on_a_spline_is_simple_harmonic_to_the_splines_accuracy() -> None:
    # y_T = e sin(theta) + R, v = e omega cos(theta), a = -e omega^2 sin(theta) (e = 12, R = 35, omega = 15)
    errors = []
    for n in (36, 72):
        result = sweep(_flat_follower(n), steps=120)
        assert (result.status == 0).all()
        theta = np.radians(result.input.values)
        errors.append([float(np.max(np.abs(result.column("r_T_y").values - (12.0 * np.sin(theta) + 35.0)))),
                       float(np.max(np.abs(result.column("v_T_y").values - 180.0 * np.cos(theta)))),
                       float(np.max(np.abs(result.column("a_T_y").values + 2700.0 * np.sin(theta))))])
    # measured: 36 points 8.5e-5 mm, 0.022 mm/s, 20 mm/s^2 (of 2700); 72 points 17, 8 and 4 times less
    assert errors[0] < [1.3e-4, 0.035, 30.0]
    for k, order in enumerate((4, 3, 2)):
        assert math.log2(errors[0][k] / errors[1][k]) == pytest.approx(order, abs=0.4)


FLAT_ROCKER = EXAMPLES / "spline-cam-flat-rocker.toml"


def _flat_rocker_exact(theta: float) -> tuple[float, float, float]:
    """The face (through Q, the cam on its left) tangent to the disc of centre K = 15 e^(i theta), radius 40:
    its direction phi has 40 = Im(e^(-i phi) (K - Q)), so phi = beta - asin(40 / rho); theta3 = phi - pi."""
    with mp.workdps(30):
        def phi(t: mp.mpf) -> mp.mpf:
            k = 15 * mp.expj(t) - mp.mpc(60, 60)
            return mp.arg(k) - mp.asin(40 / abs(k))

        first, second = mp.diff(phi, theta, 1), mp.diff(phi, theta, 2)
        return float(phi(theta) - mp.pi), float(10 * first), float(100 * second + 5 * first)


def test_a_flat_faced_rocker_on_a_spline_agrees_with_the_exact_tangent() -> None:
    for degrees in (0, 30, 100, 220, 300):
        data = kinepoly.to_json(kinepoly.solve(_with_points(FLAT_ROCKER, _circle(72),
                                                            {"angle = 30": f"angle = {degrees}"})))
        angle, omega, alpha = _flat_rocker_exact(math.radians(degrees))
        link = data["links"]["3"]
        assert math.remainder(math.radians(link["angle"]) - angle, 2 * math.pi) == pytest.approx(0.0, abs=1e-6)
        assert link["omega"] == pytest.approx(omega, abs=2e-5 * 10)
        assert link["alpha"] == pytest.approx(alpha, abs=5e-3 * 100)
        assert data["check"]["max_rel_error"] < 1e-12
        assert _normal_residual(data, 10.0, "S") < 1e-12


def test_a_flat_face_on_a_concave_stretch_exits_3_with_the_radius() -> None:
    # at theta = 30 deg the bean's hollow is on top: the face rests on the two lobes, but a guess at the
    # hollow's bottom picks the contact there, where a face cannot touch
    text = FLAT.read_text().replace(FLAT_CIRCLE, f"profile = {{ points = {_bean(90)!r} }}").replace(
        "angle = 40", "angle = 30")
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text, "flat.toml")))
    assert data["contacts"]["23"]["normal"] == pytest.approx([0.0, 1.0], abs=1e-9)
    assert data["points"]["T"]["position"][1] == pytest.approx(34.646, abs=1e-3)  # above the hollow (32)
    text = text.replace("T = [0, 43]", "T = [0, 32]")
    with pytest.raises(AssemblyError, match=r"cams\.23: at theta12 = 30 deg, the flat face meets the profile where "
                       r"it is concave \(radius 2\d\.\d+ mm\)"):
        kinepoly.solve(kinepoly.loads_scene(text, "flat.toml"))


def test_each_row_records_the_contact_parameter_point_and_centre_of_curvature() -> None:
    from kinepoly.engine.assembly import position_at_input
    from kinepoly.engine.plan import make_plan
    from kinepoly.geom.spline import periodic_spline
    from kinepoly.model.mechanism import build_mechanism

    mechanism = build_mechanism(kinepoly.load_scene(ROCKER))
    positions = position_at_input(mechanism, make_plan(mechanism))
    u = float(positions.contact_parameters["23"][0])
    cam = mechanism.scene.cams[0]
    frame = periodic_spline(cam.profile_points).frame(np.array([u]))
    theta = math.radians(30.0)
    turned = complex(math.cos(theta), math.sin(theta))
    q, k = complex(positions.marks["Q23"][0]), complex(positions.marks["K23"][0])
    assert q == pytest.approx(turned * complex(frame.point[0]), abs=1e-12)
    assert k == pytest.approx(turned * complex(frame.centre_of_curvature[0]), abs=1e-12)
    assert abs(k - q) == pytest.approx(40.0, rel=1e-2)  # the circle's radius, to the spline's curvature error
    w = complex(positions.point("W")[0])
    assert abs(w - q) == pytest.approx(10.0, rel=1e-12)  # the roller's centre, r from the contact on the normal
    assert abs(((w - q) / (k - q)).imag) < 1e-9
