"""Plain TOML values checked and reported: tables, their keys, names and finite numbers.

Each function takes the :class:`~kinepoly.scene.problems.ProblemReport`, the key path and
the value; it returns the value in its strict type, or None after reporting what is wrong.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from typing import cast

from kinepoly.scene.lines import KeyPath
from kinepoly.scene.problems import ProblemReport, show_value, suggest
from kinepoly.scene.source import Table

__all__ = ["Vector", "check_keys", "pair_name", "read_finite", "read_name", "read_table", "require"]

Vector = tuple[float, float]


def read_finite(report: ProblemReport, path: KeyPath, value: object, expected: str) -> float | None:
    """A TOML number (int or float, not bool) as a finite float."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        report.add(path, f"expected {expected}, got {show_value(value)}")
        return None
    try:
        number = float(value)
    except OverflowError:
        report.add(path, f"{show_value(value)} is too large; expected {expected}")
        return None
    if not math.isfinite(number):
        report.add(path, f"{show_value(value)} is not a finite number; expected {expected}")
        return None
    return number


def read_name(report: ProblemReport, path: KeyPath, value: object, what: str, example: str) -> str | None:
    """A non-empty string naming something."""
    if isinstance(value, str) and value:
        return value
    report.add(path, f'expected {what} as a string like "{example}", got {show_value(value)}')
    return None


def read_table(report: ProblemReport, path: KeyPath, value: object, expected: str) -> Table | None:
    if isinstance(value, dict):
        return cast(Table, value)
    report.add(path, f"expected {expected}, got {show_value(value)}")
    return None


def check_keys(report: ProblemReport, path: KeyPath, table: Table, allowed: Collection[str]) -> None:
    for key in table:
        if key not in allowed:
            report.add(path + (key,), f"unknown key; {suggest(key, allowed)}")


def require(report: ProblemReport, path: KeyPath, table: Table, key: str, expected: str) -> object | None:
    if key not in table:
        report.add(path + (key,), f"missing; expected {expected}")
        return None
    return table[key]


def pair_name(first: str, second: str) -> str:
    return first + second if len(first) == 1 and len(second) == 1 else f"{first}-{second}"
