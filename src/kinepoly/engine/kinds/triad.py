"""Triad kind: the links left form a class-3 group (a ternary link and three legs; a leg may hold a driven joint
or be a floating follower's contact), placed together by damped Newton as a Newton group is (``kinds.newton``),
its polygons constructed through its Assur point (``engine.triad``)."""

from __future__ import annotations

from kinepoly.engine import triad as triads
from kinepoly.engine.groups import TriadGroup
from kinepoly.engine.kind import Kind
from kinepoly.engine.kinds import newton
from kinepoly.engine.polygon import Polygon
from kinepoly.engine.results import AccelerationContext, VelocityContext
from kinepoly.model.mechanism import Mechanism

__all__ = ["KIND", "acceleration", "find", "velocity"]


def find(mechanism: Mechanism, known: set[str]) -> TriadGroup | None:
    """The links not yet known, where they form a triad (and hold no gear: a planet's group is the planet kind's)."""
    group = newton.find(mechanism, known)
    if group is None or group.gears or triads.triad_of(mechanism, group) is None:
        return None
    return TriadGroup(group.links, group.joints, group.drives, group.cams, group.gears)


def velocity(state: VelocityContext, group: TriadGroup) -> None:
    """Through the Assur point: each leg's line, the ternary's image, the point where they meet."""
    triads.velocity_by_assur_point(state.polygon, _triad(state.polygon, group), state.sliding, state.equivalent)


def acceleration(ctx: AccelerationContext, group: TriadGroup) -> None:
    """As ``velocity`` constructs it, with the normal (and Coriolis) terms laid first."""
    triads.acceleration_by_assur_point(ctx, _triad(ctx.b, group))


def _triad(polygon: Polygon, group: TriadGroup) -> triads.Triad:
    """The triad the group is (its ternary, legs and Assur point's name), found once for the plan (``PlanConstants``)
    and read by every construction of its polygons."""
    found = polygon.constants.groups.get(id(group))
    if found is None:
        found = polygon.constants.groups[id(group)] = triads.triad_of(polygon.mechanism, group)
        assert found is not None, "a TriadGroup is a triad (find)"
    return found


KIND: Kind[TriadGroup] = Kind(find, newton.place, velocity, acceleration)
