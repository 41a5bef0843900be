"""A cam whose follower is itself a profile of points (two splines in contact, examples/spline-on-spline.toml).

The construction replaces the pair by the link joining both centres of curvature; here the follower's motion is
checked against a contact solve written in this file (Newton on the cam's parameter u, the follower's v and the
rocker's angle phi: the points coincide and the tangents are parallel), differentiated by central differences
over the input; against the exact case of two circles given as dense point sets (the four-bar of R1 + R2, as the
circle follower_profile solves it); on random ovals; and bad input is named by its key.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from tests.cli_support import run

import kinepoly
from kinepoly.engine.cam_curves import CurveContactRows, degenerate_rows
from kinepoly.errors import SceneError
from kinepoly.geom.spline import PeriodicSpline, periodic_spline
from kinepoly.homework.toml_out import scene_toml
from kinepoly.sweep import sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
EXAMPLE = EXAMPLES / "spline-on-spline.toml"
TEXT = EXAMPLE.read_text(encoding="utf-8")
CIRCLES = (EXAMPLES / "curve-on-curve.toml").read_text(encoding="utf-8")
PIVOT = complex(70.0, 45.0)


def _oval(a: float, b: float, cx: float, count: int) -> list[tuple[float, float]]:
    return [(cx + a * math.cos(2 * math.pi * j / count), b * math.sin(2 * math.pi * j / count)) for j in range(count)]


def _toml_points(points: list[tuple[float, float]]) -> str:
    return "[" + ", ".join(f"[{x!r}, {y!r}]" for x, y in points) + "]"


def _scene_text(cam: list[tuple[float, float]], bulb: list[tuple[float, float]], theta: float = 30.0) -> str:
    start, end = TEXT.index("profile = { points"), TEXT.index("[input]")
    pair = f"profile = {{ points = {_toml_points(cam)} }}\nfollower_profile = {{ points = {_toml_points(bulb)} }}\n\n"
    return (TEXT[:start] + pair + TEXT[end:]).replace("angle = 30", f"angle = {theta!r}")


def _read(points: list[tuple[float, float]]) -> PeriodicSpline:
    return periodic_spline(points)


def _rocker(phi: float) -> tuple[complex, complex]:
    """The rocker's frame turned by phi about PIVOT (its frame's origin): (origin, rotation)."""
    return PIVOT, complex(math.cos(phi), math.sin(phi))


def _contact(cam: PeriodicSpline, bulb: PeriodicSpline, theta: float, start: tuple[float, float, float],
             place: Callable[[float], tuple[complex, complex]] = _rocker) -> tuple[float, float, float]:
    """(u, v, q): the cam turned by theta about O, the follower placed by ``place(q)`` (its origin and rotation),
    the two curves touching: P1(u) = P2(v) and T1(u) x T2(v) = 0, by Newton with a finite-difference Jacobian."""
    turn = complex(math.cos(theta), math.sin(theta))

    def residual(x: np.ndarray) -> np.ndarray:
        u, v, q = x
        p1, d1, _ = (complex(z[0]) for z in cam.derivatives(np.array([u])))
        p2, d2, _ = (complex(z[0]) for z in bulb.derivatives(np.array([v])))
        origin, rocker = place(q)
        gap = turn * p1 - (origin + rocker * p2)
        return np.array([gap.real, gap.imag, ((turn * d1).conjugate() * rocker * d2).imag / (abs(d1) * abs(d2))])

    x = np.array(start, dtype=float)
    for _ in range(60):
        f = residual(x)
        jac = np.empty((3, 3))
        for k in range(3):
            e = np.zeros(3)
            e[k] = 1e-7
            jac[:, k] = (residual(x + e) - residual(x - e)) / 2e-7
        step = np.linalg.solve(jac, -f)
        x = x + step
        if np.abs(step).max() < 1e-15:
            break
    assert np.abs(residual(x)).max() < 1e-11
    return float(x[0]), float(x[1]), float(x[2])


def _start(cam: PeriodicSpline, bulb: PeriodicSpline, theta: float, phi: float) -> tuple[float, float, float]:
    """Where to start the contact solve: the rocker at phi, the nearest pair of samples of both curves."""
    grid_u = cam.period * np.arange(400) / 400
    grid_v = bulb.period * np.arange(400) / 400
    one = np.exp(1j * theta) * cam.point(grid_u)
    two = PIVOT + np.exp(1j * phi) * bulb.point(grid_v)
    i, k = np.unravel_index(int(np.argmin(np.abs(one[:, None] - two[None, :]))), (400, 400))
    return float(grid_u[i]), float(grid_v[k]), phi


def _differences(cam: PeriodicSpline, bulb: PeriodicSpline, theta: float, phi: float, omega2: float,
                 alpha2: float, h: float = 1e-4) -> tuple[float, float, float]:
    """phi, omega3 and alpha3 from differences (5 points) of the contact solve's phi over theta: central, or, where
    the contact crosses a knot of either spline within them (a cubic spline's third derivative jumps there, so a
    second difference across it is in error by about h times the jump), one-sided from theta away from the knot."""
    x = _contact(cam, bulb, theta, _start(cam, bulb, theta, phi))
    solved = {k: _contact(cam, bulb, theta + k * h, x) for k in (-2, -1, 0, 1, 2)}
    if _one_piece(cam, bulb, [solved[k] for k in (-2, -1, 0, 1, 2)]):
        f = np.unwrap(np.array([solved[k][2] for k in (-2, -1, 0, 1, 2)]))
        first = (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * h)
        second = (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * h * h)
        return x[2], omega2 * first, omega2 * omega2 * second + alpha2 * first
    for side in (1, -1):
        solved.update({side * k: _contact(cam, bulb, theta + side * k * h, x) for k in (3, 4)})
        if _one_piece(cam, bulb, [solved[side * k] for k in range(5)]):
            break
    f = np.unwrap(np.array([solved[side * k][2] for k in range(5)]))
    first = side * (-25 * f[0] + 48 * f[1] - 36 * f[2] + 16 * f[3] - 3 * f[4]) / (12 * h)
    second = (35 * f[0] - 104 * f[1] + 114 * f[2] - 56 * f[3] + 11 * f[4]) / (12 * h * h)
    return x[2], omega2 * first, omega2 * omega2 * second + alpha2 * first


def _one_piece(cam: PeriodicSpline, bulb: PeriodicSpline, contacts: list[tuple[float, float, float]]) -> bool:
    """Whether the contacts (u, v, phi) lie on one piece of each spline (no knot between them)."""
    def pieces(spline: PeriodicSpline, at: list[float]) -> set[int]:
        return set(np.searchsorted(spline.knots, np.mod(at, spline.period), side="right").tolist())

    return len(pieces(cam, [c[0] for c in contacts])) == 1 and len(pieces(bulb, [c[1] for c in contacts])) == 1


def _solved(text: str) -> dict[str, float]:
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text, "sos.toml")))
    link = data["links"]["3"]
    return {"angle": math.radians(link["angle"]), "omega": link["omega"], "alpha": link["alpha"],
            "check": data["check"]["max_rel_error"]}


def test_the_example_against_finite_differences_of_its_own_contact_solve() -> None:
    scene = kinepoly.load_scene(EXAMPLE)
    cam = _read(list(scene.cams[0].profile_points))
    bulb = _read(list(scene.cams[0].follower_points))
    found = _solved(TEXT)
    phi, omega, alpha = _differences(cam, bulb, math.radians(30.0), found["angle"], 10.0, 5.0)
    assert found["check"] < 1e-12
    assert math.remainder(found["angle"] - phi, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    assert found["omega"] == pytest.approx(omega, rel=1e-8)
    assert found["alpha"] == pytest.approx(alpha, rel=2e-6)


def test_a_sweep_follows_the_contact_solve_over_a_turn() -> None:
    scene = kinepoly.load_scene(EXAMPLE)
    cam = _read(list(scene.cams[0].profile_points))
    bulb = _read(list(scene.cams[0].follower_points))
    result = sweep(scene, steps=12)
    assert (result.status == 0).all()
    assert result.input.values[-1] - result.input.values[0] > 300.0  # a full turn of the cam
    for row, value in enumerate(result.input.values[::3]):
        at = 3 * row
        theta3 = math.radians(result.column("theta_3").values[at])
        phi, omega, alpha = _differences(cam, bulb, math.radians(value), theta3, 10.0, 5.0)
        assert math.remainder(theta3 - phi, 2 * math.pi) == pytest.approx(0.0, abs=1e-10)
        assert result.column("omega_3").values[at] == pytest.approx(omega, rel=1e-7, abs=1e-9)
        assert result.column("alpha_3").values[at] == pytest.approx(alpha, rel=1e-5, abs=1e-6)


def _circles_as_points(count: int) -> str:
    """The curve-on-curve example (a disc R = 30 about [12, 0] on an arc r = 20 about C) with both circles
    given as ``count`` points each."""
    disc = _oval(30.0, 30.0, 12.0, count)
    arc = [(-50.0 + 20.0 * math.cos(2 * math.pi * j / count), 20.0 * math.sin(2 * math.pi * j / count))
           for j in range(count)]
    text = CIRCLES.replace("profile = { circle = { center = [12, 0], radius = 30 } }\n"
                           'follower_profile = { circle = { center = "C", radius = 20 } }',
                           f"profile = {{ points = {_toml_points(disc)} }}\n"
                           f"follower_profile = {{ points = {_toml_points(arc)} }}")
    assert text != CIRCLES
    return text


def test_two_circles_as_points_are_the_four_bar_of_r1_plus_r2_to_the_splines_accuracy() -> None:
    # the circle follower_profile solves the four-bar O K C P (12, 50, 50, 83.2) exactly (test_curve_on_curve);
    # given by points, both circles are splines: the error falls with the points (measured: 36 points 1.7e-4 in
    # omega and 2.8e-3 in alpha, 144 points 8.2e-7 and 2.9e-4)
    exact = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(CIRCLES)))["links"]["3"]
    errors = {}
    for count in (36, 144):
        found = _solved(_circles_as_points(count))
        assert found["check"] < 1e-12
        assert math.degrees(found["angle"]) == pytest.approx(exact["angle"], abs=1e-3)
        errors[count] = [abs(found[key] / exact[key] - 1.0) for key in ("omega", "alpha")]
    assert errors[144][0] < 1e-5 and errors[144][1] < 2e-3
    assert errors[144][0] < errors[36][0] / 20.0 and errors[144][1] < errors[36][1] / 4.0


# the ovals always reach each other: the bulb comes within 83.2 - 50 - 9.5 = 23.7 of O, inside the cam's smallest
# radius (26 - 8 offset along the way at worst still beyond it: the cam's profile never leaves the bulb's reach)
@settings(max_examples=6, deadline=None)
@given(a=st.floats(33.0, 37.0), b=st.floats(26.0, 30.0), bulb_a=st.floats(9.5, 12.0), bulb_b=st.floats(6.0, 8.0),
       theta=st.floats(0.0, 359.0))
@example(a=35.0, b=27.0, bulb_a=11.0, bulb_b=7.0, theta=224.0)
@example(a=33.0, b=26.0, bulb_a=10.75, bulb_b=6.25, theta=33.75)  # a knot of the cam within the central differences
def test_random_ovals_against_their_contact_solve(a: float, b: float, bulb_a: float, bulb_b: float,
                                                  theta: float) -> None:
    # the differences' step: the contact solve's rounding, divided by h squared, is the second difference's error
    # (at the example, h = 1e-4 gives 5e-5 of alpha, more than the tolerance; 2e-3 gives 1e-7, while its
    # truncation, 1e-6 at h = 1e-2, stays small)
    cam_points = _oval(a, b, 8.0, 16)
    bulb_points = [(x - 50.0, y) for x, y in _oval(bulb_a, bulb_b, 0.0, 12)]
    found = _solved(_scene_text(cam_points, bulb_points, theta))
    phi, omega, alpha = _differences(_read(cam_points), _read(bulb_points), math.radians(theta), found["angle"],
                                     10.0, 5.0, h=2e-3)
    assert found["check"] < 1e-11
    assert math.remainder(found["angle"] - phi, 2 * math.pi) == pytest.approx(0.0, abs=1e-10)
    assert found["omega"] == pytest.approx(omega, rel=1e-7, abs=1e-9)
    assert found["alpha"] == pytest.approx(alpha, rel=1e-5, abs=1e-6)


def test_the_solve_marks_both_centres_of_curvature_on_the_common_normal() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLE))
    marks = solution.pose.marks
    k1, k2, q = (complex(*marks[name]) for name in ("K23", "K223", "Q23"))
    scene = solution.scene
    bulb = _read(list(scene.cams[0].follower_points))
    # K1, Q and K2 on one line (the common normal), Q between them (both profiles convex at the contact)
    assert abs(((q - k1).conjugate() * (k2 - q)).imag) < 1e-9 * abs(k2 - k1) ** 2
    assert ((q - k1).conjugate() * (k2 - q)).real > 0.0
    # K2 is the bulb's centre of curvature: |K2 - Q| = 1 / kappa2 at the contact's v
    rocker = solution.pose.links["3"]
    local = (q - complex(rocker.x, rocker.y)) * complex(math.cos(rocker.theta), -math.sin(rocker.theta))
    grid = bulb.period * np.arange(4000) / 4000
    v = float(grid[int(np.argmin(np.abs(bulb.point(grid) - local)))])
    assert abs(k2 - q) == pytest.approx(1.0 / float(bulb.frame(np.array([v])).curvature[0]), rel=1e-3)


def test_conforming_or_straight_contacts_are_refused_with_the_reason() -> None:
    cam = kinepoly.load_scene(EXAMPLE).cams[0]

    def rows(k1: float, k2: float) -> CurveContactRows:
        return CurveContactRows(np.zeros(1, np.complex128), np.array([k2]), np.array([k1]))

    assert not degenerate_rows(cam, rows(0.05, 0.1))[0].any()
    bad, why = degenerate_rows(cam, rows(-0.1, 0.1))
    assert bad.all() and "conform" in why and "1/rho1 + 1/rho2" in why
    bad, why = degenerate_rows(cam, rows(-0.2, 0.1))
    assert bad.all() and "cut into each other" in why
    bad, why = degenerate_rows(cam, rows(0.1, 0.0))
    assert bad.all() and "infinity" in why


_BULB = TEXT[TEXT.index("follower_profile = { points"):TEXT.index("\n\n[input]")]


@pytest.mark.parametrize(("new", "message"), [
    ("follower_profile = { points = [[-40, 0], [-50, 7], [-60, 0]] }",
     r"cams\.1\.follower_profile\.points: expected at least 4 points"),
    ("follower_profile = { points = [[-40, 0], [-50, -7], [-60, 0], [-50, 7]] }",
     r"cams\.1\.follower_profile\.points: the points run clockwise"),
    ("follower_profile = { points = [[-40, 0], [-50, 7], [-60, 0], [-50, -7], [-40, 0]] }",
     r"cams\.1\.follower_profile\.points\.5: the last point repeats the first"),
    ('follower_profile = { points = [[-40, 0], [-50, 7], [-60, 0], [-50, -7]], circle = { center = "C", radius = 5 } }',
     r"cams\.1\.follower_profile: a follower profile is a circle or points"),
    ("follower_profile = { points = [[-40, 0], [-50, 7], [-60, 0], [-50, -7]] }\ncontact = \"inside\"",
     r"cams\.1\.contact: two profiles of points touch from outside only"),
    ("follower_profile = { points = [[-40, 0], [-50, 7], [-60, 0], [-50, -7]], width = 2 }",
     r"cams\.1\.follower_profile\.width: unknown key"),
])
def test_bad_follower_points_are_named_by_their_key(new: str, message: str) -> None:
    with pytest.raises(SceneError, match=message):
        kinepoly.loads_scene(TEXT.replace(_BULB, new), "sos.toml")


def test_follower_points_on_a_circle_cam_are_refused() -> None:
    text = CIRCLES.replace('follower_profile = { circle = { center = "C", radius = 20 } }',
                           "follower_profile = { points = [[-40, 0], [-50, 7], [-60, 0], [-50, -7]] }")
    with pytest.raises(SceneError, match=r"cams\.1\.follower_profile\.points: a follower profile of points touches "
                                         r"a cam profile of points"):
        kinepoly.loads_scene(text, "cam.toml")


def test_bad_follower_points_exit_2_and_an_unreachable_bulb_exits_3(tmp_path: Path,
                                                                    capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text(TEXT.replace(_BULB, "follower_profile = { points = [[0, 0], [1, 0]] }"), encoding="utf-8")
    code, out, err = run(capsys, "solve", str(bad))
    assert code == 2 and out == "" and "bad.toml" in err and "follower_profile.points" in err
    assert "Traceback" not in err
    far = tmp_path / "far.toml"
    far.write_text(TEXT.replace("P = [70, 45]", "P = [170, 45]"), encoding="utf-8")
    code, out, err = run(capsys, "solve", str(far))
    assert code == 3 and out == "" and "far.toml" in err
    assert "its profile cannot be laid against the cam's profile" in err and "Traceback" not in err


def test_the_follower_points_are_written_back_as_read() -> None:
    scene = kinepoly.load_scene(EXAMPLE)
    again = kinepoly.loads_scene(scene_toml(scene))
    assert again.cams[0].follower_points == scene.cams[0].follower_points
    assert again.cams[0].profile_points == scene.cams[0].profile_points


SLIDE = """title = "Oval cam on a translating follower with a round end given by points"
[links]
1 = { points = { O = [0, 0], G = [0, 60] } }
2 = { points = { O = [0, 0] } }
3 = { points = { B = [0, 0] } }
[[sliders]]
guide = "1"
block = "3"
point = "B"
line = { through = [5, 0], angle = 90 }
[[cams]]
cam = "2"
follower = "3"
profile = { points = CAM }
follower_profile = { points = BULB }
[input]
link = "2"
angle = 30
omega = 10
alpha = 5
[guess]
B = [5, 45]
"""


def test_a_translating_follower_against_finite_differences_of_its_contact_solve() -> None:
    cam_points, bulb_points = _oval(34.0, 28.0, 8.0, 16), _oval(10.0, 7.0, 0.0, 12)
    text = SLIDE.replace("CAM", _toml_points(cam_points)).replace("BULB", _toml_points(bulb_points))
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text, "slide.toml")))
    assert data["check"]["max_rel_error"] < 1e-12
    y, (vx, vy), (ax, ay) = (data["points"]["B"]["position"][1], data["points"]["B"]["velocity"],
                             data["points"]["B"]["acceleration"])
    cam, bulb = _read(cam_points), _read(bulb_points)

    def slid(s: float) -> tuple[complex, complex]:  # the block's frame turned with its slide, 90 degrees
        return complex(5.0, s), 1j

    theta, h = math.radians(30.0), 1e-4
    grid_u, grid_v = cam.period * np.arange(400) / 400, bulb.period * np.arange(400) / 400
    one = np.exp(1j * theta) * cam.point(grid_u)
    two = complex(5.0, y) + 1j * bulb.point(grid_v)
    i, k = np.unravel_index(int(np.argmin(np.abs(one[:, None] - two[None, :]))), (400, 400))
    x = _contact(cam, bulb, theta, (float(grid_u[i]), float(grid_v[k]), y), slid)
    f = [_contact(cam, bulb, theta + j * h, x, slid)[2] for j in (-2, -1, 0, 1, 2)]
    first = (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * h)
    second = (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * h * h)
    assert y == pytest.approx(x[2], abs=1e-10)
    assert vx == pytest.approx(0.0, abs=1e-12) and ax == pytest.approx(0.0, abs=1e-10)
    assert vy == pytest.approx(10.0 * first, rel=1e-8)
    assert ay == pytest.approx(100.0 * second + 5.0 * first, rel=2e-6)
