"""The words of the construction: every step's sentence from its data, in the catalogue's language.

One phrasing serves everything that says a step: ``kinepoly solve --steps`` and the JSON's
``steps[].text`` (English), the drawing's step blocks (English) and the handout's pages (any
language). Nothing here is translated from English: the words come from the message catalogue
(``present.catalogue``), the names and numbers from ``Step.topic``, ``Step.params``,
``Step.directions`` and ``Step.vectors`` (``kinepoly.engine.steps`` lists each topic's
parameters), from the Kennedy steps and the angular velocities the instant centers give, and
from the solution they belong to (the tips of the polygons, the angular velocities, the pose).

Every number a student needs to redo a step by hand is in its sentence, and the length of each
vector on the paper at the polygon's scale (``Context.scales``, mm per unit of the polygon).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from functools import cache, cached_property
from typing import TYPE_CHECKING

from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.groups import NewtonGroup
from kinepoly.engine.steps import Direction, DrawnVector, Step, term_name
from kinepoly.geom.tolerances import COINCIDENT_REL, SAME_REL
from kinepoly.geom.vec import Vec, norm, sub
from kinepoly.present.catalogue import Catalogue, load_catalogue
from kinepoly.present.clean import Noise, noise_of
from kinepoly.present.scales import PolygonScale
from kinepoly.scene.link_point import LinkPoint, point_of
from kinepoly.solution import Solution

if TYPE_CHECKING:  # the instant centers' modules are loaded only for a solution with centers
    from kinepoly.engine.center_values import KennedyStep
    from kinepoly.engine.center_velocity import CenterOmega

__all__ = [
    "Context",
    "Words",
    "canonical_terms",
    "canonical_text",
    "center_omega_sentence",
    "english",
    "equivalent_name",
    "kennedy_sentence",
    "kennedy_words",
    "scale_note",
    "segment",
    "step_sentence",
    "step_words",
    "term_ends",
    "tip_name",
]

_TINY = COINCIDENT_REL
_FLAT_MM = 0.01
"""An image point stood off the line of two tips by less than this on the paper is drawn on that line."""


@cache
def english() -> Catalogue:
    """The shipped English catalogue (loaded once): the words of ``solve --steps``, the JSON and the drawings."""
    return load_catalogue("en")


def equivalent_name(params: Mapping[str, object], say: Catalogue) -> str:
    """A circle cam's equivalent link as the course texts name it, from its step's parameters: the equivalent link
    K23W by its two pins, the block at K on the face of the follower (a spline's, made at one position, keeps
    the name the construction gave it)."""
    if params.get("spline") == "yes":
        return str(params["link"])
    if params["kind"] == "flat":
        return say.say("higher_pairs.named_block", centre=str(params["centre"]), follower=str(params["follower"]))
    return say.say("higher_pairs.named_link", name=f"{params['centre']}{params['point']}")


class Context(Struct, frozen=True, dict=True):
    """What a step's sentence needs besides the step: the solution it belongs to and the scales it is drawn at.

    ``scales`` are paper mm per unit of each polygon, keyed ``velocity`` and ``acceleration``
    (kv and ka; other keys are ignored): the sentences give every vector's length on the paper.
    """

    solution: Solution
    scales: Mapping[str, float]

    @cached_property
    def terms(self) -> dict[str, str]:
        """``canonical_terms`` of the solution, found once for all the steps phrased in this context."""
        return canonical_terms(self.solution)

    @cached_property
    def noise(self) -> Noise:
        """``present.clean.noise_of`` the solution, found once for all the steps phrased in this context."""
        return noise_of(self.solution)


def tip_name(label: str, polygon: str) -> str:
    """A point's tip in the polygon: ``B0`` -> ``b0``; in the acceleration polygon primed, ``b′0``."""
    named = LinkPoint.parse(label)
    m = re.match(r"^(\D+)(\d*)$", named.point)
    base, digits = (m.group(1), m.group(2)) if m else (named.point, "")
    prime = "′" if polygon == "acceleration" else ""
    return f"{base.lower()}{prime}{digits}{named.at_link}"


def segment(first: str, second: str) -> str:
    """The segment between two points of the mechanism: ``A@4`` and ``B0`` -> ``AB0``."""
    return point_of(first) + point_of(second)


_TOKEN = re.compile(r"[va](?:\^[nt])?_[^\s/|,;()=]+/[^\s|,;()=]+")


def _canonical(label: str, solution: Solution, tips: set[str]) -> str:
    """``a^n_A/B0`` as ``a^n_A@4/B0`` where A is no point of a link that carries B0 but A@4 is a tip.

    A relative term belongs to the link that carries both its points: where the point named is the
    point of another link (A, the block's pin, over the slotted link 4), it is the coincident
    point of that link (A@4), as the equation of the step that crosses its line names it.
    """
    name = term_name(label)
    if name is None or name.reference is None or name.point.link is not None or name.component not in ("", "n", "t"):
        return label
    point = name.point.point
    mechanism = solution.mechanism
    on_base = mechanism.links_of_point(name.reference.point)  # in scene order
    if set(mechanism.links_of_point(point)).intersection(on_base):
        return label
    carriers = [k for k in on_base if k != mechanism.ground and LinkPoint(point, k).text in tips]
    return replace(name, point=LinkPoint(point, carriers[0])).text if len(carriers) == 1 else label


