"""The pole of a link's finite displacement between two positions (RO 2.1, Fig. 1).

A link moved from one position to another, not by a pure translation, is turned about one point,
the pole P12: the crossing of the perpendicular bisectors of A1A2 and B1B2 for any two of its points
A and B. As the two positions close, P12 tends to the link's instant center with the frame.
"""

from __future__ import annotations

import cmath

from msgspec import Struct

from kinepoly.geom.tolerances import COINCIDENT_REL, PARALLEL_SIN
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose

__all__ = ["FinitePole", "bisectors_crossing", "finite_pole"]


def bisectors_crossing(a1: complex, a2: complex, b1: complex, b2: complex) -> complex | None:
    """The point as far from a1 as from a2 and from b1 as from b2: a point that did not move is the pole
    itself; None where the bisectors are parallel (a translation: the pole is at infinity) or nothing moved."""
    da, db = a2 - a1, b2 - b1
    size = max(abs(a1), abs(a2), abs(b1), abs(b2), 1.0)
    still_a, still_b = abs(da) <= COINCIDENT_REL * size, abs(db) <= COINCIDENT_REL * size
    if still_a or still_b:
        return None if still_a and still_b else (a1 if still_a else b1)
    ma, mb = (a1 + a2) / 2, (b1 + b2) / 2
    # z on the bisector of a1a2: Re((z - ma) conj(da)) = 0, i.e. x da.x + y da.y = ma . da
    det = da.real * db.imag - da.imag * db.real
    scale = abs(da) * abs(db)
    if scale == 0.0 or abs(det) <= PARALLEL_SIN * scale:
        return None
    ca = ma.real * da.real + ma.imag * da.imag
    cb = mb.real * db.real + mb.imag * db.imag
    return complex((ca * db.imag - da.imag * cb) / det, (da.real * cb - ca * db.real) / det)


class FinitePole(Struct, frozen=True):
    """The pole of ``link``'s displacement from ``first`` to ``second`` (poses), through points ``a`` and ``b``."""

    link: str
    a: str
    b: str
    a1: complex
    a2: complex
    b1: complex
    b2: complex
    pole: complex | None
    turn: float
    """The angle the link turned through (rad, ccw positive, in (-pi, pi])."""


def _two_points(mechanism: Mechanism, link: str) -> tuple[str, str]:
    """The link's two points farthest apart (the bisectors cross most sharply for them)."""
    points = mechanism.scene.link(link).points
    pairs = [(abs(complex(*p.local) - complex(*q.local)), p.name, q.name)
             for k, p in enumerate(points) for q in points[k + 1:]]
    if not pairs or max(pairs)[0] == 0.0:
        raise ValueError(f"link {link} needs two distinct points for its pole")
    _, a, b = max(pairs)
    return a, b


def finite_pole(mechanism: Mechanism, link: str, first: LinkPose, second: LinkPose) -> FinitePole:
    """P12 of ``link`` between its poses ``first`` and ``second``."""
    a, b = _two_points(mechanism, link)
    la, lb = mechanism.local(link, a), mechanism.local(link, b)
    a1, a2 = complex(*first.world(la)), complex(*second.world(la))
    b1, b2 = complex(*first.world(lb)), complex(*second.world(lb))
    turn = cmath.phase(cmath.exp(1j * (second.theta - first.theta)))
    return FinitePole(link, a, b, a1, a2, b1, b2, bisectors_crossing(a1, a2, b1, b2), turn)
