"""Why an answer is wrong: the problem recomputed with each common mistake, matched to the answer.

The mistakes tried, each with a stable code:

``sign-reversed``          the sense (cw/ccw) of a rate or the direction of a vector reversed
``coriolis-left-out``      the acceleration polygon drawn without the Coriolis term
``coriolis-reversed``      ... with the Coriolis term the wrong way round
``normal-reversed``        the normal terms omega^2 r drawn away from the center
``kv-not-divided``         a length read off the velocity polygon (mm) not divided by kv
``ka-not-divided``         ... off the acceleration polygon, not divided by ka
``degrees-for-radians``    the input angle's degrees used as radians (a calculator in radian
                           mode), an input omega in deg/s used as rad/s, or a rate or angle
                           written in degrees where radians are meant (and the other way round)
``rpm-for-rad/s``          an input omega in rpm used as rad/s
``other-point``            the right value of another point
``other-link``             the right value of another link (or slider, or instant center)

The construction mistakes are recomputed honestly: the acceleration polygon is constructed again
with the term left out, reversed or turned (``engine.acceleration.Rules``); the input mistakes
solve the scene again at the mistaken input; only the reading mistakes (kv, ka, a unit) and the
sign act on the right answer itself. An answer matches a mistake when it is within the answers
file's tolerance of the recomputed value; the closest match wins (of matches equally close to
roundoff, the first tried), and a mistake that changes nothing visible is never offered.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Generic, TypeVar

from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.acceleration import Rules
from kinepoly.errors import KinepolyError
from kinepoly.geom.tolerances import SAME_REL
from kinepoly.homework.answers import AnswerKey, Direction, Tolerance, Value
from kinepoly.homework.compare import compare
from kinepoly.homework.reference import (
    Reference,
    Values,
    asked_keys,
    fixed_angles,
    solve_for,
    student_solution,
    value_in,
)
from kinepoly.scene.link_point import LinkPoint
from kinepoly.scene.spec import LinkInput, Scene

__all__ = ["Candidate", "Diagnosis", "Mistake", "Recomputed", "candidates", "diagnose", "recompute"]

_CONSTRUCTIONS = (
    ("coriolis-left-out", "the Coriolis term 2 omega x v_rel left out of the acceleration polygon",
     Rules(coriolis=0.0)),
    ("coriolis-reversed", "the Coriolis term 2 omega x v_rel laid the wrong way round",
     Rules(coriolis=-1.0)),
    ("normal-reversed", "the normal terms omega^2 r drawn away from the center instead of toward it",
     Rules(normal=1.0)),
)
_TIE = SAME_REL  # matches this much closer (relative) than another are a tie: the earlier candidate wins
_VELOCITY_LEVEL = ("velocity", "s_dot", "omega")
_ACCELERATION_LEVEL = ("acceleration", "s_ddot", "alpha")
_NOUNS = {"omega": "angular velocity", "alpha": "angular acceleration", "theta": "angle",
          "velocity": "velocity", "acceleration": "acceleration", "s": "slider position s",
          "s_dot": "sliding velocity s_dot", "s_ddot": "sliding acceleration s_ddot", "center": "instant center"}


_Answer = TypeVar("_Answer")


class Mistake(Struct, Generic[_Answer], frozen=True):
    """What one mistake (its code and its text) makes of the answers: of the whole problem (``Recomputed``,
    its answers by key) or of one key (``Candidate``)."""

    code: str
    text: str
    answer: _Answer


Recomputed = Mistake[Values]
Candidate = Mistake[Value]


class Diagnosis(Struct, frozen=True):
    """The likely mistake behind a wrong answer (``value``: the answer that mistake gives).

    ``code`` is ``unrecognised`` (and ``value`` None) when no mistake reproduces the answer, and
    ``not-answered`` for a question of the scene's [find] that the file does not answer.
    """

    code: str
    text: str
    value: Value | None = None
    alternatives: tuple[str, ...] = ()


# --------------------------------------------------------------------------------------------
# The problem recomputed with each mistake, once per scene


def _construction_mistakes(reference: Reference) -> list[Recomputed]:
    if not any(key.kind == "alpha" for key in reference.values):
        return []  # no accelerations in this problem
    return [Recomputed(code, text, student_solution(reference.solution, rules)) for code, text, rules in _CONSTRUCTIONS]


def _resolved(scene: Scene, reference: Reference, code: str, text: str, changed: LinkInput) -> list[Recomputed]:
    """The scene solved again at a mistaken input (nothing when it does not assemble there)."""
    keys = asked_keys(reference.values)
    try:
        values = solve_for(replace(scene, input=changed), keys, everything=False)
    except KinepolyError:
        return []
    return [Recomputed(code, text, values)]


def _input_mistakes(reference: Reference, written: Mapping[str, object] | None) -> list[Recomputed]:
    scene = reference.scene
    inp = scene.input
    if not isinstance(inp, LinkInput):
        return []
    out: list[Recomputed] = []
    if scene.units.angle == "deg":
        degrees = math.degrees(inp.angle_rad)
        out += _resolved(scene, reference, "degrees-for-radians",
                         f"the input angle {degrees:g} deg used as {degrees:g} rad (a calculator in radian mode)",
                         replace(inp, angle_rad=degrees))
    else:
        out += _resolved(scene, reference, "degrees-for-radians",
                         f"the input angle {inp.angle_rad:g} rad used as {inp.angle_rad:g} deg",
                         replace(inp, angle_rad=math.radians(inp.angle_rad)))
    for name, unit in (("omega", "deg/s"), ("omega", "rpm"), ("alpha", "deg/s^2")):
        number = _number_in(written, name, unit)
        if number is not None:
            mistake = "degrees-for-radians" if unit.startswith("deg") else "rpm-for-rad/s"
            si = "rad/s" if name == "omega" else "rad/s^2"
            changed = replace(inp, omega=number) if name == "omega" else replace(
                inp, alpha=number)
            out += _resolved(scene, reference, mistake, f"the input {name} {number:g} {unit} used as {number:g} {si}",
                             changed)
    return out


def _number_in(written: Mapping[str, object] | None, name: str, unit: str) -> float | None:
    """The number of ``[input] name = "NUMBER UNIT"`` when it is written with ``unit`` (``deg/s`` covers ^2)."""
    text = (written or {}).get(name)
    if not isinstance(text, str):
        return None
    parts = text.split()
    if len(parts) != 2 or not parts[1].startswith(unit):
        return None
    try:
        return float(parts[0])
    except ValueError:
        return None


def recompute(reference: Reference, written_input: Mapping[str, object] | None = None) -> tuple[Recomputed, ...]:
    """Every whole-problem mistake, solved: the construction ones and the input ones.

    ``written_input`` is the scene's ``[input]`` table as written (for omega given as "300 rpm").
    """
    return (*_construction_mistakes(reference), *_input_mistakes(reference, written_input))


# --------------------------------------------------------------------------------------------
# What each mistake makes of one answer


def _negated(value: Value) -> Value | None:
    if isinstance(value, tuple):
        return (-value[0], -value[1])
    if isinstance(value, Direction):
        return None
    return -value


def _scaled(value: Value, factor: float) -> Value:
    if isinstance(value, tuple):
        return (value[0] * factor, value[1] * factor)
    assert isinstance(value, float)
    return value * factor


def _owner(scene: Scene, label: str) -> str:
    named = LinkPoint.parse(label)
    return named.link or next(link.name for link in scene.links if named.point in link.point_names)


def _reading_mistakes(reference: Reference, key: AnswerKey, expected: Value) -> list[Candidate]:
    out: list[Candidate] = []
    kind, noun = key.kind, _NOUNS[key.kind]
    negated = _negated(expected)
    if negated is not None and kind != "center":
        what = ("the sense reversed (cw for ccw)" if kind in ("omega", "alpha") else
                "the direction reversed (the polygon's vector read from its tip to its tail)" if key.is_vector
                else "the sign reversed")
        out.append(Candidate("sign-reversed", what, negated))
    unit = reference.scene.units.length
    if kind in _VELOCITY_LEVEL and reference.kv is not None:
        out.append(Candidate("kv-not-divided", f"the {noun} read off the velocity polygon in mm and not divided by "
                                               f"kv = {reference.kv:g} mm per {unit}/s",
                             _scaled(expected, reference.kv)))
    if kind in _ACCELERATION_LEVEL and reference.ka is not None:
        out.append(Candidate("ka-not-divided", f"the {noun} read off the acceleration polygon in mm and not divided "
                                               f"by ka = {reference.ka:g} mm per {unit}/s^2",
                             _scaled(expected, reference.ka)))
    if kind in ("omega", "alpha"):
        per = "s" if kind == "omega" else "s^2"
        out.append(Candidate("degrees-for-radians", f"the {noun} written in deg/{per} instead of rad/{per}",
                             _scaled(expected, 180.0 / math.pi)))
    if kind == "theta":
        assert isinstance(expected, float)
        if reference.scene.units.angle == "deg":
            out.append(Candidate("degrees-for-radians", "the angle written in radians where degrees are asked",
                                 math.radians(expected)))
        else:
            out.append(Candidate("degrees-for-radians", "the angle written in degrees where radians are asked",
                                 math.degrees(expected)))
    return out


def _others(reference: Reference, key: AnswerKey) -> list[Candidate]:
    """The right values of every other point (link, slider, center) for the same question."""
    scene = reference.scene
    kind, noun = key.kind, _NOUNS[key.kind]
    fixed = set(fixed_angles(scene))
    same = [other for other in reference.values if other.kind == kind]
    if kind in ("velocity", "acceleration"):
        same = [other for other in same if _owner(scene, other.target) not in (scene.ground, *fixed)]
        code, name = "other-point", "point"
    elif kind in ("omega", "alpha", "theta"):
        same = [other for other in same if other.target not in fixed]
        code, name = "other-link", "link"
    elif kind == "center":
        code, name = "other-link", "instant center"
    else:
        code, name = "other-link", "slider"
    out = []
    for other in same:
        if other.question != key.question:
            if kind == "center":
                text = f"the right value of another instant center: {other.text}, of links " + " and ".join(
                    sorted(other.question[1]))
            else:
                text = f"the right value of another {name}: {other.text}, the {noun} of {name} {other.target}"
            out.append(Candidate(code, text, reference.values[other]))
    return out


def candidates(reference: Reference, recomputed: tuple[Recomputed, ...], key: AnswerKey) -> list[Candidate]:
    """What the answer to ``key`` would be with each mistake, in the order ties are broken."""
    expected = reference.expected(key)
    if expected is None:
        return []
    out = _reading_mistakes(reference, key, expected)
    for mistake in recomputed:
        value = value_in(mistake.answer, key)
        if value is not None:
            out.append(Candidate(mistake.code, mistake.text, value))
    return out + _others(reference, key)


def diagnose(reference: Reference, recomputed: tuple[Recomputed, ...], key: AnswerKey, given: Value,
             tolerance: Tolerance) -> Diagnosis:
    """The mistake whose recomputed answer is nearest ``given`` (within the tolerance), or ``unrecognised``."""
    expected = reference.expected(key)
    floor = reference.floor(key)
    tried: list[str] = []
    matches: list[tuple[float, int, Candidate]] = []
    for candidate in candidates(reference, recomputed, key):
        if expected is not None and compare(key.kind, expected, candidate.answer, tolerance, floor).is_correct:
            continue  # this mistake changes nothing visible here
        tried.append(candidate.code)
        match = compare(key.kind, candidate.answer, given, tolerance, floor)
        if match.is_correct:
            matches.append((match.closeness, len(matches), candidate))
    if not matches:
        names = ", ".join(dict.fromkeys(tried)) or "none applies"
        return Diagnosis("unrecognised", f"no common mistake gives this answer (tried: {names})")
    least = min(closeness for closeness, _, _ in matches)
    matches.sort(key=lambda item: (0.0 if item[0] <= least * (1.0 + _TIE) else item[0], item[1]))
    best = matches[0][2]
    others = tuple(dict.fromkeys(c.code for _, _, c in matches[1:] if c.code != best.code))
    return Diagnosis(best.code, best.text, best.answer, others)
