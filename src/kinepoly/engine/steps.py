"""The construction as data: each step lays vectors, draws direction lines, finds one thing."""

from __future__ import annotations

import re
from functools import cache
from typing import Literal

from msgspec import Struct

from kinepoly.geom.lines import Line
from kinepoly.scene.link_point import LinkPoint

__all__ = ["Direction", "DrawnVector", "Step", "Term", "TermName", "term_name"]

Vec = tuple[float, float]
Term = Literal["absolute", "relative", "normal", "tangential", "coriolis", "sliding"]
StepKind = Literal["known", "image", "proportional", "intersection", "coriolis", "read", "linear-solve"]
Relation = Literal["perpendicular", "parallel", "at-angle", "along", "face"]


_TERM_TEXT = re.compile(r"^([va])(?:\^([a-z]))?_([^/\s]+)(?:/([^/\s]+))?$")


class TermName(Struct, frozen=True):
    """A term of a vector equation as a value: ``a^n_B@4/A`` is the ``quantity`` a (v for a velocity), its
    ``component`` n (t tangential, c Coriolis; "" for a whole velocity or acceleration) of ``point`` B@4
    relative to ``reference`` A (None for an absolute term, ``a_B``). ``text`` is the textbook's name."""

    quantity: Literal["v", "a"]
    component: str
    point: LinkPoint
    reference: LinkPoint | None = None

    @property
    def text(self) -> str:
        return self.quantity + (f"^{self.component}" if self.component else "") + "_" + self.subscript

    @property
    def subscript(self) -> str:
        """What the name writes below the line: ``B@4/A``."""
        return self.point.text if self.reference is None else f"{self.point.text}/{self.reference.text}"

    @property
    def loose(self) -> TermName:
        """The same term whatever links its points are taken on (``a_B@4/A@3`` -> ``a_B/A``)."""
        reference = None if self.reference is None else LinkPoint(self.reference.point)
        return TermName(self.quantity, self.component, LinkPoint(self.point.point), reference)

    def __str__(self) -> str:
        return self.text


@cache
def term_name(text: str) -> TermName | None:
    """The term a name like ``v_B/A``, ``a^t_B@4/C`` or ``a_B`` says, as a value; None for any other text
    (``...``, ``2 omega x v_B/A``). The one reader of the names the construction writes."""
    m = _TERM_TEXT.match(text)
    if m is None:
        return None
    quantity: Literal["v", "a"] = "v" if m.group(1) == "v" else "a"
    reference = None if m.group(4) is None else LinkPoint.parse(m.group(4))
    return TermName(quantity, m.group(2) or "", LinkPoint.parse(m.group(3)), reference)


class DrawnVector(Struct, frozen=True):
    """A vector of the polygon from ``start`` to ``end`` (physical units, pole at 0)."""

    label: str
    start: Vec
    end: Vec
    term: Term

    @property
    def name(self) -> TermName | None:
        """The term the vector is (``label`` as a value: its quantity, component, point and reference)."""
        return term_name(self.label)


class Direction(Struct, frozen=True):
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

    @property
    def terms(self) -> tuple[TermName, ...]:
        """The unknown terms the line carries, as values: one, two along a triad's line toward its Assur point
        (``v_B/A + v_S/B``), none for an image's line."""
        names = (term_name(part.strip()) for part in self.term.split(" + ")) if self.term else ()
        return tuple(name for name in names if name is not None)


class Step(Struct, frozen=True):
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

    @property
    def sides(self) -> tuple[tuple[str, ...], ...]:
        """The vector equation's sides, each its terms in order (``v_B = v_A + v_B/A`` -> ((v_B,), (v_A, v_B/A)));
        ``term_name`` reads a term as a value."""
        return tuple(tuple(term.strip() for term in side.split(" + ")) for side in self.equation.split(" = "))

    def param(self, name: str) -> str | float:
        """The named argument of the step's topic (KeyError when the topic has none of that name)."""
        for key, value in self.params:
            if key == name:
                return value
        raise KeyError(f"step {self.equation!r} ({self.topic or self.kind}) has no parameter {name!r}")
