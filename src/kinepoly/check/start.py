"""Start poses for the analytic Newton: links missing from a start guessed from their placed neighbours."""

from __future__ import annotations

from kinepoly.check.coordinates import Vec, as_array, rotation
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose

__all__ = ["complete_start"]


def complete_start(mechanism: Mechanism, start: dict[str, LinkPose]) -> dict[str, LinkPose]:
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
    arm = rotation(theta) @ as_array(local)
    return LinkPose(world[0] - float(arm[0]), world[1] - float(arm[1]), theta)
