"""The groups of a position plan as values, one type per group kind (``engine.table`` maps each type to
its kind's functions), and the plan itself."""

from __future__ import annotations

from functools import cached_property
from typing import Any

from msgspec import Struct, field

from kinepoly.model.mechanism import Drive, Joint, Mechanism, Revolute, joint_links
from kinepoly.scene.spec import CamSpec, GearSpec, SliderSpec

__all__ = [
    "CamGroup",
    "CarriedDyad",
    "DriveGroup",
    "Dyad",
    "GearGroup",
    "Group",
    "NewtonGroup",
    "PlanetGroup",
    "PlanConstants",
    "PositionPlan",
    "SlideRoles",
    "TriadGroup",
    "TwoSlideRoles",
    "far_side",
    "free_joints",
    "joint_kind",
    "slide_roles",
    "two_slide_roles",
]


def joint_kind(joint: Joint) -> str:
    return "R" if isinstance(joint, Revolute) else "P"


class Dyad(Struct, frozen=True, dict=True):
    """Two links solved together in closed form.

    A *carried* dyad's first side is two links held together by a driven joint: ``carrier`` has the
    outer joint, ``drive`` joins it to ``first``, which has the inner joint (an RRR dyad only).
    """

    kind: str
    first: str
    second: str
    first_joint: Joint
    inner: Joint
    second_joint: Joint
    carrier: str | None = None
    drive: Drive | None = None

    @property
    def links(self) -> tuple[str, ...]:
        return (self.first, self.second) if self.carrier is None else (self.carrier, self.first, self.second)

    @property
    def one_assembly(self) -> bool:
        """Whether the dyad closes in one way only: two slides, whose lines cross in one point (PRP, RPP)."""
        return self.kind in ("PRP", "RPP")

    @property
    def outer_first(self) -> str:
        """The link that has the first outer joint: ``first``, or the carrier of a carried dyad."""
        return self.first if self.carrier is None else self.carrier

    def known_links(self) -> tuple[str, str]:
        a = next(x for x in joint_links(self.first_joint) if x != self.outer_first)
        b = next(x for x in joint_links(self.second_joint) if x != self.second)
        return (a, b)

    @cached_property
    def slide_roles(self) -> SlideRoles:
        """The roles of an RPR dyad's links and pins (``slide_roles``)."""
        return _slide_roles(self)

    @property
    def name(self) -> str:
        if self.carrier is not None and self.drive is not None:
            return f"{self.carrier}+{self.first}-{self.second} ({self.kind}, {self.drive.name} driven)"
        return f"{self.first}-{self.second} ({self.kind})"


class DriveGroup(Struct, frozen=True):
    """One link placed on a known one by a driven joint between them (a motor on a link, a cylinder)."""

    drive: Drive
    link: str
    known: str

    @property
    def links(self) -> tuple[str, ...]:
        return (self.link,)

    def known_links(self) -> tuple[str, ...]:
        return (self.known,)

    @property
    def name(self) -> str:
        return f"{self.link} on {self.known} ({self.drive.name} driven)"


class _HigherPairGroup(Struct, frozen=True):
    """One link placed on a known one through a higher pair: ``link`` is held by one ``joint`` to the known
    ``carrier``; ``known`` carries the other element of the pair."""

    link: str
    known: str
    carrier: str
    joint: Joint

    @property
    def links(self) -> tuple[str, ...]:
        return (self.link,)

    def known_links(self) -> tuple[str, ...]:
        return (self.known, self.carrier)


class GearGroup(_HigherPairGroup, frozen=True, kw_only=True):
    """A gear placed by rolling on a known gear: ``link`` is pinned at its pitch centre to the known
    ``carrier`` (the frame, an arm), or is a rack sliding on it; ``known`` carries the other pitch curve."""

    gear: GearSpec

    @property
    def name(self) -> str:
        return f"{self.link} rolling on {self.known} (gears {self.gear.name})"


class CamGroup(_HigherPairGroup, frozen=True, kw_only=True):
    """A spline cam's follower placed on the known cam link by its contact: ``link`` (the follower) is held
    by one ``joint`` to the known ``carrier``, a pin (a pivoted rocker) or a slider whose block it is (a
    translating follower); ``engine.cam_contact`` finds the contact."""

    cam: CamSpec

    @property
    def name(self) -> str:
        return f"{self.link} on cam {self.known} (cam {self.cam.name})"


class SlideRoles(Struct, frozen=True):
    """Who is who in an RPR dyad: the guide turns about its pin ``guide_pin`` on ``guide_known``;
    the block is pinned at ``block_pin`` to ``block_known``; the unknown tip is block_pin@guide."""

    slider: SliderSpec
    guide: str
    block: str
    guide_pin: str
    block_pin: str
    guide_known: str
    block_known: str


class TwoSlideRoles(Struct, frozen=True):
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


def far_side(joint: Joint, link: str) -> str:
    return next(x for x in joint_links(joint) if x != link)


def slide_roles(dyad: Dyad) -> SlideRoles:
    """The roles of an RPR dyad's links and pins (found once per dyad)."""
    return dyad.slide_roles


def _slide_roles(dyad: Dyad) -> SlideRoles:
    slider = dyad.inner
    assert isinstance(slider, SliderSpec) and dyad.kind == "RPR"
    outer = {dyad.first: dyad.first_joint, dyad.second: dyad.second_joint}
    guide_joint, block_joint = outer[slider.guide], outer[slider.block]
    assert isinstance(guide_joint, Revolute) and isinstance(block_joint, Revolute), "RPR: the outer joints are pins"
    return SlideRoles(slider, slider.guide, slider.block, guide_joint.point, block_joint.point,
                      far_side(guide_joint, slider.guide), far_side(block_joint, slider.block))


