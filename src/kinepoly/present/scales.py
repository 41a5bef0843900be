"""The polygon scales kv and ka, decided once per scene and paper. Pure functions.

One decision (``decide_scales``) serves every output: the JSON's polygon tips and the table of
``kinepoly solve``, the drawing of ``kinepoly draw``, every page of a handout in every language,
and the homework checker's ``kv-not-divided`` and ``ka-not-divided`` diagnoses. The rule:

1. the wanted scale: the scene's ``[draw] kv`` / ``ka``, else a round number (1, 2, 2.5 or 5
   times a power of ten) that draws the polygon about 100 mm across (``nice_scale``);
2. the polygon must fit, alone, the room a sheet of that paper gives a polygon (``polygon_room``:
   the paper inside its margins, less the title block's strip); where it does not, the scale is
   the largest round number at which it does, and ``PolygonScale.reduced`` says so (the table,
   the JSON's warnings, the drawing and the handout all say it).

The round numbers (``nice_scale``, ``nice_floor``) are those of every scale kinepoly draws at: the
layout's panels and scale bars, the animation's frames.

A layout places the polygons at these scales and finds the room for them (a panel of their own,
or a larger paper); it never changes a scale. A handout keeps the scales of the paper asked for,
whatever paper its text then needs, so that every language draws the same polygons.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING

from msgspec import Struct

from kinepoly.errors import SceneError
from kinepoly.geom.hull import diameter
from kinepoly.geom.tolerances import ROUNDING_REL, TINY_POSITIVE
from kinepoly.geom.vec import Vec

if TYPE_CHECKING:
    from kinepoly.solution import Solution

__all__ = [
    "A4",
    "PolygonScale",
    "PolygonScales",
    "decide_scales",
    "nice_floor",
    "nice_scale",
    "polygon_room",
    "polygon_scales",
]

A4 = (297.0, 210.0)
"""The default paper (A4 landscape), width and height in mm: ``kinepoly draw``'s and the handout's."""

_NICE = (1.0, 2.0, 2.5, 5.0)
_SIDE_MM = 22.0
"""On each side of a polygon's room: the border's margin (10 mm), the space inside it (3) and the panel's padding
(9)."""
_TITLE_MM = 52.0
"""Below a polygon's room: the title block's strip; above it: the panel's heading."""
_KINDS = (("velocity", "kv"), ("acceleration", "ka"))


def nice_scale(extent: float, target_mm: float = 100.0) -> float:
    """A round scale (1, 2, 2.5 or 5 times a power of ten) that draws ``extent`` about ``target_mm`` long."""
    if not (extent > 0.0 and math.isfinite(extent)):
        return 1.0
    raw = min(target_mm / extent, 1e300)  # a polygon too small for any scale (subnormal: omega = 5e-324) is a dot
    exponent = math.floor(math.log10(raw))
    candidates = [m * 10.0 ** (exponent + k) for k in (-1, 0, 1) for m in _NICE]
    return min(candidates, key=lambda c: abs(math.log(c / raw)))


def nice_floor(x: float) -> float:
    """The largest round number (1, 2, 2.5 or 5 times a power of ten) not above ``x`` (> 0).

    Beyond double precision's normal range it gives the smallest (1e-300) or the largest (1e300) kept.
    """
    if not x >= TINY_POSITIVE:
        return TINY_POSITIVE
    if x >= 1e300:
        return 1e300
    exponent = math.floor(math.log10(x))
    candidates = (m * 10.0**e for e in (exponent - 1, exponent, exponent + 1) for m in _NICE)
    return max(c for c in candidates if c <= x * (1.0 + ROUNDING_REL))


def polygon_room(paper: tuple[float, float]) -> tuple[float, float]:
    """Width and height in mm that a polygon may take on ``paper`` (width, height in mm), alone in its panel."""
    width, height = paper
    return max(width - 2.0 * _SIDE_MM, 1.0), max(height - 2.0 * _SIDE_MM - _TITLE_MM, 1.0)


