"""Colours, widths and sizes of the sheet, in one place (paper millimetres)."""

from __future__ import annotations

from kinepoly.render.primitives import Stroke

__all__ = [
    "BORDER",
    "DIRECTION_LINE",
    "HALO",
    "HEAD_HALF_WIDTH_MM",
    "HEAD_LENGTH_MM",
    "INK",
    "LABEL_MM",
    "LINK_STROKE",
    "MUTED_INK",
    "NOTE_INK",
    "PATH",
    "PIN_RADIUS_MM",
    "RULE",
    "SMALL_MM",
    "TERM_COLORS",
    "TERM_NAMES",
    "THIN",
    "TITLE_MM",
    "VECTOR_WIDTH_MM",
    "link_color",
    "link_label_color",
]

LABEL_MM = 2.6
"""Em size of labels (points, tips, vectors)."""
SMALL_MM = 2.1
"""Em size of the title block's tables and notes."""
TITLE_MM = 4.4
PIN_RADIUS_MM = 1.1
VECTOR_WIDTH_MM = 0.35
HEAD_LENGTH_MM = 2.6
HEAD_HALF_WIDTH_MM = 0.75
INK = "#000000"
"""Text and the sheet's frame."""
NOTE_INK = "#7a1f1f"
"""A note on what the layout had to change (a larger paper than asked)."""
BORDER = Stroke(INK, 0.5)
RULE = Stroke(INK, 0.35)
"""The title block's rule, a cursor."""
LINK_STROKE = Stroke("#1a1a1a", 0.6)
THIN = Stroke("#000000", 0.18)
MUTED_INK = "#6b6b6b"
"""What a panel says in place of a drawing it leaves out."""
DIRECTION_LINE = Stroke(MUTED_INK, 0.18, (2.0, 1.0))
PATH = Stroke("#8a8a8a", 0.25)
"""A point's path traced over a motion."""
HALO = Stroke("#ffe27a", 1.6)
"""Under what the current step adds, in the step-by-step sheets."""

TERM_COLORS = {
    "absolute": "#111111",
    "relative": "#1f5fbf",
    "normal": "#1a8a4a",
    "tangential": "#d9480f",
    "coriolis": "#a61e8c",
    "sliding": "#7a4b12",
}
TERM_NAMES = {
    "absolute": "absolute",
    "relative": "relative",
    "normal": "normal",
    "tangential": "tangential",
    "coriolis": "Coriolis",
    "sliding": "sliding",
}
_FILLS = ("#8ecae6", "#ffc857", "#9bd18b", "#f4978e", "#c3b1e1", "#f7d08a", "#8fd3c7", "#e5a3c8")
_INKS = ("#1d6a8a", "#9a6b00", "#3b7d2c", "#b2413a", "#6a4fa0", "#8f6a1e", "#2f7f73", "#9c3c74")


def link_color(index: int) -> str:
    """The light fill of link number ``index`` (in scene order): its plate and its image triangles."""
    return _FILLS[index % len(_FILLS)]


def link_label_color(index: int) -> str:
    """The darker ink of the same hue, for the link's number."""
    return _INKS[index % len(_INKS)]
