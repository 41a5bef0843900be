"""Label clearance measured on a finished sheet, as a reader sees it, independent of the label placer.

Every text's box (grown by ``CLEARANCE_MM``) is tested against every other text's box and against
the ink of everything drawn: strokes at their width (dashes taken as solid), arrows' shafts and
heads, circles as discs, opaque symbols (a pivot's triangle, a slider's block) as areas. Only
background may lie under a label: light shading (plates, image triangles: fill opacity below 1)
and the highlight under a step's new elements (role ``highlight``; the line it highlights is
measured itself); and a label's own leader and ring may touch it. Texts must lie on the page. The geometry is made here
from the primitives, not taken from ``kinepoly.render.labels``, so a blind spot of the placer is not one
of the measure.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from kinepoly.render.primitives import Arrow, Circle, Item, Sheet, Text

__all__ = ["CLEARANCE_MM", "Conflict", "conflicts", "ink"]

CLEARANCE_MM = 0.2
"""The least gap between a label and anything else (the placer keeps 0.35 mm)."""


@dataclass(frozen=True)
class Conflict:
    text: str
    role: str
    other: str

    def __str__(self) -> str:
        return f"{self.text!r} ({self.role}) touches {self.other}"


def ink(item: Item) -> Any:
    """The area ``item`` inks on the paper, as a shapely geometry."""
    from shapely.geometry import LineString, Polygon, box
    from shapely.geometry import Point as P

    if isinstance(item, Text):
        return box(*item.box)
    if isinstance(item, Arrow):
        return LineString([item.start, item.end]).buffer(item.width / 2).union(Polygon(item.head))
    if isinstance(item, Circle):
        width = item.stroke.width if item.stroke is not None else 0.0
        return P(item.center).buffer(item.radius + width / 2)
    width = item.stroke.width if item.stroke is not None else 0.0
    points = list(item.points)
    if item.closed and item.fill is not None and item.fill_opacity >= 1.0 and len(points) >= 3:
        return Polygon(points).buffer(width / 2)
    if item.closed:
        points.append(points[0])
    if len(points) == 1:
        return P(points[0]).buffer(max(width / 2, 0.01))
    return LineString(points).buffer(max(width / 2, 0.01))


def _own(text: Text, item: Item) -> bool:
    return bool(text.role) and item.role in (f"leader {text.role}", f"ring {text.role}")


def conflicts(sheet: Sheet, clearance: float = CLEARANCE_MM) -> list[Conflict]:
    """Every text that touches another text, something drawn, or the page's edge."""
    from shapely import STRtree
    from shapely.geometry import box

    items = sheet.items()
    texts = [item for item in items if isinstance(item, Text) and item.string.strip()]
    marks = [item for item in items if not isinstance(item, Text) and item.role != "highlight"]
    boxes = [ink(t) for t in texts]
    mark_ink = [ink(m) for m in marks]
    text_tree, mark_tree = STRtree(boxes), STRtree(mark_ink)
    page = box(0.0, 0.0, sheet.width, sheet.height)
    out: list[Conflict] = []
    for k, text in enumerate(texts):
        grown = boxes[k].buffer(clearance, join_style="mitre")
        if not page.contains(boxes[k]):
            out.append(Conflict(text.string, text.role, "the page's edge"))
        for j in mark_tree.query(grown, predicate="intersects"):
            if not _own(text, marks[j]):
                out.append(Conflict(text.string, text.role, f"{type(marks[j]).__name__} {marks[j].role!r}"))
        for j in text_tree.query(grown, predicate="intersects"):
            if j > k:
                other = texts[j]
                out.append(Conflict(text.string, text.role, f"text {other.string!r} ({other.role})"))
    return out
