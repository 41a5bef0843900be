"""A range's search wants only the run of rows that close about the scene's input: a group solved by Newton's
method, walked row by row, stops each way at the first row that does not close (``Continuity.run_only``). The
range found is the one the whole walk finds, to the bit, and far fewer rows are solved."""

from __future__ import annotations

from pathlib import Path

import pytest

import kinepoly
from kinepoly.engine.groups import NewtonGroup
from kinepoly.engine.newton_walk import Walk
from kinepoly.scene.spec import GivenInput
from kinepoly.sweep import inputs, prepare_sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
NEWTON = ("crank-rocker-cylinder", "differential", "kc0-six-bar", "planetary-free-arm", "platform-lift",
          "spline-cam-floating-flat", "spline-cam-floating-sleeve", "spline-cam-floating-triad", "triad-slot", "triad")
"""The examples whose plans hold a group solved by Newton's method."""
SLOW = {"platform-lift"}
"""Its whole walk over the search's grid solves some 4,000 rows by Newton's method: seconds."""
SKIPPED = {"crank-rocker-cylinder"}
"""Left out: its whole walk costs as much as the lifting platform's, whose slider stroke takes the same path."""


def _search(name: str, monkeypatch: pytest.MonkeyPatch, whole: bool) -> tuple[inputs.DefaultRange, int]:
    """The default range, and how many rows the Newton groups' walks solved (``whole``: every row of the grid)."""
    prepared = prepare_sweep(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    seed = prepared.seed
    evaluate = inputs._evaluate
    rows = [0]
    walk_row = Walk.row

    def counting(self: Walk, row: int) -> object:
        rows[0] += 1
        return walk_row(self, row)

    def evaluate_whole(*args: object, run_only: bool = False, **kwargs: object) -> object:
        return evaluate(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(Walk, "row", counting)
    if whole:
        monkeypatch.setattr(inputs, "_evaluate", evaluate_whole)
    found = inputs.default_range(prepared.mechanism, prepared.plan, seed)
    monkeypatch.undo()
    return found, rows[0]


def test_the_examples_with_newton_groups_are_these() -> None:
    found = []
    for path in sorted(EXAMPLES.glob("*.toml")):
        scene = kinepoly.load_scene(path)
        if scene.input is not None and not isinstance(scene.input, GivenInput):
            found += [path.stem] if any(isinstance(g, NewtonGroup) for g in prepare_sweep(scene).plan.groups) else []
    assert sorted(found) == sorted(NEWTON)


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n
                                  for n in NEWTON if n not in SKIPPED])
def test_the_run_alone_gives_the_whole_walks_range(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    run, run_rows = _search(name, monkeypatch, whole=False)
    whole, whole_rows = _search(name, monkeypatch, whole=True)
    assert run == whole  # ends, periodicity, notices and margins, to the bit
    assert run_rows <= whole_rows
    if name in SLOW:  # a slider's stroke within a grid of ten times the mechanism's size each way
        assert run_rows * 5 < whole_rows
