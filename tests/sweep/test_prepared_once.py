"""What a sweep needs once per scene is found once: the default range is searched once for every call on a prepared
sweep (and for ``cycle_turns``), and ``kinepoly.sweep.sweep`` keeps a scene's prepared sweep for the calls that
follow; the results are those of a sweep prepared afresh."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import kinepoly
from kinepoly.sweep import SweepResult, cycle_turns, inputs, prepare_sweep, run_sweep, sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _same(a: SweepResult, b: SweepResult) -> None:
    assert np.array_equal(a.input.values, b.input.values)
    assert np.array_equal(a.status, b.status)
    assert a.warnings == b.warnings and a.notices == b.notices
    for x, y in zip(a.columns, b.columns, strict=True):
        assert x.name == y.name
        assert np.array_equal(x.values, y.values) and np.array_equal(x.valid, y.valid)


@pytest.mark.parametrize("name", ["four-bar", "gear-pair", "slider-crank"])
def test_the_default_range_is_searched_once(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    fresh = [run_sweep(prepare_sweep(scene), steps=steps) for steps in (36, 72)]
    searches = []
    search = inputs._default_range

    def counting(*args: object) -> object:
        searches.append(args)
        return search(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(inputs, "_default_range", counting)
    prepared = prepare_sweep(scene)
    cycle_turns(prepared)
    again = [run_sweep(prepared, steps=steps) for steps in (36, 72)]
    assert len(searches) == 1
    for a, b in zip(fresh, again, strict=True):
        _same(a, b)


def test_a_repeated_sweep_of_one_scene_is_prepared_once(monkeypatch: pytest.MonkeyPatch) -> None:
    scene = kinepoly.load_scene(EXAMPLES / "four-bar.toml")
    first = sweep(scene, steps=36, start=10.0, stop=50.0)
    from kinepoly.sweep import run

    def not_again(*args: object, **kwargs: object) -> object:
        raise AssertionError("prepared again")

    monkeypatch.setattr(run, "prepare_sweep", not_again)
    _same(first, sweep(scene, steps=36, start=10.0, stop=50.0))
    _same(run_sweep(run.prepared_sweep(scene), steps=36), sweep(scene, steps=36))
