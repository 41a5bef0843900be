"""A cam pair's instant center as a line edge of the circle diagram, against the velocity pole.

The engine finds I23 where one triangle's Kennedy line crosses the common normal at the contact.
Derived apart from it here: the analytic check (``check.analytic``, which shares no code with the
engine) gives every link's omega and the velocity of its frame origin o; the center of links i and
j is the point P that has one velocity as a point of either,

    v_i + omega_i i (P - o_i) = v_j + omega_j i (P - o_j)
      =>   P = (v_j - v_i + i (omega_i o_i - omega_j o_j)) / (i (omega_i - omega_j)),

and where omega_i = omega_j the relative motion is a translation by v_j - v_i: the center is at infinity,
perpendicular to it. Every cam example is checked at its input and at random cam angles over a turn
(circle and spline profiles; rocker, translating and flat-faced followers), METU's cam with its three
centers, and a disc cam whose roller rides on a coupler held by two rockers (a triad) with all ten.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinepoly
from kinepoly.check.analytic import solve_analytic
from kinepoly.scene.loader import loads_scene

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
CAMS = ("cam-roller-rocker", "eccentric-cam-flat", "metu-cam", "spline-cam-flat-rocker", "spline-cam-knife",
        "spline-cam-roller-rocker")

TRIAD = (Path(__file__).resolve().parent / "cam-on-coupler.toml").read_text()


def _text(name: str, angle: float | None = None, omega: float | None = None) -> str:
    """The example asking I23 (and what it asked), at another cam angle or omega when given."""
    text = (EXAMPLES / f"{name}.toml").read_text()
    if "instant_centers" not in text:
        text = text.replace("[find]\n", '[find]\ninstant_centers = ["23"]\n')
    if angle is not None:
        text = re.sub(r"(?m)^angle = \S+", f"angle = {angle!r}", text, count=1)
    if omega is not None:
        text = re.sub(r"(?m)^omega = \S+", f"omega = {omega!r}", text, count=1)
    return text


def _poles(solution: kinepoly.Solution) -> dict[str, tuple[str, complex]]:
    """Each asked center from the analytic check's velocities: ("position", P) or ("direction", u)."""
    analytic = solve_analytic(solution.mechanism, dict(solution.pose.links), with_acceleration=False)
    out = {}
    for key in solution.centers.asked if solution.centers else ():
        i, j = solution.centers.centers[key[1]].links
        oi, oj = (complex(analytic.poses[k].x, analytic.poses[k].y) for k in (i, j))
        vi, vj = (complex(*analytic.linear_velocity[k]) for k in (i, j))
        wi, wj = analytic.omega[i], analytic.omega[j]
        relative = vj - vi + 1j * (wi * oi - wj * oj)
        if abs(wi - wj) * solution_size(solution) <= 1e-12 * abs(relative):
            out[key[0]] = ("direction", 1j * (vj - vi) / abs(vj - vi))
        else:
            out[key[0]] = ("position", relative / (1j * (wi - wj)))
    return out


def solution_size(solution: kinepoly.Solution) -> float:
    """The mechanism's size: the largest distance between two of its links' points."""
    points = [complex(*solution.pose.links[k].world(p.local)) for k in solution.pose.links
              for p in solution.scene.link(k).points]
    return max(abs(a - b) for a in points for b in points)


def _assert_centers_are_the_poles(solution: kinepoly.Solution, tolerance: float,
                                  data: dict[str, dict[str, list[float]]] | None = None) -> None:
    """Every asked center (the solve's, or ``data`` in its JSON form) is its pair's velocity pole."""
    data = kinepoly.to_json(solution)["instant_centers"] if data is None else data
    size = solution_size(solution)
    poles = _poles(solution)
    assert poles and set(poles) == set(data)
    for key, (kind, want) in poles.items():
        assert kind in data[key], (key, data[key], want)
        got = complex(*data[key][kind])
        if kind == "position":
            assert abs(got - want) <= tolerance * max(size, abs(want)), (key, got, want)
        else:
            assert abs((got * want.conjugate()).imag) <= tolerance, (key, got, want)  # the same line direction


@pytest.mark.parametrize("name", CAMS)
def test_the_cam_pairs_center_is_the_velocity_pole_at_the_examples_input(name: str) -> None:
    solution = kinepoly.solve(loads_scene(_text(name)))
    _assert_centers_are_the_poles(solution, 1e-9)
    assert solution.centers is not None
    [step] = [s for s in solution.centers.steps if s.center == "23"]
    assert step.equation == "I23 = (I12 I13) x n(C23)" and step.triangles == ("123",)
    assert step.lines[1].is_common_normal and step.lines[1].contact == "C23"
    contact = kinepoly.to_json(solution)["contacts"]["23"]
    assert step.lines[1].through == pytest.approx(tuple(contact["point"]), abs=1e-9)
    # I23 lies on the common normal: (I23 - C) x n = 0
    i23 = complex(*kinepoly.to_json(solution)["instant_centers"]["23"]["position"])
    offset = i23 - complex(*contact["point"])
    assert abs((offset * complex(*contact["normal"]).conjugate()).imag) <= 1e-9 * solution_size(solution)


