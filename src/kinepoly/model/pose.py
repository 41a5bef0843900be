"""The position of every link at one input: frozen values."""

from __future__ import annotations

import math

from msgspec import Struct, field

__all__ = ["LinkPose", "Pose"]

Vec = tuple[float, float]


class LinkPose(Struct, frozen=True):
    """A link's place in the frame: world = (x, y) + R(theta) local; theta in radians."""

    x: float
    y: float
    theta: float

    def world(self, local: Vec) -> Vec:
        c, s = math.cos(self.theta), math.sin(self.theta)
        return (self.x + c * local[0] - s * local[1], self.y + s * local[0] + c * local[1])

    def to_local(self, world: Vec) -> Vec:
        c, s = math.cos(self.theta), math.sin(self.theta)
        dx, dy = world[0] - self.x, world[1] - self.y
        return (c * dx + s * dy, -s * dx + c * dy)


class Pose(Struct, frozen=True):
    """Poses of the links that were solved (only those the question needs)."""

    links: dict[str, LinkPose]
    marks: dict[str, Vec] = field(default_factory=dict)
    """Points the construction found on the mechanism that no link names (a triad's Assur point)."""

    def world(self, mechanism_local: Vec, link: str) -> Vec:
        return self.links[link].world(mechanism_local)
