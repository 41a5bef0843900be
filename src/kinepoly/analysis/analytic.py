"""The independent analytic solution: body coordinates, constraint equations, Newton, linear solves.

This module cross-checks the graphical construction. It shares no code with
``kinepoly.construct`` or ``kinepoly.solve.position``: it only reads the mechanism (links,
points in their own frames, joints, input) and writes frozen values.

Coordinates
-----------
Every moving link k has q_k = (x_k, y_k, theta_k), its ``LinkPose``: a point with local
coordinates p is at r_k + A(theta_k) p in the frame, A(theta) the rotation by theta. The
ground has the constant pose (0, 0, 0). With J = [[0, -1], [1, 0]] (a quarter turn ccw),
dA/dtheta = J A, so a point's velocity is v = r_dot + omega J A p and its acceleration
a = r_ddot + alpha J A p - omega^2 A p.

Constraints Phi(q, t) = 0
-------------------------
* revolute at P of links i and j (2 rows):
  r_i + A_i p_i - r_j - A_j p_j = 0
* slider, block b on guide g, block point s_b, line through t_g at angle c in g's frame,
  e_g = (cos c, sin c), n_g = J e_g (2 rows):
  theta_b - theta_g - c = 0  and  n . d = 0,
  where n = A_g n_g, d = r_b + A_b s_b - r_g - A_g t_g; the slider variable is s = e . d, e = A_g e_g
* driver (1 row): theta_link - angle = 0 (``LinkInput``) or e . d - s = 0 (``SliderInput``).

Velocity: Phi_q q_dot = nu (nu = omega or s_dot for the driver row, 0 elsewhere).
Acceleration: Phi_q q_ddot = gamma, gamma = (driver's alpha or s_ddot) - (the terms of
d^2 Phi / dt^2 quadratic in the velocities); each constraint documents its own gamma.

Position: damped Newton from a start pose; every linear solve is checked for its condition
first. The Jacobian is made dimensionless before it is judged or solved: theta columns are
multiplied by the mechanism's size L (theta * L is a length) and the angle rows by L.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from kinepoly.errors import AssemblyError, SceneError, SingularityError
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import GivenInput, GivenPoint, LinkInput, SliderInput, SliderSpec
from kinepoly.solve.pose import LinkPose

__all__ = [
    "NEWTON_REL_TOL",
    "RIGID_REL_TOL",
    "SINGULAR_CONDITION",
    "AnalyticSolution",
    "solve_analytic",
]

Vec = tuple[float, float]

SINGULAR_CONDITION = 1e7
"""A (dimensionless) velocity Jacobian whose 2-norm condition number exceeds this is singular.

Near a dead-centre the condition grows like 1 / sqrt(distance of the input from it); at the
dead-centre itself Newton finds the (double) root only to about sqrt(unit roundoff), which
leaves a condition of 1e8 to 1e9. Ordinary poses have 1 to 1e3; 1e7 flags inputs within
about 1e-12 rad of a dead-centre of a well-proportioned linkage.
"""

NEWTON_REL_TOL = 1e-12
"""Newton stops when every residual is below this times the mechanism's size (lengths)."""

RIGID_REL_TOL = 1e-9
"""Given velocities (accelerations) of a rigid body may break rigidity by this much, relative."""

_MAX_NEWTON_STEPS = 100
_J = np.array([[0.0, -1.0], [1.0, 0.0]])


