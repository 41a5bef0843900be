"""Cylinders inside larger groups: the lifting platform of ``examples/platform-lift.toml``.

The platform 3 hangs from the frame on the arms 2 (A0 A) and 4 (B0 B), and the cylinder from C0 on the
frame to P on the platform sets its stroke s = |C0 P|. Everything here is derived on its own, in
mpmath at 40 digits, from the four-bar's closed form (B the crossing of the circles about A and about B0
on the platform's side of A B0), and shares nothing with kinepoly: the stroke at an arm angle theta2,
the arm angle at a stroke (a root of s(theta2) - s), the ends of the stroke (the roots of ds/dtheta2, where
the platform meets a dead point), and the rates by differentiating the closed form (d theta2 / dt =
s_dot / s'(theta2), d2 theta2 / dt2 = (s_ddot - s''(theta2) theta2_dot^2) / s'(theta2)).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import mpmath as mp  # type: ignore[import-untyped]
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.present.catalogue import load_catalogue
from kinepoly.present.phrasing import Context, step_sentence
from kinepoly.sweep import sweep

mp.mp.dps = 40

A0, B0, C0 = mp.mpc(0, 0), mp.mpc(400, 0), mp.mpc(350, -50)
ARM2, ARM4, AB = mp.mpf(250), mp.mpf(250), mp.mpf(300)
P_ON_PLATFORM = mp.mpc(100, 80)  # P in the platform's frame: A at its origin, B on its x-axis
S_DOT, S_DDOT = 50, -20

OWN_FRAMES = (EXAMPLES / "platform-lift.toml").read_text()
FRAME_COORDINATES = OWN_FRAMES.replace(
    "5 = { points = { C0 = [0, 0] } }", "5 = { points = { C0 = [350, -50] } }").replace(
    "6 = { points = { P = [0, 0] } }", "6 = { points = { P = [190.8773300227689, 316.9877053789638] } }").replace(
    "line = { through = [0, 0], angle = 0 }", "line = { through = [350, -50], angle = 113.44113455483786 }")
"""The same platform with the barrel and the rod written in frame coordinates at the scene's stroke."""


def _platform(theta2: mp.mpf) -> tuple[mp.mpc, mp.mpc, mp.mpc]:
    """A, B and P at the arm angle theta2 (the assembly with the platform above the line A B0)."""
    a = A0 + ARM2 * mp.expjpi(theta2 / mp.pi)
    d = B0 - a
    dist = abs(d)
    along = (AB**2 - ARM4**2 + dist**2) / (2 * dist)
    b = a + (along + 1j * mp.sqrt(AB**2 - along**2)) * d / dist
    return a, b, a + P_ON_PLATFORM * (b - a) / AB


def _stroke(theta2: mp.mpf) -> mp.mpf:
    return abs(_platform(theta2)[2] - C0)


def _dead_points() -> tuple[mp.mpf, mp.mpf]:
    """The arm angles where ds/dtheta2 = 0 on either side of the scene's position: from a scan, refined."""
    scan = np.radians(np.linspace(-60.0, 113.0, 347))
    strokes = np.array([float(_stroke(mp.mpf(t))) for t in scan])
    turns = np.flatnonzero(np.diff(np.sign(np.diff(strokes))))
    assert len(turns) == 2  # one least and one greatest stroke on this stretch
    return tuple(mp.findroot(lambda t: mp.diff(_stroke, t), mp.mpf(scan[k + 1])) for k in turns)


LOW, HIGH = _dead_points()


def _arm_at(stroke: float) -> mp.mpf:
    """theta2 at the stroke, between the dead points (s grows with theta2 there)."""
    return mp.findroot(lambda t: _stroke(t) - stroke, (LOW + mp.mpf("1e-6"), HIGH - mp.mpf("1e-6")),
                       solver="anderson")


def _motion(stroke: float, point: Callable[[mp.mpf], mp.mpc]) -> tuple[complex, complex, complex]:
    """The point's position, velocity and acceleration at the stroke, s_dot = 50, s_ddot = -20."""
    t = _arm_at(stroke)
    s1, s2 = mp.diff(_stroke, t, 1), mp.diff(_stroke, t, 2)
    w = S_DOT / s1
    alpha = (S_DDOT - s2 * w * w) / s1
    x1, x2 = mp.diff(point, t, 1), mp.diff(point, t, 2)
    return complex(point(t)), complex(x1 * w), complex(x2 * w * w + x1 * alpha)


