"""The diameter of a point set (the largest distance between two of its points) in O(n log n).

The farthest pair lies on the convex hull (Andrew's monotone chain), whose vertices are then
compared pairwise: exactly the all-pairs maximum, without its quadratic cost for long mechanisms.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

__all__ = ["convex_hull", "diameter"]

Point = tuple[float, float]


def _cross(o: Point, a: Point, b: Point) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def convex_hull(points: Iterable[Point]) -> list[Point]:
    """The hull's vertices counter-clockwise (collinear points dropped); all points when fewer than three."""
    pts = sorted(set(points))
    if len(pts) <= 2:
        return pts
    lower: list[Point] = []
    for p in pts:
        while len(lower) >= 2 and _cross(lower[-2], lower[-1], p) <= 0.0:
            lower.pop()
        lower.append(p)
    upper: list[Point] = []
    for p in reversed(pts):
        while len(upper) >= 2 and _cross(upper[-2], upper[-1], p) <= 0.0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def diameter(points: Iterable[Point]) -> float:
    """The largest distance between two of ``points`` (0 for fewer than two); non-finite points give nan/inf."""
    pts = [(float(x), float(y)) for x, y in points]
    if not all(math.isfinite(x) and math.isfinite(y) for x, y in pts):
        return math.nan if any(math.isnan(x) or math.isnan(y) for x, y in pts) else math.inf
    hull = convex_hull(pts)
    return max((math.hypot(a[0] - b[0], a[1] - b[1]) for i, a in enumerate(hull) for b in hull[i + 1:]),
               default=0.0)
