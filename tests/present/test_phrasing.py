"""One phrasing of the steps (``present.phrasing``): every step of every example in every language,
with its numbers, through the catalogue; ``solve --steps``, the JSON and the drawings say the same.
"""

from __future__ import annotations

import math
import re
from functools import cache

import msgspec
import pytest
from tests.scenes import EXAMPLES, slider_crank

import kinepoly
from kinepoly.engine.center_values import KennedyStep
from kinepoly.engine.center_velocity import CenterOmega
from kinepoly.engine.steps import Step
from kinepoly.geom.vec import norm, sub
from kinepoly.present.catalogue import Catalogue, load_catalogue
from kinepoly.present.phrasing import (
    Context,
    center_omega_sentence,
    english,
    kennedy_sentence,
    step_sentence,
    step_words,
)
from kinepoly.present.report import steps_text, to_json
from kinepoly.present.scales import polygon_scales
from kinepoly.solution import Solution

LANGUAGES = ("en", "tr", "ro")
NAMES = sorted(p.stem for p in EXAMPLES.glob("*.toml"))
UNFILLED = re.compile(r"\{[A-Za-z_]*\}|[{}]")
NOT_A_NUMBER = re.compile(r"\b(nan|inf)\b", re.IGNORECASE)
ENGLISH_WORDS = re.compile(r"\b(the|is|of|from|toward|Found|Given|link|point|Lay|Draw|clockwise|counter-clockwise)\b")

# the numbers each topic's sentence must quote (all of its numeric parameters but these)
NOT_QUOTED = {"proportional": {"height"}}  # a height of (almost) zero is the plain division: no height is said

DRIVEN = slider_crank(40, 120, 10, 60, 10, 0).split("[input]")[0] + """
[input]
slider = "14"
s = 120
s_dot = 100
s_ddot = 20
[guess]
B = [150, 10]
[find]
velocity = ["A", "C"]
acceleration = ["A", "C"]
instant_centers = "all"
"""


OFFSET_BLOCK_TRIAD = """
title = "A triad whose block slides on the frame by a point off its pin (no Assur-point construction)"
[links]
1 = { points = { A0 = [0, 0], E = [150, 100] } }
2 = { points = { A0 = [0, 0], A = [30, 0] } }
3 = { points = { D = [0, 0], B = [40.0, 30.0], C = [30.0, -30.0] } }
4 = { points = { E = [0, 0], B = [44.721359549995796, 0] } }
5 = { points = { C = [0, 0], G = [0, -10] } }
6 = { points = { A = [0, 0], D = [60.01602943086692, 0] } }
[[sliders]]
block = "5"
guide = "1"
point = "G"
line = { through = [110, 0], angle = 90 }
[input]
link = "2"
angle = 60
omega = 5
alpha = 2
[guess]
D = [71, 49]
B = [109, 81]
C = [100, 20]
"""


@cache
def _solved(name: str) -> Solution:
    if name == "driven-slider-crank":
        return kinepoly.solve(kinepoly.loads_scene(DRIVEN))
    if name == "offset-block-triad":
        return kinepoly.solve(kinepoly.loads_scene(OFFSET_BLOCK_TRIAD))
    return kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))


def _context(solution: Solution) -> Context:
    return Context(solution, polygon_scales(solution))


def _check_words(sentence: str, say: Catalogue) -> None:
    assert sentence.strip(), "an empty sentence"
    assert not UNFILLED.search(sentence), sentence
    assert not NOT_A_NUMBER.search(sentence), sentence
    if say.code != "en":  # a polygon segment such as "(of = 35 mm)", pole o to tip f, is not a word
        assert not ENGLISH_WORDS.search(re.sub(r"\(\w+ = ", "(", sentence)), sentence


def _quoted(step: Step) -> list[tuple[str, float]]:
    skip = NOT_QUOTED.get(step.topic, set())
    if step.topic == "proportional" and abs(float(step.param("height"))) > 1e-9:
        skip = set()
    return [(k, v) for k, v in step.params if isinstance(v, float) and k not in skip]


@pytest.mark.parametrize("lang", LANGUAGES)
@pytest.mark.parametrize("name", [*NAMES, "driven-slider-crank"])
def test_every_step_of_every_example_has_a_sentence_with_its_numbers(name: str, lang: str) -> None:
    solution = _solved(name)
    say, context = load_catalogue(lang), _context(solution)
    assert solution.steps
    for step in solution.steps:
        sentence = step_sentence(step, say, context)
        _check_words(sentence, say)
        for key, value in _quoted(step):
            assert say.number(abs(value)) in sentence, (step.topic, key, value, sentence)
        for vector in step.vectors:  # the terms laid (normals, Coriolis, given normal) are quoted by size
            if step.topic in ("normals", "given-normal", "coriolis"):
                assert say.number(norm(sub(vector.end, vector.start))) in sentence, (vector.label, sentence)
    centers = solution.centers
    for kennedy in centers.steps if centers is not None else ():
        sentence = kennedy_sentence(kennedy, say, context)
        _check_words(sentence, say)
        assert all(line.label in sentence for line in kennedy.lines)
    for found in centers.omegas if centers is not None else ():
        sentence = center_omega_sentence(found, say, context)
        _check_words(sentence, say)
        assert say.number(found.omega) in sentence


