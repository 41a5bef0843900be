"""One page per construction step, written from the step's data in the catalogue's language.

Each page says the step's vector equation, a table of what is known of each term (magnitude and
direction, ``?`` where unknown), what to draw and why, and what the step yields. Nothing is
translated from the English ``Step.text``: the words come from the catalogue, the names and
numbers from ``Step.topic``, ``Step.params``, ``Step.directions``, ``Step.vectors`` and the polygon
(``kinepoly.engine.steps`` lists each topic's parameters).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from kinepoly.engine.center_values import InstantCenters, KennedyStep
from kinepoly.engine.circle_diagram import center_label
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.geom.vec import Vec, norm, sub
from kinepoly.handout.catalogue import Catalogue
from kinepoly.handout.content import Column, Drawing, Page, Paragraph, Table
from kinepoly.handout.notation import typographic
from kinepoly.model.mechanism import Revolute, joint_links
from kinepoly.solution import Solution
from kinepoly.engine.plan import NewtonGroup

__all__ = ["construction_pages", "step_equation", "tip_name"]

_TINY = 1e-12


def tip_name(label: str, polygon: str) -> str:
    """A point's tip in the polygon: ``B0`` -> ``b0``; in the acceleration polygon primed, ``b′0``."""
    point, at, link = label.partition("@")
    m = re.match(r"^(\D+)(\d*)$", point)
    base, digits = (m.group(1), m.group(2)) if m else (point, "")
    prime = "′" if polygon == "acceleration" else ""
    return f"{base.lower()}{prime}{digits}{at}{link}"


def _segment(first: str, second: str) -> str:
    """The segment between two points of the mechanism: ``A@4`` and ``B0`` -> ``AB0``."""
    return first.partition("@")[0] + second.partition("@")[0]


