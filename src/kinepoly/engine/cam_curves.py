"""Two splines in contact: a ``points`` cam touching a follower whose own profile is a closed spline of points.

The cam's profile P1(u) (in the cam's frame) and the follower's Pf(v) (in the follower's frame) are closed
counter-clockwise cubic splines (``geom.spline``). The follower is held by one joint to a known carrier, so
its pose has one unknown q: its angle about the pivot (a rocker) or its slide s (a translating follower).
At every row the contact is a root (u, v, q) of three equations, in the frame:

    P1(u) - P2(v; q) = 0                   (2 equations: the two points coincide)
    T1(u) x T2(v; q) = 0                   (1 equation: the tangents are parallel)

with T the tangents (the curves' derivatives turned into the frame); the tangents must run opposite (both
curves counter-clockwise, touching from outside: normals opposite). Newton's method on (u, v, q), in numpy
over all rows and many starting points at once (a grid of u and v on both curves, q from the tangents),
keeps every distinct root of every row (the grid at a few rows spread over the input, every other row
started from the roots of the nearest of them); the assembly policy then keeps one per row as for any spline cam.

Both centres of curvature at the contact, K1 = Q + n1 / kappa1 on the cam and K2 = Q + n2 / kappa2 on the
follower, are points of their links at that instant: the pair acts as the link K1 K2 of length
1/kappa1 + 1/kappa2 (``engine.cam_polygons``). Where kappa1 + kappa2 is not positive the curves conform
(the link has no length) or cut into each other, and where a curvature is zero its centre is at infinity:
such a contact is refused.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from msgspec import Struct

from kinepoly.engine.cam_contact import Candidates, Ints, cam_spline
from kinepoly.engine.groups import CamGroup
from kinepoly.geom.arrays import Bools, Points, Reals, turn
from kinepoly.geom.spline import PeriodicSpline, periodic_spline
from kinepoly.geom.tolerances import (
    CONTACT_DISTINCT_REL,
    CURVES_CONFORMING,
    CURVES_STRAIGHT,
    NEWTON_CLOSED_REL,
    TINY_POSITIVE,
)
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import CamSpec, SliderSpec, Vector

__all__ = ["CurveCandidates", "CurveContactRows", "curve_candidates", "curve_contact_rows", "degenerate_rows",
           "follower_centre_label", "follower_spline"]


def follower_centre_label(cam: CamSpec) -> str:
    """The mark of the follower profile's centre of curvature at the contact: ``K223`` (K2, then the pair)."""
    return f"K2{cam.name}"


@lru_cache(maxsize=64)
def _spline(points: tuple[Vector, ...]) -> PeriodicSpline:
    return periodic_spline(points)


def follower_spline(cam: CamSpec) -> PeriodicSpline:
    """The follower profile's spline, in the follower's frame."""
    return _spline(cam.follower_points)


class _Carried(Struct, frozen=True):
    """The follower's pose as a function of its one unknown q, per row: turned by q about the pivot (a rocker:
    rotation e^{iq}) or slid by q along the guide (a translating follower: its rotation fixed)."""

    revolute: bool
    pivot: Points       # a rocker: the pivot in the frame; a slide: the origin at s = 0
    pivot_local: complex
    rotation: Points    # a slide: the follower's fixed rotation
    direction: Points   # a slide: the unit direction of s

    def pose(self, row: Ints, q: Reals) -> tuple[Points, Points, Points, Points]:
        """origin, rotation and their derivatives by q, for lanes of rows ``row``."""
        if self.revolute:
            rotation = np.exp(1j * q)
            return (np.asarray(self.pivot[row] - rotation * self.pivot_local), np.asarray(rotation),
                    np.asarray(-1j * rotation * self.pivot_local), np.asarray(1j * rotation))
        return (np.asarray(self.pivot[row] + q * self.direction[row]), np.asarray(self.rotation[row]),
                np.asarray(self.direction[row]), np.zeros(q.shape, np.complex128))


