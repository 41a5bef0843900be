"""The polygons of a spline cam's follower, through the instantaneously equivalent link K W.

At each row the profile's centre of curvature K at the contact (``engine.cam_place`` marked it) is a point
of the cam, and W (the knife edge, or the roller's centre, on the offset curve with the same centre of
curvature) stays |K W| from it to second order: the pair acts, for velocities and accelerations, as a binary
link K W pinned to the cam at K and to the follower at W (the Romanian text's K_A(-1), eq. 4 and 5). So W's
tip is found as in an RRR (a rocker) or RRP (a translating follower) dyad, with the direction lines of
``engine.lines`` and ``engine.results``:

* velocity: through k (the image of K on the cam) perpendicular to K W; through the tip of the pivot
  perpendicular to pivot-W, or through the tip of W's point of the guide along the slide;
* acceleration: from k the normal term omega_KW^2 |K W| toward K, then perpendicular to K W; the
  follower's normal term and perpendicular (a rocker), or the Coriolis term and the slide (a translating one).

omega_KW is read off the velocity crossing (the length of the first direction is |K W|).

A flat face: K stays the radius of curvature from the face to second order, so the pair acts as a block
pinned to the cam at K sliding on the follower parallel to the face (an RPR dyad for a rocker, PRP for a
translating follower). K's tip as a point of the follower is where the line through k along the face
crosses the follower's own line; for accelerations the Coriolis term 2 omega_follower x v (the block over
the face) is laid from k first.
"""

from __future__ import annotations

import numpy as np

from kinepoly.engine.cam_contact import centre_label, face_direction
from kinepoly.engine.cam_curves import follower_centre_label
from kinepoly.engine.groups import CamGroup
from kinepoly.engine.lines import (
    known_pairs,
    parallel,
    perpendicular,
    perpendicular_label,
    read_rate,
    record_intersection,
    revolute_line,
    slide_line,
    slide_rel,
)
from kinepoly.engine.polygon import Line, Polygon
from kinepoly.engine.results import along_normal, along_slide, record_crossing
from kinepoly.engine.steps import Direction, DrawnVector
from kinepoly.geom.arrays import Points
from kinepoly.model.mechanism import Joint, Revolute
from kinepoly.scene.spec import SliderSpec

__all__ = ["acceleration_by_cam", "velocity_by_cam"]


def _ends(group: CamGroup) -> tuple[str, str]:
    """K (the cam's point at the centre of curvature) and W (the follower's point; where the follower's profile
    is a spline, its own centre of curvature K2)."""
    if group.cam.is_curve_pair:
        return centre_label(group.cam), follower_centre_label(group.cam)
    return centre_label(group.cam), group.cam.point or ""


def _own_line(polygon: Polygon, group: CamGroup, point: str, size_link: str | None,
              tip: str) -> tuple[Line, str, str, Direction]:
    """The follower's own direction line for ``point``: perpendicular to pivot-point through the pivot's tip
    (a rocker), or along the slide through the tip of ``point`` on the guide; with its label, the known end
    of its term and the term's direction (``tip``: the unknown tip's label)."""
    joint = group.joint
    if isinstance(joint, Revolute):
        far = joint.point
        return (revolute_line(polygon, group.carrier, far, point, size_link),
                perpendicular_label(polygon, group.carrier, far, point), far,
                perpendicular(polygon, f"v_{tip}/{far}", group.carrier, far, point))
    assert isinstance(joint, SliderSpec)
    far = polygon.label(group.carrier, point)
    return (slide_line(polygon, joint, group.carrier, point),
            f"parallel to slider {joint.name} through {far.lower()}", far,
            parallel(polygon, f"v_{tip}/{far}", joint, group.carrier, point))


