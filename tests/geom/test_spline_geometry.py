"""The periodic cubic spline of a ``points`` profile (``geom.spline``) against derivations of its own:
the points it must pass through, continuity at every knot, a dense solve of its equations, closed
forms of circles and ellipses, and the order at which its error shrinks as points are added."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from kinepoly.geom.profile import outline
from kinepoly.geom.spline import CurveFrame, PeriodicSpline, periodic_spline, roots_along, signed_area
from kinepoly.scene.spec import CamSpec

A, B = 50.0, 30.0  # the ellipse's half axes


def _ellipse(n: int, a: float = A, b: float = B) -> list[tuple[float, float]]:
    return [(a * math.cos(2.0 * math.pi * k / n), b * math.sin(2.0 * math.pi * k / n)) for k in range(n)]


def _ellipse_errors(n: int) -> tuple[float, float, float]:
    """Worst distance from the ellipse, worst tangent angle and worst relative curvature error of the
    spline through ``n`` points of the ellipse, over a dense sampling of the spline."""
    spline = periodic_spline(_ellipse(n))
    frame = spline.frame(np.linspace(0.0, spline.period, 4001))
    x, y = frame.point.real, frame.point.imag
    # distance: the implicit function over its gradient (exact to second order in the distance, itself tiny)
    implicit = (x / A) ** 2 + (y / B) ** 2 - 1.0
    gradient = np.hypot(2.0 * x / A**2, 2.0 * y / B**2)
    distance = np.max(np.abs(implicit / gradient))
    # the ellipse's own tangent and curvature at the parameter of the nearest point (x = a cos t, y = b sin t)
    t = np.arctan2(y / B, x / A)
    tangent = -A * np.sin(t) + 1j * B * np.cos(t)
    angle = np.max(np.abs(np.angle(frame.tangent / tangent)))
    curvature = A * B / (A**2 * np.sin(t) ** 2 + B**2 * np.cos(t) ** 2) ** 1.5
    return float(distance), float(angle), float(np.max(np.abs(frame.curvature / curvature - 1.0)))


def _convex_points(draw: st.DrawFn) -> list[tuple[float, float]]:
    """4 to 24 points of a smooth convex closed curve, unevenly spaced, counter-clockwise."""
    n = draw(st.integers(4, 24))
    gaps = np.array(draw(st.lists(st.floats(0.3, 1.0), min_size=n, max_size=n)))
    angles = 2.0 * np.pi * np.cumsum(gaps) / np.sum(gaps)
    a, b = draw(st.floats(5.0, 80.0)), draw(st.floats(5.0, 80.0))
    cx, cy = draw(st.floats(-50.0, 50.0)), draw(st.floats(-50.0, 50.0))
    return [(cx + a * math.cos(t), cy + b * math.sin(t)) for t in angles]


convex_points = st.composite(_convex_points)


@settings(max_examples=60, deadline=None)
@given(convex_points())
def test_the_spline_passes_through_its_points_with_continuous_curvature(points: list[tuple[float, float]]) -> None:
    spline = periodic_spline(points)
    given_points = np.array([complex(x, y) for x, y in points])
    size = float(np.max(np.abs(given_points - given_points.mean())))
    assert np.max(np.abs(spline.point(spline.knots[:-1]) - given_points)) <= 1e-12 * size
    assert spline.period == pytest.approx(float(np.sum(np.abs(np.roll(given_points, -1) - given_points))), rel=1e-14)
    # each piece's end (its own polynomial at t = h) meets the next piece's start: point, r', r''
    h = np.diff(spline.knots)
    c = spline.coefficients
    end = c[:, 0] + h * c[:, 1] + h**2 * c[:, 2] + h**3 * c[:, 3]
    end_first = c[:, 1] + 2.0 * h * c[:, 2] + 3.0 * h**2 * c[:, 3]
    end_second = 2.0 * c[:, 2] + 6.0 * h * c[:, 3]
    start = np.roll(c, -1, axis=0)
    speed = float(np.max(np.abs(c[:, 1])))
    assert np.max(np.abs(end - start[:, 0])) <= 1e-11 * size
    assert np.max(np.abs(end_first - start[:, 1])) <= 1e-11 * speed
    assert np.max(np.abs(end_second - 2.0 * start[:, 2])) <= 1e-9 * float(np.max(np.abs(c[:, 2]))) + 1e-12


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(0.05, 20.0), min_size=3, max_size=40), st.integers(0, 2**31 - 1))
def test_the_second_derivatives_solve_the_periodic_system_written_densely(gaps: list[float], seed: int) -> None:
    # the n x n matrix of the periodic spline's equations, solved by numpy: the spline's M_k = 2 c_k
    rng = np.random.default_rng(seed)
    h = np.array(gaps)
    angles = 2.0 * np.pi * np.cumsum(h) / np.sum(h)
    radius = 10.0 * (1.0 + 0.3 * rng.random(len(h)))
    points = [(r * math.cos(t), r * math.sin(t)) for r, t in zip(radius, angles, strict=True)]
    z = np.array([complex(x, y) for x, y in points])
    chord = np.abs(np.roll(z, -1) - z)
    n = len(z)
    matrix = np.zeros((n, n))
    rhs = np.zeros(n, dtype=complex)
    for k in range(n):
        before, after = chord[k - 1], chord[k]
        matrix[k, (k - 1) % n] += before
        matrix[k, k] += 2.0 * (before + after)
        matrix[k, (k + 1) % n] += after
        rhs[k] = 6.0 * ((z[(k + 1) % n] - z[k]) / after - (z[k] - z[k - 1]) / before)
    dense = np.linalg.solve(matrix, rhs)
    spline = periodic_spline(points)
    assert np.max(np.abs(2.0 * spline.coefficients[:, 2] - dense)) <= 1e-10 * float(np.max(np.abs(dense)))


def test_the_error_shrinks_at_the_order_of_a_cubic_spline() -> None:
    # doubling the points divides the distance by about 16 (h^4), the tangent's angle by 8 (h^3),
    # the curvature's error by 4 (h^2); figures stated in docs/scene-format.md
    errors = {n: _ellipse_errors(n) for n in (32, 64, 128, 256)}
    for small, large in ((32, 64), (64, 128), (128, 256)):
        orders = [math.log2(e_small / e_large) for e_small, e_large in zip(errors[small], errors[large], strict=True)]
        assert orders[0] > 3.8 and orders[1] > 2.8 and orders[2] > 1.9, (small, orders)
    distance, angle, curvature = errors[64]
    assert distance < 3e-6 * A and angle < 2e-4 and curvature < 1e-2


def test_a_circle_through_its_points_has_its_centre_of_curvature_at_the_centre() -> None:
    radius, centre = 40.0, 12.0 - 5.0j
    points = [(centre.real + radius * math.cos(2 * math.pi * k / 48),
               centre.imag + radius * math.sin(2 * math.pi * k / 48))
              for k in range(48)]
    spline = periodic_spline(points)
    frame = spline.frame(np.linspace(0.0, spline.period, 997))
    assert not frame.is_straight.any()
    # curvature is the spline's least accurate quantity, O(h^2): here h = 2 pi R / 48
    assert np.max(np.abs(frame.centre_of_curvature - centre)) < 2e-3 * radius
    assert np.max(np.abs(frame.curvature * radius - 1.0)) < 2e-3
    # the normal points at the centre (ccw curve: the centre on the tangent's left)
    assert np.min(np.real(np.conj(frame.normal) * (centre - frame.point))) > 0.99 * radius


def test_a_straight_stretch_has_no_finite_centre_of_curvature() -> None:
    frame = CurveFrame(np.array([1.0 + 2.0j, 3.0 + 0.0j]), np.array([1.0 + 0.0j, 1.0j]), np.array([1.0j, -1.0 + 0.0j]),
                       np.array([0.0, 0.5]), 1.0 / 100.0)
    assert frame.is_straight.tolist() == [True, False]
    assert frame.centre_of_curvature.tolist() == [1.0 + 2.0j, 1.0 + 0.0j]  # 3 + (-1) / 0.5


@settings(max_examples=30, deadline=None)
@given(st.floats(-0.95, 0.95))
def test_roots_along_find_where_a_line_crosses_the_curve(fraction: float) -> None:
    # the line x = c crosses the ellipse at y = +-b sqrt(1 - (c/a)^2); the spline's crossings agree to its accuracy
    spline = periodic_spline(_ellipse(128))
    c = fraction * A
    roots = roots_along(spline, lambda u: spline.point(u).real - c)
    assert len(roots) == 2
    found = spline.point(roots)
    assert np.max(np.abs(found.real - c)) <= 1e-12 * A
    assert sorted(found.imag.tolist()) == pytest.approx(
        [-B * math.sqrt(1 - (c / A) ** 2), B * math.sqrt(1 - (c / A) ** 2)], abs=1e-5 * A)
    assert np.all((roots >= 0.0) & (roots < spline.period))


def test_roots_along_keep_roots_on_the_sampling_grid_and_see_no_graze() -> None:
    spline = periodic_spline(_ellipse(8))
    # x = 0 runs through two of the given points exactly (knots 2 and 6): found once each
    roots = roots_along(spline, lambda u: spline.point(u).real)
    assert roots.tolist() == pytest.approx([spline.knots[2], spline.knots[6]], abs=1e-12 * spline.period)
    # y = max(y) touches the curve without crossing it: a dead point, no assembly
    top = float(np.max(spline.point(np.linspace(0.0, spline.period, 20001)).imag))
    assert roots_along(spline, lambda u: spline.point(u).imag - (top + 1e-9)).size == 0


def test_periodic_spline_refuses_what_is_not_a_closed_curve() -> None:
    with pytest.raises(ValueError, match="at least 3 points"):
        periodic_spline([(0.0, 0.0), (1.0, 0.0)])
    with pytest.raises(ValueError, match="coincide"):
        periodic_spline([(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (0.0, 1.0)])


def test_outline_samples_a_spline_profile_from_its_first_point_counter_clockwise() -> None:
    points = tuple(_ellipse(12, 40.0, 40.0))
    cam = CamSpec("23", "2", "3", (0.0, 0.0), 0.0, "knife", point="W", profile_points=points)
    drawn = outline(cam, 120)
    assert len(drawn) == 120
    assert drawn[0] == pytest.approx(points[0], abs=1e-12)
    # every tenth sample is a given point (a circle's equal chords: the knots are equally spaced)
    assert [drawn[10 * k] for k in range(12)] == [pytest.approx(p, abs=1e-9) for p in points]
    assert signed_area(drawn) > 0.0
    assert isinstance(periodic_spline(points), PeriodicSpline)
    circle = CamSpec("23", "2", "3", (1.0, 2.0), 5.0, "knife", point="W")
    assert outline(circle, 4)[1] == pytest.approx((1.0, 7.0))


@settings(max_examples=40, deadline=None)
@given(convex_points(), st.floats(0.0, 2.0 * math.pi), st.floats(-0.9, 0.9))
def test_a_line_through_a_random_convex_profile_crosses_it_twice(points: list[tuple[float, float]], angle: float,
                                                                   offset: float) -> None:
    # a line through a point inside (on the way from the mean point to the curve's farthest point across
    # the line): two crossings, on the line to rounding, one each side of that point; the spline turns once
    spline = periodic_spline(points)
    assume(bool(np.all(spline.frame(np.linspace(0.0, spline.period, 4001)).curvature > 0.0)))  # a convex curve
    dense = spline.point(np.linspace(0.0, spline.period, 4001))
    direction = complex(math.cos(angle), math.sin(angle))
    across = np.imag(np.conj(direction) * (dense - dense.mean()))
    farthest = dense[np.argmax(across) if offset > 0 else np.argmin(across)]
    through = dense.mean() + abs(offset) * (farthest - dense.mean())
    def side(u: np.ndarray) -> np.ndarray:
        return np.asarray(np.imag(np.conj(direction) * (spline.point(u) - through)))
    roots = roots_along(spline, side)
    size = float(np.max(np.abs(dense - dense.mean())))
    assert len(roots) == 2
    assert np.max(np.abs(side(roots))) <= 1e-11 * size
    along = np.real(np.conj(direction) * (spline.point(roots) - through))
    assert along.min() < 0.0 < along.max()
    frame = spline.frame(np.linspace(0.0, spline.period, 64 * spline.pieces, endpoint=False))
    assert float(np.sum(np.angle(np.roll(frame.tangent, -1) / frame.tangent))) == pytest.approx(2.0 * math.pi)
