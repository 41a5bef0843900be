"""Checking answers: the tolerance rule at its edges, and every diagnosis on a case where the mistake is the
only difference. Each mistaken answer is derived here, independently of kinepoly.homework: the
construction mistakes by solving the textbook vector equations (complex numbers, J r = i r) with the
term changed, the input mistakes by solving a scene written with the mistaken input."""

from __future__ import annotations

import math
from typing import Any

import msgspec
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.scenes import EXAMPLES, four_bar, slider_crank, slotted_lever

import kinepoly
from kinepoly.engine.acceleration import RIGHT, Rules
from kinepoly.errors import SceneError
from kinepoly.homework import check, loads_answers, make_checker
from kinepoly.homework.answers import AnswerKey, Value
from kinepoly.homework.checking import CheckResult
from kinepoly.homework.reference import prepare, student_solution

DRAW = "\n[draw]\nkv = 0.5\nka = 0.02\n"
FOUR_BAR = (EXAMPLES / "four-bar.toml").read_text() + DRAW  # alpha12 = 5: reversing the normals is not a sign flip
SLOTTED = (EXAMPLES / "slotted-lever.toml").read_text().replace("alpha = 0", "alpha = 3").replace(
    'alpha = ["4"]', 'alpha = ["4"]\nsliders = ["43"]') + DRAW


def solved(text: str) -> dict[str, Any]:
    return kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text)))


def z(v: list[float]) -> complex:
    return complex(v[0], v[1])


def plain(value: Value) -> complex | float:
    """A number or a vector (as a complex number) of kinepoly.homework."""
    assert isinstance(value, (float, tuple))
    return complex(*value) if isinstance(value, tuple) else value


def toml_value(value: complex) -> str:
    return f"[{value.real!r}, {value.imag!r}]" if isinstance(value, complex) else repr(value)


def right_answers(data: dict[str, Any]) -> dict[str, complex | float]:
    """Every key a solved scene reports, at its right value."""
    out: dict[str, complex | float] = {}
    for link, entry in data.get("links", {}).items():
        out.update({f"{kind}_{link}": entry[kind] for kind in ("omega", "alpha") if kind in entry})
    for label, entry in data.get("points", {}).items():
        out.update({f"{'v' if kind == 'velocity' else 'a'}_{label}": z(entry[kind])
                    for kind in ("velocity", "acceleration") if kind in entry})
    for name, entry in data.get("sliders", {}).items():
        out.update({f"{kind}_{name}": entry[kind] for kind in ("s", "s_dot", "s_ddot")})
    return out


def checked(text: str, answers: dict[str, complex | float], extra: str = "") -> CheckResult:
    scene = kinepoly.loads_scene(text, "scene.toml")
    body = "\n".join(f'"{key}" = {toml_value(value)}' for key, value in answers.items()) + "\n" + extra
    parsed = loads_answers(body, scene, "answers.toml")
    return check(parsed, make_checker(scene, [parsed], text))


def only_wrong(result: CheckResult) -> tuple[str, str]:
    wrong = [v for v in result.verdicts if not v.is_correct]
    assert len(wrong) == 1, [(v.key.text, v.diagnosis) for v in wrong]
    assert wrong[0].diagnosis is not None
    return wrong[0].key.text, wrong[0].diagnosis.code


def with_mistake(text: str, key: str, value: complex) -> tuple[str, str]:
    answers = right_answers(solved(text))
    assert key in answers
    answers[key] = value
    return only_wrong(checked(text, answers))


# --------------------------------------------------------------------------------------------
# Independent derivations of the construction mistakes


