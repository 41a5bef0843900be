"""One row of a batch as plain values: what a solve reports, drawings draw and handouts explain.

A solve is a batch of one: these frozen values are row 0 of the engine's arrays, with the
steps the polygons recorded.
"""

from __future__ import annotations

from msgspec import Struct

from kinepoly.engine.acceleration import AccelerationResult
from kinepoly.engine.position import Positions
from kinepoly.engine.steps import Step
from kinepoly.engine.velocity import VelocityResult
from kinepoly.geom.arrays import Points, Reals
from kinepoly.model.pose import Pose

__all__ = ["AccelerationPolygon", "SliderValues", "VelocityPolygon", "acceleration_row", "pose_row", "velocity_row"]

Vec = tuple[float, float]


class VelocityPolygon(Struct, frozen=True):
    """Tips (physical velocities, pole at 0), omegas, sliding velocities, steps, and each link's known tips."""

    tips: dict[str, Vec]
    omega: dict[str, float]
    sliding: dict[str, Vec]
    steps: tuple[Step, ...]
    members: dict[str, list[tuple[str, Vec]]]


class SliderValues(Struct, frozen=True):
    """A slider's s, and where the polygons were constructed s_dot, s_ddot and the Coriolis term."""

    s: float
    s_dot: float | None
    s_ddot: float | None
    coriolis: Vec | None


class AccelerationPolygon(Struct, frozen=True):
    """Tips (physical accelerations, pole at 0), alphas, sliding accelerations, Coriolis terms, steps."""

    tips: dict[str, Vec]
    alpha: dict[str, float]
    sliding: dict[str, Vec]
    coriolis: dict[str, Vec]
    steps: tuple[Step, ...]
    members: dict[str, list[tuple[str, Vec]]]


def _vec(z: Points, k: int) -> Vec:
    c = complex(z[k])
    return (c.real, c.imag)


def _vectors(values: dict[str, Points], k: int) -> dict[str, Vec]:
    return {name: _vec(z, k) for name, z in values.items()}


def _rates(values: dict[str, Reals], k: int) -> dict[str, float]:
    return {name: float(x[k]) for name, x in values.items()}


def pose_row(positions: Positions, k: int = 0) -> Pose:
    return Pose(positions.row(k), _vectors(positions.marks, k))


def velocity_row(result: VelocityResult, k: int = 0) -> VelocityPolygon:
    polygon = result.polygon
    members = {link: [(m.label, _vec(polygon.at(m), k)) for m in entries] for link, entries in polygon.members.items()}
    return VelocityPolygon(_vectors(polygon.tips, k), _rates(polygon.rate, k), _vectors(result.sliding, k),
                           tuple(polygon.steps), members)


def acceleration_row(result: AccelerationResult, k: int = 0) -> AccelerationPolygon:
    polygon = result.polygon
    members = {link: [(m.label, _vec(polygon.at(m), k)) for m in entries] for link, entries in polygon.members.items()}
    return AccelerationPolygon(_vectors(polygon.tips, k), _rates(polygon.rate, k), _vectors(result.sliding, k),
                               _vectors(result.coriolis, k), tuple(polygon.steps), members)
