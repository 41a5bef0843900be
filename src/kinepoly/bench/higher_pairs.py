"""The reference's rows for the higher pairs: each gear pair's rolling and each cam's contact, in mpmath.

They are written from the pairs' own geometry, not from the equivalent links the construction uses
(the reference drops those links and their joints):

* **A cam** (a circle of radius R about K on the cam): the follower's roller (radius r, about W)
  touches the circle when |W - K| = R + r (R - r inside a groove); a knife edge W when |W - K| = R;
  a flat face (a line through T along d, in the follower's frame) when K lies R to the face's left,
  (K - T) . (J d) = R.
* **A gear pair**: the pitch point P (on the line of centres, r_0 from the first centre, or the foot
  of the perpendicular from the pinion's centre to the rack's line); each side's rolled arc sigma
  (a circle: r (angle of P from its centre - theta - phase); a line: (P - T) . d - phase) and the
  tangent t at P (a circle: J m, m the unit from its centre to P; a line: d). Rolling without slip
  keeps sigma_1 - c sigma_0 constant, c = t_0 . t_1 = +-1. The phase rule fixes that constant to
  2 pi (n_1 r_1 - c n_0 r_0) for whole turns n_k of the circles (a line has none); the construction's
  pose tells which turns (the fewest, where radii nearly commensurable leave several within the
  tolerance), and the reference takes that constant exactly, to its 80 digits. A pose
  more than ``PHASE_TOLERANCE`` (relative) off every such constant is a construction that broke the
  phase rule, raised as such.

Angles are measured from the start pose's direction (atan of a small ratio, analytic in the
complex step), so that no branch cut is met.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from msgspec import Struct

from kinepoly.geom.tolerances import PHASE_TOLERANCE
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import CamSpec, GearSpec, PitchCircle, PitchLine

__all__ = ["PHASE_TOLERANCE", "GearRow", "cam_row", "gear_rows", "replaced_links", "square_root"]

_TURNS = 1000
"""Whole turns of the first circle searched for the phase rule's constant."""

Pair = tuple[Any, Any]
World = Callable[[list[Any], str, tuple[float, float]], Pair]
Angle = Callable[[list[Any], str], Any]


def replaced_links(mechanism: Mechanism) -> frozenset[str]:
    """The equivalent links the scene added for its cams (the reference leaves them out)."""
    return frozenset(mechanism.scene.equivalent_links)


def _near_real(mp: Any, z: Any, f: Callable[[Any], Any], df: Callable[[Any], Any]) -> Any:
    """f(z) for z real or a complex step a + i b (b of the step's size, 1e-40): f(a) + i b f'(a), exact to
    the working precision (b^2 is below it). mpmath's own complex atan loses the digits of b."""
    if isinstance(z, mp.mpc):
        return mp.mpc(f(z.real), z.imag * df(z.real))
    return f(z)


def _atan(mp: Any, z: Any) -> Any:
    return _near_real(mp, z, mp.atan, lambda a: 1 / (1 + a * a))


def square_root(mp: Any, z: Any) -> Any:
    """sqrt(z) for z real or with a complex step (see ``_near_real``)."""
    return _near_real(mp, z, mp.sqrt, lambda a: 1 / (2 * mp.sqrt(a)))



def _dot(a: Pair, b: Pair) -> Any:
    return a[0] * b[0] + a[1] * b[1]


def _minus(a: Pair, b: Pair) -> Pair:
    return a[0] - b[0], a[1] - b[1]


def _left(a: Pair) -> Pair:
    """J a: a turned a quarter turn counter-clockwise."""
    return -a[1], a[0]


def cam_row(mp: Any, mechanism: Mechanism, cam: CamSpec, q: list[Any], world: World, angle: Angle) -> Any:
    """The contact of ``cam``'s circle with its follower: zero when they touch (a spline cam:
    ``bench.spline_pairs``)."""
    k = world(q, cam.cam, mechanism.local(cam.cam, cam.center_point))
    if cam.kind == "flat":
        assert cam.flat is not None
        through, face = cam.flat
        t = world(q, cam.follower, through)
        turn = angle(q, cam.follower) + mp.mpf(face)
        return _dot(_minus(k, t), _left((mp.cos(turn), mp.sin(turn)))) - mp.mpf(cam.radius)
    assert cam.point is not None
    w = world(q, cam.follower, mechanism.local(cam.follower, cam.point))
    gap = _minus(w, k)
    reach = mp.mpf(cam.radius) + (-1 if cam.inside else 1) * mp.mpf(cam.roller_radius)
    return square_root(mp, _dot(gap, gap)) - reach


