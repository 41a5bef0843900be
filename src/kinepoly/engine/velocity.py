"""The velocity polygon over rows: the inputs' known terms, then each group of the plan constructed by its
kind (``engine.table``, ``engine.kinds``).

For each dyad the unknown tip is where two lines through known tips cross: perpendicular to
the link for a turning relative velocity (v_B/A is perpendicular to AB), parallel to the slide
for a sliding one. Omega of a link is then read off the polygon, |v_B/A| / |AB| with the sense
of v_B/A: the line through a along k x AB meets the other at a + t (k x AB), so omega = t, the
crossing's ``along`` (``read_rate``).
"""

from __future__ import annotations

import math

import numpy as np

from kinepoly.engine.contacts import record_equivalent_links
from kinepoly.engine.groups import PositionPlan
from kinepoly.engine.lines import lay_driven_slider, link_length, read_rate, slide_direction, slide_reference
from kinepoly.engine.polygon import CrossLines, Polygon, sense
from kinepoly.engine.position import Positions
from kinepoly.engine.results import VelocityContext, VelocityResult
from kinepoly.engine.steps import DrawnVector, Step
from kinepoly.engine.table import kind_of
from kinepoly.errors import SceneError
from kinepoly.geom.arrays import Points, cross_lines
from kinepoly.geom.tolerances import RIGID_REL_TOL, TINY_POSITIVE
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput

__all__ = ["VelocityResult", "construct_velocity", "link_length", "read_rate", "slide_direction", "slide_reference"]


def _drive(polygon: Polygon, sliding: dict[str, Points]) -> None:
    mech = polygon.mechanism
    if isinstance(mech.scene.input, GivenInput):
        _given(polygon, mech.scene.input)
        return
    for drive in mech.drives:
        if drive.on_frame:
            _frame_drive(polygon, drive.spec, sliding)


def _frame_drive(polygon: Polygon, inp: LinkInput | SliderInput, sliding: dict[str, Points]) -> None:
    mech = polygon.mechanism
    if isinstance(inp, LinkInput):
        polygon.set_rate(inp.link, np.full(polygon.n, inp.omega))
        if polygon.record:
            polygon.step(Step(polygon="velocity", kind="known", equation=f"omega{mech.ground}{inp.link} given",
                              result=f"omega{mech.ground}{inp.link}", value=(inp.omega,), topic="input-rate",
                              params=(("link", inp.link), ("ground", mech.ground or ""), ("rate", abs(inp.omega)),
                                      ("sense", sense(inp.omega)))))
    else:
        slider = mech.slider(inp.slider)
        sliding[slider.name] = lay_driven_slider(polygon, slider, inp.s_dot)


def _given(polygon: Polygon, given: GivenInput) -> None:
    link = polygon.mechanism.link_names[0]
    for g in given.points:
        value = np.full(polygon.n, complex(*g.velocity))
        polygon.add_tip(link, g.name, value)
        if polygon.record:
            polygon.step(Step(polygon="velocity", kind="known", equation=f"v_{g.name} given", result=g.name.lower(),
                              known=((f"v_{g.name}", "magnitude and direction"),),
                              vectors=(DrawnVector(f"v_{g.name}", (0.0, 0.0), g.velocity, "absolute"),),
                              value=g.velocity, topic="given-point",
                              params=(("point", g.name), ("magnitude", math.hypot(*g.velocity)))))
    first, second = given.points[0], given.points[1]
    at = polygon.world(second.name) - polygon.world(first.name)
    rel = complex(*second.velocity) - complex(*first.velocity)
    along = float(np.real(np.conj(at[0] / abs(at[0])) * rel))
    if abs(along) > RIGID_REL_TOL * max(math.hypot(*first.velocity), math.hypot(*second.velocity), TINY_POSITIVE):
        raise SceneError(f"{polygon.mechanism.scene.source}: given.{second.name}.velocity: the given velocities of "
                         f"{first.name} and {second.name} differ by {along:.6g} {polygon.unit} along "
                         f"{first.name}{second.name}; a rigid body allows none (make v_{second.name}/{first.name} "
                         f"perpendicular to {first.name}{second.name})")
    read_rate(polygon, link, first.name, second.name, np.asarray((rel / (1j * at)).real))


def construct_velocity(positions: Positions, plan: PositionPlan, wanted: tuple[tuple[str, str], ...] = (), *,
                       unit: str = "mm", record: bool = False, strict: bool = False,
                       crossing: CrossLines = cross_lines) -> VelocityResult:
    """Construct the velocity polygon at every row for every group of ``plan``, then the tips of ``wanted``.

    ``wanted`` holds (link, point) pairs: the velocity of ``point`` as a point of ``link``.
    ``record``: keep the steps of row 0; ``strict``: a parallel pair of lines raises (a solve).
    """
    polygon = Polygon(positions, "velocity", unit=unit, record=record, strict=strict, crossing=crossing,
                      constants=plan.constants)
    state = VelocityContext(polygon)
    _drive(polygon, state.sliding)
    record_equivalent_links(polygon)
    for group in plan.groups:
        kind_of(group).velocity(state, group)
    for link, point in wanted:
        polygon.tip(link, point)
    return VelocityResult(polygon, state.sliding, state.equivalent)