class PolygonScale(Struct, frozen=True):
    """One polygon's scale in mm of paper per unit of the polygon (mm per mm/s, mm per mm/s²)."""

    kind: str
    """``velocity`` or ``acceleration``."""
    value: float
    """The scale every output uses."""
    wanted: float
    """The scene's ``[draw]`` value, or the round one for a polygon about 100 mm across."""
    given: bool
    """Whether ``wanted`` is the scene's ``[draw]`` value."""

    @property
    def symbol(self) -> str:
        return "kv" if self.kind == "velocity" else "ka"

    @property
    def reduced(self) -> bool:
        """The wanted scale did not fit the paper: ``value`` is smaller."""
        return self.value < self.wanted * (1.0 - ROUNDING_REL)


class PolygonScales(Struct, frozen=True):
    """kv and ka of one solution on one paper."""

    paper: tuple[float, float]
    polygons: tuple[PolygonScale, ...]

    def get(self, kind: str) -> float | None:
        """The scale of ``kind`` (``velocity`` or ``acceleration``), None when that polygon is not drawn."""
        return next((p.value for p in self.polygons if p.kind == kind), None)

    def as_dict(self) -> dict[str, float]:
        """``{"velocity": kv, "acceleration": ka}`` of the polygons drawn."""
        return {p.kind: p.value for p in self.polygons}

    @property
    def reduced(self) -> tuple[PolygonScale, ...]:
        return tuple(p for p in self.polygons if p.reduced)


def _box(points: Iterable[Vec]) -> tuple[float, float]:
    pts = [(0.0, 0.0), *points]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    return max(xs) - min(xs), max(ys) - min(ys)


def _drawn_points(solution: Solution, kind: str) -> list[Vec]:
    """Every point the polygon's drawing reaches: its tips and the ends of the steps' vectors."""
    polygon = solution.velocity if kind == "velocity" else solution.acceleration
    assert polygon is not None
    points = list(polygon.tips.values())
    for step in solution.steps:
        if step.polygon == kind:
            for vector in step.vectors:
                points += [vector.start, vector.end]
    return points


def _fitting(wanted: float, box: tuple[float, float], room: tuple[float, float]) -> float:
    """``wanted``, or the largest round scale not above it at which ``box`` fits ``room``."""
    fit = min(r / b if b > 0.0 else math.inf for b, r in zip(box, room, strict=True))
    if not math.isfinite(fit) or wanted <= fit * (1.0 + ROUNDING_REL):
        return wanted
    return min(nice_floor(fit), wanted)


def decide_scales(solution: Solution, paper: tuple[float, float] = A4) -> PolygonScales:
    """kv and ka of ``solution`` on ``paper`` (width, height in mm): the one decision every output uses.

    Raises ``SceneError`` where a ``[draw]`` scale draws the polygon beyond any paper (its size overflows).
    """
    draw = solution.scene.draw
    room = polygon_room(paper)
    out = []
    for kind, symbol in _KINDS:
        polygon = solution.velocity if kind == "velocity" else solution.acceleration
        if polygon is None:
            continue
        extent = diameter([(0.0, 0.0), *polygon.tips.values()])
        given = draw.kv if kind == "velocity" else draw.ka
        if given is not None and not math.isfinite(given * extent):
            raise SceneError(f"[draw] {symbol} = {given:g} draws the {kind} polygon beyond any paper (its size "
                             f"overflows); expected a smaller scale like {nice_scale(extent):g}, or \"auto\"")
        wanted = given if given is not None else nice_scale(extent)
        value = _fitting(wanted, _box(_drawn_points(solution, kind)), room)
        out.append(PolygonScale(kind, value, wanted, given is not None))
    return PolygonScales((float(paper[0]), float(paper[1])), tuple(out))


def polygon_scales(solution: Solution, paper: tuple[float, float] = A4) -> dict[str, float]:
    """kv and ka as used on ``paper`` (``decide_scales``), keyed ``velocity`` and ``acceleration``."""
    return decide_scales(solution, paper).as_dict()
