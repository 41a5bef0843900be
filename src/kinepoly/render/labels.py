"""Labels placed clear of the drawn geometry and of each other (shapely does the geometry).

A label is tried at candidate places nearest its anchor first: around a point, or beside an
arrow's shaft. A place is taken only when the label's box, grown by a small clearance, touches
no drawn stroke, arrow, circle or label and lies inside the label's region. Light shading
(plates, image triangles) is avoided when possible and allowed when not. When every near place
is taken, the label goes further out with a thin leader line back to its anchor. Where no place within
reach is free of the drawing (many tips and short vectors in a small spot of a polygon), the label is
still kept clear of every other label: it takes the place, near or out on a leader (from its point, or
from a point along its vector's shaft), under which the least ink lies, and counts as crowded when that
is not none. Where the other labels wall in every such place (or every leader to it), the places tried lie
on a grid over the whole region, their leaders from the point or from the shaft's nearest point.

On an animation's frames a label is tried first where it was on the frame before (``LabelCache.hints``): at the
same place beside its point or along its arrow, else at the free place there nearest it; a label that was set out
goes back beside its point where a place there is free, and else out on the same leader. Labels move with their
points instead of jumping about.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from msgspec import Struct
from msgspec.structs import replace

from kinepoly.geom.tolerances import PAPER_EXACT_MM, PAPER_SAME_MM, PARALLEL_SIN
from kinepoly.render.primitives import Arrow, Circle, Item, Path, Stroke, Text
from kinepoly.render.text import Run, runs_box, text_width

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt
    from shapely.geometry.base import BaseGeometry

__all__ = ["BACKGROUND_ROLES", "CLEARANCE_MM", "FEW", "LEADER", "Hint", "LabelCache", "Placer", "Request",
           "draft_place", "fill_geometry", "item_geometry", "place", "wrapped"]

Point = tuple[float, float]
Box = tuple[float, float, float, float]
Hint = tuple[str, int]
"""Where a label was put on an animation's frame before (``LabelCache.hints``): ``("near", k)``, the k-th of its
places near its anchor, or ``("far", k)``, the k-th of its far rings' places, with a leader (``Placer.taken``)."""

CLEARANCE_MM = 0.35
"""The least gap kept between a label's box and anything drawn."""
LEADER = Stroke("#555555", 0.13)
_RINGS_MM = (0.5, 1.2, 2.2, 3.5)
_LEADER_FREE_MM = 2.0
"""Near its anchor a leader may cross what is drawn there (the pin, the shaft it names)."""
_FAR_RINGS_MM = (5.0, 7.5, 10.0, 14.0, 19.0, 25.0, 32.0, 40.0)
_DIRECTIONS_DEG = (45, 135, -45, -135, 0, 180, 90, -90, 22.5, 157.5, -22.5, -157.5, 67.5, 112.5, -67.5, -112.5)
_DIRECTIONS = tuple((math.cos(math.radians(angle)), math.sin(math.radians(angle))) for angle in _DIRECTIONS_DEG)
_ALONG_T = (0.5, 0.38, 0.62, 0.26, 0.74, 0.15, 0.85)
"""Where along a vector's shaft its label is tried, the middle first."""
_FURTHEST_RINGS_MM = (50.0, 62.0, 76.0, 92.0, 110.0)
"""Where no place within the far rings is clear of the other labels: further out, a longer leader (the region bounds
them)."""
_LEADER_INK_MM2 = 0.02
"""Where every place within reach lies on something drawn: how much ink under a label (mm²) one mm less of leader
is worth (``Placer._least_inked``)."""
_FAR_RING_GROUPS = (_FAR_RINGS_MM[:2], _FAR_RINGS_MM[2:4], _FAR_RINGS_MM[4:])
"""The far rings in the groups tested together: a label that finds a place near stops the search there."""
_SEARCH_BUDGET = 1000
"""The most tests one label's search may make (``_Placed.scanned``: places tried and placed geometries looked
at) before it takes the nearest place, crowded. The examples' drawings and handouts make at most about 430 per
label, 500 points on one coupler 1,900; 2,000 points in a 6 mm square made 17,000 each."""


class Request(Struct, frozen=True, cache_hash=True):
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

    The inside of a lightly shaded closed path (plates, image triangles) is left out: see
    ``fill_geometry``; an opaque one (a pivot's triangle, a slider's block) is whole.
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
    width = item.stroke.width if item.stroke else 0.0
    if item.closed and item.fill is not None and item.fill_opacity >= 1.0 and len(points) >= 3:
        # an opaque symbol (a pivot's triangle, a slider's block): its whole area, not only its outline
        return Polygon(points).buffer(max(width / 2, 1e-3), join_style="mitre")
    if item.closed:
        points.append(points[0])
    if len(points) == 1:
        return ShapelyPoint(points[0]).buffer(max(width / 2, 1e-3))
    return LineString(points).buffer(max(width / 2, 1e-3), cap_style="flat", join_style="mitre")


_PIECE_MM = 2.5
"""Strokes are tested against labels in pieces no longer than this: a piece's bounding box hugs it, so a
label's box meets the boxes of the strokes that pass near it only, not of every long one around it."""


def item_pieces(item: Item) -> list[BaseGeometry]:
    """``item_geometry`` as the union of small pieces: a stroke's segments cut every ``_PIECE_MM`` (with a
    small disc at each corner), an arrow's shaft so cut and its head; any other item whole."""
    import numpy as np
    import shapely

    heads: list[BaseGeometry] = []
    if isinstance(item, Arrow):
        if item.length == 0.0:
            return [item_geometry(item)]
        points, half, closed = [item.start, item.shaft_end], item.width / 2, False
        heads.append(shapely.Polygon(item.head))
    elif isinstance(item, Path) and len(item.points) >= 2 and not (item.closed and item.fill is not None
                                                                    and item.fill_opacity >= 1.0):
        width = item.stroke.width if item.stroke else 0.0
        points, half, closed = list(item.points), max(width / 2, 1e-3), item.closed
    else:
        return [item_geometry(item)]
    ends = np.asarray(points + ([points[0]] if closed else []), dtype=float)
    pieces = []
    for a, b in itertools.pairwise(ends):
        t = np.linspace(0.0, 1.0, max(1, math.ceil(math.hypot(*(b - a)) / _PIECE_MM)) + 1)[:, None]
        cuts = a + t * (b - a)
        pieces.append(np.stack([cuts[:-1], cuts[1:]], axis=1))
    lines = shapely.linestrings(np.concatenate(pieces))
    corners = ends[1:-1] if not closed else ends[:-1]
    discs = shapely.buffer(shapely.points(corners), half, quad_segs=2) if len(corners) else []
    return [*shapely.buffer(lines, half, cap_style="flat"), *discs, *heads]


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
    t = _push(abs(direction[0]), abs(direction[1]), a, b, gap)
    cx, cy = anchor[0] + direction[0] * t, anchor[1] + direction[1] * t
    return (cx - a, cy - b, cx + a, cy + b)


@functools.lru_cache(maxsize=4096)
def _push(ux: float, uy: float, a: float, b: float, gap: float) -> float:
    """How far ``_pushed_box`` moves a box of half sizes (a, b) along (ux, uy) (both >= 0); the same few labels
    and directions come again and again, so it is kept."""
    candidates = []
    if ux > PARALLEL_SIN and uy * (a + gap) / ux <= b + PAPER_EXACT_MM:
        candidates.append((a + gap) / ux)
    if uy > PARALLEL_SIN and ux * (b + gap) / uy <= a + PAPER_EXACT_MM:
        candidates.append((b + gap) / uy)
    p = a * ux + b * uy
    q = a * a + b * b - gap * gap
    if p * p - q >= 0.0:
        t = p + math.sqrt(p * p - q)
        if ux * t >= a - PAPER_EXACT_MM and uy * t >= b - PAPER_EXACT_MM:
            candidates.append(t)
    return min(candidates) if candidates else gap + a + b