class _Side(Struct, frozen=True):
    """One gear of a pair in the reference: its link, its pitch circle or line, and the phase its rolled arc
    sigma is measured from (an angle for a circle, a distance along a rack's line)."""

    link: str
    curve: PitchCircle | PitchLine
    phase: float


class GearRow(Struct, frozen=True):
    """One gear pair's rolling row: sigma_1 - c sigma_0 - constant, with the start pose's directions."""

    gear: GearSpec
    sides: tuple[_Side, _Side]
    sign: int
    """c = t_0 . t_1."""
    rack_side: int
    """+1 or -1: which side of a rack's line the pinion's centre is on (+1 for two circles)."""
    aims: tuple[float, float]
    """Each circle's direction to the pitch point at the start (rad), where its angle is measured from."""
    constant: Any

    def value(self, mp: Any, mechanism: Mechanism, q: list[Any], world: World, angle: Angle) -> Any:
        return _unshifted(self, mp, mechanism, q, world, angle) - self.constant


def _circle_centre(mechanism: Mechanism, side: _Side, q: list[Any], world: World) -> Pair:
    assert isinstance(side.curve, PitchCircle)
    return world(q, side.link, mechanism.local(side.link, side.curve.center))


def _line(mp: Any, side: _Side, q: list[Any], world: World, angle: Angle) -> tuple[Pair, Pair]:
    assert isinstance(side.curve, PitchLine)
    turn = angle(q, side.link) + mp.mpf(side.curve.angle_rad)
    return world(q, side.link, side.curve.through), (mp.cos(turn), mp.sin(turn))


def _pitch_point(mp: Any, row: GearRow, mechanism: Mechanism, q: list[Any], world: World,
                 angle: Angle) -> Pair:
    one, two = row.sides
    if isinstance(one.curve, PitchCircle) and isinstance(two.curve, PitchCircle):
        o = (_circle_centre(mechanism, one, q, world), _circle_centre(mechanism, two, q, world))
        radii = (mp.mpf(one.curve.radius), mp.mpf(two.curve.radius))
        base = 0 if not row.gear.internal or radii[0] > radii[1] else 1
        d = _minus(o[1 - base], o[base])
        size = square_root(mp, _dot(d, d))
        return o[base][0] + radii[base] * d[0] / size, o[base][1] + radii[base] * d[1] / size
    circle, line = (one, two) if isinstance(one.curve, PitchCircle) else (two, one)
    assert isinstance(circle.curve, PitchCircle)
    o = _circle_centre(mechanism, circle, q, world)
    _, d = _line(mp, line, q, world, angle)
    nu = _left(d)
    reach = row.rack_side * mp.mpf(circle.curve.radius)
    return o[0] + reach * nu[0], o[1] + reach * nu[1]


def _direction(mp: Any, v: Pair, aim: float) -> Any:
    """The angle of ``v``, near ``aim`` (within a quarter turn), without a branch cut."""
    c, s = mp.cos(aim), mp.sin(aim)
    return mp.mpf(aim) + _atan(mp, (-s * v[0] + c * v[1]) / (c * v[0] + s * v[1]))


def _sigma(mp: Any, row: GearRow, k: int, p: Pair, mechanism: Mechanism, q: list[Any], world: World,
           angle: Angle) -> Any:
    side = row.sides[k]
    if isinstance(side.curve, PitchCircle):
        o = _circle_centre(mechanism, side, q, world)
        turned = _direction(mp, _minus(p, o), row.aims[k]) - angle(q, side.link) - mp.mpf(side.phase)
        return mp.mpf(side.curve.radius) * turned
    t, d = _line(mp, side, q, world, angle)
    return _dot(_minus(p, t), d) - mp.mpf(side.phase)


