"""Units and quantities: plain numbers in the scene's units, or strings like ``"4 cm"``, ``"300 rpm"``.

A :class:`Kind` (length, velocity, acceleration, angle, angular velocity, angular
acceleration) says what a plain number means and which unit strings it takes;
:func:`kinds_for` makes them for a scene's ``[units]``. Lengths are stored in the scene's
length unit, angles in radians, angular velocities in rad/s and accelerations in rad/s^2.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from msgspec import Struct, field

from kinepoly.scene.lines import KeyPath
from kinepoly.scene.problems import ProblemReport, show_value, suggest
from kinepoly.scene.spec import Units
from kinepoly.scene.values import Vector, read_finite

__all__ = ["ANGLE_UNITS", "LENGTH_UNITS", "Kind", "Kinds", "kinds_for", "quantity", "quantity_pair"]

LENGTH_UNITS = ("mm", "cm", "m", "in")
ANGLE_UNITS = ("deg", "rad")
_MICROMETRES = {"mm": 1_000.0, "cm": 10_000.0, "m": 1_000_000.0, "in": 25_400.0}
_RADIANS = {"deg": math.pi / 180.0, "rad": 1.0}


class Kind(Struct, frozen=True):
    """A kind of quantity: how plain numbers and unit strings turn into the stored unit."""

    noun: str
    plain: str  # what a plain number means, e.g. "in mm"
    example: str
    units: Mapping[str, float]  # unit -> size in a base unit (µm, rad)
    per: float = 1.0  # base units per stored unit
    scale: float = 1.0  # stored units per plain number
    plain_unit: str = ""  # the unit a plain number is in, where whole turns can be taken off exactly
    whole_turns: Mapping[str, float] = field(default_factory=dict)  # unit -> one turn, removed before scaling

    def expected(self) -> str:
        return f'{self.noun} (a number {self.plain}, or a string like "{self.example}")'


class Kinds(Struct, frozen=True):
    length: Kind
    speed: Kind
    accel: Kind
    angle: Kind
    omega: Kind
    alpha: Kind


def kinds_for(units: Units) -> Kinds:
    lu = units.length
    per = _MICROMETRES[lu]
    speeds = {f"{u}/s": size for u, size in _MICROMETRES.items()}
    accels = {f"{u}/s{sq}": size for u, size in _MICROMETRES.items() for sq in ("^2", "²")}
    turns = {"rad/s": 1.0, "deg/s": math.pi / 180.0, "rpm": math.pi / 30.0}
    spins = {f"{u}/s{sq}": size for u, size in _RADIANS.items() for sq in ("^2", "²")}
    return Kinds(
        length=Kind("a length", f"in {lu}", f"40 {lu}", _MICROMETRES, per),
        speed=Kind("a velocity", f"in {lu}/s", f"-500 {lu}/s", speeds, per),
        accel=Kind("an acceleration", f"in {lu}/s^2", f"0 {lu}/s^2", accels, per),
        angle=Kind("an angle", f"in {units.angle}", "30 deg", _RADIANS, 1.0, _RADIANS[units.angle], units.angle,
                   {"deg": 360.0}),
        omega=Kind("an angular velocity", "in rad/s", "300 rpm", turns),
        alpha=Kind("an angular acceleration", "in rad/s^2", "2 rad/s^2", spins),
    )


_QUANTITY = re.compile(r"\s*(?P<number>[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*(?P<unit>\S+)?\s*", re.ASCII)


def quantity(report: ProblemReport, path: KeyPath, value: object, kind: Kind) -> float | None:
    """A number in the scene's unit, or a string with a unit; in the stored unit."""
    if isinstance(value, str):
        return _unit_string(report, path, value, kind)
    number = read_finite(report, path, value, kind.expected())
    return None if number is None else _without_turns(number, kind.plain_unit, kind) * kind.scale


def _without_turns(number: float, unit: str, kind: Kind) -> float:
    """Whole turns taken off exactly (fmod is exact): 60 + 360e9 deg becomes 60 deg, not 60 deg +- 1e-6."""
    turn = kind.whole_turns.get(unit)
    return math.fmod(number, turn) if turn else number


def _unit_string(report: ProblemReport, path: KeyPath, text: str, kind: Kind) -> float | None:
    match = _QUANTITY.fullmatch(text)
    if match is None or match.group("unit") is None:
        report.add(path, f"expected {kind.expected()}, got {show_value(text)}")
        return None
    unit = match.group("unit")
    size = kind.units.get(unit)
    if size is None:
        report.add(path, lambda: f'unknown unit "{unit}" for {kind.noun} in {show_value(text)}; '
                                 f'{suggest(unit, kind.units)}')
        return None
    stored = _without_turns(float(match.group("number")), unit, kind) * size / kind.per
    if not math.isfinite(stored):
        report.add(path, f"{show_value(text)} is too large; expected {kind.expected()}")
        return None
    return stored


def quantity_pair(report: ProblemReport, path: KeyPath, value: object, kind: Kind) -> Vector | None:
    """``[x, y]``, each a quantity of ``kind``."""
    if not isinstance(value, list) or len(value) != 2:
        report.add(path, f"expected [x, y], each {kind.noun}, got {show_value(value)}")
        return None
    x = quantity(report, path + ("x",), value[0], kind)
    y = quantity(report, path + ("y",), value[1], kind)
    return None if x is None or y is None else (x, y)
