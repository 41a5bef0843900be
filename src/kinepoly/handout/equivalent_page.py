"""The handout's page of a cam's equivalent-linkage step (the step of topic ``equivalent-link``).

It says what the pair is replaced by (a binary link between the two centres of curvature, or, for a
flat face, a block pinned at the disc's centre sliding on the follower), where the link's ends are at
this position, and why the replacement is valid at this instant (K_A(-1) by K_B(-1): the pair's
velocity and acceleration relations are those of the link), in the catalogue's language.
"""

from __future__ import annotations

from kinepoly.engine.steps import Step
from kinepoly.handout.content import Column, Drawing, Page, Paragraph, Table
from kinepoly.present.catalogue import Catalogue
from kinepoly.present.phrasing import Context, equivalent_name, step_words
from kinepoly.solution import Solution

__all__ = ["equivalent_page"]


def _equation(step: Step, solution: Solution, say: Catalogue) -> str:
    p = dict(step.params)
    unit = solution.scene.units.length
    length = say.number(float(p["length"]))
    if p["kind"] == "flat":
        return f"{p['centre']} ∥ {p['follower']}, d = {length} {unit}"
    return f"{p['centre']}{p['point']} = {length} {unit}"


def _ends(step: Step, solution: Solution, say: Catalogue) -> Table:
    p = dict(step.params)
    unit = solution.scene.units.length
    centre = str(p["centre"])
    rows = [(centre, str(p["cam"]), say.pair(*solution.position(centre)))]
    if p["kind"] == "flat":
        rows.append((say.say("higher_pairs.end_slide"), str(p["follower"]),
                     f"d = {say.number(float(p['length']))}"))
    else:
        point = str(p["point"])
        rows.append((point, str(p["follower"]), say.pair(*solution.position(point))))
    header = (say.say("higher_pairs.end"), say.say("higher_pairs.on_link"), say.say("higher_pairs.place", unit=unit))
    return Table("", header, tuple(rows))


def equivalent_page(context: Context, say: Catalogue, step: Step, number: int, total: int) -> Page:
    """The page of ``step`` (number ``number`` of ``total``): the replacement, its ends, why it holds."""
    solution = context.solution
    p = dict(step.params)
    pair, unit = str(p["pair"]), solution.scene.units.length
    contact_name = f"C{pair}"
    contact = solution.contacts.get(pair)
    what, _ = step_words(step, say, context)
    key = "higher_pairs.why_block" if p["kind"] == "flat" else "higher_pairs.why_link"
    why = say.say(key + ("_spline" if p.get("spline") == "yes" else ""), contact=contact_name,
                  centre=str(p["centre"]), point=str(p["point"]), follower=str(p["follower"]),
                  length=say.number(float(p["length"])), unit=unit)
    at = say.pair(*contact.point) if contact is not None else "?"
    result = say.say("higher_pairs.equivalent_result", link=equivalent_name(p, say), pair=pair, contact=contact_name,
                     at=at, unit=unit)
    heading = say.say("page.step", number=str(number), total=str(total), polygon=say.say(f"polygon.{step.polygon}"))
    equation = _equation(step, solution, say)
    first = (Paragraph(heading, "heading"), Paragraph(say.say("higher_pairs.equivalent_heading", pair=pair), "note"),
             Paragraph(equation, "equation"), _ends(step, solution, say))
    columns = (Column(first), Column((Paragraph(what), Paragraph(why), Paragraph(result, "result")), fill=True),
               Column((), legend=True))
    return Page("step", Drawing("step", number), columns, equation, heading)
