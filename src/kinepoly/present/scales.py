"""The polygon scales kv and ka: the scene's ``[draw]`` values, else a round number. Pure functions.

The JSON's polygon tips, the table's scale lines and the drawings all use these.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from kinepoly.errors import SceneError
from kinepoly.geom.hull import diameter
from kinepoly.geom.vec import Vec

if TYPE_CHECKING:
    from kinepoly.solution import Solution

__all__ = ["nice_scale", "polygon_scales"]

_NICE = (1.0, 2.0, 2.5, 5.0)


def nice_scale(extent: float, target_mm: float = 100.0) -> float:
    """A round scale (1, 2, 2.5 or 5 times a power of ten) that draws ``extent`` about ``target_mm`` long."""
    if not (extent > 0.0 and math.isfinite(extent)):
        return 1.0
    raw = target_mm / extent
    exponent = math.floor(math.log10(raw))
    candidates = [m * 10.0 ** (exponent + k) for k in (-1, 0, 1) for m in _NICE]
    return min(candidates, key=lambda c: abs(math.log(c / raw)))


def _extent(tips: dict[str, Vec]) -> float:
    """The polygon's size: the largest distance between two of its tips or the pole."""
    return diameter([(0.0, 0.0), *tips.values()])


def polygon_scales(solution: Solution) -> dict[str, float]:
    """kv and ka as used: from ``[draw]``, else a round number for a polygon about 100 mm across."""
    scales = {}
    draw = solution.scene.draw
    for kind, polygon, given, symbol in (("velocity", solution.velocity, draw.kv, "kv"),
                                         ("acceleration", solution.acceleration, draw.ka, "ka")):
        if polygon is None:
            continue
        extent = _extent(polygon.tips)
        if given is not None and not math.isfinite(given * extent):
            raise SceneError(f"[draw] {symbol} = {given:g} draws the {kind} polygon beyond any paper (its size "
                             f"overflows); expected a smaller scale like {nice_scale(extent):g}, or \"auto\"")
        scales[kind] = given if given is not None else nice_scale(extent)
    return scales
