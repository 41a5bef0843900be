"""What a scene reader knows so far: its report, the unit kinds, and the links, sliders and ground read.

The section readers (:mod:`kinepoly.scene.mechanism_tables`, :mod:`kinepoly.scene.input_tables`,
:mod:`kinepoly.scene.request_tables`) share this state, and check the names a scene uses
against the names it defines.
"""

from __future__ import annotations

import math

from msgspec import Struct, field

from kinepoly.geom.tolerances import LAST_BITS_REL
from kinepoly.scene.lines import KeyPath
from kinepoly.scene.problems import ProblemReport, show_value
from kinepoly.scene.spec import LinkSpec, SliderSpec
from kinepoly.scene.units import Kinds, quantity, quantity_pair
from kinepoly.scene.values import Vector, check_keys, require

__all__ = ["ReaderState", "polar_point"]

_POLAR_KEYS = ("polar",)


class ReaderState(Struct):
    """The state of one scene's reading; each section reader checks one section and reports what is wrong."""

    report: ProblemReport
    kinds: Kinds
    links: dict[str, LinkSpec] | None = None  # None: [links] could not be read at all
    sliders: list[SliderSpec] = field(default_factory=list)
    ground: str | None = None
    _point_names: tuple[tuple[int, int], set[str]] | None = None

    # -- names known so far

    def has_link(self, name: str) -> bool:
        return self.links is None or name in self.links

    @property
    def point_names(self) -> set[str]:
        """Every point's name, gathered once for the links read (each reference to a point asks for it)."""
        links = self.links or {}
        key = (id(links), len(links))
        if self._point_names is None or self._point_names[0] != key:
            self._point_names = (key, {p.name for link in links.values() for p in link.points})
        return self._point_names[1]

    @property
    def slider_names(self) -> list[str]:
        return [slider.name for slider in self.sliders]

    # -- a point: [x, y] or { polar = [r, angle] } (a link's points, a cam circle's centre)

    def read_point_value(self, path: KeyPath, value: object) -> tuple[Vector | None, tuple[float, float] | None]:
        """The point in x, y, and (r, angle in radians) where it is written in polar form."""
        if isinstance(value, list) and len(value) == 2:
            return quantity_pair(self.report, path, value, self.kinds.length), None
        if not isinstance(value, dict):
            self.report.add(path, f"expected [x, y] or {{ polar = [r, angle] }}, got {show_value(value)}")
            return None, None
        check_keys(self.report, path, value, _POLAR_KEYS)
        polar = require(self.report, path, value, "polar", "[x, y] or { polar = [r, angle] }")
        if polar is None:
            return None, None
        if not isinstance(polar, list) or len(polar) != 2:
            self.report.add(path + ("polar",), f"expected [r, angle], got {show_value(polar)}")
            return None, None
        r = quantity(self.report, path + ("polar", "r"), polar[0], self.kinds.length)
        angle = quantity(self.report, path + ("polar", "angle"), polar[1], self.kinds.angle)
        return (None, None) if r is None or angle is None else (polar_point(r, angle), (r, angle))


def polar_point(r: float, angle: float) -> Vector:
    """The point at distance r and angle (rad); exact on the axes."""
    quarter = angle / (math.pi / 2.0)
    if abs(quarter - round(quarter)) < LAST_BITS_REL * max(1.0, abs(quarter)):
        cos, sin = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[round(quarter) % 4]
        return (r * cos, r * sin)
    return (r * math.cos(angle), r * math.sin(angle))
