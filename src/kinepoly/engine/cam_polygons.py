"""The polygons of a spline cam's follower, through the instantaneously equivalent link K W.

At each row the profile's centre of curvature K at the contact (``engine.cam_place`` marked it) is a point
of the cam, and W (the knife edge, or the roller's centre, on the offset curve with the same centre of
curvature) stays |K W| from it to second order: the pair acts, for velocities and accelerations, as a binary
link K W pinned to the cam at K and to the follower at W (the Romanian text's K_A(-1), eq. 4 and 5). So W's
tip is found as in an RRR (a rocker) or RRP (a translating follower) dyad, with the direction lines of
``engine.velocity`` and ``engine.acceleration``:

* velocity: through k (the image of K on the cam) perpendicular to K W; through the tip of the pivot
  perpendicular to pivot-W, or through the tip of W's point of the guide along the slide;
* acceleration: from k the normal term omega_KW^2 |K W| toward K, then perpendicular to K W; the
  follower's normal term and perpendicular (a rocker), or the Coriolis term and the slide (a translating one).

omega_KW is read off the velocity crossing (the length of the first direction is |K W|).
"""

from __future__ import annotations

from kinepoly.engine.cam_contact import centre_label
from kinepoly.engine.plan import CamGroup
from kinepoly.engine.polygon import Line, Polygon
from kinepoly.engine.steps import DrawnVector
from kinepoly.engine.velocity import (
    _known_pairs,
    _parallel,
    _perpendicular,
    _perpendicular_label,
    _record_intersection,
    _revolute_line,
    _slide_line,
    _slide_rel,
    read_rate,
)
from kinepoly.geom.arrays import Points, Reals
from kinepoly.model.mechanism import Revolute
from kinepoly.scene.spec import SliderSpec

__all__ = ["acceleration_by_cam", "velocity_by_cam"]


def _ends(group: CamGroup) -> tuple[str, str]:
    """K (the cam's point at the centre of curvature) and W (the follower's point)."""
    return centre_label(group.cam), group.cam.point or ""


def velocity_by_cam(polygon: Polygon, group: CamGroup, sliding: dict[str, Points],
                    equivalent: dict[str, Reals]) -> None:
    k, w = _ends(group)
    line1 = _revolute_line(polygon, group.known, k, w, None)
    label1 = _perpendicular_label(polygon, group.known, k, w)
    joint = group.joint
    if isinstance(joint, Revolute):
        line2 = _revolute_line(polygon, group.carrier, joint.point, w, group.link)
        label2 = _perpendicular_label(polygon, group.carrier, joint.point, w)
    else:
        assert isinstance(joint, SliderSpec)
        line2 = _slide_line(polygon, joint, group.carrier, w)
        label2 = f"parallel to slider {joint.name} through {polygon.label(group.carrier, w).lower()}"
    crossing = polygon.cross_lines(line1, line2, w, group.name, (label1, label2))
    polygon.add_tip(group.link, w, crossing.point)
    equivalent[group.cam.name] = crossing.along_first
    k_label = polygon.label(group.known, k)
    if polygon.record:
        if isinstance(joint, Revolute):
            far = joint.point
            direction2 = _perpendicular(polygon, f"v_{w}/{far}", group.carrier, far, w)
        else:
            far = polygon.label(group.carrier, w)
            direction2 = _parallel(polygon, f"v_{w}/{far}", joint, group.carrier, w)
        _record_intersection(polygon, w, f"v_{w} = v_{k_label} + v_{w}/{k_label} = v_{far} + v_{w}/{far}", line1, line2,
                             (label1, label2), crossing,
                             _known_pairs((f"v_{k_label}", f"v_{w}/{k_label}"), (f"v_{far}", f"v_{w}/{far}")),
                             (_perpendicular(polygon, f"v_{w}/{k_label}", group.known, k, w), direction2))
    if isinstance(joint, Revolute):
        read_rate(polygon, group.link, joint.point, w, crossing.along_second())
    else:
        _slide_rel(polygon, joint, group.link, w, sliding)


def acceleration_by_cam(ctx: object, group: CamGroup) -> None:
    """The acceleration polygon's part (``ctx`` is ``engine.acceleration``'s context)."""
    from kinepoly.engine.acceleration import _along_normal, _along_slide, _record

    b: Polygon = ctx.b  # type: ignore[attr-defined]
    k, w = _ends(group)
    omega = ctx.v.equivalent[group.cam.name]  # type: ignore[attr-defined]
    line1, n1, label1 = ctx.normal_line(group.known, k, w, group.link, rigid=False, omega=omega)  # type: ignore[attr-defined]
    vectors: list[DrawnVector] = [n1] if n1 else []
    joint = group.joint
    line2: Line
    if isinstance(joint, Revolute):
        line2, n2, label2 = ctx.normal_line(group.carrier, joint.point, w, group.link)  # type: ignore[attr-defined]
        vectors += [n2] if n2 else []
        laid: list[DrawnVector] = []
    else:
        assert isinstance(joint, SliderSpec)
        line2, laid = ctx.slide_line(joint, group.carrier, group.link, w)  # type: ignore[attr-defined]
        label2 = f"sliding term along slider {joint.name}"
    crossing = b.cross_lines(line1, line2, w, group.name, (label1, label2))
    b.add_tip(group.link, w, crossing.point)
    if b.record:
        k_label = b.label(group.known, k)
        far = joint.point if isinstance(joint, Revolute) else b.label(group.carrier, w)
        second = (_along_normal(ctx, f"a^t_{w}/{far}", group.carrier, far, w, vectors[-1] if len(vectors) > 1 else None)  # type: ignore[arg-type]
                  if isinstance(joint, Revolute) else _along_slide(ctx, f"a_{w}/{far}", joint, group.carrier, w, laid))  # type: ignore[arg-type]
        _record(ctx, w, f"a_{w} = a_{k_label} + a^n_{w}/{k_label} + a^t_{w}/{k_label} = a_{far} + a_{w}/{far}",  # type: ignore[arg-type]
                line1, line2, (label1, label2), crossing, [*vectors, *laid],
                (_along_normal(ctx, f"a^t_{w}/{k_label}", group.known, k, w, n1), second))  # type: ignore[arg-type]
    if isinstance(joint, Revolute):
        read_rate(b, group.link, joint.point, w, crossing.along_second())
    else:
        ctx.slide_values(joint, group.link, w)  # type: ignore[attr-defined]

