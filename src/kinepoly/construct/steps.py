"""The construction as data: each step lays vectors, draws direction lines, finds one thing."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from kinepoly.geom.lines import Line

__all__ = ["DrawnVector", "Step", "Term"]

Vec = tuple[float, float]
Term = Literal["absolute", "relative", "normal", "tangential", "coriolis", "sliding"]
StepKind = Literal["known", "image", "proportional", "intersection", "coriolis", "read", "linear-solve"]


@dataclass(frozen=True)
class DrawnVector:
    """A vector of the polygon from ``start`` to ``end`` (physical units, pole at 0)."""

    label: str
    start: Vec
    end: Vec
    term: Term


@dataclass(frozen=True)
class Step:
    """One step of the construction.

    ``known`` says, for each term of the vector equation, what is known of it
    ("magnitude and direction" or "direction"); ``lines`` are the direction lines drawn
    (physical units, through a tip, along a direction); ``result`` names what the step yields.
    """

    polygon: Literal["velocity", "acceleration"]
    kind: StepKind
    equation: str
    text: str
    result: str
    known: tuple[tuple[str, str], ...] = ()
    vectors: tuple[DrawnVector, ...] = ()
    lines: tuple[Line, ...] = ()
    value: tuple[float, ...] = ()
