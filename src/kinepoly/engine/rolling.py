"""The polygons of a gear placed by rolling, by two direction lines like any dyad.

At the pitch point P the gears roll without slipping: the two gears' points at P have the same
velocity, and their accelerations differ only along the common normal (the line of centres). So the
tip of P as a point of the unknown gear lies

* on the line through the tip of P as a point of the known gear, along the common normal (the
  tangential components are equal: for the velocity, with the centre distance kept, the tips coincide);
* on the line of the unknown gear's own motion: through the tip of its centre (and, for the
  acceleration, the normal term -omega^2 O P laid from it), perpendicular to O P; for a rack, through
  the tip of the point of its guide under P (and the Coriolis term), along the slide.

Their crossing gives the tip; omega (alpha) of the gear is read off as for any link.

A planet on an arm that no input drives (``engine.planet``) meshes two known gears: its velocity tips at
both pitch points are those of the known gears there (``velocity_of_planet``), so its centre's tip follows
by Mehmke's theorem (on the line of the two, in the same proportion), its omega is read off, and the arm's
from its pivot and the centre. For the accelerations its points at the pitch points lie on the common
normals (the line of centres) through the known gears' tips there, so by Mehmke's theorem the image of the
centre C lies on the line along the line of centres through the point dividing those two tips as C divides
the two pitch points; crossed with the line of the arm's tangential term at C (after its normal term) it
gives C (``acceleration_of_planet``), alpha of the arm is read off, and the planet is then a gear rolling
on a known one about a known centre, as above.
"""

from __future__ import annotations

import numpy as np

from kinepoly.engine.gears import Mesh, mesh, pitch_label
from kinepoly.engine.groups import GearGroup
from kinepoly.engine.lines import read_rate, slide_direction
from kinepoly.engine.planet import Planet
from kinepoly.engine.polygon import Line, Polygon
from kinepoly.engine.results import AccelerationContext
from kinepoly.engine.steps import DrawnVector, Step
from kinepoly.geom.arrays import Crossing, Points, Reals
from kinepoly.model.mechanism import Revolute
from kinepoly.scene.spec import GearSpec, SliderSpec

__all__ = ["acceleration_by_rolling", "acceleration_of_planet", "mark_pitch_point", "velocity_by_rolling",
           "velocity_of_planet"]


def mark_pitch_point(polygon: Polygon, group: GearGroup | GearSpec) -> Mesh:
    """The pair's mesh, its pitch point marked on the mechanism as ``P<pair>``."""
    gear = group.gear if isinstance(group, GearGroup) else group
    found = mesh(polygon.mechanism, gear, polygon.positions.poses)
    label = pitch_label(gear)
    if label not in polygon.positions.marks:
        polygon.positions.add_point(label, found.point)
    return found


def _record(polygon: Polygon, group: GearGroup, tip: str, known_tip: str, first: Line, second: Line,
            crossing: Crossing, vectors: tuple[DrawnVector, ...] = ()) -> None:
    if not polygon.record:
        return
    rack = isinstance(group.joint, SliderSpec)
    through = (polygon.label(group.carrier, pitch_label(group.gear)) if rack else
               group.joint.point if isinstance(group.joint, Revolute) else "")
    sym = polygon.symbol
    own = f"{sym}{'^t' if polygon.kind == 'acceleration' and not rack else ''}_{tip}/{through}"
    laid = "".join(f" + {v.label}" for v in vectors)
    polygon.step(Step(polygon=polygon.kind, kind="intersection",
                      equation=f"{sym}_{tip} = {sym}_{through}{laid} + {own} = {sym}_{known_tip} + "
                               f"{sym}_{tip}/{known_tip}",
                      result=tip.lower(), vectors=vectors,
                      lines=(polygon.step_line(first, f"line of {tip} on link {group.link}"),
                             polygon.step_line(second, f"common normal through {known_tip.lower()}")),
                      value=polygon.vec(crossing.point), topic="rolling",
                      params=(("pair", group.gear.name), ("link", group.link), ("known", group.known),
                              ("point", tip), ("known_point", known_tip), ("through", through),
                              ("rack", "yes" if rack else "no"))))