def four_bar_normals_reversed(text: str = FOUR_BAR, a1: float = 100.0) -> dict[str, complex | float]:
    """a_B = a_A + a^n_BA + a^t_BA = a^n_BB0 + a^t_BB0 with every normal term omega^2 r laid away from its center."""
    data = solved(text)
    scene = kinepoly.loads_scene(text)
    assert isinstance(scene.input, kinepoly.scene.spec.LinkInput)
    p = {name: z(data["points"][name]["position"]) for name in ("A", "B", "C")}
    a0, b0 = 0j, a1 + 0j
    w2, al2 = scene.input.omega, scene.input.alpha
    w3, w4 = data["links"]["3"]["omega"], data["links"]["4"]["omega"]
    r_a, r_ab, r_bb, r_ac = p["A"] - a0, p["B"] - p["A"], p["B"] - b0, p["C"] - p["A"]
    a_a = w2**2 * r_a + 1j * al2 * r_a  # + omega^2 r: away from A0
    rhs = w4**2 * r_bb - a_a - w3**2 * r_ab
    m = np.array([[(1j * r_ab).real, (-1j * r_bb).real], [(1j * r_ab).imag, (-1j * r_bb).imag]])
    al3, al4 = np.linalg.solve(m, [rhs.real, rhs.imag])
    return {"alpha_3": float(al3), "alpha_4": float(al4), "a_A": a_a,
            "a_B": w4**2 * r_bb + 1j * al4 * r_bb, "a_C": a_a + w3**2 * r_ac + 1j * al3 * r_ac}


def slotted_coriolis(factor: float, text: str = SLOTTED, a1: float = 80.0) -> dict[str, complex | float]:
    """a_A = a_A@4 + s_ddot e + factor * 2 omega4 x v_rel, a_A@4 = -omega4^2 r + alpha4 x r (r = B0 -> A)."""
    data = solved(text)
    a = z(data["points"]["A"]["position"])
    r = a - a1
    w4 = data["links"]["4"]["omega"]
    e = complex(math.cos(math.radians(data["links"]["4"]["angle"] + 90.0)),
                math.sin(math.radians(data["links"]["4"]["angle"] + 90.0)))
    v_rel = z(data["points"]["A"]["velocity"]) - z(data["points"]["A@4"]["velocity"])
    rhs = z(data["points"]["A"]["acceleration"]) + w4**2 * r - factor * 2.0 * w4 * 1j * v_rel
    m = np.array([[(1j * r).real, e.real], [(1j * r).imag, e.imag]])
    al4, s_ddot = np.linalg.solve(m, [rhs.real, rhs.imag])
    return {"alpha_4": float(al4), "a_A@4": -(w4**2) * r + 1j * al4 * r, "s_ddot_43": float(s_ddot)}


def test_the_derivations_reproduce_the_right_answers_when_nothing_is_changed() -> None:
    right = right_answers(solved(SLOTTED))
    for key, value in slotted_coriolis(1.0).items():
        assert abs(value - right[key]) <= 1e-9 * max(1.0, abs(right[key]))


@pytest.mark.parametrize("key", ["alpha_3", "alpha_4", "a_B", "a_C"])
def test_normal_terms_drawn_away_from_the_center(key: str) -> None:
    assert with_mistake(FOUR_BAR, key, four_bar_normals_reversed()[key]) == (key, "normal-reversed")


@pytest.mark.parametrize("factor, code", [(0.0, "coriolis-left-out"), (-1.0, "coriolis-reversed")])
@pytest.mark.parametrize("key", ["alpha_4", "a_A@4", "s_ddot_43"])
def test_coriolis_left_out_or_reversed(key: str, factor: float, code: str) -> None:
    assert with_mistake(SLOTTED, key, slotted_coriolis(factor)[key]) == (key, code)


# --------------------------------------------------------------------------------------------
# Reading mistakes, input mistakes, another point's value


def test_sign_reversed_for_rates_and_vectors() -> None:
    right = right_answers(solved(FOUR_BAR))
    assert with_mistake(FOUR_BAR, "a_C", -right["a_C"]) == ("a_C", "sign-reversed")
    assert with_mistake(FOUR_BAR, "omega_3", -right["omega_3"]) == ("omega_3", "sign-reversed")
    answers = right_answers(solved(FOUR_BAR))
    answers.pop("omega_4")
    w4 = right["omega_4"]
    assert isinstance(w4, float) and w4 > 0
    result = checked(FOUR_BAR, answers, extra=f'omega_4 = "{w4} cw"\n')
    assert only_wrong(result) == ("omega_4", "sign-reversed")


