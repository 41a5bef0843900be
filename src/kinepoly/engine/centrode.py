"""The instant center of a link with the frame at every row, from the velocity polygon: its centrodes.

The center is the point of the link whose velocity image is the pole: from a point P of the link
with velocity v, I = P + (k x v) / omega. Over a sweep's rows it traces the fixed centrode (in the
frame) and the moving one (in the link's own coordinates). Where the link does not turn the
center is at infinity, and those rows have none.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from msgspec import Struct

from kinepoly.engine.velocity import VelocityResult
from kinepoly.geom.arrays import Bools, Points
from kinepoly.geom.hull import diameter
from kinepoly.geom.tolerances import AT_INFINITY_REL
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose

__all__ = ["Centrodes", "frame_centrodes", "mechanism_size"]


class Centrodes(Struct, frozen=True):
    """The instant center of one link with the frame at every row: in the frame (``fixed``) and in the
    link's own coordinates (``moving``); ``finite`` the rows where it is not at infinity."""

    fixed: Points
    moving: Points
    finite: Bools


def mechanism_size(mechanism: Mechanism, poses: Mapping[str, LinkPose]) -> float:
    """The largest distance between two points of the posed links (1.0 when there is none)."""
    return diameter([pose.world(p.local) for link, pose in poses.items()
                     for p in mechanism.scene.link(link).points]) or 1.0


def frame_centrodes(velocity: VelocityResult, link: str, size_row: int = 0) -> Centrodes:
    """The instant center of ``link`` with the frame at every row (the mechanism's size, which tells a
    center at infinity, is taken at row ``size_row``)."""
    polygon = velocity.polygon
    positions = polygon.positions
    point = positions.mechanism.scene.link(link).points[0].name
    v = polygon.tip(link, point)
    omega = polygon.rate_of(link)
    assert omega is not None
    size = mechanism_size(positions.mechanism, positions.row(size_row))
    finite = np.abs(omega) * AT_INFINITY_REL * size > np.abs(v)
    center = positions.point(point) + (1j * v) / np.where(finite, omega, 1.0)
    return Centrodes(center, positions.poses[link].to_local(center), finite)
