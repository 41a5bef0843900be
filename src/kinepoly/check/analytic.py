"""The independent analytic solution: body coordinates, constraint equations, Newton, linear solves.

This module cross-checks the graphical construction. It shares no code with
``kinepoly.engine.construct`` or ``kinepoly.engine.position``: it only reads the mechanism (links,
points in their own frames, joints, input) and writes frozen values.

The work is shared out, one job a module:

* :mod:`~kinepoly.check.coordinates`: body coordinates q and each link's place and motion;
* :mod:`~kinepoly.check.constraints`: the constraint equations Phi(q, t) = 0, with their
  Jacobian Phi_q and right-hand sides nu (velocity) and gamma (acceleration);
* :mod:`~kinepoly.check.newton`: the dimensionless system, damped Newton for the position,
  and the linear solves, each checked for its condition first;
* :mod:`~kinepoly.check.start`: the start pose of Newton;
* :mod:`~kinepoly.check.given`: a ``[given]`` scene, one free body;
* :mod:`~kinepoly.check.rolling`, :mod:`~kinepoly.check.spline_contact`: gear pairs and spline cams (loaded only
  for a mechanism that has them).

This module puts them together: :func:`solve_analytic` and its :class:`AnalyticSolution`.
"""

from __future__ import annotations

import math

import numpy as np
from msgspec import Struct

from kinepoly.check.constraints import Constraint, constraints_of
from kinepoly.check.coordinates import (
    J,
    Layout,
    Vec,
    as_array,
    as_pair,
    bodies,
    mechanism_size,
    plain_float,
    rotation,
)
from kinepoly.check.newton import (
    NEWTON_REL_TOL,
    SINGULAR_CONDITION,
    IndexedLayout,
    System,
    newton,
    singular_error,
    solve_scaled,
)
from kinepoly.check.start import complete_start
from kinepoly.errors import SceneError
from kinepoly.geom.tolerances import RIGID_REL_TOL
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.scene.link_point import LinkPoint
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput

__all__ = [
    "NEWTON_REL_TOL",
    "RIGID_REL_TOL",
    "SINGULAR_CONDITION",
    "AnalyticSolution",
    "solve_analytic",
    "velocity_condition",
]


# --------------------------------------------------------------------------------------------
# The solution
# --------------------------------------------------------------------------------------------


