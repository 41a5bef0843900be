"""A step's terms as values: every term the construction names (its vectors, its direction lines, its equation's
sides) reads as a ``TermName`` (quantity, component, point and reference, the points as ``LinkPoint``s) whose
text is the name written, on every example scene."""

from __future__ import annotations

import pytest
from tests.scenes import EXAMPLES

from kinepoly.engine.steps import TermName, term_name
from kinepoly.scene.link_point import LinkPoint
from kinepoly.scene.loader import load_scene
from kinepoly.solution import solve


def test_a_term_name_is_its_parts() -> None:
    assert term_name("a^n_B@4/A") == TermName("a", "n", LinkPoint("B", "4"), LinkPoint("A"))
    assert term_name("v_C") == TermName("v", "", LinkPoint("C"))
    assert term_name("a_B/B@1") == TermName("a", "", LinkPoint("B"), LinkPoint("B", "1"))
    assert term_name("a^c_K@3/K").loose == TermName("a", "c", LinkPoint("K"), LinkPoint("K"))  # type: ignore[union-attr]
    assert term_name("a^t_B@4/C").subscript == "B@4/C"  # type: ignore[union-attr]
    for text in ("...", "2 omega x v_B/A", "alpha12 given", "omega12", "v_", "x_B/A"):
        assert term_name(text) is None


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_every_term_of_the_steps_reads_as_a_value_and_back(path) -> None:  # type: ignore[no-untyped-def]
    solution = solve(load_scene(str(path)))
    assert solution.steps
    for step in solution.steps:
        for vector in step.vectors:
            assert vector.name is not None and vector.name.text == vector.label
            assert vector.name.quantity == ("v" if step.polygon == "velocity" else "a")
        for direction in step.directions:
            assert " + ".join(t.text for t in direction.terms) == direction.term
        assert " = ".join(" + ".join(side) for side in step.sides) == step.equation
        for side in step.sides[1:] if step.kind == "intersection" else ():
            names = [term_name(term) for term in side if term != "..."]
            assert all(name is not None for name in names), (step.equation, side)
