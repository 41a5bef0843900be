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
from kinepoly.scene.loader import loads_scene

_OFF_ORIGIN = {"6 = { points = { P = [0, 0] } }": "6 = { points = { P = [30, 10] } }",
               "line = { through = [0, 0], angle = 0 }": "line = { through = [0, 20], angle = 0 }"}
"""The lifting platform with its cylinder's rod point and axis off the links' origins: the drive's and the slide's
entries in the links' angles are not zero there (they are in the example)."""


def _scene(name: str) -> kinepoly.Scene:
    if name != "platform-lift-off-origin":
        return kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    text = (EXAMPLES / "platform-lift.toml").read_text()
    for old, new in _OFF_ORIGIN.items():
        assert old in text
        text = text.replace(old, new)
    return loads_scene(text, "platform-lift-off-origin.toml")


def _systems(name: str, cams: bool = False) -> list[tuple[_RowSystem, np.ndarray]]:
    """The Newton groups of an example (``_scene``) at its input, each with its poses there; ``cams``: the groups
    with a cam's contact too, its parameter appended to the poses."""
    mechanism = build_mechanism(_scene(name))
    plan = make_plan(mechanism, set(mechanism.link_names))
    positions = position_at_input(mechanism, plan)
    known = positions.row(0)
    values = {index: float(v[0]) for index, v in enumerate(positions.values)} or {0: float(input_values(mechanism)[0])}
    out = []
    for group in plan.groups:
        if isinstance(group, NewtonGroup) and not group.gears and (cams or not group.cams):
            q = np.array([c for link in group.links for c in (known[link].x, known[link].y, known[link].theta)])
            others = {link: pose for link, pose in known.items() if link not in group.links}
            system = _RowSystem(mechanism, group, others, group_size(mechanism, group, {}), values)
            out.append((system, np.concatenate((q, system.start_parameters(q))) if group.cams else q))
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


@pytest.mark.parametrize("name", ["platform-lift", "platform-lift-off-origin", "triad", "crank-rocker-cylinder",
                                  "triad-slot", "kc0-six-bar", "spline-cam-floating-flat", "spline-cam-floating-sleeve",
                                  "spline-cam-floating-triad"])
@settings(max_examples=10, deadline=None)
@given(nudge=st.lists(st.floats(-0.05, 0.05), min_size=30, max_size=30))
def test_the_jacobian_is_the_residuals_derivative(name: str, nudge: list[float]) -> None:
    """The closed-form Jacobian (pins, slides, drives, a cam's contact or flat face) against 4-point central
    differences of the residual, column by column: an independent check of every entry the rows write."""
    systems = _systems(name, cams=True)
    assert systems, "the example has a group closed by Newton's method"
    for system, q in systems:
        point = q + np.array(nudge[: len(q)])
        _, jacobian = system.evaluate(point)
        scale = max(1.0, float(np.max(np.abs(point))))
        for column in range(len(point)):
            h = 1e-4 * (scale if column % 3 != 2 or column >= 3 * (len(point) // 3) else 1.0)
            e = np.zeros(len(point))
            e[column] = h
            f = [system.residual(point + k * e) for k in (-2.0, -1.0, 1.0, 2.0)]
            derivative = (f[0] - 8.0 * f[1] + 8.0 * f[2] - f[3]) / (12.0 * h)
            assert np.allclose(jacobian[:, column], derivative, rtol=1e-6, atol=1e-6 * system.scale), (column,)
