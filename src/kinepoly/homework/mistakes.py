"""The polygons' equations as a student writes them, with a construction mistake switched in.

The relative-motion equations the velocity and acceleration polygons draw are written for every
joint and solved as one linear system, so dyads and triads alike are covered. With each moving
link's frame origin O_k, angle theta_k and r the arm from O_k to a point (in frame axes),
J the quarter turn ccw:

* a point of link k: v = v_k + omega_k J r;  a = a_k + alpha_k J r + n omega_k^2 r
  (n = -1: the normal term points from the point toward the center, as it must; n = +1: away);
* a pin P of links i and j: v_P(i) = v_P(j), a_P(i) = a_P(j);
* a slider, block b on guide g, block point P, slide direction e (turning with g):
  omega_b = omega_g, alpha_b = alpha_g, v_P(b) = v_P(g) + s_dot e,
  a_P(b) = a_P(g) + s_ddot e + c 2 omega_g J (s_dot e)   (c = 1 right; 0 left out; -1 reversed);
* the driver: omega and alpha of the input link, or s_dot and s_ddot of the input slider; in a
  ``[given]`` scene the given points' motion (solved by least squares, exact for rigid data).

Unknowns: (v_k, omega_k) then (a_k, alpha_k) of every moving link and s_dot, s_ddot of every
slider. The poses are read from the reference :class:`~kinepoly.solution.Solution`; velocities
are solved here, so the right construction (n = -1, c = 1) reproduces the reference exactly:
the tests hold it to that. Nothing here reads kinepoly's construction or analytic modules.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinepoly.homework.answers import AnswerKey, Value
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import GivenInput, LinkInput, Scene, SliderInput, SliderSpec
from kinepoly.solution import Solution

__all__ = ["RIGHT", "Construction", "student_solution"]

Vec = tuple[float, float]

_SINGULAR_CONDITION = 1e10


@dataclass(frozen=True)
class Construction:
    """How the known acceleration terms are laid: ``normal_sign`` n and ``coriolis_factor`` c above."""

    normal_sign: float = -1.0
    coriolis_factor: float = 1.0


RIGHT = Construction()


@dataclass(frozen=True)
class _Pose:
    theta: float
    origin: np.ndarray

    def world(self, local: Vec) -> np.ndarray:
        c, s = math.cos(self.theta), math.sin(self.theta)
        return np.asarray(self.origin + np.array([c * local[0] - s * local[1], s * local[0] + c * local[1]]))


def _quarter(v: np.ndarray) -> np.ndarray:
    """J v: v turned 90 degrees ccw."""
    return np.array([-v[1], v[0]])


def _poses(scene: Scene, pose: Pose) -> dict[str, _Pose] | None:
    """Each link's pose in the reference solution; None when a link was not solved."""
    poses: dict[str, _Pose] = {}
    for link in scene.links:
        if link.name == scene.ground:
            poses[link.name] = _Pose(0.0, np.zeros(2))
        elif link.name in pose.links:
            place = pose.links[link.name]
            poses[link.name] = _Pose(place.theta, np.array([place.x, place.y]))
        else:
            return None
    return poses


def _owner(scene: Scene, point: str) -> str:
    return next(link.name for link in scene.links if point in link.point_names)


