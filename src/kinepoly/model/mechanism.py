"""The mechanism: links with points in their own frames, revolute joints, sliders, mobility.

A revolute joint is implied by a point name that two links share; a point of k links is a
compound hinge, k - 1 revolute joints. A slider's block turns
with its guide, so links joined by sliders form a *rotation class*: they share omega and
alpha. A block that slides on a guide of another rotation class than the frame's needs a
Coriolis term; that is the test ``has_turning_guide``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cached_property
from typing import TypeVar

from msgspec import Struct

from kinepoly.errors import MobilityError, SceneError
from kinepoly.scene.spec import LinkInput, Scene, SliderInput, SliderSpec

__all__ = ["Drive", "Joint", "Mechanism", "Revolute", "build_mechanism"]

Vec = tuple[float, float]
T = TypeVar("T")


class Revolute(Struct, frozen=True):
    """A pin: ``point`` is a point of both ``links``."""

    point: str
    links: tuple[str, str]

    def other(self, link: str) -> str:
        return self.links[1] if self.links[0] == link else self.links[0]

    @property
    def name(self) -> str:
        return self.point


Joint = Revolute | SliderSpec


def joint_links(joint: Joint) -> tuple[str, str]:
    if isinstance(joint, Revolute):
        return joint.links
    return (joint.block, joint.guide)


class Drive(Struct, frozen=True):
    """One input as the joint it drives: ``moving`` turns (about ``joint``'s pin) or slides (the block of
    ``joint``) on ``base``, which is the frame or a moving link. ``index`` 0 is the first input, the one
    a sweep varies."""

    spec: LinkInput | SliderInput
    moving: str
    base: str
    joint: Revolute | SliderSpec
    index: int
    on_frame: bool

    @property
    def name(self) -> str:
        """theta32 or s34: the driven variable as a textbook writes it."""
        if isinstance(self.spec, SliderInput):
            return f"s{self.spec.slider}"
        return f"theta{self.base}{self.moving}"

    def value(self) -> float:
        """The scene's value: theta (rad) or s (length)."""
        return self.spec.angle_rad if isinstance(self.spec, LinkInput) else self.spec.s

    def rate(self, order: int) -> float:
        """omega or s_dot (order 1), alpha or s_ddot (order 2), relative to ``base``."""
        if isinstance(self.spec, LinkInput):
            return self.spec.omega if order == 1 else self.spec.alpha
        return self.spec.s_dot if order == 1 else self.spec.s_ddot


