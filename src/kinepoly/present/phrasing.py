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
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache

from kinepoly.engine.center_values import KennedyStep
from kinepoly.engine.center_velocity import CenterOmega
from kinepoly.engine.circle_diagram import center_label, pair_name
from kinepoly.engine.plan import NewtonGroup
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.geom.vec import Vec, norm, sub
from kinepoly.present.catalogue import Catalogue, load_catalogue
from kinepoly.solution import Solution

__all__ = [
    "Context",
    "Words",
    "center_omega_sentence",
    "english",
    "kennedy_sentence",
    "kennedy_words",
    "segment",
    "step_sentence",
    "step_words",
    "tip_name",
]

_TINY = 1e-12


@cache
def english() -> Catalogue:
    """The shipped English catalogue (loaded once): the words of ``solve --steps``, the JSON and the drawings."""
    return load_catalogue("en")


@dataclass(frozen=True)
class Context:
    """What a step's sentence needs besides the step: the solution it belongs to and the scales it is drawn at.

    ``scales`` are paper mm per unit of each polygon, keyed ``velocity`` and ``acceleration``
    (kv and ka; other keys are ignored): the sentences give every vector's length on the paper.
    """

    solution: Solution
    scales: Mapping[str, float]


def tip_name(label: str, polygon: str) -> str:
    """A point's tip in the polygon: ``B0`` -> ``b0``; in the acceleration polygon primed, ``b′0``."""
    point, at, link = label.partition("@")
    m = re.match(r"^(\D+)(\d*)$", point)
    base, digits = (m.group(1), m.group(2)) if m else (point, "")
    prime = "′" if polygon == "acceleration" else ""
    return f"{base.lower()}{prime}{digits}{at}{link}"


def segment(first: str, second: str) -> str:
    """The segment between two points of the mechanism: ``A@4`` and ``B0`` -> ``AB0``."""
    return first.partition("@")[0] + second.partition("@")[0]


def _ends(label: str) -> tuple[str, str]:
    """The point and the reference of a relative term: ``a^n_B@4/A`` -> (``B@4``, ``A``)."""
    point, _, reference = label.partition("_")[2].partition("/")
    return point, reference


