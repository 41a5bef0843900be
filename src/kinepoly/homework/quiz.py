"""A variant as a quiz question: each asked quantity a number with its tolerance, and the numbers of the
typical mistakes, each with the words that name it.

The mistakes are those ``kinepoly check`` recognises, computed the way it computes them
(``homework.checking.make_checker`` and ``homework.diagnose.candidates``): the problem constructed
again with the Coriolis term left out or reversed, the normal terms reversed, the input angle's
degrees used as radians; a polygon length not divided by kv or ka; the sense reversed; the right
value of another point or link. A vector is asked as its magnitude and its direction (degrees from
+x, counter-clockwise, in (-180, 180]), as it is read off a polygon.

A mistake whose number lies within the tolerance of the right one, or of a mistake kept before it
(in the order ``check`` breaks ties), is left out: the platform could not tell them apart. Each
one left out is kept in ``Quantity.omitted`` to be said; a mistake that does not change the number
at all (the Coriolis term and a velocity) is no mistake of that number and is not listed.

The tolerance is a percentage of the value (``2%``; a value is judged against at least 1 % of the
largest value of its kind, as ``check`` does), or the length a hand construction holds on the paper
(``0.5mm``): that length over kv for a velocity, over ka for an acceleration, over the space scale
for a slider's position, over kv (ka) times the link's longest dimension for omega (alpha), and the
angle it subtends at the vector's tip for a direction.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from typing import Literal

from msgspec import Struct

from kinepoly.errors import SceneError
from kinepoly.geom.tolerances import ANGLE_SAME_DEG, SAME_REL
from kinepoly.homework.answers import AnswerKey, Direction, Value
from kinepoly.homework.checking import make_checker
from kinepoly.homework.diagnose import Candidate, candidates
from kinepoly.homework.reference import Reference
from kinepoly.homework.variants import Variant
from kinepoly.present.catalogue import Catalogue
from kinepoly.present.scales import A4
from kinepoly.scene.spec import Scene
from kinepoly.solution import solve

__all__ = ["DEFAULT_ANGLE_DEG", "Omitted", "Quantity", "Question", "Quiz", "QuizTolerance", "Wrong", "make_quiz",
           "parse_tolerance", "quantities"]

DEFAULT_ANGLE_DEG = 2.0
"""A direction's tolerance with a percentage tolerance, in degrees (``check``'s default)."""

Part = Literal["value", "magnitude", "direction"]

_TOLERANCE = re.compile(r"^\s*(?P<number>\d+(?:\.\d*)?|\.\d+)\s*(?P<unit>%|mm)\s*$")
_SAME = SAME_REL
"""A mistake's number this close (relative) to the right one is the right one: that mistake does not touch it."""
_SLIDER_NAMES = {"s": "s", "s_dot": "ds/dt", "s_ddot": "d²s/dt²"}


class QuizTolerance(Struct, frozen=True):
    """``relative`` (a fraction: 0.02 for ``2%``) or ``paper_mm`` (a length on the paper), one of them."""

    relative: float | None = 0.02
    paper_mm: float | None = None

    @property
    def text(self) -> str:
        return (f"{self.paper_mm:g} mm on the paper" if self.paper_mm is not None
                else f"{100 * (self.relative or 0):g} %")


def parse_tolerance(text: str) -> QuizTolerance:
    """``--tolerance``: ``2%`` or ``0.5mm``; SceneError (exit 2) saying what is accepted."""
    match = _TOLERANCE.match(text)
    expected = ("expected a percentage of the value like 2% (from above 0 to 50), or the length a hand "
                "construction holds on the paper like 0.5mm (from above 0 to 10)")
    if match is None:
        raise SceneError([f"--tolerance: {text!r} is not a tolerance; {expected}"])
    number = float(match.group("number"))
    if match.group("unit") == "%":
        if not 0.0 < number <= 50.0:
            raise SceneError([f"--tolerance: {text!r}; {expected}"])
        return QuizTolerance(relative=number / 100.0)
    if not 0.0 < number <= 10.0:
        raise SceneError([f"--tolerance: {text!r}; {expected}"])
    return QuizTolerance(relative=None, paper_mm=number)


class Wrong(Struct, frozen=True):
    """A typical mistake's number for a quantity, its code (as ``check`` names it) and the words naming it."""

    code: str
    words: str
    value: float


class Omitted(Struct, frozen=True):
    """A mistake left out: its number coincides, within the tolerance, with ``with_`` (``right`` or a code)."""

    code: str
    value: float
    with_: str