class Mechanism(Struct, frozen=True, dict=True):
    """The links (points in their own frames), the joints, the ground and the input of a scene."""

    scene: Scene

    @property
    def ground(self) -> str | None:
        return self.scene.ground

    @property
    def sliders(self) -> tuple[SliderSpec, ...]:
        return self.scene.sliders

    @cached_property
    def link_names(self) -> tuple[str, ...]:
        return tuple(link.name for link in self.scene.links)

    @cached_property
    def _locals(self) -> dict[tuple[str, str], Vec]:
        """Every point of every link, keyed (link, point): the one index of the mechanism's names."""
        return {(link.name, p.name): p.local for link in self.scene.links for p in link.points}

    @cached_property
    def _links_of(self) -> dict[str, tuple[str, ...]]:
        out: dict[str, list[str]] = {}
        for link in self.scene.links:
            for p in link.points:
                out.setdefault(p.name, []).append(link.name)
        return {point: tuple(links) for point, links in out.items()}

    @cached_property
    def revolutes(self) -> tuple[Revolute, ...]:
        """The pins implied by shared point names. A point of k links is a compound hinge: k - 1 pins,
        each joining the first of those links (in scene order) to one of the others."""
        return tuple(Revolute(point, (links[0], other))
                     for point, links in self._links_of.items() for other in links[1:])

    @cached_property
    def _joints_of(self) -> dict[str, tuple[Joint, ...]]:
        out: dict[str, list[Joint]] = {name: [] for name in self.link_names}
        for joint in self.joints:
            for link in dict.fromkeys(joint_links(joint)):
                out.setdefault(link, []).append(joint)
        return {link: tuple(joints) for link, joints in out.items()}

    @cached_property
    def _sliders(self) -> dict[str, SliderSpec]:
        return {s.name: s for s in self.sliders}

    def local(self, link: str, point: str) -> Vec:
        """Coordinates of ``point`` in ``link``'s own frame (KeyError when the link has no such point)."""
        return self._locals[(link, point)]

    @cached_property
    def link_size(self) -> float:
        """The longest distance between two points of one link (the scene's points): the mechanism's own length
        scale."""
        return max((abs(complex(*p.local) - complex(*q.local)) for link in self.scene.links for p in link.points
                    for q in link.points), default=0.0)

    def local_at(self, link: str, point: str) -> complex:
        """``local`` as x + iy (``model.array_pose.local_point``), made once per point: a family's point one per
        row (``model.family``)."""
        key = (link, point)
        known = self._local_at
        return known[key] if key in known else known.setdefault(key, self._complex(self.local(link, point)))

    @staticmethod
    def _complex(local: Vec) -> complex:
        """A point's own coordinates as x + iy: one number (a family's, one per row: ``model.family``)."""
        return complex(local[0], local[1])

    @cached_property
    def _local_at(self) -> dict[tuple[str, str], complex]:
        return {}

    def places_of(self, point: str) -> tuple[tuple[str, complex], ...]:
        """The links that have ``point``, in scene order, each with the point's ``local_at``: where a position
        looks the point up, made once per point."""
        known = self._places
        if point in known:
            return known[point]
        found = known[point] = tuple((link, self.local_at(link, point)) for link in self.links_of_point(point))
        return found

    @cached_property
    def _places(self) -> dict[str, tuple[tuple[str, complex], ...]]:
        return {}

    def distance(self, link: str, a: str, b: str) -> float:
        """|ab| in ``link``'s own frame (a link length)."""
        key = (link, a, b)
        known = self._lengths
        if key in known:
            return known[key]
        (ax, ay), (bx, by) = self.local(link, a), self.local(link, b)
        found = known[key] = math.hypot(bx - ax, by - ay)
        return found

    @cached_property
    def _lengths(self) -> dict[tuple[str, str, str], float]:
        return {}

    def slide_through(self, slider: SliderSpec) -> Vec:
        """A point of ``slider``'s line in its guide's own frame (the line's ``through``)."""
        return slider.through

    def has_point(self, link: str, point: str) -> bool:
        return (link, point) in self._locals

    def links_of_point(self, point: str) -> tuple[str, ...]:
        """The links that have ``point``, in scene order."""
        return self._links_of.get(point, ())

    def owner(self, point: str) -> str:
        """The first link (in scene order) that has ``point``."""
        owners = self.links_of_point(point)
        if not owners:
            raise KeyError(point)
        return owners[0]

    def slider(self, name: str) -> SliderSpec:
        return self._sliders[name]

    @cached_property
    def joints(self) -> tuple[Joint, ...]:
        return (*self.revolutes, *self.sliders)

    def joints_of(self, link: str) -> tuple[Joint, ...]:
        return self._joints_of.get(link, ())

    @cached_property
    def rotation_class(self) -> dict[str, str]:
        """Each link mapped to a representative of the links that must turn with it (sliders)."""
        parent = {name: name for name in self.link_names}

        def find(x: str) -> str:
            while parent[x] != x:
                x = parent[x]
            return x

        for s in self.sliders:
            a, b = find(s.block), find(s.guide)
            if a != b:
                parent[max(a, b)] = min(a, b)
        return {name: find(name) for name in self.link_names}

    @cached_property
    def _classes(self) -> dict[str, tuple[str, ...]]:
        cls = self.rotation_class
        out: dict[str, list[str]] = {}
        for name in self.link_names:
            out.setdefault(cls[name], []).append(name)
        return {name: tuple(out[cls[name]]) for name in self.link_names}

    def turning_together(self, link: str) -> tuple[str, ...]:
        """``link`` and every link that must turn with it (joined by sliders): one omega, one alpha."""
        return self._classes[link]

    def class_rate(self, rates: Mapping[str, T], link: str) -> T | None:
        """The rate (omega or alpha) of ``link`` from ``rates`` known for any link that turns with it."""
        if link in rates:
            return rates[link]
        cls = self.rotation_class
        return next((value for other, value in rates.items() if cls[other] == cls[link]), None)

    def turns_with_ground(self, link: str) -> bool:
        """True when ``link`` can never turn: it is the ground or slides on it (via sliders)."""
        if self.ground is None:
            return False
        return self.rotation_class[link] == self.rotation_class[self.ground]

    def has_turning_guide(self, slider: SliderSpec) -> bool:
        """A Coriolis term exists for this slider: its guide may turn."""
        return self._turning[slider.guide]

    @cached_property
    def _turning(self) -> dict[str, bool]:
        """Whether each link may turn (``turns_with_ground``)."""
        return {link: not self.turns_with_ground(link) for link in self.link_names}

    @cached_property
    def drives(self) -> tuple[Drive, ...]:
        """Every input of the scene as the joint it drives, the first input first."""
        out = []
        for index, spec in enumerate(self.scene.inputs):
            if isinstance(spec, SliderInput):
                slider = self.slider(spec.slider)
                on_frame = self.ground in (slider.block, slider.guide)
                out.append(Drive(spec, slider.block, slider.guide, slider, index, on_frame))
            elif isinstance(spec, LinkInput):
                base = spec.relative_to or self.ground
                assert base is not None
                out.append(Drive(spec, spec.link, base, self._pin_between(spec.link, base, index), index,
                                 base == self.ground))
        return tuple(out)

    def _pin_between(self, link: str, base: str, index: int) -> Revolute:
        for joint in self.joints_of(link):
            if isinstance(joint, Revolute) and base in joint.links:
                return joint
        shared = [p for p in self.scene.link(link).point_names if base in self.links_of_point(p)]
        where = "input" if len(self.scene.inputs) == 1 else f"input.{index + 1}"
        if shared:
            return Revolute(shared[0], (link, base))
        frame = " (the frame)" if base == self.ground else ""
        raise SceneError(
            f"{self.scene.source}: {where}.link: link {link} has no pin with link {base}{frame}; "
            f"expected the input link to turn about a point it shares with link {base}"
        )

    def input_pivot(self, spec: LinkInput | None = None) -> Revolute:
        """The pin about which an input link (the first input's, by default) turns on its base."""
        wanted = spec if spec is not None else self.scene.input
        for drive in self.drives:
            if drive.spec is wanted and isinstance(drive.joint, Revolute):
                return drive.joint
        raise SceneError(f"{self.scene.source}: input: the input does not turn a link")


