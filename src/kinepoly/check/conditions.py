"""Conditions worth a warning, with stable codes, and the wording of a singular position.

* ``transmission-angle``: a dyad transmits its motion at a transmission angle under
  ``MIN_TRANSMISSION_DEG`` (a design concern: the force that drives the output link is
  mostly spent pressing on its bearing). The angle is the textbook one (``engine.transmission``):
  for two pins, the angle between the two links at the inner joint (coupler and rocker); with a
  slider, the angle between the force line (along a pinned link, or normal to a slide) and the
  path the driven point can take (along a slide, or normal to the arm of a turning link). 90
  degrees is ideal; it is reported folded into [0, 90].
* ``near-singular``: the error estimate of some kind exceeds ``NEAR_SINGULAR_ERROR``
  (relative): the position is close to a dead point or a change point.
"""

from __future__ import annotations

from kinepoly.check.estimate import ErrorEstimate, crossings
from kinepoly.engine.steps import Step
from kinepoly.engine.transmission import Transmission
from kinepoly.errors import SingularityError
from kinepoly.geom.tolerances import NEAR_SINGULAR_ERROR
from kinepoly.notice import Notice

__all__ = [
    "MIN_TRANSMISSION_DEG",
    "NEAR_SINGULAR_ERROR",
    "near_singular_notice",
    "singular_position_error",
    "transmission_notices",
]

MIN_TRANSMISSION_DEG = 40.0
"""Below this transmission angle a dyad gets a ``transmission-angle`` warning."""


def transmission_notices(found: list[Transmission], where: str) -> list[Notice]:
    return [Notice("transmission-angle",
                   f"group {t.group} at {where}: the transmission angle at {t.joint} (between {t.between}) is "
                   f"{t.angle_deg:.3g} deg, under {MIN_TRANSMISSION_DEG:g} deg: most of the driving force presses on "
                   "the bearings instead of moving the link (a design concern, not a numerical one)")
            for t in found if t.angle_deg < MIN_TRANSMISSION_DEG]


def near_singular_notice(estimate: ErrorEstimate, where: str) -> Notice | None:
    """A ``near-singular`` warning when some kind's estimate exceeds NEAR_SINGULAR_ERROR."""
    if estimate.largest <= NEAR_SINGULAR_ERROR:
        return None
    kind = max(estimate.relative, key=lambda name: estimate.relative[name])
    crossing = ""
    polygon = "acceleration" if kind in ("acceleration", "alpha") else "velocity"
    worst = estimate.worst_crossing.get(polygon) or estimate.worst_crossing.get("velocity")
    if worst is not None:
        crossing = (f"; the flattest crossing is that of {worst.result} ({worst.equation}), whose direction lines "
                    f"meet at {worst.angle_deg:.3g} deg")
    return Notice("near-singular",
                  f"at {where} the estimated relative error of the {kind} is {estimate.relative[kind]:.2g}, above "
                  f"{NEAR_SINGULAR_ERROR:g}: the position is near a dead point or a change point (condition number "
                  f"of the velocity equations {estimate.condition_number:.3g}{crossing})")


def singular_position_error(where: str, found: list[Transmission], steps: tuple[Step, ...],
                            reason: str) -> SingularityError:
    """The error for a position the construction passed but whose velocity equations are singular.

    It names the joint (the dyad with the smallest transmission angle, or the flattest crossing
    of the polygons), the position, and why: what lies in line there, and ``reason``.
    """
    flat = min(found, key=lambda t: t.angle_deg, default=None)
    crossing = min(crossings(steps), key=lambda c: abs(c.sin_angle), default=None)
    if flat is not None:
        what = (f"joint {flat.joint} of group {flat.group}: {flat.at_zero} (transmission angle "
                f"{flat.angle_deg:.2g} deg), a dead centre where the input cannot drive {flat.joint}")
    elif crossing is not None:
        what = (f"{crossing.result} ({crossing.equation}): its direction lines meet at "
                f"{crossing.angle_deg:.2g} deg")
    else:
        what = "the velocity equations"
    return SingularityError(f"singular position at {where}: {what}; {reason}")
