"""A cam's profile as a closed curve in the cam's own frame: points along it for drawing.

A circle profile is exact; a ``points`` profile (a periodic spline through the given points,
``geom.spline``) is sampled at equal steps of its chord-length parameter, starting at its first
point. Both go counter-clockwise.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Protocol

from kinepoly.geom.spline import periodic_spline

__all__ = ["Profile", "outline"]

Point = tuple[float, float]


class Profile(Protocol):
    """What a profile is made of (a scene's cam is one): a circle (``center``, ``radius``), or the points a
    closed spline runs through (``profile_points``, counter-clockwise) when ``is_spline``."""

    @property
    def center(self) -> Point: ...

    @property
    def radius(self) -> float: ...

    @property
    def profile_points(self) -> Sequence[Point]: ...

    @property
    def is_spline(self) -> bool: ...


def outline(cam: Profile, count: int = 180) -> list[Point]:
    """``count`` points along the profile of ``cam`` in the cam's frame, counter-clockwise, not closed."""
    if cam.is_spline:
        return [(z.real, z.imag) for z in periodic_spline(cam.profile_points).sample(count).tolist()]
    cx, cy = cam.center
    return [(cx + cam.radius * math.cos(2.0 * math.pi * k / count),
             cy + cam.radius * math.sin(2.0 * math.pi * k / count))
            for k in range(count)]
