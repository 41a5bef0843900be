"""The mechanism at the analysed position: links, plates, joints, the hatched frame, slider blocks.

Sizes of symbols (pins, blocks, frame hatching) are in paper millimetres whatever the space
scale, as a draughtsman draws them; positions follow the scale.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from kinepoly.geom.vec import Vec, add, dot, norm, perp, rotate, scale, sub
from kinepoly.render.labels import Request
from kinepoly.render.layout import Panel
from kinepoly.render.primitives import Arrow, Circle, Item, Path, Stroke
from kinepoly.render.style import (
    LABEL_MM,
    LINK_STROKE,
    PIN_RADIUS_MM,
    THIN,
    link_color,
    link_label_color,
)
from kinepoly.render.text import Run, plain_runs, point_runs, text_width
from kinepoly.scene.spec import LinkInput, SliderSpec
from kinepoly.solution import Solution

__all__ = ["block_symbol", "mechanism_box", "mechanism_items", "world_points"]

Point = tuple[float, float]
LAYER = "mechanism"
_BLOCK_MM = (10.0, 6.0)
_HATCH_STEP_MM = 1.6
_HATCH_LEN_MM = 2.2


def world_points(solution: Solution) -> dict[str, dict[str, Vec]]:
    """Each solved link's named points in the frame (scene units)."""
    out: dict[str, dict[str, Vec]] = {}
    for link in solution.scene.links:
        pose = solution.pose.links.get(link.name)
        if pose is None and link.name == solution.mechanism.ground:
            out[link.name] = {p.name: p.local for p in link.points}
        elif pose is not None:
            out[link.name] = {p.name: pose.world(p.local) for p in link.points}
    return out


def assur_lines(solution: Solution) -> list[tuple[str, Vec, tuple[Vec, ...]]]:
    """Each triad's Assur point S found on the mechanism, with the points its two leg lines are drawn
    through (a rod's two pins; a block's pin, the line then normal to the slide): only where S lies
    within the mechanism's own extent grown by half its size, so that a far S does not shrink the sheet."""
    points = [p for pts in world_points(solution).values() for p in pts.values()]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    out = []
    for step in solution.steps:
        if step.polygon != "velocity" or step.topic != "assur-point":
            continue
        name = str(step.param("point"))
        at = solution.pose.marks.get(name)
        if at is None or not (min(xs) - size / 2 <= at[0] <= max(xs) + size / 2
                              and min(ys) - size / 2 <= at[1] <= max(ys) + size / 2):
            continue
        through = []
        for which in ("first", "second"):
            params = dict(step.params)
            key = f"{which}_pin" if f"{which}_pin" in params else f"{which}_point"
            through.append(solution.position(str(params[key])))
        out.append((name, at, tuple(through)))
    return out


def mechanism_box(solution: Solution) -> tuple[float, float, float, float]:
    points = [p for pts in world_points(solution).values() for p in pts.values()]
    points += [at for _, at, _ in assur_lines(solution)]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    return (min(xs), min(ys), max(xs), max(ys))


def _slide_direction(solution: Solution, slider: SliderSpec) -> Vec:
    guide = solution.pose.links.get(slider.guide)
    theta = guide.theta if guide is not None else 0.0
    return rotate((1.0, 0.0), theta + slider.angle_rad)


def _hatch(a: Point, b: Point, side: Vec) -> list[Item]:
    """A hatched ground surface along a -> b, its short slanted strokes on ``side`` (a unit normal)."""
    items: list[Item] = [Path((a, b), Stroke("#000000", 0.35), role="frame")]
    length = norm(sub(b, a))
    if length == 0.0:
        return items
    u = scale(1.0 / length, sub(b, a))
    slant = _unit(add(scale(-1.0, u), side))
    for k in range(int((length - 0.3) // _HATCH_STEP_MM) + 1):
        start = add(a, scale(0.3 + k * _HATCH_STEP_MM, u))
        items.append(Path((start, add(start, scale(_HATCH_LEN_MM, slant))), THIN, role="frame hatch"))
    return items


def _unit(v: Vec) -> Vec:
    n = norm(v)
    return (v[0] / n, v[1] / n)


def _ground_pivot(at: Point) -> list[Item]:
    """The frame's pivot symbol under a pin: a triangle standing on a hatched base."""
    r = PIN_RADIUS_MM
    apex = (at[0], at[1] - r)
    left, right = (at[0] - 3.2, at[1] - 5.0), (at[0] + 3.2, at[1] - 5.0)
    items: list[Item] = [Path((apex, left, right), Stroke("#000000", 0.35), fill="#ffffff", closed=True,
                              role="frame pivot")]
    items += _hatch((at[0] - 5.0, at[1] - 5.0), (at[0] + 5.0, at[1] - 5.0), (0.0, -1.0))
    return items


def _block(center: Point, direction: Vec, role: str) -> Path:
    half_l, half_h = _BLOCK_MM[0] / 2, _BLOCK_MM[1] / 2
    n = perp(direction)
    corners = tuple(add(center, add(scale(sx * half_l, direction), scale(sy * half_h, n)))
                    for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)))
    return Path(corners, Stroke("#000000", 0.35), fill="#ffffff", closed=True, role=role)


