"""Velocities and accelerations of a group that is not a dyad (solved by Newton for position).

Such a group (a triad, say) has no two-line construction: its tips come from one linear
solve of the joint equations, the honest stand-in for Assur's auxiliary-point construction.
Unknowns per link k: the velocity (acceleration) of its frame origin and omega_k (alpha_k).
A pin at P of links i and j: v_i(P) = v_j(P). A slider: omega_b = omega_g, and the block's
point moves relative to the guide only along the slide (for accelerations after taking off
the Coriolis term 2 omega_g x v_rel).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from kinepoly.construct.builder import PolygonBuilder
from kinepoly.engine.steps import Step
from kinepoly.errors import SingularityError
from kinepoly.geom.vec import Vec, perp, rotate, sub
from kinepoly.model.mechanism import Revolute
from kinepoly.engine.plan import NewtonGroup

if TYPE_CHECKING:
    from kinepoly.construct.acceleration import _Context

__all__ = ["acceleration_by_linear_solve", "velocity_by_linear_solve"]

_SINGULAR = 1e12


def _rows(builder: PolygonBuilder, group: NewtonGroup,
          known_tip: dict[tuple[str, str], Vec], extra: dict[tuple[str, str], Vec]) -> tuple[np.ndarray, np.ndarray]:
    """Linear equations M u = rhs, u = (ox, oy, rate) per group link.

    ``known_tip`` gives the tips of joint points on known links; ``extra`` the part of a group
    link's tip that does not depend on the unknowns (zero for velocities, -omega^2 r for
    accelerations), keyed by (link, point name).
    """
    links = group.links
    n = 3 * len(links)
    rows: list[np.ndarray] = []
    rhs: list[float] = []
    pose = builder.pose

    def coeff(link: str, point: str, sign: float, row_x: np.ndarray, row_y: np.ndarray) -> tuple[float, float]:
        """Add sign * tip(link, point) to the two rows; return its known part."""
        at = builder.world(point)
        if link in links:
            k = 3 * links.index(link)
            r = sub(at, (pose.links[link].x, pose.links[link].y))
            row_x[k] += sign
            row_y[k + 1] += sign
            row_x[k + 2] += sign * -r[1]
            row_y[k + 2] += sign * r[0]
            e = extra.get((link, point), (0.0, 0.0))
            return (sign * e[0], sign * e[1])
        t = known_tip[(link, point)]
        return (sign * t[0], sign * t[1])

    for joint in group.joints:
        if isinstance(joint, Revolute):
            rx, ry = np.zeros(n), np.zeros(n)
            a = coeff(joint.links[0], joint.point, 1.0, rx, ry)
            b = coeff(joint.links[1], joint.point, -1.0, rx, ry)
            rows += [rx, ry]
            rhs += [-(a[0] + b[0]), -(a[1] + b[1])]
        else:
            rate = np.zeros(n)
            known = 0.0
            for link, sign in ((joint.block, 1.0), (joint.guide, -1.0)):
                if link in links:
                    rate[3 * links.index(link) + 2] += sign
                else:
                    known += sign * (builder.rate_of(link) or 0.0)
            rows.append(rate)
            rhs.append(-known)
            rx, ry = np.zeros(n), np.zeros(n)
            a = coeff(joint.block, joint.point, 1.0, rx, ry)
            b = coeff(joint.guide, joint.point, -1.0, rx, ry)
            normal = perp(rotate((1.0, 0.0), pose.links[joint.guide].theta + joint.angle_rad))
            offset = extra.get(("slide", joint.name), (0.0, 0.0))
            rows.append(normal[0] * rx + normal[1] * ry)
            rhs.append(-(normal[0] * (a[0] + b[0] + offset[0]) + normal[1] * (a[1] + b[1] + offset[1])))
    return np.array(rows), np.array(rhs)


def _solve(builder: PolygonBuilder, group: NewtonGroup, matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve, after judging the condition of the equations made dimensionless.

    The rate columns hold arms (lengths) and are divided by the largest arm L; the rows that
    hold only rates (a block turning with its guide) are multiplied by L. The condition of
    that matrix does not change when the mechanism is scaled.
    """
    from kinepoly.solve.position import describe_input

    rates = matrix[:, 2::3]
    length = float(np.max(np.abs(rates[np.any(matrix[:, np.arange(matrix.shape[1]) % 3 != 2] != 0, axis=1)]),
                          initial=0.0)) or 1.0
    scaled = matrix.copy()
    scaled[:, 2::3] /= length
    only_rates = ~np.any(matrix[:, np.arange(matrix.shape[1]) % 3 != 2] != 0, axis=1)
    scaled[only_rates] *= length
    condition = float(np.linalg.cond(scaled)) if matrix.shape[0] == matrix.shape[1] else math.inf
    if not condition <= _SINGULAR:
        joints = ", ".join(j.name for j in group.joints)
        raise SingularityError(
            f"singular position at {describe_input(builder.mechanism)}: the {builder.kind} equations of group "
            f"{group.name} (joints {joints}) have condition number {condition:.3g}, above {_SINGULAR:.0e}: its "
            f"links can move with the input held (a change point), so their {builder.kind}s are not determined")
    return np.asarray(np.linalg.solve(matrix, rhs))


