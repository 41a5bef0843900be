"""The bench's reference: the mechanism solved in mpmath, good to 50 digits.

It is written from the position equations alone and shares no derivative with the analytic
solver: the unknowns are every moving link's pose q = (x, y, theta); the equations Phi(q, t) = 0
are the pins (r_i + A_i p_i = r_j + A_j p_j), the sliders (the block turns with its guide; its
point stays on the line), the higher pairs from their own geometry (``bench.higher_pairs``: a gear
pair's rolling with the phase rule, a cam's contact; a cam's equivalent link is not an unknown; a
spline cam's contact parameter is, ``bench.spline_pairs``) and the driver (theta = t, or the slider variable s = t).

* Jacobians by the complex step, dPhi/dq_k = Im Phi(q + i h e_k) / h, which has no
  cancellation: with h = 1e-40 it is exact to the working precision (80 digits).
* Position by Newton from the construction's double-precision pose (three or four steps).
* q' = dq/dt from Phi_q q' = -Phi_t.
* q'' from Phi_q q'' = -g, g = d^2/de^2 Phi(q + e q', t + e) at e = 0, taken as a central
  difference (step 1e-27) of the complex-step first derivative: error about 1e-54.

Then q_dot = q' t_dot and q_ddot = q'' t_dot^2 + q' t_ddot. The reference is rounded to 50
digits; a method's error is computed against it in mpmath, so that an error below the unit
roundoff of doubles is still seen.
"""

from __future__ import annotations

import math
from typing import Any

from msgspec import Struct

from kinepoly.bench.higher_pairs import cam_row, gear_rows, replaced_links, square_root
from kinepoly.bench.motion import LinkMotion, Trig, evaluate
from kinepoly.bench.spline_pairs import spline_contacts
from kinepoly.errors import SingularityError
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import LinkInput, SliderInput

__all__ = ["REFERENCE_DIGITS", "Reference", "input_rates", "reference_values"]

REFERENCE_DIGITS = 50
"""Digits the reference is good to (it is computed with 30 more)."""

_WORK_DIGITS = 80
_NEWTON_STEPS = 40


class Reference(Struct, frozen=True):
    """Reference values (mpmath numbers or pairs of them) by quantity key, at one input ``t``."""

    t: Any
    values: dict[str, Any]


def input_rates(mechanism: Mechanism) -> tuple[float, float, float]:
    """(t, t_dot, t_ddot): the input's value and its rates (theta, omega, alpha or s, s_dot, s_ddot)."""
    inp = mechanism.scene.input
    if isinstance(inp, LinkInput):
        return inp.angle_rad, inp.omega, inp.alpha
    if isinstance(inp, SliderInput):
        return inp.s, inp.s_dot, inp.s_ddot
    raise TypeError("the bench needs a scene driven by [input]")


