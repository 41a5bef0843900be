"""The rolling constraint of a gear pair, for the analytic check (written apart from ``engine.gears``).

Two pitch circles a, b (radii r_a, r_b, centres c_a, c_b in their links' frames), D = C_b - C_a the
line of centres in the frame, phi = atg(D). Rolling without slip conserves the arc each pitch circle
has rolled off, counted from the pitch point:

    G = (r_a - c r_b) phi - r_a theta_a + c r_b theta_b = const,   c = -1 external, +1 internal

(the pitch point's angle is phi or phi + pi seen from either centre; the constant takes the pi's).
With k = (r_a - c r_b) / |D|^2 and dphi = (J D) . dD / |D|^2:
  Phi_q: by r_b  k (J D),  by theta_b  k (J D) . (J A_b c_b) + c r_b,
         by r_a -k (J D),  by theta_a -k (J D) . (J A_a c_a) - r_a;   nu = 0;
  gamma = -(r_a - c r_b) [ (D x Q_D) / |D|^2 - 2 (D x D_dot)(D . D_dot) / |D|^4 ],
  Q_D = -omega_b^2 A_b c_b + omega_a^2 A_a c_a (the part of D_ddot quadratic in the velocities).

A circle (centre o on link c, radius r) on a rack's line (through t at direction d_l on link l),
d = A_l d_l, w = C - T, s = the side of the line the centre is on (+1 when (T - C) . J d > 0):

    G = w . d + s r (theta_l - theta_c) = const
  Phi_q: by r_c d, by theta_c d . (J A_c o) - s r, by r_l -d, by theta_l -d . (J A_l t) + w . (J d) + s r;
  gamma = -[ (-omega_c^2 A_c o + omega_l^2 A_l t) . d - omega_l^2 w . d + 2 omega_l w_dot . (J d) ].

The constant is the one of the start pose (the construction's): Newton keeps each gear's phase as
the construction found it; velocities and accelerations follow from Phi_q, nu and gamma alone.
"""

from __future__ import annotations

import math

import numpy as np
from msgspec import Struct

from kinepoly.check.coordinates import Body, J, Layout, as_array
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import GearSpec, PitchCircle, PitchLine

__all__ = ["rolling_constraints"]


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _put(out: np.ndarray, layout: Layout, link: str, d_r: np.ndarray, d_theta: float) -> None:
    k = layout.column(link)
    if k is not None:
        out[0, k : k + 2] += d_r
        out[0, k + 2] += d_theta


class _Circles(Struct, frozen=True):
    a: str
    b: str
    c_a: np.ndarray
    c_b: np.ndarray
    r_a: float
    r_b: float
    sign: float
    phi0: float
    g0: float
    angle_rows: tuple[bool, ...] = (False,)

    def _d(self, bd: dict[str, Body]) -> np.ndarray:
        ba, bb = bd[self.a], bd[self.b]
        return np.asarray(bb.r + bb.A @ self.c_b - ba.r - ba.A @ self.c_a, dtype=float)

    def value(self, bd: dict[str, Body]) -> float:
        d = self._d(bd)
        phi = self.phi0 + math.remainder(math.atan2(d[1], d[0]) - self.phi0, math.tau)
        return ((self.r_a - self.sign * self.r_b) * phi - self.r_a * bd[self.a].theta
                + self.sign * self.r_b * bd[self.b].theta)

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        return np.array([self.value(b) - self.g0])

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        d = self._d(b)
        k = (self.r_a - self.sign * self.r_b) / float(d @ d)
        jd = J @ d
        out = np.zeros((1, layout.n))
        _put(out, layout, self.b, k * jd, k * float(jd @ (J @ b[self.b].A @ self.c_b)) + self.sign * self.r_b)
        _put(out, layout, self.a, -k * jd, -k * float(jd @ (J @ b[self.a].A @ self.c_a)) - self.r_a)
        return out

    def nu(self) -> np.ndarray:
        return np.zeros(1)

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        ba, bb = b[self.a], b[self.b]
        d = self._d(b)
        arm_a, arm_b = ba.A @ self.c_a, bb.A @ self.c_b
        d_dot = bb.r_dot + bb.omega * (J @ arm_b) - ba.r_dot - ba.omega * (J @ arm_a)
        q_d = -(bb.omega**2) * arm_b + ba.omega**2 * arm_a
        dd = float(d @ d)
        quadratic = _cross(d, q_d) / dd - 2.0 * _cross(d, d_dot) * float(d @ d_dot) / (dd * dd)
        return np.array([-(self.r_a - self.sign * self.r_b) * quadratic])


