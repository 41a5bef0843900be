"""The transmission angle of each dyad: the angle at which its two velocity direction lines cross.

For a four-bar's output dyad the lines are perpendicular to the coupler and to the rocker, so
the angle is the textbook one between coupler and rocker; for a slider-crank, between the rod
and the normal to the slide; for a slotted lever, between the slot's normal and the lever. It
is reported acute, from 0 to 90 degrees: 90 transmits best, 0 is a dead point, where the
velocity lines are parallel and the construction fails. A group solved by Newton's method has
no two lines and no transmission angle.
"""

from __future__ import annotations

import numpy as np

from kinepoly.engine.plan import Dyad, PositionPlan
from kinepoly.engine.position import Positions
from kinepoly.geom.arrays import Points, Reals, cross, length, turn
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import SliderSpec

__all__ = ["dyad_point", "transmission_angles"]


def dyad_point(mechanism: Mechanism, dyad: Dyad) -> str:
    """The point whose velocity the dyad's two lines find (it names the dyad's transmission angle)."""
    if dyad.kind in ("RRR", "RRP", "PRP"):
        assert isinstance(dyad.inner, Revolute)
        return dyad.inner.point
    if dyad.kind == "RPR":
        assert isinstance(dyad.inner, SliderSpec)
        block_joint = dyad.first_joint if dyad.first == dyad.inner.block else dyad.second_joint
        assert isinstance(block_joint, Revolute)
        return block_joint.point
    return mechanism.scene.link(dyad.second).points[0].name


def _slide(positions: Positions, slider: SliderSpec) -> Points:
    return positions.poses[slider.guide].rotation * turn(slider.angle_rad)


def _directions(positions: Positions, dyad: Dyad) -> tuple[Points, Points]:
    point = positions.point
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p2 = dyad.inner.point
        first = 1j * (point(p2) - point(dyad.first_joint.point))
        if isinstance(dyad.second_joint, Revolute):
            return first, 1j * (point(p2) - point(dyad.second_joint.point))
        return first, _slide(positions, dyad.second_joint)
    if dyad.kind == "RPR":
        slider = dyad.inner
        assert isinstance(slider, SliderSpec)
        guide_joint = dyad.first_joint if dyad.first == slider.guide else dyad.second_joint
        block_joint = dyad.second_joint if dyad.first == slider.guide else dyad.first_joint
        assert isinstance(guide_joint, Revolute) and isinstance(block_joint, Revolute)
        return 1j * (point(block_joint.point) - point(guide_joint.point)), _slide(positions, slider)
    first_slider = dyad.first_joint if dyad.kind == "PRP" else dyad.inner
    assert isinstance(first_slider, SliderSpec) and isinstance(dyad.second_joint, SliderSpec)
    return _slide(positions, first_slider), _slide(positions, dyad.second_joint)


def transmission_angles(positions: Positions, plan: PositionPlan,
                        line_sines: dict[str, Reals] | None = None) -> dict[str, Reals]:
    """Per dyad (named by ``dyad_point``), the acute angle in radians between its velocity lines.

    ``line_sines``: the sines the velocity construction met, by group name, when it ran.
    """
    out: dict[str, Reals] = {}
    for group in plan.groups:
        if isinstance(group, Dyad):
            sine = None if line_sines is None else line_sines.get(group.name)
            if sine is None:
                first, second = _directions(positions, group)
                sine = cross(first, second) / (length(first) * length(second))
            out[dyad_point(positions.mechanism, group)] = np.arcsin(np.minimum(np.abs(sine), 1.0))
    return out
