"""The handout's web page in a real browser (Debian's chromium, headless): it steps through the construction.

Driven by playwright (``tests/chromium.py``): the address's ``#page-N`` opens a page, the arrow
keys, Home and End, the buttons (real mouse clicks) and the slider (focused, moved with a key)
change it, and the page shown is always the one the address and the label name. Skipped where
chromium is not installed, except on CI (CI set), where that is a failure.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from tests.scenes import EXAMPLES

from kinepoly.cli import main


@pytest.fixture(scope="module")
def page(tmp_path_factory: pytest.TempPathFactory) -> Path:
    target = tmp_path_factory.mktemp("handout") / "four-bar.html"
    assert main(["handout", str(EXAMPLES / "four-bar.toml"), "--html", str(target), "--lang", "tr"]) == 0
    return target


def _go(browser: Any, url: str) -> None:
    """Load ``url`` afresh (by way of about:blank, so that a change of the hash alone loads it too)."""
    browser.goto("about:blank")
    browser.goto(url)


def _state(browser: Any) -> tuple[int, str, str, str]:
    """(page number shown, the address's hash, the id of the one section shown, the label)."""
    shown = browser.evaluate("Array.from(document.querySelectorAll('section.page')).filter(s => !s.hidden)"
                             ".map(s => s.id)")
    assert len(shown) == 1
    return (int(browser.evaluate("document.body.dataset.page")), browser.evaluate("location.hash"), shown[0],
            browser.evaluate("document.getElementById('where').textContent"))


def test_the_page_steps_through_the_construction(browser: Any, page: Path, tmp_path: Path) -> None:
    _go(browser, page.as_uri() + "#page-3")
    count = browser.evaluate("document.querySelectorAll('section.page').length")
    assert count == 15
    number, where, shown, label = _state(browser)
    assert (number, where, shown) == (3, "#page-3", "page-3") and label.startswith("Adım 2 / 13")
    browser.screenshot(path=str(tmp_path / "page-3.png"))
    browser.keyboard.press("ArrowRight")
    assert _state(browser)[:3] == (4, "#page-4", "page-4")
    browser.click("#next")
    assert _state(browser)[:3] == (5, "#page-5", "page-5")
    browser.click("#previous")
    browser.click("#previous")
    assert _state(browser)[:3] == (3, "#page-3", "page-3")
    browser.keyboard.press("End")
    assert _state(browser)[:3] == (15, "#page-15", "page-15")
    assert browser.evaluate("document.getElementById('next').disabled") is True
    browser.keyboard.press("ArrowRight")  # past the end: stays
    assert _state(browser)[0] == 15
    browser.keyboard.press("Home")
    number, _, _, label = _state(browser)
    assert number == 1 and label == "Soru" and browser.evaluate("document.getElementById('previous').disabled")
    browser.focus("#slider")
    browser.keyboard.press("ArrowRight")  # the slider's own key: one page on, not two
    assert _state(browser)[:3] == (2, "#page-2", "page-2")
    assert browser.evaluate("document.getElementById('slider').value") == "2"
    browser.screenshot(path=str(tmp_path / "page-2.png"))
    assert (tmp_path / "page-2.png").read_bytes().startswith(b"\x89PNG")
    assert browser.errors == []


def test_each_section_shows_its_drawing_and_its_equation(browser: Any, page: Path) -> None:
    _go(browser, page.as_uri() + "#page-11")
    shown = browser.evaluate("(() => { const s = document.querySelector('section.page:not([hidden])');"
                             " const r = s.querySelector('svg').getBoundingClientRect();"
                             " return [s.dataset.equation, "
                             "s.querySelector('.equation').textContent, r.width, r.height];"
                             " })()")
    equation, written, width, height = shown
    assert equation.startswith("a_B = a_A + a^n_B/A") and written.replace(" ", "") == \
        equation.replace("_", "").replace("^", "").replace(" ", "")
    assert width > 400 and height > 200  # the drawing is laid out, not collapsed
    assert browser.errors == []
