"""A cam's profile as a closed curve in the cam's own frame: points along it for drawing.

A circle profile is exact; a ``points`` profile (a periodic spline through the given points,
``geom.spline``) is sampled at equal steps of its chord-length parameter, starting at its first
point. Both go counter-clockwise.
"""

from __future__ import annotations

import math

from kinepoly.geom.spline import periodic_spline
from kinepoly.scene.spec import CamSpec

__all__ = ["outline"]

Point = tuple[float, float]


def outline(cam: CamSpec, count: int = 180) -> list[Point]:
    """``count`` points along the profile of ``cam`` in the cam's frame, counter-clockwise, not closed."""
    if cam.is_spline:
        return [(z.real, z.imag) for z in periodic_spline(cam.profile_points).sample(count).tolist()]
    cx, cy = cam.center
    return [(cx + cam.radius * math.cos(2.0 * math.pi * k / count), cy + cam.radius * math.sin(2.0 * math.pi * k / count))
            for k in range(count)]