def canonical_terms(solution: Solution) -> dict[str, str]:
    """Each relative term's label written otherwise in the steps (``a^n_A/B0``) and how every step writes it."""
    tips = {label for polygon in (solution.velocity, solution.acceleration) if polygon is not None
            for label in polygon.tips}
    found: set[str] = set()
    for step in solution.steps:
        texts = [step.equation, *(t for t, _ in step.known), *(v.label for v in step.vectors),
                 *(d.term for d in step.directions), *(d.after for d in step.directions),
                 *(str(v) for k, v in step.params if k == "term")]
        for text in texts:
            found.update(_TOKEN.findall(text))
    out = {}
    for label in sorted(found):
        canonical = _canonical(label, solution, tips)
        if canonical != label:
            out[label] = canonical
    return out


def _literal(text: str) -> Callable[[re.Match[str]], str]:
    """A replacement that is ``text`` as written (a point name with a backslash is no group reference)."""
    return lambda _: text


def canonical_text(text: str, terms: Mapping[str, str]) -> str:
    """``text`` with every term of ``terms`` (``canonical_terms``) written as the steps write it."""
    for label, canonical in terms.items():
        text = re.sub(rf"(?<![\w@^]){re.escape(label)}(?![\w@])", _literal(canonical), text)
    return text


def term_ends(vector: DrawnVector) -> tuple[str, str]:
    """The point and the reference of a vector's term, as named: ``a^n_B@4/A`` -> (``B@4``, ``A``); ``a_B`` ->
    (``B``, "")."""
    name = vector.name
    if name is None:
        return "", ""
    return name.point.text, "" if name.reference is None else name.reference.text


class Words:
    """The words of one solution's steps in one language: symbols, units, poles, tips, scales on paper."""

    def __init__(self, context: Context, say: Catalogue) -> None:
        self.solution = context.solution
        self.say = say
        self.scales = context.scales
        self.unit = context.solution.scene.units.length
        self.ground = context.solution.mechanism.ground or ""
        self.noise: Noise = context.noise
        self.terms = context.terms

    def clean(self, value: str | float, kind: str) -> float:
        """``value`` of ``kind`` (``present.clean.KINDS``), 0 where below its error estimate."""
        return self.noise.value(float(value), kind)

    def rate_kind(self, polygon: str) -> str:
        return "omega" if polygon == "velocity" else "alpha"

    def size_kind(self, polygon: str) -> str:
        return polygon  # the magnitudes of the velocity (acceleration) polygon are velocities (accelerations)

    def is_zero(self, value: str | float, kind: str) -> bool:
        return self.clean(value, kind) == 0.0

    def unit_of(self, polygon: str) -> str:
        return f"{self.unit}/s" if polygon == "velocity" else f"{self.unit}/s²"

    def pole(self, polygon: str) -> str:
        return "o" if polygon == "velocity" else "o′"

    def symbol(self, polygon: str) -> str:
        return "v" if polygon == "velocity" else "a"

    def rate_unit(self, polygon: str) -> str:
        return "rad/s" if polygon == "velocity" else "rad/s²"

    def rate_name(self, polygon: str, ground: str, link: str) -> str:
        return f"{'ω' if polygon == 'velocity' else 'α'}{ground}{link}"

    def paper(self, polygon: str, magnitude: float) -> str:
        """``magnitude`` of a vector of ``polygon`` as mm on the paper."""
        if polygon not in self.scales:
            raise KeyError(f"no scale for the {polygon} polygon; Context.scales has {sorted(self.scales)}")
        return self.say.number(abs(self.clean(magnitude, self.size_kind(polygon))) * self.scales[polygon])

    def tips(self, polygon: str) -> dict[str, Vec]:
        found = self.solution.velocity if polygon == "velocity" else self.solution.acceleration
        return dict(found.tips) if found is not None else {}

    def tip_or_pole(self, polygon: str, label: str) -> str:
        """The tip of ``label``, or the pole when the point does not move (a point of the frame)."""
        tips = self.tips(polygon)
        tip = tips.get(label)
        if tip is not None and norm(tip) <= _TINY * max((norm(t) for t in tips.values()), default=1.0):
            return self.pole(polygon)
        return tip_name(label, polygon)

    def sense(self, code: str | float) -> str:
        return self.say.say(f"sense.{code}")

    def sense_of(self, value: float, kind: str = "omega") -> str:
        value = self.clean(value, kind)
        return self.sense("ccw" if value > 0.0 else "cw" if value < 0.0 else "zero")

    def n(self, value: str | float, kind: str | None = None) -> str:
        """A number as the catalogue writes it; with ``kind``, 0 where below that kind's error estimate."""
        return self.say.number(float(value) if kind is None else self.clean(value, kind))

    def rate_found(self, polygon: str, name: str, value: float) -> str:
        """``Found: ω13 = 1.2 rad/s, clockwise.``, or ``Found: ω13 = 0 rad/s.`` (a zero has no sense)."""
        kind = self.rate_kind(polygon)
        if self.is_zero(value, kind):
            return self.say.say("result.rate_zero", rate_name=name, unit=self.rate_unit(polygon))
        return self.say.say("result.rate", rate_name=name, value=self.n(value, kind), unit=self.rate_unit(polygon),
                            sense=self.sense_of(value, kind))

    def term(self, label: str) -> str:
        """A term's label as every step writes it (``canonical_terms``)."""
        return self.terms.get(label, label)

    def angle_of(self, value: Vec) -> str:
        return self.say.angle(math.atan2(value[1], value[0]))

    def normal_fields(self, vector: DrawnVector) -> dict[str, str]:
        """ω, its name, the segment and its length of a normal term (``a^n_B/A = ω13² · |AB|``)."""
        point, reference = term_ends(vector)
        size = norm(sub(vector.end, vector.start))
        mechanism = self.solution.mechanism
        omega = self.solution.velocity.omega if self.solution.velocity is not None else {}
        (p, p_on), (r, r_on) = ((named.point, named.link or "") for named in map(LinkPoint.parse, (point, reference)))
        members = self.solution.velocity.members if self.solution.velocity is not None else {}

        def carries(link: str, name: str) -> bool:  # a point of the link, or one the construction found on it (S)
            return mechanism.has_point(link, name) or any(label == name for label, _ in members.get(link, ()))

        # the link turning: the one the term names (B@4), else one that carries both points, else (a
        # point that slides on a link, A@4 of a slot) one that carries the reference, else the point
        tiers = ([k for k in omega if k in (p_on, r_on)],
                 [k for k in omega if carries(k, p) and carries(k, r)],
                 [k for k in omega if carries(k, r)],
                 [k for k in omega if carries(k, p)])
        links = next((tier for tier in tiers if tier), None)
        if links is None:
            raise KeyError(f"{vector.label}: no link of known ω carries {point} or {reference}")
        length = norm(sub(self.solution.position(point), self.solution.position(reference)))
        link = min(links, key=lambda k: abs(omega[k] ** 2 * length - size))
        return {"omega_name": self.rate_name("velocity", self.ground, link), "omega": self.n(abs(omega[link]), "omega"),
                "segment": segment(reference, point), "length": self.n(length, "position")}


