"""The construction of one row as a solve reports it: positions, then the polygons, then the sliders.

``kinepoly.solve`` (with its steps, strict), the bench (with another crossing primitive) and the
homework checker (with a construction mistake switched in) all construct a row through here.
"""

from __future__ import annotations

import numpy as np
from msgspec import Struct

from kinepoly.engine.acceleration import RIGHT, Rules, construct_acceleration
from kinepoly.engine.assembly import position_at_input
from kinepoly.engine.contacts import ContactRows, contacts_over_rows, polygon_velocity
from kinepoly.engine.groups import PositionPlan
from kinepoly.engine.polygon import CrossLines
from kinepoly.engine.position import Positions
from kinepoly.engine.row import (
    AccelerationPolygon,
    SliderValues,
    VelocityPolygon,
    acceleration_row,
    pose_row,
    velocity_row,
)
from kinepoly.engine.sliders import slider_motion
from kinepoly.engine.velocity import construct_velocity
from kinepoly.geom.arrays import cross_lines
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import Pose

__all__ = ["Construction", "Wanted", "construct_row"]

Vec = tuple[float, float]


class Wanted(Struct, frozen=True):
    """What to construct: (link, point) tips of each polygon, whether each polygon is needed, sliders."""

    velocity: tuple[tuple[str, str], ...]
    acceleration: tuple[tuple[str, str], ...]
    needs_velocity: bool
    needs_acceleration: bool
    sliders: tuple[str, ...]


class Construction(Struct, frozen=True):
    """Row 0 constructed: the positions (arrays), the pose, the polygons and the asked sliders' motion."""

    positions: Positions
    pose: Pose
    velocity: VelocityPolygon | None
    acceleration: AccelerationPolygon | None
    sliders: dict[str, SliderValues]
    contacts: dict[str, ContactRows]
    """Each higher pair's contact, on the batch of one row (``engine.contacts``)."""


def _value(x: np.ndarray | None) -> float | None:
    return None if x is None else float(x[0])


def _vector(z: np.ndarray | None) -> Vec | None:
    return None if z is None else (float(z[0].real), float(z[0].imag))


def construct_row(mechanism: Mechanism, plan: PositionPlan, wanted: Wanted, *, origin: Vec = (0.0, 0.0),
                  unit: str = "mm", record: bool = False, strict: bool = True, crossing: CrossLines = cross_lines,
                  rules: Rules = RIGHT) -> Construction:
    """Positions at the scene's input (nearest the ``[guess]``), then what ``wanted`` asks of the polygons."""
    with np.errstate(all="ignore"):  # strict: a singular row raises by name; the caller checks what overflowed
        positions = position_at_input(mechanism, plan, origin)
        velocity = acceleration = None
        if wanted.needs_velocity:
            velocity = construct_velocity(positions, plan, wanted.velocity, unit=unit, record=record, strict=strict,
                                          crossing=crossing)
            if wanted.needs_acceleration:
                acceleration = construct_acceleration(velocity, plan, wanted.acceleration, unit=unit, record=record,
                                                      strict=strict, rules=rules, crossing=crossing)
        sliders = {}
        for name in wanted.sliders:
            motion = slider_motion(positions, mechanism.slider(name), velocity, acceleration)
            sliders[name] = SliderValues(float(motion.s[0]), _value(motion.s_dot), _value(motion.s_ddot),
                                         _vector(motion.coriolis))
        moving = polygon_velocity(mechanism, velocity.polygon) if velocity is not None else None
        contacts = contacts_over_rows(mechanism, positions.poses, moving, positions.contact_parameters)
    return Construction(positions, pose_row(positions), velocity_row(velocity) if velocity else None,
                        acceleration_row(acceleration) if acceleration else None, sliders, contacts)
