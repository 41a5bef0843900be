"""Issue 13, item 7: N positions are N equal intervals; the asymptote stops at ten times the size."""

from __future__ import annotations

import numpy as np
import pytest
from tests.scenes import EXAMPLES

from kinepoly.scene.loader import load_scene
from kinepoly.sweep.run import sweep


def test_a_full_turn_in_360_intervals_is_one_degree_apart_without_repeating() -> None:
    result = sweep(load_scene(EXAMPLES / "four-bar.toml"), steps=360, start=0.0, stop=360.0)
    x = result.input.values
    assert len(x) == 360 and result.periodic
    assert np.allclose(x, np.arange(360.0))
    assert 135.0 in x and 250.0 in x


def test_a_range_has_both_ends() -> None:
    result = sweep(load_scene(EXAMPLES / "four-bar.toml"), steps=90, start=0.0, stop=90.0)
    assert np.allclose(result.input.values, np.arange(91.0))


def test_the_slotted_crank_stops_at_ten_times_its_size_with_a_warning() -> None:
    result = sweep(load_scene(EXAMPLES / "slotted-crank-slider.toml"), steps=72)
    assert any(n.code == "open-range" for n in result.notices)
    for column in result.columns:
        if column.name.startswith("r_"):
            assert np.max(np.abs(column.values)) <= 10 * 80 + 100, column.name


@pytest.mark.parametrize("steps", [1])
def test_too_few_intervals_is_a_scene_error(steps: int) -> None:
    from kinepoly.errors import SceneError

    with pytest.raises(SceneError, match="--positions"):
        sweep(load_scene(EXAMPLES / "four-bar.toml"), steps=steps)
