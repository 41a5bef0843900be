"""Frozen values of a scene, as the loader makes them from TOML.

Units are converted at the edge: every length here is in the scene's length unit, every
angle in radians, every angular speed in rad/s. ``Located`` items keep the TOML line so that
later stages can still point a user at the right place.
"""

from __future__ import annotations

import functools
from typing import Literal

from msgspec import Struct, field
from msgspec.structs import replace

__all__ = [
    "CamSpec",
    "DrawSpec",
    "FindSpec",
    "GearSpec",
    "GivenInput",
    "GivenPoint",
    "InputSpec",
    "LinkInput",
    "LinkSpec",
    "PitchCircle",
    "PitchLine",
    "PointSpec",
    "Scene",
    "SliderInput",
    "SliderSpec",
    "Units",
]

Vector = tuple[float, float]


class Units(Struct, frozen=True):
    """The scene's units: the length unit of every output and the angle unit of angles shown."""

    length: Literal["mm", "cm", "m", "in"] = "mm"
    angle: Literal["deg", "rad"] = "deg"


class PointSpec(Struct, frozen=True):
    """A named point of a link, in the link's own frame (scene length unit)."""

    name: str
    local: Vector
    line: int = 0
    polar: tuple[float, float] | None = None
    """(r, angle in radians) where the scene wrote the point as ``{ polar = [r, angle] }`` (``local`` is then
    the same point in x, y); a scene written back writes it so."""


class LinkSpec(Struct, frozen=True):
    """A rigid body and its named points."""

    name: str
    points: tuple[PointSpec, ...]
    line: int = 0

    def point(self, name: str) -> PointSpec:
        for p in self.points:
            if p.name == name:
                return p
        raise KeyError(name)

    @property
    def point_names(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.points)


class SliderSpec(Struct, frozen=True):
    """A prismatic joint: ``block`` slides on ``guide``; ``point`` of the block runs on the line.

    ``through`` and ``angle_rad`` give the line in the guide's own frame; the block's local
    x-axis runs along the line's direction.
    """

    name: str
    block: str
    guide: str
    point: str
    through: Vector
    angle_rad: float
    line: int = 0


class PitchCircle(Struct, frozen=True):
    """A gear's pitch circle: centred on ``center`` (a point of the gear's link), radius ``radius``."""

    center: str
    radius: float


class PitchLine(Struct, frozen=True):
    """A rack's pitch line, in the rack link's own frame."""

    through: Vector
    angle_rad: float


class GearSpec(Struct, frozen=True):
    """Two pitch curves rolling without slip (``[[gears]]``): ``links[k]`` carries ``pitch[k]``.

    ``phase[k]``: at the reference mesh, a circle's x-axis turned by phase points at the pitch point; a
    line's ``through`` moved by phase (a length) along it lies at the pitch point. A circle's phase is
    written in the scene's angle unit (degrees by default) and stored here in radians, as every angle
    of a spec; docs/scene-format.md ("Higher pairs") says what it places."""

    name: str
    links: tuple[str, str]
    pitch: tuple[PitchCircle | PitchLine, PitchCircle | PitchLine]
    internal: bool = False
    phase: tuple[float, float] = (0.0, 0.0)
    line: int = 0


class CamSpec(Struct, frozen=True):
    """A circle (or ``points``) profile on ``cam`` touching ``follower`` (``[[cams]]``): by a roller (``roller`` a
    point of the follower and ``roller_radius``), a flat face (``flat``: through, angle in the follower's frame) or a
    knife edge (``knife``, a point of the follower). ``equivalent``: the link the pair is replaced by."""

    name: str
    cam: str
    follower: str
    center: Vector
    radius: float
    kind: Literal["roller", "flat", "knife"]
    point: str | None = None
    roller_radius: float = 0.0
    flat: tuple[Vector, float] | None = None
    inside: bool = False
    line: int = 0
    equivalent: str = ""
    """The name of the equivalent link (a binary link or a block), set when the scene is made."""
    center_point: str = ""
    """The name of the profile's centre as a point of the cam (and of the equivalent link)."""
    profile_points: tuple[Vector, ...] = ()
    """A ``points`` profile: the points the closed spline runs through, counter-clockwise, in the cam's
    frame (empty for a circle; ``center`` and ``radius`` describe a circle profile only)."""
    follower_profile: bool = False
    """Whether the follower touches by a circular profile of its own (``follower_profile``), centred on
    ``point`` with radius ``roller_radius``, rather than by a roller turning on a pin at ``point``: the same
    motion (a roller's spin moves nothing else), so the pair is read as a roller (``kind`` "roller")."""
    follower_points: tuple[Vector, ...] = ()
    """A follower profile of points (``follower_profile = { points = [...] }``): the points its closed spline
    runs through, counter-clockwise, in the follower's frame. The two splines touch (``kind`` "knife",
    ``point`` None): the pair is replaced by the link joining both centres of curvature."""

    @property
    def is_spline(self) -> bool:
        """Whether the profile is a closed spline through ``profile_points`` rather than a circle."""
        return bool(self.profile_points)

    @property
    def is_curve_pair(self) -> bool:
        """Whether the follower touches by a spline profile of points of its own (two splines in contact)."""
        return bool(self.follower_points)