POINTS: dict[str, Callable[[mp.mpf], mp.mpc]] = {
    "A": lambda t: _platform(t)[0], "B": lambda t: _platform(t)[1], "P": lambda t: _platform(t)[2]}


def _scene(text: str, stroke: float) -> kinepoly.Scene:
    theta = _arm_at(stroke)
    a, b, p = (complex(z) for z in _platform(theta))
    guess = f"A = [{a.real:.0f}, {a.imag:.0f}]\nB = [{b.real:.0f}, {b.imag:.0f}]\nP = [{p.real:.0f}, {p.imag:.0f}]"
    text = text.replace("s = 400", f"s = {stroke!r}")
    start, end = text.index("\n[guess]") + 1, text.index("\n[find]") + 1
    return kinepoly.loads_scene(text[:start] + "[guess]\n" + guess + "\n\n" + text[end:])


def test_the_stroke_range_is_where_the_platform_meets_its_dead_points() -> None:
    assert float(_stroke(LOW)) == pytest.approx(194.293652, abs=1e-6)  # the figures the example's comment gives
    assert float(_stroke(HIGH)) == pytest.approx(462.553059, abs=1e-6)
    for text in (OWN_FRAMES, FRAME_COORDINATES):
        result = sweep(kinepoly.loads_scene(text), steps=40)
        values = result.input.values
        assert (result.status[1:-1] == 0).all()
        assert float(values[0]) == pytest.approx(float(_stroke(LOW)), abs=1e-4)  # 1e-7 of the size inside
        assert float(values[-1]) == pytest.approx(float(_stroke(HIGH)), abs=1e-4)


@pytest.mark.parametrize("text", [OWN_FRAMES, FRAME_COORDINATES], ids=["own-frames", "frame-coordinates"])
def test_a_sweep_follows_the_stroke_between_the_dead_points(text: str) -> None:
    result = sweep(kinepoly.loads_scene(text), steps=13, start=260.0, stop=325.0)
    assert (result.status == 0).all(), result.warnings
    for row, stroke in enumerate(result.input.values):
        for name, point in POINTS.items():
            x, v, a = _motion(float(stroke), point)
            got = complex(result.column(f"r_{name}_x").values[row], result.column(f"r_{name}_y").values[row])
            assert abs(got - x) <= 1e-9 * 500, (stroke, name)
            got = complex(result.column(f"v_{name}_x").values[row], result.column(f"v_{name}_y").values[row])
            assert abs(got - v) <= 1e-9 * abs(v), (stroke, name)
            got = complex(result.column(f"a_{name}_x").values[row], result.column(f"a_{name}_y").values[row])
            assert abs(got - a) <= 1e-8 * abs(a), (stroke, name)


@pytest.mark.parametrize("stroke", [200.0, 260.0, 325.0, 400.0, 455.0])
def test_the_platform_in_own_frames_solves_as_in_frame_coordinates(stroke: float) -> None:
    """The same values from both ways of writing the cylinder, each equal to the closed form's."""
    solutions = [kinepoly.solve(_scene(text, stroke)) for text in (OWN_FRAMES, FRAME_COORDINATES)]
    for s in solutions:
        assert s.velocity is not None and s.acceleration is not None
        for name, point in POINTS.items():
            x, v, a = _motion(stroke, point)
            assert abs(complex(*s.position(name)) - x) <= 1e-9 * 500, name
            assert abs(complex(*s.velocity.tips[name]) - v) <= 1e-9 * abs(v), name
            assert abs(complex(*s.acceleration.tips[name]) - a) <= 1e-8 * abs(a), name
        assert s.slider("56").s == pytest.approx(stroke, rel=1e-12)
    own, frame = solutions
    assert math.remainder(own.angle("5") - frame.angle("5") - math.radians(113.44113455483786), math.tau) == (
        pytest.approx(0.0, abs=1e-9))  # the barrel's frame is turned by the axis' angle; its motion is the same


