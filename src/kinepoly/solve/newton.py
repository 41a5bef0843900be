"""Damped Newton for a group of links that is not a dyad, started from the ``[guess]``.

Unknowns are the poses (x, y, theta) of the group's links; equations are the joints that
touch the group (a pin: two equations, a slider: two). The step is a least-squares solve of
the Jacobian (finite differences are enough for position: the residual, not the Jacobian,
decides the accuracy), halved until the residual falls.
"""

from __future__ import annotations

import math

import numpy as np

from kinepoly.errors import AssemblyError
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.engine.plan import NewtonGroup
from kinepoly.model.pose import LinkPose

__all__ = ["group_residual", "solve_newton_group"]

Vec = tuple[float, float]


def group_residual(mechanism: Mechanism, group: NewtonGroup, poses: dict[str, LinkPose]) -> np.ndarray:
    """Constraint residuals of every joint touching the group, at ``poses``."""
    out: list[float] = []
    for joint in group.joints:
        if isinstance(joint, Revolute):
            a, b = joint.links
            wa = poses[a].world(mechanism.local(a, joint.point))
            wb = poses[b].world(mechanism.local(b, joint.point))
            out += [wa[0] - wb[0], wa[1] - wb[1]]
        else:
            block, guide = poses[joint.block], poses[joint.guide]
            turn = block.theta - guide.theta - joint.angle_rad
            out.append(math.atan2(math.sin(turn), math.cos(turn)))
            s = block.world(mechanism.local(joint.block, joint.point))
            t = guide.world(joint.through)
            n_angle = guide.theta + joint.angle_rad
            out.append(-math.sin(n_angle) * (s[0] - t[0]) + math.cos(n_angle) * (s[1] - t[1]))
    return np.array(out)


def _start_pose(mechanism: Mechanism, link: str, known: dict[str, Vec]) -> LinkPose | None:
    pts = [(p.local, known[p.name]) for p in mechanism.scene.link(link).points if p.name in known]
    if len(pts) >= 2:
        (la, wa), (lb, wb) = pts[0], pts[1]
        theta = math.atan2(wb[1] - wa[1], wb[0] - wa[0]) - math.atan2(lb[1] - la[1], lb[0] - la[0])
    elif len(pts) == 1:
        (la, wa), theta = pts[0], 0.0
    else:
        return None
    c, s = math.cos(theta), math.sin(theta)
    return LinkPose(wa[0] - (c * la[0] - s * la[1]), wa[1] - (s * la[0] + c * la[1]), theta)


def solve_newton_group(mechanism: Mechanism, group: NewtonGroup, poses: dict[str, LinkPose],
                       guess: dict[str, Vec], input_text: str) -> dict[str, LinkPose]:
    known: dict[str, Vec] = dict(guess)
    for link, pose in poses.items():
        for p in mechanism.scene.link(link).points:
            known[p.name] = pose.world(p.local)
    start: dict[str, LinkPose] = {}
    for link in group.links:
        found = _start_pose(mechanism, link, known)
        if found is None:
            raise AssemblyError(
                f"group {group.name} is not a dyad and is solved by Newton's method from [guess]; "
                f"link {link} has no guessed or known point: add [guess] positions for its points"
            )
        start[link] = found
    # the group's size sets every tolerance, so that scaling the mechanism scales nothing else
    size = max((abs(v) for link in group.links for p in mechanism.scene.link(link).points for v in p.local),
               default=0.0)
    size = max(size, *(abs(v) for xy in known.values() for v in xy)) or 1.0
    q = np.array([v for link in group.links for v in (start[link].x, start[link].y, start[link].theta)])
    # angle rows (a block turning with its guide) in lengths, like the others
    rows = np.array([w for j in group.joints for w in ((1.0, 1.0) if isinstance(j, Revolute) else (size, 1.0))])
    steps = np.array([v for _ in group.links for v in (size, size, 1.0)])

    def residual(vec: np.ndarray) -> np.ndarray:
        trial = dict(poses)
        for k, link in enumerate(group.links):
            trial[link] = LinkPose(float(vec[3 * k]), float(vec[3 * k + 1]), float(vec[3 * k + 2]))
        return np.asarray(rows * group_residual(mechanism, group, trial), dtype=float)

    r = residual(q)
    for _ in range(100):  # on to the rounding level: stop when no step lowers the residual
        if not np.linalg.norm(r) > 0.0:
            break
        jac = np.empty((r.size, q.size))
        for c in range(q.size):
            h = 1e-7 * max(float(steps[c]), abs(q[c]))
            e = np.zeros_like(q)
            e[c] = h
            jac[:, c] = (residual(q + e) - residual(q - e)) / (2 * h)
        step = np.linalg.lstsq(jac, -r, rcond=None)[0]
        t = 1.0
        while t > 1e-6:
            trial = residual(q + t * step)
            if np.linalg.norm(trial) < np.linalg.norm(r):
                q, r = q + t * step, trial
                break
            t /= 2
        else:
            break
    if not np.linalg.norm(r) <= 1e-9 * size:
        raise AssemblyError(
            f"group {group.name} does not close at {input_text}: Newton's method stopped with a joint "
            f"residual of {np.linalg.norm(r):.3g}; the group cannot be assembled there, or [guess] is far from it"
        )
    return {link: LinkPose(float(q[3 * k]), float(q[3 * k + 1]), float(q[3 * k + 2]))
            for k, link in enumerate(group.links)}
