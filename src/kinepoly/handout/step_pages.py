"""One page per construction step, written from the step's data in the catalogue's language.

Each page says the step's vector equation, a table of what is known of each term (magnitude and
direction, ``?`` where unknown), what to draw and why, and what the step yields. The words of
the step are the shared phrasing's (``kinepoly.present.phrasing``, from ``Step.topic``,
``Step.params``, ``Step.directions``, ``Step.vectors`` and the polygon), as in ``solve --steps``.
"""

from __future__ import annotations

from collections.abc import Mapping

from kinepoly.engine.center_values import InstantCenters, KennedyStep
from kinepoly.engine.circle_diagram import center_label
from kinepoly.engine.steps import Direction, DrawnVector, Step, term_name
from kinepoly.geom.vec import norm, sub
from kinepoly.handout.content import Column, Drawing, Page, Paragraph, Table
from kinepoly.handout.equivalent_page import equivalent_page
from kinepoly.handout.notation import typographic
from kinepoly.model.mechanism import Revolute, joint_links
from kinepoly.present.catalogue import Catalogue
from kinepoly.present.phrasing import Context, Words, kennedy_words, segment, step_words, term_ends, tip_name
from kinepoly.scene.link_point import point_of
from kinepoly.solution import Solution

__all__ = ["construction_pages", "step_equation", "tip_name"]


class _Writer(Words):
    """The words of one solution's steps, and the table of a step's terms."""

    # -- the table of terms --------------------------------------------------------------------
    def vector_direction(self, vector: DrawnVector) -> str:
        point, reference = term_ends(vector)
        if vector.term == "normal":
            return self.say.say("table.toward", segment=segment(point, reference),
                                point=point_of(reference))
        if vector.term in ("tangential", "relative"):
            return self.say.say("table.perpendicular", reference=segment(reference, point))
        if vector.term == "coriolis":
            return self.say.say("table.coriolis")
        return self.say.say("table.known")

    def line_direction(self, direction: Direction) -> str:
        if direction.relation == "perpendicular":
            return self.say.say("table.perpendicular", reference=direction.reference)
        if direction.relation == "parallel":
            return self.say.say("table.parallel", slider=direction.reference)
        if direction.relation == "face":
            return self.say.say("table.face", link=direction.reference)
        return self.say.say("table.known")

    def absolute_row(self, polygon: str, term: str) -> tuple[str, str, str]:
        name = term_name(term)
        label = name.point.text if name is not None and name.reference is None else ""
        tip = self.tips(polygon).get(label) if label else None
        if tip is None:
            return (term, self.say.say("table.known"), self.say.say("table.known"))
        if self.tip_or_pole(polygon, label) == self.pole(polygon):
            return (term, "0", self.say.say("table.pole", pole=self.pole(polygon)))
        return (term, f"{self.n(norm(tip))} {self.unit_of(polygon)}",
                self.say.say("table.known_tip", pole=self.pole(polygon), tip=tip_name(label, polygon)))

    def rows(self, step: Step) -> tuple[tuple[str, ...], ...]:
        sides = step.sides
        laid = {v.label: v for v in step.vectors}
        loose = {v.name.loose: v for v in step.vectors if v.name is not None}
        unit = self.unit_of(step.polygon)
        out: list[tuple[str, ...]] = [(sides[0][0], "?", "?")]
        for k, side in enumerate(sides[1:]):
            for n, term in enumerate(side):
                name = term_name(term)
                vector = laid.get(term) or (loose.get(name.loose) if name is not None else None)
                if step.topic == "intersection" and n == len(side) - 1 and k < len(step.directions):
                    out.append((term, "?", self.line_direction(step.directions[k])))
                elif vector is not None:
                    out.append((term, f"{self.n(norm(sub(vector.end, vector.start)))} {unit}",
                                self.vector_direction(vector)))
                elif step.topic == "relative" and name is not None and name.reference is not None:
                    for v in step.vectors:  # the term's components laid (a^n_B/A and a^t_B/A for a_B/A)
                        if v.name is not None and (v.name.point, v.name.reference) == (name.point, name.reference):
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


def _step_page(writer: _Writer, context: Context, step: Step, number: int, total: int) -> Page:
    say = writer.say
    if step.topic == "equivalent-link":
        return equivalent_page(context, say, step, number, total)
    text, result = step_words(step, say, context)
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


def _kennedy_page(context: Context, say: Catalogue, step: KennedyStep, number: int, total: int) -> Page:
    solution = context.solution
    centers = solution.centers
    assert centers is not None
    text, result = kennedy_words(step, say, context)
    used = list(dict.fromkeys(c for line in step.lines for c in line.centers))
    heading = say.say("page.step", number=str(number), total=str(total), polygon=say.say("polygon.centers"))
    equation = typographic(step.equation)
    rows = tuple((center_label(c), _how_found(solution, centers, c, say)) for c in used)
    rows += tuple((line.label, say.say("kennedy.normal", contact=line.contact, pair=step.center))
                  for line in step.lines if line.is_common_normal)
    table = Table("", (say.say("kennedy.center"), say.say("kennedy.found")), rows)
    columns = (Column((Paragraph(heading, "heading"), Paragraph(equation, "equation"), table)),
               Column((Paragraph(text), Paragraph(result, "result")), fill=True))
    return Page("step", Drawing("kennedy", step.number), columns, equation, heading)


def construction_pages(solution: Solution, say: Catalogue, scales: Mapping[str, float]) -> list[Page]:
    """A page per construction step, then one per Kennedy step; ``scales`` are kv and ka as drawn."""
    context = Context(solution, scales)
    writer = _Writer(context, say)
    kennedy = solution.centers.steps if solution.centers is not None and solution.scene.find.instant_centers else ()
    total = len(solution.steps) + len(kennedy)
    pages = [_step_page(writer, context, step, n, total) for n, step in enumerate(solution.steps, 1)]
    pages += [_kennedy_page(context, say, step, len(solution.steps) + k, total) for k, step in enumerate(kennedy, 1)]
    return pages
