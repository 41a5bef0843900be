"""The constraint equations Phi(q, t) = 0 of a mechanism; each constraint knows its rows of Phi, Phi_q, nu, gamma.

* revolute at P of links i and j (2 rows):
  r_i + A_i p_i - r_j - A_j p_j = 0
* slider, block b on guide g, block point s_b, line through t_g at angle c in g's frame,
  e_g = (cos c, sin c), n_g = J e_g (2 rows):
  theta_b - theta_g - c = 0  and  n . d = 0,
  where n = A_g n_g, d = r_b + A_b s_b - r_g - A_g t_g; the slider variable is s = e . d, e = A_g e_g
* driver (1 row per input): theta_link - theta_base - angle = 0 (``LinkInput``; the base is the frame
  or the ``relative_to`` link) or e . d - s = 0 (``SliderInput``, the guide the frame or a moving link).

Velocity: Phi_q q_dot = nu (nu = omega or s_dot for the driver row, 0 elsewhere).
Acceleration: Phi_q q_ddot = gamma, gamma = (driver's alpha or s_ddot) - (the terms of
d^2 Phi / dt^2 quadratic in the velocities); each constraint documents its own gamma.
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np
from msgspec import Struct

from kinepoly.check.coordinates import Body, J, Layout, as_array
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import LinkInput, SliderInput, SliderSpec

__all__ = ["Constraint", "constraints_of"]


class Constraint(Protocol):
    """Rows of Phi, Phi_q, nu and gamma; ``angle_rows`` flags the rows that are angles."""

    @property
    def angle_rows(self) -> tuple[bool, ...]: ...

    def phi(self, b: dict[str, Body]) -> np.ndarray: ...

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray: ...

    def nu(self) -> np.ndarray: ...

    def gamma(self, b: dict[str, Body]) -> np.ndarray: ...


def _put(out: np.ndarray, layout: Layout, link: str, d_r: np.ndarray, d_theta: np.ndarray) -> None:
    """Add a link's partial derivatives (by r: rows x 2, by theta: rows) to Jacobian rows."""
    k = layout.column(link)
    if k is not None:
        out[:, k : k + 2] += d_r
        out[:, k + 2] += d_theta


class _Pin(Struct, frozen=True):
    """Revolute: r_i + A_i p_i - r_j - A_j p_j = 0.

    Phi_q: by r_i I, by theta_i J A_i p_i; by r_j -I, by theta_j -J A_j p_j.  nu = 0.
    gamma = omega_i^2 A_i p_i - omega_j^2 A_j p_j.
    """

    i: str
    j: str
    p_i: np.ndarray
    p_j: np.ndarray
    angle_rows: tuple[bool, ...] = (False, False)

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        bi, bj = b[self.i], b[self.j]
        return np.asarray(bi.r + bi.A @ self.p_i - bj.r - bj.A @ self.p_j, dtype=float)

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        out = np.zeros((2, layout.n))
        _put(out, layout, self.i, np.eye(2), J @ b[self.i].A @ self.p_i)
        _put(out, layout, self.j, -np.eye(2), -(J @ b[self.j].A @ self.p_j))
        return out

    def nu(self) -> np.ndarray:
        return np.zeros(2)

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        bi, bj = b[self.i], b[self.j]
        return np.asarray(bi.omega**2 * (bi.A @ self.p_i) - bj.omega**2 * (bj.A @ self.p_j), dtype=float)


class _AngleOffset(Struct, frozen=True):
    """theta_a - theta_b - offset = 0, modulo a turn (a slider's block turns with its guide).

    Phi_q: +1 by theta_a, -1 by theta_b; nu = 0; gamma = 0.
    """

    a: str
    b: str
    offset: float
    angle_rows: tuple[bool, ...] = (True,)

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        return np.array([math.remainder(b[self.a].theta - b[self.b].theta - self.offset, math.tau)])

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        out = np.zeros((1, layout.n))
        _put(out, layout, self.a, np.zeros((1, 2)), np.array([1.0]))
        _put(out, layout, self.b, np.zeros((1, 2)), np.array([-1.0]))
        return out

    def nu(self) -> np.ndarray:
        return np.zeros(1)

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        return np.zeros(1)


