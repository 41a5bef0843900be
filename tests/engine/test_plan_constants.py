"""A plan keeps its construction's constants (``engine.groups.PlanConstants``): the next construction of the same
plan replays them and gives the same polygons to the last bit; a plan constructed on a mechanism of other
dimensions (the same topology) finds its own, so that an image is never built with another link's shape."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kinepoly.engine.acceleration import construct_acceleration
from kinepoly.engine.assembly import position_at_input
from kinepoly.engine.groups import PositionPlan
from kinepoly.engine.plan import make_plan
from kinepoly.engine.velocity import construct_velocity
from kinepoly.model.mechanism import Mechanism, build_mechanism
from kinepoly.scene.loader import loads_scene

FOUR_BAR = (Path(__file__).resolve().parents[2] / "examples" / "four-bar.toml").read_text()
WANTED = (("3", "C"),)
RIGID_REL = 1e-12
"""C's tips against link 3's rigid-body relations, relative to the largest term: a few roundings."""


def _mechanism(c_polar: tuple[float, float] = (60.0, 30.0)) -> Mechanism:
    text = FOUR_BAR.replace("C = { polar = [60, 30] }", f"C = {{ polar = [{c_polar[0]}, {c_polar[1]}] }}")
    assert text != FOUR_BAR or c_polar == (60.0, 30.0)
    return build_mechanism(loads_scene(text, "four-bar.toml"))


def _construct(mechanism: Mechanism, plan: PositionPlan) -> dict[str, np.ndarray]:
    with np.errstate(all="ignore"):
        positions = position_at_input(mechanism, plan)
        velocity = construct_velocity(positions, plan, WANTED)
        acceleration = construct_acceleration(velocity, plan, WANTED)
    return {"r_A": positions.point("A"), "r_C": positions.point("C"), "v_A": velocity.tips["A"],
            "v_C": velocity.tips["C"], "a_A": acceleration.tips["A"], "a_C": acceleration.tips["C"],
            "omega3": velocity.omega["3"], "alpha3": acceleration.polygon.rate["3"]}


def _rigid_misfit(found: dict[str, np.ndarray]) -> tuple[float, float]:
    """How far C's tips are from the rigid-body relations of link 3 (closed forms, not the image):
    v_C = v_A + i omega3 r_AC and a_C = a_A + (i alpha3 - omega3^2) r_AC, relative to the largest term."""
    r = found["r_C"] - found["r_A"]
    w, alpha = found["omega3"], found["alpha3"]
    v = found["v_A"] + 1j * w * r
    a = found["a_A"] + (1j * alpha - w * w) * r
    scale_v = max(float(np.abs(found["v_A"]).max()), float(np.abs(w * r).max()))
    scale_a = max(float(np.abs(found["a_A"]).max()), float(np.abs(w * w * r).max()), float(np.abs(alpha * r).max()))
    return float(np.abs(found["v_C"] - v).max()) / scale_v, float(np.abs(found["a_C"] - a).max()) / scale_a


def test_the_next_construction_replays_the_constants_to_the_last_bit() -> None:
    mechanism = _mechanism()
    plan = make_plan(mechanism, set(mechanism.link_names))
    first = _construct(mechanism, plan)
    assert plan.constants.images, "the first construction keeps the image of C"
    assert plan.constants.mechanism is mechanism
    kept = plan.constants
    assert kept.labels and kept.tips and kept.groups and kept.frame, "labels, members, the dyad's lines, the frame"
    found = (dict(kept.labels), dict(kept.tips), dict(kept.groups), dict(kept.images))
    replayed = _construct(mechanism, plan)
    assert (kept.labels, kept.tips, kept.groups, kept.images) == found, "the replay finds every constant kept"
    fresh = _construct(mechanism, PositionPlan(plan.driven, plan.groups))
    for name, values in first.items():
        assert values.tobytes() == replayed[name].tobytes() == fresh[name].tobytes(), name
    assert max(_rigid_misfit(replayed)) < RIGID_REL


@pytest.mark.parametrize("c_polar", [(90.0, -45.0), (30.0, 120.0), (150.0, 10.0)])
def test_a_plan_on_other_dimensions_finds_its_own_constants(c_polar: tuple[float, float]) -> None:
    base = _mechanism()
    plan = make_plan(base, set(base.link_names))
    _construct(base, plan)  # the constants found on the base mechanism's coupler
    other = _mechanism(c_polar)
    found = _construct(other, plan)
    assert max(_rigid_misfit(found)) < RIGID_REL
    fresh = _construct(other, PositionPlan(plan.driven, plan.groups))
    for name, values in found.items():
        assert values.tobytes() == fresh[name].tobytes(), name
