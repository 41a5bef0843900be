"""Plain TOML values checked and reported: tables, their keys, names and finite numbers.

Each function takes the :class:`~kinepoly.scene.problems.ProblemReport`, the key path and
the value; it returns the value in its strict type, or None after reporting what is wrong.
"""

from __future__ import annotations

import math
import unicodedata
from collections.abc import Collection
from functools import partial
from typing import cast

from kinepoly.scene.lines import KeyPath
from kinepoly.scene.problems import ProblemReport, show_value, unknown_key
from kinepoly.scene.source import Table

__all__ = ["Vector", "check_keys", "check_showable", "pair_name", "read_finite", "read_name", "read_table", "require",
           "unshowable"]

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


def unshowable(text: str) -> str | None:
    """The first character of ``text`` no drawing can show as written, or None.

    Control characters (U+0000..U+001F, U+007F..U+009F: not allowed in XML 1.0 or not printable),
    lone surrogates, private-use characters and the noncharacters (U+FFFE, U+FFFF, U+FDD0..U+FDEF,
    ...) are refused; a title or name with one would make an SVG that is not well-formed XML or
    a page whose fonts have no glyph for it.
    """
    for ch in text:
        code = ord(ch)
        if unicodedata.category(ch) in ("Cc", "Cs", "Co") or 0xFDD0 <= code <= 0xFDEF or (code & 0xFFFE) == 0xFFFE:
            return ch
    return None


def check_showable(report: ProblemReport, path: KeyPath, text: str, what: str) -> bool:
    """Report ``text`` (a title or a name) when it has a character no drawing can show; True when it is fine."""
    bad = unshowable(text)
    if bad is None:
        return True
    report.add(path, f"{what} has the character U+{ord(bad):04X}, which cannot be shown in a drawing or a page; "
               "expected printable text (letters, digits, punctuation, spaces)")
    return False


def read_name(report: ProblemReport, path: KeyPath, value: object, what: str, example: str) -> str | None:
    """A non-empty string naming something, every character of it showable."""
    if isinstance(value, str) and value:
        return value if check_showable(report, path, value, what) else None
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
            report.add(path + (key,), partial(unknown_key, key, allowed))


def require(report: ProblemReport, path: KeyPath, table: Table, key: str, expected: str) -> object | None:
    if key not in table:
        report.add(path + (key,), f"missing; expected {expected}")
        return None
    return table[key]


def pair_name(first: str, second: str) -> str:
    return first + second if len(first) == 1 and len(second) == 1 else f"{first}-{second}"
