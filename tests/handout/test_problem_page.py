"""The handout's problem page lets a student redo the problem: every dimension the construction uses is on it.

The dimensions are read off the scene (its links, frame, slides, input, cams and gears), not listed
here: each point of a moving link located by its distances to other points of the link, the frame's
points, the slides, the input, each cam's profile and contact, each gear's pitch curve. And nothing the
construction makes up for itself (an equivalent link's name) reaches the page.
"""

from __future__ import annotations

import math
import re

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.handout.content import Page, Paragraph, Table
from kinepoly.handout.problem import problem_page
from kinepoly.present.catalogue import Catalogue, load_catalogue
from kinepoly.scene.spec import LinkInput, PitchCircle, Scene, SliderInput
from kinepoly.solution import Solution


def _higher_or_cylinder(scene: Scene) -> bool:
    """A cam, a gear or a cylinder (a slide between two moving links)."""
    ground = scene.ground
    return bool(scene.cams or scene.gears or any(s.guide != ground and s.block != ground and
                                                 s.block not in scene.equivalent_links for s in scene.sliders))


NAMES = sorted(p.stem for p in EXAMPLES.glob("*.toml") if _higher_or_cylinder(kinepoly.load_scene(p)))


def _text(page: Page) -> str:
    out = []
    for column in page.columns:
        for part in column.parts:
            if isinstance(part, Paragraph):
                out.append(part.text)
            elif isinstance(part, Table):
                out += [part.title, " ".join(part.header)] + [" ".join(row) for row in part.rows]
    return "\n".join(out)


def _has(text: str, number: str) -> bool:
    """``number`` (as the catalogue writes it) stands in ``text`` as a whole number, not inside a longer one."""
    return re.search(rf"(?<![\d.,]){re.escape(number)}(?![\d]|[.,]\d)", text) is not None


def _needed(solution: Solution, say: Catalogue) -> list[tuple[str, list[str]]]:
    """What the page must state: (what it is, the forms any one of which will do; two of them for "distances")."""
    scene = solution.scene
    ground = scene.ground
    equivalent = set(scene.equivalent_links)
    n = say.number
    out: list[tuple[str, list[str]]] = []
    frame_points = set(scene.link(ground).point_names) if ground else set()
    for p in scene.link(ground).points if ground else ():
        out.append((f"frame point {p.name}", [say.pair(*p.local)]))
    cam_centres = {c.center_point for c in scene.cams}
    for spec in scene.links:
        if spec.name == ground or spec.name in equivalent:
            continue
        points = [p for p in spec.points if p.name not in cam_centres]
        for p in points:  # located by its distances to two other points of the link (to one on a binary link)
            others = [q for q in points if q is not p]
            lengths = [n(math.dist(p.local, q.local)) for q in others]
            if others:
                what = "distances" if len(others) >= 2 else "a distance"
                out.append((f"{what} locating {p.name} on link {spec.name}", lengths))
    for s in scene.sliders:
        if s.block in equivalent:
            continue
        out.append((f"slider {s.name}'s line", [say.pair(*s.through)]))
        out.append((f"slider {s.name}'s angle", [f"{n(math.degrees(s.angle_rad))}°"]))
    inp = scene.input
    if isinstance(inp, LinkInput):
        out += [("input omega", [n(abs(inp.omega))]), ("input alpha", [n(abs(inp.alpha))]),
                ("input angle", [f"{n(math.degrees(inp.angle_rad))}°", f"{n(inp.angle_rad)} rad"])]
    elif isinstance(inp, SliderInput):
        out += [("input s", [n(inp.s)]), ("input s_dot", [n(inp.s_dot)]), ("input s_ddot", [n(inp.s_ddot)])]
    for cam in scene.cams:
        if cam.is_spline:
            out.append((f"cam {cam.name}'s profile", [str(len(cam.profile_points))]))
            continue
        out.append((f"cam {cam.name}'s radius", [n(cam.radius)]))
        pivots = [p for p in scene.link(cam.cam).points if p.name in frame_points]
        out += [(f"cam {cam.name}'s eccentricity from {p.name}", [n(math.dist(p.local, cam.center))]) for p in pivots]
        if cam.kind == "roller":
            out.append((f"cam {cam.name}'s roller radius", [n(cam.roller_radius)]))
        if cam.kind == "flat":
            assert cam.flat is not None
            (x, y), angle = cam.flat
            follower = scene.link(cam.follower).points
            offsets = [n(abs((p.local[0] - x) * math.sin(angle) - (p.local[1] - y) * math.cos(angle)))
                       for p in follower]
            out.append((f"cam {cam.name}'s face offset", offsets))
            out.append((f"cam {cam.name}'s face angle", [f"{n(math.degrees(angle) % 180.0)}°"]))
    for gear in scene.gears:
        for link, pitch in zip(gear.links, gear.pitch, strict=True):
            if isinstance(pitch, PitchCircle):
                out.append((f"gear {link}'s pitch radius", [n(pitch.radius)]))
            else:
                out.append((f"rack {link}'s pitch line", [say.pair(*pitch.through)]))
        for link, pitch in zip(gear.links, gear.pitch, strict=True):
            if (isinstance(pitch, PitchCircle) and link != ground
                    and not (isinstance(inp, LinkInput) and inp.link == link)):
                out.append((f"gear {link}'s angle", [f"θ{ground}{link} = {n(math.degrees(solution.angle(link)))}"]))
    return out


@pytest.mark.parametrize("lang", ["en", "tr", "ro"])
@pytest.mark.parametrize("name", NAMES)
def test_problem_page_gives_every_dimension(name: str, lang: str) -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    say = load_catalogue(lang)
    text = _text(problem_page(solution, say, {}))
    missing = [what for what, forms in _needed(solution, say)
               if sum(_has(text, f) for f in forms) < (2 if what.startswith("distances") else 1)]
    assert not missing, (missing, text)
    page = problem_page(solution, say, {})
    tables = [part for column in page.columns for part in column.parts if isinstance(part, Table)]
    for made in solution.scene.equivalent_links:  # the construction's own link stays off the problem's tables
        assert all(made not in row[:3] for table in tables for row in table.rows), tables
        assert f"eq{made}" not in text and "eq2" not in text


def test_the_examples_checked_are_cams_gears_and_cylinders() -> None:
    scenes = [kinepoly.load_scene(EXAMPLES / f"{name}.toml") for name in NAMES]
    assert any(s.cams and not s.cams[0].is_spline for s in scenes)
    assert any(s.gears for s in scenes)
    assert {"dump-body", "eccentric-cam-flat", "gear-pair", "cam-roller-rocker"} <= set(NAMES)
