"""The ``instant-centers`` layer: the instant centers on the mechanism and the circle diagram beside it.

The sheet always has this layer; it stays empty unless the scene asks for instant centers.
Centers are labelled points (I13); the Kennedy lines of each derived center are drawn thin and
dotted through the two centers that make them; a center at infinity is an arrow toward it at the
panel's edge (``I16 ∞``), and so is a center too far away to draw at the mechanism's scale,
labelled with its coordinates. A cam pair's common normal, the line its center was found on, is
drawn as a Kennedy line from the contact through the center. The circle diagram shows the links on
a circle, the joints' centers as solid edges and the derived ones dashed, numbered in the order they
were found; a cam pair's line edge (known at once as its common normal) dash-dot, numbered when its
point was found.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from kinepoly.geom.tolerances import BOX_FLOOR, PARALLEL_SIN
from kinepoly.geom.vec import Vec, norm, sub
from kinepoly.render.labels import Request
from kinepoly.render.layout import Content, Panel
from kinepoly.render.primitives import Arrow, Circle, Item, Path, Stroke
from kinepoly.render.style import LABEL_MM, SMALL_MM, link_label_color
from kinepoly.render.text import Run, plain_runs, text_width
from kinepoly.solution import Solution

if TYPE_CHECKING:
    from kinepoly.engine.centers import InstantCenters

__all__ = ["LAYER", "centers_content", "centers_items", "centers_of", "near_centers"]

LAYER = "instant-centers"
CENTER_COLOR = "#7b2cbf"
KENNEDY = Stroke("#9d7cc9", 0.15, (0.6, 0.8))
LINE_EDGE = Stroke(CENTER_COLOR, 0.3, (2.4, 0.7, 0.4, 0.7))
"""A line edge of the circle diagram (a cam pair's center, known at once as a line): dash-dot."""
DIAGRAM_SCALE_MM = 22.0
"""The circle diagram's radius on paper."""
_NEAR = 0.6
"""A center is drawn in place when it lies within this many mechanism sizes of the mechanism."""


def centers_of(solution: Solution) -> InstantCenters | None:
    """The solution's instant centers, when the scene asks for them."""
    if not solution.scene.find.instant_centers:
        return None
    return solution.centers


def near_centers(solution: Solution, box: tuple[float, float, float, float]) -> list[Vec]:
    """Positions of the centers close enough to the mechanism's box to be drawn at its scale."""
    centers = centers_of(solution)
    if centers is None:
        return []
    size = max(box[2] - box[0], box[3] - box[1], BOX_FLOOR)
    out = []
    for center in centers.centers.values():
        p = center.position
        if p is not None and box[0] - _NEAR * size <= p[0] <= box[2] + _NEAR * size \
                and box[1] - _NEAR * size <= p[1] <= box[3] + _NEAR * size:
            out.append(p)
    return out


def centers_content(solution: Solution) -> Content | None:
    """Room for the circle diagram beside the mechanism, or None when no centers are asked."""
    if centers_of(solution) is None:
        return None
    return Content("centers", (-1.0, -1.0, 1.0, 1.0), DIAGRAM_SCALE_MM, 9.0)


def _runs(name: str, suffix: str = "") -> tuple[Run, ...]:
    runs: tuple[Run, ...] = (Run("I", 0.0, 0.0, LABEL_MM),
                             Run(name, text_width("I", LABEL_MM), -0.22 * LABEL_MM, 0.7 * LABEL_MM))
    if suffix:
        x = text_width("I", LABEL_MM) + text_width(name, 0.7 * LABEL_MM) + 0.4
        runs = (*runs, Run(suffix, x, 0.0, SMALL_MM))
    return runs


def _inside(rect: tuple[float, float, float, float], p: Vec, margin: float = 0.0) -> bool:
    return rect[0] + margin <= p[0] <= rect[2] - margin and rect[1] + margin <= p[1] <= rect[3] - margin


def _edge_arrow(panel: Panel, toward: Vec, name: str, note: str) -> tuple[list[Item], list[Request]]:
    """An arrow at the panel's edge pointing along ``toward`` (a direction), labelled."""
    x0, y0, x1, y1 = panel.drawing_rect
    center = ((x0 + x1) / 2, (y0 + y1) / 2)
    u = (toward[0] / norm(toward), toward[1] / norm(toward))
    reach = min((((x1 - 6.0) - center[0]) / u[0] if u[0] > PARALLEL_SIN else ((x0 + 6.0) - center[0]) / u[0]
                 if u[0] < -PARALLEL_SIN else math.inf),
                (((y1 - 6.0) - center[1]) / u[1] if u[1] > PARALLEL_SIN else ((y0 + 6.0) - center[1]) / u[1]
                 if u[1] < -PARALLEL_SIN else math.inf))
    end = (center[0] + reach * u[0], center[1] + reach * u[1])
    start = (end[0] - 9.0 * u[0], end[1] - 9.0 * u[1])
    arrow = Arrow(start, end, CENTER_COLOR, 0.3, 2.4, 0.8, role=f"center I{name} toward")
    request = Request(LAYER, panel.drawing_rect, _runs(name, note), start, color=CENTER_COLOR,
                      role=f"center I{name}", priority=1, gap=0.8)
    return [arrow], [request]


def _mechanism_part(centers: InstantCenters, panel: Panel) -> tuple[list[Item], list[Request]]:
    items: list[Item] = []
    requests: list[Request] = []
    rect = panel.drawing_rect
    shown = {name for _, name in centers.asked} | {s.center for s in centers.steps}
    from shapely.geometry import LineString, box

    area = box(*rect)
    for step in centers.steps:
        for line in step.lines:
            if line.through is None or line.direction is None:
                continue
            anchors = line.points[:1] if line.is_common_normal else line.points  # a normal: from its contact
            ends = [panel.paper((t[0] / t[2], t[1] / t[2])) for t in (*anchors, step.result)
                    if abs(t[2]) > PARALLEL_SIN]
            d = line.direction
            a = panel.paper(line.through)
            u = (d[0] / norm(d), d[1] / norm(d))
            along = [(p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1] for p in ends] or [0.0]
            far = 4.0 * max(rect[2] - rect[0], rect[3] - rect[1])
            lo = min(along) - 5.0 if all(abs(t[2]) > PARALLEL_SIN for t in anchors) else -far
            hi = max(along) + 5.0 if all(abs(t[2]) > PARALLEL_SIN for t in (*anchors, step.result)) else far
            piece = LineString([(a[0] + lo * u[0], a[1] + lo * u[1]), (a[0] + hi * u[0], a[1] + hi * u[1])])
            clipped = piece.intersection(area)
            if clipped.geom_type == "LineString" and clipped.length > 0.5:
                coords = list(clipped.coords)
                items.append(Path(((coords[0][0], coords[0][1]), (coords[-1][0], coords[-1][1])), KENNEDY,
                                  role=f"kennedy {line.label}"))
    for name, center in centers.centers.items():
        if name not in shown:
            continue
        if center.position is None:
            assert center.direction is not None
            more_items, more_requests = _edge_arrow(panel, center.direction, name, "∞")
        else:
            p = panel.paper(center.position)
            if _inside(rect, p, 1.0):
                items.append(Circle(p, 0.7, Stroke(CENTER_COLOR, 0.25), fill="#ffffff", role=f"center I{name}"))
                requests.append(Request(LAYER, rect, _runs(name), p, color=CENTER_COLOR, role=f"center I{name}",
                                        priority=1, gap=0.8))
                continue
            x, y = center.position
            more_items, more_requests = _edge_arrow(panel, sub(p, panel.paper(_middle(panel))), name,
                                                    f"({x:.1f}, {y:.1f})")
        items += more_items
        requests += more_requests
    return items, requests


def _middle(panel: Panel) -> Vec:
    x0, y0, x1, y1 = panel.drawing_rect
    return ((((x0 + x1) / 2) - panel.origin[0]) / panel.scale, (((y0 + y1) / 2) - panel.origin[1]) / panel.scale)


def _diagram_part(centers: InstantCenters, panel: Panel, order: tuple[str, ...]) -> tuple[list[Item], list[Request]]:
    items: list[Item] = []
    requests: list[Request] = []
    diagram = centers.diagram
    at = {link: panel.paper(p) for link, p in diagram.on_circle.items()}
    for e in diagram.edges:
        a, b = at[e.links[0]], at[e.links[1]]
        stroke = {"joint": Stroke("#333333", 0.3), "line": LINE_EDGE}.get(e.kind, Stroke(CENTER_COLOR, 0.3, (1.2, 0.8)))
        items.append(Path((a, b), stroke, role=f"diagram edge {e.name}"))
        if e.number > 0:
            mid = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
            requests.append(Request(LAYER, panel.drawing_rect, plain_runs(str(e.number), SMALL_MM), mid,
                                    color=CENTER_COLOR, role=f"diagram number {e.name}", priority=6, gap=0.3,
                                    optional=True))
    for link, p in at.items():
        index = order.index(link) if link in order else 0
        items.append(Circle(p, 0.8, Stroke("#000000", 0.25), fill="#ffffff", role=f"diagram link {link}"))
        requests.append(Request(LAYER, panel.drawing_rect, plain_runs(link, LABEL_MM), p,
                                color=link_label_color(index), role=f"diagram link {link}", priority=1, gap=0.9))
    return items, requests


def centers_items(solution: Solution, mechanism: Panel, diagram: Panel | None) -> tuple[list[Item], list[Request]]:
    """The centers on the mechanism's panel and the circle diagram on its own panel (empty when not asked)."""
    centers = centers_of(solution)
    if centers is None:
        return [], []
    items, requests = _mechanism_part(centers, mechanism)
    if diagram is not None:
        more_items, more_requests = _diagram_part(centers, diagram, solution.mechanism.link_names)
        items += more_items
        requests += more_requests
    return items, requests
