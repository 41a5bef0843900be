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

__all__ = [
    "Dyad",
    "NewtonGroup",
    "PositionPlan",
    "SlideRoles",
    "TwoSlideRoles",
    "make_plan",
    "slide_roles",
    "two_slide_roles",
]


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
class SlideRoles:
    """Who is who in an RPR dyad: the guide turns about its pin ``guide_pin`` on ``guide_known``;
    the block is pinned at ``block_pin`` to ``block_known``; the unknown tip is block_pin@guide."""

    slider: SliderSpec
    guide: str
    block: str
    guide_pin: str
    block_pin: str
    guide_known: str
    block_known: str


@dataclass(frozen=True)
class TwoSlideRoles:
    """Who is who in a PRP or RPP dyad: ``point`` of ``moving`` is where the two slide lines cross.

    The first line slides on ``side1`` along ``first_slider``, the second on ``side2`` along
    ``second_slider``; ``first_relative`` is the link whose motion relative to ``side1`` the first
    slider carries. In an RPP dyad the first link turns with the second's guide and is pinned at
    ``pin`` to the known link ``pin_known``, so its tips come from that pin.
    """

    first_slider: SliderSpec
    second_slider: SliderSpec
    point: str
    moving: str
    side1: str
    side2: str
    first_relative: str
    pin: str | None
    pin_known: str | None


def _far_side(joint: Joint, link: str) -> str:
    return next(x for x in joint_links(joint) if x != link)


def slide_roles(dyad: Dyad) -> SlideRoles:
    """The roles of an RPR dyad's links and pins."""
    slider = dyad.inner
    assert isinstance(slider, SliderSpec) and dyad.kind == "RPR"
    outer = {dyad.first: dyad.first_joint, dyad.second: dyad.second_joint}
    guide_joint, block_joint = outer[slider.guide], outer[slider.block]
    assert isinstance(guide_joint, Revolute) and isinstance(block_joint, Revolute), "RPR: the outer joints are pins"
    return SlideRoles(slider, slider.guide, slider.block, guide_joint.point, block_joint.point,
                      _far_side(guide_joint, slider.guide), _far_side(block_joint, slider.block))


def two_slide_roles(dyad: Dyad, mechanism: Mechanism) -> TwoSlideRoles:
    """The roles of a PRP or RPP dyad's links and points."""
    i, j = dyad.first, dyad.second
    second = dyad.second_joint
    assert isinstance(second, SliderSpec) and dyad.kind in ("PRP", "RPP")
    if dyad.kind == "PRP":
        first, inner = dyad.first_joint, dyad.inner
        assert isinstance(first, SliderSpec) and isinstance(inner, Revolute)
        return TwoSlideRoles(first, second, inner.point, i, _far_side(first, i), _far_side(second, j), i, None, None)
    pin, inner_slider = dyad.first_joint, dyad.inner
    assert isinstance(pin, Revolute) and isinstance(inner_slider, SliderSpec)
    point = mechanism.scene.link(j).points[0].name
    return TwoSlideRoles(inner_slider, second, point, j, i, _far_side(second, j), j, pin.point, _far_side(pin, i))


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