def _carried(mechanism: Mechanism, group: CamGroup, carrier_pose: ArrayPose) -> _Carried:
    joint = group.joint
    n = len(carrier_pose.origin)
    if isinstance(joint, Revolute):
        pivot = carrier_pose.world(mechanism.local(group.carrier, joint.point))
        zero = np.zeros(n, np.complex128)
        return _Carried(True, np.asarray(pivot), complex(*mechanism.local(group.link, joint.point)), zero, zero)
    assert isinstance(joint, SliderSpec)
    rotation = np.asarray(carrier_pose.rotation * turn(joint.angle_rad))
    start = carrier_pose.world(joint.through) - rotation * complex(*mechanism.local(group.link, joint.point))
    return _Carried(False, np.asarray(start), 0j, rotation, rotation)


def _cross(a: Points, b: Points) -> Reals:
    return np.asarray((np.conj(a) * b).imag)


class CurveCandidates(Struct, frozen=True):
    """The contacts of every row (``Candidates``) with the follower profile's parameter v of each."""

    candidates: Candidates
    v: Reals

    def follower_parameter(self, choice: Ints) -> Reals:
        return np.asarray(self.v[np.arange(len(choice)), np.maximum(choice, 0)])


def _residual(cam_pose: ArrayPose, carried: _Carried, s1: PeriodicSpline, s2: PeriodicSpline, row: Ints,
              u: Reals, v: Reals, q: Reals) -> tuple[Points, Reals, np.ndarray]:
    """(E, G) and the 3x3 Jacobian by (u, v, q), one per lane (lanes of rows ``row``)."""
    rc = cam_pose.rotation[row]
    p1, d1, e1 = s1.derivatives(u)
    p2, d2, e2 = s2.derivatives(v)
    origin, rotation, d_origin, d_rotation = carried.pose(row, q)
    t1, t2 = rc * d1, rotation * d2
    gap = cam_pose.origin[row] + rc * p1 - origin - rotation * p2
    parallel = _cross(t1, t2)
    dq = -(d_origin + d_rotation * p2)
    jac = np.empty((len(u), 3, 3))
    for col, de, dg in ((0, t1, _cross(rc * e1, t2)), (1, -t2, _cross(t1, rotation * e2)),
                        (2, dq, _cross(t1, d_rotation * d2))):
        jac[:, 0, col], jac[:, 1, col], jac[:, 2, col] = de.real, de.imag, dg
    return np.asarray(gap), parallel, jac


def _det3(m: np.ndarray) -> Reals:
    """The determinants of a stack of 3x3 matrices, written out."""
    return np.asarray(m[:, 0, 0] * (m[:, 1, 1] * m[:, 2, 2] - m[:, 1, 2] * m[:, 2, 1])
                      - m[:, 0, 1] * (m[:, 1, 0] * m[:, 2, 2] - m[:, 1, 2] * m[:, 2, 0])
                      + m[:, 0, 2] * (m[:, 1, 0] * m[:, 2, 1] - m[:, 1, 1] * m[:, 2, 0]))


def _solve3(jac: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, Bools]:
    """jac x = rhs for every lane by Cramer's rule, with the lanes where jac is singular."""
    det = _det3(jac)
    good = np.abs(det) > TINY_POSITIVE
    safe = np.where(good, det, 1.0)
    out = np.empty(rhs.shape)
    for col in range(3):
        swapped = jac.copy()
        swapped[:, :, col] = rhs
        out[:, col] = _det3(swapped) / safe
    return out, np.asarray(good)


_SEEDS_PER_CURVE = 12
_SEARCHED_ROWS = 48
_STEPS = 30
_WANDER_STEP = 10
_WANDER_REL = 1e-2
"""At that step, lanes whose contact gap is still above this times the profiles' size are dropped (a search
heuristic, not a tolerance)."""
_BIN_REL = 1e-6
"""Roots are sorted by their contact point rounded to this times the size, so that equal ones come together."""


