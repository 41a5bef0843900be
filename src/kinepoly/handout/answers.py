"""The last page of a handout: the answers, their lengths on the paper, and the cross-check.

Every asked quantity as the construction gives it (with the length of each polygon vector on
the paper, to compare a hand drawing with), the instant centers and the angular velocities
they give, then the check against the analytic solution: the largest relative error per kind
of quantity and its estimate, and the verdict.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from kinepoly.engine.circle_diagram import center_label
from kinepoly.geom.tolerances import LOUD_ERROR
from kinepoly.handout.content import Column, Drawing, Page, Paragraph, Part, Table
from kinepoly.present.catalogue import Catalogue
from kinepoly.solution import Solution

__all__ = ["KINDS", "answers_page"]

KINDS = ("position", "velocity", "acceleration", "angle", "omega", "alpha", "instant_center")
"""The kinds of quantity the cross-check reports, each with its words in the catalogue (``check.KIND``)."""


def _n(say: Catalogue, value: float | None) -> str:
    return "" if value is None else say.number(value)


def _angle_of(say: Catalogue, v: Sequence[float] | None) -> str:
    if v is None or math.hypot(v[0], v[1]) == 0.0:
        return ""
    return say.angle(math.atan2(v[1], v[0]))


def _links(data: dict[str, Any], say: Catalogue, ground: str, angle_unit: str) -> Table:
    rows = tuple((f"{say.say('answers.link')} {name}", f"{say.number(v['angle'])}", _n(say, v.get("omega")),
                  _n(say, v.get("alpha"))) for name, v in data["links"].items())
    unit = "°" if angle_unit == "deg" else "rad"
    return Table(say.say("answers.links"), ("", f"θ ({unit})", "ω (rad/s)", "α (rad/s²)"), rows)


def _points(data: dict[str, Any], say: Catalogue, unit: str, scales: Mapping[str, float]) -> Table:
    rows = []
    for label, v in data["points"].items():
        vel, acc = v.get("velocity"), v.get("acceleration")
        speed = math.hypot(*vel) if vel else None
        size = math.hypot(*acc) if acc else None
        rows.append((label, _n(say, speed), _angle_of(say, vel),
                     _n(say, speed * scales["velocity"]) if speed is not None and "velocity" in scales else "",
                     _n(say, size), _angle_of(say, acc),
                     _n(say, size * scales["acceleration"]) if size is not None and "acceleration" in scales else ""))
    header = ("", f"|v| ({unit}/s)", "∠v", say.say("answers.on_paper", segment="o→tip"),
              f"|a| ({unit}/s²)", "∠a", say.say("answers.on_paper", segment="o′→tip"))
    keep = [c for c in range(len(header)) if c == 0 or any(r[c] for r in rows)]
    return Table(say.say("answers.points"), tuple(header[c] for c in keep),
                 tuple(tuple(r[c] for c in keep) for r in rows))


def _sliders(data: dict[str, Any], say: Catalogue, unit: str) -> Table:
    rows = tuple((f"{say.say('answers.slider')} {name}", say.number(v["s"]), _n(say, v.get("s_dot")),
                  _n(say, v.get("s_ddot")), _n(say, math.hypot(*v["coriolis"]) if "coriolis" in v else None))
                 for name, v in data["sliders"].items())
    header = ("", f"s ({unit})", f"ṡ ({unit}/s)", f"s̈ ({unit}/s²)", f"|aᶜ| ({unit}/s²)")
    keep = [c for c in range(len(header)) if c == 0 or any(r[c] for r in rows)]
    return Table(say.say("answers.sliders"), tuple(header[c] for c in keep),
                 tuple(tuple(r[c] for c in keep) for r in rows))


def _centers(solution: Solution, say: Catalogue) -> list[Part]:
    centers = solution.centers
    assert centers is not None
    rows = []
    for key, name in centers.asked:
        center = centers.centers[name]
        if center.position is not None:
            place = say.pair(*center.position)
        else:
            assert center.direction is not None
            place = say.say("answers.at_infinity", angle=say.angle(math.atan2(center.direction[1],
                                                                               center.direction[0])))
        rows.append((center_label(key), place))
    return [Table(say.say("answers.centers"), ("", say.say("answers.position", unit=solution.scene.units.length)),
                  tuple(rows))]


def _center_omegas(solution: Solution, say: Catalogue) -> list[Part]:
    """The angular velocities the instant centers give (a third check of the polygon)."""
    if solution.centers is None or not solution.scene.find.instant_centers or not solution.centers.omegas:
        return []
    values = ", ".join(f"{o.symbol.replace('omega', 'ω')} = {say.number(o.omega)}" for o in solution.centers.omegas)
    return [Paragraph(say.say("answers.center_omegas", values=values), "note")]


def _error(say: Catalogue, x: float) -> str:
    """A relative error in two digits; an exact agreement is 0 (not 0.0e+00)."""
    text = "0" if x == 0.0 else f"{x:.1e}"
    return text.replace(".", say.decimal) if say.decimal != "." else text


def _check(solution: Solution, say: Catalogue) -> list[Part]:
    check = solution.check
    verdict = say.say("answers.agrees") if check.max_rel_error <= LOUD_ERROR else say.say("answers.disagrees")
    text = say.say("answers.check", error=_error(say, check.max_rel_error), verdict=verdict)
    kinds = [kind for kind in KINDS if kind in check.relative]
    if kinds:
        listed = ", ".join(say.say("answers.kind_error", kind=say.say(f"check.{kind}"),
                                   error=_error(say, check.relative[kind])) for kind in kinds)
        text += " " + say.say("answers.by_kind", errors=listed)
    return [Paragraph(text)]


def answers_page(solution: Solution, say: Catalogue, scales: Mapping[str, float]) -> Page:
    """The answers of the construction and the cross-check; ``scales`` as drawn, for the lengths on paper."""
    from kinepoly.present.report import readable_json

    data = readable_json(solution)  # a value below its error estimate is printed as 0
    unit = solution.scene.units.length
    ground = solution.mechanism.ground or ""
    first: list[Part] = [Paragraph(solution.scene.title, "title"), Paragraph(say.say("answers.title"), "heading"),
                         *_check(solution, say)]
    tables: list[Column] = []
    if "links" in data:
        tables.append(Column((_links(data, say, ground, solution.scene.units.angle),)))
    if "points" in data:
        tables.append(Column((_points(data, say, unit, scales),)))
    if "sliders" in data:
        tables.append(Column((_sliders(data, say, unit),)))
    if solution.centers is not None and solution.scene.find.instant_centers:
        tables.append(Column(tuple(_centers(solution, say))))
    first += _center_omegas(solution, say)
    if "points" in data and scales:
        first.append(Paragraph(say.say("answers.paper_note"), "note"))
    return Page("answers", Drawing("answers"), (Column(tuple(first), fill=True), *tables),
                heading=say.say("answers.title"))