class _Writer:
    """The words of one polygon's steps: its symbols, unit, pole and scale on paper."""

    def __init__(self, solution: Solution, say: Catalogue, scales: Mapping[str, float]) -> None:
        self.solution = solution
        self.say = say
        self.scales = scales
        self.unit = solution.scene.units.length

    def unit_of(self, polygon: str) -> str:
        return f"{self.unit}/s" if polygon == "velocity" else f"{self.unit}/s²"

    def pole(self, polygon: str) -> str:
        return "o" if polygon == "velocity" else "o′"

    def rate_unit(self, polygon: str) -> str:
        return "rad/s" if polygon == "velocity" else "rad/s²"

    def rate_name(self, polygon: str, ground: str, link: str) -> str:
        return f"{'ω' if polygon == 'velocity' else 'α'}{ground}{link}"

    def paper(self, polygon: str, magnitude: float) -> str:
        return self.say.number(magnitude * self.scales.get(polygon, 0.0))

    def tips(self, polygon: str) -> dict[str, Vec]:
        found = self.solution.velocity if polygon == "velocity" else self.solution.acceleration
        return dict(found.tips) if found is not None else {}

    def tip_or_pole(self, polygon: str, label: str) -> str:
        """The tip of ``label``, or the pole when the point does not move (a point of the frame)."""
        tip = self.tips(polygon).get(label)
        if tip is not None and norm(tip) <= _TINY * max((norm(t) for t in self.tips(polygon).values()), default=1.0):
            return self.pole(polygon)
        return tip_name(label, polygon)

    def sense(self, code: str | float) -> str:
        return self.say.say(f"sense.{code}")

    def n(self, value: str | float) -> str:
        return self.say.number(float(value))

    # -- the table of terms --------------------------------------------------------------------
    def vector_direction(self, vector: DrawnVector) -> str:
        _head, _, names = vector.label.partition("_")
        point, _, reference = names.partition("/")
        if vector.term == "normal":
            return self.say.say("table.toward", segment=_segment(point, reference),
                                point=reference.partition("@")[0])
        if vector.term in ("tangential", "relative"):
            return self.say.say("table.perpendicular", reference=_segment(reference, point))
        if vector.term == "coriolis":
            return self.say.say("table.coriolis")
        return self.say.say("table.known")

    def line_direction(self, direction: Direction) -> str:
        if direction.relation == "perpendicular":
            return self.say.say("table.perpendicular", reference=direction.reference)
        if direction.relation == "parallel":
            return self.say.say("table.parallel", slider=direction.reference)
        return self.say.say("table.known")

    def absolute_row(self, polygon: str, term: str) -> tuple[str, str, str]:
        label = term.partition("_")[2]
        tip = self.tips(polygon).get(label)
        if tip is None:
            return (term, self.say.say("table.known"), self.say.say("table.known"))
        if self.tip_or_pole(polygon, label) == self.pole(polygon):
            return (term, "0", self.say.say("table.pole", pole=self.pole(polygon)))
        return (term, f"{self.n(norm(tip))} {self.unit_of(polygon)}",
                self.say.say("table.known_tip", pole=self.pole(polygon), tip=tip_name(label, polygon)))

    def rows(self, step: Step) -> tuple[tuple[str, ...], ...]:
        sides = [[t.strip() for t in side.split(" + ")] for side in step.equation.split(" = ")]
        laid = {v.label: v for v in step.vectors}
        loose = {re.sub(r"@\d+", "", label): v for label, v in laid.items()}
        unit = self.unit_of(step.polygon)
        out: list[tuple[str, ...]] = [(sides[0][0], "?", "?")]
        for k, side in enumerate(sides[1:]):
            for n, term in enumerate(side):
                vector = laid.get(term) or loose.get(re.sub(r"@\d+", "", term))
                if step.topic == "intersection" and n == len(side) - 1 and k < len(step.directions):
                    out.append((term, "?", self.line_direction(step.directions[k])))
                elif vector is not None:
                    out.append((term, f"{self.n(norm(sub(vector.end, vector.start)))} {unit}",
                                self.vector_direction(vector)))
                elif step.topic == "relative" and "/" in term:
                    suffix = "_" + term.partition("_")[2]
                    for v in step.vectors:
                        if v.label.endswith(suffix):
                            out.append((v.label, f"{self.n(norm(sub(v.end, v.start)))} {unit}",
                                        self.vector_direction(v)))
                else:
                    out.append(self.absolute_row(step.polygon, term))
        return tuple(out)

    def table(self, step: Step) -> Table:
        header = (self.say.say("table.term"), self.say.say("table.magnitude"), self.say.say("table.direction"))
        return Table("", header, self.rows(step))


def step_equation(step: Step, say: Catalogue, solution: Solution) -> str:
    """The equation a step's page shows: the step's own, typeset, where it is notation only."""
    unit = solution.scene.units.length
    p = dict(step.params)
    symbol = "v" if step.polygon == "velocity" else "a"
    if step.topic == "input-rate":
        rate = step.value[0] if step.value else 0.0
        name = f"{'ω' if step.polygon == 'velocity' else 'α'}{p['ground']}{p['link']}"
        return f"{name} = {say.number(rate)} {'rad/s' if step.polygon == 'velocity' else 'rad/s²'}"
    if step.topic == "driven-slider":
        name = f"{'ṡ' if step.polygon == 'velocity' else 's̈'}{p['slider']}"
        suffix = "/s" if step.polygon == "velocity" else "/s²"
        return f"{symbol}_{p['point']} = {name} = {say.number(float(p['amount']))} {unit}{suffix}"
    if step.topic == "given-point":
        suffix = "/s" if step.polygon == "velocity" else "/s²"
        return f"{symbol}_{p['point']} = {say.pair(step.value[0], step.value[1])} {unit}{suffix}"
    if step.topic in ("image", "image-translating", "proportional"):
        first, second, point = str(p["first"]), str(p["second"]), str(p["point"])
        image = "".join(tip_name(x, step.polygon) for x in (first, second, point))
        return f"△{image} ∼ △{first}{second}{point}"
    if step.topic == "normals":
        return ", ".join(v.label for v in step.vectors)
    if step.kind == "linear-solve":
        symbols = ", ".join(f"{symbol}_{tip.strip().upper()}" for tip in step.result.split(","))
        return f"{symbols} = ?"
    return typographic(step.equation)


