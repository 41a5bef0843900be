"""The course's notation inside running text, typeset: for the sheets as runs, for the page as HTML.

Text of the handout is written in words with the notation of the steps embedded, e.g.
``Through a draw the direction of v_B/A, perpendicular to A0B.``. Words are separated by spaces;
punctuation around a word stays as it is. A word is typeset when it is

- a vector: ``v_B/A``, ``a^n_B/A``, ``a^c_A@4/A`` (the letter, the superscript over the subscript),
- a name with digits: ``ω13``, ``I13``, ``A0``, ``A0B``, ``b0``, ``s14``, ``b′0`` (a tip of the
  acceleration polygon, primed): the digits after a letter lowered.

Everything else is drawn as written. Plain-text forms ``omega``, ``alpha``, ``theta``, ``^2`` and
`` x `` (a cross product) become ω, α, θ, ² and ×.
"""

from __future__ import annotations

import functools
import html
import re
from collections.abc import Iterator

from msgspec import Struct

from kinepoly.geom.tolerances import PAPER_ROUNDING_MM
from kinepoly.render import text as render_text
from kinepoly.render.text import Run
from kinepoly.scene.link_point import LinkPoint

__all__ = ["Piece", "html_of", "pieces", "plain_of", "quantity_name", "runs_of", "text_width", "typographic", "wrap"]

_SUB = 0.70
_LETTER = r"[A-Za-zωαθ][\u0300-\u036f]*"
_VECTOR = re.compile(r"^([a-z])(?:\^([a-z]))?_([A-Za-z0-9@/]+)$")
_NAMED = re.compile(rf"^(?:{_LETTER}′?\d*)+(?:@\d+)?$")
_GROUP = re.compile(rf"({_LETTER}′?)(\d*)")
_LEAD = "(|[«„\""
_TRAIL = ")|].,;:!?»\"²"


_COLUMN = re.compile(r"^(theta|omega|alpha|s_ddot|s_dot|s)_(\w+)$")
_DOTS = {"s": "s", "s_dot": "s\u0307", "s_ddot": "s\u0308"}


def quantity_name(column: str, ground: str) -> str:
    """A sweep's column name as the course writes the quantity, in this notation's plain form: ``omega_3`` is
    ``omega13`` (link 3's angular velocity relative to the frame ``1``), ``s_dot_14`` is ``ṡ14``; any other
    name (``|v_B|``, ``mu_T``) as it is."""
    m = _COLUMN.match(column)
    if m is None:
        return column
    kind, rest = m.groups()
    return f"{kind}{ground}{rest}" if kind in ("theta", "omega", "alpha") else f"{_DOTS[kind]}{rest}"


def text_width(text: str, size: float, bold: bool = False) -> float:
    """Advance width of ``text`` in DejaVu Sans (Bold) at em size ``size`` (mm), any character.

    Read from the font matplotlib draws with, so that Turkish, Romanian or any other letters
    and the symbols of the handout (⊥, ∥, →, △) are measured as drawn.
    """
    return size * sum(render_text.glyph_em(ch, bold) for ch in text)


def wrap(text: str, size: float, width: float, bold: bool = False) -> list[str]:
    """Break ``text`` at spaces into lines no wider than ``width`` as typeset (a longer word stands alone).

    A line's typeset width is the sum of its words' and spaces' (each word is typeset on its own),
    so each word is measured once.
    """
    space = text_width(" ", size, bold)
    lines: list[str] = []
    current: list[str] = []
    current_w = 0.0
    for word in text.split():
        w = _typeset_width(word, size, bold)
        trial = current_w + space + w if current else w
        if current and trial > width + PAPER_ROUNDING_MM:  # a sum's rounding does not break a line measured whole
            lines.append(" ".join(current))
            current, current_w = [word], w
        else:
            current.append(word)
            current_w = trial
    if current:
        lines.append(" ".join(current))
    return lines