class AnalyticSolution(Struct, frozen=True):
    """Poses, velocities and accelerations of every link at one instant, analytically.

    ``linear_velocity`` and ``linear_acceleration`` are those of each link's frame origin;
    ``alpha`` and ``linear_acceleration`` are None when accelerations were not asked.
    ``condition_number`` is the 2-norm condition of the dimensionless velocity Jacobian;
    ``position_residual`` the largest |Phi| left by Newton, in lengths (angle rows times L).
    """

    poses: dict[str, LinkPose]
    omega: dict[str, float]
    alpha: dict[str, float] | None
    linear_velocity: dict[str, Vec]
    linear_acceleration: dict[str, Vec] | None
    condition_number: float
    position_residual: float

    def position(self, link: str, local: Vec) -> Vec:
        """r = r_k + A_k p."""
        return self.poses[link].world(local)

    def _arm(self, link: str, local: Vec) -> np.ndarray:
        """A_k p: from the link's frame origin to the point, in frame coordinates."""
        pose = self.poses[link]
        return np.asarray(rotation(pose.theta) @ as_array(local), dtype=float)

    def velocity(self, link: str, local: Vec) -> Vec:
        """v = r_dot_k + omega_k J A_k p."""
        arm = self._arm(link, local)
        return as_pair(as_array(self.linear_velocity[link]) + self.omega[link] * (J @ arm))

    def acceleration(self, link: str, local: Vec) -> Vec:
        """a = r_ddot_k + alpha_k J A_k p - omega_k^2 A_k p."""
        if self.alpha is None or self.linear_acceleration is None:
            raise ValueError("accelerations were not solved: call solve_analytic(..., with_acceleration=True)")
        arm = self._arm(link, local)
        w = self.omega[link]
        return as_pair(as_array(self.linear_acceleration[link]) + self.alpha[link] * (J @ arm) - w * w * arm)

    def material_point(self, mechanism: Mechanism, label: str) -> tuple[str, Vec]:
        """The link and local coordinates a label names.

        ``"A"`` is point A of its first owner link (scene order); ``"A@4"`` is the material point
        of link 4 that is now under A.
        """
        named = LinkPoint.parse(label)
        point, on = named.point, named.link or ""
        try:
            owner = mechanism.owner(point)
        except KeyError:
            raise KeyError(f"{label}: no link has a point {point!r}") from None
        local = mechanism.local(owner, point)
        if not on:
            return owner, local
        if on not in self.poses:
            raise KeyError(f"{label}: there is no link {on!r}")
        return on, self.poses[on].to_local(self.position(owner, local))

    def point_position(self, mechanism: Mechanism, label: str) -> Vec:
        return self.position(*self.material_point(mechanism, label))

    def point_velocity(self, mechanism: Mechanism, label: str) -> Vec:
        return self.velocity(*self.material_point(mechanism, label))

    def point_acceleration(self, mechanism: Mechanism, label: str) -> Vec:
        return self.acceleration(*self.material_point(mechanism, label))

    def slider_values(self, mechanism: Mechanism, name: str) -> dict[str, float | Vec]:
        """s, s_dot (and s_ddot, coriolis when accelerations were solved) of a slider.

        With P the block's point and P@g the guide's material point under it:
        s = e . (P - T), v_rel = v_P - v_P@g = s_dot e,
        a_P = a_P@g + s_ddot e + coriolis, coriolis = 2 omega_g J v_rel.
        """
        slider = mechanism.slider(name)
        block, guide = slider.block, slider.guide
        s_b = mechanism.local(block, slider.point)
        p = as_array(self.position(block, s_b))
        e = rotation(self.poses[guide].theta + slider.angle_rad) @ np.array([1.0, 0.0])
        t = as_array(self.position(guide, slider.through))
        under = self.poses[guide].to_local(as_pair(p))
        v_rel = as_array(self.velocity(block, s_b)) - as_array(self.velocity(guide, under))
        out: dict[str, float | Vec] = {"s": float(e @ (p - t)), "s_dot": float(e @ v_rel)}
        if self.alpha is not None:
            coriolis = 2.0 * self.omega[guide] * (J @ v_rel)
            a_rel = as_array(self.acceleration(block, s_b)) - as_array(self.acceleration(guide, under))
            out["s_ddot"] = float(e @ (a_rel - coriolis))
            out["coriolis"] = as_pair(coriolis)
        return out



# --------------------------------------------------------------------------------------------
# The input, in words
# --------------------------------------------------------------------------------------------


def _where(mechanism: Mechanism) -> str:
    """The input value, named as a user wrote it."""
    scene = mechanism.scene
    inp = scene.input
    if isinstance(inp, LinkInput):
        if scene.units.angle == "deg":
            return f"input link {inp.link} at angle {math.degrees(inp.angle_rad):.10g} deg"
        return f"input link {inp.link} at angle {inp.angle_rad:.10g} rad"
    if isinstance(inp, SliderInput):
        return f"input slider {inp.slider} at s = {inp.s:.10g} {scene.units.length}"
    return "the given motion"


# --------------------------------------------------------------------------------------------
# Solve
# --------------------------------------------------------------------------------------------


def solve_analytic(mechanism: Mechanism, start: dict[str, LinkPose], *, with_acceleration: bool) -> AnalyticSolution:
    """Solve position (Newton from ``start``), velocity and, if asked, acceleration analytically.

    ``start``: a pose of each moving link near the wanted assembly (the construction's pose);
    missing links are guessed from their neighbours. A ``[given]`` scene needs no start.
    Raises AssemblyError when Newton cannot close the loops and SingularityError when the
    velocity Jacobian is singular at the input.
    """
    if mechanism.ground is None or isinstance(mechanism.scene.input, GivenInput):
        return _given_solution(mechanism, with_acceleration=with_acceleration)
    layout, system, q, residual = _closed(mechanism, start)
    jac = system.scaled_jacobian(q)
    condition = system.condition(jac)  # each group's own, block by block (linear in the number of groups)
    if condition > SINGULAR_CONDITION:
        raise singular_error(system, condition)
    q_dot = solve_scaled(system, jac, system.nu())
    q_ddot = solve_scaled(system, jac, system.gamma(q, q_dot)) if with_acceleration else None
    return _solution(layout, q, q_dot, q_ddot, condition, residual)


