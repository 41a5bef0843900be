"""Labels placed clear of the drawn geometry and of each other (shapely does the geometry).

A label is tried at candidate places nearest its anchor first: around a point, or beside an
arrow's shaft. A place is taken only when the label's box, grown by a small clearance, touches
no drawn stroke, arrow, circle or label and lies inside the label's region. Light shading
(plates, image triangles) is avoided when possible and allowed when not. When every near place
is taken, the label goes further out with a thin leader line back to its anchor.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from kinepoly.render.primitives import Arrow, Circle, Item, Path, Stroke, Text
from kinepoly.render.text import Run, runs_box

if TYPE_CHECKING:
    from shapely.geometry.base import BaseGeometry

__all__ = ["CLEARANCE_MM", "LEADER", "LabelCache", "Placer", "Request", "fill_geometry", "item_geometry", "place"]

Point = tuple[float, float]
Box = tuple[float, float, float, float]

CLEARANCE_MM = 0.35
"""The least gap kept between a label's box and anything drawn."""
LEADER = Stroke("#555555", 0.13)
_RINGS_MM = (0.5, 1.2, 2.2, 3.5)
_FAR_RINGS_MM = (5.0, 7.5, 10.0, 14.0, 19.0, 25.0, 32.0, 40.0)
_DIRECTIONS_DEG = (45, 135, -45, -135, 0, 180, 90, -90, 22.5, 157.5, -22.5, -157.5, 67.5, 112.5, -67.5, -112.5)


@dataclass(frozen=True)
class Request:
    """A label to place: near ``anchor``, or beside the segment ``anchor`` -> ``end`` when ``end`` is given.

    ``layer`` is where the label goes; ``region`` the rectangle it must stay in; lower
    ``priority`` is placed first.
    """

    layer: str
    region: tuple[float, float, float, float]
    runs: tuple[Run, ...]
    anchor: Point
    end: Point | None = None
    color: str = "#000000"
    role: str = ""
    priority: int = 0
    gap: float = 0.0
    bold: bool = False
    ring: bool = False
    """Draw a thin circle round the label (a link's number), so it does not read as a point's name."""
    optional: bool = False
    """Leave the label out rather than put it where it touches something (a link's number)."""


def item_geometry(item: Item) -> BaseGeometry:
    """What a reader sees of ``item`` as a shapely geometry: strokes with their width, heads, boxes.

    The inside of a filled closed path (light shading) is left out: see ``fill_geometry``.
    """
    from shapely.geometry import LineString, Polygon, box
    from shapely.geometry import Point as ShapelyPoint

    if isinstance(item, Text):
        return box(*item.box)
    if isinstance(item, Arrow):
        shaft = LineString([item.start, item.shaft_end]).buffer(item.width / 2, cap_style="flat")
        return shaft.union(Polygon(item.head))
    if isinstance(item, Circle):
        width = item.stroke.width if item.stroke else 0.0
        disc = ShapelyPoint(item.center).buffer(item.radius + width / 2, quad_segs=8)
        if item.fill is not None or item.stroke is None:
            return disc
        return disc.difference(ShapelyPoint(item.center).buffer(max(item.radius - width / 2, 0.0), quad_segs=8))
    points = list(item.points)
    if item.closed:
        points.append(points[0])
    width = item.stroke.width if item.stroke else 0.0
    if len(points) == 1:
        return ShapelyPoint(points[0]).buffer(max(width / 2, 1e-3))
    return LineString(points).buffer(max(width / 2, 1e-3), cap_style="flat", join_style="mitre")


def fill_geometry(item: Item) -> BaseGeometry | None:
    """The shaded area of a filled closed path, or None."""
    from shapely.geometry import Polygon

    if isinstance(item, Path) and item.closed and item.fill is not None and len(item.points) >= 3:
        return Polygon(item.points).buffer(0)
    return None


def _pushed_box(anchor: Point, direction: Point, size: tuple[float, float], gap: float) -> Box:
    """The box of a label moved from ``anchor`` along the unit ``direction`` until it is ``gap`` away from it.

    With the box's centre at anchor + t u and half sizes (a, b), its distance from the anchor is
    hypot(max(|ux| t - a, 0), max(|uy| t - b, 0)); the least t at which that reaches ``gap``.
    """
    a, b = size[0] / 2, size[1] / 2
    ux, uy = abs(direction[0]), abs(direction[1])
    candidates = []
    if ux > 1e-12 and uy * (a + gap) / ux <= b + 1e-12:
        candidates.append((a + gap) / ux)
    if uy > 1e-12 and ux * (b + gap) / uy <= a + 1e-12:
        candidates.append((b + gap) / uy)
    p = a * ux + b * uy
    q = a * a + b * b - gap * gap
    if p * p - q >= 0.0:
        t = p + math.sqrt(p * p - q)
        if ux * t >= a - 1e-12 and uy * t >= b - 1e-12:
            candidates.append(t)
    t = min(candidates) if candidates else gap + a + b
    cx, cy = anchor[0] + direction[0] * t, anchor[1] + direction[1] * t
    return (cx - a, cy - b, cx + a, cy + b)