def two_slide_roles(dyad: Dyad, mechanism: Mechanism) -> TwoSlideRoles:
    """The roles of a PRP or RPP dyad's links and points."""
    i, j = dyad.first, dyad.second
    second = dyad.second_joint
    assert isinstance(second, SliderSpec) and dyad.kind in ("PRP", "RPP")
    if dyad.kind == "PRP":
        first, inner = dyad.first_joint, dyad.inner
        assert isinstance(first, SliderSpec) and isinstance(inner, Revolute)
        return TwoSlideRoles(first, second, inner.point, i, far_side(first, i), far_side(second, j), i, None, None)
    pin, inner_slider = dyad.first_joint, dyad.inner
    assert isinstance(pin, Revolute) and isinstance(inner_slider, SliderSpec)
    point = mechanism.scene.link(j).points[0].name
    return TwoSlideRoles(inner_slider, second, point, j, i, far_side(second, j), j, pin.point, far_side(pin, i))


class NewtonGroup(Struct, frozen=True):
    """Links that form no dyad: solved together by damped Newton from the guess. ``drives``: the inputs
    that drive joints of the group (each one more equation); ``cams``: the spline cams whose follower floats
    in the group on a cam known before it (the contact's parameter one more unknown, ``engine.newton``);
    ``gears``: the gear pairs with a gear in the group (a planet on an arm that no input drives: placed by
    rolling in ``engine.planet``, its polygons constructed in ``engine.rolling``)."""

    links: tuple[str, ...]
    joints: tuple[Joint, ...]
    drives: tuple[Drive, ...] = ()
    cams: tuple[CamSpec, ...] = ()
    gears: tuple[GearSpec, ...] = ()

    @property
    def name(self) -> str:
        return "-".join(self.links) + (" (planet on its arm)" if self.gears else " (Newton)")

    def known_links(self) -> tuple[str, ...]:
        return tuple(sorted({x for j in self.joints for x in joint_links(j) if x not in self.links}
                            | {cam.cam for cam in self.cams}
                            | {x for gear in self.gears for x in gear.links if x not in self.links}))


class CarriedDyad(Dyad, frozen=True):
    """A carried RRR dyad (see ``Dyad``): its ``carrier`` and ``drive`` are given."""


class TriadGroup(NewtonGroup, frozen=True):
    """A class-3 group (a triad: a ternary link and three legs, a leg with a driven joint or a floating follower's
    contact among them): placed by damped Newton as a ``NewtonGroup``, its polygons constructed through its Assur
    point (``engine.triad``)."""


class PlanetGroup(NewtonGroup, frozen=True):
    """A group holding gears that no dyad and no single pair places: a planet on an arm that no input drives,
    placed by rolling (``engine.planet``), the only such group this version places."""


Group = Dyad | DriveGroup | GearGroup | CamGroup | NewtonGroup


class PlanConstants(Struct):
    """What constructing a plan's polygons finds that does not depend on the rows, kept by its first construction
    for the next ones (``engine.polygon``): the frame's points with the links that have each, and each image of a
    rigid link as the two known tips it is built from and Mehmke's factor, keyed by the link, the point and the
    link's known tips (their members). A prepared sweep's plan is constructed at every call: its calls replay these."""

    mechanism: Mechanism | None = None
    """The mechanism they were found on: a polygon of another (the same plan on other dimensions) finds its own."""
    frame: tuple[tuple[str, tuple[tuple[str, Any], ...]], ...] | None = None
    """The frame's points: each one's label and the links it is a member of, with the member (``tips``)."""
    labels: dict[tuple[str, str], str] = field(default_factory=dict)
    """The label of each (link, point) asked for: the point's name, or ``B@4``."""
    tips: dict[tuple[str, str], tuple[str, tuple[tuple[str, Any], ...]]] = field(default_factory=dict)
    """What recording the tip of a (link, point) does: its label and the links it becomes a member of, each with
    the member (``engine.polygon.Member``)."""
    together: dict[str, tuple[str, ...]] = field(default_factory=dict)
    """Each link and the links that turn with it (``Mechanism.turning_together``)."""
    groups: dict[int, Any] = field(default_factory=dict)
    """What a group's kind finds of it once for the plan (its points, links, lengths and line labels), keyed by the
    group's identity: the plan holds its groups."""
    images: dict[tuple[str, str, tuple[Any, ...]], tuple[str, str, complex] | None] = field(default_factory=dict)
    """None: the image is built row by row (a corner of its triangle slides on the link)."""


class PositionPlan(Struct, frozen=True):
    """Links known from the input, then the groups in order."""

    driven: tuple[str, ...]
    groups: tuple[Group, ...]
    constants: PlanConstants = field(default_factory=PlanConstants)
    """The construction's constants, found on the plan's first construction (``PlanConstants``)."""

    def describe(self) -> list[str]:
        lines = [f"input: link(s) {', '.join(self.driven)}"] if self.driven else []
        lines += [f"group {g.name}" for g in self.groups]
        return lines


def free_joints(mechanism: Mechanism, link: str) -> list[Joint]:
    """The joints of ``link`` that no input drives."""
    driven = {d.joint for d in mechanism.drives if not d.on_frame}
    return [joint for joint in mechanism.joints_of(link) if joint not in driven]