class _LineCoordinate(Struct, frozen=True):
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

    def _parts(self, b: dict[str, Body]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        bb, bg = b[self.block], b[self.guide]
        u = bg.A @ self.u_g
        arm_b = bb.A @ self.s_b
        arm_g = bg.A @ self.t_g
        d = bb.r + arm_b - bg.r - arm_g
        return u, d, arm_b, arm_g

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        u, d, _, _ = self._parts(b)
        return np.array([u @ d - self.target])

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        u, d, arm_b, arm_g = self._parts(b)
        out = np.zeros((1, layout.n))
        _put(out, layout, self.block, u[None, :], np.array([u @ (J @ arm_b)]))
        _put(out, layout, self.guide, -u[None, :], np.array([(J @ u) @ d - u @ (J @ arm_g)]))
        return out

    def nu(self) -> np.ndarray:
        return np.array([self.target_dot])

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        bb, bg = b[self.block], b[self.guide]
        u, d, arm_b, arm_g = self._parts(b)
        wb, wg = bb.omega, bg.omega
        d_dot = bb.r_dot + wb * (J @ arm_b) - bg.r_dot - wg * (J @ arm_g)
        quadratic = -(wg**2) * (u @ d) + 2.0 * wg * ((J @ u) @ d_dot) - wb**2 * (u @ arm_b) + wg**2 * (u @ arm_g)
        return np.array([self.target_ddot - quadratic])


class _AngleDriver(Struct, frozen=True):
    """theta_link - theta_base - angle = 0, modulo a turn: Phi_q 1 by theta_link, -1 by theta_base;
    nu = omega; gamma = alpha (the base is the frame, whose theta is 0, or a moving link)."""

    link: str
    base: str
    angle: float
    omega: float
    alpha: float
    angle_rows: tuple[bool, ...] = (True,)

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        return np.array([math.remainder(b[self.link].theta - b[self.base].theta - self.angle, math.tau)])

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        out = np.zeros((1, layout.n))
        _put(out, layout, self.link, np.zeros((1, 2)), np.array([1.0]))
        _put(out, layout, self.base, np.zeros((1, 2)), np.array([-1.0]))
        return out

    def nu(self) -> np.ndarray:
        return np.array([self.omega])

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        return np.array([self.alpha])


def _slider_constraints(mechanism: Mechanism, slider: SliderSpec) -> list[Constraint]:
    """The two rows of a slider: the block turns with the guide; its point stays on the line."""
    c = slider.angle_rad
    return [
        _AngleOffset(slider.block, slider.guide, c),
        _LineCoordinate(
            slider.block,
            slider.guide,
            as_array(mechanism.local(slider.block, slider.point)),
            as_array(slider.through),
            np.array([-math.sin(c), math.cos(c)]),
        ),
    ]


def _driver(mechanism: Mechanism, inp: LinkInput | SliderInput) -> Constraint:
    if isinstance(inp, LinkInput):
        base = inp.relative_to or mechanism.ground
        assert base is not None
        return _AngleDriver(inp.link, base, inp.angle_rad, inp.omega, inp.alpha)
    if isinstance(inp, SliderInput):
        slider = mechanism.slider(inp.slider)
        c = slider.angle_rad
        return _LineCoordinate(
            slider.block,
            slider.guide,
            as_array(mechanism.local(slider.block, slider.point)),
            as_array(slider.through),
            np.array([math.cos(c), math.sin(c)]),
            inp.s,
            inp.s_dot,
            inp.s_ddot,
        )


def constraints_of(mechanism: Mechanism) -> list[Constraint]:
    """Revolutes (2 rows each), sliders (2 rows each), then the drivers (1 row each)."""
    out: list[Constraint] = []
    for pin in mechanism.revolutes:
        out.append(_pin(mechanism, pin))
    for slider in mechanism.sliders:
        out.extend(_slider_constraints(mechanism, slider))
    for inp in mechanism.scene.inputs:
        assert isinstance(inp, LinkInput | SliderInput)
        out.append(_driver(mechanism, inp))
    return out


def _pin(mechanism: Mechanism, pin: Revolute) -> _Pin:
    i, j = pin.links
    return _Pin(i, j, as_array(mechanism.local(i, pin.point)), as_array(mechanism.local(j, pin.point)))
