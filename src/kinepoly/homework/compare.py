"""When is an answer right: the tolerance rule, one function per shape of value.

With ``relative`` and ``angle_deg`` from the answers file's ``[tolerance]`` and ``floor`` the
least size a value of that kind is judged against (1 % of the largest value of its kind in the
mechanism, so that a zero can be checked at all):

* a number (omega, alpha, s, s_dot, s_ddot): |given - expected| <= relative * max(|expected|, floor);
* a link's angle (theta): the difference, taken modulo 360 degrees, <= angle_deg;
* a vector (v, a): | |given| - |expected| | <= relative * max(|expected|, floor), and the angle
  between them <= angle_deg (or the whole difference |given - expected| within that same
  magnitude tolerance, which is what a vector too short to have a readable direction needs);
* an instant center: |given - expected| <= relative * max(size, |expected|), size the mechanism's;
  a center at infinity: its direction within angle_deg, either sense.

``closeness`` is the error over what is allowed (at most 1 when right); the diagnosis ranks the
mistakes it tries by it.
"""

from __future__ import annotations

import math

from msgspec import Struct

from kinepoly.homework.answers import Direction, Kind, Tolerance, Value

__all__ = ["Comparison", "compare"]


class Comparison(Struct, frozen=True):
    """Whether ``given`` is right, how close it is (error / allowed) and the error's parts for the report.

    ``error`` has ``relative`` (the error over the size it is judged against, so that the answer is
    right when it is at most the tolerance's ``relative``) and, for vectors and angles, ``angle_deg``.
    """

    is_correct: bool
    closeness: float
    error: dict[str, float]


def _ratio(error: float, allowed: float) -> float:
    if error <= allowed:
        return 0.0 if error == 0.0 else error / allowed
    return math.inf if allowed == 0.0 else error / allowed


def _angle_between(first: tuple[float, float], second: tuple[float, float]) -> float:
    """Degrees between two vectors, in [0, 180]."""
    return abs(math.degrees(math.atan2(first[0] * second[1] - first[1] * second[0],
                                       first[0] * second[0] + first[1] * second[1])))


def compare(kind: Kind, expected: Value, given: Value, tolerance: Tolerance, floor: float) -> Comparison:
    """Judge ``given`` against ``expected`` (internal units: radians for theta)."""
    if kind == "theta":
        assert isinstance(expected, float) and isinstance(given, float)
        off = abs(math.degrees(math.remainder(given - expected, 2.0 * math.pi)))
        closeness = _ratio(off, tolerance.angle_deg)
        return Comparison(closeness <= 1.0, closeness, {"angle_deg": off})
    if kind == "center":
        return _center(expected, given, tolerance, floor)
    if isinstance(expected, tuple) and isinstance(given, tuple):
        return _vector(expected, given, tolerance, floor)
    assert isinstance(expected, float) and isinstance(given, float)
    size = max(abs(expected), floor)
    closeness = _ratio(abs(given - expected), tolerance.relative * size)
    return Comparison(closeness <= 1.0, closeness,
                      {"absolute": given - expected, "relative": abs(given - expected) / size if size else math.inf})


def _vector(expected: tuple[float, float], given: tuple[float, float], tolerance: Tolerance,
            floor: float) -> Comparison:
    size = max(math.hypot(*expected), floor)
    allowed = tolerance.relative * size
    magnitude = abs(math.hypot(*given) - math.hypot(*expected))
    apart = math.dist(given, expected)
    has_directions = math.hypot(*given) > 0.0 and math.hypot(*expected) > 0.0
    angle = _angle_between(expected, given) if has_directions else math.nan
    by_angle = _ratio(angle, tolerance.angle_deg) if has_directions else math.inf
    closeness = max(_ratio(magnitude, allowed), min(by_angle, _ratio(apart, allowed)))
    error = {"absolute": apart, "relative": magnitude / size if size else math.inf}
    if has_directions:
        error["angle_deg"] = angle
    return Comparison(closeness <= 1.0, closeness, error)


def _center(expected: Value, given: Value, tolerance: Tolerance, size: float) -> Comparison:
    if isinstance(expected, Direction) or isinstance(given, Direction):
        if not (isinstance(expected, Direction) and isinstance(given, Direction)):
            return Comparison(False, math.inf, {})  # a point for a center at infinity, or the other way round
        angle = _angle_between((expected.x, expected.y), (given.x, given.y))
        off = min(angle, 180.0 - angle)
        closeness = _ratio(off, tolerance.angle_deg)
        return Comparison(closeness <= 1.0, closeness, {"angle_deg": off})
    assert isinstance(expected, tuple) and isinstance(given, tuple)
    scale = max(size, math.hypot(*expected))
    apart = math.dist(given, expected)
    closeness = _ratio(apart, tolerance.relative * scale)
    return Comparison(closeness <= 1.0, closeness,
                      {"absolute": apart, "relative": apart / scale if scale else math.inf})
