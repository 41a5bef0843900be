"""Damped Newton for a group of links that is not a dyad: the one position solver of such groups.

Unknowns are the poses (x, y, theta) of the group's links; equations are the joints that touch
the group (a pin: two equations; a slider: the block turns with its guide, and its point lies on
the guide's line; an input driving a joint of the group: its angle or stroke; a spline cam whose follower floats in
the group: its knife edge or roller centre W on the profile's offset curve X(u), the parameter u one more
unknown). The Jacobian is in closed form; the step is a least-squares solve, halved
until the residual falls, and the iteration goes on to the rounding level (until no step lowers
the residual). A row that cannot close makes the residual stall at its least-squares floor:
after three steps in a row that do not halve it, far from closing, the row is given up.

Where each row starts is the assembly policy's business (``engine.assembly``): from the
``[guess]`` for a solve, from the rows before it for a sweep. This module solves one row.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from msgspec import Struct

from kinepoly.engine.cam_contact import cam_spline, face_parameter, offset_of
from kinepoly.engine.groups import NewtonGroup
from kinepoly.geom.arrays import Reals
from kinepoly.geom.spline import nearest_parameter
from kinepoly.geom.tolerances import NEWTON_CLOSED_REL, NEWTON_LEAST_STEP
from kinepoly.geom.vec import phase
from kinepoly.model.mechanism import Drive, Mechanism, Revolute
from kinepoly.model.pose import LinkPose
from kinepoly.scene.spec import CamSpec, SliderSpec

__all__ = ["RowClosure", "group_reach", "group_size", "newton_row", "start_poses"]

_MAX_STEPS = 100
_Turned = tuple[float, float, float, float, float]
"""A link's x, y, theta, cos theta and sin theta."""


