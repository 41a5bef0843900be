"""The handout as one self-contained web page that steps through the construction.

Every page of the handout is a section: its drawing (the drawing without the band, the text beside
it in HTML) and its text. A small script (the package's ``static/handout.js``, with ``static/handout.css``,
written into the page) shows one section at a time: the Previous and Next
buttons, a slider over all pages, the arrow keys (Home and End jump to the problem and the answers),
and the address's ``#page-N``, which the page keeps up to date, so a step can be linked to. Nothing
is fetched from anywhere.

The drawing is ONE inline SVG for all pages (``render.svg``), so the page grows with the number of
steps, not with its square: each element is written once, in an order that keeps every page's own
order (``merged_pages``); the elements not on every page are grouped in a ``<g data-pages="3-9 12">``
by the pages that show them. The script moves the drawing into the section shown and hides the
groups that page does not show (``display="none"``, as written for page 1), and sets its title.
"""

from __future__ import annotations

import html
import re
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from kinepoly.assets import static_text
from kinepoly.handout.build import crowded_labels, drawn_kinds, handout_content
from kinepoly.handout.content import Column, Handout, Page, Paragraph, Table
from kinepoly.handout.drawing import Frame, band_frame, blank_sheet, drawing_layers, page_frame_items, scales_of
from kinepoly.handout.notation import html_of
from kinepoly.present.catalogue import Catalogue
from kinepoly.render.layout import larger_papers, paper_size
from kinepoly.render.primitives import LAYERS, Item
from kinepoly.render.sheet import readable_values, roomy
from kinepoly.render.style import TERM_COLORS
from kinepoly.solution import Solution

if TYPE_CHECKING:
    from kinepoly.loops.rates import LoopSolution

__all__ = ["drawing_frame", "handout_html", "merged_pages", "page_ranges", "text_html"]

_LEGEND_ORDER = ("absolute", "relative", "sliding", "normal", "tangential", "coriolis")

def _table(table: Table) -> str:
    numeric = [c > 0 and all(not cell or cell[0].isdigit() or cell[0] == "−" for cell in (r[c] for r in table.rows))
               for c in range(len(table.header))]
    caption = f"<caption>{html_of(table.title)}</caption>" if table.title else ""
    head = "".join(f"<th>{html_of(h)}</th>" for h in table.header)
    rows = "".join("<tr>" + "".join(f'<td{" class=num" if numeric[c] else ""}>{html_of(cell)}</td>'
                                    for c, cell in enumerate(row)) + "</tr>" for row in table.rows)
    return f"<table>{caption}<thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>"


def _paragraph(paragraph: Paragraph) -> str:
    text = html_of(paragraph.text)
    if paragraph.style == "title":
        return f"<h2>{text}</h2>"
    if paragraph.style == "heading":
        return f"<h3>{text}</h3>"
    return f'<p class="{paragraph.style}">{text}</p>'


def _legend(kinds: list[str], say: Catalogue) -> str:
    spans = "".join(f'<span style="--c:{TERM_COLORS[k]}">{html.escape(say.say(f"legend.{k}"))}</span>'
                    for k in _LEGEND_ORDER if k in kinds)
    return f'<div class="legend"><b>{html.escape(say.say("legend.title"))}</b>{spans}</div>'


def _column(column: Column, kinds: list[str], say: Catalogue) -> str:
    if column.legend:
        return _legend(kinds, say) if kinds else ""
    return "".join(_paragraph(p) if isinstance(p, Paragraph) else _table(p) for p in column.parts)


def text_html(page: Page, kinds: list[str], say: Catalogue) -> str:
    """A page's text as the web page shows it beside the drawing (``kinds``: the drawn vectors, for the legend)."""
    return "".join(_column(c, kinds, say) for c in page.columns)


