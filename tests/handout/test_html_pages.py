"""The web page's one drawing: page k shows exactly the drawing of page k alone, each element written once.

Page k's drawing is reconstructed from the page (its one SVG parsed, the groups whose ``data-pages`` leave k
out dropped) and compared, element by element, with page k's drawing made alone as the per-page functions
make it (``drawing_layers`` and the page's border on a sheet of its own, through ``render.svg.svg_text``): two
examples, one with instant centers, and a chain of three loops. In chromium the page shows, at page k, the
drawing in the section shown with exactly those elements displayed.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st
from tests.scenes import EXAMPLES

from kinepoly.bench.chain import chain_text
from kinepoly.handout import handout_html, load_catalogue
from kinepoly.handout.build import crowded_labels
from kinepoly.handout.content import Handout
from kinepoly.handout.drawing import blank_sheet, drawing_layers, page_frame_items
from kinepoly.handout.html import drawing_frame, merged_pages, page_ranges
from kinepoly.render.layout import paper_size
from kinepoly.render.primitives import LAYERS, Stroke
from kinepoly.render.primitives import Path as PathItem
from kinepoly.render.svg import svg_text
from kinepoly.scene.loader import load_scene, loads_scene
from kinepoly.solution import Solution, solve

SVG = "{http://www.w3.org/2000/svg}"
Element = tuple[str, tuple[tuple[str, str], ...], str, tuple[Any, ...]]


def _solution(name: str) -> Solution:
    if name == "chain-3":
        return solve(loads_scene(chain_text(3), "chain-3.toml"))
    return solve(load_scene(EXAMPLES / f"{name}.toml"))


def _leaf(element: ET.Element) -> Element:
    """An element as comparable data: tag, attributes, text, and so its runs."""
    return (element.tag, tuple(sorted(element.attrib.items())), element.text or "", tuple(_leaf(e) for e in element))


def _alone(solution: Solution, handout: Handout, lang: str) -> list[tuple[str, dict[str, list[Element]]]]:
    """Each page's (title, drawing layer by layer) as the pages were made before, each on a sheet of its own."""
    say = load_catalogue(lang)
    frame = drawing_frame(solution, paper_size("A4"))
    crowded_labels(solution, frame)
    pages = []
    for page in handout.pages:
        layers = drawing_layers(solution, frame, page.drawing, say)
        layers["title"] += page_frame_items(frame)
        title = f"{solution.scene.title}: {page.heading}"
        root = ET.fromstring(svg_text(blank_sheet(frame, title, layers)).encode())
        pages.append((root.findtext(f"{SVG}title") or "",
                      {g.attrib["id"]: [_leaf(e) for e in g] for g in root.findall(f"{SVG}g")}))
    return pages


def _ranges(text: str) -> list[tuple[int, int]]:
    return [(int(r.split("-")[0]), int(r.split("-")[-1])) for r in text.split()]


def _shown(group: ET.Element, number: int) -> list[Element]:
    """The elements of a layer that page ``number`` shows: a ``<g data-pages>`` opened when it names the page."""
    out: list[Element] = []
    for element in group:
        if element.tag == f"{SVG}g" and "data-pages" in element.attrib:
            assert len(element.attrib) <= 2 and set(element.attrib) <= {"data-pages", "display"}
            if any(a <= number <= b for a, b in _ranges(element.attrib["data-pages"])):
                out += [_leaf(e) for e in element]
        else:
            out.append(_leaf(element))
    return out


def _drawing(text: str) -> ET.Element:
    svgs = re.findall(r"<svg\b.*?</svg>", text, flags=re.DOTALL)
    assert len(svgs) == 1  # one drawing for every page
    return ET.fromstring(svgs[0])


CASES = [("four-bar", "tr"), ("centers-six-bar", "en"), ("chain-3", "ro")]


