"""Links added and removed as edits of the scene's text: what the solve then gives, and what is refused."""

from __future__ import annotations

import math

import pytest

from kinepoly.editor.document import template_text
from kinepoly.editor.edits import EditError, apply_edit
from kinepoly.editor.evaluate import evaluate


def _solved(text: str) -> object:
    evaluation = evaluate(text, "scene.toml", draw=False)
    assert evaluation.ok, evaluation.errors
    return evaluation.solution


def test_a_dyad_pinned_to_a_frame_pivot_closes_where_it_was_placed_and_goes_away_without_a_trace() -> None:
    text = template_text("four-bar")
    solution = _solved(text)
    added = apply_edit(text, {"op": "add-dyad", "from": "C", "joint": [150, 130], "to": {"point": "B0"}}, solution)
    six = evaluate(added, "scene.toml")
    assert six.ok, six.errors
    points = six.handles["points"]
    assert points["D"]["links"] == ["5", "6"] and "6" in points["B0"]["links"]
    assert points["D"]["at"] == pytest.approx([150, 130], abs=0.01)  # the guess took the assembly clicked
    c = points["C"]["at"]
    assert math.dist(c, [150, 130]) == pytest.approx(six.solution.scene.link("5").points[1].local[0], abs=0.01)
    assert set(six.result["links"]) == {"3", "4", "5", "6"}  # [find] lists the new links
    assert {"D"} <= set(six.result["points"])
    back = apply_edit(apply_edit(added, {"op": "remove-link", "link": "6"}, six.solution),
                      {"op": "remove-link", "link": "5"}, six.solution)
    assert back == text


def test_a_link_left_with_one_joint_is_the_solve_s_mobility_message() -> None:
    text = template_text("four-bar")
    added = apply_edit(text, {"op": "add-dyad", "from": "C", "joint": [150, 130], "to": {"at": [200, 0]}},
                       _solved(text))
    six = evaluate(added, "scene.toml")
    half = evaluate(apply_edit(added, {"op": "remove-link", "link": "6"}, six.solution), "scene.toml")
    assert not half.ok and half.exit == 2 and "mobility" in half.errors[0] and "link 5 is joined only at C" in \
        "\n".join(half.errors)
    assert "D0" not in apply_edit(added, {"op": "remove-link", "link": "6"}, six.solution)  # its frame pivot went


@pytest.mark.parametrize(("edit", "message"), [
    ({"op": "remove-link", "link": "2"}, "driven by the input"),
    ({"op": "remove-link", "link": "1"}, "the frame"),
    ({"op": "remove-link", "link": "9"}, "no link '9'"),
    ({"op": "add-dyad", "from": "Q", "joint": [1, 2], "to": {"at": [3, 4]}}, "'Q' is not a point"),
    ({"op": "add-dyad", "from": "C", "joint": [1, 2], "to": {"point": "C"}}, "ends where it starts"),
    ({"op": "add-dyad", "from": "C", "joint": [1, 2], "to": "B0"}, "\"to\" is"),
    ({"op": "add-dyad", "from": "C", "joint": [1, 2], "to": {"at": [1, 2]}, "slider": True}, "direction"),
])
def test_what_cannot_be_added_or_removed_says_why(edit: dict[str, object], message: str) -> None:
    text = template_text("four-bar")
    with pytest.raises(EditError, match=message):
        apply_edit(text, edit, _solved(text))
