"""The reference's rows for a spline cam (a ``points`` profile), in mpmath, with the contact parameter an unknown.

The profile is rebuilt here from its definition, at the reference's precision, sharing no code with
``geom.spline``: the closed curve through the points P_0 .. P_(n-1) (counter-clockwise, in the cam's frame)
that is a cubic in the chord-length parameter u on each stretch P_k P_(k+1) (length h_k, indices modulo n),
with the point, the tangent and the second derivative continuous all round. Writing M_k for the second
derivative at P_k, the cubic on stretch k (0 <= t <= h_k) is

    S_k(t) = P_k + B_k t + M_k t^2 / 2 + (M_(k+1) - M_k) t^3 / (6 h_k),
    B_k = (P_(k+1) - P_k) / h_k - h_k (2 M_k + M_(k+1)) / 6,

which passes through P_k and P_(k+1) and has the second derivatives M_k and M_(k+1) at its ends; equal
tangents where stretches k - 1 and k meet give, for every k, the cyclic system

    h_(k-1) M_(k-1) + 2 (h_(k-1) + h_k) M_k + h_k M_(k+1) = 6 ((P_(k+1) - P_k) / h_k - (P_k - P_(k-1)) / h_(k-1)),

solved here densely (mpmath's LU) for the x and y coordinates.

A spline cam adds its contact parameter u to the reference's unknowns and two rows:

* a knife edge or a roller (radius r) turning on W: the follower's W is the cam's point
  X(u) = S(u) + rho n(u), n the unit left normal (inward), rho = -r outside the profile, +r inside a
  groove, 0 for a knife (two rows: the world x and y of X(u) - W);
* a flat face (through T along d, in the follower's frame; the cam on its left): the cam's point S(u) is
  on the face, (S - T) . (J d) = 0, and the profile's tangent runs along it, t(u) . (J d) = 0.

A follower profile of points (a second closed spline S2(v), in the follower's frame) adds both parameters
u and v and three rows: the world x and y of S(u) - S2(v), and the cross product of both world tangents
(they are parallel at the contact).

u may carry a complex step (its real part picks the stretch; the cubic is analytic in t), so the
reference's complex-step Jacobian differentiates these rows exactly as it does the others.
"""

from __future__ import annotations

import bisect
from collections.abc import Callable
from functools import lru_cache
from typing import Any

from msgspec import Struct

from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import CamSpec, Vector

__all__ = ["MpSpline", "SplineContact", "mp_spline", "spline_contacts"]

Pair = tuple[Any, Any]
World = Callable[[list[Any], str, tuple[float, float]], Pair]
Angle = Callable[[list[Any], str], Any]

_START_SAMPLES = 16
"""Samples of each stretch among which the contact parameter's start is the best (Newton settles it)."""


class MpSpline(Struct, frozen=True):
    """The closed spline in mpmath: ``knots[k]`` the parameter of P_k (``knots[n]`` the period) and each
    stretch's coefficients ((a_x, a_y), (b_x, b_y), (c_x, c_y), (d_x, d_y)) of a + b t + c t^2 + d t^3."""

    knots: tuple[Any, ...]
    stretches: tuple[tuple[Pair, Pair, Pair, Pair], ...]

    @property
    def period(self) -> Any:
        return self.knots[-1]

    def point_and_tangent(self, mp: Any, u: Any) -> tuple[Pair, Pair]:
        """S(u) and S'(u); u real or with a complex step."""
        real = u.real if isinstance(u, mp.mpc) else u
        u = u - self.period * mp.floor(real / self.period)
        real = u.real if isinstance(u, mp.mpc) else u
        k = min(max(bisect.bisect_right(self.knots, real) - 1, 0), len(self.stretches) - 1)
        t = u - self.knots[k]
        a, b, c, d = self.stretches[k]
        point = tuple(a[i] + t * (b[i] + t * (c[i] + t * d[i])) for i in (0, 1))
        tangent = tuple(b[i] + t * (2 * c[i] + 3 * t * d[i]) for i in (0, 1))
        return (point[0], point[1]), (tangent[0], tangent[1])


