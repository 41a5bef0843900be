"""What the positions make once for the polygons built on them: the sine of two turned chords' crossing
(``Positions.chord_sine``: the bits ``geom.arrays.cross_lines`` makes of them, the same array for the velocity and the
acceleration polygon's crossing of the same two lines, none where a length is measured or differs by row), a chord
from the frame's origin (its end point itself), and the zeros of the pole and the frame's rate."""

from __future__ import annotations

import numpy as np
from tests.scenes import EXAMPLES

from kinepoly.engine.acceleration import construct_acceleration
from kinepoly.engine.placement import Positions
from kinepoly.engine.polygon import LineCrossing
from kinepoly.engine.velocity import construct_velocity
from kinepoly.geom.arrays import cross_lines
from kinepoly.scene.loader import load_scene
from kinepoly.sweep import PreparedSweep, prepare_sweep, run_sweep


def _positions() -> tuple[PreparedSweep, Positions]:
    prepared = prepare_sweep(load_scene(EXAMPLES / "four-bar.toml"))
    result = run_sweep(prepared, steps=36, start=0.0, stop=360.0)
    assert result.positions is not None
    return prepared, result.positions


def test_the_sine_is_cross_lines_own_and_made_once_per_lengths() -> None:
    _, positions = _positions()
    first, second = positions.chord("A", "B")[1], positions.chord("B0", "B")[1]
    product = positions.chord_product(first, second)
    assert product is not None
    sine = positions.chord_sine(product, 120.0, 80.0)
    assert sine is not None
    own = cross_lines(positions.point("A"), first, positions.point("B0"), second, 120.0, 80.0, product).sin_angle
    assert sine.tobytes() == own.tobytes()
    assert positions.chord_sine(product, 120.0, 80.0) is sine
    other = positions.chord_sine(product, 1.0, 80.0)  # other lengths: another sine, not the one kept
    assert other is not None and other.tobytes() == (product.imag / 80.0).tobytes()
    assert other.tobytes() != sine.tobytes()
    assert positions.chord_sine(product, None, 80.0) is None
    assert positions.chord_sine(product, np.full(36, 120.0), 80.0) is None  # type: ignore[arg-type]
    assert positions.chord_sine(None, 120.0, 80.0) is None


def test_both_polygons_cross_the_same_lines_at_one_sine_of_the_plain_bits() -> None:
    prepared, positions = _positions()
    velocity = construct_velocity(positions, prepared.plan)
    acceleration = construct_acceleration(velocity, prepared.plan)
    (v,), (a,) = velocity.polygon.crossings, acceleration.polygon.crossings
    assert isinstance(v, LineCrossing) and isinstance(a, LineCrossing)
    assert v.sin_angle is a.sin_angle
    first, second = positions.chord("A", "B")[1], positions.chord("B0", "B")[1]
    plain = (first.conjugate() * second).imag / (np.abs(first) * np.abs(second))  # lengths measured: near, not same
    assert np.allclose(v.sin_angle, plain, rtol=1e-13, atol=0.0)
    assert v.sin_angle.tobytes() == ((first.conjugate() * second).imag / (120.0 * 80.0)).tobytes()


def test_a_chord_from_the_frames_origin_is_its_end_point() -> None:
    """A chord from the frame's point at its origin (+0 at every row) is its end point, bit for bit what the
    subtraction gives; from any other point, the subtraction's own array."""
    _, positions = _positions()
    frame = positions.poses["1"]
    origin = frame.made(0j)
    assert origin is not None and origin is positions.point("A0")
    assert not np.signbit(origin.real).any() and not np.signbit(origin.imag).any()
    r, turned = positions.chord("A0", "A")
    assert r is positions.point("A")
    assert r.tobytes() == (positions.point("A") - positions.point("A0")).tobytes()
    assert turned.tobytes() == (1j * r).tobytes()
    r, _ = positions.chord("B0", "B")
    assert r is not positions.point("B")
    assert r.tobytes() == (positions.point("B") - positions.point("B0")).tobytes()
    assert frame.made(complex(-0.0, 0.0)) is None  # -0 is another point: not made


def test_both_polygons_share_the_zeros_of_their_positions() -> None:
    prepared, positions = _positions()
    velocity = construct_velocity(positions, prepared.plan)
    acceleration = construct_acceleration(velocity, prepared.plan)
    zero, zero_rate = positions.zeros()
    assert velocity.polygon.zero is zero and acceleration.polygon.zero is zero
    assert velocity.omega["1"] is zero_rate and acceleration.alpha["1"] is zero_rate
    assert not zero.any() and not zero_rate.any() and len(zero) == len(positions.ok)


def test_every_ok_is_ok_at_every_row() -> None:
    _, positions = _positions()
    assert positions.every_ok() is True
    some = Positions(positions.mechanism, positions.poses, np.array([True] * 35 + [False]))
    assert some.every_ok() is False and some.every_ok() is False
    assert Positions(positions.mechanism, positions.poses, np.ones(0, np.bool_)).every_ok() is True
