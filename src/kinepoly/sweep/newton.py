"""A group that is not a dyad, over rows: positions by Newton row after row, rates by stacked linear solves.

Positions: damped Newton on the joint equations of ``solve.newton`` at each row, a Python loop
over rows (not vectorised), with the Jacobian in closed form (the finite differences of the
one-input solver would cost milliseconds a row). Each row starts from the group's points one
and two rows back, extrapolated (one row back next to the seed), so the group is followed
continuously from the seed row, forward and then backward. A row where Newton's method does
not close is marked and skipped; the next row starts from the last row that closed.

Velocities and accelerations: the joint equations of ``construct.group`` (the stand-in for a
two-line construction), one small linear system per row, all rows solved by one stacked
``numpy.linalg.solve``. The same condition test marks singular rows.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from kinepoly.errors import SingularityError
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import SliderSpec
from kinepoly.engine.plan import NewtonGroup
from kinepoly.model.pose import LinkPose
from kinepoly.geom.arrays import Bools, Points, Reals, turn
from kinepoly.sweep.polygon import ArrayPolygon, JointSolve
from kinepoly.model.array_pose import ArrayPose

if TYPE_CHECKING:
    from kinepoly.sweep.acceleration import AccelerationContext

__all__ = ["NEAR_SINGULAR_CONDITION", "SINGULAR_CONDITION", "acceleration_rows", "newton_rows", "velocity_rows"]

SINGULAR_CONDITION = 1e12
"""The condition number above which ``construct.group`` calls the joint equations singular."""
NEAR_SINGULAR_CONDITION = 1e8
"""Above this the sweep warns that a row is near-singular (relative error about condition x u).
A sound triad's scaled joint equations have condition numbers near 1e4."""
_MAX_STEPS = 40

Vec = tuple[float, float]


def _points_of(mechanism: Mechanism, group: NewtonGroup, poses: dict[str, LinkPose]) -> dict[str, complex]:
    return {p.name: complex(*poses[link].world(p.local)) for link in group.links
            for p in mechanism.scene.link(link).points}


class _RowSystem:
    """The joint equations of the group at one row, with their Jacobian in closed form.

    Unknowns (x, y, theta) per group link. A pin at P: world_a(P) - world_b(P) = 0. A slider:
    theta_block - theta_guide - angle = 0 (wrapped), and the distance of the block's point from
    the guide's line, n . (s - t) = 0: the equations of ``solve.newton.group_residual``.
    """

    def __init__(self, mechanism: Mechanism, group: NewtonGroup, known: dict[str, LinkPose]) -> None:
        self.known = known
        self.index = {link: 3 * k for k, link in enumerate(group.links)}
        self.size = 3 * len(group.links)
        self.pins: list[tuple[str, tuple[float, float], str, tuple[float, float]]] = []
        self.slides: list[tuple[SliderSpec, tuple[float, float]]] = []
        for joint in group.joints:
            if isinstance(joint, Revolute):
                a, b = joint.links
                self.pins.append((a, mechanism.local(a, joint.point), b, mechanism.local(b, joint.point)))
            else:
                self.slides.append((joint, mechanism.local(joint.block, joint.point)))
        self.count = 2 * (len(self.pins) + len(self.slides))

    def _point(self, q: Reals, link: str, local: tuple[float, float]) -> tuple[float, float, float, float, float]:
        """World point of ``local`` on ``link``, its lever r = R local, and the link's theta."""
        k = self.index.get(link)
        if k is None:
            pose = self.known[link]
            x, y, theta = pose.x, pose.y, pose.theta
        else:
            x, y, theta = float(q[k]), float(q[k + 1]), float(q[k + 2])
        c, s = math.cos(theta), math.sin(theta)
        rx, ry = c * local[0] - s * local[1], s * local[0] + c * local[1]
        return x + rx, y + ry, rx, ry, theta

    def evaluate(self, q: Reals) -> tuple[Reals, Reals]:
        out = np.zeros(self.count)
        jac = np.zeros((self.count, self.size))
        row = 0
        for a, local_a, b, local_b in self.pins:
            ax, ay, arx, ary, _ = self._point(q, a, local_a)
            bx, by, brx, bry, _ = self._point(q, b, local_b)
            out[row], out[row + 1] = ax - bx, ay - by
            for link, sign, rx, ry in ((a, 1.0, arx, ary), (b, -1.0, brx, bry)):
                k = self.index.get(link)
                if k is not None:
                    jac[row, k] += sign
                    jac[row + 1, k + 1] += sign
                    jac[row, k + 2] -= sign * ry
                    jac[row + 1, k + 2] += sign * rx
            row += 2
        for joint, local in self.slides:
            sx, sy, bx, by, theta_b = self._point(q, joint.block, local)
            tx, ty, lx, ly, theta_g = self._point(q, joint.guide, joint.through)
            turn_rel = theta_b - theta_g - joint.angle_rad
            ex, ey = math.cos(theta_g + joint.angle_rad), math.sin(theta_g + joint.angle_rad)
            nx, ny = -ey, ex
            out[row] = math.atan2(math.sin(turn_rel), math.cos(turn_rel))
            out[row + 1] = nx * (sx - tx) + ny * (sy - ty)
            k = self.index.get(joint.block)
            if k is not None:
                jac[row, k + 2] += 1.0
                jac[row + 1, k:k + 3] += (nx, ny, -nx * by + ny * bx)
            k = self.index.get(joint.guide)
            if k is not None:
                jac[row, k + 2] -= 1.0
                jac[row + 1, k:k + 3] += (-nx, -ny, -(ex * (sx - tx) + ey * (sy - ty)) + nx * ly - ny * lx)
            row += 2
        return out, jac