def block_symbol(center: Point, direction: Vec, role: str) -> Path:
    """A slider's block centred at ``center`` (paper), its long side along ``direction``."""
    return _block(center, direction, role)


def _link_shape(name: str, points: Sequence[Point], index: int) -> list[Item]:
    from shapely.geometry import MultiPoint

    if len(points) < 2:
        return []
    if len(points) == 2:
        return [Path((points[0], points[1]), LINK_STROKE, role=f"link {name}")]
    hull = MultiPoint(list(points)).convex_hull
    # the farthest pair lies on the hull: only its corners are paired (a link of many points stays cheap)
    corners = {(float(x), float(y)) for x, y in getattr(hull, "exterior", hull).coords}
    ends = [p for p in points if (float(p[0]), float(p[1])) in corners]
    ends = ends if len(ends) >= 2 else list(points)
    longest = max(((a, b) for a in ends for b in ends), key=lambda ab: norm(sub(ab[1], ab[0])))
    if hull.geom_type != "Polygon" or hull.area < 0.02 * norm(sub(longest[1], longest[0])) ** 2:
        return [Path(longest, LINK_STROKE, role=f"link {name}")]
    ring = tuple((float(x), float(y)) for x, y in list(hull.exterior.coords)[:-1])
    return [Path(ring, LINK_STROKE, fill=link_color(index), fill_opacity=0.45, closed=True, role=f"link {name}")]


def _free_angle(taken: Sequence[float]) -> float:
    """The direction (radians) farthest from every direction in ``taken``, in steps of 15 degrees."""
    def clearance(angle: float) -> float:
        return min(abs(math.remainder(angle - t, 2 * math.pi)) for t in taken)

    return max((math.radians(15 * k) for k in range(24)), key=clearance)


def _input_arrow(inp: LinkInput, pair: str, panel: Panel, at: Point, taken: Sequence[float]) -> tuple[
        list[Item], list[Request]]:
    """A curved arrow round an input pivot in the sense of omega, labelled omega12 (``pair`` = "12"), clear
    of the links."""
    if inp.omega == 0.0:
        return [], []
    radius = 6.5
    sign = 1.0 if inp.omega > 0 else -1.0
    mid = _free_angle([*taken, -math.pi / 2, -math.pi / 2 + 0.6, -math.pi / 2 - 0.6])
    angles = [mid - sign * math.radians(55) + sign * math.radians(110) * k / 24 for k in range(25)]
    arc = tuple((at[0] + radius * math.cos(a), at[1] + radius * math.sin(a)) for a in angles)
    end = arc[-1]
    tangent = (-math.sin(angles[-1]) * sign, math.cos(angles[-1]) * sign)
    head_start = sub(end, scale(2.2, tangent))
    items: list[Item] = [Path(arc[:-3], Stroke("#000000", 0.3), role="input omega"),
                         Arrow(head_start, end, "#000000", 0.3, 2.2, 0.8, role="input omega head")]
    label = f"ω{pair}"
    runs = _stack_runs("ω", pair)
    request = Request(LAYER, panel.drawing_rect, runs, arc[12], color="#000000", role=f"input {label}", priority=1)
    return items, [request]


