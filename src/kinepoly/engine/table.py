"""The group kinds, by the type of their groups: the one table the drivers call (``engine.plan``,
``engine.position``, ``engine.velocity``, ``engine.acceleration``).

Its order is the plan's: each time, the first kind that finds a group among the links not yet known
places the next one; a Newton group, found last, takes whatever is left.

A kind's module is imported when the kind is first asked for (the pattern of ``kinepoly.__init__``'s public
names): a four-bar loads the dyad's and the drive's, not the gears', the cams' nor the Newton groups'. The
gear, planet and cam kinds find a group only in a scene with gear pairs or cams: ``kinds_for`` leaves them
out of any other (``engine.plan``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from importlib import import_module
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
    PositionPlan,
    TriadGroup,
)
from kinepoly.engine.kind import Kind
from kinepoly.model.mechanism import Mechanism

__all__ = ["KINDS", "batched", "kind_of", "kinds_for"]


def _always(mechanism: Mechanism) -> bool:
    return True


def _has_gears(mechanism: Mechanism) -> bool:
    return bool(mechanism.scene.gears)


def _has_cams(mechanism: Mechanism) -> bool:
    return bool(mechanism.scene.cams)


_ROWS: dict[type, tuple[str, Callable[[Mechanism], bool]]] = {
    DriveGroup: ("drive", _always),
    GearGroup: ("gear", _has_gears),
    CamGroup: ("cam", _has_cams),
    Dyad: ("dyad", _always),
    CarriedDyad: ("carried", _always),
    PlanetGroup: ("planet", _has_gears),
    TriadGroup: ("triad", _always),
    NewtonGroup: ("newton", _always),
}
"""Each group type's kind module (under ``engine.kinds``) and whether the kind can find a group in a mechanism."""


class _Table(Mapping[type, Kind[Any]]):
    """The kinds by the type of their groups, in the plan's order; a kind's module is imported when first asked."""

    def __init__(self) -> None:
        self._loaded: dict[type, Kind[Any]] = {}

    def __getitem__(self, group_type: type) -> Kind[Any]:
        kind = self._loaded.get(group_type)
        if kind is None:
            kind = self._loaded[group_type] = import_module(f"kinepoly.engine.kinds.{_ROWS[group_type][0]}").KIND
        return kind

    def __iter__(self) -> Iterator[type]:
        return iter(_ROWS)

    def __len__(self) -> int:
        return len(_ROWS)


KINDS: Mapping[type, Kind[Any]] = _Table()


def kinds_for(mechanism: Mechanism) -> Iterator[Kind[Any]]:
    """The kinds that can find a group in ``mechanism``, in the plan's order, each imported when reached."""
    for group_type, (_, can_find) in _ROWS.items():
        if can_find(mechanism):
            yield KINDS[group_type]


def kind_of(group: Group) -> Kind[Any]:
    """The kind of ``group``: its row of the table."""
    return KINDS[type(group)]


def batched(plan: PositionPlan) -> bool:
    """Whether a family's members run through ``plan`` in one batch: every group's kind places them so
    (``Kind.batched``)."""
    return all(kind_of(group).batched for group in plan.groups)
