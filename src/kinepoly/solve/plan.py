"""The position plan: the input, then Assur groups in the order they can be solved.

A *dyad* is two unknown links i and j joined to each other by an inner joint, each joined to
an already-known link by one outer joint. Its kind spells the joints in order, outer of i,
inner, outer of j, with R for a pin and P for a slider, normalised so that only RRR, RRP, RPR,
PRP and RPP occur (PRR and PPR are the same groups read from the other end). What is left
when no dyad can be found is one group solved by damped Newton.

The plan is made backwards from what is asked: only the groups on the path to an asked
link are kept.
"""

from __future__ import annotations

from dataclasses import dataclass

from kinepoly.errors import MobilityError
from kinepoly.model.mechanism import Joint, Mechanism, Revolute, joint_links
from kinepoly.scene.spec import SliderSpec

__all__ = ["Dyad", "NewtonGroup", "PositionPlan", "make_plan"]


def joint_kind(joint: Joint) -> str:
    return "R" if isinstance(joint, Revolute) else "P"


@dataclass(frozen=True)
class Dyad:
    """Two links solved together in closed form."""

    kind: str
    first: str
    second: str
    first_joint: Joint
    inner: Joint
    second_joint: Joint

    @property
    def links(self) -> tuple[str, str]:
        return (self.first, self.second)

    def known_links(self) -> tuple[str, str]:
        a = next(x for x in joint_links(self.first_joint) if x != self.first)
        b = next(x for x in joint_links(self.second_joint) if x != self.second)
        return (a, b)

    @property
    def name(self) -> str:
        return f"{self.first}-{self.second} ({self.kind})"


@dataclass(frozen=True)
class NewtonGroup:
    """Links that form no dyad: solved together by damped Newton from the guess."""

    links: tuple[str, ...]
    joints: tuple[Joint, ...]

    @property
    def name(self) -> str:
        return "-".join(self.links) + " (Newton)"

    def known_links(self) -> tuple[str, ...]:
        return tuple(sorted({x for j in self.joints for x in joint_links(j) if x not in self.links}))


Group = Dyad | NewtonGroup


@dataclass(frozen=True)
class PositionPlan:
    """Links known from the input, then the groups in order."""

    driven: tuple[str, ...]
    groups: tuple[Group, ...]

    def describe(self) -> list[str]:
        lines = [f"input: link(s) {', '.join(self.driven)}"]
        lines += [f"group {g.name}" for g in self.groups]
        return lines


def _driven_links(mechanism: Mechanism) -> tuple[str, ...]:
    if mechanism.ground is None:
        return ()
    if mechanism.input_link is not None:
        mechanism.input_pivot()  # raises when the input link does not turn about the frame
        return (mechanism.input_link,)
    slider = mechanism.input_slider
    assert slider is not None
    if slider.guide == mechanism.ground:
        return (slider.block,)
    if slider.block == mechanism.ground:
        return (slider.guide,)
    raise MobilityError(
        f"{mechanism.scene.source}: input.slider: slider {slider.name} joins links {slider.block} and "
        f"{slider.guide}, neither of which is the frame; expected a driven slider on the frame link"
    )


def _find_dyad(mechanism: Mechanism, known: set[str]) -> Dyad | None:
    unknown = [n for n in mechanism.link_names if n not in known]
    for i in unknown:
        for inner in mechanism.joints_of(i):
            j = [x for x in joint_links(inner) if x != i]
            if not j or j[0] in known:
                continue
            j_name = j[0]
            outer_i = [jt for jt in mechanism.joints_of(i) if any(x in known for x in joint_links(jt))]
            outer_j = [jt for jt in mechanism.joints_of(j_name) if any(x in known for x in joint_links(jt))]
            if len(outer_i) != 1 or len(outer_j) != 1:
                continue
            kind = joint_kind(outer_i[0]) + joint_kind(inner) + joint_kind(outer_j[0])
            if kind == "PPP":
                raise MobilityError(
                    f"{mechanism.scene.source}: sliders: links {i} and {j_name} are held by three sliders; "
                    "their place along the slides is not fixed (expected at least one pin in the group)"
                )
            if kind in ("PRR", "PPR"):
                return Dyad(kind[::-1], j_name, i, outer_j[0], inner, outer_i[0])
            return Dyad(kind, i, j_name, outer_i[0], inner, outer_j[0])
    return None


def _all_groups(mechanism: Mechanism) -> tuple[tuple[str, ...], list[Group]]:
    driven = _driven_links(mechanism)
    known: set[str] = {mechanism.ground, *driven} if mechanism.ground is not None else set(mechanism.link_names)
    groups: list[Group] = []
    while True:
        dyad = _find_dyad(mechanism, known)
        if dyad is None:
            break
        groups.append(dyad)
        known.update(dyad.links)
    rest = tuple(n for n in mechanism.link_names if n not in known)
    if rest:
        joints = tuple(j for j in mechanism.joints if any(x in rest for x in joint_links(j)))
        groups.append(NewtonGroup(rest, joints))
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


def slider_between(joint: Joint) -> SliderSpec | None:
    return joint if isinstance(joint, SliderSpec) else None
