"""A sweep's columns where every row is ok: each column's values as the stage gave them (as doubles) under one mask,
unless a column has rows of its own without a value, which the builder notes as the column comes in."""

from __future__ import annotations

import numpy as np
from tests.scenes import EXAMPLES

from kinepoly.geom.arrays import trues
from kinepoly.scene.loader import load_scene
from kinepoly.sweep import prepare_sweep, run_sweep
from kinepoly.sweep.columns import ColumnBuilder


def _builder() -> ColumnBuilder:
    prepared = prepare_sweep(load_scene(EXAMPLES / "four-bar.toml"))
    result = run_sweep(prepared, steps=8, start=0.0, stop=360.0)
    assert result.positions is not None
    return ColumnBuilder(prepared.mechanism, result.positions)


def test_a_column_with_rows_of_its_own_keeps_its_mask_however_it_comes_in() -> None:
    values = np.arange(8.0) + 1.0
    own = np.array([True, False] * 4)
    shown = trues(8)
    for add in ("add", "extend"):
        out = _builder()
        out.add("plain", "angle", values.copy())
        if add == "add":
            out.add("masked", "angle", values.copy(), own)
        else:  # told nothing: the builder looks
            out.extend((("masked", "angle", values.copy(), own),), (("angle", values),))
        plain, masked = out.columns(None, shown, True)
        assert plain.valid.all() and np.array_equal(plain.values, values)
        assert np.array_equal(masked.valid, own)
        assert np.array_equal(masked.values, np.where(own, values, 0.0))


def test_plain_columns_are_doubles_as_given() -> None:
    out = _builder()
    given = np.linspace(0.0, 1.0, 8)
    out.add("doubles", "angle", given)
    out.add("whole", "angle", np.arange(8))  # type: ignore[arg-type]  # a stage's integers: made doubles
    doubles, whole = out.columns(None, trues(8), True)
    assert doubles.values is given
    assert whole.values.dtype == np.float64 and np.array_equal(whole.values, np.arange(8.0))
    shown = np.array([True, True, False, True, True, True, True, False])
    doubles, whole = out.columns(None, shown, False)
    assert np.array_equal(doubles.values, given[shown]) and whole.values.dtype == np.float64
    assert doubles.valid.all() and len(doubles.valid) == 6


def test_trues_is_a_fresh_mask_of_every_row() -> None:
    for n in (0, 1, 36, np.int64(3600)):
        mask = trues(n)
        assert mask.dtype == np.bool_ and mask.shape == (int(n),) and mask.all()
        assert mask.flags.writeable and mask.flags.owndata
    first, second = trues(4), trues(4)
    first[0] = False
    assert second[0]
