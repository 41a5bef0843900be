"""The backend-neutral sheet: a page in millimetres (x right, y up) holding primitives on named layers.

Everything a backend needs is decided here and in the layout: where each line, arrow head and
label is, its colour, width and size. The SVG, DXF and matplotlib writers only translate.
Each primitive carries a ``role`` ("link 3", "vector v_B/A", "tip b", ...) so tests and
readers can find it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from kinepoly.render.text import Run, runs_box

__all__ = [
    "LAYERS",
    "Arrow",
    "Circle",
    "Item",
    "Layer",
    "Path",
    "Sheet",
    "Stroke",
    "Text",
    "hash_once",
]

Point = tuple[float, float]

def hash_once(item: object) -> int:
    """A frozen value's hash, computed on its first use and kept on it: a handout's pages look the same
    items and label requests up by value many times (``handout.drawing``, ``render.labels.LabelCache``)."""
    found: int | None = item.__dict__.get("_hash")
    if found is None:
        found = hash(tuple(getattr(item, name) for name in item.__dataclass_fields__))  # type: ignore[attr-defined]
        object.__setattr__(item, "_hash", found)
    return found


LAYERS = ("mechanism", "higher-pairs", "velocity-polygon", "acceleration-polygon", "instant-centers", "scales", "title")
"""The layers of every sheet, bottom to top. A layer may be empty; it is still written."""


@dataclass(frozen=True)
class Stroke:
    """A line style: colour ``#rrggbb``, width in mm, dash pattern in mm (empty: solid)."""

    color: str = "#000000"
    width: float = 0.25
    dash: tuple[float, ...] = ()


@dataclass(frozen=True)
class Path:
    """A polyline or polygon; ``fill`` colour with ``fill_opacity`` for a closed one."""

    points: tuple[Point, ...]
    stroke: Stroke | None = Stroke()
    fill: str | None = None
    fill_opacity: float = 1.0
    closed: bool = False
    role: str = ""

    __hash__ = hash_once


@dataclass(frozen=True)
class Circle:
    center: Point
    radius: float
    stroke: Stroke | None = Stroke()
    fill: str | None = None
    role: str = ""

    __hash__ = hash_once


@dataclass(frozen=True)
class Arrow:
    """A vector from ``start`` to ``end`` (the head's tip is exactly ``end``), with a filled head."""

    start: Point
    end: Point
    color: str
    width: float
    head_length: float
    head_half_width: float
    role: str = ""

    __hash__ = hash_once

    @property
    def length(self) -> float:
        return math.hypot(self.end[0] - self.start[0], self.end[1] - self.start[1])

    @property
    def head(self) -> tuple[Point, Point, Point]:
        """The head's triangle: tip, then the two back corners."""
        ux, uy = ((self.end[0] - self.start[0]) / self.length, (self.end[1] - self.start[1]) / self.length)
        bx, by = self.end[0] - self.head_length * ux, self.end[1] - self.head_length * uy
        w = self.head_half_width
        return (self.end, (bx - w * uy, by + w * ux), (bx + w * uy, by - w * ux))

    @property
    def shaft_end(self) -> Point:
        """Where the shaft stops: a little inside the head so that no gap shows."""
        ux, uy = ((self.end[0] - self.start[0]) / self.length, (self.end[1] - self.start[1]) / self.length)
        back = 0.8 * self.head_length
        return (self.end[0] - back * ux, self.end[1] - back * uy)


@dataclass(frozen=True)
class Text:
    """A label: runs placed from the baseline-left point (x, y); ``anchor`` is what it names."""

    x: float
    y: float
    runs: tuple[Run, ...]
    color: str = "#000000"
    role: str = ""
    anchor: Point | None = None
    bold: bool = False

    __hash__ = hash_once

    @property
    def box(self) -> tuple[float, float, float, float]:
        x0, y0, x1, y1 = runs_box(self.runs, self.bold)
        return (self.x + x0, self.y + y0, self.x + x1, self.y + y1)

    @property
    def string(self) -> str:
        return "".join(r.text for r in self.runs)


Item = Path | Circle | Arrow | Text


@dataclass(frozen=True)
class Layer:
    name: str
    items: tuple[Item, ...]


@dataclass(frozen=True)
class Sheet:
    """A page ``width`` x ``height`` mm and its layers in drawing order."""

    width: float
    height: float
    title: str
    layers: tuple[Layer, ...]

    def layer(self, name: str) -> Layer:
        for layer in self.layers:
            if layer.name == name:
                return layer
        raise KeyError(name)

    def items(self) -> tuple[Item, ...]:
        return tuple(item for layer in self.layers for item in layer.items)