def _newton(system: _RowSystem, start: Reals, size: float) -> Reals | None:
    """Damped Newton as ``solve.newton`` does it (halve the step until the residual falls), with the
    Jacobian in closed form; None when it does not close to 1e-9 of the size.

    A row that cannot close makes the residual stall at its least-squares floor: after three
    steps in a row that do not halve it, the row is given up (a closing row, started from the
    rows before it, converges quadratically within a few steps).
    """
    q = start
    r, jac = system.evaluate(q)
    norm_r = float(np.linalg.norm(r))
    stalled = 0
    for _ in range(_MAX_STEPS):
        if norm_r <= 1e-13 * size or stalled >= 3:
            break
        step = np.linalg.lstsq(jac, -r, rcond=None)[0]
        t = 1.0
        while t > 1e-6:
            trial, trial_jac = system.evaluate(q + t * step)
            norm_trial = float(np.linalg.norm(trial))
            if norm_trial < norm_r:
                stalled = stalled + 1 if norm_trial > 0.5 * norm_r else 0
                q, r, jac, norm_r = q + t * step, trial, trial_jac, norm_trial
                break
            t /= 2
        else:
            break
    return q if norm_r <= 1e-9 * size else None


def _start(mechanism: Mechanism, group: NewtonGroup, guess: dict[str, complex], known: dict[str, LinkPose]) -> Reals:
    """Poses from the guessed points as ``solve.newton`` starts (the first two points of each link)."""
    points = dict(guess)
    for link, pose in known.items():
        for p in mechanism.scene.link(link).points:
            points[p.name] = complex(*pose.world(p.local))
    q: list[float] = []
    for link in group.links:
        pts = [(complex(*p.local), points[p.name]) for p in mechanism.scene.link(link).points if p.name in points]
        (la, wa), (lb, wb) = pts[0], pts[1] if len(pts) > 1 else pts[0]
        theta = cmath.phase(wb - wa) - cmath.phase(lb - la) if len(pts) > 1 else 0.0
        origin = wa - la * complex(math.cos(theta), math.sin(theta))
        q += [origin.real, origin.imag, theta]
    return np.array(q)


