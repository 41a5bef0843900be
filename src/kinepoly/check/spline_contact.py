"""A spline cam's contact as a constraint row, for the analytic check (written apart from ``engine.cam_*``).

The profile r(u) (``geom.spline``, in the cam c's frame) touches the follower f at W (local w): W runs on the
curve X(u) = r(u) + rho n(u), n the unit left normal of r, rho = 0 for a knife edge, -r for a roller outside,
+r for a roller in a groove. With u as one more unknown the contact is the vector equation

    F(q, u) = r_c + A_c X(u) - r_f - A_f w = 0        (2 rows, 1 more coordinate).

F_u = A_c X'(u) is along the tangent t, so the tangential row only fixes u: it is solved inside the row (u*
the foot of W on X, ``geom.spline.nearest_parameter``), and the row left is the normal one,

    Phi = n_w . (W - X(u*)),   n_w = A_c n(u*)   (the signed gap of W from X)

  Phi_q: by r_f n_w, by theta_f n_w . (J A_f w), by r_c -n_w, by theta_c -n_w . (J A_c X);   nu = 0
  (the derivative through u* vanishes: X' is square to n_w and n' . (W - X) = 0 at the foot).

Twice along the motion, F = 0 gives, on n_w (sigma = |r'|, kappa the curvature, X' = sigma (1 - rho kappa) t,
n . X'' = sigma^2 kappa (1 - rho kappa)), with u_dot from the tangential row:

    u_dot = -t_w . (r_dot_c + omega_c J A_c X - r_dot_f - omega_f J A_f w) / (sigma (1 - rho kappa))
    gamma = n_w . (-omega_c^2 A_c X + omega_f^2 A_f w) + 2 omega_c sigma (1 - rho kappa) u_dot
            + sigma^2 kappa (1 - rho kappa) u_dot^2.
"""

from __future__ import annotations

import numpy as np
from msgspec import Struct

from kinepoly.check.coordinates import Body, J, Layout, as_array
from kinepoly.geom.spline import PeriodicSpline, nearest_parameter, periodic_spline
from kinepoly.model.mechanism import Mechanism

__all__ = ["spline_contacts"]


class _LengthRow:
    """One row of Phi, a length, whose velocity right-hand side is zero (no input drives it)."""

    angle_rows: tuple[bool, ...] = (False,)

    def nu(self) -> np.ndarray:
        return np.zeros(1)


class _Local(Struct, frozen=True):
    """The contact's curve quantities at u*, in the cam's frame."""

    x: np.ndarray
    t: np.ndarray
    n: np.ndarray
    sigma: float
    kappa: float


class _SplineContact(Struct, _LengthRow, frozen=True):
    cam: str
    follower: str
    w: np.ndarray
    spline: PeriodicSpline
    rho: float

    def _world_w(self, b: dict[str, Body]) -> np.ndarray:
        f = b[self.follower]
        return np.asarray(f.r + f.A @ self.w, dtype=float)

    def _local(self, b: dict[str, Body]) -> _Local:
        c = b[self.cam]
        in_cam = c.A.T @ (self._world_w(b) - c.r)
        u = nearest_parameter(self.spline, complex(in_cam[0], in_cam[1]), self.rho)
        point, first, second = (complex(z[0]) for z in self.spline.derivatives(np.array([u])))
        sigma = abs(first)
        kappa = (first.conjugate() * second).imag / sigma**3
        tangent = first / sigma
        normal = 1j * tangent
        x = point + self.rho * normal
        return _Local(as_array((x.real, x.imag)), as_array((tangent.real, tangent.imag)),
                      as_array((normal.real, normal.imag)), sigma, kappa)

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        c, here = b[self.cam], self._local(b)
        return np.array([float((c.A @ here.n) @ (self._world_w(b) - c.r - c.A @ here.x))])

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        c, f, here = b[self.cam], b[self.follower], self._local(b)
        n_w = c.A @ here.n
        out = np.zeros((1, layout.n))
        for link, sign, arm in ((self.follower, 1.0, f.A @ self.w), (self.cam, -1.0, c.A @ here.x)):
            k = layout.column(link)
            if k is not None:
                out[0, k : k + 2] += sign * n_w
                out[0, k + 2] += sign * float(n_w @ (J @ arm))
        return out

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        c, f, here = b[self.cam], b[self.follower], self._local(b)
        arm_c, arm_f = c.A @ here.x, f.A @ self.w
        n_w, t_w = c.A @ here.n, c.A @ here.t
        stretch = here.sigma * (1.0 - self.rho * here.kappa)
        relative = c.r_dot + c.omega * (J @ arm_c) - f.r_dot - f.omega * (J @ arm_f)
        u_dot = -float(t_w @ relative) / stretch
        quadratic = float(n_w @ (-(c.omega**2) * arm_c + f.omega**2 * arm_f))
        return np.array([quadratic + 2.0 * c.omega * stretch * u_dot + here.sigma * here.kappa * stretch * u_dot**2])


