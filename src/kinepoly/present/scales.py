"""The polygon scales kv and ka: the scene's ``[draw]`` values, else a round number. Pure functions.

The JSON's polygon tips, the table's scale lines and the drawings all use these.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

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
    pts = [(0.0, 0.0), *tips.values()]
    return max((math.hypot(a[0] - b[0], a[1] - b[1]) for a in pts for b in pts), default=0.0)


def polygon_scales(solution: Solution) -> dict[str, float]:
    """kv and ka as used: from ``[draw]``, else a round number for a polygon about 100 mm across."""
    scales = {}
    draw = solution.scene.draw
    if solution.velocity is not None:
        scales["velocity"] = draw.kv if draw.kv is not None else nice_scale(_extent(solution.velocity.tips))
    if solution.acceleration is not None:
        scales["acceleration"] = draw.ka if draw.ka is not None else nice_scale(_extent(solution.acceleration.tips))
    return scales