def merged_pages(pages: Sequence[Sequence[Item]]) -> list[tuple[Item, list[int]]]:
    """One layer's items of every page (page 1 first) merged into one sequence of (item, the pages showing it).

    The items a page shows come in that page's order; an item comes once for all the pages where that order
    allows it, again where a page has it before one it followed elsewhere. Items are told apart by identity
    (``drawing_layers`` gives an equal item as the same object on every page): one item per page is looked at.
    """
    order: list[tuple[Item, list[int]]] = []
    kept: dict[int, list[tuple[Item, list[int]]]] = {}  # by the item's id, its entries in ``order``
    for number, items in enumerate(pages, 1):
        # by the entry's id (this page's new ones: none)
        position = dict(zip(map(id, order), range(len(order)), strict=True))
        merged: list[tuple[Item, list[int]]] = []
        start = 0
        for item in items:
            found = min((p for e in kept.get(id(item), ()) if (p := position.get(id(e), -1)) >= start), default=None)
            if found is None:
                entry: tuple[Item, list[int]] = (item, [number])
                kept.setdefault(id(item), []).append(entry)
                merged.append(entry)
                continue
            merged += order[start:found]
            order[found][1].append(number)
            merged.append(order[found])
            start = found + 1
        order = merged + order[start:]
    return order


def page_ranges(numbers: Sequence[int]) -> str:
    """Increasing page numbers as ranges: ``[3, 4, 5, 9]`` is ``"3-5 9"``."""
    ranges: list[list[int]] = []
    for n in numbers:
        if ranges and ranges[-1][1] == n - 1:
            ranges[-1][1] = n
        else:
            ranges.append([n, n])
    return " ".join(str(a) if a == b else f"{a}-{b}" for a, b in ranges)


_ELEMENT = re.compile(r"<(?![/?!]|tspan\b)")
"""The start of an element that is not inside another (only a text's runs are; ``<`` is escaped elsewhere)."""


def _page_layers(solution: Solution, frame: Frame, page: Page, say: Catalogue, border: list[Item]) -> list[list[Item]]:
    """The items of a page's drawing, layer by layer in the order of ``LAYERS``."""
    layers = drawing_layers(solution, frame, page.drawing, say)
    layers["title"] += border
    return [layers[name] for name in LAYERS]


def _group(group: str, shown: list[tuple[Item, list[int]]], made: dict[Any, str], height: float, count: int) -> str:
    """A layer's ``<g>`` as ``svg_text`` wrote it, the runs of elements shown on the same pages (not all ``count``)
    wrapped in a ``<g data-pages>``, hidden unless page 1 shows them."""
    if not shown:
        return group
    shell, *elements = group.removesuffix("\n</g>").split("\n<")
    sizes = [len(_ELEMENT.findall(made[item, height])) for item, _ in shown]
    if sum(sizes) != len(elements):
        raise AssertionError("the SVG's elements do not match the items drawn")  # render.svg's own layout changed
    out = [shell]
    at = 0
    runs: list[tuple[list[int], list[str]]] = []
    for (_, numbers), size in zip(shown, sizes, strict=True):
        if not runs or runs[-1][0] != numbers:
            runs.append((numbers, []))
        runs[-1][1].extend("<" + e for e in elements[at:at + size])
        at += size
    for numbers, parts in runs:
        if len(numbers) == count:
            out += parts
        else:
            hidden = "" if numbers[0] == 1 else ' display="none"'
            out += [f'<g data-pages="{page_ranges(numbers)}"{hidden}>', *parts, "</g>"]
    return "\n".join(out) + "\n</g>"


def _svg(solution: Solution, frame: Frame, handout: Handout, say: Catalogue) -> str:
    """The drawing of every page as one inline SVG, each element written once (see the module's text)."""
    from kinepoly.render.svg import svg_text

    border = page_frame_items(frame)
    per_page = [_page_layers(solution, frame, page, say, border) for page in handout.pages]
    shown = [merged_pages([layers[n] for layers in per_page]) for n in range(len(LAYERS))]
    sheet = blank_sheet(frame, _title(solution, handout.pages[0]),
                        {name: [item for item, _ in items] for name, items in zip(LAYERS, shown, strict=True)})
    made: dict[Any, str] = {}
    text = svg_text(sheet, made)
    groups = [made[layer, frame.height] for layer in sheet.layers]
    head = text.split("\n", 1)[1].split(groups[0], 1)[0]  # no XML declaration inside HTML
    body = "\n".join(_group(group, items, made, frame.height, len(per_page))
                     for group, items in zip(groups, shown, strict=True))
    text = head + body + "\n</svg>"
    return re.sub(r'(<g\b[^>]*?) id="([a-z-]+)"', r'\1 class="layer-\2"', text)  # ids kept for the document


