"""Closed forms of the standard mechanisms, batched over inputs with numpy.

Each recognises its mechanism in a scene (which link is the crank, the coupler, ...), takes
the assembly the solve took, and gives every link's motion for an array of inputs:

* four-bar, crank driven: Freudenstein's half-angle solution for theta4 and theta3, then
  omega3 = a omega2 sin(theta4 - theta2) / (b sin(theta3 - theta4)) and its mate, and the
  textbook 2x2 Cramer solution for alpha3, alpha4 (angles from the frame line O2 O4);
* slider-crank, crank driven: with u along the slide and w across it (origin at the crank
  pivot, the slide at w = h): sin theta3 = (h - a sin phi) / b, omega3 = -a omega2 cos phi /
  (b cos theta3), alpha3 = (b omega3^2 sin theta3 + a omega2^2 sin phi - a alpha2 cos phi) /
  (b cos theta3), and u_B = a cos phi + b cos theta3 with its two derivatives;
* slider-crank, piston driven: the crank angle from the triangle O2 A B, then omega2, omega3
  and alpha2, alpha3 from the differentiated loop O2 + a e2 + b e3 = T + s e, dotted with e3
  and e2: omega2 = s_dot (e3 . e) / (a cross(e2, e3)), omega3 = -s_dot (e2 . e) / (b cross(e2, e3));
* crank and slotted lever (the block on the crank pin slides in the lever's slot): with
  R = A - O4 and m the offset of the slot from the lever's pivot, theta4 + c = psi - asin(m / rho)
  (psi, rho the polar angle and length of R), differentiated twice (m = 0 gives the course
  text's omega3 = omega1 l1 (l1 + l0 sin phi1) / (l1^2 + 2 l0 l1 sin phi1 + l0^2)).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from msgspec import Struct

from kinepoly.bench.motion import LinkMotion
from kinepoly.check.series import pin_between, slider_crank_links
from kinepoly.geom.vec import Vec
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import LinkInput, SliderInput

__all__ = ["ClosedForm", "closed_form"]

Array = np.ndarray
Pair = tuple[Array, Array]


class ClosedForm(Struct, frozen=True):
    """A recognised standard mechanism: its name and its motion for an array of inputs."""

    name: str
    motion: Callable[[Array], dict[str, LinkMotion]]


def _angle(v: Vec) -> float:
    return float(np.arctan2(v[1], v[0]))


def _from_point(mechanism: Mechanism, link: str, point: str, at: Pair, vel: Pair, acc: Pair,
                theta: Array, omega: Array, alpha: Array) -> LinkMotion:
    """A link's motion from one of its points' motion and the link's angle and rates."""
    px, py = mechanism.local(link, point)
    c, s = np.cos(theta), np.sin(theta)
    ax_, ay_ = c * px - s * py, s * px + c * py
    return LinkMotion(at[0] - ax_, at[1] - ay_, theta,
                      vel[0] + omega * ay_, vel[1] - omega * ax_, omega,
                      acc[0] + alpha * ay_ + omega * omega * ax_, acc[1] - alpha * ax_ + omega * omega * ay_, alpha)


def _fixed(x: float, y: float, n: Array) -> tuple[Pair, Pair, Pair]:
    zero = np.zeros_like(n)
    return (zero + x, zero + y), (zero, zero), (zero, zero)


def _link_theta(mechanism: Mechanism, link: str, first: str, second: str, world_angle: Array) -> Array:
    """The link's pose angle when its segment first->second points at ``world_angle``."""
    a, b = mechanism.local(link, first), mechanism.local(link, second)
    return world_angle - _angle((b[0] - a[0], b[1] - a[1]))


def _ground_point(mechanism: Mechanism, point: str) -> Vec:
    assert mechanism.ground is not None
    return mechanism.local(mechanism.ground, point)


def _length(mechanism: Mechanism, link: str, p: str, q: str) -> float:
    a, b = mechanism.local(link, p), mechanism.local(link, q)
    return float(np.hypot(b[0] - a[0], b[1] - a[1]))


