"""The pieces every edit of a scene's text uses: its error, a place from the mouse, a number as the user writes
it, a value stored into a table keeping its formatting."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, TypeGuard

from tomlkit.items import Array

if TYPE_CHECKING:
    from kinepoly.solution import Solution

__all__ = ["EditError", "decimals", "is_finite_number", "number", "pair", "place", "store", "tidy"]

_DECIMALS = {"mm": 2, "cm": 3, "in": 3, "m": 5}
"""The decimals a length is written to from the mouse: a hundredth of a millimetre, whatever the unit."""


class EditError(ValueError):
    """An edit that cannot be made on this text: an unknown point or key, a value of the wrong kind."""


def decimals(solution: Solution) -> int:
    """The decimals a length of this scene is written to from the mouse."""
    return _DECIMALS.get(solution.scene.units.length, 4)


def pair(solution: Solution, at: Sequence[float]) -> list[float]:
    """A place or coordinates as the scene writes them from the mouse (``_DECIMALS``)."""
    d = decimals(solution)
    return [tidy(round(at[0], d)), tidy(round(at[1], d))]


def tidy(x: float) -> float:
    """``x``, a zero written without its sign."""
    return 0.0 if x == 0 else x


def store(table: Any, key: str, value: Any) -> None:
    """``table[key] = value``, an existing list of numbers changed in place (its formatting kept)."""
    old = table.get(key)
    if isinstance(old, Array) and isinstance(value, list) and len(old) == len(value) and \
            all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in old):
        for i, x in enumerate(value):
            old[i] = number(x)
        return
    table[key] = [number(x) for x in value] if isinstance(value, list) else number(value)


def number(x: Any) -> Any:
    """A number as the user writes it: a whole float as an integer."""
    if isinstance(x, float) and x.is_integer() and abs(x) < 1e15:
        return int(x)  # written as the user would: 40, not 40.0
    return x


def is_finite_number(x: object) -> TypeGuard[int | float]:
    """Whether ``x`` is a number (not a bool) a float holds finite: JSON's whole numbers have no bound."""
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return False
    try:
        return math.isfinite(float(x))
    except OverflowError:
        return False


def place(to: object) -> tuple[float, float]:
    """An edit's place ``[x, y]``; EditError when it is not one."""
    if not (isinstance(to, list) and len(to) == 2 and all(is_finite_number(x) for x in to)):
        raise EditError(f"{to!r} is not a place; expected [x, y] in the scene's length unit")
    return float(to[0]), float(to[1])