def _rot(theta: float) -> np.ndarray:
    """A(theta), the rotation matrix by theta (ccw)."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def _vec(v: Vec) -> np.ndarray:
    return np.array([float(v[0]), float(v[1])])


def _f(x: float) -> float:
    """A plain float, with -0.0 made 0.0."""
    return float(x) + 0.0


def _tup(v: np.ndarray) -> Vec:
    return (_f(v[0]), _f(v[1]))


# --------------------------------------------------------------------------------------------
# The solution
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class AnalyticSolution:
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
        return np.asarray(_rot(pose.theta) @ _vec(local), dtype=float)

    def velocity(self, link: str, local: Vec) -> Vec:
        """v = r_dot_k + omega_k J A_k p."""
        arm = self._arm(link, local)
        return _tup(_vec(self.linear_velocity[link]) + self.omega[link] * (_J @ arm))

    def acceleration(self, link: str, local: Vec) -> Vec:
        """a = r_ddot_k + alpha_k J A_k p - omega_k^2 A_k p."""
        if self.alpha is None or self.linear_acceleration is None:
            raise ValueError("accelerations were not solved: call solve_analytic(..., with_acceleration=True)")
        arm = self._arm(link, local)
        w = self.omega[link]
        return _tup(_vec(self.linear_acceleration[link]) + self.alpha[link] * (_J @ arm) - w * w * arm)

    def material_point(self, mechanism: Mechanism, label: str) -> tuple[str, Vec]:
        """The link and local coordinates a label names.

        ``"A"`` is point A of its first owner link (scene order); ``"A@4"`` is the material point
        of link 4 that is now under A.
        """
        point, _, on = label.partition("@")
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
        p = _vec(self.position(block, s_b))
        e = _rot(self.poses[guide].theta + slider.angle_rad) @ np.array([1.0, 0.0])
        t = _vec(self.position(guide, slider.through))
        under = self.poses[guide].to_local(_tup(p))
        v_rel = _vec(self.velocity(block, s_b)) - _vec(self.velocity(guide, under))
        out: dict[str, float | Vec] = {"s": float(e @ (p - t)), "s_dot": float(e @ v_rel)}
        if self.alpha is not None:
            coriolis = 2.0 * self.omega[guide] * (_J @ v_rel)
            a_rel = _vec(self.acceleration(block, s_b)) - _vec(self.acceleration(guide, under))
            out["s_ddot"] = float(e @ (a_rel - coriolis))
            out["coriolis"] = _tup(coriolis)
        return out


# --------------------------------------------------------------------------------------------
# Body coordinates
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Layout:
    """Which columns of q belong to which link, the ground, and the mechanism's size L."""

    moving: tuple[str, ...]
    ground: str
    size: float

    def column(self, link: str) -> int | None:
        """The column of x_link in q (y, theta follow), None for the ground."""
        return None if link == self.ground else 3 * self.moving.index(link)

    @property
    def n(self) -> int:
        return 3 * len(self.moving)


@dataclass(frozen=True)
class _Body:
    """One link's place and motion: r, theta, A(theta), omega, r_dot (zeros for the ground).

    theta is kept as q has it (not wrapped), so angle rows of Phi are exactly linear.
    """

    r: np.ndarray
    theta: float
    A: np.ndarray
    omega: float
    r_dot: np.ndarray


def _bodies(layout: _Layout, q: np.ndarray, q_dot: np.ndarray | None = None) -> dict[str, _Body]:
    """Every link's _Body from q (and q_dot; zero velocities without it)."""
    zero = np.zeros(2)
    out = {layout.ground: _Body(zero, 0.0, np.eye(2), 0.0, zero)}
    for link in layout.moving:
        k = layout.column(link)
        assert k is not None
        theta = float(q[k + 2])
        w, rd = (0.0, zero) if q_dot is None else (float(q_dot[k + 2]), q_dot[k : k + 2].copy())
        out[link] = _Body(q[k : k + 2].copy(), theta, _rot(theta), w, rd)
    return out


def _size(mechanism: Mechanism) -> float:
    """L: the largest distance of any named point (or slider line point) from its link's origin."""
    lengths = [math.hypot(*p.local) for link in mechanism.scene.links for p in link.points]
    lengths += [math.hypot(*s.through) for s in mechanism.sliders]
    inp = mechanism.scene.input
    if isinstance(inp, SliderInput):
        lengths.append(abs(inp.s))
    size = max(lengths, default=0.0)
    return size if size > 0.0 else 1.0


# --------------------------------------------------------------------------------------------
# Constraints: each knows its rows of Phi, Phi_q, nu and gamma
# --------------------------------------------------------------------------------------------


class _Constraint(Protocol):
    """Rows of Phi, Phi_q, nu and gamma; ``angle_rows`` flags the rows that are angles."""

    @property
    def angle_rows(self) -> tuple[bool, ...]: ...

    def phi(self, b: dict[str, _Body]) -> np.ndarray: ...

    def jacobian(self, b: dict[str, _Body], layout: _Layout) -> np.ndarray: ...

    def nu(self) -> np.ndarray: ...

    def gamma(self, b: dict[str, _Body]) -> np.ndarray: ...