class _RowSystem:
    """The joint equations of the group at one row, with their Jacobian in closed form.

    A pin at P: world_a(P) - world_b(P) = 0. A slider: theta_block - theta_guide - angle = 0
    (wrapped, in lengths: times the group's size), and the distance of the block's point from
    the guide's line, n . (s - t) = 0.
    """

    def __init__(self, mechanism: Mechanism, group: NewtonGroup, known: Mapping[str, LinkPose], size: float,
                 values: Mapping[int, float]) -> None:
        self.known = known
        self._turned: dict[str, _Turned] = {}
        self.index = {link: 3 * k for k, link in enumerate(group.links)}
        self.size = 3 * len(group.links) + len(group.cams)
        self.scale = size
        self.pins: list[tuple[str, tuple[float, float], str, tuple[float, float]]] = []
        self.slides: list[tuple[SliderSpec, tuple[float, float]]] = []
        for joint in group.joints:
            if isinstance(joint, Revolute):
                a, b = joint.links
                self.pins.append((a, mechanism.local(a, joint.point), b, mechanism.local(b, joint.point)))
            else:
                self.slides.append((joint, mechanism.local(joint.block, joint.point)))
        self._block_point = {slider.name: local for slider, local in self.slides}
        self.drives = [(drive, values[drive.index]) for drive in group.drives]
        self.cams = [(cam, cam.flat[0] if cam.flat is not None and cam.kind == "flat" else
                      mechanism.local(cam.follower, cam.point or "")) for cam in group.cams]
        self.count = 2 * (len(self.pins) + len(self.slides) + len(self.cams)) + len(self.drives)

    def _turns(self, v: list[float]) -> dict[str, _Turned]:
        """Each link's x, y, theta, cos theta and sin theta at the unknowns ``v`` (``q.tolist()``: the same doubles
        as ``float(q[k])``): an unknown link's worked out once for all its joints, a known one's as found before
        (``_known_turned``)."""
        turns = dict(self._turned)  # the known links met so far (``_known_turned``)
        for link, k in self.index.items():
            turns[link] = (v[k], v[k + 1], v[k + 2], math.cos(v[k + 2]), math.sin(v[k + 2]))
        return turns

    def _point(self, turns: dict[str, _Turned], link: str,
               local: tuple[float, float]) -> tuple[float, float, float, float, float]:
        """World point of ``local`` on ``link``, its lever r = R local, and the link's theta (``turns``: the links'
        at this iterate, ``_turns``)."""
        x, y, theta, c, s = turns.get(link) or self._known_turned(link)
        rx, ry = c * local[0] - s * local[1], s * local[0] + c * local[1]
        return x + rx, y + ry, rx, ry, theta

    def _known_turned(self, link: str) -> _Turned:
        """A known link's x, y, theta, cos theta and sin theta, worked out once per row (they do not move while
        the iteration runs)."""
        found = self._turned.get(link)
        if found is None:
            pose = self.known[link]
            found = self._turned[link] = (pose.x, pose.y, pose.theta, math.cos(pose.theta), math.sin(pose.theta))
        return found

    def residual(self, q: Reals) -> Reals:
        """The joint residual alone (a line search's trial, whose Jacobian is wanted only if it is taken): the same
        numbers as ``evaluate``'s first."""
        return self.evaluate(q, jacobian=False)[0]

    def evaluate(self, q: Reals, jacobian: bool = True) -> tuple[Reals, Reals]:
        """The joint residual at ``q`` and (with ``jacobian``) its Jacobian, in closed form; without it the residual
        again in the Jacobian's place (``residual`` takes the first). Both are summed as Python floats (the same
        doubles, in the same order, as numpy's element by element) and made arrays once."""
        v = q.tolist()
        turns = self._turns(v)
        n = self.size
        out = [0.0] * self.count
        jac = [0.0] * (self.count * n) if jacobian else None
        row = 0
        for a, local_a, b, local_b in self.pins:  # ``_point`` of each side, written out: most of the calls are here
            xa, ya, _, ca, sa = turns.get(a) or self._known_turned(a)
            xb, yb, _, cb, sb = turns.get(b) or self._known_turned(b)
            arx, ary = ca * local_a[0] - sa * local_a[1], sa * local_a[0] + ca * local_a[1]
            brx, bry = cb * local_b[0] - sb * local_b[1], sb * local_b[0] + cb * local_b[1]
            out[row], out[row + 1] = (xa + arx) - (xb + brx), (ya + ary) - (yb + bry)
            if jac is not None:
                i, j = row * n, (row + 1) * n
                for link, sign, rx, ry in ((a, 1.0, arx, ary), (b, -1.0, brx, bry)):
                    k = self.index.get(link)
                    if k is not None:
                        jac[i + k] += sign
                        jac[j + k + 1] += sign
                        jac[i + k + 2] -= sign * ry
                        jac[j + k + 2] += sign * rx
            row += 2
        for joint, local in self.slides:
            sx, sy, bx, by, theta_b = self._point(turns, joint.block, local)
            tx, ty, lx, ly, theta_g = self._point(turns, joint.guide, joint.through)
            turn_rel = theta_b - theta_g - joint.angle_rad
            ex, ey = math.cos(theta_g + joint.angle_rad), math.sin(theta_g + joint.angle_rad)
            nx, ny = -ey, ex
            out[row] = self.scale * math.atan2(math.sin(turn_rel), math.cos(turn_rel))
            out[row + 1] = nx * (sx - tx) + ny * (sy - ty)
            if jac is not None:
                i, j = row * n, (row + 1) * n
                k = self.index.get(joint.block)
                if k is not None:
                    jac[i + k + 2] += self.scale
                    jac[j + k] += nx
                    jac[j + k + 1] += ny
                    jac[j + k + 2] += -nx * by + ny * bx
                k = self.index.get(joint.guide)
                if k is not None:
                    jac[i + k + 2] -= self.scale
                    jac[j + k] += -nx
                    jac[j + k + 1] += -ny
                    jac[j + k + 2] += -(ex * (sx - tx) + ey * (sy - ty)) + nx * ly - ny * lx
            row += 2
        for drive, value in self.drives:
            self._drive_row(turns, drive, value, row, out, jac)
            row += 1
        for c, (cam, local) in enumerate(self.cams):
            rows = self._face_rows if cam.kind == "flat" else self._contact_rows
            rows(v, turns, cam, local, self.size - len(self.cams) + c, row, out, jac)
            row += 2
        residual = np.array(out)
        return residual, (np.array(jac).reshape(self.count, n) if jac is not None else residual)

    def _contact_rows(self, v: list[float], turns: dict[str, _Turned], cam: CamSpec, local: tuple[float, float],
                      column: int, row: int, out: list[float], jac: list[float] | None) -> None:
        """W - (r_cam + A_cam X(u)) = 0, with dX/du = r'(u) (1 - rho kappa) (the offset curve runs along r)."""
        u = v[column]
        r, first, second = (complex(z[0]) for z in cam_spline(cam).derivatives(np.array([u])))
        speed = abs(first)
        rho = offset_of(cam)
        x_cam = r + rho * 1j * first / speed
        slope = first * (1.0 - rho * (first.conjugate() * second).imag / speed**3)
        wx, wy, rx, ry, _ = self._point(turns, cam.follower, local)
        cx, cy, _, _, theta_c = self._point(turns, cam.cam, (x_cam.real, x_cam.imag))
        out[row], out[row + 1] = wx - cx, wy - cy
        if jac is None:
            return
        i, j = row * self.size, (row + 1) * self.size
        k = self.index.get(cam.follower)
        if k is not None:
            jac[i + k] += 1.0
            jac[j + k + 1] += 1.0
            jac[i + k + 2] -= ry
            jac[j + k + 2] += rx
        along = complex(math.cos(theta_c), math.sin(theta_c)) * slope
        jac[i + column] -= along.real
        jac[j + column] -= along.imag

    def _face_rows(self, v: list[float], turns: dict[str, _Turned], cam: CamSpec, local: tuple[float, float],
                   column: int, row: int, out: list[float], jac: list[float] | None) -> None:
        """A flat face (through T, direction e; the cam on its left) on the profile point P(u): P on the face's
        line, cross(e, P - T) = 0, and the tangent along it, size cross(e, r'(u)) / |r'(u)| = 0."""
        assert cam.flat is not None
        u = v[column]
        r, first, second = (complex(z[0]) for z in cam_spline(cam).derivatives(np.array([u])))
        cx, cy, _, _, theta_c = self._point(turns, cam.cam, (r.real, r.imag))
        tx, ty, _, _, theta_f = self._point(turns, cam.follower, local)
        turn_c = complex(math.cos(theta_c), math.sin(theta_c))
        tangent, bend = turn_c * first, turn_c * second
        e = complex(math.cos(theta_f + cam.flat[1]), math.sin(theta_f + cam.flat[1]))
        gap = complex(cx - tx, cy - ty)
        speed = abs(tangent)
        sine = (e.conjugate() * tangent).imag / speed
        out[row] = (e.conjugate() * gap).imag
        out[row + 1] = self.scale * sine
        if jac is None:
            return
        i, j = row * self.size, (row + 1) * self.size
        k = self.index.get(cam.follower)
        if k is not None:
            origin = self._pose(v, cam.follower)
            jac[i + k] += e.imag
            jac[i + k + 1] -= e.real
            jac[i + k + 2] -= (e.conjugate() * (complex(cx, cy) - complex(origin.x, origin.y))).real
            jac[j + k + 2] -= self.scale * (e.conjugate() * tangent).real / speed
        jac[i + column] += (e.conjugate() * tangent).imag
        jac[j + column] += self.scale * ((e.conjugate() * bend).imag / speed
                                         - sine * (tangent.conjugate() * bend).real / speed**2)

    def start_parameters(self, q: Reals) -> Reals:
        """Each contact's parameter to start from at the start poses: the point of the offset curve nearest W, or
        for a flat face the point whose tangent runs along the face."""
        v = q.tolist()
        turns = self._turns(v)
        out = []
        for cam, local in self.cams:
            wx, wy, _, _, theta_f = self._point(turns, cam.follower, local)
            pose = self._pose(v, cam.cam)
            to_cam = complex(math.cos(pose.theta), -math.sin(pose.theta))
            at = (complex(wx, wy) - complex(pose.x, pose.y)) * to_cam
            if cam.kind == "flat":
                assert cam.flat is not None
                along = complex(math.cos(theta_f + cam.flat[1]), math.sin(theta_f + cam.flat[1])) * to_cam
                out.append(face_parameter(cam, along, at))
            else:
                out.append(nearest_parameter(cam_spline(cam), at, offset_of(cam)))
        return np.array(out)

    def _pose(self, v: list[float], link: str) -> LinkPose:
        k = self.index.get(link)
        return self.known[link] if k is None else LinkPose(v[k], v[k + 1], v[k + 2])

    def _drive_row(self, turns: dict[str, _Turned], drive: Drive, value: float, row: int, out: list[float],
                   jac: list[float] | None) -> None:
        """A motor: (theta_moving - theta_base - value) times the size; a cylinder: e . (s - t) - value."""
        joint = drive.joint
        i = row * self.size
        if isinstance(joint, Revolute):
            theta_m = self._point(turns, drive.moving, (0.0, 0.0))[4]
            theta_b = self._point(turns, drive.base, (0.0, 0.0))[4]
            out[row] = self.scale * math.remainder(theta_m - theta_b - value, math.tau)
            if jac is None:
                return
            for link, sign in ((drive.moving, 1.0), (drive.base, -1.0)):
                k = self.index.get(link)
                if k is not None:
                    jac[i + k + 2] += sign * self.scale
            return
        local = self._block_point[joint.name]
        sx, sy, bx, by, _ = self._point(turns, joint.block, local)
        tx, ty, lx, ly, theta_g = self._point(turns, joint.guide, joint.through)
        ex, ey = math.cos(theta_g + joint.angle_rad), math.sin(theta_g + joint.angle_rad)
        out[row] = ex * (sx - tx) + ey * (sy - ty) - value
        if jac is None:
            return
        k = self.index.get(joint.block)
        if k is not None:
            jac[i + k] += ex
            jac[i + k + 1] += ey
            jac[i + k + 2] += -ex * by + ey * bx
        k = self.index.get(joint.guide)
        if k is not None:
            jac[i + k] += -ex
            jac[i + k + 1] += -ey
            jac[i + k + 2] += (-ey * (sx - tx) + ex * (sy - ty)) + ex * ly - ey * lx

