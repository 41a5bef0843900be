"""The layer ``higher-pairs``: cam profiles, rollers, flat faces, pitch circles and lines, each pair's
contact point with its common normal, and each cam's equivalent link drawn dashed between its ends.

A cam's profile comes from ``geom.profile.outline`` (points in the cam's own frame), placed with the
cam link; radii and lengths follow the space scale, symbols are in paper millimetres like the rest
of the mechanism. The contact and its normal are the solve's ``contacts`` (``engine.contacts``).
"""

from __future__ import annotations

import math

from msgspec.structs import replace

from kinepoly.geom.profile import outline
from kinepoly.geom.spline import periodic_spline
from kinepoly.geom.vec import Vec, add, scale
from kinepoly.render.labels import Request
from kinepoly.render.layout import Panel
from kinepoly.render.mechanism import block_symbol
from kinepoly.render.primitives import Circle, Item, Path, Stroke
from kinepoly.render.style import LABEL_MM, PIN_RADIUS_MM, link_color, link_label_color
from kinepoly.render.text import point_runs
from kinepoly.scene.spec import CamSpec, GearSpec, PitchCircle, PitchLine
from kinepoly.solution import Solution

__all__ = ["LAYER", "contact_label", "higher_pair_items", "higher_pair_points", "is_equivalent"]

LAYER = "higher-pairs"
_PROFILE_POINTS = 180
_PROFILE = 0.45
_NORMAL = Stroke("#7b2d8e", 0.25, (4.0, 1.0, 0.8, 1.0))
"""The common normal: dash-dot, like a centre line."""
_EQUIVALENT = Stroke("#1a1a1a", 0.45, (2.4, 1.2))
_PITCH = Stroke("#444444", 0.3, (5.0, 1.0, 1.0, 1.0))
_NORMAL_REACH = 0.35
"""How far the normal runs past the contact's pair (a share of the pair's extent)."""


def is_equivalent(solution: Solution, link: str) -> bool:
    """Whether ``link`` is a cam's equivalent link (drawn dashed here, not as a link of the mechanism)."""
    return link in solution.scene.equivalent_links


def contact_label(solution: Solution, pair: str) -> str:
    """The contact point's name: the pitch point ``P23`` of a gear pair, ``C23`` of a cam."""
    return f"P{pair}" if any(g.name == pair for g in solution.scene.gears) else f"C{pair}"


def _world(solution: Solution, link: str, local: Vec) -> Vec:
    if link == solution.mechanism.ground or link not in solution.pose.links:
        return local
    return solution.pose.links[link].world(local)


def _point(solution: Solution, link: str, name: str) -> Vec:
    return _world(solution, link, solution.mechanism.local(link, name))


def _profile(solution: Solution, cam: CamSpec) -> list[Vec]:
    return [_world(solution, cam.cam, p) for p in outline(cam, _PROFILE_POINTS)]


def _follower_profile(solution: Solution, cam: CamSpec) -> list[Vec]:
    """A follower profile of points, placed with the follower (empty for any other follower)."""
    if not cam.follower_points or cam.follower not in solution.pose.links:
        return []
    return [_world(solution, cam.follower, (z.real, z.imag))
            for z in periodic_spline(cam.follower_points).sample(_PROFILE_POINTS).tolist()]


def _follower_centre(solution: Solution, cam: CamSpec) -> Vec | None:
    """A follower profile of points: its centre of curvature at the contact (the equivalent link's end)."""
    k = solution.pose.marks.get(f"K2{cam.name}") if cam.follower_points else None
    return k if k is not None and all(math.isfinite(c) for c in k) else None


def _size(cam: CamSpec) -> float:
    """The profile's size, which sets how far the face and the normal reach: a circle's radius, a spline's
    largest distance from the middle of its points."""
    if not cam.is_spline:
        return cam.radius
    xs, ys = [p[0] for p in cam.profile_points], [p[1] for p in cam.profile_points]
    return 0.5 * max(max(xs) - min(xs), max(ys) - min(ys))


def _centre(solution: Solution, cam: CamSpec) -> Vec | None:
    """The profile's centre of curvature at the contact (a circle's centre; None on a straight stretch)."""
    if not cam.is_spline:
        return _point(solution, cam.cam, cam.center_point)
    k = solution.pose.marks.get(f"K{cam.name}")
    return k if k is not None and all(math.isfinite(c) for c in k) else None


def _circle_points(center: Vec, radius: float) -> list[Vec]:
    return [(center[0] + radius * c, center[1] + radius * s) for c, s in ((1, 0), (-1, 0), (0, 1), (0, -1))]