def _flat_velocity(polygon: Polygon, group: CamGroup, sliding: dict[str, Points],
                   equivalent: dict[str, Points]) -> None:
    """The block pinned at K on the cam slides along the face: K's tip as a point of the follower lies on
    the line through k along the face and on the follower's own line (about its pivot, or along its slide)."""
    k = centre_label(group.cam)
    on_cam = polygon.tip(group.known, k)
    along_face: Line = (on_cam, face_direction(polygon.positions.poses, group.cam), 1.0)
    label2 = f"parallel to the face of {group.link} through {polygon.label(group.known, k).lower()}"
    joint = group.joint
    line1, label1, far, direction1 = _own_line(polygon, group, k, None, polygon.label(group.link, k))
    crossing = polygon.cross_lines(line1, along_face, k, group.name, (label1, label2))
    tip = polygon.add_tip(group.link, k, crossing.point)
    equivalent[group.cam.name] = np.asarray(on_cam - crossing.point)  # v of the block over the face
    if polygon.record:
        k_label = polygon.label(group.known, k)
        record_intersection(polygon, tip, f"v_{tip} = v_{far} + v_{tip}/{far} = v_{k_label} + v_{tip}/{k_label}",
                             line1, along_face, (label1, label2), crossing,
                             known_pairs((f"v_{far}", f"v_{tip}/{far}"), (f"v_{k_label}", f"v_{tip}/{k_label}")),
                             (direction1, Direction(f"v_{tip}/{k_label}", "face", group.link, k_label.lower())))
    if isinstance(joint, Revolute):
        read_rate(polygon, group.link, joint.point, tip, crossing.along_first)
    else:
        slide_rel(polygon, joint, group.link, k, sliding)


def velocity_by_cam(polygon: Polygon, group: CamGroup, sliding: dict[str, Points],
                    equivalent: dict[str, Points]) -> None:
    if group.cam.kind == "flat":
        _flat_velocity(polygon, group, sliding, equivalent)
        return
    k, w = _ends(group)
    line1 = revolute_line(polygon, group.known, k, w, None)
    label1 = perpendicular_label(polygon, group.known, k, w)
    joint = group.joint
    tip = polygon.label(group.link, w)  # W itself, or K2@follower for a follower profile of points
    line2, label2, far, direction2 = _own_line(polygon, group, w, None if group.cam.is_curve_pair else group.link, tip)
    crossing = polygon.cross_lines(line1, line2, w, group.name, (label1, label2))
    tip = polygon.add_tip(group.link, w, crossing.point)
    equivalent[group.cam.name] = np.asarray(crossing.along_first + 0j)
    k_label = polygon.label(group.known, k)
    if polygon.record:
        record_intersection(polygon, tip, f"v_{tip} = v_{k_label} + v_{tip}/{k_label} = v_{far} + v_{tip}/{far}",
                            line1, line2,
                             (label1, label2), crossing,
                             known_pairs((f"v_{k_label}", f"v_{tip}/{k_label}"), (f"v_{far}", f"v_{tip}/{far}")),
                             (perpendicular(polygon, f"v_{tip}/{k_label}", group.known, k, w), direction2))
    if isinstance(joint, Revolute):
        read_rate(polygon, group.link, joint.point, tip, crossing.along_second())
    else:
        slide_rel(polygon, joint, group.link, w, sliding)


def _flat_acceleration(ctx: object, group: CamGroup) -> None:
    """a_K@cam = a_K@follower + a^c (2 omega_follower x the block's velocity over the face) + a term along the
    face: the line through a_K@cam - a^c along the face, crossed with the follower's own line."""
    b: Polygon = ctx.b  # type: ignore[attr-defined]
    k = centre_label(group.cam)
    on_cam = b.tip(group.known, k)
    relative = ctx.v.equivalent[group.cam.name]  # type: ignore[attr-defined]
    coriolis = np.asarray(ctx.rules.coriolis * 2.0 * b.omega_of(group.link) * (1j * relative))  # type: ignore[attr-defined]
    start = np.asarray(on_cam - coriolis)
    along_face: Line = (start, face_direction(b.positions.poses, group.cam), 1.0)
    joint = group.joint
    line1: Line
    laid: list[DrawnVector] = []
    if isinstance(joint, Revolute):
        line1, normal, label1 = ctx.normal_line(group.carrier, joint.point, k, group.link, rigid=False)  # type: ignore[attr-defined]
        laid += [normal] if normal else []
    else:
        assert isinstance(joint, SliderSpec)
        line1, slid = ctx.slide_line(joint, group.carrier, group.link, k)  # type: ignore[attr-defined]
        laid += slid
        label1 = f"sliding term along slider {joint.name}"
    label2 = f"along the face of {group.link}, after the Coriolis term"
    crossing = b.cross_lines(line1, along_face, k, group.name, (label1, label2))
    tip = b.add_tip(group.link, k, crossing.point)
    if b.record:
        k_label = b.label(group.known, k)
        far = joint.point if isinstance(joint, Revolute) else b.label(group.carrier, k)
        term = f"a^c_{tip}/{k_label}"
        vectors = [*laid, DrawnVector(term, b.vec(on_cam), b.vec(start), "coriolis")]
        own = (along_normal(ctx, f"a^t_{tip}/{far}", group.carrier, far, k, laid[-1] if laid else None)  # type: ignore[arg-type]
               if isinstance(joint, Revolute) else along_slide(ctx, f"a_{tip}/{far}", joint, group.carrier, k, laid))  # type: ignore[arg-type]
        record_crossing(ctx, tip, f"a_{tip} = {_own_side(joint, tip, far, laid)} = a_{k_label} + "  # type: ignore[arg-type]
                                  f"{term} + a_{tip}/{k_label}",
                line1, along_face, (label1, label2), crossing, vectors,
                (own, Direction(f"a_{tip}/{k_label}", "face", group.link, k_label.lower(), after=term)))
    if isinstance(joint, Revolute):
        read_rate(b, group.link, joint.point, tip, crossing.along_first)
    else:
        ctx.slide_values(joint, group.link, k)  # type: ignore[attr-defined]


