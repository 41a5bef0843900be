"""The position plan: the input, then Assur groups in the order they can be solved.

A *dyad* is two unknown links i and j joined to each other by an inner joint, each joined to
an already-known link by one outer joint. Its kind spells the joints in order, outer of i,
inner, outer of j, with R for a pin and P for a slider, normalised so that only RRR, RRP, RPR,
PRP and RPP occur (PRR and PPR are the same groups read from the other end). What is left
when no dyad can be found is one group solved by damped Newton.

Inputs may drive any joint. An input on the frame places its link at once. An input between two
moving links (a motor on a link, a cylinder) either places its link on an already-known one
(``DriveGroup``), or makes the two links one body of a known shape at each row: a dyad whose
first side is that composite is a *carried* dyad (``CarriedDyad``), closed like any other.

Each kind of group finds its own groups (``engine.kinds``, asked in the order of ``engine.table``). The
plan is made backwards from what is asked: only the groups on the path to an asked link are kept.
"""

from __future__ import annotations

from kinepoly.engine.groups import Group, PositionPlan
from kinepoly.engine.table import kinds_for
from kinepoly.model.mechanism import Mechanism, Revolute

__all__ = ["make_plan"]


def _frame_drives(mechanism: Mechanism) -> tuple[str, ...]:
    """The links the inputs on the frame place at once."""
    if mechanism.ground is None:
        return ()
    out = []
    for drive in mechanism.drives:
        if not drive.on_frame:
            continue
        if isinstance(drive.joint, Revolute):
            out.append(drive.moving)
        else:  # a slider on the frame: whichever side is not the frame
            out.append(drive.base if drive.moving == mechanism.ground else drive.moving)
    return tuple(out)


def _all_groups(mechanism: Mechanism) -> tuple[tuple[str, ...], list[Group]]:
    """The groups in solving order: each time, the first kind of the table that finds one among the links
    not yet known."""
    driven = _frame_drives(mechanism)
    known: set[str] = {mechanism.ground, *driven} if mechanism.ground is not None else set(mechanism.link_names)
    groups: list[Group] = []
    every = set(mechanism.link_names)
    while not known >= every:  # a kind finds a group only among links not yet known
        group: Group | None = next((found for kind in kinds_for(mechanism)
                                    if (found := kind.find(mechanism, known))), None)
        if group is None:
            break
        groups.append(group)
        known.update(group.links)
    return driven, groups


def make_plan(mechanism: Mechanism, needed_links: set[str] | None = None) -> PositionPlan:
    """The groups in solving order; with ``needed_links`` only those on the path to them."""
    driven, groups = _all_groups(mechanism)
    if needed_links is None:
        return PositionPlan(driven, tuple(groups))
    solver_of = {link: g for g in groups for link in g.links}
    wanted: set[int] = set()
    stack = [solver_of[link] for link in needed_links if link in solver_of]
    while stack:
        group = stack.pop()
        if id(group) in wanted:
            continue
        wanted.add(id(group))
        stack.extend(solver_of[k] for k in group.known_links() if k in solver_of)
    return PositionPlan(driven, tuple(g for g in groups if id(g) in wanted))