def _unshifted(row: GearRow, mp: Any, mechanism: Mechanism, q: list[Any], world: World, angle: Angle) -> Any:
    p = _pitch_point(mp, row, mechanism, q, world, angle)
    sigma = [_sigma(mp, row, k, p, mechanism, q, world, angle) for k in (0, 1)]
    return sigma[1] - row.sign * sigma[0]


def _tangent(mp: Any, side: _Side, p: Pair, mechanism: Mechanism, q: list[Any], world: World,
             angle: Angle) -> tuple[float, float]:
    if isinstance(side.curve, PitchCircle):
        o = _circle_centre(mechanism, side, q, world)
        return float(o[1] - p[1]), float(p[0] - o[0])
    _, d = _line(mp, side, q, world, angle)
    return float(d[0]), float(d[1])


def _phase_constant(mp: Any, gear: GearSpec, sides: tuple[_Side, _Side], sign: int, value: Any) -> Any:
    """The constant 2 pi (n_1 r_1 - c n_0 r_0) nearest ``value`` (a line side has no turns)."""
    radii = [s.curve.radius if isinstance(s.curve, PitchCircle) else 0.0 for s in sides]
    tau = 2.0 * math.pi
    if radii[0] and radii[1]:
        turns = [(n0, round((float(value) + sign * tau * radii[0] * n0) / (tau * radii[1])))
                 for n0 in range(-_TURNS, _TURNS + 1)]
    elif radii[0]:
        turns = [(round(-float(value) / (sign * tau * radii[0])), 0)]
    else:
        turns = [(0, round(float(value) / (tau * radii[1])))]
    tolerance = PHASE_TOLERANCE * max(radii + [1.0])
    misses = [(abs(float(value) - tau * (n1 * radii[1] - sign * n0 * radii[0])), n0, n1) for n0, n1 in turns]
    near = [(abs(n0) + abs(n1), n0, n1) for miss, n0, n1 in misses if miss <= tolerance]
    if not near:
        raise RuntimeError(f"gears.{gear.name}: the construction's gear angles are {min(misses)[0]:.3g} of rolled "
                           "arc from every angle the phase rule allows; the reference cannot take its constant")
    _, n0, n1 = min(near)  # radii nearly commensurable give more: the construction's turns are the fewest
    return 2 * mp.pi * (n1 * mp.mpf(radii[1]) - sign * n0 * mp.mpf(radii[0]))


def gear_rows(mp: Any, mechanism: Mechanism, start: list[Any], world: World, angle: Angle) -> list[GearRow]:
    """One rolling row per ``[[gears]]`` pair, its directions and constant taken at the ``start`` unknowns."""
    out = []
    for gear in mechanism.scene.gears:
        sides = (_Side(gear.links[0], gear.pitch[0], gear.phase[0]), _Side(gear.links[1], gear.pitch[1], gear.phase[1]))
        draft = GearRow(gear, sides, 1, 1, (0.0, 0.0), mp.mpf(0))
        rack_side = 1
        if not all(isinstance(s.curve, PitchCircle) for s in sides):
            circle, line = (sides[0], sides[1]) if isinstance(sides[0].curve, PitchCircle) else (sides[1], sides[0])
            o = _circle_centre(mechanism, circle, start, world)
            t, d = _line(mp, line, start, world, angle)
            rack_side = 1 if float(_dot(_minus(t, o), _left(d))) >= 0.0 else -1
        draft = GearRow(gear, sides, 1, rack_side, (0.0, 0.0), mp.mpf(0))
        p = _pitch_point(mp, draft, mechanism, start, world, angle)
        tangents = [_tangent(mp, s, p, mechanism, start, world, angle) for s in sides]
        sign = 1 if tangents[0][0] * tangents[1][0] + tangents[0][1] * tangents[1][1] > 0.0 else -1
        aims = tuple(math.atan2(-t[0], t[1]) if isinstance(s.curve, PitchCircle) else 0.0
                     for s, t in zip(sides, tangents, strict=True))
        draft = GearRow(gear, sides, sign, rack_side, (aims[0], aims[1]), mp.mpf(0))
        value = _unshifted(draft, mp, mechanism, start, world, angle)
        out.append(GearRow(gear, sides, sign, rack_side, draft.aims,
                           _phase_constant(mp, gear, sides, sign, value)))
    return out