def _put(out: np.ndarray, layout: _Layout, link: str, d_r: np.ndarray, d_theta: np.ndarray) -> None:
    """Add a link's partial derivatives (by r: rows x 2, by theta: rows) to Jacobian rows."""
    k = layout.column(link)
    if k is not None:
        out[:, k : k + 2] += d_r
        out[:, k + 2] += d_theta


@dataclass(frozen=True)
class _Pin:
    """Revolute: r_i + A_i p_i - r_j - A_j p_j = 0.

    Phi_q: by r_i I, by theta_i J A_i p_i; by r_j -I, by theta_j -J A_j p_j.  nu = 0.
    gamma = omega_i^2 A_i p_i - omega_j^2 A_j p_j.
    """

    i: str
    j: str
    p_i: np.ndarray
    p_j: np.ndarray
    angle_rows: tuple[bool, ...] = (False, False)

    def phi(self, b: dict[str, _Body]) -> np.ndarray:
        bi, bj = b[self.i], b[self.j]
        return np.asarray(bi.r + bi.A @ self.p_i - bj.r - bj.A @ self.p_j, dtype=float)

    def jacobian(self, b: dict[str, _Body], layout: _Layout) -> np.ndarray:
        out = np.zeros((2, layout.n))
        _put(out, layout, self.i, np.eye(2), _J @ b[self.i].A @ self.p_i)
        _put(out, layout, self.j, -np.eye(2), -(_J @ b[self.j].A @ self.p_j))
        return out

    def nu(self) -> np.ndarray:
        return np.zeros(2)

    def gamma(self, b: dict[str, _Body]) -> np.ndarray:
        bi, bj = b[self.i], b[self.j]
        return np.asarray(bi.omega**2 * (bi.A @ self.p_i) - bj.omega**2 * (bj.A @ self.p_j), dtype=float)


@dataclass(frozen=True)
class _AngleOffset:
    """theta_a - theta_b - offset = 0 (a slider's block turns with its guide).

    Phi_q: +1 by theta_a, -1 by theta_b; nu = 0; gamma = 0.
    """

    a: str
    b: str
    offset: float
    angle_rows: tuple[bool, ...] = (True,)

    def phi(self, b: dict[str, _Body]) -> np.ndarray:
        return np.array([b[self.a].theta - b[self.b].theta - self.offset])

    def jacobian(self, b: dict[str, _Body], layout: _Layout) -> np.ndarray:
        out = np.zeros((1, layout.n))
        _put(out, layout, self.a, np.zeros((1, 2)), np.array([1.0]))
        _put(out, layout, self.b, np.zeros((1, 2)), np.array([-1.0]))
        return out

    def nu(self) -> np.ndarray:
        return np.zeros(1)

    def gamma(self, b: dict[str, _Body]) -> np.ndarray:
        return np.zeros(1)


