"""Velocities and accelerations of a group that is not a dyad, over rows: one linear solve per row.

Such a group (a triad, say) has no two-line construction of a dyad: its tips come from one
linear solve of the joint equations, and the step says so. Unknowns per link k: the velocity
(acceleration) of its frame origin and omega_k (alpha_k). A pin at P of links i and j:
v_i(P) = v_j(P). A slider: omega_b = omega_g, and the block's point moves relative to the
guide only along the slide (for accelerations after taking off the Coriolis term). A spline cam whose
follower floats in the group: at this instant the pair is the equivalent link K W (K the profile's centre
of curvature, a point of the cam; ``engine.cam_polygons``), whose length does not change to second order:
(v_W - v_K) . e = 0, e the unit vector from K to W, and (a_W - a_K) . e = -|v_W - v_K|^2 / |K W| (its
normal term; the link's own omega and alpha drop out of these two rows). A flat face: a block pinned to the
cam at K slides along the face, so the follower's point under K moves relative to K only along the face:
(v_K@f - v_K) . m = 0, m the face's normal, and (a_K@f - a_K) . m = -a^c . m (a^c = 2 omega_f x the block's
velocity over the face).
All rows are solved by one stacked ``numpy.linalg.solve``; a row whose equations (made
dimensionless) have a condition number above ``SINGULAR_CONDITION`` is singular.

A group of class 4 once its inputs are given (``assur_class``: four links, two links held by a driven
joint counted as one, whose moving links close a contour of four) is beyond the constructions of the
course, which reach class 3; its step says so, and lays the relative vectors the solve gives: each
link's from its first joint to its others (for accelerations the normal term, then the tangential one),
and each slider's block over its guide.
"""

from __future__ import annotations

import numpy as np

from kinepoly.engine.cam_contact import centre_label, face_direction
from kinepoly.engine.groups import NewtonGroup
from kinepoly.engine.inputs import describe_input
from kinepoly.engine.polygon import JointSolve, Polygon
from kinepoly.engine.results import AccelerationContext
from kinepoly.engine.steps import DrawnVector, Step
from kinepoly.errors import SingularityError
from kinepoly.geom.arrays import Points, Reals, turn
from kinepoly.geom.tolerances import NEAR_SINGULAR_CONDITION, SINGULAR_CONDITION
from kinepoly.model.mechanism import Revolute
from kinepoly.scene.spec import CamSpec, SliderSpec

__all__ = ["NEAR_SINGULAR_CONDITION", "SINGULAR_CONDITION", "acceleration_by_linear_solve", "assur_class",
           "velocity_by_linear_solve"]


def _joint_links(joint: Revolute | SliderSpec) -> tuple[str, str]:
    return joint.links if isinstance(joint, Revolute) else (joint.block, joint.guide)


def _origin(polygon: Polygon, link: str) -> Points:
    return polygon.positions.poses[link].origin


def _system(polygon: Polygon, group: NewtonGroup, extra: dict[tuple[str, str], Points]) -> tuple[Reals, Reals]:
    """The joint equations M u = rhs, one system per row: (N, m, n), (N, m)."""
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
    for cam in group.cams:  # the equivalent link K W: no stretch along e; a flat face's block: no motion along m
        row_x, row_y = np.zeros((n, size)), np.zeros((n, size))
        w, k = _follower_point(cam), centre_label(cam)
        if cam.kind == "flat":
            e = 1j * face_direction(polygon.positions.poses, cam)
        else:
            e = polygon.world(w) - polygon.world(k)
            e = e / np.abs(e)
        known = term(cam.follower, w, 1.0, row_x, row_y) - polygon.tip(cam.cam, k)
        rows.append(e.real[:, None] * row_x + e.imag[:, None] * row_y)
        rhs.append(extra.get(("contact", cam.name), polygon.zero).real - (e.real * known.real + e.imag * known.imag))
    order = 1 if polygon.kind == "velocity" else 2
    for drive in group.drives:  # one more equation each: the input's rate
        if isinstance(drive.joint, Revolute):  # omega_moving - omega_base = omega of the motor
            rate_row, known_rate = np.zeros((n, size)), np.full(n, -drive.rate(order))
            for link, sign in ((drive.moving, 1.0), (drive.base, -1.0)):
                if link in links:
                    rate_row[:, 3 * links.index(link) + 2] += sign
                elif (value := polygon.rate_of(link)) is not None:
                    known_rate = known_rate + sign * value
            rows.append(rate_row)
            rhs.append(-known_rate)
            continue
        slider = drive.joint  # e . (tip of the block's point - tip of the guide's) = s_dot (s_ddot)
        row_x, row_y = np.zeros((n, size)), np.zeros((n, size))
        known = term(slider.block, slider.point, 1.0, row_x, row_y) + term(slider.guide, slider.point, -1.0, row_x,
                                                                            row_y)
        along = polygon.positions.poses[slider.guide].rotation * turn(slider.angle_rad)
        rows.append(along.real[:, None] * row_x + along.imag[:, None] * row_y)
        rhs.append(drive.rate(order) - (along.real * known.real + along.imag * known.imag))
    return np.stack(rows, axis=1), np.stack(rhs, axis=1)


