"""Body coordinates of the analytic solution: each moving link's place and motion as numbers.

Every moving link k has q_k = (x_k, y_k, theta_k), its ``LinkPose``: a point with local
coordinates p is at r_k + A(theta_k) p in the frame, A(theta) the rotation by theta. The
ground has the constant pose (0, 0, 0). With J = [[0, -1], [1, 0]] (a quarter turn ccw),
dA/dtheta = J A, so a point's velocity is v = r_dot + omega J A p and its acceleration
a = r_ddot + alpha J A p - omega^2 A p.

:class:`Layout` says which columns of q belong to which link; :func:`bodies` turns q (and
q_dot) into each link's :class:`Body`; :func:`mechanism_size` is the length L that makes
the equations dimensionless.
"""

from __future__ import annotations

import math

import numpy as np
from msgspec import Struct

from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import SliderInput

__all__ = [
    "Body",
    "J",
    "Layout",
    "Vec",
    "as_array",
    "as_pair",
    "bodies",
    "mechanism_size",
    "plain_float",
    "rotation",
]

Vec = tuple[float, float]

J = np.array([[0.0, -1.0], [1.0, 0.0]])
"""The quarter turn ccw: dA/dtheta = J A."""


def rotation(theta: float) -> np.ndarray:
    """A(theta), the rotation matrix by theta (ccw)."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def as_array(v: Vec) -> np.ndarray:
    return np.array([float(v[0]), float(v[1])])


def plain_float(x: float) -> float:
    """A plain float, with -0.0 made 0.0."""
    return float(x) + 0.0


def as_pair(v: np.ndarray) -> Vec:
    return (plain_float(v[0]), plain_float(v[1]))



class Layout(Struct, frozen=True):
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


class Body(Struct, frozen=True):
    """One link's place and motion: r, theta, A(theta), omega, r_dot (zeros for the ground).

    theta is kept as q has it (not wrapped), so angle rows of Phi are exactly linear.
    """

    r: np.ndarray
    theta: float
    A: np.ndarray
    omega: float
    r_dot: np.ndarray


def bodies(layout: Layout, q: np.ndarray, q_dot: np.ndarray | None = None) -> dict[str, Body]:
    """Every link's Body from q (and q_dot; zero velocities without it)."""
    zero = np.zeros(2)
    out = {layout.ground: Body(zero, 0.0, np.eye(2), 0.0, zero)}
    for link in layout.moving:
        k = layout.column(link)
        assert k is not None
        theta = float(q[k + 2])
        w, rd = (0.0, zero) if q_dot is None else (float(q_dot[k + 2]), q_dot[k : k + 2].copy())
        out[link] = Body(q[k : k + 2].copy(), theta, rotation(theta), w, rd)
    return out


def mechanism_size(mechanism: Mechanism) -> float:
    """L: the largest distance of any named point (or slider line point) from its link's origin."""
    lengths = [math.hypot(*p.local) for link in mechanism.scene.links for p in link.points]
    lengths += [math.hypot(*s.through) for s in mechanism.sliders]
    lengths += [abs(inp.s) for inp in mechanism.scene.inputs if isinstance(inp, SliderInput)]
    size = max(lengths, default=0.0)
    return size if size > 0.0 else 1.0
