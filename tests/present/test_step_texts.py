"""Issue 13, item 5: step texts a student can redo by hand, in every shipped language.

Angles in (-180, 180]; a point on the line of two points of its link divided as a length on the
paper, with no ratio of the wrong sign and no offset of nothing; every normal term with its
numbers and its centre; one label per relative term in all the steps; no sense given to a zero.
Each expectation is derived here from the solution (tips, positions, scales), not from the text.
"""

from __future__ import annotations

import math
import re
from functools import cache

import msgspec
import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.engine.steps import Step
from kinepoly.geom.vec import norm, sub
from kinepoly.present.catalogue import Catalogue, load_catalogue
from kinepoly.present.phrasing import Context, step_sentence, step_words
from kinepoly.present.report import steps_text
from kinepoly.present.scales import polygon_scales
from kinepoly.solution import Solution

LANGUAGES = ("en", "tr", "ro")
NAMES = sorted(p.stem for p in EXAMPLES.glob("*.toml"))
_DEGREES = re.compile(r"([−-]?\d+(?:[.,]\d+)?)°")
_TERM = re.compile(r"a\^([nt])_([^\s/|,;()=@]+)(@\w+)?/([^\s|,;()=.]+)")


@cache
def _solved(name: str) -> Solution:
    return kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))


def _context(solution: Solution) -> Context:
    return Context(solution, polygon_scales(solution))


def _value(text: str) -> float:
    return float(text.replace("−", "-").replace(",", "."))


def _sentences(name: str, say: Catalogue) -> list[tuple[Step, str]]:
    solution = _solved(name)
    return [(step, step_sentence(step, say, _context(solution))) for step in solution.steps]


@pytest.mark.parametrize("lang", LANGUAGES)
@pytest.mark.parametrize("name", NAMES)
def test_every_angle_is_printed_in_minus_180_to_180(name: str, lang: str) -> None:
    for _step, sentence in _sentences(name, load_catalogue(lang)):
        for number in _DEGREES.findall(sentence):
            assert -180.0 < _value(number) <= 180.0, sentence


@pytest.mark.parametrize("lang", LANGUAGES)
def test_an_image_angle_beyond_a_turn_is_its_equivalent(lang: str) -> None:
    solution, say = _solved("four-bar"), load_catalogue(lang)
    image = next(s for s in solution.steps if s.topic == "image")
    turned = msgspec.structs.replace(image, params=tuple((k, -342.1 if k == "angle_first" else v)
                                                         for k, v in image.params))
    sentence = step_sentence(turned, say, _context(solution))
    assert f"{say.number(17.9)}°" in sentence and "342" not in sentence


def _collinear_steps(solution: Solution) -> list[Step]:
    return [s for s in solution.steps if s.topic == "proportional"]


@pytest.mark.parametrize("lang", LANGUAGES)
def test_a_collinear_image_point_is_measured_off_on_its_line(lang: str) -> None:
    """The shaper's C on the line B0A@4: its tip at |oc| = |C B0| / |A B0| x |o a@4| on the paper, beyond a@4."""
    solution, say = _solved("shaper"), load_catalogue(lang)
    steps = _collinear_steps(solution)
    assert steps
    scales = polygon_scales(solution)
    for step in steps:
        sentence = step_sentence(step, say, _context(solution))
        polygon = solution.velocity if step.polygon == "velocity" else solution.acceleration
        assert polygon is not None
        first, second, point = (str(step.param(k)) for k in ("first", "second", "point"))
        k = scales[step.polygon]
        side = norm(sub(polygon.tips[second], polygon.tips[first])) * k
        distance = norm(sub(polygon.tips[point], polygon.tips[first])) * k
        ratio = norm(sub(solution.position(point), solution.position(first))) / norm(
            sub(solution.position(second), solution.position(first)))
        assert say.number(side) in sentence and say.number(distance) in sentence and say.number(ratio) in sentence
        assert say.say("step.collinear_beyond_second", first=first.partition("@")[0],
                       second=second.partition("@")[0]) in sentence
        what, _found = step_words(step, say, _context(solution))
        assert "−" not in what  # no ratio of the wrong sign: the side is said in words


@pytest.mark.parametrize("lang", LANGUAGES)
@pytest.mark.parametrize("ratio, where", [(-0.8, "collinear_beyond_first"), (0.4, "collinear_between"),
                                          (1.5, "collinear_beyond_second")])
def test_each_side_of_a_collinear_point_has_its_words(lang: str, ratio: float, where: str) -> None:
    solution, say = _solved("shaper"), load_catalogue(lang)
    step = _collinear_steps(solution)[0]
    moved = msgspec.structs.replace(step, params=tuple((k, ratio if k == "ratio" else 1e-13 if k == "height" else v)
                                                   for k, v in step.params))
    sentence = step_sentence(moved, say, _context(solution))
    first, second = (str(step.param(k)).partition("@")[0] for k in ("first", "second"))
    assert say.say(f"step.{where}", first=first, second=second) in sentence
    assert say.number(abs(ratio)) in sentence and say.number(ratio) not in sentence.replace(say.number(abs(ratio)), "")


@pytest.mark.parametrize("lang", LANGUAGES)
@pytest.mark.parametrize("name", NAMES)
def test_every_normal_term_has_its_numbers_and_its_centre(name: str, lang: str) -> None:
    """a^n_B/A = ω13² · |AB| = ω² × |AB| = size, and the centre A it points to, for every normal term laid."""
    solution, say = _solved(name), load_catalogue(lang)
    for step, sentence in _sentences(name, say):
        if step.topic not in ("normals", "given-normal"):
            continue
        for vector in step.vectors[:1] if step.topic == "given-normal" else step.vectors:
            point, reference = vector.label.partition("_")[2].split("/")
            length = norm(sub(solution.position(point), solution.position(reference)))
            size = norm(sub(vector.end, vector.start))
            assert f"× {say.number(length)} = {say.number(size)}" in sentence, (vector.label, sentence)
            assert reference.partition("@")[0] in sentence
        for omega, length, size in re.findall(r"= (\S+)² × (\S+) = (\S+) mm/s²", sentence):
            assert math.isclose(_value(omega) ** 2 * _value(length), _value(size), rel_tol=1e-3, abs_tol=1e-9)


@pytest.mark.parametrize("name", NAMES)
def test_a_relative_term_has_one_label_in_all_the_steps(name: str) -> None:
    """a^n_A/B0 beside a^t_A@4/B0 is one point written two ways: the text writes it one way throughout."""
    solution = _solved(name)
    text = steps_text(solution)
    forms: dict[tuple[str, str], set[str]] = {}
    for _kind, point, at, reference in _TERM.findall(text):
        forms.setdefault((point, reference), set()).add(at)
    assert all(len(ats) == 1 for ats in forms.values()), forms


@pytest.mark.parametrize("lang", LANGUAGES)
@pytest.mark.parametrize("name", NAMES)
def test_a_zero_is_given_no_sense(name: str, lang: str) -> None:
    say = load_catalogue(lang)
    zero = say.say("sense.zero")
    for _step, sentence in _sentences(name, say):
        assert not re.search(rf"(, |\(){re.escape(zero)}\b", sentence), sentence


def test_the_examples_have_zero_rates_to_say() -> None:
    """The zero wording is exercised: some example has alpha12 = 0 and a link at rest in a polygon."""
    rates = [s for name in NAMES for s in _solved(name).steps if s.topic in ("input-rate", "relative", "read")]
    assert any(float(s.param("rate")) == 0.0 for s in rates)