def group_size(mechanism: Mechanism, group: NewtonGroup, points: Mapping[str, complex]) -> float:
    """The group's length scale: its links' local coordinates and the known or guessed points."""
    size = max((abs(v) for link in group.links for p in mechanism.scene.link(link).points for v in p.local),
               default=0.0)
    size = max(size, *(max(abs(z.real), abs(z.imag)) for z in points.values())) if points else size
    return size if size > 0.0 and math.isfinite(size) else 1.0


def group_reach(mechanism: Mechanism, group: NewtonGroup, default: float = 1.0) -> float:
    """The longest distance of a point of the group's links from the link's own origin (``default`` if none)."""
    return max((abs(complex(*p.local)) for link in group.links for p in mechanism.scene.link(link).points),
               default=default) or default


def start_poses(mechanism: Mechanism, group: NewtonGroup, points: Mapping[str, complex],
                values: Mapping[int, float] | None = None) -> tuple[
        Reals | None, str]:
    """The group's starting poses from known or guessed points (the first two points of each link
    that have one); None and the link's name when a link has none.

    A guide with one placed point only (a cylinder's barrel, in its own frame or in the frame's) turns so
    that its line runs through the block's placed point, at the stroke ``values`` gives where an input
    drives the slider (else at the farther of the two places on the line at that distance): its angle
    does not depend on how its points are written. Other links with one placed point start at angle 0
    (a block's angle follows its guide's in Newton's first step).
    """
    placed: dict[str, tuple[complex, complex]] = {}  # one placed point: (local, world)
    angle: dict[str, float] = {}
    for link in group.links:
        pts = [(complex(*p.local), points[p.name]) for p in mechanism.scene.link(link).points if p.name in points]
        if not pts:
            return None, link
        if len(pts) > 1:
            (la, wa), (lb, wb) = pts[0], pts[1]
            angle[link] = phase(wb - wa) - phase(lb - la)
        placed[link] = pts[0]
    for link in group.links:
        if link not in angle:
            turned = _guide_angle(group, link, placed[link], points, values or {})
            if turned is not None:
                angle[link] = turned
    q: list[float] = []
    for link in group.links:
        local, world = placed[link]
        theta = angle.get(link, 0.0)
        origin = world - local * complex(math.cos(theta), math.sin(theta))
        q += [origin.real, origin.imag, theta]
    return np.array(q), ""


