"""What a scene reader knows so far: its report, the unit kinds, and the links, sliders and ground read.

The section readers (:mod:`kinepoly.scene.mechanism_tables`, :mod:`kinepoly.scene.input_tables`,
:mod:`kinepoly.scene.request_tables`) share this state, and check the names a scene uses
against the names it defines.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from kinepoly.scene.problems import ProblemReport
from kinepoly.scene.spec import LinkSpec, SliderSpec
from kinepoly.scene.units import Kinds

__all__ = ["ReaderState"]


@dataclass
class ReaderState:
    """The state of one scene's reading; each section reader checks one section and reports what is wrong."""

    report: ProblemReport
    kinds: Kinds
    links: dict[str, LinkSpec] | None = None  # None: [links] could not be read at all
    sliders: list[SliderSpec] = field(default_factory=list)
    ground: str | None = None

    # -- names known so far

    def has_link(self, name: str) -> bool:
        return self.links is None or name in self.links

    @property
    def point_names(self) -> set[str]:
        return {p.name for link in (self.links or {}).values() for p in link.points}

    @property
    def slider_names(self) -> list[str]:
        return [slider.name for slider in self.sliders]