def _own_side(joint: Joint, tip: str, far: str, laid: list[DrawnVector]) -> str:
    """The follower's side of an acceleration equation: about its pivot, or along its slide (with the
    Coriolis term where the guide turns)."""
    if isinstance(joint, Revolute):
        return f"a_{far} + a^n_{tip}/{far} + a^t_{tip}/{far}"
    return "".join([f"a_{far}", *(f" + {v.label}" for v in laid if v.term == "coriolis"), f" + a_{tip}/{far}"])


def acceleration_by_cam(ctx: object, group: CamGroup) -> None:
    """The acceleration polygon's part (``ctx`` is ``engine.acceleration``'s context)."""
    if group.cam.kind == "flat":
        _flat_acceleration(ctx, group)
        return
    b: Polygon = ctx.b  # type: ignore[attr-defined]
    k, w = _ends(group)
    omega = np.asarray(ctx.v.equivalent[group.cam.name].real)  # type: ignore[attr-defined]
    named = b.label(group.link, w)  # W itself, or K2@follower for a follower profile of points
    line1, n1, label1 = ctx.normal_line(group.known, k, w, group.link, rigid=False, omega=omega,  # type: ignore[attr-defined]
                                        name=named)
    vectors: list[DrawnVector] = [n1] if n1 else []
    joint = group.joint
    line2: Line
    if isinstance(joint, Revolute):
        line2, n2, label2 = ctx.normal_line(group.carrier, joint.point, w, group.link,  # type: ignore[attr-defined]
                                            rigid=not group.cam.is_curve_pair, name=named)
        vectors += [n2] if n2 else []
        laid: list[DrawnVector] = []
    else:
        assert isinstance(joint, SliderSpec)
        line2, laid = ctx.slide_line(joint, group.carrier, group.link, w)  # type: ignore[attr-defined]
        label2 = f"sliding term along slider {joint.name}"
    crossing = b.cross_lines(line1, line2, w, group.name, (label1, label2))
    tip = b.add_tip(group.link, w, crossing.point)  # W itself, or K2@follower for a follower profile of points
    if b.record:
        k_label = b.label(group.known, k)
        far = joint.point if isinstance(joint, Revolute) else b.label(group.carrier, w)
        second = (along_normal(ctx, f"a^t_{tip}/{far}", group.carrier, far, w,  # type: ignore[arg-type]
                               vectors[-1] if len(vectors) > 1 else None)
                  if isinstance(joint, Revolute) else along_slide(ctx, f"a_{tip}/{far}", joint, group.carrier, w, laid))  # type: ignore[arg-type]
        record_crossing(ctx, tip, f"a_{tip} = a_{k_label} + a^n_{tip}/{k_label} + a^t_{tip}/{k_label} = "  # type: ignore[arg-type]
                                  f"{_own_side(joint, tip, far, laid)}",
                line1, line2, (label1, label2), crossing, [*vectors, *laid],
                (along_normal(ctx, f"a^t_{tip}/{k_label}", group.known, k, w, n1), second))  # type: ignore[arg-type]
    if isinstance(joint, Revolute):
        read_rate(b, group.link, joint.point, tip, crossing.along_second())
    else:
        ctx.slide_values(joint, group.link, w)  # type: ignore[attr-defined]