_SUPPORT_SAMPLES_PER_PIECE = 64
_SUPPORT_STEPS = 8


def _vector(z: complex) -> np.ndarray:
    return as_array((z.real, z.imag))


class _SplineFace(Struct, _LengthRow, frozen=True):
    """A flat face (through f, direction d_l in the follower's frame; the cam on its left) on the profile:
    m = -J A_f d_l the profile's outward normal at the contact, u* the profile's support point along m,
    Phi = m . (r_c + A_c r(u*) - r_f - A_f f).

      Phi_q: by r_c m, by theta_c m . (J A_c r), by r_f -m, by theta_f -m . (J A_f f) + (J m) . (P - F);  nu = 0
      gamma = omega_f^2 m . (P - F) - 2 omega_f (J m) . (P_dot - F_dot)
              - m . (-omega_c^2 A_c r + 2 omega_c J A_c r' u_dot + A_c r'' u_dot^2 + omega_f^2 A_f f),
      u_dot = (omega_f - omega_c) / (kappa sigma)   (the tangent turns with the face),
      P_dot - F_dot = r_dot_c + omega_c J A_c r + A_c r' u_dot - r_dot_f - omega_f J A_f f.
    """

    cam: str
    follower: str
    f: np.ndarray
    d: np.ndarray
    spline: PeriodicSpline

    def _support(self, b: dict[str, Body]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """m (frame), then r, r', r'' at u* (cam frame)."""
        c, f = b[self.cam], b[self.follower]
        m = -(J @ (f.A @ self.d))
        m_cam = c.A.T @ m
        toward = complex(m_cam[0], m_cam[1])
        count = _SUPPORT_SAMPLES_PER_PIECE * self.spline.pieces
        grid = self.spline.period * np.arange(count) / count
        u = float(grid[int(np.argmax((self.spline.point(grid) * toward.conjugate()).real))])
        for _ in range(_SUPPORT_STEPS):
            _, first, second = (complex(z[0]) for z in self.spline.derivatives(np.array([u])))
            slope, curve = (first * toward.conjugate()).real, (second * toward.conjugate()).real
            if curve == 0.0:
                break
            u -= slope / curve
        point, first, second = (complex(z[0]) for z in self.spline.derivatives(np.array([u])))
        return m, _vector(point), _vector(first), _vector(second)

    def _gap(self, b: dict[str, Body], point: np.ndarray) -> np.ndarray:
        c, f = b[self.cam], b[self.follower]
        return np.asarray(c.r + c.A @ point - f.r - f.A @ self.f, dtype=float)

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        m, point, _, _ = self._support(b)
        return np.array([float(m @ self._gap(b, point))])

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        c, f = b[self.cam], b[self.follower]
        m, point, _, _ = self._support(b)
        out = np.zeros((1, layout.n))
        for link, sign, arm, extra in ((self.cam, 1.0, c.A @ point, 0.0),
                                       (self.follower, -1.0, f.A @ self.f, float((J @ m) @ self._gap(b, point)))):
            k = layout.column(link)
            if k is not None:
                out[0, k : k + 2] += sign * m
                out[0, k + 2] += sign * float(m @ (J @ arm)) + extra
        return out

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        c, f = b[self.cam], b[self.follower]
        m, point, first, second = self._support(b)
        sigma = float(np.hypot(*first))
        kappa = float(first[0] * second[1] - first[1] * second[0]) / sigma**3
        u_dot = (f.omega - c.omega) / (kappa * sigma)
        arm_c, arm_f = c.A @ point, f.A @ self.f
        rate = c.r_dot + c.omega * (J @ arm_c) + (c.A @ first) * u_dot - f.r_dot - f.omega * (J @ arm_f)
        quadratic = (-(f.omega**2) * float(m @ self._gap(b, point)) + 2.0 * f.omega * float((J @ m) @ rate)
                     + float(m @ (-(c.omega**2) * arm_c + 2.0 * c.omega * (J @ (c.A @ first)) * u_dot
                                  + (c.A @ second) * u_dot**2 + f.omega**2 * arm_f)))
        return np.array([-quadratic])


_PAIR_SAMPLES_PER_PIECE = 16
_PAIR_STEPS = 40


class _SplinePair(Struct, _LengthRow, frozen=True):
    """Two splines in contact: the cam's r1(u) and the follower's r2(v) (each in its own link's frame), both
    counter-clockwise, touching from outside. (u*, v*) is their common normal: the tangents T1 = A_c r1',
    T2 = A_f r2' parallel and P2 - P1 along the normal n1 = J t1 (t1 = T1 / sigma1),

        T1 x T2 = 0,   T1 . (P2 - P1) = 0        (Newton on u, v from the nearest pair of samples)

    and the row is the gap along it, Phi = n1 . (P2 - P1), P1 = r_c + A_c r1(u*), P2 = r_f + A_f r2(v*).

      Phi_q: by r_f n1, by theta_f n1 . (J A_f r2), by r_c -n1, by theta_c -n1 . (J A_c r1);   nu = 0
      (u*, v* move the points along the common tangent only, square to n1, while the gap is zero).

    Along the motion the points stay together (t1 . (V2 - V1) = sigma1 u_dot + sigma2 v_dot, V the material
    velocities) and the tangents turn together (omega_c + kappa1 sigma1 u_dot = omega_f + kappa2 sigma2 v_dot);
    with n1 . J T2 = -sigma2, n1 . r2'' = -sigma2^2 kappa2 (t2 = -t1) the second derivative of Phi = 0 gives

      gamma = n1 . (-omega_c^2 A_c r1 + omega_f^2 A_f r2) + 2 omega_c sigma1 u_dot + sigma1^2 kappa1 u_dot^2
              + 2 omega_f sigma2 v_dot + sigma2^2 kappa2 v_dot^2.
    """

    cam: str
    follower: str
    first: PeriodicSpline
    second: PeriodicSpline

    def _common_normal(self, b: dict[str, Body]) -> tuple[complex, complex, complex, complex, complex, complex]:
        """(A_c r1, A_c r1', A_c r1'', A_f r2, A_f r2', A_f r2'') at (u*, v*), as complex numbers in the frame."""
        c, f = b[self.cam], b[self.follower]
        turn_c, turn_f = complex(c.A[0, 0], c.A[1, 0]), complex(f.A[0, 0], f.A[1, 0])
        origin_c, origin_f = complex(c.r[0], c.r[1]), complex(f.r[0], f.r[1])
        grid_u = self.first.period * np.arange(_PAIR_SAMPLES_PER_PIECE * self.first.pieces) / (
            _PAIR_SAMPLES_PER_PIECE * self.first.pieces)
        grid_v = self.second.period * np.arange(_PAIR_SAMPLES_PER_PIECE * self.second.pieces) / (
            _PAIR_SAMPLES_PER_PIECE * self.second.pieces)
        distance = np.abs((origin_c + turn_c * self.first.point(grid_u))[:, None]
                          - (origin_f + turn_f * self.second.point(grid_v))[None, :])
        i, k = np.unravel_index(int(np.argmin(distance)), distance.shape)
        u, v = float(grid_u[i]), float(grid_v[k])
        for _ in range(_PAIR_STEPS):
            p1, d1, e1 = (turn_c * complex(z[0]) for z in self.first.derivatives(np.array([u])))
            p2, d2, e2 = (turn_f * complex(z[0]) for z in self.second.derivatives(np.array([v])))
            gap = origin_f + p2 - origin_c - p1
            f1, f2 = (d1.conjugate() * d2).imag, (d1.conjugate() * gap).real
            a, bb = (e1.conjugate() * d2).imag, (d1.conjugate() * e2).imag
            c2, d = (e1.conjugate() * gap).real - abs(d1) ** 2, (d1.conjugate() * d2).real
            det = a * d - bb * c2
            if det == 0.0:
                break
            du, dv = -(d * f1 - bb * f2) / det, -(-c2 * f1 + a * f2) / det
            u, v = u + du, v + dv
            if abs(du) <= 1e-15 * self.first.period and abs(dv) <= 1e-15 * self.second.period:
                break
        p1, d1, e1 = (turn_c * complex(z[0]) for z in self.first.derivatives(np.array([u])))
        p2, d2, e2 = (turn_f * complex(z[0]) for z in self.second.derivatives(np.array([v])))
        return p1, d1, e1, p2, d2, e2

    def _normal(self, d1: complex) -> np.ndarray:
        n = 1j * d1 / abs(d1)
        return _vector(n)

    def phi(self, b: dict[str, Body]) -> np.ndarray:
        c, f = b[self.cam], b[self.follower]
        p1, d1, _, p2, _, _ = self._common_normal(b)
        gap = f.r + _vector(p2) - c.r - _vector(p1)
        return np.array([float(self._normal(d1) @ gap)])

    def jacobian(self, b: dict[str, Body], layout: Layout) -> np.ndarray:
        p1, d1, _, p2, _, _ = self._common_normal(b)
        n1 = self._normal(d1)
        out = np.zeros((1, layout.n))
        for link, sign, arm in ((self.follower, 1.0, _vector(p2)), (self.cam, -1.0, _vector(p1))):
            k = layout.column(link)
            if k is not None:
                out[0, k : k + 2] += sign * n1
                out[0, k + 2] += sign * float(n1 @ (J @ arm))
        return out

    def gamma(self, b: dict[str, Body]) -> np.ndarray:
        c, f = b[self.cam], b[self.follower]
        p1, d1, e1, p2, d2, e2 = self._common_normal(b)
        sigma1, sigma2 = abs(d1), abs(d2)
        kappa1 = (d1.conjugate() * e1).imag / sigma1**3
        kappa2 = (d2.conjugate() * e2).imag / sigma2**3
        t1, n1 = _vector(d1 / sigma1), self._normal(d1)
        arm_c, arm_f = _vector(p1), _vector(p2)
        relative = f.r_dot + f.omega * (J @ arm_f) - c.r_dot - c.omega * (J @ arm_c)
        along, turning = float(t1 @ relative), f.omega - c.omega
        a = (kappa2 * along + turning) / (kappa1 + kappa2)  # sigma1 u_dot
        bb = along - a                                      # sigma2 v_dot
        quadratic = float(n1 @ (-(c.omega**2) * arm_c + f.omega**2 * arm_f))
        return np.array([quadratic + 2.0 * c.omega * a + kappa1 * a * a + 2.0 * f.omega * bb + kappa2 * bb * bb])


def spline_contacts(mechanism: Mechanism) -> list[_SplineContact | _SplineFace | _SplinePair]:
    """One row per spline cam pair (a knife edge, a roller, a flat face or a follower profile of points)."""
    out: list[_SplineContact | _SplineFace | _SplinePair] = []
    for cam in mechanism.scene.cams:
        if not cam.is_spline:
            continue
        if cam.follower_points:
            out.append(_SplinePair(cam.cam, cam.follower, periodic_spline(cam.profile_points),
                                   periodic_spline(cam.follower_points)))
            continue
        if cam.flat is not None and cam.kind == "flat":
            (x, y), angle = cam.flat
            out.append(_SplineFace(cam.cam, cam.follower, as_array((x, y)),
                                   as_array((np.cos(angle), np.sin(angle))), periodic_spline(cam.profile_points)))
            continue
        if cam.point is None:
            continue
        rho = 0.0 if cam.kind != "roller" else (cam.roller_radius if cam.inside else -cam.roller_radius)
        w = as_array(mechanism.local(cam.follower, cam.point))
        out.append(_SplineContact(cam.cam, cam.follower, w, periodic_spline(cam.profile_points), rho))
    return out

