"""Carried dyad kind: an RRR dyad whose first side is two links held together by a driven joint (a motor, a
cylinder): closed like any dyad (``engine.closures``, ``engine.carry``); in the polygons the drive's relative
term is laid from the carrier's known tip before the line across the carrier's span."""

from __future__ import annotations

import numpy as np

from kinepoly.engine.carry import relative_acceleration, relative_velocity
from kinepoly.engine.closures import other_side
from kinepoly.engine.groups import CarriedDyad, free_joints
from kinepoly.engine.kind import Kind
from kinepoly.engine.kinds import dyad as dyads
from kinepoly.engine.lines import (
    add_motor_rate,
    perpendicular,
    perpendicular_label,
    read_rate,
    record_drive_term,
    record_intersection,
    revolute_line,
    slide_direction,
)
from kinepoly.engine.polygon import Line, Polygon
from kinepoly.engine.results import AccelerationContext, VelocityContext, along_normal, normals_step, record_crossing
from kinepoly.engine.steps import Direction, DrawnVector
from kinepoly.geom.arrays import Points
from kinepoly.model.mechanism import Drive, Mechanism, Revolute, joint_links

__all__ = ["KIND", "acceleration", "carried_parts", "drive_geometry", "find", "velocity"]


def find(mechanism: Mechanism, known: set[str]) -> CarriedDyad | None:
    """An RRR dyad whose first side is two unknown links held together by a driven joint."""
    for drive in mechanism.drives:
        if drive.on_frame or drive.moving in known or drive.base in known:
            continue
        for carrier, first in ((drive.moving, drive.base), (drive.base, drive.moving)):
            outer = [jt for jt in free_joints(mechanism, carrier) if any(x in known for x in joint_links(jt))]
            rest = [jt for jt in free_joints(mechanism, first) if jt not in outer]
            inner = [jt for jt in rest if all(x not in known for x in joint_links(jt))]
            if len(outer) != 1 or len(inner) != 1 or any(jt for jt in rest if jt not in inner):
                continue
            second = next(x for x in joint_links(inner[0]) if x != first)
            if second == carrier:
                continue
            outer_second = [jt for jt in free_joints(mechanism, second) if any(x in known for x in joint_links(jt))]
            if len(outer_second) != 1:
                continue
            if not all(isinstance(jt, Revolute) for jt in (outer[0], inner[0], outer_second[0])):
                continue
            return CarriedDyad("RRR", first, second, outer[0], inner[0], outer_second[0], carrier, drive)
    return None


def carried_parts(dyad: CarriedDyad) -> tuple[str, str, str, Drive, tuple[str, str, str], tuple[str, str]]:
    """A carried RRR dyad's links (first, second, carrier), its drive, its three pins (the carrier's known
    one, the inner one, the second link's known one) and the known links across the two outer pins."""
    carrier, drive = dyad.carrier, dyad.drive
    assert carrier is not None and drive is not None
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
    assert isinstance(dyad.second_joint, Revolute)
    pins = (dyad.first_joint.point, dyad.inner.point, dyad.second_joint.point)
    return (dyad.first, dyad.second, carrier, drive, pins,
            (other_side(dyad.first_joint, carrier), other_side(dyad.second_joint, dyad.second)))


def drive_geometry(polygon: Polygon, dyad: CarriedDyad) -> tuple[Points, Points | None, Points | None]:
    """For a carried dyad: where its inner joint is, the motor's pin (or None), the slide's direction (or None)."""
    drive = dyad.drive
    assert drive is not None and isinstance(dyad.inner, Revolute)
    at = polygon.world(dyad.inner.point)
    if isinstance(drive.joint, Revolute):
        return at, polygon.world(drive.joint.point), None
    return at, None, slide_direction(polygon.positions, drive.joint)