def test_the_platform_is_a_triad_built_through_its_assur_point() -> None:
    """Once the stroke is given the cylinder is one leg C0 P: the group is a triad, with no linear solve, its
    Assur point S on the lines of the two legs the step names, and every velocity tip on both of its direction
    lines (the acceleration steps' lines are the triads' own, tested over every example with the triads)."""
    s = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "platform-lift.toml"))
    assert not [step for step in s.steps if step.kind == "linear-solve"]
    assur = [step for step in s.steps if step.topic == "assur-point"]
    assert {step.polygon for step in assur} == {"velocity", "acceleration"}
    at = complex(*s.position("S"))
    lines = {"2": ("A0", "A"), "4": ("B0", "B"), "5+6": ("C0", "P")}
    for step in assur:
        assert {str(step.param("first")), str(step.param("second")), str(step.param("third"))} == set(lines)
        for name in ("first", "second"):
            p, q = (complex(*s.position(x)) for x in lines[str(step.param(name))])
            assert abs(((at - p) / (q - p)).imag) <= 1e-12 * abs(at - p) / abs(q - p) + 1e-15
    for step in s.steps:
        if step.kind == "intersection" and step.polygon == "velocity":
            tip = complex(*step.value)
            for line in step.lines:
                through, direction = complex(*line.through), complex(*line.direction)
                assert abs(((tip - through) * direction.conjugate()).imag) <= 1e-9 * 100 * abs(direction)
    # the drive's terms: P over the barrel's point under it moves along the axis at s_dot
    assert s.velocity is not None and s.acceleration is not None
    x = _motion(400.0, POINTS["P"])[0]
    axis = (x - complex(C0)) / abs(x - complex(C0))
    rel = complex(*s.velocity.tips["P"]) - complex(*s.velocity.tips["P@5"])
    assert abs(rel - S_DOT * axis) <= 1e-12 * S_DOT
    omega = s.velocity.omega["5"]
    rel = complex(*s.acceleration.tips["P"]) - complex(*s.acceleration.tips["P@5"])
    assert abs(rel - (S_DDOT * axis + 2 * omega * 1j * S_DOT * axis)) <= 1e-9 * abs(rel)
    assert s.slider("56").s_dot == pytest.approx(S_DOT, rel=1e-12)
    assert s.slider("56").s_ddot == pytest.approx(S_DDOT, rel=1e-9)


# -- a cylinder between the crank and the rocker of a crank-rocker: a class-4 group -----------------------

CRANK_ROCKER = (EXAMPLES / "crank-rocker-cylinder.toml").read_text()
F0 = mp.mpc(100, 0)
CRANK, COUPLER, ROCKER = mp.mpf(30), mp.mpf(110), mp.mpf(80)
C_ON_CRANK, D_ON_ROCKER = mp.mpc(20, 15), mp.mpc(40, -10)


def _crank_rocker(theta2: mp.mpf) -> dict[str, mp.mpc]:
    """A, B, C, D at the crank angle theta2 (the four-bar closed with B above the line A B0)."""
    turn = mp.expjpi(theta2 / mp.pi)
    a = CRANK * turn
    d = F0 - a
    dist = abs(d)
    along = (COUPLER**2 - ROCKER**2 + dist**2) / (2 * dist)
    b = a + (along + 1j * mp.sqrt(COUPLER**2 - along**2)) * d / dist
    return {"A": a, "B": b, "C": C_ON_CRANK * turn, "D": F0 + D_ON_ROCKER * (b - F0) / ROCKER}


def _cylinder(theta2: mp.mpf) -> mp.mpf:
    at = _crank_rocker(theta2)
    return abs(at["D"] - at["C"])


def _stroke_ends() -> tuple[mp.mpf, mp.mpf]:
    """The crank angles of the least and the greatest stroke over a turn (ds/dtheta2 = 0)."""
    scan = np.radians(np.arange(0.0, 360.0, 1.0))
    strokes = np.array([float(_cylinder(mp.mpf(t))) for t in scan])
    low, high = (mp.findroot(lambda t: mp.diff(_cylinder, t), mp.mpf(scan[k]))
                 for k in (strokes.argmin(), strokes.argmax()))
    return low, high


SHORTEST, LONGEST = _stroke_ends()


def _configurations(stroke: float) -> tuple[mp.mpf, mp.mpf]:
    """The crank angle at the stroke in each configuration: the stroke growing with theta2 (from the shortest
    to the longest) and shrinking (from the longest round to the shortest)."""
    grow = mp.findroot(lambda t: _cylinder(t) - stroke,
                       (SHORTEST - 2 * mp.pi + mp.mpf("1e-9"), LONGEST - mp.mpf("1e-9")), solver="anderson")
    shrink = mp.findroot(lambda t: _cylinder(t) - stroke, (LONGEST + mp.mpf("1e-9"), SHORTEST - mp.mpf("1e-9")),
                         solver="anderson")
    return grow, shrink


def _crank_rocker_scene(stroke: float, guess: dict[str, complex]) -> kinepoly.Scene:
    text = CRANK_ROCKER.replace("s = 100", f"s = {stroke!r}")
    start, end = text.index("\n[guess]") + 1, text.index("\n[find]") + 1
    lines = "\n".join(f"{name} = [{z.real!r}, {z.imag!r}]" for name, z in guess.items())
    return kinepoly.loads_scene(text[:start] + "[guess]\n" + lines + "\n\n" + text[end:])


