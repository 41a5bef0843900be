"""A Newton line search tries steps with the joint residual alone (``_RowSystem.residual``) and evaluates the
Jacobian only at the step it takes: the residual must be the very numbers of the full evaluation, at the start and
at points about it (the sweeps of groups closed by Newton's method stay bit for bit what they were)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.engine.assembly import position_at_input
from kinepoly.engine.groups import NewtonGroup
from kinepoly.engine.newton import _RowSystem, group_size
from kinepoly.engine.plan import make_plan
from kinepoly.engine.position import input_values
from kinepoly.model.mechanism import build_mechanism


def _systems(name: str) -> list[tuple[_RowSystem, np.ndarray]]:
    mechanism = build_mechanism(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    plan = make_plan(mechanism, set(mechanism.link_names))
    positions = position_at_input(mechanism, plan)
    known = positions.row(0)
    values = {index: float(v[0]) for index, v in enumerate(positions.values)} or {0: float(input_values(mechanism)[0])}
    out = []
    for group in plan.groups:
        if isinstance(group, NewtonGroup) and not group.gears and not group.cams:
            q = np.array([c for link in group.links for c in (known[link].x, known[link].y, known[link].theta)])
            others = {link: pose for link, pose in known.items() if link not in group.links}
            out.append((_RowSystem(mechanism, group, others, group_size(mechanism, group, {}), values), q))
    return out


@pytest.mark.parametrize("name", ["platform-lift", "triad", "crank-rocker-cylinder", "triad-slot"])
@settings(max_examples=25, deadline=None)
@given(nudge=st.lists(st.floats(-0.5, 0.5), min_size=30, max_size=30))
def test_the_residual_alone_is_the_full_evaluations(name: str, nudge: list[float]) -> None:
    systems = _systems(name)
    assert systems, "the example has a group closed by Newton's method"
    for system, q in systems:
        moved = q + np.array(nudge[: len(q)])
        for point in (q, moved):
            full, jacobian = system.evaluate(point)
            assert np.array_equal(system.residual(point), full)
            assert jacobian.shape == (system.count, system.size) and np.isfinite(jacobian).all()
