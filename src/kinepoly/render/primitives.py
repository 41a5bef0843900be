"""The backend-neutral sheet: a page in millimetres (x right, y up) holding primitives on named layers.

Everything a backend needs is decided here and in the layout: where each line, arrow head and
label is, its colour, width and size. The SVG, DXF and matplotlib writers only translate.
Each primitive carries a ``role`` ("link 3", "vector v_B/A", "tip b", ...) so tests and
readers can find it.
"""

from __future__ import annotations

import math

from msgspec import Struct

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
]

Point = tuple[float, float]


LAYERS = ("mechanism", "higher-pairs", "velocity-polygon", "acceleration-polygon", "instant-centers", "scales", "title")
"""The layers of every sheet, bottom to top. A layer may be empty; it is still written."""


class Stroke(Struct, frozen=True):
    """A line style: colour ``#rrggbb``, width in mm, dash pattern in mm (empty: solid)."""

    color: str = "#000000"
    width: float = 0.25
    dash: tuple[float, ...] = ()


class Path(Struct, frozen=True, cache_hash=True):
    """A polyline or polygon; ``fill`` colour with ``fill_opacity`` for a closed one."""

    points: tuple[Point, ...]
    stroke: Stroke | None = Stroke()
    fill: str | None = None
    fill_opacity: float = 1.0
    closed: bool = False
    role: str = ""


class Circle(Struct, frozen=True, cache_hash=True):
    center: Point
    radius: float
    stroke: Stroke | None = Stroke()
    fill: str | None = None
    role: str = ""


class Arrow(Struct, frozen=True, cache_hash=True):
    """A vector from ``start`` to ``end`` (the head's tip is exactly ``end``), with a filled head."""

    start: Point
    end: Point
    color: str
    width: float
    head_length: float
    head_half_width: float
    role: str = ""

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


class Text(Struct, frozen=True, cache_hash=True):
    """A label: runs placed from the baseline-left point (x, y); ``anchor`` is what it names."""

    x: float
    y: float
    runs: tuple[Run, ...]
    color: str = "#000000"
    role: str = ""
    anchor: Point | None = None
    bold: bool = False

    @property
    def box(self) -> tuple[float, float, float, float]:
        x0, y0, x1, y1 = runs_box(self.runs, self.bold)
        return (self.x + x0, self.y + y0, self.x + x1, self.y + y1)

    @property
    def string(self) -> str:
        return "".join(r.text for r in self.runs)


Item = Path | Circle | Arrow | Text


class Layer(Struct, frozen=True):
    name: str
    items: tuple[Item, ...]


class Sheet(Struct, frozen=True):
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