@pytest.mark.parametrize("name, lang", CASES, ids=[c[0] for c in CASES])
def test_each_page_shows_the_drawing_it_shows_alone(name: str, lang: str) -> None:
    solution = _solution(name)
    handout, text = handout_html(solution, load_catalogue(lang))
    alone = _alone(solution, handout, lang)
    root = _drawing(text)
    layers = root.findall(f"{SVG}g")
    assert [g.attrib["class"] for g in layers] == [f"layer-{layer}" for layer in LAYERS]
    titles = re.findall(r'data-title="([^"]*)"', text)
    assert len(titles) == len(alone) == len(handout.pages)
    for number, (title, drawing) in enumerate(alone, 1):
        assert ET.fromstring(f"<t>{titles[number - 1]}</t>").text == title
        for group in layers:
            layer = group.attrib["class"].removeprefix("layer-")
            assert _shown(group, number) == drawing[layer], f"page {number}, layer {layer}"
    hidden = [g for g in root.iter(f"{SVG}g") if "data-pages" in g.attrib]
    assert hidden, "some elements are not on every page"
    for group in hidden:  # as written, the page shows page 1's drawing
        assert (group.attrib.get("display") == "none") == (_ranges(group.attrib["data-pages"])[0][0] != 1)
    leaves = sum(len(group) for page in alone for group in page[1].values())
    assert len(re.findall(r"<(?:path|circle|line|text)\b", text)) < leaves / 3  # written once, not once a page


def _item(n: int) -> PathItem:
    return PathItem(((float(n), 0.0), (0.0, 1.0)), Stroke("#000000", 0.25))


@given(st.lists(st.lists(st.integers(0, 6), max_size=8), min_size=1, max_size=6))
def test_the_merged_sequence_holds_each_page_in_its_order(pages: list[list[int]]) -> None:
    items = [_item(n) for n in range(7)]
    merged = merged_pages([[items[n] for n in page] for page in pages])
    for number, page in enumerate(pages, 1):
        assert [item for item, numbers in merged if number in numbers] == [items[n] for n in page]
    assert all(numbers == sorted(set(numbers)) for _, numbers in merged)
    assert len(merged) <= sum(len(page) for page in pages)
    if all(page == pages[0] for page in pages):
        assert len(merged) == len(pages[0])  # the same page again adds nothing


def test_page_ranges() -> None:
    assert page_ranges([3, 4, 5, 9]) == "3-5 9"
    assert page_ranges([1]) == "1" and page_ranges([2, 4, 5]) == "2 4-5"


@pytest.fixture(scope="module")
def chain_page(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Solution, Handout]:
    solution = _solution("chain-3")
    handout, text = handout_html(solution, load_catalogue("en"))
    target = tmp_path_factory.mktemp("handout") / "chain-3.html"
    target.write_text(text, encoding="utf-8")
    return target, solution, handout


_VISIBLE = """(() => {
  const s = document.querySelector('section.page:not([hidden])');
  const svg = s.querySelector('svg');
  const shown = Array.from(svg.querySelectorAll('g[class^=layer-] > path, g[class^=layer-] > circle,'
    + ' g[class^=layer-] > line, g[class^=layer-] > text, g[class^=layer-] > g > *'))
    .filter(e => getComputedStyle(e).display !== 'none' && !e.closest('[display=none]'));
  return [document.querySelectorAll('svg').length, shown.length, svg.querySelector('title').textContent];
})()"""


def test_chromium_shows_page_k_drawing(browser: Any, chain_page: tuple[Path, Solution, Handout],
                                       tmp_path: Path) -> None:
    target, solution, handout = chain_page
    alone = _alone(solution, handout, "en")
    for number in (1, 2, 9, len(alone)):
        browser.goto("about:blank")
        browser.goto(target.as_uri() + f"#page-{number}")
        count, shown, title = browser.evaluate(_VISIBLE)
        assert (count, title) == (1, alone[number - 1][0])
        assert shown == sum(len(group) for group in alone[number - 1][1].values()), f"page {number}"
    browser.keyboard.press("Home")
    browser.keyboard.press("ArrowRight")
    assert browser.evaluate(_VISIBLE)[1] == sum(len(group) for group in alone[1][1].values())
    browser.screenshot(path=str(tmp_path / "page-2.png"))
    assert browser.errors == []