def test_the_crank_rocker_cylinder_is_a_class_4_group_and_its_steps_say_so() -> None:
    """Once the stroke is given the crank, coupler, rocker and cylinder close a contour of four: no Assur point;
    the linear solve's steps name class 4 (in every language) and lay the relative vectors it gives, each
    square to its link (the tangential terms too), the normal terms toward the first joint, and the slider's
    (s_dot along its axis; s_ddot along it and the Coriolis term), every one ending on the tip of its point."""
    s = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "crank-rocker-cylinder.toml"))
    assert s.check.max_rel_error <= 1e-9
    assert not [step for step in s.steps if step.topic == "assur-point"]
    steps = [step for step in s.steps if step.kind == "linear-solve"]
    assert [step.polygon for step in steps] == ["velocity", "acceleration"]
    assert all(step.param("assur_class") == 4 for step in steps)
    for lang, words in (("en", "class 4"), ("tr", "4. sınıftandır"), ("ro", "clasa 4")):
        say = load_catalogue(lang)
        assert all(words in step_sentence(step, say, Context(s, {"velocity": 1.0, "acceleration": 1.0}))
                   for step in steps), lang
    assert s.velocity is not None and s.acceleration is not None
    axis = complex(*s.position("D")) - complex(*s.position("C"))
    for step in steps:
        tips = (s.velocity if step.polygon == "velocity" else s.acceleration).tips
        drawn = {v.label: v for v in step.vectors}
        assert {"v_B/A", "v_D@5/C", "v_D/D@5"} <= set(drawn) if step.polygon == "velocity" else (
            {"a^n_B/A", "a^t_B/A", "a^n_D@5/C", "a^t_D@5/C", "a_D/D@5"} <= set(drawn))
        for label, v in drawn.items():
            along = complex(*v.end) - complex(*v.start)
            term, _, ends = label.partition("_")
            point, _, ref = ends.partition("/")
            segment = complex(*s.position(point.partition("@")[0])) - complex(*s.position(ref.partition("@")[0]))
            if ref.partition("@")[0] == point.partition("@")[0]:  # the slider's: s_dot e; s_ddot e + 2 omega x s_dot e
                e = axis / abs(axis)
                want = 10 * e if step.polygon == "velocity" else -2 * e + 2 * s.velocity.omega["5"] * 1j * 10 * e
                assert abs(along - want) <= 1e-9 * abs(want)
            elif term == "a^n":  # toward the first joint
                assert abs((along * segment.conjugate()).imag) <= 1e-9 * abs(along) * abs(segment)
                assert (along * segment.conjugate()).real <= 0.0
            else:  # square to the link
                assert abs((along * segment.conjugate()).real) <= 1e-9 * abs(along) * abs(segment) + 1e-12
            if term != "a^n":  # it ends on its point's tip
                assert abs(complex(*v.end) - complex(*tips[point])) <= 1e-9 * abs(complex(*tips[point]))


def test_a_guess_far_from_every_assembly_is_said_to_be() -> None:
    """Every guessed point 60 mm off: whichever assembly the solve takes, it warns that another may lie nearer."""
    theta = _configurations(100.0)[0]
    guess = {name: complex(z) + 60 + 60j for name, z in _crank_rocker(theta).items()}
    s = kinepoly.solve(_crank_rocker_scene(100.0, guess))
    warned = [n.message for n in s.notices if n.code == "far-from-guess"]
    assert len(warned) == 1 and "from its guess" in warned[0] and "another assembly" in warned[0]


@pytest.mark.parametrize("stroke", [85.0, 88.0, 91.75, 94.7, 96.2, 100.0, 110.0, 120.0, 127.0])
def test_a_solve_lands_on_the_configuration_of_an_exact_guess(stroke: float) -> None:
    """Each configuration's own points as the guess give that configuration (before: the other one, at 91.75
    to 94.7 mm, or no solution at 96.2, with the crank turned up to 80 degrees from the guess)."""
    for theta in _configurations(stroke):
        want = {name: complex(z) for name, z in _crank_rocker(theta).items()}
        s = kinepoly.solve(_crank_rocker_scene(stroke, want))
        for name, z in want.items():
            assert abs(complex(*s.position(name)) - z) <= 1e-9 * 100, (stroke, float(theta), name)
        assert not [n for n in s.notices if n.code == "far-from-guess"]