@functools.lru_cache(maxsize=65536)
def _typeset_width(text: str, size: float, bold: bool) -> float:
    runs = runs_of(text, size, bold)
    return max(r.dx + text_width(r.text, r.size, bold) for r in runs)


class Piece(Struct, frozen=True):
    """A piece of typeset text: ``base`` at full size, then ``sup`` over ``sub`` (both smaller)."""

    base: str
    sup: str = ""
    sub: str = ""


def typographic(text: str) -> str:
    """Plain-text notation made typographic: omega -> ω, alpha -> α, theta -> θ, ^2 -> ², x -> ×."""
    for plain, nice in (("omega", "ω"), ("alpha", "α"), ("theta", "θ"), ("^2", "²"), (" x ", " × "),
                        (" deg", "°")):
        text = text.replace(plain, nice)
    return text


def _word(word: str) -> Iterator[Piece]:
    start = 0
    while start < len(word) and word[start] in _LEAD:
        start += 1
    end = len(word)
    while end > start and word[end - 1] in _TRAIL:
        end -= 1
    lead, core, trail = word[:start], word[start:end], word[end:]
    if lead:
        yield Piece(lead)
    vector = _VECTOR.match(core)
    if vector:
        yield Piece(vector.group(1), vector.group(2) or "", vector.group(3))
    elif core and _NAMED.match(core) and any(ch.isdigit() for ch in core):
        named = LinkPoint.parse(core)
        for m in _GROUP.finditer(named.point):
            yield Piece(m.group(1), "", m.group(2))
        if named.link is not None:
            yield Piece(named.at_link)
    elif core:
        yield Piece(core)
    if trail:
        yield Piece(trail)


def pieces(text: str) -> list[Piece]:
    """The text as pieces; a space is a piece of its own."""
    out: list[Piece] = []
    for k, word in enumerate(text.split(" ")):
        if k:
            out.append(Piece(" "))
        out.extend(_word(word))
    return _merged(out)


def _merged(items: list[Piece]) -> list[Piece]:
    """Neighbouring plain pieces joined into one (fewer runs, same text)."""
    out: list[Piece] = []
    for piece in items:
        if out and not (piece.sup or piece.sub) and not (out[-1].sup or out[-1].sub):
            out[-1] = Piece(out[-1].base + piece.base)
        else:
            out.append(piece)
    return out


def runs_of(text: str, size: float, bold: bool = False) -> tuple[Run, ...]:
    """Runs of one line of text at em size ``size`` (mm), the notation typeset."""
    runs: list[Run] = []
    x = 0.0
    small = _SUB * size
    for piece in pieces(text):
        if piece.base:
            runs.append(Run(piece.base, x, 0.0, size))
            x += text_width(piece.base, size, bold)
        width = 0.0
        if piece.sup:
            runs.append(Run(piece.sup, x, 0.42 * size, small))
            width = text_width(piece.sup, small, bold)
        if piece.sub:
            runs.append(Run(piece.sub, x, -0.22 * size, small))
            width = max(width, text_width(piece.sub, small, bold))
        x += width
    return tuple(runs) or (Run(" ", 0.0, 0.0, size),)


def plain_of(text: str) -> str:
    """What the typeset text reads as, run after run (``v_B/A`` -> ``vB/A``): for comparisons."""
    return "".join(p.base + p.sup + p.sub for p in pieces(text))


def html_of(text: str) -> str:
    """The text as HTML, the notation typeset with <sub> and <sup> (stacked where both)."""
    out: list[str] = []
    for piece in pieces(text):
        base = html.escape(piece.base)
        if piece.sup and piece.sub:
            out.append(f'{base}<span class="ss"><sup>{html.escape(piece.sup)}</sup>'
                       f'<sub>{html.escape(piece.sub)}</sub></span>')
        elif piece.sup:
            out.append(f"{base}<sup>{html.escape(piece.sup)}</sup>")
        elif piece.sub:
            out.append(f"{base}<sub>{html.escape(piece.sub)}</sub>")
        else:
            out.append(base)
    return "".join(out)