def _crank(mechanism: Mechanism, pose: Pose) -> tuple[str, str, str, float, float] | None:
    """(crank, pivot, pin-to-next, omega, alpha) for a crank-driven scene, the pin shared with one other link."""
    inp = mechanism.scene.input
    if not isinstance(inp, LinkInput) or mechanism.ground is None:
        return None
    pivot = pin_between(mechanism, inp.link, mechanism.ground)
    others = [p for p in mechanism.revolutes if inp.link in p.links and p is not pivot]
    if pivot is None or len(others) != 1:
        return None
    return inp.link, pivot.point, others[0].point, inp.omega, inp.alpha


def _crank_motion(mechanism: Mechanism, crank: str, pivot: str, pin: str, t: Array, w2: float,
                  a2: float) -> tuple[LinkMotion, Pair, Pair, Pair, Array]:
    """The crank's motion and its pin's position, velocity, acceleration; and the pin's world angle."""
    o = _ground_point(mechanism, pivot)
    lp, lq = mechanism.local(crank, pivot), mechanism.local(crank, pin)
    theta = t
    arm_angle = theta + _angle((lq[0] - lp[0], lq[1] - lp[1]))
    r = _length(mechanism, crank, pivot, pin)
    rx, ry = r * np.cos(arm_angle), r * np.sin(arm_angle)
    w = np.zeros_like(t) + w2
    al = np.zeros_like(t) + a2
    at = (o[0] + rx, o[1] + ry)
    vel = (-w * ry, w * rx)
    acc = (-al * ry - w * w * rx, al * rx - w * w * ry)
    still = _fixed(o[0], o[1], t)
    motion = _from_point(mechanism, crank, pivot, still[0], still[1], still[2], theta, w, al)
    return motion, at, vel, acc, arm_angle