@settings(max_examples=40, deadline=None)
@given(stroke=st.floats(86.0, 126.0), which=st.integers(0, 1), offsets=st.lists(
    st.tuples(st.floats(-12.0, 12.0), st.floats(-12.0, 12.0)), min_size=4, max_size=4))
def test_a_solve_takes_the_assembly_nearest_the_guess_or_says_it_did_not(
        stroke: float, which: int, offsets: list[tuple[float, float]]) -> None:
    """A rough guess (each point up to 12 mm off one configuration): the solve takes the configuration whose
    points lie nearest the guess, or warns that it may not have."""
    configurations = [{name: complex(z) for name, z in _crank_rocker(theta).items()}
                      for theta in _configurations(stroke)]
    guess = {name: z + complex(*d) for (name, z), d in zip(configurations[which].items(), offsets, strict=True)}
    s = kinepoly.solve(_crank_rocker_scene(stroke, guess))
    if [n for n in s.notices if n.code == "far-from-guess"]:
        return
    score = [sum(abs(c[name] - g) ** 2 for name, g in guess.items()) for c in configurations]
    nearest = configurations[score.index(min(score))]
    for name, z in nearest.items():
        assert abs(complex(*s.position(name)) - z) <= 1e-9 * 100, name


def test_the_crank_rocker_cylinder_sweeps_its_whole_stroke_on_one_configuration() -> None:
    """From the shortest stroke to the longest (the dead points of the group) every row closes, on the
    configuration of the scene's guess, equal to the closed form."""
    result = sweep(kinepoly.load_scene(EXAMPLES / "crank-rocker-cylinder.toml"), steps=60)
    values = result.input.values
    assert float(values[0]) == pytest.approx(float(_cylinder(SHORTEST)), abs=1e-4)
    assert float(values[-1]) == pytest.approx(float(_cylinder(LONGEST)), abs=1e-4)
    assert (result.status[1:-1] == 0).all(), result.warnings
    for row in range(1, len(values) - 1):
        theta = _configurations(float(values[row]))[0]
        for name, z in _crank_rocker(theta).items():
            got = complex(result.column(f"r_{name}_x").values[row], result.column(f"r_{name}_y").values[row])
            assert abs(got - complex(z)) <= 1e-9 * 100, (float(values[row]), name)


def test_a_motor_in_a_leg_is_a_driven_leg_too() -> None:
    """Arm 4 split at M by a motor (theta47 driven) as well as the cylinder: both legs are driven, the group is
    still a triad, and P's velocity and acceleration equal central differences of P's place solved with both
    inputs moving at their rates (s = 400 + 50 t - 10 t^2, theta47 = 10 deg + 0.3 t - 0.1 t^2 rad)."""
    text = OWN_FRAMES.replace("4 = { points = { B0 = [0, 0], B = [250, 0] } }",
                              "4 = { points = { B0 = [0, 0], M = [125, 0] } }\n"
                              "7 = { points = { M = [0, 0], B = [125, 0] } }")
    text = text.replace("[input]\nslider", "[[input]]\nslider").replace(
        "s_ddot = -20\n", "s_ddot = -20\n\n[[input]]\nlink = \"7\"\nrelative_to = \"4\"\nangle = ANGLE\nomega = 0.3\n"
        "alpha = -0.2\n").replace("B = [396, 250]", "B = [380, 250]\nM = [400, 125]")

    def at(t: float) -> kinepoly.Solution:
        angle = 10.0 + math.degrees(0.3 * t - 0.1 * t * t)
        return kinepoly.solve(kinepoly.loads_scene(text.replace("s = 400", f"s = {400 + 50 * t - 10 * t * t!r}")
                                                   .replace("ANGLE", repr(angle))))

    s = at(0.0)
    assert s.check.max_rel_error <= 1e-9
    assert not [step for step in s.steps if step.kind == "linear-solve"]
    assur = next(step for step in s.steps if step.topic == "assur-point")
    assert {str(assur.param(k)) for k in ("first", "second", "third")} == {"2", "4+7", "5+6"}
    h = 1e-3
    before, after = (complex(*at(t).position("P")) for t in (-h, h))
    here = complex(*s.position("P"))
    assert s.velocity is not None and s.acceleration is not None
    v, a = complex(*s.velocity.tips["P"]), complex(*s.acceleration.tips["P"])
    assert abs(v - (after - before) / (2 * h)) <= 1e-6 * abs(v)
    assert abs(a - (after - 2 * here + before) / (h * h)) <= 1e-4 * abs(a)