class _Placed:
    """The geometries placed so far (labels, leaders), found by a grid of cells: only near ones are tested.

    A label's geometry is its box (a ring's too: the box round it); a leader's is its line with its width."""

    _CELL_MM = 8.0

    def __init__(self) -> None:
        self.geometries: list[Any] = []
        self._bounds: list[Box] = []
        self._cells: dict[tuple[int, int], list[int]] = {}
        self._leaders: set[int] = set()
        self.scanned = 0
        """How many times ``touches`` was asked and placed geometries it looked at: the label search's cost."""

    def _keys(self, bounds: Box) -> Iterable[tuple[int, int]]:
        c = self._CELL_MM
        for i in range(math.floor(bounds[0] / c), math.floor(bounds[2] / c) + 1):
            for j in range(math.floor(bounds[1] / c), math.floor(bounds[3] / c) + 1):
                yield (i, j)

    def append(self, geometry: Any, leader: bool = False, bounds: Box | None = None) -> None:
        index = len(self.geometries)
        if leader:
            self._leaders.add(index)
        self.geometries.append(geometry)
        bounds = bounds if bounds is not None else tuple(geometry.bounds)
        self._bounds.append(bounds)
        c, cells = self._CELL_MM, self._cells
        rows = range(math.floor(bounds[1] / c), math.floor(bounds[3] / c) + 1)
        for i in range(math.floor(bounds[0] / c), math.floor(bounds[2] / c) + 1):  # the cells of ``_keys``
            for j in rows:
                found = cells.get((i, j))
                if found is None:
                    cells[i, j] = [index]
                else:
                    found.append(index)

    def add(self, placed: Placed) -> None:
        """A placed label's geometries: its box (with its ring), then its leader if it has one."""
        _, items, geometries, bounds = placed
        has_leader = any(isinstance(item, Path) and item.role.startswith("leader ") for item in items)
        for k, (geometry, box) in enumerate(zip(geometries, bounds, strict=True)):
            self.append(geometry, has_leader and k == 1, box)

    def touches(self, geometry: Any, labels_only: bool = False, distance: float = 0.0, box: bool = False) -> bool:
        """Whether ``geometry`` comes within ``distance`` of any placed geometry (``labels_only``: of any placed
        label, leaders aside). ``box``: ``geometry`` is a box (a rectangle along the axes); a placed label is one
        too, so it meets the label where their bounds meet, with no further test."""
        import shapely

        x0, y0, x1, y1 = geometry.bounds
        x0, y0, x1, y1 = x0 - distance, y0 - distance, x1 + distance, y1 + distance
        c, cells, all_bounds, leaders = self._CELL_MM, self._cells, self._bounds, self._leaders
        scanned = self.scanned + 1
        seen: set[int] = set()
        rows = range(math.floor(y0 / c), math.floor(y1 / c) + 1)
        try:
            for i in range(math.floor(x0 / c), math.floor(x1 / c) + 1):  # the cells of ``_keys``, in its order
                for j in rows:
                    for index in cells.get((i, j), ()):
                        if index in seen or (labels_only and index in leaders):
                            continue
                        seen.add(index)
                        scanned += 1
                        b = all_bounds[index]
                        if b[0] <= x1 and b[2] >= x0 and b[1] <= y1 and b[3] >= y0:
                            if box and distance <= 0.0 and index not in leaders:
                                return True
                            g = self.geometries[index]
                            if geometry.intersects(g) if distance <= 0.0 else shapely.dwithin(geometry, g, distance):
                                return True
            return False
        finally:
            self.scanned = scanned

    def near(self, bounds: Box, distance: float = 0.0) -> list[int]:
        """The indexes of the placed geometries whose bounds come within ``distance`` of ``bounds``; counted in
        ``scanned`` as looked at."""
        x0, y0, x1, y1 = bounds[0] - distance, bounds[1] - distance, bounds[2] + distance, bounds[3] + distance
        found: set[int] = set()
        for key in self._keys((x0, y0, x1, y1)):
            for index in self._cells.get(key, ()):
                b = self._bounds[index]
                if b[0] <= x1 and b[2] >= x0 and b[1] <= y1 and b[3] >= y0:
                    found.add(index)
        self.scanned += len(found)
        return sorted(found)

    def is_leader(self, index: int) -> bool:
        return index in self._leaders

    def __len__(self) -> int:
        return len(self.geometries)

    def copy(self) -> _Placed:
        other = _Placed()
        other.geometries = list(self.geometries)
        other._bounds = list(self._bounds)
        other._cells = {key: list(indexes) for key, indexes in self._cells.items()}
        other._leaders = set(self._leaders)
        return other


