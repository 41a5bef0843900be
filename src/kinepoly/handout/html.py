"""The handout as one self-contained web page that steps through the construction.

Every page of the handout is a section: its drawing as inline SVG (``render.svg``; the drawing
without the band, the text beside it in HTML) and its text. A small inline script shows one
section at a time: the Previous and Next buttons, a slider over all pages, the arrow keys
(Home and End jump to the problem and the answers), and the address's ``#page-N``, which the
page keeps up to date, so a step can be linked to. Nothing is fetched from anywhere.
"""

from __future__ import annotations

import html
import re
from typing import Any

from kinepoly.handout.build import crowded_labels, drawn_kinds, handout_content
from kinepoly.handout.content import Column, Handout, Page, Paragraph, Table
from kinepoly.handout.drawing import Frame, band_frame, blank_sheet, drawing_layers, page_frame_items, scales_of
from kinepoly.handout.notation import html_of
from kinepoly.present.catalogue import Catalogue
from kinepoly.render.layout import larger_papers, paper_size
from kinepoly.render.sheet import roomy
from kinepoly.render.style import TERM_COLORS
from kinepoly.solution import Solution

__all__ = ["handout_html"]

_LEGEND_ORDER = ("absolute", "relative", "sliding", "normal", "tangential", "coriolis")

_STYLE = """
*{box-sizing:border-box}
body{margin:0;font-family:"DejaVu Sans",Verdana,Arial,sans-serif;color:#111;background:#f4f4f1;line-height:1.45}
header{position:sticky;top:0;z-index:1;background:#fff;border-bottom:1px solid #ccc;padding:.5rem 1rem;
 display:flex;flex-wrap:wrap;align-items:center;gap:.5rem 1rem}
header h1{font-size:1.1rem;margin:0;flex:1 1 16rem}
nav{display:flex;align-items:center;gap:.6rem;flex:2 1 30rem}
nav input{flex:1 1 auto}
nav button{font:inherit;padding:.3rem .8rem;border:1px solid #888;border-radius:.3rem;background:#fafafa;cursor:pointer}
nav button:disabled{opacity:.4;cursor:default}
nav output{min-width:9rem;font-weight:bold}
.keys{font-size:.8rem;color:#555;margin:0;flex-basis:100%}
main{padding:1rem}
.page{display:grid;grid-template-columns:minmax(0,2fr) minmax(18rem,1fr);gap:1rem;align-items:start}
.page[hidden]{display:none}
@media (max-width:60rem){.page{grid-template-columns:minmax(0,1fr)}}
.drawing{background:#fff;border:1px solid #ccc}
.drawing svg{display:block;width:100%;height:auto}
.text{background:#fff;border:1px solid #ccc;padding:.8rem 1rem}
.text h2{font-size:1.2rem;margin:.2rem 0 .4rem}
.text h3{font-size:1rem;margin:.8rem 0 .3rem}
.text p{margin:.3rem 0}
.text .equation{font-weight:bold;font-size:1.08rem;margin:.4rem 0 .6rem}
.text .result{font-weight:bold}
.text .note{font-size:.9rem;color:#333}
table{border-collapse:collapse;margin:.4rem 0 .8rem;font-size:.92rem}
caption{text-align:left;font-weight:bold;padding-bottom:.2rem}
th,td{border-bottom:1px solid #ddd;padding:.15rem .6rem .15rem 0;text-align:left;vertical-align:top}
td.num{text-align:right}
.ss{display:inline-block;vertical-align:-.45em;line-height:1;font-size:.7em;text-align:left}
.ss sup,.ss sub{display:block;font-size:1em;line-height:1.05;vertical-align:baseline;position:static}
.legend{display:flex;flex-wrap:wrap;gap:.3rem 1rem;font-size:.85rem;margin-top:.8rem}
.legend span::before{content:"";display:inline-block;width:1.4rem;height:.2rem;margin-right:.3rem;
 vertical-align:middle;background:var(--c)}
"""

_SCRIPT = """
(function () {
  "use strict";
  var pages = Array.prototype.slice.call(document.querySelectorAll("section.page"));
  var slider = document.getElementById("slider");
  var previous = document.getElementById("previous");
  var next = document.getElementById("next");
  var where = document.getElementById("where");
  var current = 0;
  function show(k) {
    k = Math.max(0, Math.min(pages.length - 1, k));
    pages.forEach(function (page, n) { page.hidden = n !== k; });
    current = k;
    slider.value = String(k + 1);
    previous.disabled = k === 0;
    next.disabled = k === pages.length - 1;
    where.textContent = pages[k].getAttribute("data-label");
    document.body.setAttribute("data-page", String(k + 1));
    var hash = "#page-" + (k + 1);
    if (location.hash !== hash) {
      try { history.replaceState(null, "", hash); } catch (error) { /* an address that cannot change */ }
    }
  }
  function fromHash() {
    var m = /^#page-(\\d+)$/.exec(location.hash);
    return m ? parseInt(m[1], 10) - 1 : 0;
  }
  previous.addEventListener("click", function () { show(current - 1); });
  next.addEventListener("click", function () { show(current + 1); });
  slider.addEventListener("input", function () { show(parseInt(slider.value, 10) - 1); });
  document.addEventListener("keydown", function (event) {
    if (event.target === slider || event.altKey || event.ctrlKey || event.metaKey) { return; }
    if (event.key === "ArrowRight" || event.key === "PageDown") { show(current + 1); }
    else if (event.key === "ArrowLeft" || event.key === "PageUp") { show(current - 1); }
    else if (event.key === "Home") { show(0); }
    else if (event.key === "End") { show(pages.length - 1); }
    else { return; }
    event.preventDefault();
  });
  window.addEventListener("hashchange", function () { show(fromHash()); });
  show(fromHash());
}());
"""


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


