"""A ``[given]`` scene: one free body whose points' velocities (and accelerations) are given.

The body is solved in its own frame (pose (0, 0, 0)) from the motion of two or more of its
points, after checking that the given motion is that of a rigid body; the problems name the
given point, its line and what a rigid body would need.
"""

from __future__ import annotations

import numpy as np
from msgspec import Struct

from kinepoly.check.coordinates import Vec, as_array, mechanism_size
from kinepoly.check.newton import SINGULAR_CONDITION, condition_number
from kinepoly.errors import SceneError
from kinepoly.geom.tolerances import COINCIDENT_REL, RIGID_REL_TOL
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import GivenInput, GivenPoint

__all__ = ["RIGID_REL_TOL", "GivenMotion", "solve_given"]


class GivenMotion(Struct, frozen=True):
    """The motion of a [given] scene's one link, whose frame is the ground's (pose (0, 0, 0)).

    ``velocity`` and ``acceleration`` are those of the frame origin; ``alpha`` and
    ``acceleration`` are None when accelerations were not asked. ``condition_number`` is the
    2-norm condition of the dimensionless least-squares matrix of the velocities.
    """

    link: str
    omega: float
    velocity: Vec
    alpha: float | None
    acceleration: Vec | None
    condition_number: float


def _at(source: str, given: GivenPoint) -> str:
    return f"{source}:{given.line}: " if given.line else f"{source}: "


def solve_given(mechanism: Mechanism, *, with_acceleration: bool) -> GivenMotion:
    """One rigid body in its own frame (pose (0, 0, 0)); v_P = v_o + omega J P, a_P = a_o + alpha J P - omega^2 P.

    Rigidity is checked pair by pair against the first given point A: (v_P - v_A) . u_AP = 0 and
    (a_P - a_A) . u_AP = -omega^2 |AP|. The unknowns (v_o, omega) and (a_o, alpha) are then
    found by least squares over all given points (exact for two points).
    """
    scene = mechanism.scene
    inp = scene.input
    if not isinstance(inp, GivenInput) or len(scene.links) != 1:
        raise SceneError(f"{scene.source}: given: expected one link and a [given] input")
    link = scene.links[0].name
    pts = inp.points
    if len(pts) < 2:
        raise SceneError(f"{scene.source}: given: {len(pts)} given point(s); expected two points of link {link}")
    local = _given_locals(mechanism, link, pts)
    size = mechanism_size(mechanism)
    _check_distinct(scene.source, pts, local, size)

    # rows of v_P = v_o + omega J P; the omega column made a length per L, as in check.newton.System
    matrix = np.array([row for p in local for row in ([1.0, 0.0, -p[1]], [0.0, 1.0, p[0]])])
    condition = condition_number(matrix * np.array([1.0, 1.0, 1.0 / size])[None, :])
    if condition > SINGULAR_CONDITION:
        raise SceneError(
            f"{_at(scene.source, pts[1])}given: the given points {', '.join(p.name for p in pts)} are too close "
            f"together (condition {condition:.3g}) to fix the body's rotation; give two points farther apart"
        )

    v = [as_array(p.velocity) for p in pts]
    _check_rigid_velocity(scene.source, scene.units.length, pts, local, v)
    sol_v = np.linalg.lstsq(matrix, np.concatenate(v), rcond=None)[0]
    omega = float(sol_v[2])

    alpha: float | None = None
    acceleration: Vec | None = None
    if with_acceleration:
        a = _given_accelerations(scene.source, pts)
        _check_rigid_acceleration(scene.source, scene.units.length, pts, local, a, omega)
        rhs = np.concatenate([a[k] + omega**2 * local[k] for k in range(len(pts))])
        sol_a = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
        alpha = float(sol_a[2])
        acceleration = (float(sol_a[0]), float(sol_a[1]))
    return GivenMotion(link, omega, (float(sol_v[0]), float(sol_v[1])), alpha, acceleration, condition)


def _given_locals(mechanism: Mechanism, link: str, pts: tuple[GivenPoint, ...]) -> list[np.ndarray]:
    out = []
    for p in pts:
        if not mechanism.has_point(link, p.name):
            raise SceneError(f"{_at(mechanism.scene.source, p)}given.{p.name}: link {link} has no point {p.name}")
        out.append(as_array(mechanism.local(link, p.name)))
    return out


def _check_distinct(source: str, pts: tuple[GivenPoint, ...], local: list[np.ndarray], size: float) -> None:
    for k in range(1, len(pts)):
        if float(np.hypot(*(local[k] - local[0]))) <= COINCIDENT_REL * size:
            raise SceneError(
                f"{_at(source, pts[k])}given.{pts[k].name}: {pts[0].name} and {pts[k].name} are the same point; "
                "the motion of a body needs two distinct points"
            )


def _given_accelerations(source: str, pts: tuple[GivenPoint, ...]) -> list[np.ndarray]:
    out = []
    for p in pts:
        if p.acceleration is None:
            raise SceneError(
                f"{_at(source, p)}given.{p.name}.acceleration: missing; accelerations are asked, so every "
                "given point needs an acceleration"
            )
        out.append(as_array(p.acceleration))
    return out


def _check_rigid_velocity(
    source: str, unit: str, pts: tuple[GivenPoint, ...], local: list[np.ndarray], v: list[np.ndarray]
) -> None:
    """A rigid body: (v_P - v_A) . u_AP = 0, to RIGID_REL_TOL of the speeds."""
    a = pts[0]
    for k in range(1, len(pts)):
        u = (local[k] - local[0]) / float(np.hypot(*(local[k] - local[0])))
        along = float((v[k] - v[0]) @ u)
        scale = max(float(np.hypot(*v[0])), float(np.hypot(*v[k])))
        if abs(along) > RIGID_REL_TOL * scale:
            p = pts[k]
            raise SceneError(
                f"{_at(source, p)}given.{p.name}.velocity: the velocities of {a.name} and {p.name} differ by "
                f"{abs(along):.6g} {unit}/s along {a.name}{p.name}; a rigid body allows none (make the component "
                f"of given.{p.name}.velocity along {a.name}{p.name} equal that of {a.name}: "
                f"{float(v[0] @ u):.6g} {unit}/s)"
            )


def _check_rigid_acceleration(
    source: str, unit: str, pts: tuple[GivenPoint, ...], local: list[np.ndarray], acc: list[np.ndarray], omega: float
) -> None:
    """A rigid body: (a_P - a_A) . u_AP = -omega^2 |AP|, to RIGID_REL_TOL of the accelerations."""
    a = pts[0]
    for k in range(1, len(pts)):
        length = float(np.hypot(*(local[k] - local[0])))
        u = (local[k] - local[0]) / length
        along = float((acc[k] - acc[0]) @ u)
        expected = -(omega**2) * length
        scale = max(float(np.hypot(*acc[0])), float(np.hypot(*acc[k])), abs(expected))
        if abs(along - expected) > RIGID_REL_TOL * scale:
            p = pts[k]
            raise SceneError(
                f"{_at(source, p)}given.{p.name}.acceleration: the accelerations of {a.name} and {p.name} differ by "
                f"{along:.6g} {unit}/s^2 along {a.name}{p.name}, but a rigid body turning at omega = {omega:.6g} rad/s "
                f"needs -omega^2 |{a.name}{p.name}| = {expected:.6g} {unit}/s^2: off by {abs(along - expected):.6g} "
                f"{unit}/s^2"
            )