def curve_candidates(mechanism: Mechanism, group: CamGroup, poses: dict[str, ArrayPose]) -> CurveCandidates:
    """Every contact of the two splines at every row, with the follower's pose each gives: a grid of starts
    on both curves at a few rows spread over the input, then every row from the roots of the nearest of them."""
    s1, s2 = cam_spline(group.cam), follower_spline(group.cam)
    cam_pose, carried = poses[group.known], _carried(mechanism, group, poses[group.carrier])
    n = len(cam_pose.origin)
    size = _size(s1, s2)
    searched = np.unique(np.linspace(0, n - 1, min(n, _SEARCHED_ROWS)).round().astype(np.intp))
    grid_u = s1.period * (np.arange(_SEEDS_PER_CURVE) + 0.5) / _SEEDS_PER_CURVE
    grid_v = s2.period * (np.arange(_SEEDS_PER_CURVE) + 0.5) / _SEEDS_PER_CURVE
    seeds = _SEEDS_PER_CURVE ** 2
    row = np.repeat(searched, seeds)
    u = np.tile(np.repeat(grid_u, _SEEDS_PER_CURVE), len(searched))
    v = np.tile(np.tile(grid_v, _SEEDS_PER_CURVE), len(searched))
    t1 = cam_pose.rotation[row] * s1.derivatives(u)[1]
    d2 = s2.derivatives(v)[1]
    if carried.revolute:  # turned so that the tangents run opposite
        q = np.angle(-t1 / d2)
    else:
        origin, rotation, _, _ = carried.pose(row, np.zeros(len(u)))
        p1 = cam_pose.origin[row] + cam_pose.rotation[row] * s1.point(u)
        q = ((p1 - origin - rotation * s2.point(v)) * np.conj(carried.direction[row])).real
    row, u, v, q = _newton(cam_pose, carried, s1, s2, row, u, v, q, size)
    u, v = np.mod(u, s1.period), np.mod(v, s2.period)
    _, once = np.unique(np.stack([row, np.round(u / s1.period * 1e6), np.round(v / s2.period * 1e6)]), axis=1,
                        return_index=True)  # each root once (many starts reach the same)
    row, u, v, q = row[once], u[once], v[once], q[once]
    if len(searched) < n:  # every row from the roots of its nearest searched row
        nearest = searched[np.abs(np.arange(n)[:, None] - searched[None, :]).argmin(axis=1)]
        lanes = [np.flatnonzero(row == at) for at in range(n)]
        source = np.concatenate([lanes[int(at)] for at in nearest]).astype(np.intp)
        target = np.concatenate([np.full(len(lanes[int(at)]), k, np.intp) for k, at in enumerate(nearest)])
        row, u, v, q = _newton(cam_pose, carried, s1, s2, target, u[source], v[source], q[source], size)
    return _distinct(cam_pose, s1, carried, n, row, u, v, q, size)


def _newton(cam_pose: ArrayPose, carried: _Carried, s1: PeriodicSpline, s2: PeriodicSpline, row: Ints, u: Reals,
            v: Reals, q: Reals, size: float) -> tuple[Ints, Reals, Reals, Reals]:
    """Newton's method on (u, v, q) from every lane's start; the lanes that reach a contact (the tangents
    opposite) kept."""
    limit = np.array([s1.period / 8.0, s2.period / 8.0, 0.5 if carried.revolute else size / 4.0])
    for step_number in range(_STEPS):
        gap, parallel, jac = _residual(cam_pose, carried, s1, s2, row, u, v, q)
        if step_number == _WANDER_STEP:  # lanes still far from any root are dropped
            near = (np.abs(gap) < _WANDER_REL * size) & np.isfinite(q)
            row, u, v, q = row[near], u[near], v[near], q[near]
            gap, parallel, jac = gap[near], parallel[near], jac[near]
        step, good = _solve3(jac, -np.stack([gap.real, gap.imag, parallel], axis=-1))
        step = np.where(good[:, None], np.clip(step, -limit, limit), 0.0)
        u, v, q = u + step[:, 0], v + step[:, 1], q + step[:, 2]
    gap, parallel, _ = _residual(cam_pose, carried, s1, s2, row, u, v, q)
    t1 = cam_pose.rotation[row] * s1.derivatives(u)[1]
    _, rotation, _, _ = carried.pose(row, q)
    t2 = rotation * s2.derivatives(v)[1]
    converged = ((np.abs(gap) <= NEWTON_CLOSED_REL * size)
                 & (np.abs(parallel) <= NEWTON_CLOSED_REL * np.abs(t1) * np.abs(t2))
                 & ((np.conj(t1) * t2).real < 0.0) & np.isfinite(q))
    return row[converged], u[converged], v[converged], q[converged]