class Placer:
    """Places labels one after another in one region, avoiding what is drawn and what is placed."""

    _candidates: int | None = None
    """How many of a label's near places are made, nearest first (None: all)."""
    _tested: tuple[Sequence[Box], Any, set[int]] | None = None
    """The boxes ``_free_of`` tested last against the drawing, grown by the clearance, and those that touch it."""

    def __init__(self, region: Box, hard: list[Any], soft: list[Any], placed: _Placed) -> None:
        """``hard``: what is drawn near the region (``item_pieces``), which a label may not touch; ``soft``: the
        light shading there, which it avoids where it can; ``placed``: the labels placed so far."""
        import numpy as np
        import shapely
        from shapely import STRtree

        self.region = region
        self._hard, self._soft = hard, soft
        self._hard_tree = STRtree(self._hard)
        self._hard_array = np.asarray(self._hard, dtype=object).reshape(-1)
        self._hard_bounds = shapely.bounds(self._hard_array).reshape(-1, 4)
        self._hard_areas = shapely.area(self._hard)
        self._soft_tree = STRtree(self._soft)
        self._placed = placed
        self._start = 0
        self.crowded: list[str] = []
        """The roles of labels put where they touch something: no free place was within reach."""
        self.set_out: list[str] = []
        """The roles of labels that found no free place within reach of their anchor (``_far``'s last resorts):
        the crowded ones, and those set clear of the other labels where a little ink, or none, lies under them."""
        self.taken: Hint | None = None
        """Where the label placed last was put: one of its near places or of its far rings' (None: elsewhere)."""

    def _inside(self, b: Box) -> bool:
        x0, y0, x1, y1 = self.region
        return b[0] >= x0 and b[1] >= y0 and b[2] <= x1 and b[3] <= y1

    def _free_of(self, boxes: Sequence[Box], avoid_fill: bool) -> Iterator[bool]:
        """For each of ``boxes`` in turn, whether it lies inside the region, its clearance touching nothing
        drawn (with ``avoid_fill`` no shading either) and no placed label; the drawing is tested for all
        boxes at once, the placed labels box by box as asked (the first free one often ends the search).
        Asked again for the same boxes (``_near``'s second round), the drawing is not tested again."""
        import numpy as np

        if not boxes:
            return
        if self._tested is not None and self._tested[0] is boxes:
            _, grown, taken = self._tested
        else:
            grown = _grown_boxes(boxes)
            taken = set(np.flatnonzero(_touching(self._hard_tree, self._hard_bounds, grown)).tolist())
            self._tested = (boxes, grown, taken)
        if avoid_fill:
            taken = taken | set(self._soft_tree.query(grown, predicate="intersects")[0].tolist())
        for k, box in enumerate(boxes):
            yield k not in taken and self._inside(box) and not self._placed.touches(grown[k], box=True)

    def _leader_ok(self, line: Any, strict: bool) -> bool:
        """A leader (its centre line) keeps its clearance from every label (other leaders may meet it, at a spot
        they share); ``strict``: from everything drawn too, beyond ``_LEADER_FREE_MM`` of its anchor."""
        from shapely.geometry import LineString

        reach = LEADER.width / 2 + CLEARANCE_MM
        if self._placed.touches(line, labels_only=True, distance=reach):
            return False
        if not strict:
            return True
        (ax, ay), (bx, by) = line.coords[0], line.coords[-1]
        length = math.hypot(bx - ax, by - ay)
        if length <= _LEADER_FREE_MM:
            return True
        t = _LEADER_FREE_MM / length
        clear = LineString([(ax + t * (bx - ax), ay + t * (by - ay)), (bx, by)])
        return not len(self._hard_tree.query(clear, predicate="dwithin", distance=reach))

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
        self._placed.append(leader.buffer(LEADER.width / 2), leader=True)
        points = tuple((float(x), float(y)) for x, y in leader.coords)
        return [Path(points, LEADER, role=f"leader {role}"), text]

    def _spent(self) -> bool:
        """Whether the label being placed has used its share of the search (``_SEARCH_BUDGET``)."""
        return self._placed.scanned - self._start > _SEARCH_BUDGET

    def _near(self, candidates: Sequence[Box]) -> Box | None:
        for avoid_fill in (True, False):
            for b, free in zip(candidates, self._free_of(candidates, avoid_fill), strict=True):
                if free:
                    return b
                if self._spent():
                    return None
        return None

    def _far(self, runs: tuple[Run, ...], color: str, role: str, anchor: Point, bold: bool,
             size: tuple[float, float], optional: bool = False, near: Sequence[Box] = (),
             feet: Sequence[Point] = (), shaft: tuple[Point, Point] | None = None) -> list[Item]:
        """The label set out from ``anchor`` with a leader, at the nearest place free of everything; where there is
        none, at the place clear of every other label that the least ink drawn lies under (``_least_inked``): one
        of ``near`` (the places beside the anchor, without a leader) or one out from ``anchor`` or from one of
        ``feet`` (further points the label may name: along a vector's shaft), its leader from there; where none of
        those is clear of the other labels, one on a grid over the whole region (``_region_places``), its leader
        from ``anchor`` or from the nearest point of ``shaft`` (the vector the label names)."""
        import numpy as np

        # A leader that crosses nothing drawn first, ring after ring (the nearest that has one ends the search),
        # then one that must cross something.
        free: list[tuple[Box, Any, int]] = []
        first = 0  # the index of the group's first place among all the far rings' (``_far_places``)
        for rings in _FAR_RING_GROUPS:
            if self._spent():
                break  # its first test would end the search: nothing more is tried (the search only grows)
            candidates = [_pushed_box(anchor, direction, size, ring) for ring in rings for direction in _DIRECTIONS]
            for k, (b, ok) in enumerate(zip(candidates, self._free_of(candidates, False), strict=True)):
                if self._spent():
                    break
                leader = _leader(anchor, b) if ok else None
                if leader is None:
                    continue
                if self._leader_ok(leader, True):
                    self.taken = ("far", first + k)
                    return self._accept(b, runs, color, role, anchor, bold, leader)
                free.append((b, leader, first + k))
            first += len(candidates)
        for b, leader, k in free:
            if self._spent():
                break
            if self._leader_ok(leader, False):
                self.taken = ("far", k)
                return self._accept(b, runs, color, role, anchor, bold, leader)
        if optional:
            return []
        # Nowhere free within reach of the anchor: the place clear of the other labels with the least ink under it,
        # out from the anchor or from a foot; one on ink counts as crowded.
        self.set_out.append(role)
        boxes, leaders = _set_out_places((anchor, *feet), size)
        spent = self._spent()
        choice = self._least_inked(np.concatenate([np.asarray(near, dtype=float).reshape(-1, 4), boxes]),
                                   np.concatenate([np.full(len(near), None, dtype=object), leaders]))
        if choice is None and not spent:  # none of those clear of the other labels: anywhere in the region (once)
            choice = self._anywhere(size, anchor, shaft)
        if choice is not None:
            if choice[2]:
                self.crowded.append(role)
            return self._accept(choice[0], runs, color, role, anchor, bold, choice[1])
        # Not even that within the search's budget: the nearest place inside the region (the overlap test reports it).
        self.crowded.append(role)
        b = _inside_of(_pushed_box(anchor, (1.0, 0.0), size, _RINGS_MM[0]), self.region)
        return self._accept(b, runs, color, role, anchor, bold)

    def _least_inked(self, b: npt.NDArray[np.float64], leaders: npt.NDArray[np.object_],
                     budgeted: bool = True) -> tuple[Box, Any, bool, float] | None:
        """Of the boxes ``b`` (n x 4), each with its leader (None: beside the anchor), the one inside the region
        whose clearance touches no placed label nor leader, whose leader keeps clear of every label, and under which
        the least ink lies (about the area of what is drawn within its clearance; a leader's length weighs
        ``_LEADER_INK_MM2`` per mm): a label crowded by lines stays readable and apart from the other labels. With
        it, its leader, whether the box comes within half its clearance of anything drawn, and its weight (the ink
        and the leader's). None when the search has spent its budget already (unless not ``budgeted``).

        The boxes and leaders are tested all at once, against the placed geometries near them (``_Placed.near``)."""
        import numpy as np
        import shapely

        if budgeted and self._spent():
            return None
        x0, y0, x1, y1 = self.region
        inside = (b[:, 0] >= x0) & (b[:, 1] >= y0) & (b[:, 2] <= x1) & (b[:, 3] <= y1)
        b, leaders = b[inside], leaders[inside]
        if not len(b):
            return None
        lined = leaders != None  # noqa: E711 (elementwise)
        length = np.zeros(len(b))
        length[lined] = shapely.length(leaders[lined])
        weight = _LEADER_INK_MM2 * length
        # In order of the leaders' weight, a chunk at a time, until the leaders alone weigh more than the best place
        # found (the ink under a place only adds to it): the same place as all of them tested at once.
        order = np.argsort(weight, kind="stable")
        best: tuple[float, int, float] | None = None  # its weight, index and ink
        start, size = 0, _INK_CHUNK
        while start < len(order) and (best is None or weight[order[start]] <= best[0]):
            chunk = np.sort(order[start:start + size])
            start, size = start + size, 2 * size
            found = self._inked(b[chunk], leaders[chunk], lined[chunk], weight[chunk],
                                math.inf if best is None else best[0])
            if found is not None:
                cost, k, ink = found
                if best is None or cost < best[0] or (cost == best[0] and chunk[k] < best[1]):
                    best = (cost, int(chunk[k]), ink)
        if best is None:
            return None
        cost, k, ink = best
        box: Box = (float(b[k, 0]), float(b[k, 1]), float(b[k, 2]), float(b[k, 3]))
        h = CLEARANCE_MM / 2  # nearer than that a reader sees the label touch
        near_box = shapely.box(box[0] - h, box[1] - h, box[2] + h, box[3] + h)
        on_ink = bool(ink) and bool(len(self._hard_tree.query(near_box, predicate="intersects")))
        return box, leaders[k], on_ink, cost

    def _inked(self, b: npt.NDArray[np.float64], leaders: npt.NDArray[np.object_], lined: npt.NDArray[np.bool_],
               weight: npt.NDArray[np.float64], bound: float) -> tuple[float, int, float] | None:
        """Of the boxes ``b`` inside the region (``_least_inked``), each with its leader (``lined``: it has one) and
        the leader's weight, the first of those with the least weight and ink that are clear of the placed labels and
        whose leaders are: its weight with the ink, its index and its ink; None when none weighing at most ``bound``
        is clear.

        The placed labels' boxes are tested first (bounds only: a label is its box), then the ink under the boxes
        clear of them weighed, and only then the placed leaders and the boxes' own leaders tested, the lightest
        boxes first, a few at a time, until one is clear."""
        import numpy as np
        import shapely

        c = CLEARANCE_MM
        grown = _grown_boxes(b)
        reach = LEADER.width / 2 + CLEARANCE_MM
        e0, e1, e2, e3 = (float(v) for v in shapely.total_bounds(np.concatenate([grown, leaders[lined]])))
        near = self._placed.near((e0, e1, e2, e3), reach)
        labels = [self._placed.geometries[i] for i in near if not self._placed.is_leader(i)]
        lines = np.empty(len(near) - len(labels), dtype=object)
        lines[:] = [self._placed.geometries[i] for i in near if self._placed.is_leader(i)]
        label_tree = shapely.STRtree(labels)
        ok = weight <= bound  # a heavier leader cannot win, whatever the ink
        ok[label_tree.query(grown)[0]] = False  # a placed label is its box: it meets a box where their bounds do
        kept = np.flatnonzero(ok)
        if not len(kept):
            return None
        ink = np.zeros(len(kept))
        which, hit = _meeting(self._hard_tree, self._hard_array, self._hard_bounds, grown[kept])
        if len(which):  # each piece's area times the share of its bounds the box covers: cheap, and near enough
            bounds, areas = self._hard_bounds[hit], self._hard_areas[hit]
            g = b[kept][which]
            wide = np.minimum(g[:, 2] + c, bounds[:, 2]) - np.maximum(g[:, 0] - c, bounds[:, 0])
            high = np.minimum(g[:, 3] + c, bounds[:, 3]) - np.maximum(g[:, 1] - c, bounds[:, 1])
            spans = np.maximum(bounds[:, 2] - bounds[:, 0], 1e-9) * np.maximum(bounds[:, 3] - bounds[:, 1], 1e-9)
            share = np.clip(wide, 0.0, None) * np.clip(high, 0.0, None) / spans
            np.add.at(ink, which, areas * np.minimum(share, 1.0))
        cost = ink + weight[kept]
        order = np.argsort(cost, kind="stable")  # the least first, the first of equals first
        order = order[cost[order] <= bound]
        line_tree = shapely.STRtree(lines) if len(lines) else None
        line_bounds = shapely.bounds(lines).reshape(-1, 4)
        start, size = 0, _CLEAR_CHUNK
        while start < len(order):
            part = order[start:start + size]
            start, size = start + size, 2 * size
            boxes = kept[part]
            clear = np.ones(len(part), dtype=bool)
            if line_tree is not None:  # clear of the placed leaders
                clear[_touching(line_tree, line_bounds, grown[boxes])] = False
            tested = np.flatnonzero(clear & lined[boxes])
            if len(tested) and labels:  # its leader clear of the placed labels
                clear[tested[label_tree.query(leaders[boxes[tested]], predicate="dwithin", distance=reach)[0]]] = False
            found = np.flatnonzero(clear)
            if len(found):
                j = part[found[0]]
                return float(cost[j]), int(kept[j]), float(ink[j])
        return None

    def _anywhere(self, size: tuple[float, float], anchor: Point,
                  shaft: tuple[Point, Point] | None) -> tuple[Box, Any, bool, float] | None:
        """``_least_inked`` of the places on a grid over the whole region (``_region_places``), whatever the search
        spent: tried in order of their leader's length, ``_GRID_CHUNK`` at a time, until the leaders alone weigh
        more than the best place found (the ink under a place only adds to its leader's weight)."""
        import numpy as np

        boxes, feet = _region_places(self.region, size, anchor, shaft)
        _, reach = _leader_reach(boxes, feet)
        order = np.argsort(reach, kind="stable")
        best: tuple[Box, Any, bool, float] | None = None
        for start in range(0, len(order), _GRID_CHUNK):
            chunk = order[start:start + _GRID_CHUNK]
            if best is not None and _LEADER_INK_MM2 * (reach[chunk[0]] - 0.6) >= best[3]:
                break
            found = self._least_inked(boxes[chunk], _leaders(boxes[chunk], feet[chunk]), budgeted=False)
            if found is not None and (best is None or found[3] < best[3]):
                best = found
        return best

    def _hinted(self, hint: Hint | None, near: Sequence[Box], runs: tuple[Run, ...], color: str, role: str,
                anchor: Point, bold: bool, size: tuple[float, float]) -> list[Item] | None:
        """The label at the place ``hint`` names (where it was on the frame before: one of ``near``, or of the far
        rings round ``anchor`` with a leader), where that place is free of everything and its leader clear of the
        labels; None where not, or without a hint."""
        if hint is None:
            return None
        kind, k = hint
        places = near if kind == "near" else _far_places(anchor, size)
        if k >= len(places):
            return None
        b = places[k]
        leader = None if kind == "near" else _leader(anchor, b)
        if kind == "far" and leader is None:
            return None
        if not next(self._free_of([b], False)) or (leader is not None and not self._leader_ok(leader, False)):
            return None
        self.taken = hint
        return self._accept(b, runs, color, role, anchor, bold, leader)

    def where_it_was(self, was: list[Item], runs: tuple[Run, ...], color: str, role: str,
                     anchor: Point) -> list[Item] | None:
        """The label at the place of ``was`` (the label it grew from, as placed on the sheet before): its box's top
        left corner kept, and its leader, if it had one, from the same point; None when that place is not free of
        everything or its leader not clear of the other labels."""
        self._start = self._placed.scanned
        text = was[-1]
        if not isinstance(text, Text):
            return None
        x0, y0, x1, y1 = runs_box(runs)
        b = (text.box[0], text.box[3] - (y1 - y0), text.box[0] + (x1 - x0), text.box[3])
        if not next(self._free_of([b], False)):
            return None
        line = next((item for item in was if isinstance(item, Path) and item.role.startswith("leader ")), None)
        leader = None if line is None else _leader(line.points[0], b)
        if leader is not None and not self._leader_ok(leader, False):
            return None
        return self._accept(b, runs, color, role, anchor, False, leader)

    def at_point(self, anchor: Point, runs: tuple[Run, ...], color: str = "#000000", role: str = "",
                 bold: bool = False, gap: float = 0.0, ring: bool = False, optional: bool = False,
                 far: bool = False, hint: Hint | None = None) -> list[Item]:
        """A label near a point (a joint, a tip): the nearest free place around it; ``far``: set out with a
        leader from the start (a point among many, whose near places would wall the others in). ``hint``: where it
        was on the frame before (``_hinted``): a near place tried first, a far one where no near place is free."""
        self._start = self._placed.scanned
        self.taken = None
        x0, y0, x1, y1 = runs_box(runs, bold)
        size = (x1 - x0, y1 - y0)
        radius = math.hypot(*size) / 2 + 0.35
        outer = (2 * radius, 2 * radius) if ring else size
        candidates = list(itertools.islice((_pushed_box(anchor, u, outer, gap + distance) for distance in _RINGS_MM
                                            for u in _DIRECTIONS), self._candidates))
        near_hint, far_hint = _kinds(hint)
        hinted = self._hinted(near_hint, candidates, runs, color, role, anchor, bold, outer)
        found = None if far or hinted is not None else self._near(_nearest_first(candidates, hint))
        if found is None:
            items = hinted or self._hinted(far_hint, candidates, runs, color, role, anchor, bold, outer) or \
                self._far(runs, color, role, anchor, bold, outer, optional, () if far else candidates)
            if not items:
                return []
            corner = _box_of(items)
            found = (corner[0], corner[1], corner[0] + outer[0], corner[1] + outer[1])
        else:
            self.taken = ("near", next(k for k, b in enumerate(candidates) if b is found))
            items = self._accept(found, runs, color, role, anchor, bold)
        if not ring:
            return items
        cx, cy = (found[0] + found[2]) / 2, (found[1] + found[3]) / 2
        text = items[-1]
        assert isinstance(text, Text)
        centred = Text(cx - (x0 + x1) / 2, cy - (y0 + y1) / 2, text.runs, text.color, text.role, text.anchor, bold)
        return [*items[:-1], Circle((cx, cy), radius, Stroke(color, 0.18), role=f"ring {role}"), centred]

    def along(self, start: Point, end: Point, runs: tuple[Run, ...], color: str = "#000000",
              role: str = "", hint: Hint | None = None) -> list[Item]:
        """A label beside a vector's shaft, either side, near its middle first; ``hint``: where it was on the frame
        before (``_hinted``): a near place tried first, a far one where no near place is free."""
        self._start = self._placed.scanned
        self.taken = None
        x0, y0, x1, y1 = runs_box(runs)
        size = (x1 - x0, y1 - y0)
        length = math.hypot(end[0] - start[0], end[1] - start[1])
        if length == 0.0:
            return self.at_point(start, runs, color, role)
        ux, uy = (end[0] - start[0]) / length, (end[1] - start[1]) / length
        candidates = list(itertools.islice((_pushed_box((start[0] + t * (end[0] - start[0]),
                                                         start[1] + t * (end[1] - start[1])),
                                                        (-side * uy, side * ux), size, ring)
                                            for ring in _RINGS_MM[:3] for t in _ALONG_T for side in (1.0, -1.0)),
                                           self._candidates))
        near_hint, far_hint = _kinds(hint)
        hinted = self._hinted(near_hint, candidates, runs, color, role, _mid(start, end), False, size)
        if hinted is not None:
            return hinted
        found = self._near(_nearest_first(candidates, hint))
        if found is not None:
            self.taken = ("near", next(k for k, b in enumerate(candidates) if b is found))
            return self._accept(found, runs, color, role, _mid(start, end), False)
        hinted = self._hinted(far_hint, candidates, runs, color, role, _mid(start, end), False, size)
        if hinted is not None:
            return hinted
        feet = [(start[0] + t * (end[0] - start[0]), start[1] + t * (end[1] - start[1])) for t in _ALONG_T[1:]]
        return self._far(runs, color, role, _mid(start, end), False, size, near=candidates, feet=feet,
                         shaft=(start, end))