def _four_bar(mechanism: Mechanism, pose: Pose) -> ClosedForm | None:
    found = _crank(mechanism, pose)
    if found is None or mechanism.sliders or len(mechanism.link_names) != 4 or len(mechanism.revolutes) != 4:
        return None
    crank, o2, pa, w2, a2 = found
    ground = mechanism.ground
    assert ground is not None
    coupler = next(k for k in _pin_links(mechanism, pa) if k != crank)
    rocker = next((k for k in mechanism.link_names if k not in (ground, crank, coupler)), None)
    pb = pin_between(mechanism, coupler, rocker) if rocker else None
    o4 = pin_between(mechanism, rocker, ground) if rocker else None
    if rocker is None or pb is None or o4 is None:
        return None
    g2, g4 = _ground_point(mechanism, o2), _ground_point(mechanism, o4.point)
    a = _length(mechanism, crank, o2, pa)
    b = _length(mechanism, coupler, pa, pb.point)
    c = _length(mechanism, rocker, o4.point, pb.point)
    d = float(np.hypot(g4[0] - g2[0], g4[1] - g2[1]))
    theta1 = _angle((g4[0] - g2[0], g4[1] - g2[1]))
    # the assembly the solve took: the sign of the Freudenstein root that reproduces theta4
    b_at = pose.links[rocker].world(mechanism.local(rocker, pb.point))
    theta4_now = _angle((b_at[0] - g4[0], b_at[1] - g4[1])) - theta1

    def angles(t: Array, sign: float) -> tuple[Array, Array, Array]:
        """theta2, theta3, theta4 from the frame line, for the crank angles t."""
        arm = t + _angle(_sub(mechanism.local(crank, pa), mechanism.local(crank, o2)))
        th2 = arm - theta1
        k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
        k4, k5 = d / b, (c * c - d * d - a * a - b * b) / (2 * a * b)
        aa = np.cos(th2) - k1 - k2 * np.cos(th2) + k3
        bb = -2 * np.sin(th2)
        cc = k1 - (k2 + 1) * np.cos(th2) + k3
        dd = np.cos(th2) - k1 + k4 * np.cos(th2) + k5
        ee = -2 * np.sin(th2)
        ff = k1 + (k4 - 1) * np.cos(th2) + k5
        th4 = 2 * np.arctan2(-bb + sign * np.sqrt(np.maximum(bb * bb - 4 * aa * cc, 0.0)), 2 * aa)
        th3 = 2 * np.arctan2(-ee + sign * np.sqrt(np.maximum(ee * ee - 4 * dd * ff, 0.0)), 2 * dd)
        return th2, th3, th4

    t_now = np.array([pose.links[crank].theta])
    sign = min((1.0, -1.0), key=lambda s: abs(float(np.remainder(angles(t_now, s)[2][0] - theta4_now + np.pi,
                                                                    2 * np.pi)) - np.pi))

    def motion(t: Array) -> dict[str, LinkMotion]:
        crank_motion, at, vel, acc, _ = _crank_motion(mechanism, crank, o2, pa, t, w2, a2)
        th2, th3, th4 = angles(t, sign)
        w3 = a * w2 * np.sin(th4 - th2) / (b * np.sin(th3 - th4))
        w4 = a * w2 * np.sin(th2 - th3) / (c * np.sin(th4 - th3))
        big_a, big_b = c * np.sin(th4), b * np.sin(th3)
        big_c = a * a2 * np.sin(th2) + a * w2 * w2 * np.cos(th2) + b * w3 * w3 * np.cos(th3) - c * w4 * w4 * np.cos(th4)
        big_d, big_e = c * np.cos(th4), b * np.cos(th3)
        big_f = a * a2 * np.cos(th2) - a * w2 * w2 * np.sin(th2) - b * w3 * w3 * np.sin(th3) + c * w4 * w4 * np.sin(th4)
        al3 = (big_c * big_d - big_a * big_f) / (big_a * big_e - big_b * big_d)
        al4 = (big_c * big_e - big_b * big_f) / (big_a * big_e - big_b * big_d)
        still = _fixed(g4[0], g4[1], t)
        return {
            ground: LinkMotion(*([np.zeros_like(t)] * 9)),
            crank: crank_motion,
            coupler: _from_point(mechanism, coupler, pa, at, vel, acc,
                                 _link_theta(mechanism, coupler, pa, pb.point, th3 + theta1), w3, al3),
            rocker: _from_point(mechanism, rocker, o4.point, still[0], still[1], still[2],
                                _link_theta(mechanism, rocker, o4.point, pb.point, th4 + theta1), w4, al4),
        }

    return ClosedForm("closed form (four-bar, Freudenstein)", motion)


def _sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1])


def _pin_links(mechanism: Mechanism, point: str) -> tuple[str, ...]:
    return mechanism.links_of_point(point)


