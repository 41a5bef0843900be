"""Gear kind: a gear placed by rolling on a known gear, pinned at its pitch centre to a known link (a rack:
the block of a slider on it); its polygons by the pitch point (``engine.gears``, ``engine.rolling``)."""

from __future__ import annotations

from msgspec.structs import replace

from kinepoly.engine.gears import place_rolling
from kinepoly.engine.groups import GearGroup, far_side, free_joints
from kinepoly.engine.kind import Kind, Later, Placed
from kinepoly.engine.placement import Placement
from kinepoly.engine.policy import Policy
from kinepoly.engine.results import AccelerationContext, VelocityContext
from kinepoly.engine.rolling import acceleration_by_rolling, velocity_by_rolling
from kinepoly.model.mechanism import Mechanism, Revolute, joint_links
from kinepoly.scene.spec import PitchCircle, SliderSpec

__all__ = ["KIND", "acceleration", "find", "place", "velocity"]


def find(mechanism: Mechanism, known: set[str]) -> GearGroup | None:
    """A gear not yet placed that meshes with a placed one and is held at its pitch centre by one pin
    (a rack: one slider) to a placed link."""
    for gear in mechanism.scene.gears:
        for side in (0, 1):
            link, other = gear.links[side], gear.links[1 - side]
            if link in known or other not in known:
                continue
            outer = [jt for jt in free_joints(mechanism, link) if any(x in known for x in joint_links(jt))]
            if len(outer) != 1:
                continue
            joint, curve = outer[0], gear.pitch[side]
            centred = isinstance(curve, PitchCircle) and isinstance(joint, Revolute) and joint.point == curve.center
            if isinstance(curve, PitchCircle) != centred:
                continue
            if isinstance(joint, SliderSpec) and joint.block != link:
                continue
            return GearGroup(link, other, far_side(joint, link), joint, gear=gear)
    return None


def place(mechanism: Mechanism, group: GearGroup, placed: Placement, policy: Policy, later: Later) -> Placed:
    """The gear rolled on the known one at every row, with how far it has rolled."""
    pose, rolled = place_rolling(mechanism, group.gear, group.link, group.joint, group.carrier,
                                 placed.poses, placed.rolled, placed.values)
    turned = placed.rolled if rolled is None else {**placed.rolled, group.link: rolled}
    return replace(placed, poses={**placed.poses, group.link: pose}, rolled=turned), False


def velocity(state: VelocityContext, group: GearGroup) -> None:
    velocity_by_rolling(state.polygon, group, state.sliding)


def acceleration(ctx: AccelerationContext, group: GearGroup) -> None:
    acceleration_by_rolling(ctx, group)


KIND: Kind[GearGroup] = Kind(find, place, velocity, acceleration)