def _within(inner: npt.NDArray[np.float64], outer: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
    """Whether each of the bounds ``inner`` (n x 4) lies within the bounds ``outer`` (n x 4), edges included."""
    return ((inner[:, 0] >= outer[:, 0]) & (inner[:, 1] >= outer[:, 1])
            & (inner[:, 2] <= outer[:, 2]) & (inner[:, 3] <= outer[:, 3]))


def _meeting(tree: Any, geometries: npt.NDArray[np.object_], bounds: npt.NDArray[np.float64],
             boxes: Any) -> tuple[npt.NDArray[np.intp], npt.NDArray[np.intp]]:
    """``tree.query(boxes, predicate="intersects")`` (``geometries`` the tree's, ``bounds`` theirs; ``boxes`` an
    array of polygons): the same pairs in the same order, with less work. A geometry whose bounds lie within a box's
    meets it; only the other pairs whose bounds meet are tested exactly."""
    import numpy as np
    import shapely

    which, hit = tree.query(boxes)  # the pairs whose bounds meet, in the order the predicate keeps
    if not len(which):
        return which, hit
    keep = _within(bounds[hit], shapely.bounds(boxes)[which])
    rest = np.flatnonzero(~keep)
    keep[rest] = shapely.intersects(boxes[which[rest]], geometries[hit[rest]])
    return which[keep], hit[keep]


def _touching(tree: Any, bounds: npt.NDArray[np.float64], boxes: Any) -> npt.NDArray[np.bool_]:
    """For each of ``boxes`` (an array of polygons), whether it meets any of the geometries of ``tree`` (``bounds``
    theirs): as ``tree.query(boxes, predicate="intersects")`` finds, with less work. A box that holds a geometry's
    bounds within its own meets it; only the other boxes are tested exactly."""
    import numpy as np
    import shapely

    met = np.zeros(len(boxes), dtype=bool)
    which, hit = tree.query(boxes)  # the pairs whose bounds meet
    if not len(which):
        return met
    met[which[_within(bounds[hit], shapely.bounds(boxes)[which])]] = True
    rest = np.unique(which[~met[which]])
    if len(rest):
        met[rest[tree.query(boxes[rest], predicate="intersects")[0]]] = True
    return met


def _grown_boxes(boxes: Sequence[Box] | npt.NDArray[np.float64]) -> Any:
    """The boxes grown by the clearance, as shapely polygons."""
    import numpy as np
    import shapely

    c = CLEARANCE_MM
    b = np.asarray(boxes, dtype=float)
    return shapely.box(b[:, 0] - c, b[:, 1] - c, b[:, 2] + c, b[:, 3] + c)


def _set_out_places(feet: Sequence[Point],
                    size: tuple[float, float]) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.object_]]:
    """The places a label of ``size`` set out is tried at: on every far ring (``_FAR_RINGS_MM``, then
    ``_FURTHEST_RINGS_MM``) round each of ``feet``, each with its leader from the foot (``_leaders``). The boxes
    (n x 4) and the leaders."""
    import numpy as np

    rings = _FAR_RINGS_MM + _FURTHEST_RINGS_MM
    offsets = np.array([_pushed_box((0.0, 0.0), direction, size, ring) for ring in rings for direction in _DIRECTIONS])
    foot = np.repeat(np.asarray(feet, dtype=float), len(offsets), axis=0)
    boxes = np.tile(offsets, (len(feet), 1)) + np.hstack([foot, foot])
    return boxes, _leaders(boxes, foot)