def velocity_condition(mechanism: Mechanism, start: dict[str, LinkPose]) -> float:
    """The condition number k of the dimensionless velocity equations at the scene's input, the position closed by
    Newton from ``start`` as ``solve_analytic`` closes it (which raises where k is above SINGULAR_CONDITION: this
    gives it, for the error estimate of a position that close to a dead point, ``check.estimate``)."""
    _, system, q, _ = _closed(mechanism, start)
    return system.condition(system.scaled_jacobian(q))


def _closed(mechanism: Mechanism, start: dict[str, LinkPose]) -> tuple[IndexedLayout, System, np.ndarray, float]:
    """The layout and the equations of a mechanism driven by [input], and its position closed by Newton from
    ``start``, with the final residual."""
    ground = mechanism.ground
    assert ground is not None
    moving = tuple(name for name in mechanism.link_names if name != ground)
    layout = IndexedLayout(moving, ground, mechanism_size(mechanism))
    poses0 = complete_start(mechanism, start) if mechanism.scene.gears else {}
    q0 = (np.array([v for link in moving for v in (poses0[link].x, poses0[link].y, poses0[link].theta)])
          if poses0 else None)
    system = System((*constraints_of(mechanism), *_higher_pairs(mechanism, layout, q0)), layout, _where(mechanism),
                    mechanism.scene.source)
    if len(system.row_scale) != layout.n:
        raise SceneError(
            f"{system.source}: links: {len(system.row_scale)} constraint equations for {layout.n} body "
            "coordinates; expected as many inputs as the mechanism has degrees of freedom"
        )

    if q0 is None:
        poses0 = complete_start(mechanism, start)
        q0 = np.array([v for link in moving for v in (poses0[link].x, poses0[link].y, poses0[link].theta)])
    q, residual = newton(system, q0)
    return layout, system, q, residual


def _solution(
    layout: Layout,
    q: np.ndarray,
    q_dot: np.ndarray,
    q_ddot: np.ndarray | None,
    condition: float,
    residual: float,
) -> AnalyticSolution:
    poses = {layout.ground: LinkPose(0.0, 0.0, 0.0)}
    omega = {layout.ground: 0.0}
    vel: dict[str, Vec] = {layout.ground: (0.0, 0.0)}
    alpha: dict[str, float] | None = {layout.ground: 0.0} if q_ddot is not None else None
    acc: dict[str, Vec] | None = {layout.ground: (0.0, 0.0)} if q_ddot is not None else None
    for link in layout.moving:
        k = layout.column(link)
        assert k is not None
        poses[link] = LinkPose(plain_float(q[k]), plain_float(q[k + 1]), plain_float(q[k + 2]))
        omega[link] = plain_float(q_dot[k + 2])
        vel[link] = (plain_float(q_dot[k]), plain_float(q_dot[k + 1]))
        if q_ddot is not None and alpha is not None and acc is not None:
            alpha[link] = plain_float(q_ddot[k + 2])
            acc[link] = (plain_float(q_ddot[k]), plain_float(q_ddot[k + 1]))
    return AnalyticSolution(poses, omega, alpha, vel, acc, condition, residual)


def _higher_pairs(mechanism: Mechanism, layout: IndexedLayout, q0: np.ndarray | None) -> list[Constraint]:
    """The rows of the gear pairs (their constants taken at ``q0``, given where the mechanism has gears) and of the
    spline cams; their modules are loaded only for a mechanism that has such pairs."""
    out: list[Constraint] = []
    if q0 is not None:
        from kinepoly.check.rolling import rolling_constraints

        out += rolling_constraints(mechanism, bodies(layout, q0))
    if any(cam.is_spline for cam in mechanism.scene.cams):
        from kinepoly.check.spline_contact import spline_contacts

        out += spline_contacts(mechanism)
    return out


def _given_solution(mechanism: Mechanism, *, with_acceleration: bool) -> AnalyticSolution:
    """A ``[given]`` scene's one body (:func:`kinepoly.check.given.solve_given`) as an AnalyticSolution."""
    from kinepoly.check.given import solve_given  # only a [given] scene has one free body

    motion = solve_given(mechanism, with_acceleration=with_acceleration)
    link = motion.link
    return AnalyticSolution(
        poses={link: LinkPose(0.0, 0.0, 0.0)},
        omega={link: motion.omega},
        alpha=None if motion.alpha is None else {link: motion.alpha},
        linear_velocity={link: motion.velocity},
        linear_acceleration=None if motion.acceleration is None else {link: motion.acceleration},
        condition_number=motion.condition_number,
        position_residual=0.0,
    )
