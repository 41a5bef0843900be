"""What every call of a prepared sweep reads alike is found once (``PreparedSweep.layout``), and the short ways a
call takes give what the long ones give: the rows as ``np.linspace`` makes them, bit for bit; the columns of a sweep
whose rows are all ok as the general pass makes them; overflow told from one sum as from each array's."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinepoly
from kinepoly.engine.transmission import transmission_angles
from kinepoly.sweep import inputs, prepare_sweep, run, run_sweep
from kinepoly.sweep.columns import ColumnBuilder
from kinepoly.sweep.result import CANNOT_ASSEMBLE, SINGULAR

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

_ENDS = st.one_of(st.floats(-1e6, 1e6, allow_nan=False),
                  st.sampled_from([0.0, -0.0, 360.0, -180.0, 2 * np.pi, 5e-324]))


@settings(max_examples=300, deadline=None)
@given(_ENDS, _ENDS, st.integers(2, 5000), st.booleans())
def test_the_rows_are_linspace_bit_for_bit(start: float, stop: float, count: int, endpoint: bool) -> None:
    made = inputs._even(start, stop, count, endpoint)
    assert made.dtype == np.float64 and made.shape == (count,)
    assert made.tobytes() == np.linspace(start, stop, count, endpoint=endpoint).tobytes()


@pytest.mark.parametrize("start", [0.0, -0.0])
@pytest.mark.parametrize("stop", [360.0, -360.0])
def test_rows_from_a_zero_keep_its_sign_as_linspace_does(start: float, stop: float) -> None:
    """Rows from 0.0 up, or from -0.0 either way, are the product alone; from 0.0 down, the first row is -0.0 made
    +0.0 by adding the start."""
    for count, endpoint in ((3600, False), (37, True)):
        made = inputs._even(start, stop, count, endpoint)
        assert made.tobytes() == np.linspace(start, stop, count, endpoint=endpoint).tobytes()


def _builder(rows: int, extra: np.ndarray | None = None) -> ColumnBuilder:
    """A builder of a four-bar's positions with columns of every order, one of them with rows of its own."""
    prepared = prepare_sweep(kinepoly.load_scene(EXAMPLES / "four-bar.toml"))
    positions = run_sweep(prepared, steps=rows - 1, start=0.0, stop=90.0).positions
    assert positions is not None
    rng = np.random.default_rng(7)
    out = ColumnBuilder(prepared.mechanism, positions)
    out.add("theta_3", "angle", rng.normal(size=rows))
    out.pair("v_B", "velocity", rng.normal(size=rows) + 1j * rng.normal(size=rows))
    out.add("alpha_4", "alpha", rng.normal(size=rows), extra)
    out.pair("a_C", "acceleration", rng.normal(size=rows) + 1j * rng.normal(size=rows))
    return out


@pytest.mark.parametrize("hidden", [None, 0, 3])
@pytest.mark.parametrize("extra", [False, True])
def test_the_columns_of_ok_rows_are_those_of_the_general_pass(hidden: int | None, extra: bool) -> None:
    rows = 8
    own = np.arange(rows) % 3 != 1 if extra else None
    out = _builder(rows, own)
    shown = np.ones(rows, np.bool_)
    if hidden is not None:
        shown[hidden] = False
    every = hidden is None
    short = out.columns(None, shown, every)  # every row ok: the single pass where no column has rows of its own
    general = out.columns(np.zeros(rows, np.int8), shown, every)  # the same rows, through each row's level
    assert [c.name for c in short] == ["theta_3", "v_B_x", "v_B_y", "alpha_4", "a_C_x", "a_C_y"]
    for a, b in zip(short, general, strict=True):
        assert (a.name, a.kind) == (b.name, b.kind)
        assert a.values.dtype == np.float64 and a.values.tobytes() == b.values.tobytes()
        assert np.array_equal(a.valid, b.valid) and len(a.values) == int(shown.sum())
    alpha = short[3]
    kept = own[shown] if own is not None else np.ones(int(shown.sum()), np.bool_)
    assert np.array_equal(alpha.valid, kept) and not alpha.values[~kept].any()


@pytest.mark.parametrize("case", ["one", "cancelling", "not a number", "with a velocity"])
def test_overflow_is_found_in_any_column_of_the_highest_order(case: str) -> None:
    rows = 8
    out = _builder(rows)
    values = {name: column for name, _, column, _ in out.raw}
    expected = np.zeros(rows, np.int8)
    values["a_C_y"][5] = np.nan if case == "not a number" else np.inf
    expected[5] = SINGULAR
    if case == "cancelling":  # the sums of two columns of the highest order: inf and -inf
        values["alpha_4"][2] = -np.inf
        expected[2] = SINGULAR
    if case == "with a velocity":  # found once the highest order tells that something overflowed
        values["v_B_x"][1] = np.inf
        expected[1] = SINGULAR
    flags = run._Flags(np.zeros(rows, np.int8))
    run._overflow_flags(flags, np.ones(rows, np.bool_), out)
    assert np.array_equal(flags.level, expected)
    assert CANNOT_ASSEMBLE not in flags.level
    finite = _builder(rows)
    run._overflow_flags(flags := run._Flags(np.zeros(rows, np.int8)), np.ones(rows, np.bool_), finite)
    assert not flags.level.any() and not flags.reasons


def test_what_every_call_reads_alike_is_found_once(monkeypatch: pytest.MonkeyPatch) -> None:
    scene = kinepoly.load_scene(EXAMPLES / "four-bar.toml")
    prepared = prepare_sweep(scene)
    found = []
    pairs = run.transmission_pairs  # type: ignore[attr-defined]

    def counting(*args: object) -> object:
        found.append(args)
        return pairs(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(run, "transmission_pairs", counting)
    first, again = run_sweep(prepared, steps=36), run_sweep(prepared, steps=72, start=10.0, stop=80.0)
    assert len(found) == 1 and prepared.layout is prepared.layout
    for result in (first, again):
        assert result.positions is not None
        (angle,) = transmission_angles(result.positions, prepared.plan)  # the solve's way, every row
        mu = result.column("mu_B")
        assert np.array_equal(mu.values, np.degrees(angle.angle)[result.shown])


def test_a_triads_shape_is_found_once_for_the_plan(monkeypatch: pytest.MonkeyPatch) -> None:
    """A triad's ternary, legs and Assur point are found when the plan is made and once by its first construction,
    not again by each polygon of each call; the calls after give what the first gives."""
    from kinepoly.engine import triad as triads

    scene = kinepoly.load_scene(EXAMPLES / "triad.toml")
    prepared = prepare_sweep(scene)
    found: list[object] = []
    triad_of = triads.triad_of

    def counting(*args: object) -> object:
        found.append(args)
        return triad_of(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(triads, "triad_of", counting)
    first = run_sweep(prepared, steps=36, start=10.0, stop=80.0)
    assert len(found) == 1  # the first construction's; both polygons read it
    again = run_sweep(prepared, steps=36, start=10.0, stop=80.0)
    assert len(found) == 1
    for a, b in zip(first.columns, again.columns, strict=True):
        assert a.name == b.name and a.values.tobytes() == b.values.tobytes()