class _Placed:
    """The geometries placed so far (labels, leaders), found by a grid of cells: only near ones are tested."""

    _CELL_MM = 8.0

    def __init__(self) -> None:
        self.geometries: list[Any] = []
        self._cells: dict[tuple[int, int], list[int]] = {}

    def _keys(self, bounds: Box) -> Iterable[tuple[int, int]]:
        c = self._CELL_MM
        for i in range(math.floor(bounds[0] / c), math.floor(bounds[2] / c) + 1):
            for j in range(math.floor(bounds[1] / c), math.floor(bounds[3] / c) + 1):
                yield (i, j)

    def append(self, geometry: Any) -> None:
        index = len(self.geometries)
        self.geometries.append(geometry)
        for key in self._keys(geometry.bounds):
            self._cells.setdefault(key, []).append(index)

    def extend(self, geometries: Iterable[Any]) -> None:
        for geometry in geometries:
            self.append(geometry)

    def touches(self, geometry: Any) -> bool:
        """Whether ``geometry`` intersects any placed geometry."""
        x0, y0, x1, y1 = geometry.bounds
        seen: set[int] = set()
        for key in self._keys((x0, y0, x1, y1)):
            for index in self._cells.get(key, ()):
                if index in seen:
                    continue
                seen.add(index)
                g = self.geometries[index]
                b = g.bounds
                if b[0] <= x1 and b[2] >= x0 and b[1] <= y1 and b[3] >= y0 and geometry.intersects(g):
                    return True
        return False

    def __len__(self) -> int:
        return len(self.geometries)