def _title(solution: Solution, page: Page) -> str:
    return f"{solution.scene.title}: {page.heading}"


def _label(page: Page, say: Catalogue) -> str:
    if page.kind == "problem":
        return say.say("page.problem")
    if page.kind == "answers":
        return say.say("page.answers")
    return page.heading


def _section(solution: Solution, page: Page, number: int, kinds: list[str], say: Catalogue, drawing: str) -> str:
    """A page's section; ``drawing`` (the one SVG) in the first, which the script moves to the page shown."""
    text = text_html(page, kinds, say)
    return (f'<section class="page" id="page-{number}" data-kind="{page.kind}" '
            f'data-label="{html.escape(_label(page, say))}" data-equation="{html.escape(page.equation)}" '
            f'data-title="{html.escape(_title(solution, page))}"'
            f'{" hidden" if number > 1 else ""}>\n<div class="drawing">{drawing}</div>\n'
            f'<div class="text">{text}</div>\n</section>\n')


def drawing_frame(solution: Solution, size: tuple[float, float]) -> Frame:
    """The drawing on the paper asked, or the smallest larger A paper that gives each polygon its scale and the
    mechanism its size (``render.sheet.roomy``), as the PDF's drawing; the scales are the paper asked's."""
    readable = readable_values(solution, size)
    for _, paper in [("", size), *larger_papers(size)]:
        frame = band_frame(solution, paper, 0.0, size, readable)
        if roomy(solution, frame.layout):
            return frame
    return band_frame(solution, size, 0.0, size, readable)


def handout_html(solution: Solution, say: Catalogue, paper: str | tuple[float, float] = "A4",
                 loops: LoopSolution | None = None) -> tuple[Handout, str]:
    """The handout as one HTML page (and its content), in the catalogue's language; with ``loops`` the
    loop-closure method's pages after the answers."""
    size = paper if isinstance(paper, tuple) else paper_size(paper)
    frame = drawing_frame(solution, size)
    handout = handout_content(solution, say, scales_of(frame.layout), loops)
    kinds = drawn_kinds(frame)
    crowded_labels(solution, frame)  # the whole drawing's labels first: each page keeps those it shows
    count = len(handout.pages)
    drawing = _svg(solution, frame, handout, say)
    sections = "".join(_section(solution, page, k, kinds, say, drawing if k == 1 else "")
                       for k, page in enumerate(handout.pages, 1))
    title = html.escape(handout.title)
    style, script = static_text("kinepoly.handout", "handout.css"), static_text("kinepoly.handout", "handout.js")
    return handout, (
        f'<!DOCTYPE html>\n<html lang="{html.escape(say.code)}">\n<head>\n<meta charset="utf-8">\n'
        f'<meta name="viewport" content="width=device-width, initial-scale=1">\n<meta name="generator" '
        f'content="kinepoly">\n<title>{title}</title>\n<style>\n{style}</style>\n</head>\n<body data-page="1">\n'
        f'<header>\n<h1>{title}</h1>\n<nav aria-label="{html.escape(say.say("page.navigation"))}">\n'
        f'<button id="previous" type="button">◀ {html.escape(say.say("page.previous"))}</button>\n'
        f'<input id="slider" type="range" min="1" max="{count}" value="1" step="1" '
        f'aria-label="{html.escape(say.say("page.navigation"))}">\n'
        f'<button id="next" type="button">{html.escape(say.say("page.next"))} ▶</button>\n'
        f'<output id="where" for="slider">{html.escape(_label(handout.pages[0], say))}</output>\n</nav>\n'
        f'<p class="keys">{html.escape(say.say("page.keys"))}</p>\n</header>\n<main>\n{sections}</main>\n'
        f"<script>\n{script}</script>\n</body>\n</html>\n"
    )
