"""Cam kind: a spline cam's follower placed on its known cam by the contact the policy keeps
(``engine.cam_contact``, ``engine.cam_place``); its polygons through the equivalent link from the profile's
centre of curvature (``engine.cam_polygons``)."""

from __future__ import annotations

from kinepoly.engine.cam_place import place_cam
from kinepoly.engine.cam_polygons import acceleration_by_cam, velocity_by_cam
from kinepoly.engine.groups import CamGroup, far_side, free_joints
from kinepoly.engine.kind import Kind, Later, Placed
from kinepoly.engine.placement import Placement
from kinepoly.engine.policy import Policy
from kinepoly.engine.results import AccelerationContext, VelocityContext
from kinepoly.model.mechanism import Mechanism, Revolute, joint_links
from kinepoly.scene.spec import SliderSpec

__all__ = ["KIND", "acceleration", "find", "place", "velocity"]


def find(mechanism: Mechanism, known: set[str]) -> CamGroup | None:
    """A spline cam's follower not yet placed, on a placed cam, held by one pin (not at its contact point)
    or as the block of one slider to a placed link."""
    for cam in mechanism.scene.cams:
        if not cam.is_spline or cam.cam not in known or cam.follower in known:
            continue
        outer = [jt for jt in free_joints(mechanism, cam.follower) if any(x in known for x in joint_links(jt))]
        if len(outer) != 1:
            continue
        joint = outer[0]
        if isinstance(joint, Revolute) and joint.point == cam.point:
            continue
        if isinstance(joint, SliderSpec) and joint.block != cam.follower:
            continue
        return CamGroup(cam.follower, cam.cam, far_side(joint, cam.follower), joint, cam=cam)
    return None


def place(mechanism: Mechanism, group: CamGroup, placed: Placement, policy: Policy, later: Later) -> Placed:
    """The follower at the contact the policy keeps at every row."""
    return place_cam(mechanism, group, placed, policy), False


def velocity(state: VelocityContext, group: CamGroup) -> None:
    velocity_by_cam(state.polygon, group, state.sliding, state.equivalent)


def acceleration(ctx: AccelerationContext, group: CamGroup) -> None:
    acceleration_by_cam(ctx, group)


KIND: Kind[CamGroup] = Kind(find, place, velocity, acceleration)