class Placer:
    """Places labels one after another in one region, avoiding what is drawn and what is placed."""

    def __init__(self, region: Box, drawn: Iterable[Item], placed: _Placed | None = None,
                 geometries: tuple[list[Any], list[Any]] | None = None) -> None:
        from shapely import STRtree

        self.region = region
        if geometries is None:
            items = list(drawn)
            self._hard: list[Any] = [item_geometry(item) for item in items]
            self._soft: list[Any] = [g for g in (fill_geometry(item) for item in items) if g is not None]
        else:
            self._hard, self._soft = geometries
        self._hard_tree = STRtree(self._hard)
        self._soft_tree = STRtree(self._soft)
        self._placed = placed if placed is not None else _Placed()

    def _inside(self, b: Box) -> bool:
        x0, y0, x1, y1 = self.region
        return b[0] >= x0 and b[1] >= y0 and b[2] <= x1 and b[3] <= y1

    def _free(self, b: Box, avoid_fill: bool) -> bool:
        from shapely.geometry import box

        if not self._inside(b):
            return False
        grown = box(b[0] - CLEARANCE_MM, b[1] - CLEARANCE_MM, b[2] + CLEARANCE_MM, b[3] + CLEARANCE_MM)
        if len(self._hard_tree.query(grown, predicate="intersects")):
            return False
        if avoid_fill and len(self._soft_tree.query(grown, predicate="intersects")):
            return False
        return not self._placed.touches(grown)

    def _leader_ok(self, line: Any) -> bool:
        return not self._placed.touches(line)

    def block(self, item: Item) -> None:
        """Treat ``item`` as drawn from now on (something added after the labels started)."""
        self._placed.append(item_geometry(item))

    def _text(self, b: Box, runs: tuple[Run, ...], color: str, role: str, anchor: Point, bold: bool) -> Text:
        x0, y0, _, _ = runs_box(runs, bold)
        return Text(b[0] - x0, b[1] - y0, runs, color, role, anchor, bold)

    def _accept(self, b: Box, runs: tuple[Run, ...], color: str, role: str, anchor: Point,
                bold: bool, leader: Any = None) -> list[Item]:
        from shapely.geometry import box

        self._placed.append(box(*b))
        text = self._text(b, runs, color, role, anchor, bold)
        if leader is None:
            return [text]
        self._placed.append(leader.buffer(LEADER.width / 2))
        points = tuple((float(x), float(y)) for x, y in leader.coords)
        return [Path(points, LEADER, role=f"leader {role}"), text]

    def _near(self, candidates: Sequence[Box]) -> Box | None:
        for avoid_fill in (True, False):
            for b in candidates:
                if self._free(b, avoid_fill):
                    return b
        return None

    def _far(self, runs: tuple[Run, ...], color: str, role: str, anchor: Point, bold: bool,
             size: tuple[float, float], shift: Point, optional: bool = False) -> list[Item]:
        from shapely.geometry import LineString, box
        from shapely.ops import nearest_points

        for ring in _FAR_RINGS_MM:
            for angle in _DIRECTIONS_DEG:
                u = (math.cos(math.radians(angle)), math.sin(math.radians(angle)))
                b = _pushed_box(anchor, u, size, ring)
                if not self._free(b, False):
                    continue
                near = nearest_points(box(*b), _point(anchor))[0]
                length = math.hypot(near.x - anchor[0], near.y - anchor[1])
                if length <= 0.6:
                    continue
                k = (length - 0.3) / length
                start = (anchor[0] + shift[0], anchor[1] + shift[1])
                end = (anchor[0] + k * (near.x - anchor[0]), anchor[1] + k * (near.y - anchor[1]))
                leader = LineString([start, end])
                if self._leader_ok(leader.buffer(LEADER.width / 2)):
                    return self._accept(b, runs, color, role, anchor, bold, leader)
        if optional:
            return []
        # Nowhere free within reach: keep the nearest place inside the region (the overlap test reports it).
        b = _pushed_box(anchor, (1.0, 0.0), size, _RINGS_MM[0])
        return self._accept(b, runs, color, role, anchor, bold)

    def at_point(self, anchor: Point, runs: tuple[Run, ...], color: str = "#000000", role: str = "",
                 bold: bool = False, gap: float = 0.0, ring: bool = False, optional: bool = False) -> list[Item]:
        """A label near a point (a joint, a tip): the nearest free place around it."""
        x0, y0, x1, y1 = runs_box(runs, bold)
        size = (x1 - x0, y1 - y0)
        radius = math.hypot(*size) / 2 + 0.35
        outer = (2 * radius, 2 * radius) if ring else size
        candidates = []
        for distance in _RINGS_MM:
            for angle in _DIRECTIONS_DEG:
                u = (math.cos(math.radians(angle)), math.sin(math.radians(angle)))
                candidates.append(_pushed_box(anchor, u, outer, gap + distance))
        found = self._near(candidates)
        if found is None:
            items = self._far(runs, color, role, anchor, bold, outer, (0.0, 0.0), optional)
            if not items:
                return []
            corner = _box_of(items)
            found = (corner[0], corner[1], corner[0] + outer[0], corner[1] + outer[1])
        else:
            items = self._accept(found, runs, color, role, anchor, bold)
        if not ring:
            return items
        cx, cy = (found[0] + found[2]) / 2, (found[1] + found[3]) / 2
        text = items[-1]
        assert isinstance(text, Text)
        centred = Text(cx - (x0 + x1) / 2, cy - (y0 + y1) / 2, text.runs, text.color, text.role, text.anchor, bold)
        return [*items[:-1], Circle((cx, cy), radius, Stroke(color, 0.18), role=f"ring {role}"), centred]

    def along(self, start: Point, end: Point, runs: tuple[Run, ...], color: str = "#000000",
              role: str = "") -> list[Item]:
        """A label beside a vector's shaft, either side, near its middle first."""
        x0, y0, x1, y1 = runs_box(runs)
        size = (x1 - x0, y1 - y0)
        length = math.hypot(end[0] - start[0], end[1] - start[1])
        if length == 0.0:
            return self.at_point(start, runs, color, role)
        ux, uy = (end[0] - start[0]) / length, (end[1] - start[1]) / length
        candidates = []
        for ring in _RINGS_MM[:3]:
            for t in (0.5, 0.38, 0.62, 0.26, 0.74, 0.15, 0.85):
                at = (start[0] + t * (end[0] - start[0]), start[1] + t * (end[1] - start[1]))
                for side in (1.0, -1.0):
                    candidates.append(_pushed_box(at, (-side * uy, side * ux), size, ring))
        found = self._near(candidates)
        if found is not None:
            return self._accept(found, runs, color, role, _mid(start, end), False)
        return self._far(runs, color, role, _mid(start, end), False, size, (0.0, 0.0))


def _mid(a: Point, b: Point) -> Point:
    return ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)


def _point(p: Point) -> Any:
    from shapely.geometry import Point as ShapelyPoint

    return ShapelyPoint(p)