def newton_rows(mechanism: Mechanism, group: NewtonGroup, poses: dict[str, ArrayPose], ok: Bools,
                seed_row: int, seed: dict[str, LinkPose],
                progress: Callable[[int, int], None] | None = None) -> tuple[dict[str, ArrayPose], Bools]:
    """Poses of the group's links at every row (and the rows where it closed)."""
    n = len(ok)
    origin = {link: np.zeros(n, np.complex128) for link in group.links}
    rotation = {link: np.ones(n, np.complex128) for link in group.links}
    closed = np.zeros(n, np.bool_)
    known_links = group.known_links()
    points = _points_of(mechanism, group, seed)
    size = max(1.0, *(abs(v.real) + abs(v.imag) for v in points.values()))
    done = 0
    for order in (range(seed_row, n), range(seed_row - 1, -1, -1)):
        history: list[dict[str, complex]] = [points]
        for row in order:
            done += 1
            if progress is not None and done % 64 == 0:
                progress(done, n)
            if not ok[row]:
                continue
            if row == seed_row:
                placed = {link: seed[link] for link in group.links}
            else:
                last = history[-1]
                guess = last if len(history) == 1 else {k: 2.0 * v - history[-2][k] for k, v in last.items()}
                known = {link: LinkPose(*poses[link].row(row)) for link in known_links}
                q = _newton(_RowSystem(mechanism, group, known), _start(mechanism, group, guess, known), size)
                if q is None:
                    continue
                placed = {link: LinkPose(float(q[3 * k]), float(q[3 * k + 1]), float(q[3 * k + 2]))
                          for k, link in enumerate(group.links)}
            for link, pose in placed.items():
                origin[link][row] = complex(pose.x, pose.y)
                rotation[link][row] = complex(math.cos(pose.theta), math.sin(pose.theta))
            closed[row] = True
            history = [*history[-1:], _points_of(mechanism, group, placed)]
    if progress is not None:
        progress(n, n)
    return {link: ArrayPose(origin[link], rotation[link]) for link in group.links}, closed


def _origin(polygon: ArrayPolygon, link: str) -> Points:
    return polygon.positions.poses[link].origin


def _joint_links(joint: Revolute | SliderSpec) -> tuple[str, str]:
    return joint.links if isinstance(joint, Revolute) else (joint.block, joint.guide)


def _system(polygon: ArrayPolygon, group: NewtonGroup, extra: dict[tuple[str, str], Points]) -> tuple[
        Reals, Reals]:
    """The joint equations M u = rhs of ``construct.group._rows``, one system per row: (N, m, n), (N, m)."""
    links = group.links
    n, size = polygon.n, 3 * len(links)
    rows: list[Reals] = []
    rhs: list[Reals] = []

    def term(link: str, point: str, sign: float, row_x: Reals, row_y: Reals) -> Points:
        """Add sign * tip(link, point) to the two rows; return its known part."""
        if link in links:
            k = 3 * links.index(link)
            r = polygon.world(point) - _origin(polygon, link)
            row_x[:, k] += sign
            row_y[:, k + 1] += sign
            row_x[:, k + 2] -= sign * r.imag
            row_y[:, k + 2] += sign * r.real
            return np.asarray(sign * extra.get((link, point), polygon.zero))
        return np.asarray(sign * polygon.tip(link, point))

    for joint in group.joints:
        row_x, row_y = np.zeros((n, size)), np.zeros((n, size))
        if isinstance(joint, Revolute):
            known = term(joint.links[0], joint.point, 1.0, row_x, row_y) + term(joint.links[1], joint.point, -1.0,
                                                                                 row_x, row_y)
            rows += [row_x, row_y]
            rhs += [-known.real, -known.imag]
            continue
        rate_row = np.zeros((n, size))
        known_rate = np.zeros(n)
        for link, sign in ((joint.block, 1.0), (joint.guide, -1.0)):
            if link in links:
                rate_row[:, 3 * links.index(link) + 2] += sign
            else:
                value = polygon.rate_of(link)
                if value is not None:
                    known_rate = known_rate + sign * value
        rows.append(rate_row)
        rhs.append(-known_rate)
        known = term(joint.block, joint.point, 1.0, row_x, row_y) + term(joint.guide, joint.point, -1.0, row_x, row_y)
        normal = 1j * (polygon.positions.poses[joint.guide].rotation * turn(joint.angle_rad))
        known = known + extra.get(("slide", joint.name), polygon.zero)
        rows.append(normal.real[:, None] * row_x + normal.imag[:, None] * row_y)
        rhs.append(-(normal.real * known.real + normal.imag * known.imag))
    return np.stack(rows, axis=1), np.stack(rhs, axis=1)