def _kinds(hint: Hint | None) -> tuple[Hint | None, Hint | None]:
    """``hint`` as a near place's and a far one's: a label set out on the frame before is tried there only where no
    place near its anchor is free (a leader only where one is needed)."""
    return (hint, None) if hint is not None and hint[0] == "near" else (None, hint)


def _nearest_first(places: list[Box], hint: Hint | None) -> list[Box]:
    """``places`` (a label's near ones) in the order they are tried: as they are, or, where the label was at one of
    them on the frame before (``hint``), the nearest to that one first (the label moves as little as it can)."""
    if hint is None or hint[0] != "near" or hint[1] >= len(places):
        return places
    x0, y0, x1, y1 = places[hint[1]]
    return sorted(places, key=lambda b: math.hypot(b[0] + b[2] - x0 - x1, b[1] + b[3] - y0 - y1))


def _far_places(anchor: Point, size: tuple[float, float]) -> list[Box]:
    """The places of a label of ``size`` on the far rings round ``anchor``, in the order ``Placer._far`` tries
    them."""
    return [_pushed_box(anchor, direction, size, ring) for ring in _FAR_RINGS_MM for direction in _DIRECTIONS]


_GRID_MM = 2.0
"""How far apart the places tried over a whole region are (``_region_places``)."""
_SHAFT_SPAN = (0.1, 0.9)
"""Where along a vector's shaft a leader from a place anywhere in the region may start."""
_GRID_CHUNK = 1000
"""How many of the grid's places ``Placer._anywhere`` tests at a time."""
_INK_CHUNK = 128
"""How many places ``Placer._least_inked`` tests first (the lightest leaders), twice as many each time after."""
_CLEAR_CHUNK = 8
"""How many of them, the lightest first, ``Placer._inked`` tests against the placed leaders at first, twice as many
each time after."""