def _rack_line(solution: Solution, gear: GearSpec, side: int) -> tuple[Vec, Vec]:
    """A rack's pitch line drawn about the pitch point: as long as four of the pinion's radii."""
    curve = gear.pitch[side]
    other = gear.pitch[1 - side]
    assert isinstance(curve, PitchLine)
    link = gear.links[side]
    through = _world(solution, link, curve.through)
    turn = solution.pose.links[link].theta if link in solution.pose.links else 0.0
    d = (math.cos(curve.angle_rad + turn), math.sin(curve.angle_rad + turn))
    contact = solution.contacts[gear.name].point if gear.name in solution.contacts else through
    reach = 2.0 * (other.radius if isinstance(other, PitchCircle) else 1.0)
    return add(contact, scale(-reach, d)), add(contact, scale(reach, d))


def _flat_face(solution: Solution, cam: CamSpec) -> tuple[Vec, Vec]:
    """The follower's face: from its ``through`` point past the contact, by half the disc's radius each way."""
    assert cam.flat is not None
    (local, angle) = cam.flat
    through = _world(solution, cam.follower, local)
    turn = solution.pose.links[cam.follower].theta
    d = (math.cos(angle + turn), math.sin(angle + turn))
    contact = solution.contacts[cam.name].point if cam.name in solution.contacts else through
    along = [0.0, (contact[0] - through[0]) * d[0] + (contact[1] - through[1]) * d[1]]
    lo, hi = min(along) - 0.5 * _size(cam), max(along) + 0.5 * _size(cam)
    return add(through, scale(lo, d)), add(through, scale(hi, d))


def higher_pair_points(solution: Solution) -> list[Vec]:
    """The frame points the layer reaches (profiles, rollers, faces, pitch circles), for the panel's box."""
    out: list[Vec] = []
    for cam in solution.scene.cams:
        if cam.cam not in solution.pose.links:
            continue
        out += _profile(solution, cam) + _follower_profile(solution, cam)
        if cam.kind == "roller" and cam.point is not None and cam.follower in solution.pose.links:
            out += _circle_points(_point(solution, cam.follower, cam.point), cam.roller_radius)
        elif cam.kind == "flat" and cam.follower in solution.pose.links:
            out += list(_flat_face(solution, cam))
    for gear in solution.scene.gears:
        for side, (link, curve) in enumerate(zip(gear.links, gear.pitch, strict=True)):
            if isinstance(curve, PitchCircle):
                out += _circle_points(_point(solution, link, curve.center), curve.radius)
            elif gear.name in solution.contacts:
                out += list(_rack_line(solution, gear, side))
    return out


def _ring(center: Vec, radius: float, stroke: Stroke, role: str) -> Path:
    """A circle drawn as its outline (a closed polyline), so that labels may sit inside it."""
    count = _PROFILE_POINTS
    return Path(tuple((center[0] + radius * math.cos(2 * math.pi * k / count),
                       center[1] + radius * math.sin(2 * math.pi * k / count)) for k in range(count)),
                stroke, closed=True, role=role)


def _link_index(solution: Solution, link: str) -> int:
    return list(solution.mechanism.link_names).index(link)


def _cam_items(solution: Solution, cam: CamSpec, panel: Panel) -> list[Item]:
    idx = _link_index(solution, cam.cam)
    ink = link_label_color(idx)
    items: list[Item] = [Path(tuple(panel.paper(p) for p in _profile(solution, cam)), Stroke(ink, _PROFILE),
                              fill=link_color(idx), fill_opacity=0.18, closed=True, role=f"cam profile {cam.name}")]
    if cam.follower not in solution.pose.links:
        return items
    follower_ink = link_label_color(_link_index(solution, cam.follower))
    if cam.kind == "roller" and cam.point is not None:
        w = panel.paper(_point(solution, cam.follower, cam.point))
        if cam.follower_profile:  # a curve of the follower's own, shaded like the cam's
            ring = _ring(w, cam.roller_radius * panel.scale, Stroke(follower_ink, _PROFILE),
                         f"follower profile {cam.name}")
            items.append(replace(ring, fill=link_color(_link_index(solution, cam.follower)), fill_opacity=0.18))
        else:
            items.append(_ring(w, cam.roller_radius * panel.scale, Stroke(follower_ink, _PROFILE),
                               f"roller {cam.name}"))
    elif cam.follower_points:  # a spline of the follower's own, shaded like the cam's
        items.append(Path(tuple(panel.paper(p) for p in _follower_profile(solution, cam)),
                          Stroke(follower_ink, _PROFILE),
                          fill=link_color(_link_index(solution, cam.follower)), fill_opacity=0.18, closed=True,
                          role=f"follower profile {cam.name}"))
    elif cam.kind == "flat":
        a, b = _flat_face(solution, cam)
        items.append(Path((panel.paper(a), panel.paper(b)), Stroke(follower_ink, 0.6), role=f"flat face {cam.name}"))
    return items