@pytest.mark.parametrize("name", CAMS)
def test_no_equivalent_link_is_a_node_of_the_circle_diagram(name: str) -> None:
    solution = kinepoly.solve(loads_scene(_text(name)))
    assert solution.centers is not None
    diagram = solution.centers.diagram
    assert diagram.links == ("1", "2", "3")
    [line] = [e for e in diagram.edges if e.kind == "line"]
    assert line.links == ("2", "3") and line.number == 1 and "common normal of cam 23" in line.via
    assert all(not any(link.startswith("eq") for link in e.links) for e in diagram.edges)


@settings(max_examples=12, deadline=None)
@given(name=st.sampled_from(CAMS), angle=st.floats(0.0, 359.9), omega=st.floats(0.5, 40.0))
def test_the_cam_pairs_center_is_the_velocity_pole_over_a_cam_turn(name: str, angle: float, omega: float) -> None:
    solution = kinepoly.solve(loads_scene(_text(name, angle, omega)))
    _assert_centers_are_the_poles(solution, 1e-8)


def test_the_metu_cams_three_centers_are_the_poles() -> None:
    solution = kinepoly.solve(loads_scene(_text("metu-cam")))
    assert [key for key, _ in solution.centers.asked] == ["12", "13", "23"] if solution.centers else False
    _assert_centers_are_the_poles(solution, 1e-10)


def test_a_disc_cam_under_a_coupler_finds_all_ten_centers_through_the_common_normal() -> None:
    solution = kinepoly.solve(loads_scene(TRIAD))
    assert solution.centers is not None
    assert len(solution.centers.asked) == 10  # five links of the scene; the equivalent link is no node
    _assert_centers_are_the_poles(solution, 1e-9)
    by_center = {s.center: s for s in solution.centers.steps}
    assert by_center["23"].equation == "I23 = (I12 I13) x n(C23)"  # I13 found first, by triangles 134 and 135
    assert by_center["13"].number < by_center["23"].number < by_center["24"].number
    # and the omegas the centers give agree with the polygon's
    omega3 = {o.link: o.omega for o in solution.centers.omegas}["3"]
    assert omega3 == pytest.approx(kinepoly.to_json(solution)["links"]["3"]["omega"], rel=1e-10)


@settings(max_examples=10, deadline=None)
@given(angle=st.floats(27.0, 33.0), omega=st.floats(-30.0, 30.0).filter(lambda w: abs(w) > 0.1))
def test_the_triads_centers_are_the_poles_near_its_position(angle: float, omega: float) -> None:
    text = re.sub(r"(?m)^angle = \S+", f"angle = {angle!r}", TRIAD, count=1)
    text = re.sub(r"(?m)^omega = \S+", f"omega = {omega!r}", text, count=1)
    _assert_centers_are_the_poles(kinepoly.solve(loads_scene(text)), 1e-8)


@pytest.mark.parametrize("name", ["cam-roller-rocker", "metu-cam"])
def test_a_center_moved_along_the_common_normal_fails_the_pole_check(name: str) -> None:
    """The check can fail: I23 moved along the common normal (so off the line I12 I13) by a millionth of
    the mechanism's size is caught."""
    solution = kinepoly.solve(loads_scene(_text(name)))
    data = kinepoly.to_json(solution)
    normal = complex(*data["contacts"]["23"]["normal"])
    i23 = complex(*data["instant_centers"]["23"]["position"])
    moved = i23 + 1e-6 * solution_size(solution) * normal
    with pytest.raises(AssertionError):
        _assert_centers_are_the_poles(solution, 1e-9, {**data["instant_centers"],
                                                       "23": {"position": [moved.real, moved.imag]}})


def test_the_steps_name_the_common_normal_in_every_language() -> None:
    from kinepoly.present.catalogue import load_catalogue
    from kinepoly.present.phrasing import Context, kennedy_sentence

    solution = kinepoly.solve(loads_scene(_text("metu-cam")))
    assert solution.centers is not None
    [step] = solution.centers.steps
    for lang, words in (("en", "common normal n(C23) through C23"),
                        ("tr", "C23 noktasından geçen n(C23) ortak normali"),
                        ("ro", "normala comună n(C23) prin C23")):
        text = kennedy_sentence(step, load_catalogue(lang), Context(solution, {}))
        assert words in text and "I12 I13" in text, (lang, text)


def test_the_sheet_draws_the_common_normal_as_a_kennedy_line_and_the_line_edge_dash_dot() -> None:
    from kinepoly.render.centers import LINE_EDGE
    from kinepoly.render.primitives import Path as Stroked
    from kinepoly.render.sheet import build_sheet

    solution = kinepoly.solve(loads_scene(_text("metu-cam")))
    items = build_sheet(solution).layer("instant-centers").items
    [normal] = [i for i in items if isinstance(i, Stroked) and i.role == "kennedy n(C23)"]
    [edge] = [i for i in items if isinstance(i, Stroked) and i.role == "diagram edge 23"]
    assert edge.stroke == LINE_EDGE and not any(i.role.startswith("diagram edge") and "eq" in i.role for i in items)
    # the normal runs from the contact through I23 (both on paper, on the drawn segment)
    (x0, y0), (x1, y1) = normal.points
    length = math.hypot(x1 - x0, y1 - y0)
    centers = [i for i in items if i.role == "center I23" and hasattr(i, "center")]
    assert length > 5.0 and centers
    cx, cy = centers[0].center  # type: ignore[attr-defined]
    assert abs((x1 - x0) * (cy - y0) - (y1 - y0) * (cx - x0)) / length <= 1e-6