def _common_normal(polygon: Polygon, group: GearGroup) -> tuple[str, str, str, Line]:
    """The pitch point's name, the known gear's tip label there, the new tip's label, and the line along the
    common normal through the known tip (the relative term of rolling pitch curves lies on it)."""
    found = mark_pitch_point(polygon, group)
    point = pitch_label(group.gear)
    return (point, polygon.label(group.known, point), polygon.label(group.link, point),
            (polygon.tip(group.known, point), found.normal, None))


def velocity_by_rolling(polygon: Polygon, group: GearGroup, sliding: dict[str, Points]) -> None:
    point, known_label, tip, second = _common_normal(polygon, group)
    if isinstance(group.joint, Revolute):
        centre = group.joint.point
        r = np.asarray(polygon.world(point) - polygon.world(centre))
        first: Line = (polygon.tip(group.carrier, centre), np.asarray(1j * r), None)
        crossing = polygon.cross_lines(first, second, tip, group.name)
        polygon.add_tip(group.link, point, crossing.point)
        _record(polygon, group, tip, known_label, first, second, crossing)
        read_rate(polygon, group.link, centre, tip, crossing.along_first)
        return
    slider = group.joint
    assert isinstance(slider, SliderSpec)
    under = polygon.tip(group.carrier, point)
    first = (under, slide_direction(polygon.positions, slider), 1.0)
    crossing = polygon.cross_lines(first, second, tip, group.name)
    polygon.add_tip(group.link, point, crossing.point)
    _record(polygon, group, tip, known_label, first, second, crossing)
    sliding[slider.name] = np.asarray(crossing.point - under)


def acceleration_by_rolling(ctx: AccelerationContext, group: GearGroup) -> None:
    """The acceleration polygon's part."""
    b = ctx.b
    point, known_label, tip, second = _common_normal(b, group)
    if isinstance(group.joint, Revolute):
        centre = group.joint.point
        start = b.tip(group.carrier, centre)
        r = np.asarray(b.world(point) - b.world(centre))
        w = b.omega_of(group.link)
        middle = np.asarray(start - (w * w) * r)
        first: Line = (middle, np.asarray(1j * r), None)
        crossing = b.cross_lines(first, second, tip, group.name)
        b.add_tip(group.link, point, crossing.point)
        vectors = (DrawnVector(f"a^n_{tip}/{centre}", b.vec(start), b.vec(middle), "normal"),) if b.record else ()
        _record(b, group, tip, known_label, first, second, crossing, vectors)
        read_rate(b, group.link, centre, tip, crossing.along_first)
        return
    slider = group.joint
    assert isinstance(slider, SliderSpec)
    line, coriolis = ctx.slide_line(slider, group.carrier, group.link, point)
    crossing = b.cross_lines(line, second, tip, group.name)
    b.add_tip(group.link, point, crossing.point)
    _record(b, group, tip, known_label, line, second, crossing, tuple(coriolis))
    ctx.slide_values(slider, group.link, point)


def _rate_from(polygon: Polygon, link: str, first: str, second: str) -> Reals:
    """omega of ``link`` from the tips of two of its points: the relative velocity along k x (first -> second)."""
    r = np.asarray(polygon.world(second) - polygon.world(first))
    rel = polygon.tip(link, second) - polygon.tip(link, first)
    return np.asarray((np.conj(r) * rel).imag / (r.real * r.real + r.imag * r.imag))


