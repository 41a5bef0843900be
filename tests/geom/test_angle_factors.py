"""A product by ``RADIANS_PER_DEGREE`` or ``DEGREES_PER_RADIAN`` is ``np.radians`` or ``np.degrees`` bit for bit: on
doubles of every bit pattern (NaNs with their payloads, subnormals, infinities, signed zeros), on one row and many,
made new and in place."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinepoly.geom.arrays import DEGREES_PER_RADIAN, RADIANS_PER_DEGREE

SPECIAL = np.array([0.0, -0.0, math.inf, -math.inf, math.nan, 5e-324, -5e-324, 2.2250738585072014e-308,
                    1.7976931348623157e308, -1.7976931348623157e308, 90.0, 180.0, 360.0, math.pi, -math.pi])


def _bits(a: np.ndarray) -> bytes:
    return np.ascontiguousarray(a).tobytes()


def _check(values: np.ndarray) -> None:
    with np.errstate(all="ignore"):
        assert _bits(values * RADIANS_PER_DEGREE) == _bits(np.radians(values))
        assert _bits(values * DEGREES_PER_RADIAN) == _bits(np.degrees(values))
        in_place = values.copy()
        in_place *= DEGREES_PER_RADIAN
        assert _bits(in_place) == _bits(np.degrees(values))


@pytest.mark.parametrize("n", [1, 7, 3600])
def test_factors_are_numpys_conversions(n: int) -> None:
    rng = np.random.default_rng(n)
    patterns = rng.integers(np.iinfo(np.int64).min, np.iinfo(np.int64).max, n, dtype=np.int64, endpoint=True)
    for values in (patterns.view(np.float64), rng.uniform(-720.0, 720.0, n), rng.normal(0.0, 1e-300, n)):
        _check(values)
    for value in SPECIAL:
        _check(np.full(n, value))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True), min_size=1, max_size=40))
def test_factors_on_any_doubles(values: list[float]) -> None:
    _check(np.array(values, np.float64))


def test_the_check_tells_other_roundings_apart() -> None:
    """Other ways to the same factor round differently on the grid a sweep makes: the checks above would fail on
    them (pi / 180 applied in two steps, a factor one unit in the last place off, a division by the other factor)."""
    rows = np.linspace(0.0, 360.0, 3600, endpoint=False)
    factor = np.nextafter(RADIANS_PER_DEGREE, 1.0)
    for wrong in (rows * math.pi / 180.0, rows * factor, rows / DEGREES_PER_RADIAN):
        assert _bits(wrong) != _bits(np.radians(rows))
