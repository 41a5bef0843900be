"""Text on the sheet: DejaVu Sans advance widths, and textbook notation as positioned runs.

Every backend draws text in DejaVu Sans (matplotlib ships it; the SVG asks for it; the DXF
text style names its file), so the boxes computed here are the boxes drawn. A label such as
``a^n_B/A`` becomes runs: ``a`` at full size, ``n`` raised and ``B/A`` lowered, both smaller
and stacked. Sizes are the font's em size in millimetres.
"""

from __future__ import annotations

import functools
import re
import unicodedata
from collections.abc import Callable
from typing import Any

from msgspec import Struct

from kinepoly.scene.link_point import LinkPoint

__all__ = [
    "ASCENT_EM",
    "CAP_HEIGHT_EM",
    "DESCENT_EM",
    "Run",
    "glyph_em",
    "plain_runs",
    "point_runs",
    "runs_box",
    "text_width",
    "tip_runs",
    "vector_runs",
    "wrap",
]

CAP_HEIGHT_EM = 1493 / 2048
"""Height of a capital letter of DejaVu Sans in ems (a DXF TEXT height is this)."""
ASCENT_EM = 0.80
"""Top of the tallest glyph we draw (ascenders, accents of Greek) above the baseline, in ems."""
DESCENT_EM = 0.24
"""Bottom of the descenders below the baseline, in ems."""

_SUB = 0.70
"""A sub- or superscript's size relative to its base."""

_CHARS = (' !"#$%&\'()*+,-./0123456789:;<=>?@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_`abcdefghijklmnopqrstuvwxyz{|}~'
          'ωαθ°²·−≡×′μ…≈Δ→ṡ\u0308ᶜ∠')
_ADVANCE = (651, 821, 942, 1716, 1303, 1946, 1597, 563, 799, 799, 1024, 1716, 651, 739, 651, 690, 1303, 1303, 1303,
            1303, 1303, 1303, 1303, 1303, 1303, 1303, 690, 690, 1716, 1716, 1716, 1087, 2048, 1401, 1405, 1430, 1577,
            1294, 1178, 1587, 1540, 604, 604, 1343, 1141, 1767, 1532, 1612, 1235, 1612, 1423, 1300, 1251, 1499, 1401,
            2025, 1403, 1251, 1403, 799, 690, 799, 1716, 1024, 1024, 1255, 1300, 1126, 1300, 1260, 721, 1300, 1298,
            569, 569, 1186, 569, 1995, 1298, 1253, 1300, 1300, 842, 1067, 803, 1298, 1212, 1675, 1212, 1212, 1075,
            1303, 690, 1303, 1716, 1715, 1350, 1253, 1024, 821, 651, 1716, 1716, 1716, 465, 1303, 2048, 1716, 1401,
            1716, 1067, 0, 758, 1836)
_ADVANCE_BOLD = (713, 934, 1067, 1716, 1425, 2052, 1786, 627, 936, 936, 1071, 1716, 778, 850, 778, 748, 1425, 1425,
            1425, 1425, 1425, 1425, 1425, 1425, 1425, 1425, 819, 819, 1716, 1716, 1716, 1188, 2048, 1585, 1561, 1503,
            1700, 1399, 1399, 1681, 1714, 762, 762, 1587, 1305, 2038, 1714, 1741, 1501, 1741, 1577, 1475, 1397, 1663,
            1585, 2259, 1579, 1483, 1485, 936, 748, 936, 1716, 1024, 1024, 1382, 1466, 1214, 1466, 1389, 891, 1466,
            1458, 702, 702, 1362, 702, 2134, 1458, 1407, 1466, 1466, 1010, 1219, 979, 1458, 1335, 1892, 1321, 1335,
            1192, 1458, 748, 1458, 1716, 1780, 1407, 1407, 1024, 897, 778, 1716, 1716, 1716, 540, 1507, 2048, 1716,
            1585, 1716, 1219, 0, 847, 1836)
_WIDTH_EM = {ch: adv / 2048 for ch, adv in zip(_CHARS, _ADVANCE, strict=True)}
_WIDTH_BOLD_EM = {ch: adv / 2048 for ch, adv in zip(_CHARS, _ADVANCE_BOLD, strict=True)}


@functools.lru_cache(maxsize=8192)
def text_width(text: str, size: float, bold: bool = False) -> float:
    """Advance width of ``text`` in DejaVu Sans (Bold) at em size ``size`` (mm).

    The table holds the characters of the drawings; any other (a Turkish or Romanian letter of
    a handout) is read from the font (``glyph_em``).
    """
    table = _WIDTH_BOLD_EM if bold else _WIDTH_EM
    return size * sum(table[ch] if ch in table else glyph_em(ch, bold) for ch in text)