class LabelCache:
    """What the sheets of one layout (a handout's pages, a drawing's step sheets) share in placing labels.

    The geometry of each drawn item is made once; a region's labels are placed once and reused on
    every later sheet whose requests in that region, and drawn items near it, are the same (the
    mechanism, the circle diagram: the fixed parts), so a page places only what changed (the
    polygons up to its step). A region's labels are kept only when they lie clear of its edges and
    of every other region's labels: then nothing outside the region could have moved them.
    """

    def __init__(self) -> None:
        self._geometry: dict[Item, tuple[Any, Any, Box]] = {}
        self._regions: dict[tuple[Any, ...], tuple[list[tuple[str, list[Item]]], list[Any]]] = {}

    def geometry(self, item: Item) -> tuple[Any, Any, Box]:
        """The item's hard geometry, its shading (or None) and the hard geometry's bounds."""
        found = self._geometry.get(item)
        if found is None:
            hard = item_geometry(item)
            found = self._geometry[item] = (hard, fill_geometry(item), tuple(hard.bounds))
        return found


def _near_region(bounds: Box, region: Box, margin: float) -> bool:
    return (bounds[0] <= region[2] + margin and bounds[2] >= region[0] - margin
            and bounds[1] <= region[3] + margin and bounds[3] >= region[1] - margin)


def _well_inside(bounds: Box, region: Box, margin: float) -> bool:
    return (bounds[0] > region[0] + margin and bounds[1] > region[1] + margin
            and bounds[2] < region[2] - margin and bounds[3] < region[3] - margin)


def place(requests: Sequence[Request], drawn: Iterable[Item], cache: LabelCache | None = None) -> dict[str, list[Item]]:
    """Place every request (by priority, then in the given order), each in its region; items per layer.

    A region's labels avoid the drawn items near the region (nothing further can touch a label
    inside it) and the labels placed before them in any region. With ``cache`` shared by the
    sheets of one layout, a region whose requests and nearby drawing are as on an earlier sheet
    gets that sheet's labels again without placing them anew: the same result, placed once.
    """
    cache = cache if cache is not None else LabelCache()
    drawn = list(drawn)
    geometry = [cache.geometry(item) for item in drawn]
    ordered = sorted(requests, key=lambda r: r.priority)
    by_region: dict[Box, list[Request]] = {}
    for request in ordered:
        by_region.setdefault(request.region, []).append(request)
    margin = CLEARANCE_MM + 1e-6
    near: dict[Box, list[int]] = {region: [k for k, g in enumerate(geometry) if _near_region(g[2], region, margin)]
                                  for region in by_region}
    keys = {region: (region, tuple(reqs), tuple(drawn[k] for k in near[region])) for region, reqs in by_region.items()}
    shared = _Placed()
    out: dict[str, list[Item]] = {}
    reused = {region for region in by_region if keys[region] in cache._regions}
    for region in reused:
        _, placed = cache._regions[keys[region]]
        shared.extend(placed)
    placers: dict[Box, Placer] = {}
    made: dict[Box, list[tuple[str, list[Item]]]] = {}
    made_geometry: dict[Box, list[Any]] = {}
    for request in ordered:
        region = request.region
        if region in reused:
            continue
        placer = placers.get(region)
        if placer is None:
            hard = [geometry[k][0] for k in near[region]]
            soft = [geometry[k][1] for k in near[region] if geometry[k][1] is not None]
            placer = placers[region] = Placer(region, (), shared, (hard, soft))
            made[region], made_geometry[region] = [], []
        before = len(shared)
        if request.end is None:
            items = placer.at_point(request.anchor, request.runs, request.color, request.role, request.bold,
                                    request.gap, request.ring, request.optional)
        else:
            items = placer.along(request.anchor, request.end, request.runs, request.color, request.role)
        made[region].append((request.layer, items))
        made_geometry[region] += shared.geometries[before:]
    for region in placers:
        own = made_geometry[region]
        mine = {id(g) for g in own}
        others = [g for g in shared.geometries if id(g) not in mine]
        if all(_well_inside(tuple(g.bounds), region, margin) for g in own) and \
                not any(_near_region(tuple(g.bounds), region, margin) for g in others):
            cache._regions[keys[region]] = (made[region], own)
    results = {region: cache._regions[keys[region]][0] for region in reused} | made
    # the layers' items in the order of the requests, as placed one after another
    counters = dict.fromkeys(results, 0)
    for request in ordered:
        k = counters[request.region]
        layer, items = results[request.region][k]
        counters[request.region] = k + 1
        out.setdefault(layer, []).extend(items)
    return out


def _box_of(items: list[Item]) -> Box:
    """The placed box of a label accepted by ``_accept`` (the last item is its text)."""
    text = items[-1]
    assert isinstance(text, Text)
    return text.box
