"""Planet kind: a planet and its arm, neither driven, placed together by rolling on two known gears about the
arm's pivot (``engine.planet``); their polygons by the pitch points (``engine.rolling``)."""

from __future__ import annotations

from kinepoly.engine.groups import PlanetGroup, free_joints
from kinepoly.engine.kind import Kind, Later, Placed
from kinepoly.engine.placement import Placement
from kinepoly.engine.planet import Planet, place_planet, planet_of
from kinepoly.engine.policy import Policy
from kinepoly.engine.results import AccelerationContext, VelocityContext
from kinepoly.engine.rolling import acceleration_of_planet, velocity_of_planet
from kinepoly.model.mechanism import Mechanism, Revolute, joint_links
from kinepoly.scene.spec import PitchCircle

__all__ = ["KIND", "acceleration", "find", "place", "velocity"]


def find(mechanism: Mechanism, known: set[str]) -> PlanetGroup | None:
    """A planet and its arm, neither placed: the planet meshes two placed gears and is pinned at its pitch centre
    to the arm, which one pin holds to a placed link (``engine.planet`` places them together)."""
    for planet in mechanism.link_names:
        if planet in known:
            continue
        meshes = [g for g in mechanism.scene.gears if planet in g.links
                  and g.links[1 - g.links.index(planet)] in known
                  and all(isinstance(c, PitchCircle) for c in g.pitch)]
        for pin in free_joints(mechanism, planet):
            if not isinstance(pin, Revolute) or any(x in known for x in pin.links):
                continue
            arm = pin.other(planet)
            centred = [g for g in meshes if getattr(g.pitch[g.links.index(planet)], "center", None) == pin.point]
            outer = [jt for jt in free_joints(mechanism, arm) if any(x in known for x in joint_links(jt))]
            if len(centred) < 2 or len(outer) != 1 or not isinstance(outer[0], Revolute):
                continue
            return PlanetGroup((arm, planet), (outer[0], pin), gears=(centred[0], centred[1]))
    return None


def _planet(group: PlanetGroup) -> Planet:
    found = planet_of(group)
    assert found is not None  # placing it raised otherwise
    return found


def place(mechanism: Mechanism, group: PlanetGroup, placed: Placement, policy: Policy, later: Later) -> Placed:
    """The arm and the planet in closed form at every row (a group of gears that is no planet: an error)."""
    return place_planet(mechanism, group, placed), False


def velocity(state: VelocityContext, group: PlanetGroup) -> None:
    velocity_of_planet(state.polygon, _planet(group))


def acceleration(ctx: AccelerationContext, group: PlanetGroup) -> None:
    acceleration_of_planet(ctx, _planet(group))


KIND: Kind[PlanetGroup] = Kind(find, place, velocity, acceleration)