def _condition(matrix: Reals) -> Reals:
    """The condition number of each row's equations made dimensionless: the rate columns hold arms
    (lengths) and are divided by the row's largest arm L; the rows that hold only rates (a block
    turning with its guide) are multiplied by L. It does not change when the mechanism is scaled."""
    scaled = matrix.copy()
    not_rate = np.arange(matrix.shape[2]) % 3 != 2
    has_length = np.any(matrix[:, :, not_rate] != 0, axis=2)
    arms = np.where(has_length[:, :, None], np.abs(matrix[:, :, 2::3]), 0.0)
    length = np.max(arms.reshape(len(matrix), -1), axis=1, initial=0.0)
    length = np.where(length > 0.0, length, 1.0)
    scaled[:, :, 2::3] /= length[:, None, None]
    scaled *= np.where(has_length, 1.0, length[:, None])[:, :, None]
    return np.asarray(np.linalg.cond(scaled))


def _solve(polygon: Polygon, group: NewtonGroup, matrix: Reals, rhs: Reals) -> Reals:
    """Every row's system solved at once; rows whose scaled matrix is singular are flagged (raised when strict)."""
    if matrix.shape[1] != matrix.shape[2]:
        raise SingularityError(f"the {polygon.kind} equations of group {group.name} are not square")
    matrix = np.where(np.isfinite(matrix), matrix, 0.0)
    rhs = np.where(np.isfinite(rhs), rhs, 0.0)
    condition = _condition(matrix)
    singular = ~(condition <= SINGULAR_CONDITION)
    if polygon.strict and singular[0]:
        joints = ", ".join(j.name for j in group.joints)
        raise SingularityError(
            f"singular position at {describe_input(polygon.mechanism)}: the {polygon.kind} equations of group "
            f"{group.name} (joints {joints}) have condition number {float(condition[0]):.3g}, above "
            f"{SINGULAR_CONDITION:.0e}: its links can move with the input held (a change point), so their "
            f"{polygon.kind}s are not determined")
    polygon.crossings.append(JointSolve(polygon.kind, group.name, np.where(singular, np.inf, condition)))
    matrix[singular] = np.eye(matrix.shape[1])
    return np.asarray(np.linalg.solve(matrix, rhs[:, :, None])[:, :, 0])


def _follower_point(cam: CamSpec) -> str:
    """The follower's point the pair's equation is written for: W, or under K for a flat face."""
    return centre_label(cam) if cam.kind == "flat" else cam.point or ""


def _group_points(group: NewtonGroup) -> list[tuple[str, str]]:
    """(link, point) of the group's joints and of its floating followers' contact points (W, or K under a face)."""
    return [*((link, joint.point) for joint in group.joints for link in _joint_links(joint)),
            *((cam.follower, _follower_point(cam)) for cam in group.cams)]


def _store(polygon: Polygon, group: NewtonGroup, u: Reals, extra: dict[tuple[str, str], Points]) -> list[str]:
    for k, link in enumerate(group.links):
        polygon.set_rate(link, u[:, 3 * k + 2])
    found = []
    for link, point in _group_points(group):
        if link in group.links and polygon.label(link, point) not in polygon.tips:
            k = 3 * group.links.index(link)
            r = polygon.world(point) - _origin(polygon, link)
            tip = u[:, k] + 1j * u[:, k + 1] + u[:, k + 2] * (1j * r) + extra.get((link, point), polygon.zero)
            found.append(polygon.add_tip(link, point, np.asarray(tip)))
    return found


def assur_class(group: NewtonGroup) -> int | None:
    """4 where the group, its driven joints' links taken as one, is four links whose joints inside the group
    close a contour of four (two outer joints); None for any other shape (not named)."""
    inside = set(group.links)
    driven = {d.joint for d in group.drives if d.moving in inside and d.base in inside}
    joints = [j for j in group.joints if j not in driven]
    inner = [j for j in joints if set(_joint_links(j)) <= inside]
    if group.cams or len(group.links) - len(driven) != 4 or len(joints) != 6 or len(inner) != 4:
        return None
    return 4