class Words:
    """The words of one solution's steps in one language: symbols, units, poles, tips, scales on paper."""

    def __init__(self, context: Context, say: Catalogue) -> None:
        self.solution = context.solution
        self.say = say
        self.scales = context.scales
        self.unit = context.solution.scene.units.length
        self.ground = context.solution.mechanism.ground or ""

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
        return self.say.number(abs(magnitude) * self.scales[polygon])

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

    def sense_of(self, value: float) -> str:
        return self.sense("ccw" if value > 0.0 else "cw" if value < 0.0 else "zero")

    def n(self, value: str | float) -> str:
        return self.say.number(float(value))

    def angle_of(self, value: Vec) -> str:
        return self.say.angle(math.atan2(value[1], value[0]))

    def normal_fields(self, vector: DrawnVector) -> dict[str, str]:
        """ω, its name, the segment and its length of a normal term (``a^n_B/A = ω13² · |AB|``)."""
        point, reference = _ends(vector.label)
        size = norm(sub(vector.end, vector.start))
        mechanism = self.solution.mechanism
        omega = self.solution.velocity.omega if self.solution.velocity is not None else {}
        (p, _, p_on), (r, _, r_on) = (label.partition("@") for label in (point, reference))
        # the link turning: the one the term names (B@4), else one that carries both points, else (a
        # point that slides on a link, A@4 of a slot) one that carries the reference, else the point
        tiers = ([k for k in omega if k in (p_on, r_on)],
                 [k for k in omega if mechanism.has_point(k, p) and mechanism.has_point(k, r)],
                 [k for k in omega if mechanism.has_point(k, r)],
                 [k for k in omega if mechanism.has_point(k, p)])
        links = next((tier for tier in tiers if tier), None)
        if links is None:
            raise KeyError(f"{vector.label}: no link of known ω carries {point} or {reference}")
        length = norm(sub(self.solution.position(point), self.solution.position(reference)))
        link = min(links, key=lambda k: abs(omega[k] ** 2 * length - size))
        return {"omega_name": self.rate_name("velocity", self.ground, link), "omega": self.n(abs(omega[link])),
                "segment": segment(reference, point), "length": self.n(length)}


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
                "magnitude": self.w.n(norm(value)), "angle": self.w.angle_of(value),
                "paper": self.w.paper(self.polygon, norm(value)), **self.common()}

    def found_tip(self) -> str:
        """The result of a step that finds a tip: the absolute vector, its angle and length on paper."""
        step = self.step
        label = step.result.upper() if step.result else ""
        tips = self.w.tips(self.polygon)
        name = next((k for k in tips if k.lower() == step.result), label)
        value = tips.get(name, (step.value[0], step.value[1]) if len(step.value) == 2 else (0.0, 0.0))
        fields = self.tip_fields(name, value)
        if norm(value) == 0.0:
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
        text = self.say.say(key, link=str(p["link"]), rate_name=name, rate=self.w.n(p["rate"]),
                            sense=self.w.sense(p["sense"]), pole=self.w.pole(self.polygon))
        value = self.step.value[0] if self.step.value else 0.0
        return text, self.say.say("result.given", rate_name=name, value=self.w.n(value),
                                  unit=self.w.rate_unit(self.polygon))

    def _driven_slider(self) -> tuple[str, str]:
        p = self.p
        name = f"{'ṡ' if self.polygon == 'velocity' else 's̈'}{p['slider']}"
        amount = float(p["amount"])
        text = self.say.say("step.driven_slider", slider=str(p["slider"]),
                            term=f"{self.w.symbol(self.polygon)}_{p['point']}", rate_name=name,
                            amount=self.w.n(amount), paper=self.w.paper(self.polygon, amount),
                            tip=tip_name(str(p["point"]), self.polygon), **self.common())
        return text, self.found_tip()

    def _given_point(self) -> tuple[str, str]:
        p = self.p
        value = self.step.value
        text = self.say.say("step.given_point", term=f"{self.w.symbol(self.polygon)}_{p['point']}",
                            magnitude=self.w.n(p["magnitude"]), angle=self.w.angle_of((value[0], value[1])),
                            paper=self.w.paper(self.polygon, float(p["magnitude"])),
                            tip=tip_name(str(p["point"]), self.polygon), **self.common())
        return text, self.found_tip()

    def _relative(self) -> tuple[str, str]:
        p = self.p
        point, reference = str(p["point"]), str(p["reference"])
        fields = {"point": point, "reference": reference, "link": str(p["link"]),
                  "segment": segment(reference, point), "length": self.w.n(p["length"]),
                  "length_unit": self.w.unit, "sense": self.w.sense(p["sense"]), "rate": self.w.n(p["rate"]),
                  "from_tip": self.w.tip_or_pole(self.polygon, reference), "tip": tip_name(point, self.polygon),
                  **self.common()}
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
        key = "step.intersection_velocity" if self.polygon == "velocity" else "step.intersection_acceleration"
        text = self.say.say(key, first_line=self._line(step.directions[0]), second_line=self._line(step.directions[1]),
                            tip=tip_name(point, self.polygon), term=f"{self.w.symbol(self.polygon)}_{point}",
                            **self.common())
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
        text = self.say.say("step.read", rate_name=name, term=str(p["term"]), segment=segment(first, second),
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
        text = self.say.say("step.coriolis", term=term, guide=str(p["guide"]),
                            omega_name=self.w.rate_name("velocity", str(p["ground"]), str(p["guide"])),
                            omega=self.w.n(p["omega"]), relative=str(p["relative"]), speed=self.w.n(p["speed"]),
                            magnitude=self.w.n(p["magnitude"]), paper=self.w.paper(self.polygon, float(p["magnitude"])),
                            sense=self.w.sense(p["sense"]), from_tip=self.w.tip_or_pole(self.polygon, str(p["start"])),
                            **self.common())
        return text, self._vector_result(term, sub(vector.end, vector.start))

    def _vector_result(self, term: str, value: Vec) -> str:
        if norm(value) == 0.0:
            return self.say.say("result.vector_zero", term=term)
        return self.say.say("result.vector", term=term, magnitude=self.w.n(norm(value)), angle=self.w.angle_of(value),
                            unit=self.w.unit_of(self.polygon))

    def _normals(self) -> tuple[str, str]:
        items = []
        for v in self.step.vectors:
            point, reference = _ends(v.label)
            size = norm(sub(v.end, v.start))
            items.append(self.say.say("step.normal_item", term=v.label, magnitude=self.w.n(size),
                                      unit=self.w.unit_of(self.polygon), point=point.partition("@")[0],
                                      reference=reference.partition("@")[0], from_tip=self._normal_start(v),
                                      paper=self.w.paper(self.polygon, size), **self.w.normal_fields(v)))
        text = self.say.say("step.normals", items="; ".join(items))
        return text, self.say.say("result.laid", terms=", ".join(v.label for v in self.step.vectors))

    def _normal_start(self, vector: DrawnVector) -> str:
        """The tip a normal term is laid from: its reference point's, else the tip that is where it starts."""
        tips = self.w.tips(self.polygon)
        _point, reference = _ends(vector.label)
        candidates = [reference, *tips] if reference in tips else list(tips)
        for label in candidates:
            if norm(sub(tips[label], vector.start)) <= 1e-12 * max(norm(tips[label]), 1.0):
                return self.w.tip_or_pole(self.polygon, label)
        return self.w.tip_or_pole(self.polygon, reference)

    def _given_normal(self) -> tuple[str, str]:
        p = self.p
        point, reference = str(p["point"]), str(p["reference"])
        normal, tangential = self.step.vectors
        fields = self.w.normal_fields(normal)
        text = self.say.say("step.given_normal", term=normal.label, tangential=tangential.label,
                            magnitude=self.w.n(p["magnitude"]), point=point, reference=reference,
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
        items = []
        for label in labels:
            fields = self.tip_fields(label, tips.get(label, (0.0, 0.0)))
            if label not in tips or norm(tips[label]) == 0.0:
                items.append(self.say.say("result.tip_item_at_pole", tip=fields["tip"], term=fields["term"],
                                          pole=fields["pole"]))
            else:
                items.append(self.say.say("result.tip_item", **fields))
        rates = self.rates()
        for link in links:
            if link in rates:
                items.append(self.say.say("result.rate_item", rate_name=self.w.rate_name(self.polygon, self.w.ground, link),
                                          value=self.w.n(rates[link]), unit=self.w.rate_unit(self.polygon),
                                          sense=self.w.sense_of(rates[link])))
        return text, self.say.say("result.tips", tips="; ".join(items))


def step_words(step: Step, say: Catalogue, context: Context) -> tuple[str, str]:
    """A construction step in words: (what to do and why, what it yields), in ``say``'s language."""
    return _Phrase(Words(context, say), step).explain()


def step_sentence(step: Step, say: Catalogue, context: Context) -> str:
    """A construction step as one paragraph: what to do and why, then what it yields."""
    return " ".join(step_words(step, say, context))


def _links(triangle: str) -> str:
    """``"123"`` or ``"1-2-14"`` (a triangle of the circle diagram) as ``1, 2, 3``."""
    return ", ".join(triangle.split("-") if "-" in triangle else list(triangle))


def kennedy_words(step: KennedyStep, say: Catalogue, context: Context) -> tuple[str, str]:
    """A Kennedy step in words: (the two lines the center lies on, where they cross)."""
    centers = context.solution.centers
    assert centers is not None, "a Kennedy step belongs to a solution with instant centers"
    center = centers.centers[step.center]
    label = center_label(step.center)
    first, second = step.lines
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