class Quantity(Struct, frozen=True):
    """One number asked: ``key`` (the answers file's, ``v_A``), ``part`` of it, the words that ask for it (the
    course's notation, ``handout.notation``), the right number, the tolerance (in its unit), the mistakes."""

    key: str
    part: Part
    label: str
    value: float
    tolerance: float
    wrong: tuple[Wrong, ...]
    omitted: tuple[Omitted, ...]
    angle: bool = False
    """A direction in degrees: numbers are compared modulo 360."""


class Question(Struct, frozen=True):
    """One variant as a question: ``name`` the variant's (``slotted-lever-01``), ``title`` its name in the question
    bank (variant and seed), the problem page's text (HTML) and figure (PNG), the numbers asked."""

    name: str
    title: str
    statement: str
    figure: bytes
    quantities: tuple[Quantity, ...]

    @property
    def figure_name(self) -> str:
        return f"{self.name}.png"


class Quiz(Struct, frozen=True):
    """The questions of a scene's variants: ``category`` the scene's name (one question bank category per
    scene), ``title`` what the platform calls the quiz, ``language`` the catalogue's code."""

    category: str
    title: str
    language: str
    questions: tuple[Question, ...]


# --------------------------------------------------------------------------------------------
# Names and words


def _name(scene: Scene, key: AnswerKey) -> str:
    ground = scene.ground or ""
    if key.kind in ("omega", "alpha"):
        return f"{'ω' if key.kind == 'omega' else 'α'}{ground}{key.target}"
    if key.kind in ("velocity", "acceleration"):
        return f"{key.kind[0]}_{key.target}"
    return f"{_SLIDER_NAMES.get(key.kind, key.kind)} ({key.target})"


def _label(scene: Scene, key: AnswerKey, part: Part, say: Catalogue) -> str:
    unit = scene.units.length
    name = _name(scene, key)
    if key.kind in ("omega", "alpha"):
        return say.say(f"quiz.{key.kind}", name=name)
    if part == "magnitude":
        return say.say("quiz.magnitude", name=name, unit=f"{unit}/s" if key.kind == "velocity" else f"{unit}/s²")
    if part == "direction":
        return say.say("quiz.direction", name=name)
    units = {"s": unit, "s_dot": f"{unit}/s", "s_ddot": f"{unit}/s²"}
    return say.say("quiz.slider", name=_SLIDER_NAMES[key.kind], slider=key.target, unit=units[key.kind])


def _other(reference: Reference, key: AnswerKey, value: Value) -> str:
    """The name of the other point or link whose right value ``value`` is (``other-point``, ``other-link``)."""
    for other, found in reference.values.items():
        if other.kind == key.kind and other.question != key.question and found == value:
            return _name(reference.scene, other)
    return "?"  # pragma: no cover - candidates() takes these values from reference.values


def _words(reference: Reference, key: AnswerKey, candidate: Candidate, say: Catalogue) -> str:
    """The catalogue's words for the mistake; check's own (English) words for a mistake the catalogue does not name."""
    code = candidate.code
    if f"quiz.{code.replace('-', '_').replace('/', '_')}" not in say.messages:
        return candidate.text
    params = {}
    if code == "kv-not-divided":
        params["scale"] = say.number(reference.kv or 0.0)
    elif code == "ka-not-divided":
        params["scale"] = say.number(reference.ka or 0.0)
    elif code in ("other-point", "other-link"):
        params["other"] = _other(reference, key, candidate.answer)
    return say.say(f"quiz.{code.replace('-', '_').replace('/', '_')}", **params)


# --------------------------------------------------------------------------------------------
# Numbers and tolerances


def _parts(value: Value) -> dict[Part, float] | None:
    if isinstance(value, Direction):
        return None
    if isinstance(value, tuple):
        magnitude = math.hypot(*value)
        parts: dict[Part, float] = {"magnitude": magnitude}
        if magnitude > 0.0:
            parts["direction"] = _degrees(math.atan2(value[1], value[0]))
        return parts
    return {"value": value}


def _degrees(radians: float) -> float:
    """An angle in degrees in (-180, 180]."""
    degrees = math.degrees(math.remainder(radians, 2.0 * math.pi))
    return 180.0 if degrees <= -180.0 + ANGLE_SAME_DEG else degrees + 0.0


def _apart(first: float, second: float, angle: bool) -> float:
    return abs(math.remainder(first - second, 360.0)) if angle else abs(first - second)


def _longest(scene: Scene, link: str) -> float:
    """The longest distance between two points of ``link`` (the mechanism's largest when it has one point)."""
    points = [p.local for p in scene.link(link).points] if link in {k.name for k in scene.links} else []
    longest = max((math.dist(a, b) for a in points for b in points), default=0.0)
    if longest > 0.0:
        return longest
    return max((math.dist(a.local, b.local) for k in scene.links for a in k.points for b in k.points), default=1.0)