@lru_cache(maxsize=16)
def _cached(points: tuple[Vector, ...], prec: int) -> MpSpline:
    import mpmath  # type: ignore[import-untyped]

    mp = mpmath.mp
    with mp.workprec(prec):
        p = [(mp.mpf(x), mp.mpf(y)) for x, y in points]
        n = len(p)
        h = [mp.sqrt((p[(k + 1) % n][0] - p[k][0]) ** 2 + (p[(k + 1) % n][1] - p[k][1]) ** 2) for k in range(n)]
        system = mp.matrix(n, n)
        for k in range(n):
            system[k, (k - 1) % n] += h[k - 1]
            system[k, k] += 2 * (h[k - 1] + h[k])
            system[k, (k + 1) % n] += h[k]
        second = []
        for i in (0, 1):
            rhs = mp.matrix([6 * ((p[(k + 1) % n][i] - p[k][i]) / h[k] - (p[k][i] - p[k - 1][i]) / h[k - 1])
                             for k in range(n)])
            second.append(mp.lu_solve(system, rhs))
        stretches = []
        for k in range(n):
            m0 = (second[0][k], second[1][k])
            m1 = (second[0][(k + 1) % n], second[1][(k + 1) % n])
            b = tuple((p[(k + 1) % n][i] - p[k][i]) / h[k] - h[k] * (2 * m0[i] + m1[i]) / 6 for i in (0, 1))
            d = tuple((m1[i] - m0[i]) / (6 * h[k]) for i in (0, 1))
            stretches.append((p[k], (b[0], b[1]), (m0[0] / 2, m0[1] / 2), (d[0], d[1])))
        knots = [mp.mpf(0)]
        for length in h:
            knots.append(knots[-1] + length)
    return MpSpline(tuple(knots), tuple(stretches))


def mp_spline(mp: Any, points: tuple[Vector, ...]) -> MpSpline:
    """The closed spline through ``points`` at mpmath's current precision (made once per profile and precision)."""
    return _cached(points, mp.prec)


def _left(a: Pair) -> Pair:
    return -a[1], a[0]


def _dot(a: Pair, b: Pair) -> Any:
    return a[0] * b[0] + a[1] * b[1]


def _rotate(mp: Any, turn: Any, v: Pair) -> Pair:
    c, s = mp.cos(turn), mp.sin(turn)
    return c * v[0] - s * v[1], s * v[0] + c * v[1]