def _relative_vectors(polygon: Polygon, group: NewtonGroup) -> tuple[DrawnVector, ...]:
    """Each link's relative vectors from its first joint to its others, and each slider's block over its guide."""
    sym = polygon.symbol
    out: list[DrawnVector] = []
    for link in group.links:
        labels = list(dict.fromkeys(polygon.label(link, point) for owner, point in _group_points(group)
                                    if owner == link))
        points = {polygon.label(link, point): point for owner, point in _group_points(group) if owner == link}
        if len(labels) < 2:
            continue
        ref = labels[0]
        start = polygon.tip(link, points[ref])
        for label in labels[1:]:
            end = polygon.tip(link, points[label])
            if polygon.kind == "velocity":
                out.append(DrawnVector(f"v_{label}/{ref}", polygon.vec(start), polygon.vec(end), "relative"))
                continue
            w = polygon.omega_of(link)
            r = polygon.world(points[label]) - polygon.world(points[ref])
            middle = np.asarray(start + (polygon.normal_sign * w * w) * r)
            out += [DrawnVector(f"a^n_{label}/{ref}", polygon.vec(start), polygon.vec(middle), "normal"),
                    DrawnVector(f"a^t_{label}/{ref}", polygon.vec(middle), polygon.vec(end), "tangential")]
    for joint in group.joints:
        if isinstance(joint, SliderSpec):
            block, guide = polygon.label(joint.block, joint.point), polygon.label(joint.guide, joint.point)
            out.append(DrawnVector(f"{sym}_{block}/{guide}", polygon.vec(polygon.tip(joint.guide, joint.point)),
                                   polygon.vec(polygon.tip(joint.block, joint.point)), "relative"))
    return tuple(out)


def _record(polygon: Polygon, group: NewtonGroup, found: list[str]) -> None:
    if polygon.record:
        order = assur_class(group)
        tips = ", ".join(f.lower() for f in found)
        links = [c for c in group.cams if c.kind != "flat"]
        faces = [c for c in group.cams if c.kind == "flat"]
        equivalent = ", ".join(f"{cam.name} {centre_label(cam)}{cam.point} {centre_label(cam)} {cam.point}"
                               for cam in links)  # pair, link, K, W
        face = ", ".join(f"{cam.name} {centre_label(cam)} {cam.follower}" for cam in faces)  # pair, K, follower
        polygon.step(Step(polygon=polygon.kind, kind="linear-solve", equation=f"joint equations of group {group.name}"
                          + "".join(f" with the equivalent link {centre_label(c)}{c.point}" for c in links)
                          + "".join(f" with the block pinned at {centre_label(c)} on the face of {c.follower}"
                                    for c in faces),
                          result=tips, vectors=_relative_vectors(polygon, group) if order else (),
                          params=(("group", group.name), ("links", ", ".join(group.links)),
                                  ("tips", tips), *((("equivalent", equivalent),) if links else ()),
                                  *((("face", face),) if faces else ()),
                                  *((("assur_class", order),) if order else ()))))


def velocity_by_linear_solve(polygon: Polygon, group: NewtonGroup, sliding: dict[str, Points]) -> None:
    matrix, rhs = _system(polygon, group, {})
    _record(polygon, group, _store(polygon, group, _solve(polygon, group, matrix, rhs), {}))
    for joint in group.joints:
        if isinstance(joint, SliderSpec):
            sliding[joint.name] = np.asarray(polygon.tip(joint.block, joint.point) - polygon.tip(joint.guide,
                                                                                                  joint.point))


def acceleration_by_linear_solve(ctx: AccelerationContext, group: NewtonGroup) -> None:
    polygon = ctx.b
    extra: dict[tuple[str, str], Points] = {}
    for link, point in _group_points(group):
        if link in group.links:
            r = polygon.world(point) - _origin(polygon, link)
            w = polygon.omega_of(link)
            extra[(link, point)] = np.asarray((ctx.rules.normal * w * w) * r)
    for cam in group.cams:  # the equivalent link's normal term along e: -|v_W - v_K|^2 / |K W|
        w_point, k = _follower_point(cam), centre_label(cam)
        v_rel = ctx.v_tip(cam.follower, w_point) - ctx.v_tip(cam.cam, k)
        if cam.kind == "flat":  # -a^c . m, the block's velocity over the face -v_rel
            m = 1j * face_direction(polygon.positions.poses, cam)
            coriolis = ctx.rules.coriolis * 2.0 * polygon.omega_of(cam.follower) * (1j * -v_rel)
            extra[("contact", cam.name)] = np.asarray(-(coriolis.real * m.real + coriolis.imag * m.imag) + 0j)
            continue
        length = np.abs(polygon.world(w_point) - polygon.world(k))
        extra[("contact", cam.name)] = np.asarray(ctx.rules.normal * np.abs(v_rel) ** 2 / length + 0j)
    for joint in group.joints:
        if isinstance(joint, SliderSpec):
            v_rel = ctx.v_tip(joint.block, joint.point) - ctx.v_tip(joint.guide, joint.point)
            w = polygon.omega_of(joint.guide)
            extra[("slide", joint.name)] = np.asarray(-(ctx.rules.coriolis * 2.0 * w) * (1j * v_rel))
    matrix, rhs = _system(polygon, group, extra)
    _record(polygon, group, _store(polygon, group, _solve(polygon, group, matrix, rhs), extra))
    for joint in group.joints:
        if isinstance(joint, SliderSpec):
            ctx.slide_values(joint, joint.block, joint.point)
