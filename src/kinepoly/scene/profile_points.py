"""A cam's ``profile = { points = [[x, y], ...] }``: the points a closed spline runs through, checked.

What a closed smooth profile needs of its points, each problem named by its key path:
at least 4 of them, each ``[x, y]`` in the scene's length unit; no two consecutive points (the last
and the first included) at one place, so the first is not repeated at the end; listed
counter-clockwise (positive area); and the spline through them turning once round (a spline that
makes a loop or a figure eight turns twice or not at all, which no cam profile does).
"""

from __future__ import annotations

import math

import numpy as np

from kinepoly.geom.spline import periodic_spline, signed_area
from kinepoly.scene.lines import KeyPath
from kinepoly.scene.problems import ProblemReport, show_value
from kinepoly.scene.spec import Vector
from kinepoly.scene.units import Kind, quantity_pair

__all__ = ["MIN_PROFILE_POINTS", "read_profile_points"]

MIN_PROFILE_POINTS = 4
"""The fewest points a ``points`` profile may have."""
_TURN_SAMPLES_PER_PIECE = 16
"""Samples of each spline piece when its turning is counted."""
_OVERFLOW = ("the area or the spline of these points overflows double precision (a coordinate too large); "
             "expected coordinates of ordinary size, in the scene's length unit")


def read_profile_points(report: ProblemReport, path: KeyPath, value: object, kind: Kind) -> tuple[Vector, ...] | None:
    """The points of ``profile.points`` at ``path``, or None with the problems reported."""
    example = "points = [[40, 0], [0, 30], [-40, 0], [0, -30]], counter-clockwise"
    if not isinstance(value, list) or len(value) < MIN_PROFILE_POINTS:
        count = f"{len(value)} points" if isinstance(value, list) else show_value(value)
        report.add(path, f"expected at least {MIN_PROFILE_POINTS} points [x, y] of a closed curve, got {count}; "
                   f"e.g. {example}")
        return None
    read = [quantity_pair(report, path + (str(k),), item, kind) for k, item in enumerate(value, start=1)]
    points = [p for p in read if p is not None]
    if len(points) != len(read):
        return None
    n = len(points)
    for k in range(n):
        (x0, y0), (x1, y1) = points[k], points[(k + 1) % n]
        if x0 == x1 and y0 == y1:
            if k == n - 1:
                report.add(path + (str(n),), f"the last point repeats the first {show_value(list(points[0]))}; "
                           "the curve closes by itself: drop the last point")
            else:
                report.add(path + (str(k + 2),), f"repeats point {k + 1} {show_value(list(points[k]))}; "
                           "expected each point once")
            return None
    with np.errstate(all="ignore"):
        area = signed_area(points)
    if not math.isfinite(area):
        report.add(path, _OVERFLOW)
        return None
    if area <= 0.0:
        report.add(path, "the points run clockwise (or enclose no area); expected them counter-clockwise: "
                   "list them in the reverse order")
        return None
    turns = _turns(points)
    if turns is None:
        report.add(path, _OVERFLOW)
        return None
    if turns != 1:
        report.add(path, f"the spline through these points turns {turns} times round instead of once (it makes a "
                   "loop or crosses itself); expected the points in order along one closed curve")
        return None
    return tuple(points)


def _turns(points: list[Vector]) -> int | None:
    """How many times the spline's tangent turns round along the curve; None where it overflows."""
    with np.errstate(all="ignore"):
        spline = periodic_spline(points)
        count = _TURN_SAMPLES_PER_PIECE * spline.pieces
        tangent = spline.frame(spline.period * np.arange(count + 1) / count).tangent
        turning = float(np.sum(np.angle(tangent[1:] / tangent[:-1])))
    return round(turning / (2.0 * np.pi)) if math.isfinite(turning) else None