def _slider_crank(mechanism: Mechanism, pose: Pose) -> ClosedForm | None:
    parts = slider_crank_links(mechanism)
    if parts is None:
        return None
    crank, rod, block, o2, pa, pb, spec, through, e = parts
    ground = mechanism.ground
    assert ground is not None
    g2 = _ground_point(mechanism, o2)
    a, b = _length(mechanism, crank, o2, pa), _length(mechanism, rod, pa, pb)
    slide_angle = _angle(e)
    h = -e[1] * (through[0] - g2[0]) + e[0] * (through[1] - g2[1])  # the slide's offset across it
    inp = mechanism.scene.input
    b_now = pose.links[block].world(mechanism.local(block, pb))
    a_now = pose.links[crank].world(mechanism.local(crank, pa))
    ahead = 1.0 if (b_now[0] - a_now[0]) * e[0] + (b_now[1] - a_now[1]) * e[1] >= 0 else -1.0

    def place(u: Array, w: Array) -> Pair:
        return (g2[0] + u * e[0] - w * e[1], g2[1] + u * e[1] + w * e[0])

    def block_motion(t: Array, u: Array, ud: Array, udd: Array) -> LinkMotion:
        zero = np.zeros_like(t)
        at = place(u, zero + h)
        return _from_point(mechanism, block, pb, at, (ud * e[0], ud * e[1]), (udd * e[0], udd * e[1]),
                           zero + spec.angle_rad, zero, zero)

    if isinstance(inp, LinkInput):
        found = _crank(mechanism, pose)
        if found is None:
            return None
        _, _, _, w2, a2 = found

        def motion(t: Array) -> dict[str, LinkMotion]:
            crank_motion, at, vel, acc, arm = _crank_motion(mechanism, crank, o2, pa, t, w2, a2)
            phi = arm - slide_angle
            sin3 = (h - a * np.sin(phi)) / b
            cos3 = ahead * np.sqrt(np.maximum(1.0 - sin3 * sin3, 0.0))
            th3 = np.arctan2(sin3, cos3)
            w3 = -a * w2 * np.cos(phi) / (b * cos3)
            al3 = (b * w3 * w3 * sin3 + a * w2 * w2 * np.sin(phi) - a * a2 * np.cos(phi)) / (b * cos3)
            u = a * np.cos(phi) + b * cos3
            ud = -a * np.sin(phi) * w2 - b * sin3 * w3
            udd = -a * np.cos(phi) * w2 * w2 - a * np.sin(phi) * a2 - b * cos3 * w3 * w3 - b * sin3 * al3
            return {ground: LinkMotion(*([np.zeros_like(t)] * 9)), crank: crank_motion,
                    rod: _from_point(mechanism, rod, pa, at, vel, acc,
                                     _link_theta(mechanism, rod, pa, pb, th3 + slide_angle), w3, al3),
                    block: block_motion(t, u, ud, udd)}

        return ClosedForm("closed form (slider-crank)", motion)
    if not isinstance(inp, SliderInput):
        return None
    s_dot, s_ddot = inp.s_dot, inp.s_ddot
    # A to the left (ccw) of O2 -> B or to its right
    side = 1.0 if (b_now[0] - g2[0]) * (a_now[1] - g2[1]) - (b_now[1] - g2[1]) * (a_now[0] - g2[0]) >= 0 else -1.0

    def piston(t: Array) -> dict[str, LinkMotion]:
        zero = np.zeros_like(t)
        bx, by = through[0] + t * e[0], through[1] + t * e[1]
        dx, dy = bx - g2[0], by - g2[1]
        dist = np.hypot(dx, dy)
        cos_a = np.clip((a * a + dist * dist - b * b) / (2 * a * dist), -1.0, 1.0)
        th2 = np.arctan2(dy, dx) + side * np.arccos(cos_a)
        e2 = (np.cos(th2), np.sin(th2))
        ax_, ay_ = g2[0] + a * e2[0], g2[1] + a * e2[1]
        th3 = np.arctan2(by - ay_, bx - ax_)
        e3 = (np.cos(th3), np.sin(th3))
        cross23 = e2[0] * e3[1] - e2[1] * e3[0]  # zero at the dead centres
        # a w2 J e2 + b w3 J e3 = s_dot e, dotted with e3 and with e2 (e3 . J e2 = cross(e2, e3))
        w2 = s_dot * (e3[0] * e[0] + e3[1] * e[1]) / (a * cross23)
        w3 = -s_dot * (e2[0] * e[0] + e2[1] * e[1]) / (b * cross23)
        rx = s_ddot * e[0] + a * w2 * w2 * e2[0] + b * w3 * w3 * e3[0]
        ry = s_ddot * e[1] + a * w2 * w2 * e2[1] + b * w3 * w3 * e3[1]
        al2 = (e3[0] * rx + e3[1] * ry) / (a * cross23)
        al3 = -(e2[0] * rx + e2[1] * ry) / (b * cross23)
        still = _fixed(g2[0], g2[1], t)
        crank_motion = _from_point(mechanism, crank, o2, still[0], still[1], still[2],
                                   _link_theta(mechanism, crank, o2, pa, th2), w2, al2)
        va = (-w2 * a * e2[1], w2 * a * e2[0])
        aa = (-al2 * a * e2[1] - w2 * w2 * a * e2[0], al2 * a * e2[0] - w2 * w2 * a * e2[1])
        u = (bx - g2[0]) * e[0] + (by - g2[1]) * e[1]
        return {ground: LinkMotion(*([zero] * 9)), crank: crank_motion,
                rod: _from_point(mechanism, rod, pa, (ax_, ay_), va, aa, _link_theta(mechanism, rod, pa, pb, th3),
                                 w3, al3),
                block: block_motion(t, u, zero + s_dot, zero + s_ddot)}

    return ClosedForm("closed form (piston-driven slider-crank)", piston)


