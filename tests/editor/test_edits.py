"""Edits from the mouse: a moved point keeps every other point where it was, and each link its textbook frame."""

from __future__ import annotations

import math
import tomllib

import pytest

from kinepoly.editor.document import template_text
from kinepoly.editor.edits import apply_edit
from kinepoly.editor.evaluate import evaluate


def _points(text: str) -> dict[str, list[float]]:
    evaluation = evaluate(text, "scene.toml", draw=False)
    assert evaluation.ok, evaluation.errors
    from kinepoly.editor.evaluate import handles

    assert evaluation.solution is not None
    return {name: p["at"] for name, p in handles(evaluation.solution)["points"].items()}


@pytest.mark.parametrize(("point", "to"), [("B0", (112.0, -8.0)), ("A", (30.0, 50.0)), ("B", (140.0, 60.0)),
                                           ("C", (70.0, 90.0)), ("A0", (-5.0, 3.0))])
def test_a_moved_point_moves_alone_and_each_link_keeps_its_first_joint_at_its_origin(
        point: str, to: tuple[float, float]) -> None:
    text = template_text("four-bar")
    before = evaluate(text, "scene.toml", draw=False)
    after_text = apply_edit(text, {"op": "move-point", "point": point, "to": list(to)}, before.solution)
    after, was = _points(after_text), _points(text)
    for name, at in after.items():
        assert at == pytest.approx(list(to) if name == point else was[name], abs=0.02), name
    links = tomllib.loads(after_text)["links"]
    for name in ("2", "3", "4"):  # the moving links' first joint at the origin, the second on the x-axis
        first, second = list(links[name]["points"].values())[:2]
        assert first == [0, 0] and second[1] == 0 and second[0] > 0, (name, links[name])
    assert isinstance(links["3"]["points"]["C"], dict)  # the coupler point still written in polar form
    scene = tomllib.loads(after_text)
    a = after["A"]
    assert scene["input"]["angle"] == pytest.approx(math.degrees(math.atan2(a[1] - after["A0"][1],
                                                                            a[0] - after["A0"][0])), abs=0.01)


def test_a_length_typed_scales_the_point_from_the_links_first_joint_and_keeps_a_polar_point_polar() -> None:
    text = template_text("four-bar")
    solution = evaluate(text, "scene.toml", draw=False).solution
    changed = apply_edit(text, {"op": "length", "link": "3", "point": "C", "value": 75}, solution)
    assert "C = { polar = [75, 30] }" in changed
    changed = apply_edit(changed, {"op": "length", "link": "4", "point": "B", "value": 85.5}, solution)
    assert "4 = { points = { B0 = [0, 0], B = [85.5, 0] } }" in changed


def test_a_guess_is_offered_for_a_dyads_inner_joint_where_no_guess_tells_its_assemblies() -> None:
    from kinepoly.editor.evaluate import handles

    def offered(text: str) -> list[str]:
        evaluation = evaluate(text, "scene.toml", draw=False)
        assert evaluation.solution is not None
        return list(handles(evaluation.solution)["assembly"])

    four_bar = template_text("four-bar")
    assert offered(four_bar) == []
    assert offered(four_bar.replace("[guess]\nB = [110, 80]\n", "")) == ["B"]
    assert offered(template_text("six-bar").replace("E = [200, 20]\n", "")) == ["E"]


@pytest.mark.parametrize("edit", [
    {"op": "move-point", "point": "B", "to": [10**400, 0]},
    {"op": "drive", "to": [0, -10**400]},
    {"op": "guess", "point": "B", "to": [10**400, 10**400]},
    {"op": "length", "link": "3", "point": "B", "value": 10**400},
    {"op": "set", "key": ["input", "omega"], "value": 10**400},
    {"op": "set", "key": ["guess", "B"], "value": [1, 10**400]},
])
def test_a_whole_number_too_large_for_a_float_is_refused_with_a_message(edit: dict[str, object]) -> None:
    # JSON holds whole numbers of any size; one beyond a float's range (found by the fuzzer) made an internal error
    from kinepoly.editor.edits import EditError

    text = template_text("four-bar")
    before = evaluate(text, "scene.toml", draw=False)
    with pytest.raises(EditError, match="expected"):
        apply_edit(text, edit, before.solution)


def test_a_length_of_a_link_the_loader_made_is_refused_with_a_message() -> None:
    # a cam's equivalent link (4: K23 to W) is not in the text; its length made an internal error (found by the fuzzer)
    from pathlib import Path

    from kinepoly.editor.edits import EditError

    text = (Path(__file__).resolve().parents[2] / "examples" / "cam-roller-rocker.toml").read_text(encoding="utf-8")
    before = evaluate(text, "scene.toml", draw=False)
    assert before.solution is not None and "4" in [link.name for link in before.solution.scene.links]
    with pytest.raises(EditError, match="length"):
        apply_edit(text, {"op": "length", "link": "4", "point": "W", "value": 100}, before.solution)