class LinkInput(Struct, frozen=True):
    """Input: ``link`` turns about its pin with ``relative_to`` (None: the ground); theta, omega, alpha
    given, relative to that link (theta_43 = angle of 3's x-axis from 4's x-axis, omega_43 = omega_3 - omega_4)."""

    link: str
    angle_rad: float
    omega: float
    alpha: float
    line: int = 0
    relative_to: str | None = None


class SliderInput(Struct, frozen=True):
    """Input: a driven slider, its variable s and derivatives given (lengths per s, per s^2)."""

    slider: str
    s: float
    s_dot: float
    s_ddot: float
    line: int = 0


class GivenPoint(Struct, frozen=True):
    """A point of the one free body of a ``[given]`` scene, with known motion."""

    name: str
    velocity: Vector
    acceleration: Vector | None
    line: int = 0


class GivenInput(Struct, frozen=True):
    """Input of a ``[given]`` scene: the motion of two points of one link."""

    points: tuple[GivenPoint, ...]
    line: int = 0


InputSpec = LinkInput | SliderInput | GivenInput


class FindSpec(Struct, frozen=True):
    """What to find. ``instant_centers`` is a tuple of pair names ("13", "2-14") or "all"."""

    velocity: tuple[str, ...] = ()
    acceleration: tuple[str, ...] = ()
    omega: tuple[str, ...] = ()
    alpha: tuple[str, ...] = ()
    sliders: tuple[str, ...] = ()
    instant_centers: tuple[str, ...] | Literal["all"] = ()
    is_default: bool = False

    @property
    def needs_acceleration(self) -> bool:
        return bool(self.acceleration or self.alpha)


class DrawSpec(Struct, frozen=True):
    """Drawing options: polygon scales in drawing mm per (length/s) and per (length/s^2)."""

    kv: float | None = None
    ka: float | None = None


class Scene(Struct, frozen=True, dict=True):
    """A whole scene, loaded and checked for its own consistency (not yet for mobility)."""

    title: str
    units: Units
    ground: str | None
    links: tuple[LinkSpec, ...]
    sliders: tuple[SliderSpec, ...]
    input: InputSpec
    """The first input: the one a sweep varies (``inputs`` holds every one)."""
    guess: tuple[tuple[str, Vector], ...] = ()
    find: FindSpec = field(default_factory=FindSpec)
    draw: DrawSpec = field(default_factory=DrawSpec)
    source: str = "<scene>"
    more_inputs: tuple[LinkInput | SliderInput, ...] = ()
    """The inputs after the first, one per further degree of freedom (``[[input]]`` tables)."""
    gears: tuple[GearSpec, ...] = ()
    cams: tuple[CamSpec, ...] = ()
    equivalent_links: tuple[str, ...] = ()
    """Links the scene did not write: each cam pair's equivalent link (not reported, not asked)."""

    @property
    def inputs(self) -> tuple[InputSpec, ...]:
        """Every input, the first one first."""
        return (self.input, *self.more_inputs)

    def link(self, name: str) -> LinkSpec:
        return self._links_by_name[name]  # KeyError for an unknown name

    def at_input(self, value: float) -> Scene:
        """This scene with its first input at ``value``: theta in radians for a link, s for a slider (its rates
        kept)."""
        inp = self.input
        if isinstance(inp, LinkInput):
            return replace(self, input=replace(inp, angle_rad=value))
        if isinstance(inp, SliderInput):
            return replace(self, input=replace(inp, s=value))
        raise TypeError("a [given] scene has no input to set")

    @functools.cached_property
    def _links_by_name(self) -> dict[str, LinkSpec]:
        """The links by name, indexed once (a scan per lookup made long mechanisms quadratic)."""
        out: dict[str, LinkSpec] = {}
        for link in self.links:
            out.setdefault(link.name, link)
        return out