def _slotted_lever(mechanism: Mechanism, pose: Pose) -> ClosedForm | None:
    found = _crank(mechanism, pose)
    if found is None or len(mechanism.sliders) != 1 or len(mechanism.link_names) != 4 or len(mechanism.revolutes) != 3:
        return None
    crank, o2, pa, w2, a2 = found
    ground = mechanism.ground
    assert ground is not None
    spec = mechanism.sliders[0]
    block, lever = spec.block, spec.guide
    o4 = pin_between(mechanism, lever, ground)
    if spec.point != pa or set(_pin_links(mechanism, pa)) != {crank, block} or o4 is None:
        return None
    g4 = _ground_point(mechanism, o4.point)
    p4 = mechanism.local(lever, o4.point)
    c_ang = spec.angle_rad
    ec = (np.cos(c_ang), np.sin(c_ang))
    m = float(ec[0] * (spec.through[1] - p4[1]) - ec[1] * (spec.through[0] - p4[0]))  # slot offset from O4
    theta_now = pose.links[lever].theta
    a_now = pose.links[crank].world(mechanism.local(crank, pa))
    psi_now = _angle((a_now[0] - g4[0], a_now[1] - g4[1]))
    rho_now = float(np.hypot(a_now[0] - g4[0], a_now[1] - g4[1]))
    gamma_now = float(np.arcsin(np.clip(m / rho_now, -1, 1)))
    # beta = theta4 + c is psi - gamma (slot pointing at A) or psi - pi + gamma (pointing away)
    turn = float(np.remainder(theta_now + c_ang - (psi_now - gamma_now) + np.pi, 2 * np.pi) - np.pi)
    away = abs(turn) > np.pi / 2

    def motion(t: Array) -> dict[str, LinkMotion]:
        crank_motion, at, vel, acc, _ = _crank_motion(mechanism, crank, o2, pa, t, w2, a2)
        rx, ry = at[0] - g4[0], at[1] - g4[1]
        rho = np.hypot(rx, ry)
        psi = np.arctan2(ry, rx)
        mm = -m if away else m
        root = np.sqrt(np.maximum(rho * rho - mm * mm, 0.0))
        gamma = np.arcsin(np.clip(mm / rho, -1.0, 1.0))
        psi_d = (rx * vel[1] - ry * vel[0]) / (rho * rho)
        rho_d = (rx * vel[0] + ry * vel[1]) / rho
        psi_dd = (rx * acc[1] - ry * acc[0]) / (rho * rho) - 2 * rho_d * psi_d / rho
        rho_dd = (vel[0] ** 2 + vel[1] ** 2 + rx * acc[0] + ry * acc[1]) / rho - rho_d * rho_d / rho
        f = rho * root
        f_d = rho_d * root + rho * rho * rho_d / root
        gamma_d = -mm * rho_d / f
        gamma_dd = -mm * (rho_dd * f - rho_d * f_d) / (f * f)
        beta = psi - gamma + (np.pi if away else 0.0)
        w4, al4 = psi_d - gamma_d, psi_dd - gamma_dd
        still = _fixed(g4[0], g4[1], t)
        return {ground: LinkMotion(*([np.zeros_like(t)] * 9)), crank: crank_motion,
                lever: _from_point(mechanism, lever, o4.point, still[0], still[1], still[2], beta - c_ang, w4, al4),
                block: _from_point(mechanism, block, pa, at, vel, acc, beta, w4, al4)}

    return ClosedForm("closed form (slotted lever)", motion)


def closed_form(mechanism: Mechanism, pose: Pose) -> ClosedForm | None:
    """The closed form of a standard mechanism in the scene, or None (``pose``: the assembly taken)."""
    for recognise in (_four_bar, _slider_crank, _slotted_lever):
        found = recognise(mechanism, pose)
        if found is not None:
            return found
    return None
