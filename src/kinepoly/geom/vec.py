"""Plain 2D vector helpers over (x, y) tuples; pure functions, no state."""

from __future__ import annotations

import math

__all__ = ["Vec", "add", "angle_of", "cross", "dot", "magnitude", "norm", "perp", "phase", "rotate", "scale", "sub",
           "unit"]

Vec = tuple[float, float]


def phase(z: complex) -> float:
    """The angle of ``z`` in (-pi, pi]: ``cmath.phase`` without its OverflowError on a subnormal part."""
    return math.atan2(z.imag, z.real)


def magnitude(z: complex) -> float:
    """|z|, infinity where it overflows double precision (``abs`` of a complex raises OverflowError there)."""
    return math.hypot(z.real, z.imag)


def add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1])


def sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1])


def scale(k: float, a: Vec) -> Vec:
    return (k * a[0], k * a[1])


def dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1]


def cross(a: Vec, b: Vec) -> float:
    """z-component of a x b: positive when b lies counter-clockwise of a."""
    return a[0] * b[1] - a[1] * b[0]


def norm(a: Vec) -> float:
    return math.hypot(a[0], a[1])


def unit(a: Vec) -> Vec:
    n = norm(a)
    if n == 0.0:
        raise ZeroDivisionError("the zero vector has no direction")
    return (a[0] / n, a[1] / n)


def perp(a: Vec) -> Vec:
    """a turned 90 degrees counter-clockwise (k x a)."""
    return (-a[1], a[0])


def rotate(a: Vec, angle_rad: float) -> Vec:
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    return (c * a[0] - s * a[1], s * a[0] + c * a[1])


def angle_of(a: Vec) -> float:
    """Direction angle of a in radians, in (-pi, pi]."""
    return math.atan2(a[1], a[0])