def test_polygon_lengths_not_divided_by_the_scale() -> None:
    right = right_answers(solved(FOUR_BAR))  # [draw] kv = 0.5, ka = 0.02
    assert with_mistake(FOUR_BAR, "v_B", 0.5 * right["v_B"]) == ("v_B", "kv-not-divided")
    assert with_mistake(FOUR_BAR, "omega_3", 0.5 * right["omega_3"]) == ("omega_3", "kv-not-divided")
    assert with_mistake(FOUR_BAR, "a_C", 0.02 * right["a_C"]) == ("a_C", "ka-not-divided")
    assert with_mistake(FOUR_BAR, "alpha_4", 0.02 * right["alpha_4"]) == ("alpha_4", "ka-not-divided")


def test_degrees_taken_for_radians() -> None:
    at_60_rad = right_answers(solved(FOUR_BAR.replace("angle = 60", 'angle = "60 rad"')))
    assert with_mistake(FOUR_BAR, "v_B", at_60_rad["v_B"]) == ("v_B", "degrees-for-radians")
    assert with_mistake(FOUR_BAR, "alpha_3", at_60_rad["alpha_3"]) == ("alpha_3", "degrees-for-radians")
    right = right_answers(solved(FOUR_BAR))
    assert with_mistake(FOUR_BAR, "omega_4", right["omega_4"] * 180.0 / math.pi) == ("omega_4", "degrees-for-radians")


@pytest.mark.parametrize("written, number, code", [('"573 deg/s"', 573.0, "degrees-for-radians"),
                                                    ('"95.5 rpm"', 95.5, "rpm-for-rad/s")])
def test_input_omega_used_without_converting_its_unit(written: str, number: float, code: str) -> None:
    scene = FOUR_BAR.replace("omega = 10", f"omega = {written}")
    student = right_answers(solved(FOUR_BAR.replace("omega = 10", f"omega = {number}")))
    assert with_mistake(scene, "v_C", student["v_C"]) == ("v_C", code)


def test_the_right_value_of_another_point_or_link() -> None:
    right = right_answers(solved(FOUR_BAR))
    assert with_mistake(FOUR_BAR, "v_B", right["v_C"]) == ("v_B", "other-point")
    assert with_mistake(FOUR_BAR, "alpha_3", right["alpha_4"]) == ("alpha_3", "other-link")
    coincident = right_answers(solved(SLOTTED))
    assert with_mistake(SLOTTED, "v_A@4", coincident["v_A"]) == ("v_A@4", "other-point")


def test_an_answer_no_mistake_explains_is_unrecognised() -> None:
    result = checked(FOUR_BAR, {**right_answers(solved(FOUR_BAR)), "v_B": 123 + 45j})
    assert only_wrong(result) == ("v_B", "unrecognised")
    [wrong] = [v for v in result.verdicts if not v.is_correct]
    assert wrong.diagnosis is not None and "sign-reversed" in wrong.diagnosis.text


def test_a_question_of_find_left_unanswered_is_wrong() -> None:
    answers = right_answers(solved(FOUR_BAR))
    del answers["a_B"]
    result = checked(FOUR_BAR, answers)
    assert only_wrong(result) == ("a_B", "not-answered")
    assert result.score == pytest.approx((len(answers)) / (len(answers) + 1))


# --------------------------------------------------------------------------------------------
# The tolerance rule at its edges


def one(text: str, key: str, value: str, tolerance: str = "") -> bool:
    scene = kinepoly.loads_scene(text)
    parsed = loads_answers(f'"{key}" = {value}\n{tolerance}', scene)
    [verdict] = [v for v in check(parsed, make_checker(scene, [parsed])).verdicts if v.key.text == key]
    return verdict.is_correct


def test_numbers_within_two_percent() -> None:
    w = right_answers(solved(FOUR_BAR))["omega_4"]
    assert isinstance(w, float)
    assert one(FOUR_BAR, "omega_4", repr(w * 1.0199)) and one(FOUR_BAR, "omega_4", repr(w * 0.9801))
    assert not one(FOUR_BAR, "omega_4", repr(w * 1.0201)) and not one(FOUR_BAR, "omega_4", repr(w * 0.9799))
    assert one(FOUR_BAR, "omega_4", repr(w * 1.049), "[tolerance]\nrelative = 0.05")
    assert not one(FOUR_BAR, "omega_4", repr(w * 1.051), "[tolerance]\nrelative = 0.05")


