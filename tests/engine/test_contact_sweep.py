"""The contacts over a batch of rows (``engine.contacts``): each row equals a solve's ``contacts`` there,
and the contact's velocity condition holds at every row."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from tests.sweep_support import row_scene

import kinepoly
from kinepoly.engine.contacts import contacts_over_rows, polygon_velocity
from kinepoly.engine.velocity import construct_velocity
from kinepoly.sweep import prepare_sweep, run_sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
PAIRS = ["eccentric-cam-flat", "cam-roller-rocker", "gear-pair", "planetary", "rack-pinion"]


def _batch(name: str, steps: int):  # type: ignore[no-untyped-def]
    text = (EXAMPLES / f"{name}.toml").read_text()
    prepared = prepare_sweep(kinepoly.loads_scene(text))
    result = run_sweep(prepared, steps=steps)
    assert result.positions is not None
    velocity = construct_velocity(result.positions, prepared.plan)
    mech = prepared.mechanism
    moving = polygon_velocity(mech, velocity.polygon)
    speed = max(float(np.max(np.abs(tip))) for tip in velocity.tips.values())
    return (text, result, mech, moving,
            contacts_over_rows(mech, result.positions.poses, moving, result.positions.contact_parameters), speed)


@pytest.mark.parametrize("name", PAIRS)
def test_each_batch_row_equals_the_solve_there(name: str) -> None:
    text, result, _, _, contacts, _ = _batch(name, 12)
    assert result.shown is not None
    computed = np.flatnonzero(result.shown)  # the batch's row of each shown row
    for row in range(result.rows):
        solved = kinepoly.solve(kinepoly.loads_scene(row_scene(text, result, row))).contacts
        assert set(solved) == set(contacts)
        for pair, found in contacts.items():
            one = found.row(int(computed[row]))
            want = solved[pair]
            assert one.point == pytest.approx(want.point, rel=1e-12, abs=1e-11)
            assert one.normal == pytest.approx(want.normal, abs=1e-13)
            assert one.sliding_velocity is not None and want.sliding_velocity is not None
            assert one.sliding_velocity == pytest.approx(want.sliding_velocity, rel=1e-11, abs=1e-9)


@pytest.mark.parametrize("name", PAIRS)
def test_normal_velocities_agree_at_every_row(name: str) -> None:
    # the two bodies neither part nor press into each other: their points at the contact have equal
    # velocity components along the common normal (for gears, equal velocities)
    _, _, mech, moving, contacts, speed = _batch(name, 720)
    specs = {**{c.name: (c.cam, c.follower) for c in mech.scene.cams},
             **{g.name: g.links for g in mech.scene.gears}}
    for pair, found in contacts.items():
        first, second = (moving(link, found.point) for link in specs[pair])
        assert first is not None and second is not None
        residual = np.abs(((second - first) * np.conj(found.normal)).real)
        # relative to the mechanism's largest velocity (a planet's point at a fixed sun stands still)
        assert np.max(residual) <= 1e-13 * speed, (pair, float(np.max(residual) / speed))
        assert np.allclose(np.abs(found.normal), 1.0, rtol=0, atol=1e-15)
