"""The construction as data: each step lays vectors, draws direction lines, finds one thing."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from kinepoly.geom.lines import Line

__all__ = ["Direction", "DrawnVector", "Step", "Term"]

Vec = tuple[float, float]
Term = Literal["absolute", "relative", "normal", "tangential", "coriolis", "sliding"]
StepKind = Literal["known", "image", "proportional", "intersection", "coriolis", "read", "linear-solve"]
Relation = Literal["perpendicular", "parallel", "at-angle", "along", "face"]


@dataclass(frozen=True)
class DrawnVector:
    """A vector of the polygon from ``start`` to ``end`` (physical units, pole at 0)."""

    label: str
    start: Vec
    end: Vec
    term: Term


@dataclass(frozen=True)
class Direction:
    """A direction line of a step as data, so that any language can say it (``Line.label`` is English).

    The line carries the unknown ``term`` (``v_B/A``, ``a^t_B/A``, ``a_B/B@1``; empty for the lines
    of an image). It is ``relation`` to ``reference``: perpendicular to a segment of the mechanism
    (``AB``), parallel to the slide of a slider (``14``), at ``angle_deg`` to a side of the polygon
    (``ab``) or along it. It is drawn through the polygon point ``through`` (``a``, ``b@4``), or,
    when ``after`` names a term laid from there (``a^n_B/A``, ``a^c_B@4/B``), through that term's end.
    """

    term: str
    relation: Relation
    reference: str
    through: str
    after: str = ""
    angle_deg: float = 0.0


@dataclass(frozen=True)
class Step:
    """One step of the construction.

    ``known`` says, for each term of the vector equation, what is known of it
    ("magnitude and direction" or "direction"); ``lines`` are the direction lines drawn
    (physical units, through a tip, along a direction); ``result`` names what the step yields.

    The step says what it does as data, from which ``kinepoly.present.phrasing`` words it in any
    language (``solve --steps``, the JSON's ``text``, the drawings and the handout all use that):
    ``topic`` names the move and ``params`` its language-neutral arguments (names of points,
    links, sliders and tips; numbers), ``directions`` describe ``lines`` one for one:

    - ``input-rate``: link, ground, rate, sense (omega12 in the velocity polygon, alpha12 in the other)
    - ``driven-slider``: slider, point, amount (s_dot or s_ddot, along the slide from the pole)
    - ``given-point``: point, magnitude
    - ``relative``: point, reference, link, ground, length, magnitude, rate, sense; for an
      acceleration also omega, normal, tangential (rate and sense are then alpha's)
    - ``image``: link, point, first, second, angle_first, angle_second (degrees)
    - ``image-translating``: link, point, first, second
    - ``proportional``: link, point, first, second, ratio, height
    - ``intersection``: point (the directions say the rest)
    - ``read``: link, ground, term, first, second, magnitude, length, rate, sense
    - ``coriolis``: term, guide, ground, omega, relative, speed, magnitude, sense, start
    - ``normals``: none (the vectors are the normal terms; their ω and segment length are the solution's)
    - ``given-normal``: point, reference, magnitude
    - ``pitch-point``: pair, pitch, point, known_point, link, known (a planet's tip at a pitch point is the
      known gear's there)
    - ``planet-centre``: planet, arm, centre, pivot, pitch_a, pitch_b, known_a, known_b (the known gears' tip
      labels), gear_a, gear_b, ratio (where the centre divides the pitch points), side (the physical length
      of the chord of the two tips), omega (the arm's), length (pivot to centre), normal (the arm's normal term)
    Steps of kind ``linear-solve`` have no topic: their ``result`` lists the tips found; their
    params are group, links (the group's, comma-separated) and tips.
    """

    polygon: Literal["velocity", "acceleration"]
    kind: StepKind
    equation: str
    result: str
    known: tuple[tuple[str, str], ...] = ()
    vectors: tuple[DrawnVector, ...] = ()
    lines: tuple[Line, ...] = ()
    value: tuple[float, ...] = ()
    topic: str = ""
    params: tuple[tuple[str, str | float], ...] = ()
    directions: tuple[Direction, ...] = ()

    def param(self, name: str) -> str | float:
        """The named argument of the step's topic (KeyError when the topic has none of that name)."""
        for key, value in self.params:
            if key == name:
                return value
        raise KeyError(f"step {self.equation!r} ({self.topic or self.kind}) has no parameter {name!r}")