def _solve(polygon: ArrayPolygon, group: NewtonGroup, matrix: Reals, rhs: Reals) -> Reals:
    """Every row's system solved at once; rows whose scaled matrix is singular are flagged."""
    if matrix.shape[1] != matrix.shape[2]:
        raise SingularityError(f"the {polygon.kind} equations of group {group.name} are not square")
    size = np.ones(polygon.n)
    for link in group.links:
        origin = _origin(polygon, link)
        size = np.maximum(size, np.abs(origin.real) + np.abs(origin.imag))
    matrix = np.where(np.isfinite(matrix), matrix, 0.0)
    rhs = np.where(np.isfinite(rhs), rhs, 0.0)
    scaled = matrix.copy()
    scaled[:, :, 2::3] *= size[:, None, None]
    condition = np.linalg.cond(scaled)
    singular = ~(condition <= SINGULAR_CONDITION)
    polygon.crossings.append(JointSolve(polygon.kind, group.name, np.where(singular, np.inf, condition)))
    matrix[singular] = np.eye(matrix.shape[1])
    return np.asarray(np.linalg.solve(matrix, rhs[:, :, None])[:, :, 0])


def _store(polygon: ArrayPolygon, group: NewtonGroup, u: Reals, extra: dict[tuple[str, str], Points]) -> None:
    for k, link in enumerate(group.links):
        polygon.set_rate(link, u[:, 3 * k + 2])
    for joint in group.joints:
        for link in _joint_links(joint):
            if link in group.links and polygon.label(link, joint.point) not in polygon.tips:
                k = 3 * group.links.index(link)
                r = polygon.world(joint.point) - _origin(polygon, link)
                tip = u[:, k] + 1j * u[:, k + 1] + u[:, k + 2] * (1j * r) + extra.get((link, joint.point),
                                                                                        polygon.zero)
                polygon.add_tip(link, joint.point, np.asarray(tip))


def velocity_rows(polygon: ArrayPolygon, group: NewtonGroup, sliding: dict[str, Points]) -> None:
    """``construct.group.velocity_by_linear_solve`` at every row."""
    matrix, rhs = _system(polygon, group, {})
    _store(polygon, group, _solve(polygon, group, matrix, rhs), {})
    for joint in group.joints:
        if isinstance(joint, SliderSpec):
            sliding[joint.name] = polygon.tip(joint.block, joint.point) - polygon.tip(joint.guide, joint.point)


def acceleration_rows(ctx: AccelerationContext, group: NewtonGroup) -> None:
    """``construct.group.acceleration_by_linear_solve`` at every row."""
    polygon = ctx.b
    extra: dict[tuple[str, str], Points] = {}
    for joint in group.joints:
        for link in _joint_links(joint):
            if link in group.links:
                r = polygon.world(joint.point) - _origin(polygon, link)
                w = polygon.omega_of(link)
                extra[(link, joint.point)] = np.asarray((-w * w) * r)
        if isinstance(joint, SliderSpec):
            v_rel = ctx.v_tip(joint.block, joint.point) - ctx.v_tip(joint.guide, joint.point)
            w = polygon.omega_of(joint.guide)
            extra[("slide", joint.name)] = np.asarray(-(2.0 * w) * (1j * v_rel))  # minus 2 omega x v_rel
    matrix, rhs = _system(polygon, group, extra)
    _store(polygon, group, _solve(polygon, group, matrix, rhs), extra)
    for joint in group.joints:
        if isinstance(joint, SliderSpec):
            ctx.slide_values(joint, joint.block, joint.point)