@functools.cache
def _font(bold: bool) -> Any:
    from matplotlib import font_manager
    from matplotlib.ft2font import FT2Font

    weight = "bold" if bold else "normal"
    font = FT2Font(font_manager.findfont(font_manager.FontProperties(family="DejaVu Sans", weight=weight)))
    font.set_size(72, 72)  # 72 pixels per em: an advance in pixels / 72 is in ems
    return font


@functools.cache
def glyph_em(ch: str, bold: bool) -> float:
    """Advance of ``ch`` in DejaVu Sans (Bold) in ems, read from the font matplotlib draws with (any character)."""
    from matplotlib import ft2font

    loaded: Any = vars(ft2font)
    flags = loaded["LoadFlags"].NO_HINTING if "LoadFlags" in loaded else loaded["LOAD_NO_HINTING"]  # before 3.10
    font = _font(bold)
    if font.get_char_index(ord(ch)) == 0:  # no glyph in DejaVu Sans: drawn as the font's box, or wide
        return 0.0 if unicodedata.combining(ch) else 1.0 if unicodedata.east_asian_width(ch) in "WF" else 0.6
    glyph = font.load_char(ord(ch), flags=flags)
    return float(glyph.linearHoriAdvance) / 65536.0 / 72.0



class Run(Struct, frozen=True):
    """A piece of text at (dx, dy) from its label's baseline-left point, at em size ``size`` (mm)."""

    text: str
    dx: float
    dy: float
    size: float


def plain_runs(text: str, size: float) -> tuple[Run, ...]:
    return (Run(text, 0.0, 0.0, size),)


def _stack(base: str, sup: str, sub: str, size: float) -> tuple[Run, ...]:
    runs = [Run(base, 0.0, 0.0, size)]
    x = text_width(base, size)
    small = _SUB * size
    if sup:
        runs.append(Run(sup, x, 0.42 * size, small))
    if sub:
        runs.append(Run(sub, x, -0.22 * size, small))
    return tuple(runs)


_NAME = re.compile(r"^([^\W\d_]+)(\d*)(.*)$")


def _name_parts(name: str) -> tuple[str, str]:
    """``A0`` -> (``A``, ``0``): trailing digits of a point name are written as a subscript."""
    m = _NAME.match(name)
    if m is None or m.group(3):
        return name, ""
    return m.group(1), m.group(2)


def point_runs(name: str, size: float) -> tuple[Run, ...]:
    """A point of the mechanism: ``A0`` as A with a subscript 0; ``A@4`` as written."""
    base, digits = _name_parts(name)
    return _stack(base, "", digits, size)


def tip_runs(name: str, size: float, prime: bool) -> tuple[Run, ...]:
    """A tip of a polygon: lower case, primed in the acceleration polygon (a', b0')."""
    named = LinkPoint.parse(name.lower())
    base, digits = _name_parts(named.point)
    if prime:
        base = base + "′"
    runs = _stack(base, "", digits, size)
    if named.link is not None:
        x = max(r.dx + text_width(r.text, r.size) for r in runs)
        runs = (*runs, Run(named.at_link, x, 0.0, size))
    return runs


def vector_runs(label: str, size: float) -> tuple[Run, ...]:
    """``v_B/A`` -> v with subscript B/A; ``a^n_B/A`` -> a with superscript n over subscript B/A."""
    head, _, sub = label.partition("_")
    base, _, sup = head.partition("^")
    return _stack(base, sup, sub, size)


def runs_box(runs: tuple[Run, ...], bold: bool = False) -> tuple[float, float, float, float]:
    """(x0, y0, x1, y1) of the runs relative to the label's baseline-left point."""
    x0 = min(r.dx for r in runs)
    x1 = max(r.dx + text_width(r.text, r.size, bold) for r in runs)
    y0 = min(r.dy - DESCENT_EM * r.size for r in runs)
    y1 = max(r.dy + ASCENT_EM * r.size for r in runs)
    return (x0, y0, x1, y1)


def wrap(text: str, size: float, width: float, bold: bool = False,
         measure: Callable[[str, float, bool], float] | None = None) -> list[str]:
    """Break ``text`` at spaces into lines no wider than ``width`` (a longer word stands alone).

    ``measure(text, size, bold)`` gives a line's width; by default this module's ``text_width``.
    """
    width_of = measure or text_width
    lines: list[str] = []
    current = ""
    for word in text.split():
        trial = f"{current} {word}" if current else word
        if current and width_of(trial, size, bold) > width:
            lines.append(current)
            current = word
        else:
            current = trial
    if current:
        lines.append(current)
    return lines
