"""From the motion of every link to the reported quantities, in any arithmetic.

A method of the bench that knows each link's pose and its first two time derivatives (the
closed forms, finite differences, the mpmath reference) turns them into the same keyed
quantities the cross-check compares (``points.B.velocity``, ``links.3.alpha``,
``sliders.14.s_ddot``, ...). The formulas are the rigid-body ones, written once for floats,
numpy arrays and mpmath numbers alike (``cos`` and ``sin`` are passed in):

    r_P = r + A p,   v_P = r_dot + omega J A p,   a_P = r_ddot + alpha J A p - omega^2 A p.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from msgspec import Struct

from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.link_point import LinkPoint

__all__ = ["LinkMotion", "Trig", "evaluate", "quantity_kind"]

Num = Any
"""A float, a numpy array (a batch of positions) or an mpmath number."""

Pair = tuple[Num, Num]


class Trig(Struct, frozen=True):
    """The cosine and sine of the arithmetic in use (math, numpy or mpmath)."""

    cos: Callable[[Num], Num]
    sin: Callable[[Num], Num]


class LinkMotion(Struct, frozen=True):
    """A link's pose (x, y, theta) in the solve's frame and its first and second time derivatives."""

    x: Num
    y: Num
    theta: Num
    vx: Num
    vy: Num
    omega: Num
    ax: Num
    ay: Num
    alpha: Num


_KINDS = {"position": "position", "velocity": "velocity", "acceleration": "acceleration", "omega": "omega",
          "alpha": "alpha", "angle": "angle", "s": "position", "s_dot": "velocity", "s_ddot": "acceleration",
          "coriolis": "acceleration"}


def quantity_kind(key: str) -> str:
    """The kind of a quantity key, as the cross-check names it."""
    return _KINDS[key.rsplit(".", 1)[1]]


class _Frame:
    def __init__(self, mechanism: Mechanism, motion: dict[str, LinkMotion], trig: Trig) -> None:
        self.mechanism = mechanism
        self.motion = motion
        self.trig = trig

    def arm(self, link: str, local: Pair) -> Pair:
        m = self.motion[link]
        c, s = self.trig.cos(m.theta), self.trig.sin(m.theta)
        return (c * local[0] - s * local[1], s * local[0] + c * local[1])

    def world(self, link: str, local: Pair) -> Pair:
        m, arm = self.motion[link], self.arm(link, local)
        return (m.x + arm[0], m.y + arm[1])

    def to_local(self, link: str, world: Pair) -> Pair:
        m = self.motion[link]
        c, s = self.trig.cos(m.theta), self.trig.sin(m.theta)
        dx, dy = world[0] - m.x, world[1] - m.y
        return (c * dx + s * dy, -s * dx + c * dy)

    def velocity(self, link: str, local: Pair) -> Pair:
        m, arm = self.motion[link], self.arm(link, local)
        return (m.vx - m.omega * arm[1], m.vy + m.omega * arm[0])

    def acceleration(self, link: str, local: Pair) -> Pair:
        m, arm = self.motion[link], self.arm(link, local)
        w2 = m.omega * m.omega
        return (m.ax - m.alpha * arm[1] - w2 * arm[0], m.ay + m.alpha * arm[0] - w2 * arm[1])

    def material(self, label: str) -> tuple[str, Pair]:
        """The link and local coordinates of ``A`` (its first owner) or ``A@k`` (link k's point under A)."""
        named = LinkPoint.parse(label)
        point, on = named.point, named.link or ""
        owner = next(k for k in self.mechanism.links_of_point(point) if k in self.motion)
        local = self.mechanism.local(owner, point)
        if not on:
            return owner, local
        return on, self.to_local(on, self.world(owner, local))

    def slider(self, name: str, what: str) -> Num:
        spec = self.mechanism.slider(name)
        g = self.motion[spec.guide]
        c, s = self.trig.cos(g.theta + spec.angle_rad), self.trig.sin(g.theta + spec.angle_rad)
        at = self.world(spec.block, self.mechanism.local(spec.block, spec.point))
        if what == "s":
            start = self.world(spec.guide, spec.through)
            return c * (at[0] - start[0]) + s * (at[1] - start[1])
        under = self.to_local(spec.guide, at)
        vb, vg = self.velocity(spec.block, self.mechanism.local(spec.block, spec.point)), self.velocity(spec.guide,
                                                                                                        under)
        rel = (vb[0] - vg[0], vb[1] - vg[1])
        if what == "s_dot":
            return c * rel[0] + s * rel[1]
        coriolis = (-2.0 * g.omega * rel[1], 2.0 * g.omega * rel[0])
        if what == "coriolis":
            return coriolis
        ab = self.acceleration(spec.block, self.mechanism.local(spec.block, spec.point))
        ag = self.acceleration(spec.guide, under)
        return c * (ab[0] - ag[0] - coriolis[0]) + s * (ab[1] - ag[1] - coriolis[1])


def evaluate(mechanism: Mechanism, motion: dict[str, LinkMotion], keys: list[str], trig: Trig,
             origin: Pair = (0.0, 0.0)) -> dict[str, Num]:
    """The value of every key (positions get ``origin`` added: the user's frame)."""
    frame = _Frame(mechanism, motion, trig)
    out: dict[str, Num] = {}
    for key in keys:
        family, rest = key.split(".", 1)
        name, what = rest.rsplit(".", 1)
        if family == "points":
            link, local = frame.material(name)
            if what == "position":
                at = frame.world(link, local)
                out[key] = (at[0] + origin[0], at[1] + origin[1])
            elif what == "velocity":
                out[key] = frame.velocity(link, local)
            else:
                out[key] = frame.acceleration(link, local)
        elif family == "links":
            m = motion[name]
            out[key] = {"angle": m.theta, "omega": m.omega, "alpha": m.alpha}[what]
        else:
            out[key] = frame.slider(name, what)
    return out