def test_every_kind_of_step_is_covered() -> None:
    """The examples (and the slider-driven crank) hold every topic the construction makes, and linear-solve."""
    topics = {step.topic or step.kind for name in [*NAMES, "driven-slider-crank", "offset-block-triad"]
              for step in _solved(name).steps}
    assert topics >= {"input-rate", "driven-slider", "given-point", "relative", "image", "proportional",
                      "intersection", "read", "coriolis", "normals", "given-normal", "linear-solve", "assur-point",
                      "assur-tip"}
    centers = [_solved(name).centers for name in ("centers-six-bar", "driven-slider-crank")]
    hows = {o.how for found in centers if found is not None for o in found.omegas}
    assert hows >= {"ratio", "velocity", "translating"}


@pytest.mark.parametrize("lang", LANGUAGES)
def test_the_rarer_topics_and_center_omegas_have_words(lang: str) -> None:
    """image-translating, a proportional point off the line, omega_1j = omega_1i: made from real steps' data."""
    say = load_catalogue(lang)
    four_bar, shaper = _solved("four-bar"), _solved("shaper")
    image = next(s for s in four_bar.steps if s.topic == "image")
    _check_words(step_sentence(msgspec.structs.replace(image, topic="image-translating"), say, _context(four_bar)), say)
    proportional = next(s for s in shaper.steps if s.topic == "proportional")
    offset = msgspec.structs.replace(proportional, params=tuple((k, 0.25 if k == "height" else v)
                                                            for k, v in proportional.params))
    sentence = step_sentence(offset, say, _context(shaper))
    _check_words(sentence, say)
    assert say.number(0.25) in sentence and say.number(float(offset.param("ratio"))) in sentence
    six_bar = _solved("centers-six-bar")
    assert six_bar.centers is not None
    ratio = next(o for o in six_bar.centers.omegas if o.how == "ratio")
    same = msgspec.structs.replace(ratio, how="same", params=(("given", ratio.omega),))
    sentence = center_omega_sentence(same, say, _context(six_bar))
    _check_words(sentence, say)
    assert say.number(ratio.omega) in sentence


def test_the_normal_terms_say_omega_squared_times_the_length() -> None:
    """a^n_B/A = ω13² · |AB| = 0.39555² × 120 = 18.775 mm/s²: ω and the length are the solution's."""
    solution = _solved("four-bar")
    assert solution.velocity is not None
    step = next(s for s in solution.steps if s.topic == "normals")
    text, _ = step_words(step, english(), _context(solution))
    say = english()
    w3, w4 = solution.velocity.omega["3"], solution.velocity.omega["4"]
    assert f"a^n_B/A = ω13² · |AB| = {say.number(abs(w3))}² × 120 = {say.number(w3 ** 2 * 120)} mm/s²" in text
    assert f"a^n_B/B0 = ω14² · |B0B| = {say.number(abs(w4))}² × 80 = " in text
    for name in NAMES:  # wherever a normal term is said, ω² × length is its size
        solved = _solved(name)
        for step in solved.steps:
            if step.topic not in ("normals", "given-normal"):
                continue
            words = step_sentence(step, english(), _context(solved))
            for omega, length, size in re.findall(r"= (\S+)² × (\S+) = (\S+) mm/s²", words):
                assert math.isclose(float(omega.replace("−", "-")) ** 2 * float(length), float(size), rel_tol=1e-3)


def test_a_linear_solve_gives_every_tip_and_rate_it_finds() -> None:
    solution = _solved("offset-block-triad")
    assert solution.velocity is not None
    step = next(s for s in solution.steps if s.kind == "linear-solve" and s.polygon == "velocity")
    sentence = step_sentence(step, english(), _context(solution))
    say = english()
    for tip in ("D", "B", "C"):
        assert f"v_{tip} = {say.number(norm(solution.velocity.tips[tip]))} mm/s" in sentence
    for link in ("3", "4", "6"):
        assert f"ω1{link} = {say.number(solution.velocity.omega[link])} rad/s" in sentence


@pytest.mark.parametrize("name", ["slotted-lever", "centers-six-bar"])
def test_solve_steps_and_the_json_say_the_english_sentences(name: str) -> None:
    solution = _solved(name)
    context, say = _context(solution), english()
    data = to_json(solution)
    construction = [s for s in data["steps"] if s["kind"] != "kennedy"]
    assert [s["text"] for s in construction] == [step_sentence(s, say, context) for s in solution.steps]
    printed = steps_text(solution)
    assert all(step_sentence(s, say, context) in printed for s in solution.steps)
    if solution.centers is not None:
        kennedy = [s for s in data["steps"] if s["kind"] == "kennedy"]
        assert [s["text"] for s in kennedy] == [kennedy_sentence(k, say, context) for k in solution.centers.steps]
        assert all(center_omega_sentence(o, say, context) in printed for o in solution.centers.omegas)


def test_a_step_carries_no_words() -> None:
    """The steps are data only: no English written in the geometry."""
    assert "text" not in {f.name for f in msgspec.structs.fields(Step)}
    assert "text" not in {f.name for f in msgspec.structs.fields(KennedyStep)}
    assert "text" not in {f.name for f in msgspec.structs.fields(CenterOmega)}
