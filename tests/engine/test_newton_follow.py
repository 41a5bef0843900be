"""A group closed by Newton's method keeps its assembly over a sweep (``engine.newton_walk``).

The floating flat-faced coupler of ``spline-cam-floating-flat.toml`` with its rockers' pivots moved a few
millimetres meets dead points within the turn and moves fast between them. A sweep on coarse rows must then
give, at every row where it closes, the value of a sweep fifty times finer at the same input: a row that
lands in another assembly (the coupler 74 degrees off, as before the walk) fails this; and it must mark a
row that only the far side of a dead point reaches, saying so.
"""

from __future__ import annotations

import numpy as np
import pytest
from tests.engine.test_spline_floating import CIRCLE, FLAT, _scene

from kinepoly.sweep import sweep


def _moved(dx: float, dy: float) -> dict[str, str]:
    """The example's text with B0 moved by (dx, dy) and C0 by (-dy, dx), the rockers' lengths kept to B and C."""
    b0, c0 = complex(-97 + dx, 45 + dy), complex(-42 - dy, 47 + dx)
    b, c = complex(-27, 59.5), complex(28, 59.5)
    return {"B0 = [-97, 45], C0 = [-42, 47]": f"B0 = [{b0.real!r}, {b0.imag!r}], C0 = [{c0.real!r}, {c0.imag!r}]",
            "B = [71.49, 0]": f"B = [{abs(b - b0)!r}, 0]", "C = [71.11, 0]": f"C = [{abs(c - c0)!r}, 0]"}


@pytest.mark.parametrize(("dx", "dy", "profile"), [(-3, 3, CIRCLE), (-3, 2, None)])
def test_coarse_rows_keep_the_assembly_of_a_fine_sweep(dx: float, dy: float, profile: str | None) -> None:
    scene = _scene(FLAT, profile, _moved(dx, dy))
    coarse = sweep(scene, steps=72, start=30.0, stop=390.0)
    fine = sweep(scene, steps=720, start=30.0, stop=390.0)
    assert np.array_equal(coarse.input.values, fine.input.values[::10])
    both = (coarse.status == 0) & (fine.status[::10] == 0)
    for name in ("theta_3", "theta_4", "theta_5", "r_W_x", "r_W_y"):
        gap = np.abs(coarse.column(name).values - fine.column(name).values[::10])[both]
        assert gap.max() <= 1e-9 * max(1.0, float(np.abs(fine.column(name).values).max())), name
    assert both.sum() >= 20 and (fine.status == 0).sum() >= 300  # and not by marking every row


def test_a_row_past_a_dead_point_is_marked_and_says_so() -> None:
    """Between 185 and 190 degrees this mechanism passes a dead point (with 0.01 degree rows it cannot be
    assembled from 187.81 degrees on, coming from below); the coarse rows beyond it are marked, not taken
    from the other side."""
    result = sweep(_scene(FLAT, CIRCLE, _moved(-2, 2)), steps=72, start=30.0, stop=390.0)
    marked = [k for k, text in result.warnings.items() if "meets a dead point" in text]
    assert marked and all(result.status[k] == 3 for k in marked)
    assert any(185.0 <= result.input.values[k] <= 190.0 for k in marked)
