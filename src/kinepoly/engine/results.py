"""The velocity and acceleration polygons as results, and the acceleration polygon's context: the polygon
being built on the velocity polygon, the rules that lay its known terms, and its direction lines with the
steps that record them (for every group kind).

``Rules`` switch a construction mistake in (the homework checker's diagnoses): the normal term
laid away from the center, the Coriolis term left out or reversed. The right rules are the default.
"""

from __future__ import annotations

import numpy as np
from msgspec import Struct, field

from kinepoly.engine.lines import link_length, slide_direction, slide_reference
from kinepoly.engine.polygon import Line, Polygon, sense
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.geom.arrays import Crossing, Points, Reals
from kinepoly.geom.vec import magnitude
from kinepoly.scene.spec import SliderSpec

__all__ = ["RIGHT", "AccelerationContext", "AccelerationResult", "Rules", "VelocityContext", "VelocityResult",
           "along_normal", "along_slide", "normals_step", "record_crossing", "slide_label"]


class VelocityResult(Struct, frozen=True):
    """The velocity polygon at every row: tips, omegas, sliding velocities, crossings and steps."""

    polygon: Polygon
    sliding: dict[str, Points]
    equivalent: dict[str, Points] = field(default_factory=dict)
    """Each spline cam's equivalent link, by pair (``engine.cam_polygons``): omega of the link K W (its real
    part), or for a flat face the velocity of the block at K over the face."""

    @property
    def tips(self) -> dict[str, Points]:
        return self.polygon.tips

    @property
    def omega(self) -> dict[str, Reals]:
        return self.polygon.rate


class VelocityContext(Struct):
    """The velocity polygon being built and what the groups find besides its tips and rates: the sliding
    velocities by slider, the equivalent links by cam pair."""

    polygon: Polygon
    sliding: dict[str, Points] = field(default_factory=dict)
    equivalent: dict[str, Points] = field(default_factory=dict)


class Rules(Struct, frozen=True):
    """How the known terms are laid: ``normal`` -1 toward the center (right), +1 away;
    ``coriolis`` 1 as it is (right), 0 left out, -1 reversed."""

    normal: float = -1.0
    coriolis: float = 1.0


RIGHT = Rules()


class AccelerationResult(Struct, frozen=True):
    """The acceleration polygon at every row: tips, alphas, sliding accelerations, Coriolis terms, steps."""

    polygon: Polygon
    sliding: dict[str, Points]
    coriolis: dict[str, Points]

    @property
    def tips(self) -> dict[str, Points]:
        return self.polygon.tips

    @property
    def alpha(self) -> dict[str, Reals]:
        return self.polygon.rate