def _region_places(region: Box, size: tuple[float, float], anchor: Point,
                   shaft: tuple[Point, Point] | None) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """The places a label of ``size`` is tried at where no place out from its anchor is clear of the other labels:
    on a grid over the whole ``region`` (``_GRID_MM`` apart), each with its leader's foot at ``anchor`` and, for a
    vector's label, each again with its foot at the point of ``shaft`` nearest the box's centre (within
    ``_SHAFT_SPAN`` of its length). The boxes (n x 4) and the feet (n x 2)."""
    import numpy as np

    width, height = size
    xs = np.arange(region[0], region[2] - width, _GRID_MM)
    ys = np.arange(region[1], region[3] - height, _GRID_MM)
    gx, gy = (grid.ravel() for grid in np.meshgrid(xs, ys))
    boxes = np.stack([gx, gy, gx + width, gy + height], axis=1)
    feet = [np.broadcast_to(np.asarray(anchor, dtype=float), (len(boxes), 2))]
    if shaft is not None:
        a, b = np.asarray(shaft[0], dtype=float), np.asarray(shaft[1], dtype=float)
        d = b - a
        if float(d @ d) > 0.0:
            centres = (boxes[:, :2] + boxes[:, 2:]) / 2
            t = np.clip((centres - a) @ d / float(d @ d), *_SHAFT_SPAN)
            feet.append(a + t[:, None] * d)
    return np.tile(boxes, (len(feet), 1)), np.concatenate(feet)


def _leader(foot: Point, b: Box) -> Any:
    """A label's leader: from ``foot`` to 0.3 mm short of the point of the box ``b`` nearest it; None within 0.6 mm
    of the foot (the label is beside it)."""
    from shapely.geometry import LineString

    near = (min(max(foot[0], b[0]), b[2]), min(max(foot[1], b[1]), b[3]))  # the box's nearest point
    length = math.hypot(near[0] - foot[0], near[1] - foot[1])
    if length <= 0.6:
        return None
    k = (length - 0.3) / length
    return LineString([foot, (foot[0] + k * (near[0] - foot[0]), foot[1] + k * (near[1] - foot[1]))])


def _leader_reach(boxes: npt.NDArray[np.float64],
                  foot: npt.NDArray[np.float64]) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Each box's point nearest its foot, and how far it is."""
    import numpy as np

    nearest = np.clip(foot, boxes[:, :2], boxes[:, 2:])
    return nearest, np.hypot(*(nearest - foot).T)


def _leaders(boxes: npt.NDArray[np.float64], foot: npt.NDArray[np.float64]) -> npt.NDArray[np.object_]:
    """Each box's leader (``_leader``, for many boxes at once): from its foot to 0.3 mm short of the box's nearest
    point; None within 0.6 mm of the foot."""
    import numpy as np
    import shapely

    nearest, length = _leader_reach(boxes, foot)
    drawn = length > 0.6
    leaders = np.full(len(boxes), None, dtype=object)
    k = ((length[drawn] - 0.3) / length[drawn])[:, None]
    ends = foot[drawn] + k * (nearest[drawn] - foot[drawn])
    leaders[drawn] = shapely.linestrings(np.stack([foot[drawn], ends], axis=1))
    return leaders


def _inside_of(b: Box, region: Box) -> Box:
    """The box moved the least way into ``region`` (its left and top edges kept in when it is the larger)."""
    dx = max(region[0] - b[0], min(region[2] - b[2], 0.0))
    dy = min(region[3] - b[3], max(region[1] - b[1], 0.0))
    return (b[0] + dx, b[1] + dy, b[2] + dx, b[3] + dy)


def _mid(a: Point, b: Point) -> Point:
    return ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)


def _point(p: Point) -> Any:
    from shapely.geometry import Point as ShapelyPoint

    return ShapelyPoint(p)


Placed = tuple[str, list[Item], list[Any], list[Box]]
"""A placed label: its layer, its items (text, and leader or ring), their geometries as placed and the
geometries' bounds."""


class LabelCache:
    """What the sheets of one layout (a handout's pages, a drawing's step sheets) share: the parts they draw
    alike (``parts``), and what placing their labels needs.

    The geometry of each drawn item is made once. A region's labels are placed once and reused on
    every later sheet whose requests in that region, and drawn items near it, are the same (the
    mechanism, the circle diagram: the fixed parts); a region's labels are kept so only when they
    lie clear of its edges and of every other region's labels (then nothing outside the region
    could have moved them). A region whose drawing grows from sheet to sheet (a polygon, step by
    step) keeps the labels of the whole drawing, placed first (they are clear of every step's
    drawing), and of the sheet before those that nothing new touches; it places only the labels
    new on the sheet: each page costs what it adds, and a label stays where the reader saw it.
    """

    def __init__(self, hints: Mapping[str, Hint] | None = None) -> None:
        self.hints: Mapping[str, Hint] = hints or {}
        """Where each label was put on the frame before (an animation's, by layer and role): tried first, so that a
        label stays where it was while that place is free."""
        self.taken: dict[str, Hint] = {}
        """Where each label placed with this cache was put (the next frame's ``hints``)."""
        self._geometry: dict[Item, tuple[Any, Any, Box]] = {}
        self._pieces: dict[Item, list[Any]] = {}
        self._fitted: dict[Request, Request] = {}
        self.parts: dict[Any, Any] = {}
        """The items and label requests of the parts that the sheets draw alike (``render.sheet.build_sheet``)."""
        self._regions: dict[tuple[Any, ...], tuple[list[Placed], list[str], list[str]]] = {}
        self._last: dict[Box, tuple[dict[Request, list[Placed]], frozenset[Item]]] = {}
        self._widest: dict[Box, tuple[dict[Request, list[Placed]], frozenset[Item]]] = {}
        """Per region, the placement on the sheet with the most drawing there (a handout's whole drawing)."""
        self.crowded: set[str] = set()
        """The roles of the labels that found no free place on any sheet placed with this cache: put where they lie
        on something drawn."""
        self.set_out: set[str] = set()
        """The roles of the labels that found no free place near their anchor on any sheet placed with this cache
        (``Placer.set_out``): the crowded ones and those set clear of everything further out. How crowded a polygon's
        points are, whatever the paper (``render.sheet.crowded``)."""

    def fitted(self, request: Request) -> Request:
        """The request wrapped to its region (``_fitted``), made once."""
        found = self._fitted.get(request)
        if found is None:
            found = self._fitted[request] = _fitted(request)
        return found

    def pieces(self, item: Item) -> list[Any]:
        """The item's geometry in pieces (``item_pieces``), made once."""
        found = self._pieces.get(item)
        if found is None:
            found = self._pieces[item] = item_pieces(item)
        return found

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


def _kept(cache: LabelCache, region: Box, requests: Sequence[Request], near: Sequence[Item]) -> dict[int, Placed]:
    """The labels that stay. First those of the sheet whose drawing in the region holds all of this sheet's
    (the whole drawing, placed first): placed clear of every step's drawing, each page shows them where
    every other page does. Then, for the requests that sheet does not have (a group of coinciding tips
    not yet complete), those of the region's previous sheet that nothing drawn since touches, nor a label
    kept before them. Each page places only the labels that are new on it."""
    widest = cache._widest.get(region)
    last = cache._last.get(region)
    sources = [source for source in (widest if widest is not None and widest[1].issuperset(near) else None, last)
               if source is not None]
    kept: dict[int, Placed] = {}
    for before, drawn_before in sources:
        available = {request: list(placed) for request, placed in before.items()}
        candidates: dict[int, Placed] = {}
        for k, request in enumerate(requests):
            entries = available.get(request)
            if entries and k not in kept:
                candidates[k] = entries.pop(0)
        _untouched(candidates, [cache.geometry(item)[0] for item in near if item not in drawn_before])
        if kept and candidates:
            taken = _Placed()
            for entry in kept.values():
                taken.add(entry)
            candidates = {k: c for k, c in candidates.items() if not any(taken.touches(g) for g in c[2])}
        kept.update(candidates)
    return kept


