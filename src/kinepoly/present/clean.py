"""The number rule: how every number meant for people is shown.

A value within its error estimate of zero is 0; a value within its estimate of a short decimal is
that decimal (``tidy``: 49.99999999999999 with an estimate of 1e-13 is 50, 210.00000000000003
written back to a scene is 210). A driven value is given, not computed: it is shown as the scene
gives it (``Solution.slider`` and the sweep's columns echo a driven slider's s, s_dot and s_ddot;
``given_angle`` turns a stored angle back into the number written in the scene's unit).

The JSON keeps the computed floats (the driven values aside, echoed exactly); the table, the steps,
the title block, the handouts and the answer keys print what ``Noise`` leaves. A quantity's floor
is its kind's estimated relative error (``Solution.accuracy``) times the natural size of that kind
in the scene (the cross-check's normwise scale): an x-coordinate of 1.4e-14 mm in a 200 mm
mechanism, a triad's angle of 4.8e-14 degrees or a unit direction's 6.1e-17 are all below it, and
print as 0. A sweep's columns take the same rule with the sweep's estimate (``sweep.shown``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from msgspec import Struct, field

from kinepoly.geom.tolerances import UNIT_ROUNDOFF

if TYPE_CHECKING:
    from kinepoly.solution import Solution

__all__ = ["KINDS", "Noise", "clean", "format_number", "given_angle", "noise_of", "roundoff", "tidy"]

KINDS = ("position", "angle", "direction", "velocity", "omega", "instant_center", "acceleration", "alpha")
"""The kinds of printed quantities: those of the cross-check, and ``direction`` (a unit vector)."""

_CLASS = {"position": "position", "angle": "position", "direction": "position", "velocity": "velocity",
          "omega": "velocity", "instant_center": "velocity", "acceleration": "acceleration", "alpha": "acceleration"}

_MIN_RELATIVE = 16.0 * UNIT_ROUNDOFF
"""No kind's estimate is taken below a few units of roundoff (a quantity computed in one operation)."""


def clean(value: float, scale: float, relative: float) -> float:
    """``value``, or 0 where its magnitude is below ``relative`` times ``scale`` (its error estimate).

    -0.0 becomes 0.0; infinities and NaN pass unchanged.
    """
    if not math.isfinite(value):
        return value
    return 0.0 if abs(value) <= abs(scale) * relative else value + 0.0


def tidy(value: float, error: float) -> float:
    """The number rule: 0 where ``|value| <= error``; else the decimal of fewest significant digits within
    ``error`` of ``value`` (``value`` itself where none is nearer than the last digit).

    ``error`` is the value's absolute error estimate (>= 0); -0.0 becomes 0.0; infinities and NaN pass.
    """
    if not math.isfinite(value):
        return value
    error = abs(error) if math.isfinite(error) else 0.0
    if abs(value) <= error:
        return 0.0
    for digits in range(17):
        shorter = float(f"{value:.{digits}e}")
        if abs(shorter - value) <= error:
            return shorter + 0.0
    return value + 0.0


def roundoff(value: float, units: float = 4.0) -> float:
    """The error estimate of a value computed in a few floating-point operations from exact numbers
    (a unit conversion, a scale factor): ``units`` units in its last place."""
    return units * math.ulp(value) if math.isfinite(value) else 0.0


def given_angle(radians: float, unit: str) -> float:
    """A stored angle in the scene's ``unit`` as the scene wrote it: the decimal of fewest digits whose
    conversion to radians is ``radians`` itself (60 degrees, not 59.99999999999999; 210, not
    210.00000000000003). In radians, ``radians``."""
    if unit != "deg" or not math.isfinite(radians):
        return radians + 0.0
    degrees = math.degrees(radians)
    for digits in range(17):
        shorter = float(f"{degrees:.{digits}e}")
        if math.radians(shorter) == radians:
            return shorter + 0.0
    return degrees + 0.0


class Noise(Struct, frozen=True):
    """The absolute error floor of each kind (the unit of the kind: mm, rad, mm/s, ...)."""

    floors: Mapping[str, float] = field(default_factory=dict)

    def floor(self, kind: str) -> float:
        return self.floors.get(kind, 0.0)

    def value(self, x: float, kind: str) -> float:
        """``x`` of ``kind`` by the number rule (``tidy``), its floor the error estimate."""
        return tidy(x, self.floor(kind))

    def pair(self, v: Sequence[float], kind: str) -> tuple[float, float]:
        """A vector of ``kind`` with each component below the floor set to 0."""
        return self.value(v[0], kind), self.value(v[1], kind)

    def degrees(self, x: float) -> float:
        """An angle already in degrees by the number rule, its estimate the angle floor (kept in radians)."""
        return tidy(x, math.degrees(self.floor("angle")))


def _scales(solution: Solution) -> dict[str, float]:
    from kinepoly.solution import _natural_scales

    natural = _natural_scales(solution)
    scales = {kind: max(solution.check.scales.get(kind, 0.0), natural.get(kind, 0.0)) for kind in KINDS}
    scales["angle"] = scales["direction"] = 1.0
    return {kind: s if s > 0.0 and math.isfinite(s) else 1.0 for kind, s in scales.items()}


def _relative(solution: Solution) -> dict[str, float]:
    estimated = dict(solution.accuracy.estimated) if solution.accuracy is not None else {}
    by_class: dict[str, float] = {}
    for kind, rel in estimated.items():
        if kind in _CLASS:
            by_class[_CLASS[kind]] = max(by_class.get(_CLASS[kind], 0.0), rel)
    fallback = max(estimated.values(), default=_MIN_RELATIVE)
    out = {}
    for kind in KINDS:
        rel = estimated.get(kind, by_class.get(_CLASS[kind], fallback))
        out[kind] = max(rel, _MIN_RELATIVE) if math.isfinite(rel) else _MIN_RELATIVE
    return out


def noise_of(solution: Solution) -> Noise:
    """Each kind's floor in ``solution``: its estimated relative error times its natural size."""
    scales, relative = _scales(solution), _relative(solution)
    return Noise({kind: scales[kind] * relative[kind] for kind in KINDS})


def format_number(x: float) -> str:
    """Fixed-point with about five significant digits; an exponent only when very large or small."""
    if x == 0.0 or not math.isfinite(x):
        return "0" if x == 0.0 else str(x)
    a = abs(x)
    if a >= 1e7 or a < 1e-4:
        return f"{x:.4e}"
    decimals = max(0, 4 - math.floor(math.log10(a)))
    text = f"{x:.{decimals}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text