@dataclass(frozen=True)
class _LineCoordinate:
    """u . d - target = 0 with u = A_g u_g, d = r_b + A_b s_b - r_g - A_g t_g.

    u_g = n_g (target 0) is the slider's line equation; u_g = e_g (target s) drives a slider.

    Phi_q: by r_b u, by theta_b u . (J A_b s_b); by r_g -u, by theta_g (J u) . d - u . (J A_g t_g).
    nu = target_dot.
    With u_dot = omega_g J u, u_ddot = alpha_g J u - omega_g^2 u and
    d_dot = r_dot_b + omega_b J A_b s_b - r_dot_g - omega_g J A_g t_g, the part of
    d^2/dt^2 (u . d) quadratic in velocities is
    Q = -omega_g^2 u . d + 2 omega_g (J u) . d_dot - omega_b^2 u . A_b s_b + omega_g^2 u . A_g t_g,
    so gamma = target_ddot - Q.
    """

    block: str
    guide: str
    s_b: np.ndarray
    t_g: np.ndarray
    u_g: np.ndarray
    target: float = 0.0
    target_dot: float = 0.0
    target_ddot: float = 0.0
    angle_rows: tuple[bool, ...] = (False,)

    def _parts(self, b: dict[str, _Body]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        bb, bg = b[self.block], b[self.guide]
        u = bg.A @ self.u_g
        arm_b = bb.A @ self.s_b
        arm_g = bg.A @ self.t_g
        d = bb.r + arm_b - bg.r - arm_g
        return u, d, arm_b, arm_g

    def phi(self, b: dict[str, _Body]) -> np.ndarray:
        u, d, _, _ = self._parts(b)
        return np.array([u @ d - self.target])

    def jacobian(self, b: dict[str, _Body], layout: _Layout) -> np.ndarray:
        u, d, arm_b, arm_g = self._parts(b)
        out = np.zeros((1, layout.n))
        _put(out, layout, self.block, u[None, :], np.array([u @ (_J @ arm_b)]))
        _put(out, layout, self.guide, -u[None, :], np.array([(_J @ u) @ d - u @ (_J @ arm_g)]))
        return out

    def nu(self) -> np.ndarray:
        return np.array([self.target_dot])

    def gamma(self, b: dict[str, _Body]) -> np.ndarray:
        bb, bg = b[self.block], b[self.guide]
        u, d, arm_b, arm_g = self._parts(b)
        wb, wg = bb.omega, bg.omega
        d_dot = bb.r_dot + wb * (_J @ arm_b) - bg.r_dot - wg * (_J @ arm_g)
        quadratic = -(wg**2) * (u @ d) + 2.0 * wg * ((_J @ u) @ d_dot) - wb**2 * (u @ arm_b) + wg**2 * (u @ arm_g)
        return np.array([self.target_ddot - quadratic])


@dataclass(frozen=True)
class _AngleDriver:
    """theta_link - angle = 0: Phi_q 1 by theta_link; nu = omega; gamma = alpha."""

    link: str
    angle: float
    omega: float
    alpha: float
    angle_rows: tuple[bool, ...] = (True,)

    def phi(self, b: dict[str, _Body]) -> np.ndarray:
        return np.array([b[self.link].theta - self.angle])

    def jacobian(self, b: dict[str, _Body], layout: _Layout) -> np.ndarray:
        out = np.zeros((1, layout.n))
        _put(out, layout, self.link, np.zeros((1, 2)), np.array([1.0]))
        return out

    def nu(self) -> np.ndarray:
        return np.array([self.omega])

    def gamma(self, b: dict[str, _Body]) -> np.ndarray:
        return np.array([self.alpha])


def _slider_constraints(mechanism: Mechanism, slider: SliderSpec) -> list[_Constraint]:
    """The two rows of a slider: the block turns with the guide; its point stays on the line."""
    c = slider.angle_rad
    return [
        _AngleOffset(slider.block, slider.guide, c),
        _LineCoordinate(
            slider.block,
            slider.guide,
            _vec(mechanism.local(slider.block, slider.point)),
            _vec(slider.through),
            np.array([-math.sin(c), math.cos(c)]),
        ),
    ]


def _driver(mechanism: Mechanism) -> _Constraint:
    inp = mechanism.scene.input
    if isinstance(inp, LinkInput):
        return _AngleDriver(inp.link, inp.angle_rad, inp.omega, inp.alpha)
    if isinstance(inp, SliderInput):
        slider = mechanism.slider(inp.slider)
        c = slider.angle_rad
        return _LineCoordinate(
            slider.block,
            slider.guide,
            _vec(mechanism.local(slider.block, slider.point)),
            _vec(slider.through),
            np.array([math.cos(c), math.sin(c)]),
            inp.s,
            inp.s_dot,
            inp.s_ddot,
        )
    raise TypeError(f"no driver for input {inp!r}")


def _constraints(mechanism: Mechanism) -> list[_Constraint]:
    """Revolutes (2 rows each), sliders (2 rows each), then the driver (1 row)."""
    out: list[_Constraint] = []
    for pin in mechanism.revolutes:
        out.append(_pin(mechanism, pin))
    for slider in mechanism.sliders:
        out.extend(_slider_constraints(mechanism, slider))
    out.append(_driver(mechanism))
    return out


def _pin(mechanism: Mechanism, pin: Revolute) -> _Pin:
    i, j = pin.links
    return _Pin(i, j, _vec(mechanism.local(i, pin.point)), _vec(mechanism.local(j, pin.point)))


@dataclass(frozen=True)
class _System:
    """The constraints of a mechanism with the scaling that makes Phi_q dimensionless.

    Dr multiplies angle rows by L; Dc multiplies theta columns by 1/L. The scaled Jacobian
    Dr Phi_q Dc is what is judged and solved; x = Dc y for Dr Phi_q Dc y = Dr b.
    """

    constraints: tuple[_Constraint, ...]
    layout: _Layout
    where: str
    source: str

    @property
    def row_scale(self) -> np.ndarray:
        flags = [f for c in self.constraints for f in c.angle_rows]
        return np.array([self.layout.size if f else 1.0 for f in flags])

    @property
    def col_scale(self) -> np.ndarray:
        return np.tile([1.0, 1.0, 1.0 / self.layout.size], len(self.layout.moving))

    def bodies(self, q: np.ndarray, q_dot: np.ndarray | None = None) -> dict[str, _Body]:
        return _bodies(self.layout, q, q_dot)

    def phi(self, q: np.ndarray) -> np.ndarray:
        b = self.bodies(q)
        return np.concatenate([c.phi(b) for c in self.constraints])

    def scaled_phi(self, q: np.ndarray) -> np.ndarray:
        """Phi with angle rows in lengths (times L)."""
        return np.asarray(self.row_scale * self.phi(q), dtype=float)

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        b = self.bodies(q)
        return np.vstack([c.jacobian(b, self.layout) for c in self.constraints])

    def scaled_jacobian(self, q: np.ndarray) -> np.ndarray:
        return np.asarray(self.row_scale[:, None] * self.jacobian(q) * self.col_scale[None, :], dtype=float)

    def nu(self) -> np.ndarray:
        return np.concatenate([c.nu() for c in self.constraints])

    def gamma(self, q: np.ndarray, q_dot: np.ndarray) -> np.ndarray:
        b = self.bodies(q, q_dot)
        return np.concatenate([c.gamma(b) for c in self.constraints])


# --------------------------------------------------------------------------------------------
# Linear solves, each checked for its condition first
# --------------------------------------------------------------------------------------------


def _condition(matrix: np.ndarray) -> float:
    """2-norm condition number by SVD (inf when singular)."""
    sv = np.linalg.svd(matrix, compute_uv=False)
    return math.inf if sv[-1] == 0.0 else float(sv[0] / sv[-1])


def _singular(system: _System, condition: float) -> SingularityError:
    return SingularityError(
        f"{system.source}: input: the velocity equations are singular at {system.where}: the condition "
        f"number of the velocity Jacobian is {condition:.3g} (above {SINGULAR_CONDITION:.0e}); the mechanism "
        "is at a dead-centre (change point) there and its velocities are not determined by the input; "
        "choose another input value"
    )


def _solve_scaled(system: _System, scaled_jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve Phi_q x = rhs through the scaled system (its condition checked by the caller)."""
    y = np.linalg.solve(scaled_jac, system.row_scale * rhs)
    return system.col_scale * y


# --------------------------------------------------------------------------------------------
# Position: damped Newton
# --------------------------------------------------------------------------------------------


def _newton(system: _System, q0: np.ndarray) -> tuple[np.ndarray, float]:
    """Damped Newton on Phi(q) = 0 from q0; returns q and max |Phi| (angle rows times L).

    Step: Phi_q dq = -Phi, halved until max |Phi| strictly decreases; where the Jacobian is
    singular (condition above SINGULAR_CONDITION) the least-squares step is taken instead.
    It runs until no step decreases the residual (rounding level), so that even at a
    dead-centre, where Newton converges only linearly, the pose is as exact as doubles allow.
    Converged when max |Phi| <= NEWTON_REL_TOL * L.
    """
    tol = NEWTON_REL_TOL * system.layout.size
    q = q0.astype(float).copy()
    f = system.scaled_phi(q)
    norm = float(np.max(np.abs(f)))
    for _ in range(_MAX_NEWTON_STEPS):
        if norm == 0.0:
            break
        step = system.col_scale * _newton_step(system.scaled_jacobian(q), f)
        improved = _line_search(system, q, step, norm)
        if improved is None:
            break
        q, f, norm = improved
    if norm > tol:
        raise AssemblyError(
            f"{system.source}: the mechanism does not close at {system.where}: Newton's method on the "
            f"loop equations stopped at a residual of {norm:.3g} (tolerance {tol:.3g}, lengths); expected an "
            "input the linkage can reach and a start pose near that assembly"
        )
    return q, norm


def _newton_step(jac: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Solve jac y = -f, by least squares where jac is singular (its condition checked first)."""
    if _condition(jac) <= SINGULAR_CONDITION:
        return np.linalg.solve(jac, -f)
    return np.asarray(np.linalg.lstsq(jac, -f, rcond=None)[0], dtype=float)


def _line_search(
    system: _System, q: np.ndarray, step: np.ndarray, norm: float
) -> tuple[np.ndarray, np.ndarray, float] | None:
    """q + lam step for the first lam = 1, 1/2, 1/4, ... that decreases max |Phi|; None if none."""
    lam = 1.0
    for _ in range(40):
        trial = q + lam * step
        f_trial = system.scaled_phi(trial)
        n_trial = float(np.max(np.abs(f_trial)))
        if n_trial < norm:
            return trial, f_trial, n_trial
        lam *= 0.5
    return None


# --------------------------------------------------------------------------------------------
# Start poses
# --------------------------------------------------------------------------------------------


def _complete_start(mechanism: Mechanism, start: dict[str, LinkPose]) -> dict[str, LinkPose]:
    """Fill links missing from ``start`` from a joined link already placed (a rough guess).

    A link pinned to a placed link gets theta 0 and its pin on the placed pin; a block or guide
    of a slider gets the angle the slider demands and its point on the line's ``through``.
    Links reached by nothing start at (0, 0, 0). Newton may then find another assembly, so
    callers should pass every link.
    """
    ground = mechanism.ground or ""
    known = dict(start)
    known[ground] = LinkPose(0.0, 0.0, 0.0)
    missing = [name for name in mechanism.link_names if name not in known]
    progress = True
    while missing and progress:
        progress = False
        for link in list(missing):
            pose = _place_from_neighbour(mechanism, link, known)
            if pose is not None:
                known[link] = pose
                missing.remove(link)
                progress = True
    for link in missing:
        known[link] = LinkPose(0.0, 0.0, 0.0)
    return known


def _place_from_neighbour(mechanism: Mechanism, link: str, known: dict[str, LinkPose]) -> LinkPose | None:
    for slider in mechanism.sliders:
        if slider.block == link and slider.guide in known:
            g = known[slider.guide]
            theta = g.theta + slider.angle_rad
            return _placed(theta, mechanism.local(link, slider.point), g.world(slider.through))
        if slider.guide == link and slider.block in known:
            b = known[slider.block]
            theta = b.theta - slider.angle_rad
            return _placed(theta, slider.through, b.world(mechanism.local(slider.block, slider.point)))
    for pin in mechanism.revolutes:
        other = pin.other(link) if link in pin.links else None
        if other is not None and other in known:
            return _placed(0.0, mechanism.local(link, pin.point), known[other].world(mechanism.local(other, pin.point)))
    return None


def _placed(theta: float, local: Vec, world: Vec) -> LinkPose:
    """The pose with angle theta that puts ``local`` at ``world``."""
    arm = _rot(theta) @ _vec(local)
    return LinkPose(world[0] - float(arm[0]), world[1] - float(arm[1]), theta)


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
        return _solve_given(mechanism, with_acceleration=with_acceleration)
    ground = mechanism.ground
    moving = tuple(name for name in mechanism.link_names if name != ground)
    layout = _Layout(moving, ground, _size(mechanism))
    system = _System(tuple(_constraints(mechanism)), layout, _where(mechanism), mechanism.scene.source)
    if len(system.row_scale) != layout.n:
        raise SceneError(
            f"{system.source}: links: {len(system.row_scale)} constraint equations for {layout.n} body "
            "coordinates; expected a mechanism of mobility one with one input"
        )

    poses0 = _complete_start(mechanism, start)
    q0 = np.array([v for link in moving for v in (poses0[link].x, poses0[link].y, poses0[link].theta)])
    q, residual = _newton(system, q0)

    jac = system.scaled_jacobian(q)
    condition = _condition(jac)
    if condition > SINGULAR_CONDITION:
        raise _singular(system, condition)
    q_dot = _solve_scaled(system, jac, system.nu())
    q_ddot = _solve_scaled(system, jac, system.gamma(q, q_dot)) if with_acceleration else None
    return _solution(layout, q, q_dot, q_ddot, condition, residual)


def _solution(
    layout: _Layout,
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
        poses[link] = LinkPose(_f(q[k]), _f(q[k + 1]), _f(q[k + 2]))
        omega[link] = _f(q_dot[k + 2])
        vel[link] = (_f(q_dot[k]), _f(q_dot[k + 1]))
        if q_ddot is not None and alpha is not None and acc is not None:
            alpha[link] = _f(q_ddot[k + 2])
            acc[link] = (_f(q_ddot[k]), _f(q_ddot[k + 1]))
    return AnalyticSolution(poses, omega, alpha, vel, acc, condition, residual)


# --------------------------------------------------------------------------------------------
# A [given] scene: one free body, the motion of two (or more) of its points known
# --------------------------------------------------------------------------------------------


def _at(source: str, given: GivenPoint) -> str:
    return f"{source}:{given.line}: " if given.line else f"{source}: "


def _solve_given(mechanism: Mechanism, *, with_acceleration: bool) -> AnalyticSolution:
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
    size = _size(mechanism)
    _check_distinct(scene.source, pts, local, size)

    # rows of v_P = v_o + omega J P; the omega column made a length per L, as in _System
    matrix = np.array([row for p in local for row in ([1.0, 0.0, -p[1]], [0.0, 1.0, p[0]])])
    condition = _condition(matrix * np.array([1.0, 1.0, 1.0 / size])[None, :])
    if condition > SINGULAR_CONDITION:
        raise SceneError(
            f"{_at(scene.source, pts[1])}given: the given points {', '.join(p.name for p in pts)} are too close "
            f"together (condition {condition:.3g}) to fix the body's rotation; give two points farther apart"
        )

    v = [_vec(p.velocity) for p in pts]
    _check_rigid_velocity(scene.source, scene.units.length, pts, local, v)
    sol_v = np.linalg.lstsq(matrix, np.concatenate(v), rcond=None)[0]
    omega = float(sol_v[2])

    alpha: dict[str, float] | None = None
    acc: dict[str, Vec] | None = None
    if with_acceleration:
        a = _given_accelerations(scene.source, pts)
        _check_rigid_acceleration(scene.source, scene.units.length, pts, local, a, omega)
        rhs = np.concatenate([a[k] + omega**2 * local[k] for k in range(len(pts))])
        sol_a = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
        alpha = {link: float(sol_a[2])}
        acc = {link: (float(sol_a[0]), float(sol_a[1]))}
    return AnalyticSolution(
        poses={link: LinkPose(0.0, 0.0, 0.0)},
        omega={link: omega},
        alpha=alpha,
        linear_velocity={link: (float(sol_v[0]), float(sol_v[1]))},
        linear_acceleration=acc,
        condition_number=condition,
        position_residual=0.0,
    )


def _given_locals(mechanism: Mechanism, link: str, pts: tuple[GivenPoint, ...]) -> list[np.ndarray]:
    out = []
    for p in pts:
        if not mechanism.has_point(link, p.name):
            raise SceneError(f"{_at(mechanism.scene.source, p)}given.{p.name}: link {link} has no point {p.name}")
        out.append(_vec(mechanism.local(link, p.name)))
    return out


def _check_distinct(source: str, pts: tuple[GivenPoint, ...], local: list[np.ndarray], size: float) -> None:
    for k in range(1, len(pts)):
        if float(np.hypot(*(local[k] - local[0]))) <= 1e-12 * size:
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
        out.append(_vec(p.acceleration))
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
                f"of given.{p.name}.velocity along {a.name}{p.name} equal that of {a.name}: {float(v[0] @ u):.6g} {unit}/s)"
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