def _svg(solution: Solution, frame: Frame, page: Page, say: Catalogue, groups: dict[Any, str]) -> str:
    """The page's drawing as inline SVG; ``groups`` holds the layers already written (the pages share most)."""
    from kinepoly.render.svg import svg_text

    layers = drawing_layers(solution, frame, page.drawing, say)
    layers["title"] += page_frame_items(frame)
    text = svg_text(blank_sheet(frame, f"{solution.scene.title}: {page.heading}", layers), groups)
    text = text.split("\n", 1)[1]  # no XML declaration inside HTML
    return re.sub(r'(<g\b[^>]*?) id="([a-z-]+)"', r'\1 class="layer-\2"', text)  # ids once per document


def _label(page: Page, say: Catalogue) -> str:
    if page.kind == "problem":
        return say.say("page.problem")
    if page.kind == "answers":
        return say.say("page.answers")
    return page.heading


def _section(solution: Solution, frame: Frame, page: Page, number: int, kinds: list[str], say: Catalogue,
             groups: dict[Any, str]) -> str:
    text = "".join(_column(c, kinds, say) for c in page.columns)
    return (f'<section class="page" id="page-{number}" data-kind="{page.kind}" '
            f'data-label="{html.escape(_label(page, say))}" data-equation="{html.escape(page.equation)}"'
            f'{" hidden" if number > 1 else ""}>\n<div class="drawing">{_svg(solution, frame, page, say, groups)}</div>\n'
            f'<div class="text">{text}</div>\n</section>\n')


def _frame(solution: Solution, size: tuple[float, float]) -> Frame:
    """The drawing on the paper asked, or the smallest larger A paper that gives each polygon its scale and the
    mechanism its size (``render.sheet.roomy``), as the PDF's drawing; the scales are the paper asked's."""
    for _, paper in [("", size), *larger_papers(size)]:
        frame = band_frame(solution, paper, 0.0, size)
        if roomy(solution, frame.layout):
            return frame
    return band_frame(solution, size, 0.0, size)


def handout_html(solution: Solution, say: Catalogue, paper: str | tuple[float, float] = "A4") -> tuple[Handout, str]:
    """The handout as one HTML page (and its content), in the catalogue's language."""
    size = paper if isinstance(paper, tuple) else paper_size(paper)
    frame = _frame(solution, size)
    handout = handout_content(solution, say, scales_of(frame.layout))
    kinds = drawn_kinds(frame)
    crowded_labels(solution, frame)  # the whole drawing's labels first: each page keeps those it shows
    count = len(handout.pages)
    groups: dict[Any, str] = {}
    sections = "".join(_section(solution, frame, page, k, kinds, say, groups) for k, page in enumerate(handout.pages, 1))
    title = html.escape(handout.title)
    return handout, (
        f'<!DOCTYPE html>\n<html lang="{html.escape(say.code)}">\n<head>\n<meta charset="utf-8">\n'
        f'<meta name="viewport" content="width=device-width, initial-scale=1">\n<meta name="generator" '
        f'content="kinepoly">\n<title>{title}</title>\n<style>{_STYLE}</style>\n</head>\n<body data-page="1">\n'
        f'<header>\n<h1>{title}</h1>\n<nav aria-label="{html.escape(say.say("page.navigation"))}">\n'
        f'<button id="previous" type="button">◀ {html.escape(say.say("page.previous"))}</button>\n'
        f'<input id="slider" type="range" min="1" max="{count}" value="1" step="1" '
        f'aria-label="{html.escape(say.say("page.navigation"))}">\n'
        f'<button id="next" type="button">{html.escape(say.say("page.next"))} ▶</button>\n'
        f'<output id="where" for="slider">{html.escape(_label(handout.pages[0], say))}</output>\n</nav>\n'
        f'<p class="keys">{html.escape(say.say("page.keys"))}</p>\n</header>\n<main>\n{sections}</main>\n'
        f"<script>{_SCRIPT}</script>\n</body>\n</html>\n"
    )
