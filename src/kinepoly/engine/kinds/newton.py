"""Newton group kind: the links left when no other kind finds a group, placed together by damped Newton as
the policy starts it (``engine.newton``), a floating follower's contact after (``engine.cam_place``). Their
polygons by one linear solve of the joint equations per row (``engine.group``); a triad is the triad kind's
(``kinds.triad``), placed as here."""

from __future__ import annotations

from kinepoly.engine.cam_place import place_floating_contacts
from kinepoly.engine.group import acceleration_by_linear_solve, velocity_by_linear_solve
from kinepoly.engine.groups import NewtonGroup, PlanetGroup
from kinepoly.engine.kind import Kind, Later, Placed
from kinepoly.engine.newton_assembly import NewtonQuestion
from kinepoly.engine.placement import Placement
from kinepoly.engine.policy import Policy
from kinepoly.engine.results import AccelerationContext, VelocityContext
from kinepoly.errors import SceneError
from kinepoly.model.mechanism import Mechanism, joint_links
from kinepoly.scene.spec import CamSpec

__all__ = ["KIND", "acceleration", "find", "place", "velocity"]


def find(mechanism: Mechanism, known: set[str]) -> NewtonGroup | None:
    """Every link not yet known, as one group (the last kind the plan asks: no other finds a group); a group
    holding gears is a ``PlanetGroup`` (``engine.kinds.planet`` places it or says why it cannot)."""
    rest = tuple(n for n in mechanism.link_names if n not in known)
    floating: list[CamSpec] = []
    for cam in mechanism.scene.cams:
        if not cam.is_spline or (cam.cam not in rest and cam.follower not in rest):
            continue
        if cam.cam in rest:
            raise SceneError(
                f"{mechanism.scene.source}:{cam.line}: cams.{cam.name}: the cam {cam.cam} is not known before its "
                f"follower {cam.follower} (the follower drives the cam); this version solves a points profile only "
                "on a cam placed first: drive the cam or join it to the frame")
        if cam.is_curve_pair:
            raise SceneError(
                f"{mechanism.scene.source}:{cam.line}: cams.{cam.name}: the follower {cam.follower} with a profile of "
                "points floats (it is not held by one pin or one slider to a link placed before it); this version "
                "solves two profiles of points in contact only for a follower on a pivot or a slide: hold the "
                "follower by one joint, or give it a circle follower_profile")
        floating.append(cam)
    if not rest:
        return None
    joints = tuple(j for j in mechanism.joints if any(x in rest for x in joint_links(j)))
    drives = tuple(d for d in mechanism.drives if not d.on_frame and (d.moving in rest or d.base in rest))
    gears = tuple(g for g in mechanism.scene.gears if any(x in rest for x in g.links))
    return (PlanetGroup if gears else NewtonGroup)(rest, joints, drives, tuple(floating), gears)


def place(mechanism: Mechanism, group: NewtonGroup, placed: Placement, policy: Policy, later: Later) -> Placed:
    """The group by Newton's method, each row started where the policy says; then any floating follower's
    contact on its cam."""
    placed = policy.assemble(mechanism, NewtonQuestion(group), placed)
    if group.cams:
        placed = place_floating_contacts(mechanism, group, placed, policy)
    return placed, False


def velocity(state: VelocityContext, group: NewtonGroup) -> None:
    """By one linear solve of the group's joint equations per row."""
    velocity_by_linear_solve(state.polygon, group, state.sliding)


def acceleration(ctx: AccelerationContext, group: NewtonGroup) -> None:
    """As ``velocity`` constructs it."""
    acceleration_by_linear_solve(ctx, group)


KIND: Kind[NewtonGroup] = Kind(find, place, velocity, acceleration)
