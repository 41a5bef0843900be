"""The contacts of the higher pairs over rows: where they touch, the common normal, the sliding velocity.

For a cam (a circle of centre K and radius R on the cam): a roller or knife edge at W touches on the
line K W, a flat face at the foot of the perpendicular from K; the normal points from the cam's side
to the follower's. For gears the contact is the pitch point and the normal the line of centres, from
the first gear's side to the second's; gears roll, so the sliding velocity is zero. The sliding
velocity is the follower's contact point's velocity relative to the cam's, along the common tangent.

Everything is computed over arrays of rows (a sweep's thousands); a solve's contacts are the same
computation on a batch of one (``engine.construct``). The cam's pressure angle and the follower's own
coordinate (its angle on a pivot, or its slider on the frame) are read here too, for the sweep.
The steps record, for each cam, that its equivalent link is used and where its ends are.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np
from msgspec import Struct

from kinepoly.engine.cam_contact import contact_rows, record_spline_equivalent
from kinepoly.engine.gears import mesh
from kinepoly.engine.polygon import Polygon
from kinepoly.engine.steps import Step
from kinepoly.geom.arrays import Bools, Points, Reals
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import CamSpec, SliderSpec

__all__ = ["Contact", "ContactRows", "FollowerCoordinate", "contact_links", "contacts_over_rows",
           "follower_coordinate", "polygon_velocity", "pressure_angles", "record_equivalent_links"]

Vec = tuple[float, float]
LinkVelocity = Callable[[str, Points], Points | None]
"""The velocity of the point at ``Points`` (frame) as a point of link ``str``, at every row; None where unknown."""


class Contact(Struct, frozen=True):
    """One pair's contact: the point (frame), the unit normal (cam side to follower side) and, where the
    velocity polygon was built, the sliding velocity along the tangent."""

    point: Vec
    normal: Vec
    sliding_velocity: Vec | None


class ContactRows(Struct, frozen=True):
    """One pair's contact at every row: the point (frame), the unit normal (cam or first gear's side to the
    other's) and, where the velocity polygon was built, the sliding velocity along the tangent."""

    point: Points
    normal: Points
    sliding_velocity: Points | None

    def row(self, k: int, offset: complex = 0j) -> Contact:
        """Row ``k`` as plain values, the point moved by ``offset``."""
        point, normal = complex(self.point[k]) + offset, complex(self.normal[k])
        sliding = None if self.sliding_velocity is None else complex(self.sliding_velocity[k])
        return Contact((point.real, point.imag), (normal.real, normal.imag),
                       None if sliding is None else (sliding.real + 0.0, sliding.imag + 0.0))


def contact_links(mechanism: Mechanism) -> set[str]:
    """The links a contact needs placed."""
    out = {link for gear in mechanism.scene.gears for link in gear.links}
    out |= {link for cam in mechanism.scene.cams for link in (cam.cam, cam.follower, cam.equivalent) if link}
    return out


def polygon_velocity(mechanism: Mechanism, polygon: Polygon) -> LinkVelocity:
    """A point's velocity as a point of a link, from a velocity polygon over rows: the link's first known
    tip plus omega x r (zero on the frame; None for a link the polygon has no tip and omega of)."""
    known: dict[str, tuple[Points, Points, Reals]] = {}
    for link, members in polygon.members.items():
        omega = polygon.rate_of(link)
        if omega is not None and members:
            known[link] = (polygon.tips[members[0].label], polygon.at(members[0]), omega)

    def velocity(link: str, at: Points) -> Points | None:
        if link == mechanism.ground:
            return np.zeros(len(at), np.complex128)
        if link not in known:
            return None
        tip, where, omega = known[link]
        return np.asarray(tip + omega * 1j * (at - where))
    return velocity


def _world(mechanism: Mechanism, poses: dict[str, ArrayPose], link: str, point: str) -> Points:
    return poses[link].world(mechanism.local(link, point))


def _cam_contact(mechanism: Mechanism, poses: dict[str, ArrayPose], cam: CamSpec,
                 parameters: Mapping[str, Reals]) -> tuple[Points, Points]:
    if cam.is_spline:
        found = contact_rows(cam, poses[cam.cam], parameters[cam.name])
        return found.point, found.normal
    k = _world(mechanism, poses, cam.cam, cam.center_point)
    if cam.kind == "flat":
        assert cam.flat is not None
        face = poses[cam.follower].rotation * complex(math.cos(cam.flat[1]), math.sin(cam.flat[1]))
        normal = np.asarray(-1j * face)  # from K toward the face (K on its left)
        return np.asarray(k + cam.radius * normal), normal
    assert cam.point is not None
    w = _world(mechanism, poses, cam.follower, cam.point)
    n = np.asarray((w - k) / np.abs(w - k))
    point = w if cam.kind == "knife" else np.asarray(k + cam.radius * n)
    return point, np.asarray(-n if cam.inside else n)


def _placed(poses: dict[str, ArrayPose], links: tuple[str, ...]) -> bool:
    return all(link in poses for link in links)