def _size(s1: PeriodicSpline, s2: PeriodicSpline) -> float:
    return max(s1.period, s2.period)


def _distinct(cam_pose: ArrayPose, s1: PeriodicSpline, carried: _Carried, n: int, row: Ints, u: Reals, v: Reals,
              q: Reals, size: float) -> CurveCandidates:
    """Each row's distinct roots side by side (the same contact point and pose counted once), padded."""
    point = cam_pose.origin[row] + cam_pose.rotation[row] * s1.point(u)
    origin, rotation, _, _ = carried.pose(row, q)
    kept: list[list[int]] = [[] for _ in range(n)]
    order = np.lexsort((np.round(point.real / (_BIN_REL * size)), row))
    for lane in order:
        mine = kept[int(row[lane])]
        if all(abs(point[lane] - point[j]) > CONTACT_DISTINCT_REL * size
               or abs(rotation[lane] - rotation[j]) > CONTACT_DISTINCT_REL for j in mine):
            mine.append(int(lane))
    width = max(1, max((len(m) for m in kept), default=0))
    pick = np.zeros((n, width), np.intp)
    found = np.zeros((n, width), np.bool_)
    for at, mine in enumerate(kept):
        pick[at, : len(mine)] = mine
        found[at, : len(mine)] = True
    if len(row) == 0:
        empty, place = np.zeros((n, 1)), np.zeros((n, 1), np.complex128)
        return CurveCandidates(Candidates(empty, found, place, place + 1.0, place), empty)
    candidates = Candidates(np.asarray(np.mod(u[pick], s1.period)), found, np.asarray(origin[pick]),
                            np.asarray(rotation[pick]), np.asarray(point[pick]))
    return CurveCandidates(candidates, np.asarray(v[pick]))


class CurveContactRows(Struct, frozen=True):
    """The follower profile's side of the chosen contact at every row, in the frame: its centre of curvature
    K2 and curvature kappa2 (positive where convex), with the cam's kappa1."""

    centre: Points
    curvature: Reals
    cam_curvature: Reals


def curve_contact_rows(cam: CamSpec, cam_pose: ArrayPose, follower_pose: ArrayPose, u: Reals,
                       v: Reals) -> CurveContactRows:
    """Both curvatures at the contact and the follower's centre of curvature K2."""
    own = follower_spline(cam).frame(v)
    bent = np.where(own.curvature == 0.0, 1.0, own.curvature)
    centre = follower_pose.origin + follower_pose.rotation * (own.point + own.normal / bent)
    return CurveContactRows(np.asarray(centre), own.curvature, cam_spline(cam).frame(u).curvature)


def degenerate_rows(cam: CamSpec, rows: CurveContactRows) -> tuple[Bools, str]:
    """Rows where the two curvatures leave no equivalent link (conforming, cutting in, or a centre at
    infinity), with the reason at the first of them."""
    scale = max(cam_spline(cam).period, follower_spline(cam).period)
    k1, k2 = rows.cam_curvature, rows.curvature
    straight = (np.abs(k1) * scale <= CURVES_STRAIGHT) | (np.abs(k2) * scale <= CURVES_STRAIGHT)
    conforming = (k1 + k2) * scale <= CURVES_CONFORMING
    bad = np.asarray(straight | conforming)
    if not bad.any():
        return bad, ""
    row = int(np.flatnonzero(bad)[0])
    a, b = float(k1[row]), float(k2[row])
    if straight[row]:
        why = (f"a profile is straight at the contact (curvatures {a:.6g} and {b:.6g}): its centre of curvature is at "
               "infinity, so no link joins the two centres; make both profiles curved there")
    else:
        how = "conform" if abs(a + b) * scale <= CURVES_CONFORMING else "cut into each other"
        why = (f"the two profiles {how} at the contact "
               f"(curvatures {a:.6g} and {b:.6g}, 1/rho1 + 1/rho2 = {a + b:.6g}, not positive): the link joining "
               "both centres of curvature has no length or turns inside out; make the follower's profile more "
               "convex than the cam's hollow there")
    return bad, why