class _StepText:
    """The explanation and the result of one step, in words."""

    def __init__(self, writer: _Writer, step: Step) -> None:
        self.w = writer
        self.step = step
        self.p = dict(step.params)
        self.polygon = step.polygon
        self.say = writer.say

    def common(self) -> dict[str, str]:
        unit = self.w.unit_of(self.polygon)
        return {"unit": unit, "pole": self.w.pole(self.polygon)}

    def found_tip(self) -> str:
        """The result of a step that finds a tip: the absolute vector, its angle and length on paper."""
        step = self.step
        label = step.result.upper() if step.result else ""
        tips = self.w.tips(self.polygon)
        name = next((k for k in tips if k.lower() == step.result), label)
        value = tips.get(name, (step.value[0], step.value[1]) if len(step.value) == 2 else (0.0, 0.0))
        symbol = "v" if self.polygon == "velocity" else "a"
        tip = tip_name(name, self.polygon)
        if norm(value) == 0.0:
            return self.say.say("result.tip_at_pole", tip=tip, term=f"{symbol}_{name}", pole=self.w.pole(self.polygon))
        return self.say.say("result.tip", tip=tip, term=f"{symbol}_{name}", magnitude=self.w.n(norm(value)),
                            angle=self.say.angle(math.atan2(value[1], value[0])),
                            paper=self.w.paper(self.polygon, norm(value)), pole=self.w.pole(self.polygon),
                            unit=self.w.unit_of(self.polygon))

    def explain(self) -> tuple[str, str]:
        """(what to do and why, what it yields)."""
        handler = getattr(self, "_" + (self.step.topic or self.step.kind).replace("-", "_"))
        result: tuple[str, str] = handler()
        return result

    def _input_rate(self) -> tuple[str, str]:
        p = self.p
        name = self.w.rate_name(self.polygon, str(p["ground"]), str(p["link"]))
        key = "step.input_rate_velocity" if self.polygon == "velocity" else "step.input_rate_acceleration"
        text = self.say.say(key, link=str(p["link"]), rate_name=name, rate=self.w.n(p["rate"]),
                            sense=self.w.sense(p["sense"]), pole=self.w.pole(self.polygon))
        value = self.step.value[0] if self.step.value else 0.0
        return text, self.say.say("result.given", rate_name=name, value=self.w.n(value),
                                  unit=self.w.rate_unit(self.polygon))

    def _driven_slider(self) -> tuple[str, str]:
        p = self.p
        name = f"{'ṡ' if self.polygon == 'velocity' else 's̈'}{p['slider']}"
        symbol = "v" if self.polygon == "velocity" else "a"
        amount = float(p["amount"])
        text = self.say.say("step.driven_slider", slider=str(p["slider"]), term=f"{symbol}_{p['point']}",
                            rate_name=name, amount=self.w.n(amount), paper=self.w.paper(self.polygon, abs(amount)),
                            tip=tip_name(str(p["point"]), self.polygon), **self.common())
        return text, self.found_tip()

    def _given_point(self) -> tuple[str, str]:
        p = self.p
        symbol = "v" if self.polygon == "velocity" else "a"
        value = self.step.value
        text = self.say.say("step.given_point", term=f"{symbol}_{p['point']}", magnitude=self.w.n(p["magnitude"]),
                            angle=self.say.angle(math.atan2(value[1], value[0])),
                            paper=self.w.paper(self.polygon, float(p["magnitude"])),
                            tip=tip_name(str(p["point"]), self.polygon), **self.common())
        return text, self.found_tip()

    def _relative(self) -> tuple[str, str]:
        p = self.p
        point, reference = str(p["point"]), str(p["reference"])
        segment = _segment(reference, point)
        fields = {"point": point, "reference": reference, "link": str(p["link"]), "segment": segment,
                  "length": self.w.n(p["length"]), "length_unit": self.w.unit, "sense": self.w.sense(p["sense"]),
                  "rate": self.w.n(p["rate"]), "from_tip": self.w.tip_or_pole(self.polygon, reference),
                  "tip": tip_name(point, self.polygon), **self.common()}
        if self.polygon == "velocity":
            text = self.say.say("step.relative_velocity", term=f"v_{point}/{reference}",
                                rate_name=self.w.rate_name("velocity", str(p["ground"]), str(p["link"])),
                                magnitude=self.w.n(p["magnitude"]),
                                paper=self.w.paper("velocity", float(p["magnitude"])), **fields)
        else:
            text = self.say.say("step.relative_acceleration", normal_term=f"a^n_{point}/{reference}",
                                tangential_term=f"a^t_{point}/{reference}",
                                omega_name=self.w.rate_name("velocity", str(p["ground"]), str(p["link"])),
                                rate_name=self.w.rate_name("acceleration", str(p["ground"]), str(p["link"])),
                                omega=self.w.n(p["omega"]), normal=self.w.n(p["normal"]),
                                tangential=self.w.n(p["tangential"]),
                                normal_paper=self.w.paper(self.polygon, float(p["normal"])),
                                tangential_paper=self.w.paper(self.polygon, float(p["tangential"])), **fields)
        return text, self.found_tip()

    def _image_fields(self) -> dict[str, str]:
        p = self.p
        first, second, point = str(p["first"]), str(p["second"]), str(p["point"])
        return {"point": point, "link": str(p["link"]), "first": first, "second": second,
                "first_tip": tip_name(first, self.polygon), "second_tip": tip_name(second, self.polygon),
                "tip": tip_name(point, self.polygon), "triangle": f"{first}{second}{point}",
                "image": "".join(tip_name(x, self.polygon) for x in (first, second, point))}

    def _image(self) -> tuple[str, str]:
        p = self.p
        text = self.say.say("step.image", angle_first=f"{self.w.n(p['angle_first'])}°",
                            angle_second=f"{self.w.n(p['angle_second'])}°", **self._image_fields())
        return text, self.found_tip()

    def _image_translating(self) -> tuple[str, str]:
        key = "step.image_translating_velocity" if self.polygon == "velocity" else "step.image_translating_acceleration"
        return self.say.say(key, **self._image_fields()), self.found_tip()

    def _proportional(self) -> tuple[str, str]:
        p = self.p
        fields = self._image_fields()
        if abs(float(p["height"])) > 1e-9:
            text = self.say.say("step.proportional_offset", ratio=self.w.n(p["ratio"]),
                                height=self.w.n(p["height"]), **fields)
        else:
            text = self.say.say("step.proportional", ratio=self.w.n(p["ratio"]), **fields)
        return text, self.found_tip()

    def _line(self, direction: Direction) -> str:
        through = direction.through
        label = next((k for k in self.w.tips(self.polygon) if k.lower() == through), through)
        tip = self.w.tip_or_pole(self.polygon, label)
        key = "line.parallel" if direction.relation == "parallel" else "line.perpendicular"
        return self.say.say(key + ("_end" if direction.after else ""), through=tip, after=direction.after,
                            term=direction.term, slider=direction.reference, reference=direction.reference)

    def _intersection(self) -> tuple[str, str]:
        step = self.step
        point = str(self.p["point"])
        symbol = "v" if self.polygon == "velocity" else "a"
        key = "step.intersection_velocity" if self.polygon == "velocity" else "step.intersection_acceleration"
        text = self.say.say(key, first_line=self._line(step.directions[0]), second_line=self._line(step.directions[1]),
                            tip=tip_name(point, self.polygon), term=f"{symbol}_{point}", **self.common())
        parts = []
        for direction, line in zip(step.directions, step.lines, strict=True):
            size = norm(sub((step.value[0], step.value[1]), line.through))
            parts.append(self.say.say("result.term", term=direction.term, magnitude=self.w.n(size),
                                      unit=self.w.unit_of(self.polygon)))
        return text, f"{self.found_tip()} {self.say.say('result.terms', terms='; '.join(parts))}"

    def _read(self) -> tuple[str, str]:
        p = self.p
        name = self.w.rate_name(self.polygon, str(p["ground"]), str(p["link"]))
        first, second = str(p["first"]), str(p["second"])
        text = self.say.say("step.read", rate_name=name, term=str(p["term"]), segment=_segment(first, second),
                            magnitude=self.w.n(p["magnitude"]), length=self.w.n(p["length"]),
                            rate=self.w.n(p["rate"]), rate_unit=self.w.rate_unit(self.polygon),
                            sense=self.w.sense(p["sense"]), first=first.partition("@")[0],
                            second=second.partition("@")[0], link=str(p["link"]))
        value = self.step.value[0] if self.step.value else 0.0
        return text, self.say.say("result.rate", rate_name=name, value=self.w.n(value),
                                  unit=self.w.rate_unit(self.polygon), sense=self.w.sense(p["sense"]))

    def _coriolis(self) -> tuple[str, str]:
        p = self.p
        term = str(p["term"])
        vector = self.step.vectors[0]
        along = sub(vector.end, vector.start)
        text = self.say.say("step.coriolis", term=term, guide=str(p["guide"]),
                            omega_name=self.w.rate_name("velocity", str(p["ground"]), str(p["guide"])),
                            omega=self.w.n(p["omega"]), relative=str(p["relative"]), speed=self.w.n(p["speed"]),
                            magnitude=self.w.n(p["magnitude"]), paper=self.w.paper(self.polygon, float(p["magnitude"])),
                            sense=self.w.sense(p["sense"]), from_tip=self.w.tip_or_pole(self.polygon, str(p["start"])),
                            **self.common())
        return text, self._vector_result(term, along)

    def _vector_result(self, term: str, value: Vec) -> str:
        if norm(value) == 0.0:
            return self.say.say("result.vector_zero", term=term)
        return self.say.say("result.vector", term=term, magnitude=self.w.n(norm(value)),
                            angle=self.say.angle(math.atan2(value[1], value[0])), unit=self.w.unit_of(self.polygon))

    def _normals(self) -> tuple[str, str]:
        items = []
        for v in self.step.vectors:
            point, _, reference = v.label.partition("_")[2].partition("/")
            size = norm(sub(v.end, v.start))
            items.append(self.say.say("step.normal_item", term=v.label, magnitude=self.w.n(size),
                                      unit=self.w.unit_of(self.polygon), point=point.partition("@")[0],
                                      reference=reference.partition("@")[0],
                                      from_tip=self._normal_start(v), paper=self.w.paper(self.polygon, size)))
        text = self.say.say("step.normals", items="; ".join(items))
        return text, self.say.say("result.laid", terms=", ".join(v.label for v in self.step.vectors))

    def _normal_start(self, vector: DrawnVector) -> str:
        tips = self.w.tips(self.polygon)
        for label, value in tips.items():
            if norm(sub(value, vector.start)) <= 1e-12 * max(norm(value), 1.0):
                return self.w.tip_or_pole(self.polygon, label)
        return "?"

    def _given_normal(self) -> tuple[str, str]:
        p = self.p
        point, reference = str(p["point"]), str(p["reference"])
        normal, tangential = self.step.vectors
        text = self.say.say("step.given_normal", term=normal.label, tangential=tangential.label,
                            segment=_segment(reference, point), magnitude=self.w.n(p["magnitude"]),
                            point=point, reference=reference, from_tip=tip_name(reference, self.polygon),
                            tip=tip_name(point, self.polygon), paper=self.w.paper(self.polygon, float(p["magnitude"])),
                            **self.common())
        return text, self._vector_result(tangential.label, sub(tangential.end, tangential.start))

    def _linear_solve(self) -> tuple[str, str]:
        step = self.step
        tips = [t.strip() for t in step.result.split(",") if t.strip()]
        shown = ", ".join(tip_name(t.upper(), self.polygon) if self.polygon == "acceleration" else t for t in tips)
        group = self.group()
        links = ", ".join(group.links) if group is not None else "?"
        key = "step.linear_solve_velocity" if self.polygon == "velocity" else "step.linear_solve_acceleration"
        text = self.say.say(key, links=links, tips=shown, count=str(len(group.links) if group else 0))
        return text, self.say.say("result.tips", tips=shown)

    def group(self) -> NewtonGroup | None:
        """The group a linear-solve step belongs to: the n-th such step of its polygon is the n-th Newton group."""
        solution = self.w.solution
        same = [s for s in solution.steps if s.polygon == self.polygon and s.kind == "linear-solve"]
        groups = [g for g in solution.plan.groups if isinstance(g, NewtonGroup)]
        index = next(k for k, s in enumerate(same) if s is self.step)
        return groups[index] if index < len(groups) else None