def _known_tips(builder: PolygonBuilder, group: NewtonGroup) -> dict[tuple[str, str], Vec]:
    tips = {}
    for joint in group.joints:
        links = joint.links if isinstance(joint, Revolute) else (joint.block, joint.guide)
        for link in links:
            if link not in group.links:
                tips[(link, joint.point)] = builder.tip(link, joint.point)
    return tips


def _store(builder: PolygonBuilder, group: NewtonGroup, u: np.ndarray,
           extra: dict[tuple[str, str], Vec]) -> list[str]:
    found = []
    for k, link in enumerate(group.links):
        builder.set_rate(link, float(u[3 * k + 2]))
    for joint in group.joints:
        links = joint.links if isinstance(joint, Revolute) else (joint.block, joint.guide)
        for link in links:
            if link in group.links and builder.label(link, joint.point) not in builder.tips:
                k = 3 * group.links.index(link)
                r = sub(builder.world(joint.point), (builder.pose.links[link].x, builder.pose.links[link].y))
                e = extra.get((link, joint.point), (0.0, 0.0))
                tip = (float(u[k] - u[k + 2] * r[1] + e[0]), float(u[k + 1] + u[k + 2] * r[0] + e[1]))
                found.append(builder.add_tip(link, joint.point, tip))
    return found


def _record(builder: PolygonBuilder, group: NewtonGroup, found: list[str]) -> None:
    builder.steps.append(Step(builder.kind, "linear-solve", f"joint equations of group {group.name}",
                              f"Group {group.name} is not a dyad, so no two direction lines fix its tips; they come "
                              f"from one linear solve of its joint equations: {', '.join(f.lower() for f in found)}.",
                              ", ".join(f.lower() for f in found)))


def velocity_by_linear_solve(builder: PolygonBuilder, group: NewtonGroup, sliding: dict[str, Vec]) -> None:
    matrix, rhs = _rows(builder, group, _known_tips(builder, group), {})
    u = _solve(builder, group, matrix, rhs)
    found = _store(builder, group, u, {})
    _record(builder, group, found)
    for joint in group.joints:
        if not isinstance(joint, Revolute):
            sliding[joint.name] = sub(builder.tip(joint.block, joint.point), builder.tip(joint.guide, joint.point))


def acceleration_by_linear_solve(ctx: _Context, group: NewtonGroup) -> None:
    builder = ctx.b
    extra: dict[tuple[str, str], Vec] = {}
    for joint in group.joints:
        links = joint.links if isinstance(joint, Revolute) else (joint.block, joint.guide)
        for link in links:
            if link in group.links:
                r = sub(builder.world(joint.point), (builder.pose.links[link].x, builder.pose.links[link].y))
                w = builder.omega_of(link)
                extra[(link, joint.point)] = (-w * w * r[0], -w * w * r[1])
        if not isinstance(joint, Revolute):
            v_rel = sub(ctx.v_tip(joint.block, joint.point), ctx.v_tip(joint.guide, joint.point))
            w = builder.omega_of(joint.guide)
            extra[("slide", joint.name)] = (2.0 * w * v_rel[1], -2.0 * w * v_rel[0])  # minus 2 omega x v_rel
    matrix, rhs = _rows(builder, group, _known_tips(builder, group), extra)
    u = _solve(builder, group, matrix, rhs)
    found = _store(builder, group, u, extra)
    _record(builder, group, found)
    for joint in group.joints:
        if not isinstance(joint, Revolute):
            ctx.slide_values(joint, joint.block, joint.point)