class SplineContact(Struct, frozen=True):
    """One spline cam's contact: its spline, its two rows, and the start of its parameter."""

    cam: CamSpec
    spline: MpSpline
    norm: Callable[[Any], Any]
    """|v| of a tangent's squared length, analytic under the complex step (the reference's square root)."""
    follower: MpSpline | None = None
    """A follower profile of points: its spline, in the follower's frame."""

    @property
    def unknowns(self) -> int:
        """The contact's parameters among the reference's unknowns: u, or u and v for two splines."""
        return 1 if self.follower is None else 2

    def _rho(self) -> int | float:
        if self.cam.kind != "roller":
            return 0
        return self.cam.roller_radius if self.cam.inside else -self.cam.roller_radius

    def _cam_point(self, mp: Any, q: list[Any], u: Any, world: World, angle: Angle) -> tuple[Pair, Pair]:
        """The world point of the cam at S(u) + rho n(u), and the profile's world unit tangent there."""
        point, tangent = self.spline.point_and_tangent(mp, u)
        size = self.norm(_dot(tangent, tangent))
        unit = (tangent[0] / size, tangent[1] / size)
        rho = mp.mpf(self._rho())
        normal = _left(unit)
        local = (point[0] + rho * normal[0], point[1] + rho * normal[1])
        turn = angle(q, self.cam.cam)
        origin = world(q, self.cam.cam, (0.0, 0.0))
        arm = _rotate(mp, turn, local)
        return (origin[0] + arm[0], origin[1] + arm[1]), _rotate(mp, turn, unit)

    def _pair_rows(self, mp: Any, q: list[Any], u: Any, v: Any, world: World, angle: Angle) -> list[Any]:
        assert self.follower is not None
        cam = self.cam
        rows = []
        ends = []
        for link, spline, t in ((cam.cam, self.spline, u), (cam.follower, self.follower, v)):
            point, tangent = spline.point_and_tangent(mp, t)
            turn = angle(q, link)
            origin = world(q, link, (0.0, 0.0))
            arm = _rotate(mp, turn, point)
            ends.append(((origin[0] + arm[0], origin[1] + arm[1]), _rotate(mp, turn, tangent)))
        (p1, t1), (p2, t2) = ends
        rows = [p1[0] - p2[0], p1[1] - p2[1], (t1[0] * t2[1] - t1[1] * t2[0]) / self.norm(_dot(t1, t1))]
        return rows

    def rows(self, mp: Any, mechanism: Mechanism, q: list[Any], params: list[Any], world: World,
             angle: Angle) -> list[Any]:
        if self.follower is not None:
            return self._pair_rows(mp, q, params[0], params[1], world, angle)
        u = params[0]
        at, tangent = self._cam_point(mp, q, u, world, angle)
        cam = self.cam
        if cam.kind == "flat":
            assert cam.flat is not None
            through, face = cam.flat
            t = world(q, cam.follower, through)
            normal = _left(_rotate(mp, angle(q, cam.follower) + mp.mpf(face), (mp.mpf(1), mp.mpf(0))))
            return [_dot((at[0] - t[0], at[1] - t[1]), normal), _dot(tangent, normal)]
        assert cam.point is not None
        w = world(q, cam.follower, mechanism.local(cam.follower, cam.point))
        return [at[0] - w[0], at[1] - w[1]]

    def starts(self, mp: Any, mechanism: Mechanism, q: list[Any], world: World, angle: Angle) -> list[Any]:
        """The start of the contact's parameter(s) at the pose ``q`` (Newton refines them)."""
        if self.follower is None:
            return [self.start(mp, mechanism, q, world, angle)]
        return self._pair_start(mp, mechanism, q, world, angle)

    def _pair_start(self, mp: Any, mechanism: Mechanism, q: list[Any], world: World, angle: Angle) -> list[Any]:
        """The pair of samples (``_START_SAMPLES`` per stretch of each spline) whose points are nearest."""
        assert self.follower is not None
        ends = []
        for link, spline in ((self.cam.cam, self.spline), (self.cam.follower, self.follower)):
            turn, origin = angle(q, link), world(q, link, (0.0, 0.0))
            samples = [spline.knots[k] + (spline.knots[k + 1] - spline.knots[k]) * j / _START_SAMPLES
                       for k in range(len(spline.stretches)) for j in range(_START_SAMPLES)]
            placed = []
            for t in samples:
                arm = _rotate(mp, turn, spline.point_and_tangent(mp, t)[0])
                placed.append((t, complex(float(origin[0] + arm[0]), float(origin[1] + arm[1]))))
            ends.append(placed)
        best = min(((a, b) for a in ends[0] for b in ends[1]), key=lambda pair: abs(pair[0][1] - pair[1][1]))
        return [best[0][0], best[1][0]]

    def start(self, mp: Any, mechanism: Mechanism, q: list[Any], world: World, angle: Angle) -> Any:
        """The sample of the profile that best meets the rows at the pose ``q`` (Newton refines it): the best
        point first, then ``_START_SAMPLES`` along each of the two stretches that meet there."""
        knots, count = self.spline.knots, len(self.spline.stretches)

        def miss(u: Any) -> Any:
            return sum(abs(r) for r in self.rows(mp, mechanism, q, [u], world, angle))

        best = min(range(count), key=lambda k: miss(knots[k]))
        samples = [knots[k] + (knots[k + 1] - knots[k]) * j / _START_SAMPLES
                   for k in ((best - 1) % count, best) for j in range(_START_SAMPLES)]
        return min(samples, key=miss)


def spline_contacts(mp: Any, mechanism: Mechanism, norm: Callable[[Any], Any]) -> list[SplineContact]:
    """One contact per spline cam of the scene, in the order of ``[[cams]]``."""
    return [SplineContact(cam, mp_spline(mp, cam.profile_points), norm,
                          mp_spline(mp, cam.follower_points) if cam.follower_points else None)
            for cam in mechanism.scene.cams if cam.is_spline]
