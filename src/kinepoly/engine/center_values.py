"""The values of the instant centers: each center, each Kennedy line and step, the plan, the whole.

Frozen; made by ``construct.centers`` (plan, find) and ``construct.kennedy`` (the geometry).
"""

from __future__ import annotations

from typing import Literal

from msgspec import Struct

from kinepoly.engine.circle_diagram import CircleDiagram, Edge, KennedyPlan, center_label, pair_name
from kinepoly.geom.homogeneous import Place, Triple
from kinepoly.geom.vec import Vec, add, perp, scale, sub
from kinepoly.model.mechanism import Joint
from kinepoly.notice import Notice
from kinepoly.scene.spec import CamSpec, GearSpec

__all__ = ["CenterOmega", "CenterPlan", "How", "InstantCenter", "InstantCenters", "KennedyLine", "KennedyStep",
           "Motion"]


class InstantCenter(Struct, frozen=True):
    """I_ij: ``place`` is its position, or its direction when at infinity.

    ``found`` says how: ``"pin A0"``, ``"slider 14"`` or ``"Kennedy step 3"``; ``number`` is 0 for
    a joint's center and n for the n-th center derived.
    """

    links: Edge
    place: Place
    found: str
    number: int

    @property
    def name(self) -> str:
        return pair_name(self.links)

    @property
    def label(self) -> str:
        return center_label(self.name)

    @property
    def is_at_infinity(self) -> bool:
        return self.place.is_at_infinity

    @property
    def position(self) -> Vec | None:
        return self.place.position

    @property
    def direction(self) -> Vec | None:
        return self.place.direction

    @property
    def homogeneous(self) -> Triple:
        """(x, y, 1) at a position, (ux, uy, 0) at infinity."""
        return self.place.homogeneous


class KennedyLine(Struct, frozen=True):
    """The line through the centers I_ik and I_jk of triangle ijk (``third`` is k), or a higher pair's
    common normal at its contact (``contact`` names the contact, ``C23``; ``third`` and ``centers`` empty).

    ``points`` are the two centers as world homogeneous triples (w = 0 at infinity), for a common
    normal the contact and the normal's direction at infinity; ``through`` and ``direction`` give the
    line in the plane, both None for the line at infinity (both centers at infinity).
    """

    third: str
    centers: tuple[str, ...]
    points: tuple[Triple, Triple]
    through: Vec | None
    direction: Vec | None
    contact: str = ""

    @property
    def is_common_normal(self) -> bool:
        return bool(self.contact)

    @property
    def label(self) -> str:
        """``I12 I13``, or ``n(C23)`` for the common normal at the contact C23."""
        if self.contact:
            return f"n({self.contact})"
        return " ".join(center_label(name) for name in self.centers)

    @property
    def is_at_infinity(self) -> bool:
        return self.through is None


class KennedyStep(Struct, frozen=True):
    """One derived center: the two Kennedy lines and where they cross.

    ``triangles`` are the two triangles whose Kennedy lines cross, or for a higher pair's center the
    one triangle whose line crosses the common normal (then ``lines[1]`` is that normal).

    ``sin_angle`` is the sine of the angle between the two lines in the plane (None when one is
    the line at infinity); ``conditioning`` the smallest sine of the step's three products (two
    joins, one crossing); ``relative_error`` the estimated error of the result. Its words come from
    ``kinepoly.present.phrasing.kennedy_words``.
    """

    number: int
    center: str
    triangles: tuple[str, ...]
    lines: tuple[KennedyLine, KennedyLine]
    result: Triple
    sin_angle: float | None
    conditioning: float
    relative_error: float
    equation: str


class CenterPlan(Struct, frozen=True):
    """Made before the position: the circle diagram's plan, the joints, what the scene asks."""

    kennedy: KennedyPlan
    joints: dict[Edge, Joint | GearSpec | CamSpec]
    asked: tuple[tuple[str, Edge], ...]
    links_needed: frozenset[str]


class InstantCenters(Struct, frozen=True):
    """Every center found (joints' and derived), the asked ones, the steps, the diagram, omegas.

    ``asked`` pairs each key as the scene wrote it ("31") with the center's name ("13").
    ``omegas`` are the angular velocities the centers give (omega_j from omega_i by the ratio
    of distances along the Kennedy line of links 1, i and j).
    """

    centers: dict[str, InstantCenter]
    asked: tuple[tuple[str, str], ...]
    steps: tuple[KennedyStep, ...]
    diagram: CircleDiagram
    omegas: tuple[CenterOmega, ...]
    notices: tuple[Notice, ...]

    def center(self, key: str) -> InstantCenter:
        """The center under the key the scene used (``"31"``) or its own name (``"13"``)."""
        names = dict(self.asked)
        return self.centers[names.get(key, key)]


class Motion(Struct, frozen=True):
    """A link's motion: it turns at ``omega`` and the point ``at`` moves with ``velocity``.

    ``about`` names the center it turns about (``"12"``) when ``velocity`` is zero there.
    """

    omega: float
    at: Vec
    velocity: Vec
    about: str | None = None

    def velocity_of(self, point: Vec) -> Vec:
        return add(self.velocity, scale(self.omega, perp(sub(point, self.at))))


How = Literal["ratio", "velocity", "same", "translating"]


class CenterOmega(Struct, frozen=True):
    """omega_1j (``symbol``, e.g. ``"omega13"``) of ``link`` j from the centers I_1j and I_ij (``centers``)
    and the motion of link i (``reference``).

    ``how`` says how, and ``params`` give its numbers, so that any language can say it
    (``kinepoly.present.phrasing``):

    - ``ratio``: I_1i, I_ij and I_1j on one line, omega_1j = omega_1i (I_1i I_ij)/(I_1j I_ij); ``given`` is
      omega_1i, ``near`` and ``far`` the two signed distances along I_1j -> I_ij
    - ``velocity``: link i does not turn about a center of its own: omega_1j = (r x v) / |r|^2 with
      ``vx``, ``vy`` the velocity of I_ij, ``rx``, ``ry`` the vector r from I_1j to I_ij, ``cross`` r x v,
      ``distance`` |r|
    - ``same``: I_ij at infinity, links i and j turn alike: ``given`` is omega_1i
    - ``translating``: I_1j at infinity, link j translates with the velocity ``vx``, ``vy`` of I_ij
    """

    link: str
    symbol: str
    omega: float
    reference: str
    centers: tuple[str, str]
    equation: str
    how: How
    params: tuple[tuple[str, float], ...]
    motion: Motion