def build_mechanism(scene: Scene) -> Mechanism:
    """Build the mechanism and check its mobility by Gruebler's count.

    Raises MobilityError when the count is not one (a ``[given]`` scene is one free body).
    """
    mechanism = Mechanism(scene)
    if scene.ground is None:
        if len(scene.links) != 1 or mechanism.joints:
            raise MobilityError(f"{scene.source}: given: a [given] scene is one free body; found "
                                f"{len(scene.links)} links and {len(mechanism.joints)} joints")
        return mechanism
    n = len(scene.links)
    j = len(mechanism.joints)
    h = len(scene.gears) + sum(1 for cam in scene.cams if cam.is_spline)  # a spline cam's contact: one pair
    mobility = 3 * (n - 1) - 2 * j - h
    inputs = len(scene.inputs)
    if mobility != inputs:
        _check_connected(mechanism)
        given = "one input" if inputs == 1 else f"{inputs} inputs"
        formula = (f"3(n - 1) - 2j = 3*({n} - 1) - 2*{j}" if not h else
                   f"3(n - 1) - 2j - h = 3*({n} - 1) - 2*{j} - {h}")
        pairs = f" and h = {h} higher pairs (gears, spline cams)" if h else ""
        raise MobilityError(
            f"{scene.source}: links: Gruebler's count gives mobility {formula} = "
            f"{mobility} for n = {n} links and j = {j} joints ({len(mechanism.revolutes)} revolute, "
            f"{len(scene.sliders)} sliding{_compound_text(mechanism)}){pairs}, but the scene gives {given}; "
            + ("add a link or remove a joint" if mobility < inputs else
               "add a joint or a link with two joints, or an [[input]] table per further degree of freedom")
            + _loose_text(mechanism)
        )
    _check_connected(mechanism)
    mechanism.drives  # noqa: B018 - raises SceneError when an input link has no pin with its base
    return mechanism


def _loose_text(mechanism: Mechanism) -> str:
    """The links held by one joint only (free to turn or slide about it), and the points that could
    join them: their points that no other link has."""
    out = []
    driven = {name for spec in mechanism.scene.inputs if isinstance(spec, LinkInput) for name in (spec.link,)}
    for link in mechanism.link_names:
        joints = mechanism.joints_of(link)
        if link == mechanism.ground or len(joints) != 1 or link in driven:
            continue
        alone = [p for p in mechanism.scene.link(link).point_names if len(mechanism.links_of_point(p)) == 1]
        hint = (f"; its point(s) {', '.join(alone)} are on no other link (did you mean to add one to the frame "
                f"{mechanism.ground} or to another link?)") if alone else ""
        out.append(f"link {link} is joined only at {joints[0].name}{hint}")
    return ("\n  " + "\n  ".join(out)) if out else ""


def _compound_text(mechanism: Mechanism) -> str:
    """The compound hinges, as Gruebler counts them: a pin of k links is k - 1 joints."""
    hinges = [(point, links) for point, links in mechanism._links_of.items() if len(links) > 2]
    return "".join(f"; pin {point} joins links {', '.join(links)}: {len(links) - 1} joints" for point, links in hinges)


def _check_connected(mechanism: Mechanism) -> None:
    scene = mechanism.scene
    parent = {name: name for name in mechanism.link_names}

    def root(link: str) -> str:
        while parent.setdefault(link, link) != link:
            link = parent[link]
        return link

    pairs = [joint_links(joint) for joint in mechanism.joints] + [gear.links for gear in scene.gears]
    pairs += [(cam.cam, cam.follower) for cam in scene.cams if cam.is_spline]
    for links in pairs:
        first = root(links[0])
        for other in links[1:]:
            parent[root(other)] = first
    ground = root(mechanism.ground or "")
    seen = {name for name in mechanism.link_names if root(name) == ground}
    loose = [name for name in mechanism.link_names if name not in seen]
    if loose:
        raise MobilityError(f"{mechanism.scene.source}: links: link(s) {', '.join(loose)} are not joined "
                            "to the frame through any chain of joints; expected one connected mechanism")