def _equivalent_items(solution: Solution, cam: CamSpec, panel: Panel) -> list[Item]:
    """The equivalent link dashed between its ends (the disc's centre and the roller's or edge's point); for a
    flat face, the dashed block at the centre and its slide, parallel to the face."""
    placed = cam.equivalent in solution.pose.links if not cam.is_spline else cam.follower in solution.pose.links
    centre = _centre(solution, cam) if placed else None
    if centre is None:
        return []
    k = panel.paper(centre)
    name = cam.equivalent or f"K{cam.name}{cam.point or ''}"
    if cam.follower_points:
        other = _follower_centre(solution, cam)
        return [] if other is None else [Path((k, panel.paper(other)), _EQUIVALENT,
                                              role=f"equivalent link {name}K2{cam.name}")]
    if cam.kind != "flat":
        assert cam.point is not None
        w = panel.paper(_point(solution, cam.follower, cam.point))
        return [Path((k, w), _EQUIVALENT, role=f"equivalent link {name}")]
    assert cam.flat is not None
    turn = solution.pose.links[cam.follower].theta + cam.flat[1]
    d = (math.cos(turn), math.sin(turn))
    reach = 0.6 * _size(cam) * panel.scale
    slide = Path((add(k, scale(-reach, d)), add(k, scale(reach, d))), _EQUIVALENT,
                 role=f"equivalent slide {cam.follower}-{name}")
    return [slide, replace(block_symbol(k, d, f"equivalent block {name}"), stroke=_EQUIVALENT)]


def _gear_items(solution: Solution, gear: GearSpec, panel: Panel) -> list[Item]:
    items: list[Item] = []
    for side, (link, curve) in enumerate(zip(gear.links, gear.pitch, strict=True)):
        if link != solution.mechanism.ground and link not in solution.pose.links:
            continue
        ink = link_label_color(_link_index(solution, link))
        if isinstance(curve, PitchCircle):
            center = panel.paper(_point(solution, link, curve.center))
            items.append(_ring(center, curve.radius * panel.scale, replace(_PITCH, color=ink),
                               f"pitch circle {gear.name} {link}"))
        elif gear.name in solution.contacts:
            a, b = _rack_line(solution, gear, side)
            items.append(Path((panel.paper(a), panel.paper(b)), replace(_PITCH, color=ink),
                              role=f"pitch line {gear.name} {link}"))
    return items


def _normal_ends(solution: Solution, pair: str, at: Vec, n: Vec) -> tuple[float, float]:
    """How far the common normal runs each way from the contact: through the pair's centres of curvature
    (a cam's disc centre and roller; both gears' centres), and a little beyond."""
    ends: list[Vec] = []
    size = 1.0
    for cam in solution.scene.cams:
        if cam.name == pair:
            centre = _centre(solution, cam)
            ends += [centre] if centre is not None else []
            ends += [_point(solution, cam.follower, cam.point)] if cam.point is not None else []
            ends += [other] if (other := _follower_centre(solution, cam)) is not None else []
            size = _size(cam)
    for gear in solution.scene.gears:
        if gear.name == pair:
            ends += [_point(solution, link, c.center) for link, c in zip(gear.links, gear.pitch, strict=True)
                     if isinstance(c, PitchCircle)]
            size = max(c.radius for c in gear.pitch if isinstance(c, PitchCircle))
    along = [(e[0] - at[0]) * n[0] + (e[1] - at[1]) * n[1] for e in ends] + [0.0]
    margin = _NORMAL_REACH * size
    return min(along) - margin, max(along) + margin


def higher_pair_items(solution: Solution, panel: Panel) -> tuple[list[Item], list[Request]]:
    """The layer's items on the mechanism's panel, and the contact points' label requests."""
    items: list[Item] = []
    requests: list[Request] = []
    for gear in solution.scene.gears:
        items += _gear_items(solution, gear, panel)
    for cam in solution.scene.cams:
        if cam.cam in solution.pose.links:
            items += _cam_items(solution, cam, panel)
    for cam in solution.scene.cams:
        items += _equivalent_items(solution, cam, panel)
    for pair, contact in solution.contacts.items():
        lo, hi = _normal_ends(solution, pair, contact.point, contact.normal)
        ends = (add(contact.point, scale(lo, contact.normal)), add(contact.point, scale(hi, contact.normal)))
        items.append(Path((panel.paper(ends[0]), panel.paper(ends[1])), _NORMAL, role=f"common normal {pair}"))
    marked = [("contact", contact_label(solution, pair), contact.point) for pair, contact in solution.contacts.items()]
    marked += [("centre of curvature", f"K{cam.name}", centre) for cam in solution.scene.cams
               if cam.is_spline and cam.follower in solution.pose.links
               and (centre := _centre(solution, cam)) is not None]
    marked += [("centre of curvature", f"K2{cam.name}", other) for cam in solution.scene.cams
               if (other := _follower_centre(solution, cam)) is not None]
    for kind, name, where in marked:
        at = panel.paper(where)
        items.append(Circle(at, 0.7, Stroke(_NORMAL.color, 0.3), fill=_NORMAL.color, role=f"{kind} {name}"))
        requests.append(Request(LAYER, panel.drawing_rect, point_runs(name, LABEL_MM), at, color=_NORMAL.color,
                                role=f"point {name}", priority=0, gap=PIN_RADIUS_MM))
    return items, requests


