"""The motion of a block along its guide at every row: s, s_dot, s_ddot and the Coriolis term.

s is the block's point measured along the slide from the guide's ``through`` point; s_dot and
s_ddot are the sliding velocity and acceleration (the block relative to the guide, along the
slide), read off the polygons; the Coriolis term is the one the acceleration polygon laid.
"""

from __future__ import annotations

import numpy as np
from msgspec import Struct

from kinepoly.engine.acceleration import AccelerationResult
from kinepoly.engine.position import Positions
from kinepoly.engine.velocity import VelocityResult, slide_direction
from kinepoly.geom.arrays import Points, Reals, dot
from kinepoly.scene.spec import SliderSpec

__all__ = ["SliderMotion", "slider_motion"]


class SliderMotion(Struct, frozen=True):
    """A slider's s at every row, and where the polygons were constructed s_dot, s_ddot and Coriolis."""

    s: Reals
    s_dot: Reals | None
    s_ddot: Reals | None
    coriolis: Points | None


def slider_motion(positions: Positions, spec: SliderSpec, velocity: VelocityResult | None = None,
                  acceleration: AccelerationResult | None = None) -> SliderMotion:
    e = slide_direction(positions, spec)
    through = positions.poses[spec.guide].world(positions.mechanism.slide_through(spec))
    s = dot(e, positions.point(spec.point) - through)
    s_dot = dot(e, velocity.sliding[spec.name]) if velocity is not None else None
    s_ddot = dot(e, acceleration.sliding[spec.name]) if acceleration is not None else None
    coriolis = np.asarray(acceleration.coriolis[spec.name]) if acceleration is not None else None
    return SliderMotion(s, s_dot, s_ddot, coriolis)