def _group(words: Words, step: Step) -> NewtonGroup | None:
    """The group a linear-solve step belongs to: the n-th such step of its polygon is the n-th Newton group."""
    solution = words.solution
    same = [s for s in solution.steps if s.polygon == step.polygon and s.kind == "linear-solve"]
    groups = [g for g in solution.plan.groups if isinstance(g, NewtonGroup)]
    index = next((k for k, s in enumerate(same) if s is step), len(groups))
    return groups[index] if index < len(groups) else None


class _Phrase:
    """The explanation and the result of one step, in words."""

    def __init__(self, words: Words, step: Step) -> None:
        self.w = words
        self.step = step
        self.p = dict(step.params)
        self.polygon = step.polygon
        self.say = words.say

    def common(self) -> dict[str, str]:
        return {"unit": self.w.unit_of(self.polygon), "pole": self.w.pole(self.polygon)}

    def tip_fields(self, name: str, value: Vec) -> dict[str, str]:
        """A tip found: the absolute vector, its angle and length on paper (``result.tip`` and ``result.tip_item``)."""
        return {"tip": tip_name(name, self.polygon), "term": f"{self.w.symbol(self.polygon)}_{name}",
                "magnitude": self.w.n(norm(value), self.w.size_kind(self.polygon)), "angle": self.w.angle_of(value),
                "paper": self.w.paper(self.polygon, norm(value)), **self.common()}

    def found_tip(self) -> str:
        """The result of a step that finds a tip: the absolute vector, its angle and length on paper."""
        step = self.step
        label = step.result.upper() if step.result else ""
        tips = self.w.tips(self.polygon)
        name = next((k for k in tips if k.lower() == step.result), label)
        value = tips.get(name, (step.value[0], step.value[1]) if len(step.value) == 2 else (0.0, 0.0))
        fields = self.tip_fields(name, value)
        if self.w.is_zero(norm(value), self.w.size_kind(self.polygon)):
            return self.say.say("result.tip_at_pole", tip=fields["tip"], term=fields["term"], pole=fields["pole"])
        return self.say.say("result.tip", **fields)

    def explain(self) -> tuple[str, str]:
        """(what to do and why, what it yields)."""
        handler = getattr(self, "_" + (self.step.topic or self.step.kind).replace("-", "_"), None)
        if handler is None:
            raise ValueError(f"no words for a step of topic {self.step.topic!r}, kind {self.step.kind!r}")
        result: tuple[str, str] = handler()
        return result

    def _input_rate(self) -> tuple[str, str]:
        p = self.p
        name = self.w.rate_name(self.polygon, str(p["ground"]), str(p["link"]))
        key = "step.input_rate_velocity" if self.polygon == "velocity" else "step.input_rate_acceleration"
        zero = self.w.is_zero(p["rate"], self.w.rate_kind(self.polygon))
        text = self.say.say(key + ("_zero" if zero else ""), link=str(p["link"]), rate_name=name,
                            rate=self.w.n(p["rate"], self.w.rate_kind(self.polygon)),
                            sense=self.w.sense(p["sense"]), pole=self.w.pole(self.polygon))
        value = self.step.value[0] if self.step.value else 0.0
        return text, self.say.say("result.given", rate_name=name, value=self.w.n(value, self.w.rate_kind(self.polygon)),
                                  unit=self.w.rate_unit(self.polygon))

    def _driven_slider(self) -> tuple[str, str]:
        p = self.p
        name = f"{'ṡ' if self.polygon == 'velocity' else 's̈'}{p['slider']}"
        amount = float(p["amount"])
        text = self.say.say("step.driven_slider", slider=str(p["slider"]),
                            term=f"{self.w.symbol(self.polygon)}_{p['point']}", rate_name=name,
                            amount=self.w.n(amount, self.w.size_kind(self.polygon)),
                            paper=self.w.paper(self.polygon, amount),
                            tip=tip_name(str(p["point"]), self.polygon), **self.common())
        return text, self.found_tip()

    def _drive_term(self) -> tuple[str, str]:
        p = self.p
        term, after = str(p["term"]), str(p["after"])
        start = self.w.tip_or_pole(self.polygon, after) if "^" not in after else after
        key = "drive.term_velocity" if self.polygon == "velocity" else "drive.term_acceleration"
        text = self.say.say(key, term=term, drive=str(p["drive"]), point=str(p["point"]), carrier=str(p["carrier"]),
                            magnitude=self.w.n(p["magnitude"]), paper=self.w.paper(self.polygon, float(p["magnitude"])),
                            from_tip=start, **self.common())
        value = self.step.value
        return text, self._vector_result(term, (value[0], value[1]))

    def _added_rate(self) -> tuple[str, str]:
        p = self.p
        ground = str(p["ground"])
        name = self.w.rate_name(self.polygon, ground, str(p["link"]))
        known = self.w.rate_name(self.polygon, ground, str(p["known"]))
        motor = f"{'ω' if self.polygon == 'velocity' else 'α'}{p['motor']}"
        text = self.say.say("drive.added_rate", link=str(p["link"]), known_link=str(p["known"]), rate_name=name,
                            known_name=known, motor=motor, sign=str(p["sign"]))
        value = self.step.value[0] if self.step.value else 0.0
        return text, self.say.say("result.rate", rate_name=name, value=self.w.n(value),
                                  unit=self.w.rate_unit(self.polygon), sense=self.w.sense_of(value))

    def _given_point(self) -> tuple[str, str]:
        p = self.p
        value = self.step.value
        text = self.say.say("step.given_point", term=f"{self.w.symbol(self.polygon)}_{p['point']}",
                            magnitude=self.w.n(p["magnitude"], self.w.size_kind(self.polygon)),
                            angle=self.w.angle_of((value[0], value[1])),
                            paper=self.w.paper(self.polygon, float(p["magnitude"])),
                            tip=tip_name(str(p["point"]), self.polygon), **self.common())
        return text, self.found_tip()

    def _relative(self) -> tuple[str, str]:
        p = self.p
        point, reference = str(p["point"]), str(p["reference"])
        rate_kind = self.w.rate_kind(self.polygon)
        fields = {"point": point, "reference": reference, "link": str(p["link"]),
                  "segment": segment(reference, point), "length": self.w.n(p["length"], "position"),
                  "length_unit": self.w.unit, "sense": self.w.sense(p["sense"]), "rate": self.w.n(p["rate"], rate_kind),
                  "from_tip": self.w.tip_or_pole(self.polygon, reference), "tip": tip_name(point, self.polygon),
                  **self.common()}
        zero_rate = self.w.is_zero(p["rate"], rate_kind)
        if self.polygon == "velocity":
            key = "step.relative_velocity_zero" if zero_rate else "step.relative_velocity"
            text = self.say.say(key, term=f"v_{point}/{reference}",
                                rate_name=self.w.rate_name("velocity", str(p["ground"]), str(p["link"])),
                                magnitude=self.w.n(p["magnitude"], "velocity"),
                                paper=self.w.paper("velocity", float(p["magnitude"])), **fields)
        else:
            zero_omega = self.w.is_zero(p["omega"], "omega")
            key = ("step.relative_acceleration_zero" if zero_omega and zero_rate else
                   "step.relative_acceleration_no_normal" if zero_omega else
                   "step.relative_acceleration_no_tangential" if zero_rate else "step.relative_acceleration")
            text = self.say.say(key, normal_term=f"a^n_{point}/{reference}",
                                tangential_term=f"a^t_{point}/{reference}",
                                omega_name=self.w.rate_name("velocity", str(p["ground"]), str(p["link"])),
                                rate_name=self.w.rate_name("acceleration", str(p["ground"]), str(p["link"])),
                                omega=self.w.n(p["omega"], "omega"), normal=self.w.n(p["normal"], "acceleration"),
                                tangential=self.w.n(p["tangential"], "acceleration"),
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
        text = self.say.say("step.image", angle_first=self.say.degrees(float(p["angle_first"])),
                            angle_second=self.say.degrees(float(p["angle_second"])), **self._image_fields())
        return text, self.found_tip()

    def _image_translating(self) -> tuple[str, str]:
        key = "step.image_translating_velocity" if self.polygon == "velocity" else "step.image_translating_acceleration"
        return self.say.say(key, **self._image_fields()), self.found_tip()

    def _proportional(self) -> tuple[str, str]:
        """A point of a flat triangle: on the line of two tips (collinear), or stood off it by a height."""
        p = self.p
        fields = self._image_fields()
        ratio, height = float(p["ratio"]), float(p["height"])
        tips = self.w.tips(self.polygon)
        first, second = tips.get(str(p["first"]), (0.0, 0.0)), tips.get(str(p["second"]), (0.0, 0.0))
        side = norm(sub(second, first)) * self.w.scales.get(self.polygon, 1.0)  # mm on the paper
        if abs(height) * side < _FLAT_MM or abs(height) <= SAME_REL:
            return self._collinear(ratio, side, fields), self.found_tip()
        text = self.say.say("step.proportional_offset", ratio=self.w.n(ratio), height=self.w.n(height),
                            foot_paper=self.say.number(abs(ratio) * side),
                            offset_paper=self.say.number(abs(height) * side),
                            **fields)
        return text, self.found_tip()

    def _collinear(self, ratio: float, side: float, fields: dict[str, str]) -> str:
        """A point on the line of two points of its link: its tip divides theirs in the same proportion."""
        p = self.p
        first, second = str(p["first"]), str(p["second"])
        solution = self.w.solution
        length = norm(sub(solution.position(second), solution.position(first)))
        first_tip, second_tip = (self.w.tip_or_pole(self.polygon, label) for label in (first, second))
        first, second, point = (point_of(label) for label in (first, second, str(p["point"])))
        where = ("collinear_between" if 0.0 <= ratio <= 1.0 else "collinear_beyond_second" if ratio > 1.0
                 else "collinear_beyond_first")
        toward = "collinear_toward" if ratio >= 0.0 else "collinear_away"
        return self.say.say("step.collinear", where=self.say.say(f"step.{where}", first=first, second=second),
                            where_tip=self.say.say(f"step.{toward}", second_tip=second_tip),
                            ratio=self.w.n(abs(ratio)), length=self.w.n(length, "position"), length_unit=self.w.unit,
                            part=self.w.n(abs(ratio) * length, "position"), side=self.say.number(side),
                            distance=self.say.number(abs(ratio) * side),
                            **{**fields, "first": first, "second": second, "point": point,
                               "first_tip": first_tip, "second_tip": second_tip})

    def _line(self, direction: Direction) -> str:
        through = direction.through
        label = next((k for k in self.w.tips(self.polygon) if k.lower() == through), through)
        tip = self.w.tip_or_pole(self.polygon, label)
        key = {"parallel": "line.parallel", "face": "line.face"}.get(direction.relation, "line.perpendicular")
        return self.say.say(key + ("_end" if direction.after else ""), through=tip, after=direction.after,
                            term=direction.term, slider=direction.reference, reference=direction.reference,
                            link=direction.reference)

    def _intersection(self) -> tuple[str, str]:
        step = self.step
        point = str(self.p["point"])
        key = "step.intersection_velocity" if self.polygon == "velocity" else "step.intersection_acceleration"
        text = self.say.say(key, first_line=self._line(step.directions[0]), second_line=self._line(step.directions[1]),
                            tip=tip_name(point, self.polygon), term=f"{self.w.symbol(self.polygon)}_{point}",
                            **self.common())
        return text, f"{self.found_tip()} {self._terms_found()}"

    def _terms_found(self) -> str:
        """The magnitude of each term along a direction line: from where the line starts (the end of the terms
        laid before it) to the tip found."""
        step = self.step
        parts = []
        for direction, line in zip(step.directions, step.lines, strict=True):
            size = norm(sub((step.value[0], step.value[1]), line.through))
            parts.append(self.say.say("result.term", term=direction.term,
                                      magnitude=self.w.n(size, self.w.size_kind(self.polygon)),
                                      unit=self.w.unit_of(self.polygon)))
        return self.say.say("result.terms", terms="; ".join(parts))

    def _rolling(self) -> tuple[str, str]:
        """A gear's pitch-point tip: the rolling condition's line crossed with the gear's own line."""
        p = self.p
        point, known = str(p["point"]), str(p["known_point"])
        pitch = point_of(point)
        how = (self.say.say("higher_pairs.how_rack") if p["rack"] == "yes" else
               self.say.say("higher_pairs.how_pin", centre=str(p["through"]), pitch=pitch))
        through_tip = self.w.tip_or_pole(self.polygon, str(p["through"]))  # a rack: its guide's point under P
        key = "higher_pairs.rolling_velocity" if self.polygon == "velocity" else "higher_pairs.rolling_acceleration"
        text = self.say.say(key, pair=str(p["pair"]), pitch=pitch, point=point, known_point=known, link=str(p["link"]),
                            known=str(p["known"]), known_tip=self.w.tip_or_pole(self.polygon, known),
                            through_tip=through_tip, how=how, tip=tip_name(point, self.polygon), **self.common())
        return text, self.found_tip()

    def _pitch_point(self) -> tuple[str, str]:
        """A planet's tip at a pitch point: the known gear's tip there (rolling, the centre distance kept)."""
        p = self.p
        known = str(p["known_point"])
        text = self.say.say("higher_pairs.pitch_point_velocity", pair=str(p["pair"]), pitch=str(p["pitch"]),
                            point=str(p["point"]), known_point=known, link=str(p["link"]), known=str(p["known"]),
                            known_tip=self.w.tip_or_pole(self.polygon, known),
                            tip=tip_name(str(p["point"]), self.polygon), **self.common())
        return text, self.found_tip()

    def _planet_centre(self) -> tuple[str, str]:
        """A planet's centre on an undriven arm: the line of centres through the point dividing the known gears'
        tips at the pitch points, crossed with the line of the arm's tangential term."""
        p, polygon, w = self.p, self.polygon, self.w
        ratio = float(p["ratio"])
        side = float(p["side"]) * w.scales.get(polygon, 1.0)  # mm on the paper
        centre, pivot = str(p["centre"]), str(p["pivot"])
        text = self.say.say(
            "higher_pairs.planet_centre_acceleration", planet=str(p["planet"]), arm=str(p["arm"]), centre=centre,
            pivot=pivot, pitch_a=str(p["pitch_a"]), pitch_b=str(p["pitch_b"]), gear_a=str(p["gear_a"]),
            gear_b=str(p["gear_b"]), tip_a=w.tip_or_pole(polygon, str(p["known_a"])),
            tip_b=w.tip_or_pole(polygon, str(p["known_b"])), ratio=w.n(ratio),
            distance=self.say.number(abs(ratio) * side), side=w.n(float(p["side"]), w.size_kind(polygon)),
            side_paper=w.paper(polygon, float(p["side"])), pivot_tip=w.tip_or_pole(polygon, pivot),
            omega_name=w.rate_name("velocity", w.ground, str(p["arm"])), omega=w.n(float(p["omega"]), "omega"),
            length=w.n(float(p["length"]), "position"), length_unit=w.unit,
            normal=w.n(float(p["normal"]), w.size_kind(polygon)), normal_paper=w.paper(polygon, float(p["normal"])),
            tip=tip_name(centre, polygon), star=tip_name(f"{centre}*", polygon), **self.common())
        return text, self.found_tip()

    def _equivalent_link(self) -> tuple[str, str]:
        p = self.p
        spline = "_spline" if p.get("spline") == "yes" else ""
        key = (f"higher_pairs.equivalent{spline}_block" if p["kind"] == "flat" else
               "higher_pairs.equivalent_spline" if spline else
               "higher_pairs.equivalent_block" if p["kind"] == "flat" else "higher_pairs.equivalent_link")
        link = str(p["link"]) if spline else f"{p['centre']}{p['point']}"  # the seeds' K23W
        text = self.say.say(key, pair=str(p["pair"]), cam=str(p["cam"]), follower=str(p["follower"]),
                            link=link, centre=str(p["centre"]), point=str(p["point"]),
                            length=self.w.n(float(p["length"]), "position"), unit=self.w.unit)
        return text, ""

    def _leg_line(self, which: str) -> str:
        p = self.p
        if f"{which}_segment" in p:
            return self.say.say("triad.leg_rod", segment=str(p[f"{which}_segment"]))
        if f"{which}_face" in p:
            return self.say.say("triad.leg_face", link=str(p[f"{which}_face"]), point=str(p[f"{which}_point"]))
        return self.say.say("triad.leg_slide", slider=str(p[f"{which}_slider"]), point=str(p[f"{which}_point"]))

    def _assur_point(self) -> tuple[str, str]:
        p = self.p
        text = self.say.say("triad.assur_point", point=str(p["point"]), ternary=str(p["ternary"]),
                            first=str(p["first"]), second=str(p["second"]), first_line=self._leg_line("first"),
                            second_line=self._leg_line("second"), third=str(p["third"]))
        return text, self.say.say("triad.assur_found", point=str(p["point"]))

    def _assur_tip(self) -> tuple[str, str]:
        step = self.step
        point = str(self.p["point"])
        key = "triad.assur_tip_velocity" if self.polygon == "velocity" else "triad.assur_tip_acceleration"
        text = self.say.say(key, point=point, ternary=str(self.p["ternary"]), first=str(self.p["first"]),
                            second=str(self.p["second"]), first_line=self._line(step.directions[0]),
                            second_line=self._line(step.directions[1]), tip=tip_name(point, self.polygon),
                            term=f"{self.w.symbol(self.polygon)}_{point}", **self.common())
        return text, f"{self.found_tip()} {self._terms_found()}"

    def _read(self) -> tuple[str, str]:
        p = self.p
        name = self.w.rate_name(self.polygon, str(p["ground"]), str(p["link"]))
        first, second = str(p["first"]), str(p["second"])
        rate_kind = self.w.rate_kind(self.polygon)
        key = "step.read_zero" if self.w.is_zero(p["rate"], rate_kind) else "step.read"
        text = self.say.say(key, rate_name=name, term=str(p["term"]), segment=segment(first, second),
                            magnitude=self.w.n(p["magnitude"], self.w.size_kind(self.polygon)),
                            length=self.w.n(p["length"], "position"),
                            rate=self.w.n(p["rate"], rate_kind), rate_unit=self.w.rate_unit(self.polygon),
                            sense=self.w.sense(p["sense"]), first=point_of(first),
                            second=point_of(second), link=str(p["link"]))
        value = self.step.value[0] if self.step.value else 0.0
        return text, self.w.rate_found(self.polygon, name, value)

    def _coriolis(self) -> tuple[str, str]:
        p = self.p
        term = str(p["term"])
        vector = self.step.vectors[0]
        key = "step.coriolis_zero" if self.w.is_zero(p["magnitude"], "acceleration") else "step.coriolis"
        text = self.say.say(key, term=term, guide=str(p["guide"]),
                            omega_name=self.w.rate_name("velocity", str(p["ground"]), str(p["guide"])),
                            omega=self.w.n(p["omega"], "omega"), relative=str(p["relative"]),
                            speed=self.w.n(p["speed"], "velocity"), magnitude=self.w.n(p["magnitude"], "acceleration"),
                            paper=self.w.paper(self.polygon, float(p["magnitude"])),
                            sense=self.w.sense(p["sense"]), from_tip=self.w.tip_or_pole(self.polygon, str(p["start"])),
                            **self.common())
        return text, self._vector_result(term, sub(vector.end, vector.start))

    def _vector_result(self, term: str, value: Vec) -> str:
        if self.w.is_zero(norm(value), self.w.size_kind(self.polygon)):
            return self.say.say("result.vector_zero", term=term)
        return self.say.say("result.vector", term=term, magnitude=self.w.n(norm(value)), angle=self.w.angle_of(value),
                            unit=self.w.unit_of(self.polygon))

    def _normals(self) -> tuple[str, str]:
        items = []
        for v in self.step.vectors:
            point, reference = term_ends(v)
            size = norm(sub(v.end, v.start))
            key = "step.normal_item_zero" if self.w.is_zero(size, "acceleration") else "step.normal_item"
            after = self._laid_after(v)
            if after and key == "step.normal_item":
                key = "step.normal_item_after"
            items.append(self.say.say(key, term=v.label, magnitude=self.w.n(size, "acceleration"),
                                      unit=self.w.unit_of(self.polygon), point=point_of(point),
                                      reference=point_of(reference), from_tip=self._normal_start(v),
                                      after=after, paper=self.w.paper(self.polygon, size), **self.w.normal_fields(v)))
        text = self.say.say("step.normals", items="; ".join(items))
        return text, self.say.say("result.laid", terms=", ".join(v.label for v in self.step.vectors))

    def _laid_after(self, vector: DrawnVector) -> str:
        """The term a normal term is laid after, where it starts at no tip but at the end of another term (a
        triad's normal term toward its Assur point, after the leg's own normal or Coriolis term); else ""."""
        tips = self.w.tips(self.polygon)
        _point, reference = term_ends(vector)
        size = max([norm(t) for t in tips.values()] + [1.0])

        def at(point: Vec, other: Vec) -> bool:
            return norm(sub(point, other)) <= COINCIDENT_REL * size

        if reference in tips and at(tips[reference], vector.start):
            return ""
        earlier = list(self.step.vectors[:self.step.vectors.index(vector)])
        earlier += [v for s in self.w.solution.steps if s.polygon == self.polygon for v in s.vectors]
        before = next((v for v in earlier if v != vector and at(v.end, vector.start) and not at(v.start, v.end)), None)
        if before is not None and not any(at(tip, vector.start) for tip in tips.values()):
            return before.label
        return ""

    def _normal_start(self, vector: DrawnVector) -> str:
        """The tip a normal term is laid from: its reference point's, else the tip that is where it starts."""
        tips = self.w.tips(self.polygon)
        _point, reference = term_ends(vector)
        candidates = [reference, *tips] if reference in tips else list(tips)
        for label in candidates:
            if norm(sub(tips[label], vector.start)) <= COINCIDENT_REL * max(norm(tips[label]), 1.0):
                return self.w.tip_or_pole(self.polygon, label)
        return self.w.tip_or_pole(self.polygon, reference)

    def _given_normal(self) -> tuple[str, str]:
        p = self.p
        point, reference = str(p["point"]), str(p["reference"])
        normal, tangential = self.step.vectors
        fields = self.w.normal_fields(normal)
        text = self.say.say("step.given_normal", term=normal.label, tangential=tangential.label,
                            magnitude=self.w.n(p["magnitude"], "acceleration"), point=point, reference=reference,
                            from_tip=tip_name(reference, self.polygon), tip=tip_name(point, self.polygon),
                            paper=self.w.paper(self.polygon, float(p["magnitude"])), **fields, **self.common())
        return text, self._vector_result(tangential.label, sub(tangential.end, tangential.start))

    def rates(self) -> dict[str, float]:
        """The angular velocities (velocity polygon) or accelerations (acceleration polygon) found."""
        if self.polygon == "velocity":
            return dict(self.w.solution.velocity.omega) if self.w.solution.velocity is not None else {}
        return dict(self.w.solution.acceleration.alpha) if self.w.solution.acceleration is not None else {}

    def _linear_solve(self) -> tuple[str, str]:
        step = self.step
        tips = self.w.tips(self.polygon)
        names = [t.strip() for t in step.result.split(",") if t.strip()]
        labels = [next((k for k in tips if k.lower() == t), t.upper()) for t in names]
        shown = ", ".join(tip_name(label, self.polygon) for label in labels)
        group = _group(self.w, step)
        if "links" in self.p:  # the group's links, comma-separated, where the step says them
            links = tuple(link.strip() for link in str(self.p["links"]).split(","))
        elif group is not None:
            links = tuple(group.links)
        else:
            raise ValueError(f"linear-solve step {step.equation!r}: no parameter 'links' and no Newton group for it")
        key = "step.linear_solve_velocity" if self.polygon == "velocity" else "step.linear_solve_acceleration"
        text = self.say.say(key, links=", ".join(links), tips=shown, count=str(len(links)))
        if "equivalent" in self.p:  # a floating follower's spline cam pair, as one of the group's equations
            for pair, link, centre, point in (part.split(" ") for part in str(self.p["equivalent"]).split(", ")):
                text += " " + self.say.say("step.linear_solve_equivalent", pair=pair, link=link, centre=centre,
                                           point=point)
        if "face" in self.p:  # a floating flat face: the block pinned at K sliding along it
            for pair, centre, follower in (part.split(" ") for part in str(self.p["face"]).split(", ")):
                text += " " + self.say.say("step.linear_solve_face", pair=pair, centre=centre, follower=follower)
        if "assur_class" in self.p:  # beyond the course's constructions: say so, and what is drawn
            text += " " + self.say.say("step.linear_solve_class", order=str(self.p["assur_class"]))
        items = []
        for label in labels:
            fields = self.tip_fields(label, tips.get(label, (0.0, 0.0)))
            if label not in tips or self.w.is_zero(norm(tips[label]), self.w.size_kind(self.polygon)):
                items.append(self.say.say("result.tip_item_at_pole", tip=fields["tip"], term=fields["term"],
                                          pole=fields["pole"]))
            else:
                items.append(self.say.say("result.tip_item", **fields))
        rates = self.rates()
        for link in links:
            if link in rates:
                rate_kind = self.w.rate_kind(self.polygon)
                key = "result.rate_item_zero" if self.w.is_zero(rates[link], rate_kind) else "result.rate_item"
                items.append(self.say.say(key, rate_name=self.w.rate_name(self.polygon, self.w.ground, link),
                                          value=self.w.n(rates[link], rate_kind), unit=self.w.rate_unit(self.polygon),
                                          sense=self.w.sense_of(rates[link], rate_kind)))
        return text, self.say.say("result.tips", tips="; ".join(items))


def step_words(step: Step, say: Catalogue, context: Context) -> tuple[str, str]:
    """A construction step in words: (what to do and why, what it yields), in ``say``'s language."""
    words = Words(context, say)
    text, result = _Phrase(words, step).explain()
    return canonical_text(text, words.terms), canonical_text(result, words.terms)


def step_sentence(step: Step, say: Catalogue, context: Context) -> str:
    """A construction step as one paragraph: what to do and why, then what it yields."""
    return " ".join(step_words(step, say, context))


def _links(triangle: str) -> str:
    """``"123"`` or ``"1-2-14"`` (a triangle of the circle diagram) as ``1, 2, 3``."""
    return ", ".join(triangle.split("-") if "-" in triangle else list(triangle))


def kennedy_words(step: KennedyStep, say: Catalogue, context: Context) -> tuple[str, str]:
    """A Kennedy step in words: (the two lines the center lies on, where they cross)."""
    from kinepoly.engine.circle_diagram import center_label

    centers = context.solution.centers
    assert centers is not None, "a Kennedy step belongs to a solution with instant centers"
    center = centers.centers[step.center]
    label = center_label(step.center)
    first, second = step.lines
    if second.is_common_normal:  # a cam pair's center: one Kennedy line crossed with the common normal
        text = say.say("step.kennedy_normal", center=label, cam=center.links[0], follower=center.links[1],
                       first_triangle=_links(step.triangles[0]), first_line=first.label, contact=second.contact,
                       normal=second.label)
    else:
        text = say.say("step.kennedy", center=label, links=", ".join(center.links),
                       first_triangle=_links(step.triangles[0]), second_triangle=_links(step.triangles[1]),
                       first_line=first.label, second_line=second.label)
    used = list(dict.fromkeys(c for line in step.lines for c in line.centers))
    if any(centers.centers[c].is_at_infinity for c in used) or center.is_at_infinity:
        text += " " + say.say("step.kennedy_infinity")
    unit = context.solution.scene.units.length
    if center.position is not None:
        result = say.say("result.center", center=label, place=say.pair(*center.position), unit=unit)
    else:
        assert center.direction is not None
        result = say.say("result.center_infinity", center=label,
                         angle=say.angle(math.atan2(center.direction[1], center.direction[0])))
    return text, result


def kennedy_sentence(step: KennedyStep, say: Catalogue, context: Context) -> str:
    """A Kennedy step as one paragraph."""
    return " ".join(kennedy_words(step, say, context))


def center_omega_sentence(found: CenterOmega, say: Catalogue, context: Context) -> str:
    """How an angular velocity follows from the instant centers (``kinepoly.engine.center_velocity``)."""
    from kinepoly.engine.circle_diagram import center_label, pair_name

    words = Words(context, say)
    ground = context.solution.mechanism.ground or ""
    p = dict(found.params)
    i, j = found.reference, found.link
    far, near = (center_label(name) for name in found.centers)
    fields = {"link_i": i, "link_j": j, "center": near, "center_j": far,
              "omega_i": words.rate_name("velocity", ground, i) if ground else f"ω{i}",
              "omega_j": words.rate_name("velocity", ground, j), "value": words.n(found.omega),
              "sense": words.sense_of(found.omega), "unit": words.unit_of("velocity"), "length_unit": words.unit}
    if found.how == "same":
        return say.say("kennedy.omega_same", **fields)
    if found.how == "translating":
        return say.say("kennedy.omega_translating", velocity=say.pair(float(p["vx"]), float(p["vy"])), **fields)
    if found.how == "ratio":
        return say.say("kennedy.omega_ratio", center_i=center_label(pair_name((ground, i))), rate=words.n(p["given"]),
                       near=words.n(p["near"]), far=words.n(p["far"]), **fields)
    return say.say("kennedy.omega_velocity", velocity=say.pair(float(p["vx"]), float(p["vy"])),
                   offset=say.pair(float(p["rx"]), float(p["ry"])), cross=words.n(p["cross"]),
                   distance=words.n(p["distance"]), **fields)


def scale_note(scale: PolygonScale, paper: tuple[float, float], say: Catalogue) -> str:
    """Why a polygon is drawn at a smaller scale than wanted (``present.scales``), in ``say``'s language."""
    return say.say("panel.reduced_note", symbol=scale.symbol, wanted=say.number(scale.wanted),
                   scale=say.number(scale.value), polygon=say.say(f"polygon.{scale.kind}"),
                   paper=f"{say.number(paper[0])} × {say.number(paper[1])} mm")
