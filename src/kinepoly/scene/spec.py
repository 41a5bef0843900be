"""Frozen values of a scene, as the loader makes them from TOML.

Units are converted at the edge: every length here is in the scene's length unit, every
angle in radians, every angular speed in rad/s. ``Located`` items keep the TOML line so that
later stages can still point a user at the right place.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Literal

__all__ = [
    "DrawSpec",
    "FindSpec",
    "GivenInput",
    "GivenPoint",
    "InputSpec",
    "LinkInput",
    "LinkSpec",
    "PointSpec",
    "Scene",
    "SliderInput",
    "SliderSpec",
    "Units",
]

Vector = tuple[float, float]


@dataclass(frozen=True)
class Units:
    """The scene's units: the length unit of every output and the angle unit of angles shown."""

    length: Literal["mm", "cm", "m", "in"] = "mm"
    angle: Literal["deg", "rad"] = "deg"


@dataclass(frozen=True)
class PointSpec:
    """A named point of a link, in the link's own frame (scene length unit)."""

    name: str
    local: Vector
    line: int = 0


@dataclass(frozen=True)
class LinkSpec:
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


@dataclass(frozen=True)
class SliderSpec:
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


@dataclass(frozen=True)
class LinkInput:
    """Input: ``link`` turns about its joint with the ground; theta, omega, alpha given."""

    link: str
    angle_rad: float
    omega: float
    alpha: float
    line: int = 0


@dataclass(frozen=True)
class SliderInput:
    """Input: a driven slider, its variable s and derivatives given (lengths per s, per s^2)."""

    slider: str
    s: float
    s_dot: float
    s_ddot: float
    line: int = 0


@dataclass(frozen=True)
class GivenPoint:
    """A point of the one free body of a ``[given]`` scene, with known motion."""

    name: str
    velocity: Vector
    acceleration: Vector | None
    line: int = 0


@dataclass(frozen=True)
class GivenInput:
    """Input of a ``[given]`` scene: the motion of two points of one link."""

    points: tuple[GivenPoint, ...]
    line: int = 0


InputSpec = LinkInput | SliderInput | GivenInput


@dataclass(frozen=True)
class FindSpec:
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


@dataclass(frozen=True)
class DrawSpec:
    """Drawing options: polygon scales in drawing mm per (length/s) and per (length/s^2)."""

    kv: float | None = None
    ka: float | None = None


@dataclass(frozen=True)
class Scene:
    """A whole scene, loaded and checked for its own consistency (not yet for mobility)."""

    title: str
    units: Units
    ground: str | None
    links: tuple[LinkSpec, ...]
    sliders: tuple[SliderSpec, ...]
    input: InputSpec
    guess: tuple[tuple[str, Vector], ...] = ()
    find: FindSpec = field(default_factory=FindSpec)
    draw: DrawSpec = field(default_factory=DrawSpec)
    source: str = "<scene>"

    def link(self, name: str) -> LinkSpec:
        return self._links_by_name[name]  # KeyError for an unknown name

    @functools.cached_property
    def _links_by_name(self) -> dict[str, LinkSpec]:
        """The links by name, indexed once (a scan per lookup made long mechanisms quadratic)."""
        out: dict[str, LinkSpec] = {}
        for link in self.links:
            out.setdefault(link.name, link)
        return out
