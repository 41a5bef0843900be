"""The contacts of the higher pairs at one row: where they touch, the common normal, the sliding velocity.

For a cam (a circle of centre K and radius R on the cam): a roller or knife edge at W touches on the
line K W, a flat face at the foot of the perpendicular from K; the normal points from the cam's side
to the follower's. For gears the contact is the pitch point and the normal the line of centres, from
the first gear's side to the second's; gears roll, so the sliding velocity is zero. The sliding
velocity is the follower's contact point's velocity relative to the cam's, along the common tangent.
The steps record, for each cam, that its equivalent link is used and where its ends are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from kinepoly.engine.gears import mesh
from kinepoly.engine.polygon import Polygon
from kinepoly.engine.row import VelocityPolygon
from kinepoly.engine.steps import Step
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import CamSpec

__all__ = ["Contact", "contact_links", "contacts_at", "record_equivalent_links"]

Vec = tuple[float, float]


@dataclass(frozen=True)
class Contact:
    """One pair's contact: the point (frame), the unit normal (cam side to follower side) and, where the
    velocity polygon was built, the sliding velocity along the tangent."""

    point: Vec
    normal: Vec
    sliding_velocity: Vec | None


def contact_links(mechanism: Mechanism) -> set[str]:
    """The links a contact needs placed."""
    out = {link for gear in mechanism.scene.gears for link in gear.links}
    out |= {link for cam in mechanism.scene.cams for link in (cam.cam, cam.follower, cam.equivalent) if link}
    return out


def _velocity(velocity: VelocityPolygon, mechanism: Mechanism, link: str, at: complex) -> complex | None:
    if link == mechanism.ground:
        return 0j
    omega = velocity.omega.get(link)
    members = velocity.members.get(link, [])
    if omega is None or not members:
        return None
    label, where = members[0]
    tip = velocity.tips[label]
    return complex(*tip) + omega * 1j * (at - complex(*where))


def _cam_contact(mechanism: Mechanism, pose: Pose, cam: CamSpec) -> tuple[complex, complex]:
    if cam.is_spline:
        from kinepoly.engine.cam_contact import contact_on_profile

        return contact_on_profile(cam, pose)
    k = complex(*pose.links[cam.cam].world(mechanism.local(cam.cam, cam.center_point)))
    if cam.kind == "flat":
        assert cam.flat is not None
        theta = pose.links[cam.follower].theta + cam.flat[1]
        normal = -1j * complex(math.cos(theta), math.sin(theta))  # from K toward the face (K on its left)
        return k + cam.radius * normal, normal
    assert cam.point is not None
    w = complex(*pose.links[cam.follower].world(mechanism.local(cam.follower, cam.point)))
    n = (w - k) / abs(w - k)
    point = w if cam.kind == "knife" else k + cam.radius * n
    return point, (-n if cam.inside else n)


def contacts_at(mechanism: Mechanism, pose: Pose, velocity: VelocityPolygon | None,
                offset: Vec = (0.0, 0.0)) -> dict[str, Contact]:
    """Every pair's contact at ``pose``; points moved by ``offset`` (the solve's frame to the user's)."""
    out: dict[str, Contact] = {}
    shift = complex(*offset)
    for gear in mechanism.scene.gears:
        if not all(link in pose.links for link in gear.links):
            continue
        arrays = {link: ArrayPose.of_rows([pose.links[link]]) for link in gear.links}
        found = mesh(mechanism, gear, arrays)
        point, normal = complex(found.point[0]) + shift, complex(found.normal[0])
        out[gear.name] = Contact((point.real, point.imag), (normal.real, normal.imag),
                                 (0.0, 0.0) if velocity is not None else None)
    for cam in mechanism.scene.cams:
        if not all(link in pose.links for link in (cam.cam, cam.follower)):
            continue
        point, normal = _cam_contact(mechanism, pose, cam)
        sliding = None
        if velocity is not None:
            on_follower = _velocity(velocity, mechanism, cam.follower, point)
            on_cam = _velocity(velocity, mechanism, cam.cam, point)
            if on_follower is not None and on_cam is not None:
                tangent = 1j * normal
                along = ((on_follower - on_cam) * tangent.conjugate()).real
                sliding = ((along * tangent).real + 0.0, (along * tangent).imag + 0.0)
        at = point + shift
        out[cam.name] = Contact((at.real, at.imag), (normal.real, normal.imag), sliding)
    return out


def record_equivalent_links(polygon: Polygon) -> None:
    """One step per cam: the equivalent link (or block) used, and where its ends are."""
    if not polygon.record or polygon.kind != "velocity":
        return
    mechanism = polygon.mechanism
    for cam in mechanism.scene.cams:
        if cam.is_spline:
            from kinepoly.engine.cam_contact import record_spline_equivalent

            record_spline_equivalent(polygon, cam)
            continue
        point = cam.point or cam.center_point
        if cam.kind == "flat":
            length = cam.radius
        else:
            (x, y) = mechanism.local(cam.equivalent, point)
            length = math.hypot(x, y)
        polygon.step(Step(polygon="velocity", kind="known",
                          equation=(f"cam {cam.name}: equivalent block {cam.equivalent} pinned at {cam.center_point}, "
                                    f"sliding on {cam.follower}" if cam.kind == "flat" else
                                    f"cam {cam.name}: equivalent link {cam.equivalent} from {cam.center_point} to {point}"),
                          result=cam.equivalent, topic="equivalent-link",
                          params=(("pair", cam.name), ("cam", cam.cam), ("follower", cam.follower),
                                  ("link", cam.equivalent), ("centre", cam.center_point), ("point", point),
                                  ("length", length), ("kind", cam.kind))))