class _Equations:
    """Phi(q, t) in mpmath (real or complex), for the mechanism's moving links."""

    def __init__(self, mechanism: Mechanism, mp: Any, first: Any, start: Pose) -> None:
        """``first``: the first input's value; ``phi`` takes time, every input moving from its value at its
        own rate and acceleration. ``start``: the pose Newton starts from, where the gears' constants are
        taken (``start_q``). A cam's equivalent link is not an unknown: its contact is a row of its own."""
        self.mp = mp
        self.drives = [(d, mp.mpf(d.value()) if d.index or first is None else first, mp.mpf(d.rate(1)),
                        mp.mpf(d.rate(2))) for d in mechanism.drives]
        self.mechanism = mechanism
        ground = mechanism.ground
        assert ground is not None
        self.ground = ground
        replaced = replaced_links(mechanism)
        self.moving = [k for k in mechanism.link_names if k != ground and k not in replaced]
        self.column = {k: 3 * n for n, k in enumerate(self.moving)}
        self.revolutes = [pin for pin in mechanism.revolutes if not replaced.intersection(pin.links)]
        self.sliders = [s.name for s in mechanism.sliders if not replaced.intersection((s.block, s.guide))]
        self.start_q = [mp.mpf(v) for k in self.moving for v in (start.links[k].x, start.links[k].y,
                                                                   start.links[k].theta)]
        self.gears = gear_rows(mp, mechanism, self.start_q, self._world, self._angle)
        self.splines = spline_contacts(mp, mechanism, lambda z: square_root(mp, z))
        self.poses = len(self.start_q)  # each spline cam's contact parameter(s) follow the poses
        for contact in self.splines:
            self.start_q += contact.starts(mp, mechanism, self.start_q[: self.poses], self._world, self._angle)

    def _pose(self, q: list[Any], link: str) -> tuple[Any, Any, Any, Any, Any]:
        mp = self.mp
        if link == self.ground:
            return mp.mpf(0), mp.mpf(0), mp.mpf(0), mp.mpf(1), mp.mpf(0)
        k = self.column[link]
        return q[k], q[k + 1], q[k + 2], mp.cos(q[k + 2]), mp.sin(q[k + 2])

    def _angle(self, q: list[Any], link: str) -> Any:
        return self._pose(q, link)[2]

    def _world(self, q: list[Any], link: str, local: tuple[float, float]) -> tuple[Any, Any]:
        x, y, _, c, s = self._pose(q, link)
        px, py = self.mp.mpf(local[0]), self.mp.mpf(local[1])
        return x + c * px - s * py, y + s * px + c * py

    def phi(self, q: list[Any], t: Any) -> list[Any]:
        mp, mech = self.mp, self.mechanism
        rows: list[Any] = []
        for pin in self.revolutes:
            i, j = pin.links
            a = self._world(q, i, mech.local(i, pin.point))
            b = self._world(q, j, mech.local(j, pin.point))
            rows += [a[0] - b[0], a[1] - b[1]]
        for name in self.sliders:
            rows += self._slider_rows(q, name, t)
        rows += [cam_row(mp, mech, cam, q, self._world, self._angle) for cam in mech.scene.cams if not cam.is_spline]
        at = self.poses
        for contact in self.splines:
            rows += contact.rows(mp, mech, q, q[at : at + contact.unknowns], self._world, self._angle)
            at += contact.unknowns
        rows += [gear.value(mp, mech, q, self._world, self._angle) for gear in self.gears]
        for drive, value, rate, accel in self.drives:
            target = value + rate * t + accel * t * t / 2
            if isinstance(drive.spec, LinkInput):
                rows.append(self._pose(q, drive.moving)[2] - self._pose(q, drive.base)[2] - target)
            else:
                rows.append(self._along(q, drive.spec.slider, normal=False) - target)
        return [mp.mpmathify(r) for r in rows]

    def _slider_rows(self, q: list[Any], name: str, t: Any) -> list[Any]:
        slider = self.mechanism.slider(name)
        turn = self._pose(q, slider.block)[2] - self._pose(q, slider.guide)[2] - self.mp.mpf(slider.angle_rad)
        return [turn, self._along(q, name, normal=True)]

    def _along(self, q: list[Any], name: str, *, normal: bool) -> Any:
        """(P - T) . n (normal=True) or . e: the block's point from the line's point."""
        mp, mech = self.mp, self.mechanism
        slider = mech.slider(name)
        at = self._world(q, slider.block, mech.local(slider.block, slider.point))
        start = self._world(q, slider.guide, slider.through)
        angle = self._pose(q, slider.guide)[2] + mp.mpf(slider.angle_rad)
        c, s = mp.cos(angle), mp.sin(angle)
        dx, dy = at[0] - start[0], at[1] - start[1]
        return -s * dx + c * dy if normal else c * dx + s * dy


def _complex_step(eq: _Equations, q: list[Any], t: Any, dq: list[Any], dt: Any) -> list[Any]:
    """d/de Phi(q + e dq, t + e dt) at e = 0 by the complex step."""
    mp = eq.mp
    h = mp.mpf(10) ** -40
    qi = [mp.mpc(a, h * b) for a, b in zip(q, dq, strict=True)]
    return [mp.im(v) / h for v in eq.phi(qi, mp.mpc(t, h * dt))]


def _jacobian(eq: _Equations, q: list[Any], t: Any) -> Any:
    mp = eq.mp
    n = len(q)
    columns = []
    for k in range(n):
        unit = [mp.mpf(0)] * n
        unit[k] = mp.mpf(1)
        columns.append(_complex_step(eq, q, t, unit, mp.mpf(0)))
    return mp.matrix([[columns[c][r] for c in range(n)] for r in range(n)])


