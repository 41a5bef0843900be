"""A follower touching the cam by a circle of its own (``follower_profile``): two circles in contact.

The exact case of two curves in contact: each circle's centre of curvature is its centre, fixed on its
link, so the pair is, at every position, the link joining both centres, of length R1 + R2 (R1 - R2 with
the follower's circle inside the cam's). The disc cam on a rocker is then the four-bar O K C P, solved
here by its own closed form (circle intersection, then the two loop equations differentiated).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from tests.cli_support import run

import kinepoly
from kinepoly.errors import SceneError
from kinepoly.homework.toml_out import scene_toml
from kinepoly.sweep import sweep

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "curve-on-curve.toml"
TEXT = EXAMPLE.read_text(encoding="utf-8")


def _dot(x: complex, y: complex) -> float:
    return (x * y.conjugate()).real


def _four_bar(k: complex, v_k: complex, a_k: complex, p: complex, c: complex) -> tuple[float, float]:
    """omega and alpha of the rocker P C driven through the coupler K C of fixed length (K's motion given):
    (v_C - v_K).(C - K) = 0 and its derivative, with v_C = omega i (C - P)."""
    u = c - k
    omega = _dot(v_k, u) / _dot(1j * (c - p), u)
    v_c = omega * 1j * (c - p)
    alpha = (_dot(a_k, u) + omega * omega * _dot(c - p, u) - abs(v_c - v_k) ** 2) / _dot(1j * (c - p), u)
    return omega, alpha


def _crossing(k: complex, p: complex, coupler: float, rocker: float, sign: float) -> complex:
    """C at ``coupler`` from K and ``rocker`` from P, on the ``sign`` side of K P."""
    d = abs(p - k)
    a = (coupler**2 - rocker**2 + d * d) / (2 * d)
    h = math.sqrt(coupler**2 - a * a)
    unit = (p - k) / d
    return k + a * unit + sign * h * 1j * unit


def test_the_example_against_its_four_bar_over_a_turn() -> None:
    # the disc: centre K 12 from O, R = 30; the arc: r = 20 about C, 50 from the pivot P = (70, 45)
    result = sweep(kinepoly.load_scene(EXAMPLE), steps=120)
    theta = np.radians(result.input.values)
    assert (result.status == 0).all()
    cx, cy = result.column("r_C_x").values, result.column("r_C_y").values
    omega, alpha = result.column("omega_3").values, result.column("alpha_3").values
    p, w2, a2 = complex(70.0, 45.0), 10.0, 5.0
    k0 = 12.0 * complex(math.cos(theta[0]), math.sin(theta[0]))
    sign = min((1.0, -1.0), key=lambda s: abs(_crossing(k0, p, 50.0, 50.0, s) - complex(cx[0], cy[0])))
    for row, t in enumerate(theta):
        k = 12.0 * complex(math.cos(t), math.sin(t))
        c = _crossing(k, p, 50.0, 50.0, sign)
        w3, a3 = _four_bar(k, w2 * 1j * k, (a2 * 1j - w2 * w2) * k, p, c)
        assert abs(complex(cx[row], cy[row]) - c) < 1e-10 * 100.0
        assert omega[row] == pytest.approx(w3, rel=1e-10, abs=1e-10 * w2)
        assert alpha[row] == pytest.approx(a3, rel=1e-10, abs=1e-10 * w2 * w2)


def test_the_solve_names_the_contact_on_both_circles() -> None:
    sol = kinepoly.solve(kinepoly.load_scene(EXAMPLE))
    data = kinepoly.to_json(sol)
    k = 12.0 * complex(math.cos(math.radians(30.0)), math.sin(math.radians(30.0)))
    c = complex(*data["points"]["C"]["position"])
    assert abs(c - k) == pytest.approx(50.0, rel=1e-14)  # the permanent link K C, R1 + R2
    contact = data["contacts"]["23"]
    q, n = complex(*contact["point"]), complex(*contact["normal"])
    assert abs(q - k) == pytest.approx(30.0, rel=1e-14)
    assert abs(q - c) == pytest.approx(20.0, rel=1e-14)
    assert abs(n - (c - k) / 50.0) < 1e-14
    # no penetration: the cam's and the arc's points at Q move alike along the normal
    v_cam = 10.0 * 1j * q
    v_arc = data["links"]["3"]["omega"] * 1j * (q - complex(70.0, 45.0))
    assert abs(_dot(v_cam - v_arc, n)) < 1e-12 * abs(v_cam)
    # the sliding velocity is what is left, along the tangent
    assert complex(*contact["sliding_velocity"]) == pytest.approx(v_arc - v_cam, rel=1e-12, abs=1e-12)
    w3, a3 = _four_bar(k, 10.0 * 1j * k, (5.0j - 100.0) * k, complex(70.0, 45.0), c)
    assert data["links"]["3"]["omega"] == pytest.approx(w3, rel=1e-13)
    assert data["links"]["3"]["alpha"] == pytest.approx(a3, rel=1e-13)
    assert data["check"]["max_rel_error"] < 1e-12
    assert sol.scene.cams[0].follower_profile and sol.scene.cams[0].equivalent == "4"


@settings(max_examples=40, deadline=None)
@given(e=st.floats(5.0, 30.0), big=st.floats(20.0, 60.0), small=st.floats(5.0, 40.0),
       theta=st.floats(0.0, 2 * math.pi), turn=st.floats(0.3, 2.8), rocker=st.floats(30.0, 90.0),
       inside=st.booleans(), w2=st.floats(-20.0, 20.0), a2=st.floats(-50.0, 50.0))
def test_random_circle_pairs_are_their_four_bar(e: float, big: float, small: float, theta: float, turn: float,
                                                rocker: float, inside: bool, w2: float, a2: float) -> None:
    # the scene is built at an assembled position: C at R +- r from K, the pivot P at `rocker` from C
    assume(not inside or small < big - 2.0)
    coupler = big - small if inside else big + small
    k = e * complex(math.cos(theta), math.sin(theta))
    c = k + coupler * complex(math.cos(theta + 0.7), math.sin(theta + 0.7))
    p = c + rocker * complex(math.cos(theta + 0.7 + turn), math.sin(theta + 0.7 + turn))
    assume(abs(p) > e + 1.0)
    u = c - k
    assume(abs(_dot(1j * (c - p), u)) > 0.2 * abs(c - p) * abs(u))  # away from the dead points
    scene = f"""
[links]
1 = {{ points = {{ O = [0, 0], P = [{p.real!r}, {p.imag!r}] }} }}
2 = {{ points = {{ O = [0, 0] }} }}
3 = {{ points = {{ P = [0, 0], C = [{rocker!r}, 0] }} }}

[[cams]]
cam = "2"
follower = "3"
profile = {{ circle = {{ center = [{e!r}, 0], radius = {big!r} }} }}
follower_profile = {{ circle = {{ center = "C", radius = {small!r} }} }}
contact = "{"inside" if inside else "outside"}"

[input]
link = "2"
angle = {math.degrees(theta)!r}
omega = {w2!r}
alpha = {a2!r}

[guess]
C = [{c.real!r}, {c.imag!r}]
"""
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(scene)))
    assert complex(*data["points"]["C"]["position"]) == pytest.approx(c, abs=1e-9 * (abs(p) + coupler))
    w3, a3 = _four_bar(k, w2 * 1j * k, (a2 * 1j - w2 * w2) * k, p, c)
    scale = max(abs(w2), 1.0) * e / rocker
    assert data["links"]["3"]["omega"] == pytest.approx(w3, rel=1e-9, abs=1e-9 * scale)
    assert data["links"]["3"]["alpha"] == pytest.approx(a3, rel=1e-9, abs=1e-9 * (scale * max(abs(w2), 1.0) + abs(a2)))
    q = complex(*data["contacts"]["23"]["point"])
    assert abs(q - k) == pytest.approx(big, rel=1e-12)
    assert abs(q - c) == pytest.approx(small, rel=1e-12)


def test_the_pressure_angle_is_taken_where_the_arc_is_pushed() -> None:
    # the force acts on the follower at the contact Q (the arc is fixed to it, no pin at C): the acute angle
    # between the common normal and Q's direction of motion about the pivot P, not C's as for a roller
    result = sweep(kinepoly.load_scene(EXAMPLE), steps=36)
    theta = np.radians(result.input.values)
    cx, cy = result.column("r_C_x").values, result.column("r_C_y").values
    pressure = result.column("pressure_angle_23")
    assert pressure.valid.all()
    p = complex(70.0, 45.0)
    worst_roller_gap = 0.0
    for row, t in enumerate(theta):
        k, c = 12.0 * complex(math.cos(t), math.sin(t)), complex(cx[row], cy[row])
        n = (c - k) / abs(c - k)
        q = k + 30.0 * n
        moving = 1j * (q - p) / abs(q - p)
        expected = math.degrees(math.acos(min(1.0, abs(_dot(n, moving)))))
        assert pressure.values[row] == pytest.approx(expected, abs=1e-9)
        at_c = math.degrees(math.acos(min(1.0, abs(_dot(n, 1j * (c - p) / abs(c - p))))))
        worst_roller_gap = max(worst_roller_gap, abs(expected - at_c))
    assert worst_roller_gap > 1.0  # the two readings differ here: the test tells them apart


def _on_spline_disc(count: int) -> dict[str, float]:
    """omega3, alpha3 and the check's error with the example's disc given as a spline through ``count`` of its
    points."""
    points = ", ".join(f"[{12 + 30 * math.cos(2 * math.pi * j / count)!r}, {30 * math.sin(2 * math.pi * j / count)!r}]"
                       for j in range(count))
    spline = TEXT.replace("profile = { circle = { center = [12, 0], radius = 30 } }",
                          f"profile = {{ points = [{points}] }}")
    assert spline != TEXT
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(spline)))
    return {"omega": data["links"]["3"]["omega"], "alpha": data["links"]["3"]["alpha"],
            "check": data["check"]["max_rel_error"]}


def test_a_spline_cam_drives_the_circle_of_the_follower_to_the_splines_accuracy() -> None:
    # the pair through the spline's centre of curvature and the arc's centre: it follows the circle-on-circle
    # four-bar to the spline's accuracy, which grows with the points (measured: 36 points 1.7e-4 in omega and
    # 2.8e-3 in alpha, 144 points 7.9e-7 and 2.9e-4)
    circle = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(TEXT)))["links"]["3"]
    errors = {}
    for count in (36, 144):
        found = _on_spline_disc(count)
        assert found["check"] < 1e-12
        errors[count] = [abs(found[key] / circle[key] - 1.0) for key in ("omega", "alpha")]
    assert errors[144][0] < 2e-6 and errors[144][1] < 5e-4
    assert errors[144][0] < errors[36][0] / 50.0 and errors[144][1] < errors[36][1] / 5.0


def test_the_follower_profile_is_written_back_as_read() -> None:
    scene = kinepoly.load_scene(EXAMPLE)
    text = scene_toml(scene)
    assert 'follower_profile = { circle = { center = "C", radius = 20 } }' in text
    assert "roller" not in text
    again = kinepoly.loads_scene(text)
    assert [(c.follower_profile, c.point, c.roller_radius) for c in again.cams] == [(True, "C", 20.0)]


@pytest.mark.parametrize(("old", "new", "message"), [
    ('follower_profile = { circle = { center = "C", radius = 20 } }',
     'follower_profile = { circle = { center = "C", radius = 20 } }\nroller = { center = "C", radius = 20 }',
     r"cams\.1: more than one follower: roller, follower_profile"),
    ('follower_profile = { circle = { center = "C", radius = 20 } }',
     "follower_profile = { points = [[0, 0], [1, 0], [1, 1], [0, 1]] }",
     r"cams\.1\.follower_profile\.points: a follower profile of points touches a cam profile of points"),
    ('center = "C", radius = 20', 'center = "D", radius = 20',
     r'cams\.1\.follower_profile\.circle\.center: no point "D" in link "3" \(the follower\)'),
    ('center = "C", radius = 20', 'center = "C", radius = -2',
     r"cams\.1\.follower_profile\.circle\.radius: -2 is not positive"),
    ('center = "C", radius = 20', 'center = "C", radius = 20, width = 3',
     r"cams\.1\.follower_profile\.circle\.width: unknown key"),
    ('follower_profile = { circle = { center = "C", radius = 20 } }', 'follower_profile = { center = "C" }',
     r"cams\.1\.follower_profile"),
    ('follower_profile = { circle = { center = "C", radius = 20 } }',
     'follower_profile = { circle = { center = "C", radius = 30 } }\ncontact = "inside"',
     r"cams\.1\.follower_profile\.circle\.radius: a circle of radius 30 inside a groove of radius 30"),
])
def test_bad_follower_profiles_are_named_by_their_key(old: str, new: str, message: str) -> None:
    assert old in TEXT
    with pytest.raises(SceneError, match=message):
        kinepoly.loads_scene(TEXT.replace(old, new), "cam.toml")


def test_a_bad_follower_profile_exits_2_without_a_traceback(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text(TEXT.replace('follower_profile = { circle = { center = "C", radius = 20 } }',
                                'follower_profile = { circle = { center = "C", radius = 20 } }\nknife = "C"'),
                   encoding="utf-8")
    code, out, err = run(capsys, "solve", str(bad))
    assert code == 2 and out == ""
    assert "bad.toml" in err and "more than one follower: knife, follower_profile" in err
    assert "Traceback" not in err


def test_an_arc_that_cannot_reach_a_spline_cam_is_named_as_the_arc(tmp_path: Path,
                                                                  capsys: pytest.CaptureFixture[str]) -> None:
    points = ", ".join(f"[{12 + 30 * math.cos(2 * math.pi * j / 36)!r}, {30 * math.sin(2 * math.pi * j / 36)!r}]"
                       for j in range(36))
    far = (TEXT.replace("profile = { circle = { center = [12, 0], radius = 30 } }",
                        f"profile = {{ points = [{points}] }}")
           .replace("P = [70, 45]", "P = [170, 45]"))
    scene = tmp_path / "far.toml"
    scene.write_text(far, encoding="utf-8")
    code, out, err = run(capsys, "solve", str(scene))
    assert code == 3 and out == ""
    assert "the centre C of the follower's arc cannot reach it" in err and "offset by the arc's radius" in err
    assert "roller" not in err and "Traceback" not in err