def _untouched(candidates: dict[int, Placed], fresh: list[Any]) -> None:
    """Drop the candidates that a ``fresh`` geometry comes within the clearance of."""
    from shapely import STRtree

    if not fresh or not candidates:
        return
    tree = STRtree(fresh)
    order = list(candidates)
    geometries = [g for k in order for g in candidates[k][2]]
    owner = [k for k in order for _ in candidates[k][2]]
    hit = tree.query(geometries, predicate="dwithin", distance=CLEARANCE_MM)[0]
    for index in set(hit.tolist()):
        candidates.pop(owner[index], None)


BACKGROUND_ROLES = frozenset({"highlight"})
"""The roles of drawn items a label may lie on (the light halo under a step's new elements)."""

_TRIES = 3
"""Placements of a region, each with the labels that found no free place before moved to the front."""
FEW = 10
"""At most this many crowded labels are worth another placement, or another paper (``render.sheet``)."""
_FEW = FEW


def _place_region(cache: LabelCache, region: Box, requests: Sequence[Request], near: Sequence[Item],
                  shared: _Placed) -> tuple[list[Placed], list[str], list[str]]:
    """The region's labels: those kept from the sheet before, then the others placed one after another; with the
    roles crowded and set out (``Placer``).

    Where some label finds no free place (the labels around a crowded spot closed every way out),
    the region is placed again with those labels first, while that helps.
    """
    kept = _kept(cache, region, requests, near)
    order = [k for k in range(len(requests)) if k not in kept]
    if order:
        base = shared.copy()
        for entry in kept.values():
            base.add(entry)
        hard = [g for item in near for g in cache.pieces(item)]
        soft = [g for g in (cache.geometry(item)[1] for item in near) if g is not None]
        placed, crowded, set_out, taken = _tries(region, requests, order, kept, hard, soft, base,
                                                 _grown(cache, region, requests, kept), cache.hints)
        cache.taken.update(taken)
    else:
        placed, crowded, set_out = [kept[k] for k in range(len(requests))], [], []
    for entry in placed:
        shared.add(entry)
    by_request: dict[Request, list[Placed]] = {}
    for request, entry in zip(requests, placed, strict=True):
        by_request.setdefault(request, []).append(entry)
    drawn = frozenset(near)
    cache._last[region] = (by_request, drawn)
    widest = cache._widest.get(region)
    if widest is None or (len(drawn) >= len(widest[1]) and drawn.issuperset(widest[1])):
        cache._widest[region] = (by_request, drawn)
    return placed, crowded, set_out


def _grown(cache: LabelCache, region: Box, requests: Sequence[Request],
           kept: dict[int, Placed]) -> dict[int, list[Item]]:
    """The labels of arrows drawn one on another whose text grew since the region's sheet before (a name joined
    them): for each request not kept, the items of the label its shaft had there."""
    last = cache._last.get(region)
    if last is None:
        return {}
    before: dict[tuple[str, Point, Point], list[Item]] = {}
    for request, entries in last[0].items():
        if request.end is not None and entries:
            before.setdefault((request.layer, request.anchor, request.end), entries[0][1])
    out: dict[int, list[Item]] = {}
    for k, request in enumerate(requests):
        was = before.get((request.layer, request.anchor, request.end)) if request.end is not None else None
        if k not in kept and was and request.role != was[-1].role:
            out[k] = was
    return out


def _tries(region: Box, requests: Sequence[Request], order: list[int], kept: dict[int, Placed], hard: list[Any],
           soft: list[Any], base: _Placed, grown: dict[int, list[Item]] | None = None,
           hints: Mapping[str, Hint] | None = None) -> tuple[list[Placed], list[str], list[str], dict[str, Hint]]:
    """The best of up to ``_TRIES`` placements of the requests not kept, each with the labels that found no free
    place before (``Placer.set_out``) moved to the front; its labels, the roles crowded and the roles set out, and
    where each label was put (``Placer.taken``)."""
    best: tuple[list[Placed], list[str], list[str], dict[str, Hint]] | None = None
    for _ in range(_TRIES):
        placed, crowded, set_out, taken = _attempt(region, requests, order, kept, hard, soft, base.copy(), grown,
                                                   hints)
        if best is not None and len(set_out) >= len(best[2]):
            break  # moving the labels set out first did not help
        best = (placed, crowded, set_out, taken)
        if not set_out or len(set_out) > _FEW:
            break  # none set out, or so many that the polygon's own points crowd: moving them first cannot help
        first = [k for k in order if requests[k].role in set_out]
        again = first + [k for k in order if k not in first]
        if again == order:
            break  # the same order again (every label set out was first already): the same placement
        order = again
    assert best is not None
    return best


_CROWD_MM = 3.0
_CROWD_COUNT = 4
"""A point label with this many other labels' anchors within ``_CROWD_MM`` is set out with a leader at once."""


def _crowd(requests: Sequence[Request]) -> set[int]:
    """The point labels among many anchors close together (a polygon's tips and short vectors near its pole)."""
    anchors = [r.anchor if r.end is None else _mid(r.anchor, r.end) for r in requests]
    cells: dict[tuple[int, int], list[int]] = {}  # squares of _CROWD_MM: the anchors close to one are in 9 of them
    for j, (x, y) in enumerate(anchors):
        cells.setdefault((math.floor(x / _CROWD_MM), math.floor(y / _CROWD_MM)), []).append(j)
    out: set[int] = set()
    for k, request in enumerate(requests):
        if request.end is not None:
            continue
        a = anchors[k]
        i0, j0 = math.floor(a[0] / _CROWD_MM), math.floor(a[1] / _CROWD_MM)
        near = (j for key in ((i, j) for i in (i0 - 1, i0, i0 + 1) for j in (j0 - 1, j0, j0 + 1))
                for j in cells.get(key, ()) if j != k and math.dist(a, anchors[j]) <= _CROWD_MM)
        if sum(1 for _ in itertools.islice(near, _CROWD_COUNT)) >= _CROWD_COUNT:  # enough found: stop looking
            out.add(k)
    return out


def _label_key(request: Request) -> str:
    """What names a label from one frame of an animation to the next: its layer and role."""
    return f"{request.layer} {request.role}"


def _attempt(region: Box, requests: Sequence[Request], order: Sequence[int], kept: dict[int, Placed],
             hard: list[Any], soft: list[Any], placed_so_far: _Placed, grown: dict[int, list[Item]] | None = None,
             hints: Mapping[str, Hint] | None = None) -> tuple[list[Placed], list[str], list[str], dict[str, Hint]]:
    """One placement of the requests not kept, in ``order``; every request's label, the roles crowded and the roles
    set out (``Placer.set_out``), and where each label was put (``Placer.taken``). A label in ``grown``
    (``_grown``) is tried first where its shorter text was; one in ``hints`` where it was on the frame before."""
    placer = Placer(region, hard, soft, placed_so_far)
    out: dict[int, Placed] = dict(kept)
    taken: dict[str, Hint] = {}
    crowd = _crowd(requests)
    for k in order:
        request = requests[k]
        before = len(placed_so_far)
        was = (grown or {}).get(k)
        found = None if was is None else placer.where_it_was(was, request.runs, request.color, request.role,
                                                              _mid(request.anchor, request.end or request.anchor))
        key = _label_key(request)
        hint = hints.get(key) if hints else None
        if found is not None:
            items = found
        elif request.end is None:
            items = placer.at_point(request.anchor, request.runs, request.color, request.role, request.bold,
                                    request.gap, request.ring, request.optional, far=k in crowd, hint=hint)
        else:
            items = placer.along(request.anchor, request.end, request.runs, request.color, request.role, hint=hint)
        if found is None and placer.taken is not None:
            taken[key] = placer.taken
        out[k] = (request.layer, items, placed_so_far.geometries[before:], placed_so_far._bounds[before:])
    return [out[k] for k in range(len(requests))], placer.crowded, placer.set_out, taken