class _Equations:
    """The linear system: columns (x, y, rate) per moving link, then one per slider."""

    def __init__(self, scene: Scene, poses: dict[str, _Pose]) -> None:
        self.scene = scene
        self.poses = poses
        self.moving = [link.name for link in scene.links if link.name != scene.ground]
        self.column = {name: 3 * k for k, name in enumerate(self.moving)}
        self.slider_column = {s.name: 3 * len(self.moving) + k for k, s in enumerate(scene.sliders)}
        self.size = 3 * len(self.moving) + len(scene.sliders)

    def position(self, point: str) -> np.ndarray:
        owner = _owner(self.scene, point)
        return self.poses[owner].world(self.scene.link(owner).point(point).local)

    def arm(self, link: str, point: str) -> np.ndarray:
        return np.asarray(self.position(point) - self.poses[link].origin)

    def direction(self, slider: SliderSpec) -> np.ndarray:
        angle = self.poses[slider.guide].theta + slider.angle_rad
        return np.array([math.cos(angle), math.sin(angle)])

    def _point_rows(self, link: str, r: np.ndarray, sign: float) -> np.ndarray:
        rows = np.zeros((2, self.size))
        if link in self.column:
            k = self.column[link]
            rows[:, k : k + 2] = sign * np.eye(2)
            rows[:, k + 2] = sign * _quarter(r)
        return rows

    def _rate_row(self, pairs: list[tuple[str, float]]) -> np.ndarray:
        row = np.zeros((1, self.size))
        for link, sign in pairs:
            if link in self.column:
                row[0, self.column[link] + 2] += sign
        return row

    def assemble(self, rates: _Rates | None, how: Construction) -> tuple[np.ndarray, np.ndarray]:
        """The matrix and the right-hand side: of the velocity equations (``rates`` None) or the acceleration ones."""
        blocks: list[np.ndarray] = []
        rhs: list[np.ndarray] = []

        def spin(link: str, r: np.ndarray) -> np.ndarray:  # the normal term n omega^2 r, as laid
            w = rates.omega.get(link, 0.0) if rates else 0.0
            return how.normal_sign * w * w * r

        for point, (i, j) in _pins(self.scene).items():
            r_i, r_j = self.arm(i, point), self.arm(j, point)
            blocks.append(self._point_rows(i, r_i, 1.0) + self._point_rows(j, r_j, -1.0))
            rhs.append(spin(j, r_j) - spin(i, r_i))
        for slider in self.scene.sliders:
            b, g = slider.block, slider.guide
            r_b, r_g, e = self.arm(b, slider.point), self.arm(g, slider.point), self.direction(slider)
            rows = self._point_rows(b, r_b, 1.0) + self._point_rows(g, r_g, -1.0)
            rows[:, self.slider_column[slider.name]] = -e
            blocks += [rows, self._rate_row([(b, 1.0), (g, -1.0)])]
            known = np.zeros(2)
            if rates:
                coriolis = 2.0 * rates.omega.get(g, 0.0) * rates.s_dot[slider.name] * _quarter(e)
                known = spin(g, r_g) - spin(b, r_b) + how.coriolis_factor * coriolis
            rhs += [known, np.zeros(1)]
        driver_rows, driver_rhs = self._driver(rates, how)
        return np.vstack([*blocks, driver_rows]), np.concatenate([*rhs, driver_rhs])

    def _driver(self, rates: _Rates | None, how: Construction) -> tuple[np.ndarray, np.ndarray]:
        inp = self.scene.input
        if isinstance(inp, LinkInput):
            return self._rate_row([(inp.link, 1.0)]), np.array([inp.alpha if rates else inp.omega])
        if isinstance(inp, SliderInput):
            row = np.zeros((1, self.size))
            row[0, self.slider_column[inp.slider]] = 1.0
            return row, np.array([inp.s_ddot if rates else inp.s_dot])
        assert isinstance(inp, GivenInput)
        link = self.moving[0]
        rows, rhs = [], []
        for given in inp.points:
            r = self.arm(link, given.name)
            rows.append(self._point_rows(link, r, 1.0))
            if rates:
                assert given.acceleration is not None
                w = rates.omega[link]
                rhs.append(np.asarray(given.acceleration, dtype=float) - how.normal_sign * w * w * r)
            else:
                rhs.append(np.asarray(given.velocity, dtype=float))
        return np.vstack(rows), np.concatenate(rhs)


@dataclass(frozen=True)
class _Rates:
    omega: dict[str, float]
    s_dot: dict[str, float]


def _pins(scene: Scene) -> dict[str, tuple[str, str]]:
    owners: dict[str, list[str]] = {}
    for link in scene.links:
        for name in link.point_names:
            owners.setdefault(name, []).append(link.name)
    return {point: (links[0], links[1]) for point, links in owners.items() if len(links) == 2}


def _solve(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray | None:
    if matrix.shape[0] < matrix.shape[1] or np.linalg.cond(matrix) > _SINGULAR_CONDITION:
        return None
    if matrix.shape[0] == matrix.shape[1]:
        return np.asarray(np.linalg.solve(matrix, rhs), dtype=float)
    return np.asarray(np.linalg.lstsq(matrix, rhs, rcond=None)[0], dtype=float)


def student_solution(solution: Solution, how: Construction = RIGHT) -> dict[AnswerKey, Value] | None:
    """The answers of a student who lays the terms as ``how`` says, at the poses of ``solution``.

    Gives links' omega and alpha, the velocity and acceleration of every point ``solution``'s [find]
    asks the velocity or acceleration of, and sliders' s_dot and s_ddot. None when ``solution``
    does not fix every link's pose, when the scene has no accelerations (a ``[given]`` scene
    without them), or when the equations are singular.
    """
    scene = solution.scene
    inp = scene.input
    if isinstance(inp, GivenInput) and any(p.acceleration is None for p in inp.points):
        return None
    poses = _poses(scene, solution.pose)
    if poses is None:
        return None
    eq = _Equations(scene, poses)
    velocity = _solve(*eq.assemble(None, how))
    if velocity is None:
        return None
    omega = {name: float(velocity[eq.column[name] + 2]) for name in eq.moving}
    s_dot = {name: float(velocity[k]) for name, k in eq.slider_column.items()}
    acceleration = _solve(*eq.assemble(_Rates(omega, s_dot), how))
    if acceleration is None:
        return None
    alpha = {name: float(acceleration[eq.column[name] + 2]) for name in eq.moving}
    out: dict[AnswerKey, Value] = {}
    for name in eq.moving:
        out[AnswerKey("omega", name)] = omega[name]
        out[AnswerKey("alpha", name)] = alpha[name]
    for label in dict.fromkeys((*scene.find.velocity, *scene.find.acceleration)):
        point, _, on = label.partition("@")
        link = on or _owner(scene, point)
        v, a = np.zeros(2), np.zeros(2)
        if link in eq.column:
            k = eq.column[link]
            r = eq.position(point) - poses[link].origin
            w = omega[link]
            v = velocity[k : k + 2] + w * _quarter(r)
            a = acceleration[k : k + 2] + alpha[link] * _quarter(r) + how.normal_sign * w * w * r
        out[AnswerKey("velocity", label)] = (float(v[0]), float(v[1]))
        out[AnswerKey("acceleration", label)] = (float(a[0]), float(a[1]))
    for name, k in eq.slider_column.items():
        out[AnswerKey("s_dot", name)] = s_dot[name]
        out[AnswerKey("s_ddot", name)] = float(acceleration[k])
    return out