def _guide_angle(group: NewtonGroup, link: str, placed: tuple[complex, complex], points: Mapping[str, complex],
                 values: Mapping[int, float]) -> float | None:
    """The angle of a guide with one placed point whose line runs through its block's point (``start_poses``)."""
    for joint in group.joints:
        if not isinstance(joint, SliderSpec) or joint.guide != link or joint.point not in points:
            continue
        local, world = placed
        reach = abs(points[joint.point] - world)
        e = complex(math.cos(joint.angle_rad), math.sin(joint.angle_rad))
        foot = complex(*joint.through) - local  # the line from the placed point: foot + s e
        driven = [values[d.index] for d in group.drives if d.joint == joint and d.index in values]
        if driven:
            stroke = driven[0]
        else:
            along = (foot * e.conjugate()).real
            stroke = -along + math.sqrt(max(reach * reach - abs(foot) ** 2 + along * along, 0.0))
        on_line = foot + stroke * e
        if reach > 0.0 and on_line != 0:
            return phase(points[joint.point] - world) - phase(on_line)
    return None


_CREEP = 0.1
"""The largest move of a step, in links' lengths, where ``newton_row`` is given ``reach``."""


def _cut(step: Reals, links: int, reach: float | None) -> float:
    """The factor that keeps a step within ``_CREEP`` of ``reach`` (1 without ``reach``)."""
    if reach is None or not reach > 0.0:
        return 1.0
    poses = step[:3 * links].reshape(links, 3)
    move = float(np.max(np.maximum(np.hypot(poses[:, 0], poses[:, 1]), np.abs(poses[:, 2]) * reach)))
    return min(1.0, _CREEP * reach / move) if move > 0.0 else 1.0


