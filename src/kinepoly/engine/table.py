"""The group kinds, by the type of their groups: the one table the drivers call (``engine.plan``,
``engine.position``, ``engine.velocity``, ``engine.acceleration``).

Its order is the plan's: each time, the first kind that finds a group among the links not yet known
places the next one; a Newton group, found last, takes whatever is left.
"""

from __future__ import annotations

from typing import Any

from kinepoly.engine.groups import (
    CamGroup,
    CarriedDyad,
    DriveGroup,
    Dyad,
    GearGroup,
    Group,
    NewtonGroup,
    PlanetGroup,
    TriadGroup,
)
from kinepoly.engine.kind import Kind
from kinepoly.engine.kinds import cam, carried, drive, dyad, gear, newton, planet, triad

__all__ = ["KINDS", "kind_of"]

KINDS: dict[type, Kind[Any]] = {
    DriveGroup: drive.KIND,
    GearGroup: gear.KIND,
    CamGroup: cam.KIND,
    Dyad: dyad.KIND,
    CarriedDyad: carried.KIND,
    PlanetGroup: planet.KIND,
    TriadGroup: triad.KIND,
    NewtonGroup: newton.KIND,
}


def kind_of(group: Group) -> Kind[Any]:
    """The kind of ``group``: its row of the table."""
    return KINDS[type(group)]