_WRAP_MM = 40.0
_WRAP_SHARE = 0.35
"""A label naming several things (``o, a0, g1, g2, ...``, ``v_Q2 = v_Q3 = ...``) is broken into lines no wider than
the larger of ``_WRAP_MM`` and this share of its region's width: the chain of a long mechanism's coinciding tips stays
on the page."""
_LINE_GAP_MM = 0.4


_BREAKS = (", ", " = ", " + ")
"""The runs a long label may be broken after: between the names of coinciding tips, of equal vectors, of the
terms of a sum."""


def wrapped(runs: tuple[Run, ...], width: float) -> tuple[Run, ...]:
    """``runs`` in lines no wider than ``width``, broken after their ", " and " = " runs (one name never
    broken); the first line stays where it was, the others below it."""
    x0, y0, x1, y1 = runs_box(runs)
    if x1 - x0 <= width:
        return runs
    pieces: list[list[Run]] = [[]]
    for run in runs:
        pieces[-1].append(run)
        if run.text in _BREAKS:
            pieces.append([])
    pieces = [piece for piece in pieces if piece]
    if len(pieces) < 2:
        return runs
    step = (y1 - y0) + _LINE_GAP_MM
    out: list[Run] = []
    line, start = 0, x0
    for piece in pieces:
        left = min(r.dx for r in piece)
        right = max(r.dx + text_width(r.text, r.size) for r in piece)
        if right - start > width and left > start:
            line, start = line + 1, left
        out += [Run(r.text, r.dx - start + x0, r.dy - line * step, r.size) for r in piece]
    return tuple(out)


def _fitted(request: Request) -> Request:
    """A label wrapped to its region (``wrapped``)."""
    width = max(_WRAP_MM, _WRAP_SHARE * (request.region[2] - request.region[0]))
    runs = wrapped(request.runs, width)
    return request if runs is request.runs else replace(request, runs=runs)


def place(requests: Sequence[Request], drawn: Iterable[Item], cache: LabelCache | None = None) -> dict[str, list[Item]]:
    """Place every request in its region (by priority, then in the given order); items per layer.

    A region's labels avoid the drawn items near the region (not the highlight under a step's new
    elements: a label may lie on it, as on the background, so that it need not move when the step is done) (nothing
    further can touch a label inside it) and the labels placed before them. With ``cache`` shared by the sheets of one
    layout, a region whose requests and nearby drawing are as on an earlier sheet gets that
    sheet's labels again, and a region that grew keeps the labels nothing new touches: each
    sheet places only what it adds (``LabelCache``).
    """
    import numpy as np

    cache = cache if cache is not None else LabelCache()
    drawn = [item for item in drawn if item.role not in BACKGROUND_ROLES]
    bounds = np.array([cache.geometry(item)[2] for item in drawn], dtype=float).reshape(-1, 4)
    ordered = sorted((cache.fitted(r) for r in requests), key=lambda r: r.priority)
    by_region: dict[Box, list[Request]] = {}
    for request in ordered:
        by_region.setdefault(request.region, []).append(request)
    margin = CLEARANCE_MM + PAPER_SAME_MM
    near = {region: [drawn[k] for k in np.flatnonzero(
        (bounds[:, 0] <= region[2] + margin) & (bounds[:, 2] >= region[0] - margin)
        & (bounds[:, 1] <= region[3] + margin) & (bounds[:, 3] >= region[1] - margin)).tolist()]
        for region in by_region}
    keys = {region: (region, tuple(reqs), tuple(near[region])) for region, reqs in by_region.items()}
    shared = _Placed()
    results: dict[Box, list[Placed]] = {}
    for region in by_region:
        found = cache._regions.get(keys[region])
        if found is not None:
            results[region] = found[0]
            cache.crowded.update(found[1])
            cache.set_out.update(found[2])
            if any(_near_region(other, region, margin) for other in by_region if other != region):
                for entry in found[0]:
                    shared.add(entry)
            # else its labels, kept only when well inside it (below), are beyond the reach of any other's
    for region, reqs in by_region.items():
        if region in results:
            continue
        placed, crowded, set_out = _place_region(cache, region, reqs, near[region], shared)
        results[region] = placed
        cache.crowded.update(crowded)
        cache.set_out.update(set_out)
        own = [g for _, _, geometries, _ in placed for g in geometries]
        mine = {id(g) for g in own}
        if all(_well_inside(b, region, margin) for _, _, _, boxes in placed for b in boxes) and \
                not any(_near_region(b, region, margin) for g, b in zip(shared.geometries, shared._bounds, strict=True)
                        if id(g) not in mine):
            cache._regions[keys[region]] = (placed, crowded, set_out)
    out: dict[str, list[Item]] = {}
    counters = dict.fromkeys(results, 0)
    for request in ordered:  # the layers' items in the order of the requests
        k = counters[request.region]
        layer, items, _, _ = results[request.region][k]
        counters[request.region] = k + 1
        out.setdefault(layer, []).extend(items)
    return out


class _DraftPlacer(Placer):
    """A placer that takes every label's first place (``Placer._near``'s first candidate) and tests nothing."""

    _candidates = 1

    def __init__(self, region: Box) -> None:
        self.region = region
        self._placed = _Placed()
        self.crowded = []
        self.set_out = []

    def _near(self, candidates: Sequence[Box]) -> Box | None:
        return candidates[0]

    def _accept(self, b: Box, runs: tuple[Run, ...], color: str, role: str, anchor: Point,
                bold: bool, leader: Any = None) -> list[Item]:
        return [self._text(b, runs, color, role, anchor, bold)]


def draft_place(requests: Sequence[Request], cache: LabelCache | None = None) -> dict[str, list[Item]]:
    """The labels of ``requests`` each at the first place ``place`` tries (beside its point or the middle of its
    shaft), with no search for a free one: the same labels, items and layers as ``place`` gives, in the same
    order, made without testing them against the drawing or each other. A sheet drawn in a hurry (the editor's,
    while the user drags) and drawn whole once the drag stops."""
    cache = cache if cache is not None else LabelCache()
    placers: dict[Box, _DraftPlacer] = {}
    out: dict[str, list[Item]] = {}
    for request in sorted((cache.fitted(r) for r in requests), key=lambda r: r.priority):
        placer = placers.setdefault(request.region, _DraftPlacer(request.region))
        if request.end is None:
            items = placer.at_point(request.anchor, request.runs, request.color, request.role, request.bold,
                                    request.gap, request.ring, request.optional)
        else:
            items = placer.along(request.anchor, request.end, request.runs, request.color, request.role)
        out.setdefault(request.layer, []).extend(items)
    return out


def _box_of(items: list[Item]) -> Box:
    """The placed box of a label accepted by ``_accept`` (the last item is its text)."""
    text = items[-1]
    assert isinstance(text, Text)
    return text.box