def contacts_over_rows(mechanism: Mechanism, poses: dict[str, ArrayPose], velocity: LinkVelocity | None,
                       parameters: Mapping[str, Reals]) -> dict[str, ContactRows]:
    """Every placed pair's contact at every row of ``poses``; ``velocity`` (``polygon_velocity``) gives the
    sliding velocities, None leaves them out; ``parameters`` the contact's parameter on each spline profile
    (``Positions.contact_parameters``)."""
    out: dict[str, ContactRows] = {}
    for gear in mechanism.scene.gears:
        if _placed(poses, gear.links):
            found = mesh(mechanism, gear, poses)
            out[gear.name] = ContactRows(found.point, found.normal,
                                         None if velocity is None else np.zeros(len(found.point), np.complex128))
    for cam in mechanism.scene.cams:
        if not _placed(poses, (cam.cam, cam.follower)):
            continue
        point, normal = _cam_contact(mechanism, poses, cam, parameters)
        sliding = None
        if velocity is not None:
            on_follower, on_cam = velocity(cam.follower, point), velocity(cam.cam, point)
            if on_follower is not None and on_cam is not None:
                tangent = 1j * normal
                sliding = np.asarray(((on_follower - on_cam) * np.conj(tangent)).real * tangent)
        out[cam.name] = ContactRows(point, normal, sliding)
    return out


class FollowerCoordinate(Struct, frozen=True):
    """What a cam designer plots for a follower: its angle (pinned to the frame at ``pivot``) or its slider
    on the frame (``slider``)."""

    link: str
    pivot: str | None = None
    slider: SliderSpec | None = None


def follower_coordinate(mechanism: Mechanism, cam: CamSpec) -> FollowerCoordinate | None:
    """The follower's joint with the frame: a pivot (a rocker) or a slide (a translating follower); None for
    a floating follower (its motion is that of its points)."""
    ground, link = mechanism.ground, cam.follower
    for joint in mechanism.revolutes:
        if set(joint.links) == {ground, link}:
            return FollowerCoordinate(link, pivot=joint.point)
    for slider in mechanism.sliders:
        if {slider.block, slider.guide} == {ground, link}:
            return FollowerCoordinate(link, slider=slider)
    return None


def _force_point(mechanism: Mechanism, poses: dict[str, ArrayPose], cam: CamSpec, contact: ContactRows) -> Points:
    """Where the contact force acts on the follower: a roller's centre (the force passes through its pin),
    else the contact point itself (a knife edge, a flat face, an arc fixed to the follower)."""
    if cam.kind == "roller" and not cam.follower_profile:
        assert cam.point is not None
        return _world(mechanism, poses, cam.follower, cam.point)
    return contact.point


def pressure_angles(mechanism: Mechanism, poses: dict[str, ArrayPose], cam: CamSpec, contact: ContactRows,
                    velocity: LinkVelocity | None) -> tuple[Reals, Bools]:
    """The cam's pressure angle at every row (radians, 0 to pi/2): the acute angle between the common normal
    and the direction in which the follower's point under the force moves (a roller's centre, else the
    contact point). That direction is the follower's own: square to the radius from its pivot, along its
    slide; for a floating follower the point's velocity, so rows where it stands still have none
    (the second value says which rows have one)."""
    at = _force_point(mechanism, poses, cam, contact)
    moving = follower_coordinate(mechanism, cam)
    if moving is not None and moving.pivot is not None:
        direction = 1j * (at - _world(mechanism, poses, cam.follower, moving.pivot))
    elif moving is not None and moving.slider is not None:
        slide = moving.slider
        direction = poses[slide.guide].rotation * complex(math.cos(slide.angle_rad), math.sin(slide.angle_rad))
    else:
        found = velocity(cam.follower, at) if velocity is not None else None
        direction = np.zeros(len(at), np.complex128) if found is None else found
    valid = np.asarray(np.abs(direction) > 0.0)
    product = contact.normal * np.conj(direction)  # |n||d| (cos, -sin) of the angle between them
    return np.asarray(np.arctan2(np.abs(product.imag), np.abs(product.real))), valid


def record_equivalent_links(polygon: Polygon) -> None:
    """One step per cam: the equivalent link (or block) used, and where its ends are."""
    if not polygon.record or polygon.kind != "velocity":
        return
    mechanism = polygon.mechanism
    for cam in mechanism.scene.cams:
        if cam.is_spline:
            record_spline_equivalent(polygon, cam)
            continue
        point = cam.point or cam.center_point
        if cam.kind == "flat":
            length = cam.radius
        else:
            (x, y) = mechanism.local(cam.equivalent, point)
            length = math.hypot(x, y)
        polygon.step(Step(polygon="velocity", kind="known",
                          equation=(f"cam {cam.name}: equivalent block at {cam.center_point} on the "
                                    f"face of {cam.follower}"
                                    if cam.kind == "flat" else
                                    f"cam {cam.name}: equivalent link {cam.center_point}{point}"),
                          result=cam.equivalent, topic="equivalent-link",
                          params=(("pair", cam.name), ("cam", cam.cam), ("follower", cam.follower),
                                  ("link", cam.equivalent), ("centre", cam.center_point), ("point", point),
                                  ("length", length), ("kind", cam.kind))))