def velocity_of_planet(polygon: Polygon, planet: Planet) -> None:
    """The planet's tips at its pitch points (the known gears' there), its centre's by Mehmke's theorem, then
    omega of the planet and of the arm."""
    for gear in planet.meshes:
        mark_pitch_point(polygon, gear)
        point = pitch_label(gear)
        known = gear.links[1 - gear.links.index(planet.planet)]
        value = polygon.tip(known, point)
        label = polygon.add_tip(planet.planet, point, value)
        if polygon.record:
            known_label = polygon.label(known, point)
            polygon.step(Step(polygon="velocity", kind="known", equation=f"v_{label} = v_{known_label}",
                              result=label.lower(), value=polygon.vec(value), topic="pitch-point",
                              params=(("pair", gear.name), ("pitch", point), ("point", label),
                                      ("known_point", known_label), ("link", planet.planet), ("known", known))))
    centre = planet.pin.point
    polygon.tip(planet.planet, centre)  # on the line of the two pitch tips: Mehmke's image
    pitch = pitch_label(planet.meshes[0])
    read_rate(polygon, planet.planet, centre, polygon.label(planet.planet, pitch),
              _rate_from(polygon, planet.planet, centre, pitch))
    pivot = planet.pivot.point
    polygon.tip(planet.base, pivot)
    read_rate(polygon, planet.arm, pivot, centre, _rate_from(polygon, planet.arm, pivot, centre))


def acceleration_of_planet(ctx: AccelerationContext, planet: Planet) -> None:
    """The planet's centre C through the known gears' tips at the pitch points, alpha of the arm, then the planet
    rolling on its first known gear about C."""
    b = ctx.b
    (one, two), centre, pivot = planet.meshes, planet.pin.point, planet.pivot.point
    known = [gear.links[1 - gear.links.index(planet.planet)] for gear in planet.meshes]
    for gear in planet.meshes:
        mark_pitch_point(b, gear)
    pa, pb = pitch_label(one), pitch_label(two)
    tip_a, tip_b = b.tip(known[0], pa), b.tip(known[1], pb)
    wa, wb, wc, wo = (b.world(x) for x in (pa, pb, centre, pivot))
    chord = wb - wa
    ratio = np.asarray(((wc - wa) * np.conj(chord)).real / (chord.real ** 2 + chord.imag ** 2))
    divided = np.asarray(tip_a + ratio * (tip_b - tip_a))
    along_centres = np.asarray(wc - wo)
    start = b.tip(planet.base, pivot)
    w = b.omega_of(planet.arm)
    middle = np.asarray(start - (w * w) * along_centres)
    arm_line: Line = (middle, np.asarray(1j * along_centres), None)
    normal_line: Line = (divided, along_centres, None)
    crossing = b.cross_lines(arm_line, normal_line, centre, f"{planet.arm}-{planet.planet} (planet on its arm)")
    b.add_tip(planet.arm, centre, crossing.point)
    if b.record:
        labels = [b.label(k, p) for k, p in zip(known, (pa, pb), strict=True)]
        length = float(np.abs(along_centres[0]))
        side = float(np.abs(tip_b[0] - tip_a[0]))
        b.step(Step(polygon="acceleration", kind="intersection",
                    equation=f"a_{centre} = a_{pivot} + a^n_{centre}/{pivot} + a^t_{centre}/{pivot} = a_{centre}* + "
                             f"a_{centre}/{centre}*",
                    result=centre.lower(), value=b.vec(crossing.point), topic="planet-centre",
                    vectors=(DrawnVector(f"a^n_{centre}/{pivot}", b.vec(start), b.vec(middle), "normal"),),
                    lines=(b.step_line(arm_line, f"line of a^t_{centre}/{pivot}"),
                           b.step_line(normal_line, f"line of centres through the point dividing "
                                                    f"{labels[0]} {labels[1]}")),
                    params=(("planet", planet.planet), ("arm", planet.arm), ("centre", centre), ("pivot", pivot),
                            ("pitch_a", pa), ("pitch_b", pb), ("known_a", labels[0]), ("known_b", labels[1]),
                            ("gear_a", known[0]), ("gear_b", known[1]), ("ratio", float(ratio[0])),
                            ("side", side), ("omega", float(abs(w[0]))), ("length", length),
                            ("normal", float(w[0] * w[0]) * length))))
    read_rate(b, planet.arm, pivot, centre, crossing.along_first)
    acceleration_by_rolling(ctx, GearGroup(planet.planet, known[0], planet.arm, planet.pin, gear=one))
