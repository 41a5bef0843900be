"""Conditions worth a warning, with stable codes, and the wording of a singular position.

* ``transmission-angle``: a dyad transmits its motion at a transmission angle under
  ``MIN_TRANSMISSION_DEG`` (a design concern: the force that drives the output link is
  mostly spent pressing on its bearing). The angle is the textbook one: for two pins, the
  angle between the two links at the inner joint (coupler and rocker); with a slider, the
  angle between the force line (along a pinned link, or normal to a slide) and the path the
  driven point can take (along a slide, or normal to the arm of a turning link). 90 degrees
  is ideal; it is reported folded into [0, 90].
* ``near-singular``: the error estimate of some kind exceeds ``NEAR_SINGULAR_ERROR``
  (relative): the position is close to a dead point or a change point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from kinepoly.check.estimate import ErrorEstimate, crossings
from kinepoly.engine.plan import Dyad, PositionPlan
from kinepoly.engine.steps import Step
from kinepoly.errors import SingularityError
from kinepoly.geom.vec import Vec, angle_of, norm, rotate, sub
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.model.pose import Pose
from kinepoly.notice import Notice
from kinepoly.scene.spec import SliderSpec

__all__ = [
    "MIN_TRANSMISSION_DEG",
    "NEAR_SINGULAR_ERROR",
    "Transmission",
    "near_singular_notice",
    "singular_position_error",
    "transmission_angles",
    "transmission_notices",
]

MIN_TRANSMISSION_DEG = 40.0
"""Below this transmission angle a dyad gets a ``transmission-angle`` warning."""

NEAR_SINGULAR_ERROR = 1e-9
"""An estimated relative error above this gets a ``near-singular`` warning."""


@dataclass(frozen=True)
class Transmission:
    """The transmission angle of one dyad, folded into [0, 90] degrees, and what it is between."""

    group: str
    joint: str
    angle_deg: float
    between: str
    at_zero: str
    """What a zero transmission angle means here, in words (a dead centre of this dyad)."""


def _fold(first: Vec, second: Vec) -> float:
    """The angle between two lines (not rays), in [0, 90] degrees."""
    if norm(first) == 0.0 or norm(second) == 0.0:
        return 90.0
    turn = math.remainder(angle_of(second) - angle_of(first), math.pi)
    return math.degrees(abs(turn))


def _world(mechanism: Mechanism, pose: Pose, link: str, point: str) -> Vec:
    return pose.links[link].world(mechanism.local(link, point))


def _slide(pose: Pose, slider: SliderSpec) -> Vec:
    return rotate((1.0, 0.0), pose.links[slider.guide].theta + slider.angle_rad)


def _other(joint: Revolute | SliderSpec, link: str) -> str:
    if isinstance(joint, Revolute):
        return joint.other(link)
    return joint.guide if joint.block == link else joint.block


def _dyad_transmission(mechanism: Mechanism, pose: Pose, dyad: Dyad) -> Transmission | None:
    i, j = dyad.first, dyad.second
    first, inner, second = dyad.first_joint, dyad.inner, dyad.second_joint
    if dyad.kind == "RRR":
        assert isinstance(first, Revolute) and isinstance(inner, Revolute) and isinstance(second, Revolute)
        p1, p2, p3 = first.point, inner.point, second.point
        arm_i = sub(_world(mechanism, pose, i, p2), _world(mechanism, pose, i, p1))
        arm_j = sub(_world(mechanism, pose, j, p2), _world(mechanism, pose, j, p3))
        return Transmission(dyad.name, p2, _fold(arm_i, arm_j), f"{p1}{p2} and {p3}{p2}",
                            f"the links {p1}{p2} and {p3}{p2} are in line")
    if dyad.kind == "RRP":
        assert isinstance(first, Revolute) and isinstance(inner, Revolute) and isinstance(second, SliderSpec)
        p1, p2 = first.point, inner.point
        arm = sub(_world(mechanism, pose, i, p2), _world(mechanism, pose, i, p1))
        return Transmission(dyad.name, p2, 90.0 - _fold(arm, _slide(pose, second)),
                            f"{p1}{p2} and the normal to slider {second.name}",
                            f"the link {p1}{p2} is square to slider {second.name}'s line")
    if dyad.kind == "RPR":
        assert isinstance(inner, SliderSpec) and isinstance(first, Revolute) and isinstance(second, Revolute)
        outer = {i: first, j: second}
        q, p = outer[inner.guide].point, outer[inner.block].point
        arm = sub(_world(mechanism, pose, inner.block, p), _world(mechanism, pose, inner.guide, q))
        return Transmission(dyad.name, p, 90.0 - _fold(arm, _slide(pose, inner)),
                            f"the normal to slider {inner.name} and the path of {p} about {q}",
                            f"slider {inner.name}'s line is square to {q}{p}")
    if dyad.kind in ("PRP", "RPP"):
        slide_a = first if isinstance(first, SliderSpec) else inner
        assert isinstance(slide_a, SliderSpec) and isinstance(second, SliderSpec)
        return Transmission(dyad.name, slide_a.point, _fold(_slide(pose, slide_a), _slide(pose, second)),
                            f"sliders {slide_a.name} and {second.name}",
                            f"the lines of sliders {slide_a.name} and {second.name} are parallel")
    return None


def transmission_angles(mechanism: Mechanism, pose: Pose, plan: PositionPlan) -> list[Transmission]:
    """The transmission angle of every dyad of the plan (groups solved by Newton have none)."""
    out = []
    for group in plan.groups:
        if isinstance(group, Dyad) and all(link in pose.links for link in group.links):
            found = _dyad_transmission(mechanism, pose, group)
            if found is not None:
                out.append(found)
    return out


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
