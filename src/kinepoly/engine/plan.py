"""The position plan: the input, then Assur groups in the order they can be solved.

A *dyad* is two unknown links i and j joined to each other by an inner joint, each joined to
an already-known link by one outer joint. Its kind spells the joints in order, outer of i,
inner, outer of j, with R for a pin and P for a slider, normalised so that only RRR, RRP, RPR,
PRP and RPP occur (PRR and PPR are the same groups read from the other end). What is left
when no dyad can be found is one group solved by damped Newton.

Inputs may drive any joint. An input on the frame places its link at once. An input between two
moving links (a motor on a link, a cylinder) either places its link on an already-known one
(``DriveGroup``), or makes the two links one body of a known shape at each row: a dyad whose
first side is that composite is a *carried* dyad (``Dyad.carrier``), closed like any other.

The plan is made backwards from what is asked: only the groups on the path to an asked
link are kept.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from kinepoly.errors import MobilityError, SceneError
from kinepoly.model.mechanism import Drive, Joint, Mechanism, Revolute, joint_links
from kinepoly.scene.spec import CamSpec, GearSpec, PitchCircle, SliderSpec

__all__ = [
    "CamGroup",
    "DriveGroup",
    "Dyad",
    "GearGroup",
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
    def outer_first(self) -> str:
        """The link that has the first outer joint: ``first``, or the carrier of a carried dyad."""
        return self.first if self.carrier is None else self.carrier

    def known_links(self) -> tuple[str, str]:
        a = next(x for x in joint_links(self.first_joint) if x != self.outer_first)
        b = next(x for x in joint_links(self.second_joint) if x != self.second)
        return (a, b)

    @property
    def name(self) -> str:
        if self.carrier is not None and self.drive is not None:
            return f"{self.carrier}+{self.first}-{self.second} ({self.kind}, {self.drive.name} driven)"
        return f"{self.first}-{self.second} ({self.kind})"


@dataclass(frozen=True)
class DriveGroup:
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


@dataclass(frozen=True)
class _HigherPairGroup:
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


@dataclass(frozen=True)
class GearGroup(_HigherPairGroup):
    """A gear placed by rolling on a known gear: ``link`` is pinned at its pitch centre to the known
    ``carrier`` (the frame, an arm), or is a rack sliding on it; ``known`` carries the other pitch curve."""

    gear: GearSpec = field(kw_only=True)

    @property
    def name(self) -> str:
        return f"{self.link} rolling on {self.known} (gears {self.gear.name})"


@dataclass(frozen=True)
class CamGroup(_HigherPairGroup):
    """A spline cam's follower placed on the known cam link by its contact: ``link`` (the follower) is held
    by one ``joint`` to the known ``carrier``, a pin (a pivoted rocker) or a slider whose block it is (a
    translating follower); ``engine.cam_contact`` finds the contact."""

    cam: CamSpec = field(kw_only=True)

    @property
    def name(self) -> str:
        return f"{self.link} on cam {self.known} (cam {self.cam.name})"


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


Group = Dyad | DriveGroup | GearGroup | CamGroup | NewtonGroup


@dataclass(frozen=True)
class PositionPlan:
    """Links known from the input, then the groups in order."""

    driven: tuple[str, ...]
    groups: tuple[Group, ...]

    def describe(self) -> list[str]:
        lines = [f"input: link(s) {', '.join(self.driven)}"] if self.driven else []
        lines += [f"group {g.name}" for g in self.groups]
        return lines


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


def _free_joints(mechanism: Mechanism, link: str) -> list[Joint]:
    """The joints of ``link`` that no input drives."""
    driven = {d.joint for d in mechanism.drives if not d.on_frame}
    return [joint for joint in mechanism.joints_of(link) if joint not in driven]


def _find_dyad(mechanism: Mechanism, known: set[str]) -> Dyad | None:
    unknown = [n for n in mechanism.link_names if n not in known]
    for i in unknown:
        for inner in _free_joints(mechanism, i):
            j = [x for x in joint_links(inner) if x != i]
            if not j or j[0] in known:
                continue
            j_name = j[0]
            outer_i = [jt for jt in _free_joints(mechanism, i) if any(x in known for x in joint_links(jt))]
            outer_j = [jt for jt in _free_joints(mechanism, j_name) if any(x in known for x in joint_links(jt))]
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


def _find_drive(mechanism: Mechanism, known: set[str]) -> DriveGroup | None:
    """A driven joint between a known link and an unknown one."""
    for drive in mechanism.drives:
        if drive.on_frame:
            continue
        if drive.base in known and drive.moving not in known:
            return DriveGroup(drive, drive.moving, drive.base)
        if drive.moving in known and drive.base not in known:
            return DriveGroup(drive, drive.base, drive.moving)
    return None


def _find_gear(mechanism: Mechanism, known: set[str]) -> GearGroup | None:
    """A gear not yet placed that meshes with a placed one and is held at its pitch centre by one pin
    (a rack: one slider) to a placed link."""
    for gear in mechanism.scene.gears:
        for side in (0, 1):
            link, other = gear.links[side], gear.links[1 - side]
            if link in known or other not in known:
                continue
            outer = [jt for jt in _free_joints(mechanism, link) if any(x in known for x in joint_links(jt))]
            if len(outer) != 1:
                continue
            joint, curve = outer[0], gear.pitch[side]
            centred = isinstance(curve, PitchCircle) and isinstance(joint, Revolute) and joint.point == curve.center
            if isinstance(curve, PitchCircle) != centred:
                continue
            if isinstance(joint, SliderSpec) and joint.block != link:
                continue
            return GearGroup(link, other, _far_side(joint, link), joint, gear=gear)
    return None


def _find_cam(mechanism: Mechanism, known: set[str]) -> CamGroup | None:
    """A spline cam's follower not yet placed, on a placed cam, held by one pin (not at its contact point)
    or as the block of one slider to a placed link."""
    for cam in mechanism.scene.cams:
        if not cam.is_spline or cam.cam not in known or cam.follower in known:
            continue
        outer = [jt for jt in _free_joints(mechanism, cam.follower) if any(x in known for x in joint_links(jt))]
        if len(outer) != 1:
            continue
        joint = outer[0]
        if isinstance(joint, Revolute) and joint.point == cam.point:
            continue
        if isinstance(joint, SliderSpec) and joint.block != cam.follower:
            continue
        return CamGroup(cam.follower, cam.cam, _far_side(joint, cam.follower), joint, cam=cam)
    return None


def _find_planet(mechanism: Mechanism, known: set[str]) -> NewtonGroup | None:
    """A planet and its arm, neither placed: the planet meshes two placed gears and is pinned at its pitch centre
    to the arm, which one pin holds to a placed link (``engine.planet`` places them together)."""
    for planet in mechanism.link_names:
        if planet in known:
            continue
        meshes = [g for g in mechanism.scene.gears if planet in g.links
                  and g.links[1 - g.links.index(planet)] in known
                  and all(isinstance(c, PitchCircle) for c in g.pitch)]
        for pin in _free_joints(mechanism, planet):
            if not isinstance(pin, Revolute) or any(x in known for x in pin.links):
                continue
            arm = pin.other(planet)
            centred = [g for g in meshes if getattr(g.pitch[g.links.index(planet)], "center", None) == pin.point]
            outer = [jt for jt in _free_joints(mechanism, arm) if any(x in known for x in joint_links(jt))]
            if len(centred) < 2 or len(outer) != 1 or not isinstance(outer[0], Revolute):
                continue
            return NewtonGroup((arm, planet), (outer[0], pin), gears=(centred[0], centred[1]))
    return None


def _find_carried(mechanism: Mechanism, known: set[str]) -> Dyad | None:
    """An RRR dyad whose first side is two unknown links held together by a driven joint."""
    for drive in mechanism.drives:
        if drive.on_frame or drive.moving in known or drive.base in known:
            continue
        for carrier, first in ((drive.moving, drive.base), (drive.base, drive.moving)):
            outer = [jt for jt in _free_joints(mechanism, carrier) if any(x in known for x in joint_links(jt))]
            rest = [jt for jt in _free_joints(mechanism, first) if jt not in outer]
            inner = [jt for jt in rest if all(x not in known for x in joint_links(jt))]
            if len(outer) != 1 or len(inner) != 1 or any(jt for jt in rest if jt not in inner):
                continue
            second = next(x for x in joint_links(inner[0]) if x != first)
            if second == carrier:
                continue
            outer_second = [jt for jt in _free_joints(mechanism, second) if any(x in known for x in joint_links(jt))]
            if len(outer_second) != 1:
                continue
            if not all(isinstance(jt, Revolute) for jt in (outer[0], inner[0], outer_second[0])):
                continue
            return Dyad("RRR", first, second, outer[0], inner[0], outer_second[0], carrier, drive)
    return None


def _all_groups(mechanism: Mechanism) -> tuple[tuple[str, ...], list[Group]]:
    driven = _frame_drives(mechanism)
    known: set[str] = {mechanism.ground, *driven} if mechanism.ground is not None else set(mechanism.link_names)
    groups: list[Group] = []
    while True:
        group: Group | None = (_find_drive(mechanism, known) or _find_gear(mechanism, known)
                               or _find_cam(mechanism, known) or _find_dyad(mechanism, known) or _find_carried(mechanism, known)
                               or _find_planet(mechanism, known))
        if group is None:
            break
        groups.append(group)
        known.update(group.links)
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
        floating.append(cam)
    if rest:
        joints = tuple(j for j in mechanism.joints if any(x in rest for x in joint_links(j)))
        drives = tuple(d for d in mechanism.drives if not d.on_frame and (d.moving in rest or d.base in rest))
        gears = tuple(g for g in mechanism.scene.gears if any(x in rest for x in g.links))
        groups.append(NewtonGroup(rest, joints, drives, tuple(floating), gears))
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