def test_vectors_by_magnitude_and_direction() -> None:
    a = right_answers(solved(FOUR_BAR))["a_C"]
    assert isinstance(a, complex)

    def turn(deg: float) -> complex:
        return a * complex(math.cos(math.radians(deg)), math.sin(math.radians(deg)))

    assert one(FOUR_BAR, "a_C", toml_value(turn(1.99))) and one(FOUR_BAR, "a_C", toml_value(turn(-1.99)))
    assert not one(FOUR_BAR, "a_C", toml_value(turn(2.01)))
    assert one(FOUR_BAR, "a_C", toml_value(a * 1.0199)) and not one(FOUR_BAR, "a_C", toml_value(a * 1.0201))
    assert one(FOUR_BAR, "a_C", toml_value(turn(4.9)), "[tolerance]\nangle_deg = 5")
    polar = f"{{ magnitude = {abs(a) * 1.01!r}, angle = {math.degrees(math.atan2(a.imag, a.real)) + 1.5!r} }}"
    assert one(FOUR_BAR, "a_C", polar)


def test_a_zero_is_judged_against_one_percent_of_its_kind() -> None:
    # a parallelogram at constant speed: omega3 = alpha3 = 0; the largest omega is 10, so alpha's size is
    # at least omega^2 = 100, and alpha_3 is judged against 1 % of that: 0.02 * 1 = 0.02 rad/s^2
    text = four_bar(100, 40, 100, 40, 60, 10, 0, guess_b=(120, 35))
    data = solved(text)
    assert abs(data["links"]["3"]["alpha"]) < 1e-9 and abs(data["links"]["3"]["omega"]) < 1e-12
    assert one(text, "alpha_3", "0.0199") and one(text, "alpha_3", "-0.0199") and not one(text, "alpha_3", "0.0201")
    assert one(text, "omega_3", "0.00199") and not one(text, "omega_3", "0.00201")  # 2 % of 1 % of 10 rad/s


def test_link_angles_modulo_a_turn() -> None:
    theta = solved(FOUR_BAR)["links"]["3"]["angle"]
    assert one(FOUR_BAR, "theta_3", repr(theta + 1.99)) and one(FOUR_BAR, "theta_3", repr(theta + 360.0 - 1.99))
    assert not one(FOUR_BAR, "theta_3", repr(theta - 2.01))
    assert one(FOUR_BAR, "theta_3", f'"{math.radians(theta)!r} rad"')


def test_instant_centers_by_distance_and_at_infinity() -> None:
    scene = kinepoly.load_scene(EXAMPLES / "centers-six-bar.toml")
    reference = prepare(scene, [AnswerKey("center", "13"), AnswerKey("center", "16")])
    if not reference.has_centers:
        pytest.skip("instant centers not computed by this kinepoly")
    text = (EXAMPLES / "centers-six-bar.toml").read_text()
    center = reference.expected(AnswerKey("center", "13"))
    assert isinstance(center, tuple)
    size = reference.scales["length"]
    allowed = 0.02 * max(size, math.hypot(*center))
    assert one(text, "I_31", f"[{center[0] + 0.99 * allowed!r}, {center[1]!r}]")
    assert not one(text, "I_13", f"[{center[0]!r}, {center[1] + 1.01 * allowed!r}]")
    direction = reference.expected(AnswerKey("center", "16"))
    if not isinstance(direction, tuple):
        assert one(text, "I_16", f"{{ direction = [{-direction.x!r}, {-direction.y!r}] }}")
        assert not one(text, "I_16", "[0, 500]")


def test_instant_center_answers_while_none_are_computed_are_a_clear_error() -> None:
    scene = kinepoly.load_scene(EXAMPLES / "centers-six-bar.toml")
    parsed = loads_answers("omega_3 = 1\nI_13 = [1, 2]\n", scene, "ana.toml")
    checker = make_checker(scene, [parsed])
    values = {k: v for k, v in checker.reference.values.items() if k.kind != "center"}
    without = msgspec.structs.replace(checker, reference=msgspec.structs.replace(checker.reference, values=values,
                                                                         has_centers=False))
    with pytest.raises(SceneError, match=r"ana.toml:2: I_13: this kinepoly does not compute instant centers yet"):
        check(parsed, without)


