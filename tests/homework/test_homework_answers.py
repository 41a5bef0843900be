"""The answers file: every accepted form reads to the same value, every malformed one gets FILE:LINE: key: why."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.errors import SceneError
from kinepoly.homework.answers import AnswerKey, Direction, Tolerance, load_answers, loads_answers

FOUR_BAR = kinepoly.load_scene(EXAMPLES / "four-bar.toml")
SLOTTED = kinepoly.load_scene(EXAMPLES / "slotted-lever.toml")
SIX_BAR = kinepoly.load_scene(EXAMPLES / "centers-six-bar.toml")


def value(text: str, scene: kinepoly.Scene = FOUR_BAR) -> object:
    [answer] = loads_answers(text, scene, "a.toml").answers
    return answer.value


@pytest.mark.parametrize("text, expected", [
    ("omega_3 = -1.70", -1.70),
    ("omega_3 = 2", 2.0),
    ('omega_3 = "1.70 cw"', -1.70),
    ('omega_3 = "1.70 ccw"', 1.70),
    ('omega_3 = "1.70CW"', -1.70),
    ('omega_3 = "1.70 rad/s cw"', -1.70),
    ('omega_3 = "1.70 clockwise"', -1.70),
    ('omega_3 = "-1.70 rad/s"', -1.70),
    ('omega_3 = "60 rpm ccw"', 2.0 * math.pi),
    ('omega_3 = "90 deg/s cw"', -math.pi / 2.0),
    ('alpha_4 = "42.6 rad/s^2 cw"', -42.6),
    ('alpha_4 = "180 deg/s^2"', math.pi),
    ('theta_3 = 90', math.pi / 2.0),
    ('theta_3 = "1.5 rad"', 1.5),
    ("s_14 = 137.4", 137.4),
])
def test_scalar_forms(text: str, expected: float) -> None:
    scene = kinepoly.load_scene(EXAMPLES / "slider-crank.toml") if "s_14" in text else FOUR_BAR
    assert value(text, scene) == pytest.approx(expected, rel=1e-15)


def test_slider_quantities_take_unit_strings_in_the_scene_unit() -> None:
    scene = kinepoly.load_scene(EXAMPLES / "slider-crank.toml")
    assert value('s_14 = "13.74 cm"', scene) == pytest.approx(137.4)
    assert value('s_dot_14 = "-0.5 m/s"', scene) == pytest.approx(-500.0)
    assert value('s_ddot_14 = "-2 m/s^2"', scene) == pytest.approx(-2000.0)


def test_vector_forms() -> None:
    assert value("v_B = [-388.4, 0]") == (-388.4, 0.0)
    polar = value("v_C = { magnitude = 376.8, angle = 150.7 }")
    assert isinstance(polar, tuple)
    assert polar == pytest.approx((376.8 * math.cos(math.radians(150.7)), 376.8 * math.sin(math.radians(150.7))))
    assert value('a_C = { magnitude = "3.7 m/s^2", angle = "0.5 rad" }') == pytest.approx(
        (3700 * math.cos(0.5), 3700 * math.sin(0.5)))
    assert value('"v_A@4" = [-44.4, -76.8]', SLOTTED) == (-44.4, -76.8)
    answers = loads_answers('"a_A@4" = [1, 2]', SLOTTED)
    assert answers.answers[0].key == AnswerKey("acceleration", "A@4")


def test_instant_centers_in_both_forms_and_either_order() -> None:
    assert value("I_13 = [249.6, 931.4]", SIX_BAR) == (249.6, 931.4)
    [answer] = loads_answers("I_61 = { direction = [0, -2] }", SIX_BAR).answers
    assert answer.value == Direction(0.0, -1.0)
    assert answer.key.question == AnswerKey("center", "16").question


def test_meta_keys_and_tolerance() -> None:
    answers = loads_answers('student = " Ana Pop "\nomega_3 = 1\n[tolerance]\nrelative = 0.05\nangle_deg = 3\n',
                            FOUR_BAR, "ana.toml")
    assert answers.student == "Ana Pop" and answers.source == "ana.toml"
    assert answers.tolerance == Tolerance(0.05, 3.0)
    assert loads_answers("omega_3 = 1", FOUR_BAR).tolerance == Tolerance(0.02, 2.0)
    assert [a.line for a in loads_answers("\n\nomega_3 = 1\nalpha_3 = 2\n", FOUR_BAR).answers] == [3, 4]


BAD: list[tuple[str, str, str]] = [
    ("omega3 = 1.7", "a.toml:1: omega3: ", 'unknown answer key; did you mean "omega_3"?'),
    ("omega_9 = 1", "a.toml:1: omega_9: ", 'no link "9"; expected one of "2", "3", "4"'),
    ("omega_1 = 1", "a.toml:1: omega_1: ", 'link "1" is the frame, it does not move'),
    ('omega_3 = "1.7 cww"', "a.toml:1: omega_3: ", 'is not a sense; did you mean "cw"?'),
    ('omega_3 = "-1.7 cw"', "a.toml:1: omega_3: ", "has both a sign and a sense"),
    ('omega_3 = "fast"', "a.toml:1: omega_3: ", 'expected a number in rad/s (ccw positive) or a string like "1.70 cw"'),
    ('omega_3 = "1.7 rad/sec"', "a.toml:1: omega_3: ", 'unknown unit "rad/sec"'),
    ("omega_3 = true", "a.toml:1: omega_3: ", "expected a number in rad/s"),
    ("omega_3 = nan", "a.toml:1: omega_3: ", "is not a finite number"),
    ("omega_3 = [1, 2]", "a.toml:1: omega_3: ", "expected a number"),
    ('v_B = [1, "x"]', "a.toml:1: v_B.y: ", "expected a velocity"),
    ("v_B = [1, 2, 3]", "a.toml:1: v_B: ", "expected [x, y] or { magnitude = m, angle = degrees from +x }"),
    ("v_B = 3", "a.toml:1: v_B: ", "expected [x, y]"),
    ("v_C = { magnitude = -3, angle = 10 }", "a.toml:1: v_C.magnitude: ", "is negative"),
    ("v_C = { magnitud = 3, angle = 10 }", "a.toml:1: v_C.magnitud: ", 'did you mean "magnitude"?'),
    ("v_C = { magnitude = 3 }", "a.toml:1: v_C.angle: ", "missing"),
    ("v_Q = [1, 2]", "a.toml:1: v_Q: ", 'no point "Q"'),
    ('"v_A@7" = [1, 2]', "a.toml:1: v_A@7: ", 'in "A@7": no link "7"'),
    ("I_11 = [1, 2]", "a.toml:1: I_11: ", 'names link "1" twice'),
    ("I_1 = [1, 2]", "a.toml:1: I_1: ", "is not a pair of links"),
    ("I_13 = { direction = [0, 0] }", "a.toml:1: I_13.direction: ", "is [0, 0]"),
    ("I_13 = [1, 2]\nI_31 = [1, 2]", "a.toml:2: I_31: ", "answers the same question as I_13"),
    ("s_99 = 3", "a.toml:1: s_99: ", 'no slider "99"'),
    ('theta_3 = "2 radians"', "a.toml:1: theta_3: ", 'unknown unit "radians"'),
    ("student = 3\nomega_3 = 1", "a.toml:1: student: ", "expected the student's name as a string"),
    ("omega_3 = 1\n[tolerance]\nrelative = 2", "a.toml:3: tolerance.relative: ", "is out of range"),
    ("omega_3 = 1\n[tolerance]\nangle_deg = 0", "a.toml:3: tolerance.angle_deg: ", "is out of range"),
    ("omega_3 = 1\n[tolerance]\nangle_dg = 3", "a.toml:3: tolerance.angle_dg: ", 'did you mean "angle_deg"?'),
    ("omega_3 = 1\ntolerance = 3", "a.toml:2: tolerance: ", "expected a [tolerance] table"),
    ("omega_3 = ", "a.toml:1: omega_3: ", "TOML syntax error"),
    ("# only a comment\n", "a.toml: (file): ", "no answers"),
    ("  \n", "a.toml: (file): ", "the file is empty"),
]


@pytest.mark.parametrize("text, where, what", BAD, ids=[b[0] for b in BAD])
def test_malformed_answers_name_file_line_key_and_fix(text: str, where: str, what: str) -> None:
    with pytest.raises(SceneError) as caught:
        loads_answers(text, SIX_BAR if text.startswith("I_") else FOUR_BAR, "a.toml")
    problems = caught.value.problems
    assert any(p.startswith(where) and what in p for p in problems), problems
    assert caught.value.exit_code == 2


def test_every_problem_is_reported_at_once() -> None:
    with pytest.raises(SceneError) as caught:
        loads_answers("omega_9 = 1\nv_B = 3\nalpha_3 = 'x'\n", FOUR_BAR, "a.toml")
    assert [p.split(": ")[0] for p in caught.value.problems] == ["a.toml:1", "a.toml:2", "a.toml:3"]


def test_a_given_scene_without_accelerations_refuses_acceleration_answers() -> None:
    text = (EXAMPLES / "image-point.toml").read_text()
    lines = [line for line in text.splitlines() if not line.startswith("acceleration")]
    scene = kinepoly.loads_scene("\n".join(lines).split("[find]")[0] + '[find]\nvelocity = ["S"]\n')
    with pytest.raises(SceneError, match="have no accelerations"):
        loads_answers("a_S = [1, 2]", scene, "a.toml")


def test_files_that_cannot_be_read(tmp_path: Path) -> None:
    for name, data, what in [("missing.toml", None, "no such file"), ("nul.toml", b"omega_3 = 1\x00", "NUL"),
                             ("latin.toml", b"omega_3 = \"\xe9\"", "not UTF-8")]:
        path = tmp_path / name
        if data is not None:
            path.write_bytes(data)
        with pytest.raises(SceneError, match=what):
            load_answers(path, FOUR_BAR)
    with pytest.raises(SceneError, match="is a directory"):
        load_answers(tmp_path, FOUR_BAR)