def _norm(r: Reals) -> float:
    """``float(np.linalg.norm(r))`` of a vector, bit for bit (numpy's is the square root of ``r.dot(r)``), without
    its checks of shape and kind: a row's iteration takes one for every trial."""
    return math.sqrt(r.dot(r))


class RowClosure(Struct, frozen=True):
    """What Newton's method made of one row: the group's poses (None where it does not close), the final
    joint residual, and the sign of the Jacobian's determinant there (0 where it is not square)."""

    poses: dict[str, LinkPose] | None
    residual: float
    sign: int


def newton_row(mechanism: Mechanism, group: NewtonGroup, known: Mapping[str, LinkPose], start: Reals,
               size: float, values: Mapping[int, float] | None = None, reach: float | None = None) -> RowClosure:
    """Close the group at one row from ``start``. ``values``: the inputs' values at the row, by input
    index (for driven joints). ``reach``: the links' length; with it no step moves a link by more than a
    tenth of it (a link's origin, or its points by turning), so that the iteration creeps from the start to
    a nearby assembly instead of leaping across to another (more steps, and no stall rule while a step is
    cut short)."""
    system = _RowSystem(mechanism, group, known, size, values or {})
    q = np.concatenate((start, system.start_parameters(start))) if group.cams else start
    r, jac = system.evaluate(q)
    norm_r = _norm(r)
    stalled = 0
    for _ in range(_MAX_STEPS):
        if not norm_r > 0.0 or (stalled >= 3 and norm_r > NEWTON_CLOSED_REL * size):
            break
        step = np.linalg.lstsq(jac, -r, rcond=None)[0]
        cut = _cut(np.asarray(step, np.float64), len(group.links), reach)
        step = step * cut
        t = 1.0
        while t > NEWTON_LEAST_STEP:
            trial = system.residual(q + t * step)
            norm_trial = _norm(trial)
            if norm_trial < norm_r:
                stalled = stalled + 1 if norm_trial > 0.5 * norm_r and cut == 1.0 else 0
                q = q + t * step
                r, jac = system.evaluate(q)
                norm_r = norm_trial
                break
            t /= 2
        else:
            break
    if not norm_r <= NEWTON_CLOSED_REL * size:
        return RowClosure(None, norm_r, 0)
    sign = int(np.sign(np.linalg.det(jac))) if jac.shape[0] == jac.shape[1] else 0
    return RowClosure({link: LinkPose(float(q[3 * k]), float(q[3 * k + 1]), float(q[3 * k + 2]))
                       for k, link in enumerate(group.links)}, norm_r, sign)