class _Rack(Struct, frozen=True):
    c: str
    line: str
    o: np.ndarray
    t: np.ndarray
    d_l: np.ndarray
    r: float
    side: float
    g0: float
    angle_rows: tuple[bool, ...] = (False,)

    def _parts(self, b: dict[str, Body]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        bc, bl = b[self.c], b[self.line]
        arm_c, arm_l = bc.A @ self.o, bl.A @ self.t
        return np.asarray(bc.r + arm_c - bl.r - arm_l, dtype=float), bl.A @ self.d_l, arm_c, arm_l

    def value(self, b: dict[str, Body]) -> float:
        w, d, _, _ = self._parts(b)
        return float(w @ d) + self.side * self.r * (b[self.line].theta - b[self.c].theta)

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        return np.array([self.value(b) - self.g0])

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        w, d, arm_c, arm_l = self._parts(b)
        out = np.zeros((1, layout.n))
        _put(out, layout, self.c, d, float(d @ (J @ arm_c)) - self.side * self.r)
        _put(out, layout, self.line, -d, -float(d @ (J @ arm_l)) + float(w @ (J @ d)) + self.side * self.r)
        return out

    def nu(self) -> np.ndarray:
        return np.zeros(1)

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        bc, bl = b[self.c], b[self.line]
        w, d, arm_c, arm_l = self._parts(b)
        w_dot = bc.r_dot + bc.omega * (J @ arm_c) - bl.r_dot - bl.omega * (J @ arm_l)
        quad_w = -(bc.omega**2) * arm_c + bl.omega**2 * arm_l
        q = float(quad_w @ d) - bl.omega**2 * float(w @ d) + 2.0 * bl.omega * float(w_dot @ (J @ d))
        return np.array([-q])


def _circles(mechanism: Mechanism, gear: GearSpec, start: dict[str, Body]) -> _Circles:
    one, two = gear.pitch
    assert isinstance(one, PitchCircle) and isinstance(two, PitchCircle)
    a, b = gear.links
    c_a, c_b = as_array(mechanism.local(a, one.center)), as_array(mechanism.local(b, two.center))
    made = _Circles(a, b, c_a, c_b, one.radius, two.radius, 1.0 if gear.internal else -1.0, 0.0, 0.0)
    d = made._d(start)
    phi0 = math.atan2(d[1], d[0])
    made = _Circles(a, b, c_a, c_b, one.radius, two.radius, made.sign, phi0, 0.0)
    return _Circles(a, b, c_a, c_b, one.radius, two.radius, made.sign, phi0, made.value(start))


def _rack(mechanism: Mechanism, gear: GearSpec, start: dict[str, Body]) -> _Rack:
    k = 0 if isinstance(gear.pitch[0], PitchCircle) else 1
    circle, line = gear.pitch[k], gear.pitch[1 - k]
    assert isinstance(circle, PitchCircle) and isinstance(line, PitchLine)
    c, l_link = gear.links[k], gear.links[1 - k]
    o = as_array(mechanism.local(c, circle.center))
    d_l = np.array([math.cos(line.angle_rad), math.sin(line.angle_rad)])
    made = _Rack(c, l_link, o, as_array(line.through), d_l, circle.radius, 1.0, 0.0)
    w, d, _, _ = made._parts(start)
    side = 1.0 if float(-w @ (J @ d)) > 0.0 else -1.0
    made = _Rack(c, l_link, o, as_array(line.through), d_l, circle.radius, side, 0.0)
    return _Rack(c, l_link, o, as_array(line.through), d_l, circle.radius, side, made.value(start))


def rolling_constraints(mechanism: Mechanism, start: dict[str, Body]) -> list[_Circles | _Rack]:
    """One row per gear pair, its constant taken at the ``start`` bodies."""
    out: list[_Circles | _Rack] = []
    for gear in mechanism.scene.gears:
        both = all(isinstance(curve, PitchCircle) for curve in gear.pitch)
        out.append(_circles(mechanism, gear, start) if both else _rack(mechanism, gear, start))
    return out