def mechanism_items(solution: Solution, panel: Panel) -> tuple[list[Item], list[Request]]:
    """The mechanism's drawn items (links under joints) and its label requests."""
    mech = solution.mechanism
    world = world_points(solution)
    paper = {link: {name: panel.paper(p) for name, p in pts.items()} for link, pts in world.items()}
    items: list[Item] = []
    requests: list[Request] = []
    region = panel.drawing_rect
    order = list(mech.link_names)
    equivalent = set(solution.scene.equivalent_links)  # drawn dashed on the layer higher-pairs
    for link, pts in paper.items():
        if link != mech.ground and link not in equivalent:
            items += _link_shape(link, list(pts.values()), order.index(link))
    # sliders: the guide's slide line, the block on it, and the frame's surface for a fixed guide
    blocks: list[Item] = []
    center = _centroid([p for pts in paper.values() for p in pts.values()])
    for slider in mech.sliders:
        if slider.block not in paper or slider.block in equivalent:
            continue
        at = paper[slider.block][slider.point]
        e = _slide_direction(solution, slider)
        if slider.guide == mech.ground:
            n = perp(e)
            side = n if dot(sub(center, at), n) < 0 else scale(-1.0, n)
            base = add(at, scale(_BLOCK_MM[1] / 2, side))
            a, b = sub(base, scale(_BLOCK_MM[0] * 1.3, e)), add(base, scale(_BLOCK_MM[0] * 1.3, e))
            items += _hatch(a, b, side)
        elif slider.guide in paper:
            guide_pts = list(paper[slider.guide].values())
            through = panel.paper(_guide_point(solution, slider))
            along = [dot(sub(p, through), e) for p in guide_pts if abs(dot(sub(p, through), perp(e))) < 0.5]
            s_block = dot(sub(at, through), e)
            lo = min([*along, s_block - _BLOCK_MM[0], 0.0])
            hi = max([*along, s_block + _BLOCK_MM[0], 0.0])
            items.append(Path((add(through, scale(lo, e)), add(through, scale(hi, e))), LINK_STROKE,
                              role=f"link {slider.guide} slide {slider.name}"))
        blocks.append(_block(at, e, f"block {slider.block}"))
    items += blocks
    if mech.ground in paper:
        for joint in mech.revolutes:
            if mech.ground in joint.links:
                items += _ground_pivot(paper[mech.ground][joint.point])
    joints = {j.point for j in mech.revolutes}
    drawn_points: dict[str, Point] = {}
    for pts in paper.values():
        for name, p in pts.items():
            drawn_points.setdefault(name, p)
    for name, s_world, leg_points in assur_lines(solution):  # the Assur point, where two legs' lines cross
        s_paper = panel.paper(s_world)
        for leg_point in leg_points:
            items.append(Path((panel.paper(leg_point), s_paper), Stroke("#555555", 0.25, (2.0, 1.2)),
                              role=f"assur line {name}"))
        items.append(Circle(s_paper, 0.9, Stroke("#000000", 0.3), fill="#ffffff", role=f"assur point {name}"))
        requests.append(Request(LAYER, region, point_runs(name, LABEL_MM), s_paper, role=f"point {name}", priority=0,
                                gap=PIN_RADIUS_MM))
    for name, p in drawn_points.items():
        if name in joints or any(s.point == name for s in mech.sliders):
            items.append(Circle(p, PIN_RADIUS_MM, Stroke("#000000", 0.3), fill="#ffffff", role=f"joint {name}"))
        else:
            items.append(Circle(p, 0.6, None, fill="#000000", role=f"point {name}"))
        requests.append(Request(LAYER, region, point_runs(name, LABEL_MM), p, role=f"point {name}", priority=0,
                                gap=PIN_RADIUS_MM))
    for link, pts in paper.items():
        if link == mech.ground or link in equivalent:
            continue
        anchor = _link_anchor(list(pts.values()))
        requests.append(Request(LAYER, region, plain_runs(link, LABEL_MM * 0.85), anchor,
                                color=link_label_color(order.index(link)), role=f"link {link}", priority=2, gap=0.8,
                                ring=True, optional=True))
    for drive in mech.drives if mech.ground is not None else ():
        if not isinstance(drive.spec, LinkInput) or drive.base not in paper:
            continue
        pivot = drive.joint.point
        at = paper[drive.base].get(pivot) or paper[drive.moving][pivot]
        taken = [math.atan2(p[1] - at[1], p[0] - at[0]) for link, pts in paper.items() if link != drive.base
                 and pivot in pts for name, p in pts.items() if name != pivot and norm(sub(p, at)) > 0]
        arrow_items, arrow_requests = _input_arrow(drive.spec, f"{drive.base}{drive.moving}", panel, at,
                                                   taken or [0.0])
        items += arrow_items
        requests += arrow_requests
    return items, requests


def _guide_point(solution: Solution, slider: SliderSpec) -> Vec:
    pose = solution.pose.links[slider.guide]
    return pose.world(slider.through)


def _centroid(points: Sequence[Point]) -> Point:
    return (sum(p[0] for p in points) / len(points), sum(p[1] for p in points) / len(points))


def _link_anchor(points: Sequence[Point]) -> Point:
    if len(points) == 2:
        return ((points[0][0] + points[1][0]) / 2, (points[0][1] + points[1][1]) / 2)
    return _centroid(points)


def _stack_runs(base: str, subscript: str) -> tuple[Run, ...]:
    return (Run(base, 0.0, 0.0, LABEL_MM), Run(subscript, text_width(base, LABEL_MM), -0.22 * LABEL_MM, 0.7 * LABEL_MM))
