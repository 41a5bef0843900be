"""The 2D kernel: vectors, lines in homogeneous coordinates, intersections with their conditioning.

It knows nothing of mechanisms. Points at infinity are values, never NaN.
"""

from kinepoly.geom.lines import (
    Intersection,
    Line,
    ParallelLinesError,
    intersect,
)
from kinepoly.geom.vec import angle_of, cross, dot, norm, perp, rotate, unit

__all__ = [
    "Intersection",
    "Line",
    "ParallelLinesError",
    "angle_of",
    "cross",
    "dot",
    "intersect",
    "norm",
    "perp",
    "rotate",
    "unit",
]