def _step_page(writer: _Writer, step: Step, number: int, total: int) -> Page:
    say = writer.say
    text, result = _StepText(writer, step).explain()
    heading = say.say("page.step", number=str(number), total=str(total), polygon=say.say(f"polygon.{step.polygon}"))
    equation = step_equation(step, say, writer.solution)
    first: list[Paragraph | Table] = [Paragraph(heading, "heading"), Paragraph(equation, "equation")]
    if step.topic in ("relative", "intersection"):
        first.append(writer.table(step))
    columns = (Column(tuple(first)), Column((Paragraph(text), Paragraph(result, "result")), fill=True),
               Column((), legend=True))
    return Page("step", Drawing("step", number), columns, equation, heading)


def _how_found(solution: Solution, centers: InstantCenters, name: str, say: Catalogue) -> str:
    center = centers.centers[name]
    if center.number > 0:
        return say.say("kennedy.derived", number=str(center.number))
    links = set(center.links)
    for joint in solution.mechanism.joints:
        if set(joint_links(joint)) == links:
            if isinstance(joint, Revolute):
                return say.say("kennedy.pin", point=joint.point)
            return say.say("kennedy.slider", slider=joint.name)
    return say.say("table.known")


def _links(triangle: str) -> str:
    """``"123"`` or ``"1-2-14"`` (a triangle of the circle diagram) as ``1, 2, 3``."""
    return ", ".join(triangle.split("-") if "-" in triangle else list(triangle))