# --------------------------------------------------------------------------------------------
# The student's construction: done right it is kinepoly's; with a mistake, the textbook derivation


def agreement(text: str, how: Rules = RIGHT) -> float:
    scene = kinepoly.loads_scene(text)
    reference = prepare(scene)
    student = student_solution(reference.solution, how)
    worst = 0.0
    for key, value in reference.values.items():
        if key.kind in ("velocity", "acceleration", "omega", "alpha"):
            worst = max(worst, abs(plain(value) - plain(student[key])) / reference.scales[key.kind])
    return worst


@pytest.mark.parametrize("name", ["four-bar", "slider-crank", "slotted-lever", "shaper", "triad", "image-point",
                                  "centers-six-bar"])
def test_the_student_equations_done_right_are_kinepoly(name: str) -> None:
    assert agreement((EXAMPLES / f"{name}.toml").read_text()) <= 1e-12


@settings(max_examples=25, deadline=None)
@given(theta=st.floats(0, 360), omega=st.floats(1, 20), sense=st.sampled_from([-1.0, 1.0]),
       alpha=st.floats(-50, 50), a3=st.floats(110, 140), offset=st.floats(-20, 20))
def test_the_student_equations_done_right_agree_on_random_slider_cranks(theta: float, omega: float, sense: float,
                                                                        alpha: float, a3: float,
                                                                        offset: float) -> None:
    omega *= sense
    find = '[find]\nvelocity = ["A", "B", "C"]\nacceleration = ["A", "B", "C"]\nomega = ["3"]\nalpha = ["3"]'
    assert agreement(slider_crank(40, a3, offset, theta, omega, alpha, find=find)) <= 1e-10


def assert_student_matches(text: str, how: Rules, derived: dict[str, complex | float]) -> None:
    scene = kinepoly.loads_scene(text)
    student = student_solution(prepare(scene).solution, how)
    size = max(abs(value) for value in derived.values())
    for key, value in derived.items():
        kind, _, target = key.partition("_")
        answer = (AnswerKey("alpha", target) if kind == "alpha" else
                  AnswerKey("s_ddot", target.removeprefix("ddot_")) if kind == "s" else
                  AnswerKey("acceleration", target))
        assert abs(plain(student[answer]) - value) <= 1e-9 * max(1.0, size), key


def test_the_normals_reversed_equations_match_the_textbook_derivation() -> None:
    assert_student_matches(FOUR_BAR, Rules(normal=1.0), four_bar_normals_reversed())


@settings(max_examples=20, deadline=None)
@given(a2=st.floats(20, 40), a3=st.floats(100, 125), a4=st.floats(75, 100), theta=st.floats(0, 360),
       omega=st.floats(1, 20), alpha=st.floats(-50, 50))
def test_normals_reversed_on_random_crank_rockers(a2: float, a3: float, a4: float, theta: float, omega: float,
                                                  alpha: float) -> None:
    text = four_bar(100, a2, a3, a4, theta, omega, alpha, guess_b=(110, 80),
                    find='[find]\nvelocity = ["A", "B", "C"]\nacceleration = ["A", "B", "C"]\nomega = ["3", "4"]')
    assert_student_matches(text, Rules(normal=1.0), four_bar_normals_reversed(text))


@settings(max_examples=20, deadline=None)
@given(offset=st.floats(0, 30), theta=st.floats(0, 360), omega=st.floats(1, 20), alpha=st.floats(-50, 50),
       factor=st.sampled_from([0.0, -1.0]))
def test_coriolis_mistakes_on_random_slotted_levers(offset: float, theta: float, omega: float, alpha: float,
                                                    factor: float) -> None:
    text = slotted_lever(80, 40, offset, theta, omega, alpha, guess_f=(70, -11))
    assert_student_matches(text, Rules(coriolis=factor), slotted_coriolis(factor, text))
