"""The first page of a handout: the problem as a student gets it.

What is given (the input, the frame's points, the higher pairs as a textbook states them, the slides,
every link's dimensions; an equivalent link is the construction's, not the problem's), what is to be found (the scene's
``[find]``), and the scales to draw at; the drawing beside it shows the mechanism and the polygon panels empty but for
their poles and scale bars.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from itertools import combinations

from kinepoly.engine.circle_diagram import center_label, pair_name, split_pair
from kinepoly.geom.tolerances import ANGLE_SAME_DEG
from kinepoly.handout.content import Column, Drawing, Page, Paragraph, Table
from kinepoly.present.catalogue import Catalogue
from kinepoly.render.titleblock import space_scale_text
from kinepoly.scene.spec import CamSpec, GearSpec, GivenInput, LinkInput, PitchCircle, SliderInput
from kinepoly.solution import Solution

__all__ = ["problem_page"]


def _angle(solution: Solution, say: Catalogue, radians: float) -> str:
    if solution.scene.units.angle == "deg":
        return f"{say.number(math.degrees(radians))}°"
    return f"{say.number(radians)} rad"


def _input(solution: Solution, say: Catalogue) -> list[Paragraph]:
    inp, unit = solution.scene.input, solution.scene.units.length
    if not isinstance(inp, GivenInput):
        return [_drive_paragraph(solution, say, drive.spec, f"{drive.base}{drive.moving}", unit)
                for drive in solution.mechanism.drives]
    assert isinstance(inp, GivenInput)
    out = [Paragraph(say.say("problem.input_given", link=solution.mechanism.link_names[0]))]
    for point in inp.points:
        acceleration = (say.say("problem.given_acceleration", point=point.name,
                                value=say.pair(*point.acceleration), unit=f"{unit}/s²")
                        if point.acceleration is not None else "")
        out.append(Paragraph(say.say("problem.given_point", point=point.name, value=say.pair(*point.velocity),
                                     unit=f"{unit}/s", acceleration=acceleration).rstrip()))
    return out


def _drive_paragraph(solution: Solution, say: Catalogue, inp: LinkInput | SliderInput, pair: str,
                     unit: str) -> Paragraph:
    if isinstance(inp, LinkInput):
        return Paragraph(say.say(
            "problem.input_link", link=inp.link, angle_name=f"θ{pair}",
            angle=_angle(solution, say, inp.angle_rad), omega_name=f"ω{pair}",
            omega=say.number(abs(inp.omega)), omega_sense=_sense_text(say, inp.omega),
            alpha_name=f"α{pair}", alpha=say.number(abs(inp.alpha)), alpha_sense=_sense_text(say, inp.alpha)))
    return Paragraph(say.say("problem.input_slider", slider=inp.slider, s=say.number(inp.s),
                             s_dot=say.number(inp.s_dot), s_ddot=say.number(inp.s_ddot), unit=unit))


def _sense_text(say: Catalogue, rate: float) -> str:
    """The sense after an input rate (`` counter-clockwise``); nothing after a zero rate (0 rad/s², not "0 rad/s²
    zero")."""
    if rate == 0.0:
        return ""
    return say.say("problem.rate_sense", sense=say.say(f"sense.{'ccw' if rate > 0 else 'cw'}"))


def _frame(solution: Solution, say: Catalogue) -> list[Paragraph]:
    ground = solution.mechanism.ground
    if ground is None:
        return []
    points = [f"{p.name} {say.pair(*solution.position(p.name))}" for p in solution.scene.link(ground).points]
    return [Paragraph(say.say("problem.frame", link=ground, points=", ".join(points),
                              unit=solution.scene.units.length))]


def _slides(solution: Solution, say: Catalogue) -> list[Table]:
    """Each slider of the scene: its block, the link it slides on, its point and line (in that link's own frame);
    an equivalent link's slide is no slider of the problem (the cam's paragraph gives its face)."""
    sliders = [s for s in solution.scene.sliders if s.block not in solution.scene.equivalent_links]
    if not sliders:
        return []
    rows = tuple((slider.name, slider.block, slider.guide, slider.point, say.pair(*slider.through),
                  f"{say.number(math.degrees(slider.angle_rad))}°") for slider in sliders)
    header = (say.say("problem.slider"), say.say("problem.block"), say.say("problem.guide"), say.say("problem.point"),
              say.say("problem.through", unit=solution.scene.units.length), say.say("problem.angle"))
    return [Table(say.say("problem.slides"), header, rows)]


def _dimensions(solution: Solution, say: Catalogue) -> Table:
    rows = []
    for link in solution.scene.links:
        if link.name == solution.mechanism.ground or link.name in solution.scene.equivalent_links:
            continue
        points = link.points
        pairs = list(combinations(points, 2)) if len(points) <= 4 else \
            [(points[0], p) for p in points[1:]] + [(points[1], p) for p in points[2:]]
        for first, second in pairs:
            length = math.hypot(second.local[0] - first.local[0], second.local[1] - first.local[1])
            rows.append((link.name, f"{first.name}{second.name}", say.number(length)))
    header = (say.say("problem.link"), say.say("problem.segment"),
              say.say("problem.length", unit=solution.scene.units.length))
    return Table(say.say("problem.dimensions"), header, tuple(rows))


def _length(say: Catalogue, x: float, unit: str) -> str:
    return f"{say.number(x)} {unit}"


def _pivot(solution: Solution, link: str) -> tuple[str, tuple[float, float]]:
    """The point a cam or a gear turns about: its first point the frame shares, else its first point."""
    spec = solution.scene.link(link)
    ground = solution.mechanism.ground
    on_frame = set(solution.scene.link(ground).point_names) if ground else set()
    point = next((p for p in spec.points if p.name in on_frame), spec.points[0])
    return point.name, point.local


def _line_degrees(radians: float) -> float:
    """A line's angle in degrees in [0, 180): the two senses of a line are one line (a face turned half a turn
    to have the disc on its left is the face given)."""
    degrees = math.degrees(radians) % 180.0
    return 0.0 if math.isclose(degrees, 180.0, abs_tol=ANGLE_SAME_DEG) else degrees


def _cam(solution: Solution, say: Catalogue, cam: CamSpec) -> list[Paragraph]:
    """A cam pair as a textbook states it: the profile (a disc's radius, centre and eccentricity) and the
    follower's contact (a roller's radius, a knife's edge, a flat face's line and its distance from a point)."""
    unit = solution.scene.units.length
    pivot, at = _pivot(solution, cam.cam)
    if cam.is_spline:
        profile = say.say("problem.cam_spline", cam=cam.cam, count=str(len(cam.profile_points)))
    else:
        centre = cam.center_point or "K"
        profile = say.say("problem.cam_disc", cam=cam.cam, radius=_length(say, cam.radius, unit), centre=centre,
                          at=say.pair(*cam.center), pivot=pivot,
                          eccentricity=_length(say, math.hypot(cam.center[0] - at[0], cam.center[1] - at[1]), unit))
    follower = cam.follower
    if cam.kind == "roller":
        assert cam.point is not None
        key = "problem.follower_circle" if cam.follower_profile else "problem.roller"
        touch = say.say(key + "_inside" if cam.inside else key, follower=follower,
                        point=cam.point, radius=_length(say, cam.roller_radius, unit))
    elif cam.follower_points:
        touch = say.say("problem.follower_spline", follower=follower, count=str(len(cam.follower_points)))
    elif cam.kind == "knife":
        touch = say.say("problem.knife", follower=follower, point=cam.point or "")
    else:
        assert cam.flat is not None
        (x, y), angle = cam.flat
        first = solution.scene.link(follower).points[0]
        u = (math.cos(angle), math.sin(angle))
        offset = abs((first.local[0] - x) * u[1] - (first.local[1] - y) * u[0])
        touch = say.say("problem.flat", follower=follower, through=say.pair(x, y),
                        angle=f"{say.number(_line_degrees(angle))}°", point=first.name,
                        offset=_length(say, offset, unit))
    out = [Paragraph(profile), Paragraph(touch)]
    if cam.equivalent:
        if cam.kind == "flat":
            out.append(Paragraph(say.say("problem.equivalent_block", centre=cam.center_point, follower=follower),
                                 "note"))
        else:
            out.append(Paragraph(say.say("problem.equivalent_link", name=f"{cam.center_point}{cam.point}",
                                         centre=cam.center_point, point=cam.point or ""), "note"))
    return out


def _gears(solution: Solution, say: Catalogue, gear: GearSpec) -> Paragraph:
    """A gear pair: each pitch circle's centre and radius (a rack's pitch line) and how they mesh."""
    unit = solution.scene.units.length
    curves = []
    for link, pitch in zip(gear.links, gear.pitch, strict=True):
        if isinstance(pitch, PitchCircle):
            curves.append(say.say("problem.pitch_circle", link=link, centre=pitch.center,
                                  radius=_length(say, pitch.radius, unit)))
        else:
            curves.append(say.say("problem.pitch_line", link=link, through=say.pair(*pitch.through),
                                  angle=f"{say.number(_line_degrees(pitch.angle_rad))}°"))
    key = "problem.gears_internal" if gear.internal else "problem.gears"
    return Paragraph(say.say(key, first=gear.links[0], second=gear.links[1], curves="; ".join(curves)))


def _gear_angles(solution: Solution, say: Catalogue) -> list[Paragraph]:
    """The angle each driven gear stands at in the position drawn: where its teeth (and its points) are follows
    from how the gears were set in mesh, which the drawing shows and a textbook's figure gives (a rack
    translates: its angle says nothing)."""
    ground = solution.mechanism.ground or ""
    inp = solution.scene.input
    driven = dict.fromkeys(link for gear in solution.scene.gears
                           for link, pitch in zip(gear.links, gear.pitch, strict=True)
                           if isinstance(pitch, PitchCircle) and link != ground and link in solution.pose.links
                           and not (isinstance(inp, LinkInput) and inp.link == link))
    if not driven:
        return []
    angles = ", ".join(f"θ{ground}{link} = {_angle(solution, say, solution.angle(link))}" for link in driven)
    return [Paragraph(say.say("problem.gear_angles", angles=angles), "note")]


def _higher_pairs(solution: Solution, say: Catalogue) -> list[Paragraph]:
    scene = solution.scene
    if not scene.cams and not scene.gears:
        return []
    out = [Paragraph(say.say("problem.higher_pairs"), "heading")]
    for cam in scene.cams:
        out += _cam(solution, say, cam)
    out += [_gears(solution, say, gear) for gear in scene.gears]
    return out + _gear_angles(solution, say)


def _find(solution: Solution, say: Catalogue) -> list[Paragraph]:
    find, ground = solution.scene.find, solution.mechanism.ground or ""
    out = []
    if find.velocity:
        out.append(say.say("problem.find_velocity", terms=", ".join(f"v_{p}" for p in find.velocity)))
    if find.acceleration:
        out.append(say.say("problem.find_acceleration", terms=", ".join(f"a_{p}" for p in find.acceleration)))
    if find.omega:
        out.append(say.say("problem.find_omega", terms=", ".join(f"ω{ground}{k}" for k in find.omega)))
    if find.alpha:
        out.append(say.say("problem.find_alpha", terms=", ".join(f"α{ground}{k}" for k in find.alpha)))
    if solution.asked.sliders:
        names = ", ".join(solution.asked.sliders)
        key = "problem.find_sliders_acceleration" if solution.acceleration is not None else "problem.find_sliders"
        out.append(say.say(key, sliders=names))
    if solution.centers is not None and find.instant_centers:
        links = solution.mechanism.link_names
        keys = ([pair_name(e) for e in combinations(links, 2)] if find.instant_centers == "all"
                else [pair_name(split_pair(k, links)) for k in find.instant_centers])
        out.append(say.say("problem.find_centers", centers=", ".join(center_label(k) for k in keys)))
    return [Paragraph("– " + line) for line in out]


def _scales(solution: Solution, say: Catalogue, scales: Mapping[str, float]) -> list[Paragraph]:
    unit = solution.scene.units.length
    out = []
    if "mechanism" in scales:
        ratio = space_scale_text(scales["mechanism"], unit).partition(" ")[2]
        out.append(say.say("problem.space_scale", ratio=ratio.replace(".", say.decimal)))
    if "velocity" in scales:
        out.append(say.say("problem.kv", scale=say.number(scales["velocity"]), unit=f"{unit}/s"))
    if "acceleration" in scales:
        out.append(say.say("problem.ka", scale=say.number(scales["acceleration"]), unit=f"{unit}/s²"))
    paragraphs = [Paragraph("– " + line) for line in out]
    if solution.velocity is not None:
        paragraphs.append(Paragraph(say.say("problem.draw_velocity"), "note"))
    if solution.acceleration is not None:
        paragraphs.append(Paragraph(say.say("problem.draw_acceleration"), "note"))
    if solution.centers is not None and solution.scene.find.instant_centers:
        paragraphs.append(Paragraph(say.say("problem.draw_centers"), "note"))
    return paragraphs


def problem_page(solution: Solution, say: Catalogue, scales: Mapping[str, float]) -> Page:
    """The problem: given, dimensions, find, scales; ``scales`` as drawn (``mechanism``, kv, ka)."""
    first = (Paragraph(solution.scene.title, "title"), Paragraph(say.say("problem.title"), "heading"),
             Paragraph(say.say("problem.given"), "heading"), *_input(solution, say), *_frame(solution, say),
             *_higher_pairs(solution, say))
    second = (_dimensions(solution, say), *_slides(solution, say))
    third = (Paragraph(say.say("problem.find"), "heading"), *_find(solution, say))
    fourth = (Paragraph(say.say("problem.scales"), "heading"), *_scales(solution, say, scales))
    columns = (Column(first, fill=True), Column(second), Column(third, fill=True), Column(fourth, fill=True))
    return Page("problem", Drawing("problem"), columns, heading=say.say("problem.title"))