class AccelerationContext:
    """The polygon being built, the velocity polygon it stands on, and the slider terms found."""

    def __init__(self, polygon: Polygon, velocity: VelocityResult, rules: Rules) -> None:
        self.b = polygon
        self.v = velocity
        self.rules = rules
        self.sliding: dict[str, Points] = {}
        self.coriolis: dict[str, Points] = {}

    def v_tip(self, link: str, point: str) -> Points:
        b = self.b
        if link == b.ground:
            return b.zero
        return self.v.polygon.tips[b.label(link, point)]

    def normal_line(self, known_link: str, known_point: str, point: str, moving: str,
                    rigid: bool = True, omega: Reals | None = None,
                    name: str | None = None) -> tuple[Line, DrawnVector | None, str]:
        """a_known + a^n (toward known_point), then the line perpendicular to known_point -> point
        (``rigid``: both are points of ``moving``, so the direction's length is a link length; ``omega``:
        the turning rate of known_point -> point when it is not ``moving``'s, as an equivalent link's;
        ``name``: the point's name in the terms when it is not ``point``, as ``A@4`` for the point of the
        guide under the block's pin, so that the normal and the tangential term name it alike)."""
        b = self.b
        start = b.tip(known_link, known_point)
        r, turned = b.positions.chord(known_point, point)
        w = b.omega_of(moving) if omega is None else omega
        normal = np.asarray((w * w) * r)
        end = np.subtract(start, normal, out=normal) if self.rules.normal < 0.0 else np.add(start, normal, out=normal)
        size = link_length(b.mechanism, moving, known_point, point) if rigid else None
        named = name or point
        vector = DrawnVector(f"a^n_{named}/{known_point}", b.vec(start), b.vec(end), "normal") if b.record else None
        return (end, turned, size), vector, f"a^t_{named}/{known_point} perpendicular to {known_point}{named}"

    def slide_line(self, slider: SliderSpec, other: str, moving: str, point: str) -> tuple[Line, list[DrawnVector]]:
        """a_point@other (+ the Coriolis term where the guide turns), then the line along the slide."""
        start = self.b.tip(other, point)
        end, coriolis = self.lay_coriolis(slider, start, moving, other, point)
        return (end, slide_direction(self.b.positions, slider), 1.0), coriolis

    def lay_coriolis(self, slider: SliderSpec, start: Points, moving: str, frame: str,
                     point: str, sign: float = 1.0) -> tuple[Points, list[DrawnVector]]:
        """Lay 2 omega_frame x v_{point of moving}/{point of frame} (times ``sign``) from ``start``, with its step.

        Nothing is laid where the slider's guide cannot turn: then there is no Coriolis term at all.
        """
        b = self.b
        if not b.mechanism.has_turning_guide(slider) or self.rules.coriolis == 0.0:
            return start, []
        w = b.omega_of(frame)
        v_rel = self.v_tip(moving, point) - self.v_tip(frame, point)
        term = np.asarray((sign * self.rules.coriolis * 2.0 * w) * (1j * v_rel))
        end = np.asarray(start + term)
        if not b.record:
            return end, []
        on_moving, on_frame = b.label(moving, point), b.label(frame, point)
        if sign < 0.0:  # laid the other way: the term of the frame's point over the moving one's
            on_moving, on_frame = on_frame, on_moving
        label = f"a^c_{on_moving}/{on_frame}"
        vector = DrawnVector(label, b.vec(start), b.vec(end), "coriolis")
        omega = b.num(w)
        b.step(Step(polygon="acceleration", kind="coriolis", equation=f"{label} = 2 omega x v_{on_moving}/{on_frame}",
                    result=label, known=((label, "magnitude and direction"),), vectors=(vector,),
                    value=b.vec(term), topic="coriolis",
                    params=(("term", label), ("guide", slider.guide), ("ground", b.ground_name()),
                            ("omega", abs(omega)), ("relative", f"v_{on_moving}/{on_frame}"),
                            ("speed", magnitude(complex(v_rel[0]))), ("magnitude", magnitude(complex(term[0]))),
                            ("sense", sense(omega)), ("start", on_frame))))
        return end, [vector]

    def slide_values(self, slider: SliderSpec, link: str, point: str) -> None:
        """Sliding acceleration and Coriolis term of the block relative to the guide (the Coriolis term as
        the rules lay it: the sliding term is what remains of the relative acceleration)."""
        b = self.b
        other = slider.guide if link == slider.block else slider.block
        block_side, guide_side = (link, other) if link == slider.block else (other, link)
        a_block, a_guide = b.tip(block_side, point), b.tip(guide_side, point)
        v_rel = self.v_tip(block_side, point) - self.v_tip(guide_side, point)
        coriolis = np.asarray((self.rules.coriolis * 2.0 * b.omega_of(slider.guide)) * (1j * v_rel))
        self.coriolis[slider.name] = coriolis
        self.sliding[slider.name] = np.asarray(a_block - a_guide - coriolis)


def record_crossing(ctx: AccelerationContext, label: str, equation: str, first: Line, second: Line,
                    labels: tuple[str, str],
            crossing: Crossing, vectors: list[DrawnVector], directions: tuple[Direction, Direction]) -> None:
    b = ctx.b
    known = tuple((v.label, "magnitude and direction") for v in vectors)
    known += tuple((d.term, "direction") for d in directions)  # the two unknown terms
    b.step(Step(polygon="acceleration", kind="intersection", equation=equation, result=label.lower(), known=known,
                vectors=tuple(vectors), lines=(b.step_line(first, labels[0]), b.step_line(second, labels[1])),
                value=b.vec(crossing.point), topic="intersection", params=(("point", label),),
                directions=directions))


def along_normal(ctx: AccelerationContext, term: str, known_link: str, known_point: str, point: str,
                  normal: DrawnVector | None) -> Direction:
    """What ``normal_line`` draws, as data: the tangential term, after the normal one."""
    return Direction(term, "perpendicular", f"{known_point}{point}", ctx.b.label(known_link, known_point).lower(),
                     after=normal.label if normal else "")


def along_slide(ctx: AccelerationContext, term: str, slider: SliderSpec, other: str, point: str,
                 laid: list[DrawnVector]) -> Direction:
    """What ``slide_line`` draws, as data: the sliding term, after the Coriolis term when there is one."""
    return Direction(term, *slide_reference(ctx.b, slider), ctx.b.label(other, point).lower(),
                     after=laid[-1].label if laid else "")


def normals_step(ctx: AccelerationContext, vectors: list[DrawnVector]) -> None:
    normals = [v for v in vectors if v.term == "normal"]
    if normals:
        ctx.b.step(Step(polygon="acceleration", kind="known", equation=" and ".join(v.label for v in normals),
                        result=", ".join(v.label for v in normals),
                        known=tuple((v.label, "magnitude and direction") for v in normals), vectors=tuple(normals),
                        topic="normals"))


def slide_label(slider: SliderSpec) -> str:
    return f"sliding term along slider {slider.name}"
