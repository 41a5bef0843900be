"""The triad is a group kind of its own (``engine.kinds.triad``, a row of ``engine.table``): a class-3 group is a
``TriadGroup``, placed as a Newton group is and constructed through its Assur point; any other group left to
Newton's method keeps the linear solve of its joint equations."""

from __future__ import annotations

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.engine import table
from kinepoly.engine.groups import NewtonGroup, TriadGroup
from kinepoly.engine.kinds import newton, triad
from kinepoly.engine.plan import make_plan
from kinepoly.model.mechanism import build_mechanism

TRIADS = ["triad", "triad-slot", "spline-cam-floating-triad", "spline-cam-floating-sleeve", "spline-cam-floating-flat",
          "kc0-six-bar", "platform-lift"]


@pytest.mark.parametrize("name", TRIADS)
def test_a_class_3_group_is_a_triad_constructed_through_its_assur_point(name: str) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    groups = make_plan(build_mechanism(scene)).groups
    triads = [g for g in groups if type(g) is TriadGroup]
    assert len(triads) == 1 and table.kind_of(triads[0]) is triad.KIND
    steps = kinepoly.solve(scene).steps
    assert any(step.topic == "assur-tip" for step in steps)
    assert not any(step.kind == "linear-solve" for step in steps)


def test_a_group_of_another_shape_keeps_the_linear_solve() -> None:
    scene = kinepoly.load_scene(EXAMPLES / "crank-rocker-cylinder.toml")
    groups = make_plan(build_mechanism(scene)).groups
    assert [type(g) for g in groups] == [NewtonGroup] and table.kind_of(groups[0]) is newton.KIND
    steps = kinepoly.solve(scene).steps
    assert any(step.kind == "linear-solve" for step in steps)
    assert not any(step.topic == "assur-tip" for step in steps)


def test_the_triad_is_placed_as_the_newton_group_is_and_found_before_it() -> None:
    assert triad.KIND.place is newton.KIND.place
    kinds = list(table.KINDS)
    assert kinds.index(TriadGroup) == len(kinds) - 2 and kinds[-1] is NewtonGroup


def test_every_kind_module_gives_the_same_four_functions() -> None:
    for kind in table.KINDS.values():
        assert all(callable(getattr(kind, name)) for name in ("find", "place", "velocity", "acceleration"))