def _drawn_tolerance(reference: Reference, key: AnswerKey, part: Part, value: float, paper_mm: float,
                     scales: Mapping[str, float]) -> float:
    kind = key.kind
    kv, ka = scales.get("velocity", reference.kv or 1.0), scales.get("acceleration", reference.ka or 1.0)
    scale = kv if kind in ("velocity", "s_dot", "omega") else ka if kind in ("acceleration", "s_ddot", "alpha") \
        else scales.get("mechanism", 1.0)
    if part == "direction":
        return math.degrees(math.atan2(paper_mm, abs(value) * scale))  # ``value``: the vector's magnitude here
    if kind in ("omega", "alpha"):
        return paper_mm / (scale * _longest(reference.scene, key.target))
    return paper_mm / scale


def _tolerance(reference: Reference, key: AnswerKey, part: Part, parts: dict[Part, float], tolerance: QuizTolerance,
               scales: Mapping[str, float]) -> float:
    if tolerance.paper_mm is not None:
        at = parts["magnitude"] if part == "direction" else parts[part]
        return _drawn_tolerance(reference, key, part, at, tolerance.paper_mm, scales)
    relative = tolerance.relative or 0.0
    if part == "direction":  # within DEFAULT_ANGLE_DEG, or the angle the magnitude's tolerance subtends at the tip
        size = relative * max(parts["magnitude"], reference.floor(key))
        return max(DEFAULT_ANGLE_DEG, math.degrees(math.asin(min(1.0, size / parts["magnitude"]))))
    return relative * max(abs(parts[part]), reference.floor(key))


def _quantity(reference: Reference, key: AnswerKey, part: Part, parts: dict[Part, float], tried: list[Candidate],
              tolerance: QuizTolerance, scales: Mapping[str, float], say: Catalogue) -> Quantity:
    right = parts[part]
    allowed = _tolerance(reference, key, part, parts, tolerance, scales)
    angle = part == "direction"
    wrong: list[Wrong] = []
    omitted: list[Omitted] = []
    for candidate in tried:
        theirs = _parts(candidate.answer)
        if theirs is None or part not in theirs:
            continue
        value = theirs[part]
        if _apart(value, right, angle) <= _SAME * max(abs(right), 1.0):
            continue  # the mistake does not change this number (the Coriolis term and a velocity, say)
        if _apart(value, right, angle) <= allowed:
            omitted.append(Omitted(candidate.code, value, "right"))
            continue
        before = next((w for w in wrong if _apart(value, w.value, angle) <= allowed), None)
        if before is not None:
            omitted.append(Omitted(candidate.code, value, before.code))
            continue
        wrong.append(Wrong(candidate.code, _words(reference, key, candidate, say), value))
    return Quantity(key.text, part, _label(reference.scene, key, part, say), right, allowed, tuple(wrong),
                    tuple(omitted), angle)


def quantities(scene: Scene, asked: tuple[tuple[AnswerKey, Value], ...], tolerance: QuizTolerance,
               scales: Mapping[str, float], say: Catalogue, scene_text: str | None = None) -> tuple[Quantity, ...]:
    """The numbers of ``asked`` (a variant's key: ``Variant.answers``), a vector as its magnitude and direction,
    each with the typical mistakes' numbers. ``scales`` are the ones the problem is drawn at (kv, ka, the space
    scale). Instant centers are not asked (``check`` knows no typical mistake of them but another center)."""
    checker = make_checker(scene, scene_text=scene_text)
    reference = checker.reference
    out: list[Quantity] = []
    for key, value in asked:
        parts = _parts(value)
        if key.kind in ("center", "theta") or parts is None:
            continue
        tried = candidates(reference, checker.recomputed, key)
        out += [_quantity(reference, key, part, parts, tried, tolerance, scales, say) for part in parts]
    return tuple(out)


def make_quiz(variants: Sequence[Variant], stem: str, seed: int, tolerance: QuizTolerance, say: Catalogue,
              paper: tuple[float, float] = A4) -> Quiz:
    """A question per variant: its problem page (text and figure, ``handout.statement``) and its numbers."""
    from kinepoly.handout.statement import problem_statement

    questions = []
    for index, variant in enumerate(variants, 1):
        statement = problem_statement(solve(variant.scene), say, paper)
        asked = quantities(variant.scene, variant.answers, tolerance, statement.scales, say, variant.scene_text)
        if not asked:
            raise SceneError(f"{variant.scene.source}: find: the quiz has no number to ask (instant centers are not "
                             "asked); expected a [find] with velocities, accelerations, omega, alpha or sliders")
        title = f"{variant.name}: variant {index} of {len(variants)}, seed {seed}"
        questions.append(Question(variant.name, title, statement.html, statement.png, asked))
    return Quiz(stem, f"{stem}: {len(variants)} variants, seed {seed}", say.code, tuple(questions))
