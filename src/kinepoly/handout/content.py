"""What a handout says, page by page, before it is laid out: the same for the PDF and the HTML page.

A page is a drawing (which state of the construction it shows) and columns of text: paragraphs
and small tables whose cells may hold the course's notation (``kinepoly.handout.notation``).
"""

from __future__ import annotations

from typing import Literal

from msgspec import Struct

__all__ = ["Column", "Drawing", "Handout", "Page", "Paragraph", "Part", "Table"]

Style = Literal["title", "heading", "equation", "body", "result", "note"]


class Paragraph(Struct, frozen=True):
    text: str
    style: Style = "body"


class Table(Struct, frozen=True):
    """A small table; the first column holds names (left-aligned), the others values."""

    title: str
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]


Part = Paragraph | Table


class Column(Struct, frozen=True):
    """A column of the text: ``fill`` takes the width the other columns leave."""

    parts: tuple[Part, ...]
    fill: bool = False
    legend: bool = False


class Drawing(Struct, frozen=True):
    """The state of the drawing a page shows.

    ``problem``: the mechanism and the empty polygon panels; ``step``: construction step
    ``number`` (1-based over ``Solution.steps``) highlighted on the growing polygons; ``kennedy``:
    the complete polygons and the instant centers up to Kennedy step ``number``, that step
    highlighted; ``answers``: everything.
    """

    kind: Literal["problem", "step", "kennedy", "answers"]
    number: int = 0


class Page(Struct, frozen=True):
    kind: Literal["problem", "step", "answers"]
    drawing: Drawing
    columns: tuple[Column, ...]
    equation: str = ""
    heading: str = ""


class Handout(Struct, frozen=True):
    title: str
    language: str
    pages: tuple[Page, ...]
    paper: str = ""
    """The paper the PDF's pages were laid out on (``A3``, ``297x210``); empty before they are."""
    notes: tuple[str, ...] = ()
    """What the layout had to change (a larger paper than asked), said on every page and by the command."""