def _newton(eq: _Equations, q: list[Any], t: Any, size: Any) -> tuple[list[Any], Any]:
    mp = eq.mp
    tol = size * mp.mpf(10) ** -(_WORK_DIGITS - 5)
    for _ in range(_NEWTON_STEPS):
        jac = _jacobian(eq, q, t)
        step = mp.lu_solve(jac, mp.matrix([-v for v in eq.phi(q, t)]))
        q = [a + step[k] for k, a in enumerate(q)]
        if mp.norm(step, mp.inf) <= tol:
            return q, _jacobian(eq, q, t)
    raise SingularityError("the 50-digit reference did not converge at this input: the position is singular")


def reference_values(mechanism: Mechanism, start: Pose, keys: list[str], *, t: float | None = None,
                     origin: tuple[float, float] = (0.0, 0.0)) -> Reference:
    """The reference value of every key at input ``t`` (default: the scene's), from ``start``.

    ``start`` is a pose near the wanted assembly (the construction's); ``mechanism`` is the one
    the solve used (its frame local to the mechanism); positions get ``origin`` added.
    Raises SingularityError where the position equations are singular.
    """
    try:
        return _reference(mechanism, start, keys, t, origin)
    except ZeroDivisionError:  # mpmath's LU met an exactly singular Jacobian
        raise SingularityError("the position equations are singular at this input (their Jacobian is singular "
                               "to 80 digits)") from None


def _on_turn_of(mechanism: Mechanism, start: Pose, t: float) -> float:
    """An input angle ``t`` moved by whole turns to the turn of the input link in ``start`` (the same position;
    Newton would otherwise have to turn the link round), any other input as it is."""
    inp = mechanism.scene.input
    if not isinstance(inp, LinkInput) or inp.link not in start.links:
        return t
    return t + 2.0 * math.pi * round((start.links[inp.link].theta - t) / (2.0 * math.pi))


def _reference(mechanism: Mechanism, start: Pose, keys: list[str], t: float | None,
               origin: tuple[float, float]) -> Reference:
    import mpmath  # type: ignore[import-untyped]

    mp = mpmath.mp
    t0, _, _ = input_rates(mechanism)
    with mp.workdps(_WORK_DIGITS):
        tt = mp.mpf(_on_turn_of(mechanism, start, t0 if t is None else t))
        eq = _Equations(mechanism, mp, tt, start)  # phi in time: every input at its own rate from its value
        q = eq.start_q
        size = max([mp.mpf(1)] + [abs(v) for v in q])
        now = mp.mpf(0)
        q, jac = _newton(eq, q, now, size)
        zero = [mp.mpf(0)] * len(q)
        q1 = list(mp.lu_solve(jac, mp.matrix([-v for v in _complex_step(eq, q, now, zero, mp.mpf(1))])))
        delta = mp.mpf(10) ** -27
        ahead = _complex_step(eq, [a + delta * b for a, b in zip(q, q1, strict=True)], now + delta, q1, mp.mpf(1))
        behind = _complex_step(eq, [a - delta * b for a, b in zip(q, q1, strict=True)], now - delta, q1, mp.mpf(1))
        g = [(a - b) / (2 * delta) for a, b in zip(ahead, behind, strict=True)]
        q2 = list(mp.lu_solve(jac, mp.matrix([-v for v in g])))
        rate, accel = mp.mpf(1), mp.mpf(0)  # q1, q2 are already time derivatives
        motion = {eq.ground: LinkMotion(*([mp.mpf(0)] * 9))}
        for link, k in eq.column.items():
            v = [q1[k + m] * rate for m in range(3)]
            a = [q2[k + m] * rate * rate + q1[k + m] * accel for m in range(3)]
            motion[link] = LinkMotion(q[k], q[k + 1], q[k + 2], v[0], v[1], v[2], a[0], a[1], a[2])
        values = evaluate(mechanism, motion, keys, Trig(mp.cos, mp.sin), (mp.mpf(origin[0]), mp.mpf(origin[1])))
        rounded = {key: _round(mp, value) for key, value in values.items()}
    return Reference(tt, rounded)


def _round(mp: Any, value: Any) -> Any:
    if isinstance(value, tuple):
        return tuple(_round(mp, v) for v in value)
    with mp.workdps(REFERENCE_DIGITS):
        return +value
