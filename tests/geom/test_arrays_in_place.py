"""The array kernels that write steps in place (``geom.arrays``: arrays made in place) give the bits of their plain
formulas, written here as they read, one new array per step: on one row (a solve) and on many (a sweep), on fixed
and random circles and lines."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinepoly.geom.arrays import circle_circle, cross_lines, length

finite = st.floats(min_value=-1e4, max_value=1e4, allow_nan=False, allow_infinity=False)
radius = st.floats(min_value=0.0, max_value=1e4, allow_nan=False, allow_infinity=False)


def _plain_circle_circle(c1: np.ndarray, r1: float, c2: np.ndarray, r2: float) -> tuple[np.ndarray, ...]:
    d_vec = c2 - c1
    d = np.abs(d_vec)
    inverse = 1.0 / d
    a = (d * d + (r1 - r2) * (r1 + r2)) * (0.5 * inverse)
    slack = (r1 - a) * (r1 + a)
    h = np.sqrt(np.maximum(slack, 0.0))
    base = c1 + d_vec * (a * inverse)
    offset = (1j * d_vec) * (h * inverse)
    return base + offset, base - offset, slack, d, h


def _plain_cross_point(through1: np.ndarray, direction1: np.ndarray, through2: np.ndarray,
                       direction2: np.ndarray) -> np.ndarray:
    c2 = (np.conjugate(through2 - through1) * direction2).imag
    w = (direction1.conjugate() * direction2).imag
    return through1 + direction1 * (c2 / w)


def _same_bits(got: tuple[np.ndarray, ...], want: tuple[np.ndarray, ...]) -> None:
    for g, w in zip(got, want, strict=True):
        g, w = np.asarray(g), np.asarray(w)
        assert g.dtype == w.dtype and g.shape == w.shape
        assert g.tobytes() == w.tobytes(), (g, w)


def _points(rng: np.random.Generator, n: int, scale: float) -> np.ndarray:
    return rng.normal(0.0, scale, n) + 1j * rng.normal(0.0, scale, n)


@pytest.mark.parametrize("n", [1, 2, 7, 36, 3600])
def test_circle_circle_is_its_plain_formula(n: int) -> None:
    rng = np.random.default_rng(n)
    for scale in (1e-3, 1.0, 100.0, 1e5):
        c1, c2 = _points(rng, n, scale), _points(rng, n, scale)
        r1, r2 = float(rng.uniform(0.0, 2.0 * scale)), float(rng.uniform(0.0, 2.0 * scale))
        with np.errstate(all="ignore"):
            _same_bits(circle_circle(c1, r1, c2, r2), _plain_circle_circle(c1, r1, c2, r2))


@pytest.mark.parametrize("n", [1, 2, 7, 36, 3600])
def test_cross_lines_is_its_plain_formula(n: int) -> None:
    rng = np.random.default_rng(100 + n)
    through1, through2 = _points(rng, n, 50.0), _points(rng, n, 50.0)
    direction1, direction2 = _points(rng, n, 1.0), _points(rng, n, 1.0)
    with np.errstate(all="ignore"):
        crossing = cross_lines(through1, direction1, through2, direction2)
        _same_bits((crossing.point,), (_plain_cross_point(through1, direction1, through2, direction2),))
        assert crossing.sin_angle.tobytes() == np.asarray(
            crossing.w / (length(direction1) * length(direction2))).tobytes()


def test_a_row_where_the_circles_miss_or_coincide_keeps_its_bits() -> None:
    """Circles apart, one inside the other, touching, and with one centre (slack not a number): the same bits."""
    c1 = np.array([0j, 0j, 0j, 1 + 1j, -0.0 - 0.0j])
    c2 = np.array([10 + 0j, 1 + 0j, 5 + 0j, 1 + 1j, 0j])
    with np.errstate(all="ignore"):
        _same_bits(circle_circle(c1, 2.0, c2, 3.0), _plain_circle_circle(c1, 2.0, c2, 3.0))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(finite, finite, finite, finite), min_size=1, max_size=9), radius, radius)
def test_random_circles_keep_the_bits_of_the_plain_formula(centres: list[tuple[float, float, float, float]],
                                                          r1: float, r2: float) -> None:
    c1 = np.array([complex(x, y) for x, y, _, _ in centres])
    c2 = np.array([complex(x, y) for _, _, x, y in centres])
    with np.errstate(all="ignore"):
        _same_bits(circle_circle(c1, r1, c2, r2), _plain_circle_circle(c1, r1, c2, r2))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(finite, finite, finite, finite, finite, finite, finite, finite), min_size=1, max_size=9))
def test_random_lines_cross_at_the_bits_of_the_plain_formula(
        rows: list[tuple[float, float, float, float, float, float, float, float]]) -> None:
    t1, d1, t2, d2 = (np.array([complex(row[2 * k], row[2 * k + 1]) for row in rows]) for k in range(4))
    with np.errstate(all="ignore"):
        _same_bits((cross_lines(t1, d1, t2, d2).point,), (_plain_cross_point(t1, d1, t2, d2),))