def _kennedy_page(solution: Solution, say: Catalogue, step: KennedyStep, number: int, total: int) -> Page:
    centers = solution.centers
    assert centers is not None
    center = centers.centers[step.center]
    label = center_label(step.center)
    first, second = step.lines
    text = say.say("step.kennedy", center=label, links=", ".join(center.links),
                   first_triangle=_links(step.triangles[0]), second_triangle=_links(step.triangles[1]),
                   first_line=first.label, second_line=second.label)
    used = list(dict.fromkeys(c for line in step.lines for c in line.centers))
    if any(centers.centers[c].is_at_infinity for c in used) or center.is_at_infinity:
        text += " " + say.say("step.kennedy_infinity")
    unit = solution.scene.units.length
    if center.position is not None:
        result = say.say("result.center", center=label, place=say.pair(*center.position), unit=unit)
    else:
        assert center.direction is not None
        result = say.say("result.center_infinity", center=label,
                         angle=say.angle(math.atan2(center.direction[1], center.direction[0])))
    heading = say.say("page.step", number=str(number), total=str(total), polygon=say.say("polygon.centers"))
    equation = typographic(step.equation)
    rows = tuple((center_label(c), _how_found(solution, centers, c, say)) for c in used)
    table = Table("", (say.say("kennedy.center"), say.say("kennedy.found")), rows)
    columns = (Column((Paragraph(heading, "heading"), Paragraph(equation, "equation"), table)),
               Column((Paragraph(text), Paragraph(result, "result")), fill=True))
    return Page("step", Drawing("kennedy", step.number), columns, equation, heading)


def construction_pages(solution: Solution, say: Catalogue, scales: Mapping[str, float]) -> list[Page]:
    """A page per construction step, then one per Kennedy step; ``scales`` are kv and ka as drawn."""
    writer = _Writer(solution, say, scales)
    kennedy = solution.centers.steps if solution.centers is not None and solution.scene.find.instant_centers else ()
    total = len(solution.steps) + len(kennedy)
    pages = [_step_page(writer, step, n, total) for n, step in enumerate(solution.steps, 1)]
    pages += [_kennedy_page(solution, say, step, len(solution.steps) + k, total) for k, step in enumerate(kennedy, 1)]
    return pages
