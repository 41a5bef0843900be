"""The acceleration polygon over rows, after the velocity polygon: the inputs' known terms, then each group
of the plan constructed by its kind (``engine.table``, ``engine.kinds``).

Known terms are laid end to end (normal terms omega^2 r toward the center, Coriolis terms
2 omega x v_rel), then two direction lines are drawn (tangential: perpendicular to the link;
sliding: parallel to the slide) and their crossing is the unknown tip. Alpha is read off the
tangential term. A Coriolis term exists only where a block slides on a guide that can turn.

``Rules`` switch a construction mistake in (the homework checker's diagnoses): the normal term
laid away from the center, the Coriolis term left out or reversed. The right rules are the default.
"""

from __future__ import annotations

import math

import numpy as np

from kinepoly.engine.groups import PositionPlan
from kinepoly.engine.lines import lay_driven_slider, read_rate
from kinepoly.engine.polygon import CrossLines, Polygon, sense
from kinepoly.engine.results import RIGHT, AccelerationContext, AccelerationResult, Rules, VelocityResult
from kinepoly.engine.steps import DrawnVector, Step
from kinepoly.engine.table import kind_of
from kinepoly.errors import SceneError
from kinepoly.geom.arrays import cross_lines
from kinepoly.geom.tolerances import RIGID_REL_TOL, TINY_POSITIVE
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput

__all__ = ["RIGHT", "AccelerationResult", "Rules", "construct_acceleration"]


def _drive(ctx: AccelerationContext) -> None:
    mech = ctx.b.mechanism
    if isinstance(mech.scene.input, GivenInput):
        _given(ctx, mech.scene.input)
        return
    for drive in mech.drives:
        if drive.on_frame:
            _frame_drive(ctx, drive.spec)


def _frame_drive(ctx: AccelerationContext, inp: LinkInput | SliderInput) -> None:
    b = ctx.b
    mech = b.mechanism
    if isinstance(inp, LinkInput):
        b.set_rate(inp.link, np.full(b.n, inp.alpha))
        if b.record:
            b.step(Step(polygon="acceleration", kind="known", equation=f"alpha{mech.ground}{inp.link} given",
                        result=f"alpha{mech.ground}{inp.link}", value=(inp.alpha,), topic="input-rate",
                        params=(("link", inp.link), ("ground", mech.ground or ""), ("rate", abs(inp.alpha)),
                                ("sense", sense(inp.alpha)))))
    else:
        slider = mech.slider(inp.slider)
        ctx.sliding[slider.name] = lay_driven_slider(b, slider, inp.s_ddot)
        ctx.coriolis[slider.name] = b.zero


def _given(ctx: AccelerationContext, given: GivenInput) -> None:
    b = ctx.b
    link = b.mechanism.link_names[0]
    for g in given.points:
        assert g.acceleration is not None
        b.add_tip(link, g.name, np.full(b.n, complex(*g.acceleration)))
        if b.record:
            b.step(Step(polygon="acceleration", kind="known", equation=f"a_{g.name} given", result=g.name.lower(),
                        known=((f"a_{g.name}", "magnitude and direction"),),
                        vectors=(DrawnVector(f"a_{g.name}", (0.0, 0.0), g.acceleration, "absolute"),),
                        value=g.acceleration, topic="given-point",
                        params=(("point", g.name), ("magnitude", math.hypot(*g.acceleration)))))
    first, second = given.points[0], given.points[1]
    assert first.acceleration is not None and second.acceleration is not None
    r = complex(b.world(second.name)[0] - b.world(first.name)[0])
    w = b.num(b.omega_of(link))
    normal = -w * w * r
    a_first, a_second = complex(*first.acceleration), complex(*second.acceleration)
    rel = a_second - a_first
    along = r / abs(r)
    misfit = ((rel - normal) * along.conjugate()).real
    if abs(misfit) > RIGID_REL_TOL * max(abs(a_first), abs(a_second), abs(normal), TINY_POSITIVE):
        raise SceneError(f"{b.mechanism.scene.source}: given.{second.name}.acceleration: along "
                         f"{first.name}{second.name} the given accelerations differ by "
                         f"{(rel * along.conjugate()).real:.6g} {b.unit}, but a rigid body turning at omega = "
                         f"{w:.6g} rad/s needs {(normal * along.conjugate()).real:.6g} (off by {misfit:.6g})")
    middle = a_first + normal
    if b.record:
        b.step(Step(polygon="acceleration", kind="known", equation=f"a^n_{second.name}/{first.name}",
                    result=f"a^n_{second.name}/{first.name}",
                    vectors=(DrawnVector(f"a^n_{second.name}/{first.name}", first.acceleration,
                                         (middle.real, middle.imag), "normal"),
                             DrawnVector(f"a^t_{second.name}/{first.name}", (middle.real, middle.imag),
                                         second.acceleration, "tangential")),
                    topic="given-normal", params=(("point", second.name), ("reference", first.name),
                                                  ("magnitude", abs(normal)))))
    read_rate(b, link, first.name, second.name, np.full(b.n, ((a_second - middle) / (1j * r)).real))


def construct_acceleration(velocity: VelocityResult, plan: PositionPlan, wanted: tuple[tuple[str, str], ...] = (),
                           *, unit: str = "mm", record: bool = False, strict: bool = False, rules: Rules = RIGHT,
                           crossing: CrossLines = cross_lines) -> AccelerationResult:
    """Construct the acceleration polygon at every row for every group of ``plan``, on top of its velocity polygon."""
    positions = velocity.polygon.positions
    polygon = Polygon(positions, "acceleration", omega=velocity.omega, unit=unit, record=record, strict=strict,
                      crossing=crossing, constants=plan.constants)
    polygon.normal_sign = rules.normal
    ctx = AccelerationContext(polygon, velocity, rules)
    _drive(ctx)
    for group in plan.groups:
        kind_of(group).acceleration(ctx, group)
    for link, point in wanted:
        polygon.tip(link, point)
    return AccelerationResult(polygon, ctx.sliding, ctx.coriolis)