def velocity(state: VelocityContext, dyad: CarriedDyad) -> None:
    """A carried RRR dyad: the drive's relative velocity is laid from the carrier's known tip, then the
    line perpendicular to the carrier's span; the second link's line as in any RRR dyad."""
    polygon, sliding = state.polygon, state.sliding
    i, j, carrier, drive, (p1, p2, p3), (k1, k2) = carried_parts(dyad)
    at, pin, slide = drive_geometry(polygon, dyad)
    rel = relative_velocity(drive, i, at, pin, slide)
    start = polygon.tip(k1, p1)
    moved = np.asarray(start + rel)
    on_carrier = polygon.label(carrier, p2)
    line1: Line = (moved, np.asarray(1j * (at - polygon.world(p1))), None)
    line2 = revolute_line(polygon, k2, p3, p2, j)
    labels = (perpendicular_label(polygon, k1, p1, p2), perpendicular_label(polygon, k2, p3, p2))
    if polygon.record:
        record_drive_term(polygon, drive, f"v_{p2}/{on_carrier}", start, moved, p2, carrier,
                          polygon.label(k1, p1).lower())
    crossing = polygon.cross_lines(line1, line2, p2, dyad.name, labels)
    polygon.add_tip(i, p2, crossing.point)
    polygon.add_tip(carrier, p2, np.asarray(crossing.point - rel))
    if polygon.record:
        record_intersection(polygon, p2, f"v_{p2} = v_{p1} + v_{p2}/{on_carrier} + v_{on_carrier}/{p1} = v_{p3} + "
                             f"v_{p2}/{p3}", line1, line2, labels, crossing,
                             ((f"v_{p1}", "magnitude and direction"),
                              (f"v_{p2}/{on_carrier}", "magnitude and direction"),
                              (f"v_{on_carrier}/{p1}", "direction"), (f"v_{p3}", "magnitude and direction"),
                              (f"v_{p2}/{p3}", "direction")),
                             (Direction(f"v_{on_carrier}/{p1}", "perpendicular", f"{p1}{p2}",
                                        polygon.label(k1, p1).lower(), after=f"v_{p2}/{on_carrier}"),
                              perpendicular(polygon, f"v_{p2}/{p3}", k2, p3, p2)),
                             (DrawnVector(f"v_{p2}/{on_carrier}", polygon.vec(start), polygon.vec(moved), "relative"),))
    read_rate(polygon, carrier, p1, on_carrier, crossing.along_first)
    if isinstance(drive.joint, Revolute):
        add_motor_rate(polygon, drive, i, carrier, crossing.along_first)
    else:
        sliding[drive.joint.name] = np.asarray(drive.rate(1) * slide_direction(polygon.positions, drive.joint))
    read_rate(polygon, j, p3, p2, crossing.along_second())


def acceleration(ctx: AccelerationContext, dyad: CarriedDyad) -> None:
    """A carried RRR dyad: the carrier's normal term and the drive's relative acceleration laid from the
    carrier's known tip, then the line perpendicular to the carrier's span; the second link as in any RRR."""
    b = ctx.b
    i, j, carrier, drive, (p1, p2, p3), (k1, k2) = carried_parts(dyad)
    at, pin, slide = drive_geometry(b, dyad)
    omega_i, omega_c = b.omega_of(i), b.omega_of(carrier)
    rel = relative_acceleration(drive, i, at, pin, slide, omega_i, omega_c, omega_c)
    on_carrier = b.label(carrier, p2)
    (start, direction, _), n1, label1 = ctx.normal_line(k1, p1, p2, carrier, rigid=False)
    if n1 is not None:
        n1 = DrawnVector(f"a^n_{on_carrier}/{p1}", n1.start, n1.end, "normal")
    moved = np.asarray(start + rel)
    line1: Line = (moved, direction, None)
    line2, n2, label2 = ctx.normal_line(k2, p3, p2, j)
    vectors = [v for v in (n1, n2) if v is not None]
    if b.record:
        normals_step(ctx, vectors)
        record_drive_term(b, drive, f"a_{p2}/{on_carrier}", start, moved, p2, carrier,
                          n1.label if n1 is not None else b.label(k1, p1).lower())
    crossing = b.cross_lines(line1, line2, p2, dyad.name, (label1, label2))
    b.add_tip(i, p2, crossing.point)
    b.add_tip(carrier, p2, np.asarray(crossing.point - rel))
    if b.record:
        drawn = vectors + [DrawnVector(f"a_{p2}/{on_carrier}", b.vec(start), b.vec(moved), "relative")]
        record_crossing(ctx, p2, f"a_{p2} = a_{p1} + a^n_{on_carrier}/{p1} + a_{p2}/{on_carrier} + "
                f"a^t_{on_carrier}/{p1} = a_{p3} + a^n_{p2}/{p3} + a^t_{p2}/{p3}", line1, line2, (label1, label2),
                crossing, drawn,
                (Direction(f"a^t_{on_carrier}/{p1}", "perpendicular", f"{p1}{p2}", b.label(k1, p1).lower(),
                           after=f"a_{p2}/{on_carrier}"),
                 along_normal(ctx, f"a^t_{p2}/{p3}", k2, p3, p2, n2)))
    read_rate(b, carrier, p1, on_carrier, crossing.along_first)
    if isinstance(drive.joint, Revolute):
        add_motor_rate(b, drive, i, carrier, crossing.along_first)
    else:
        assert slide is not None
        ctx.sliding[drive.joint.name] = np.asarray(drive.rate(2) * slide)
        ctx.coriolis[drive.joint.name] = np.asarray(2.0 * omega_c * (1j * drive.rate(1) * slide))
    read_rate(b, j, p3, p2, crossing.along_second())


KIND: Kind[CarriedDyad] = Kind(find, dyads.place, velocity, acceleration, batched=True)
