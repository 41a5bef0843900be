"""The motion's web page in a real browser (Debian's chromium, headless, driven by playwright).

It opens with no script error, plays and pauses, and moving the slider to position k shows row
k's values (exactly: each value's cell carries its number). Skipped where chromium is not
installed, except on CI (CI set), where that is a failure.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from tests.scenes import EXAMPLES

from kinepoly.cli import main
from kinepoly.scene.loader import load_scene
from kinepoly.sweep.run import sweep


@pytest.fixture(scope="module")
def page(tmp_path_factory: pytest.TempPathFactory) -> Path:
    target = tmp_path_factory.mktemp("animate") / "slotted-lever.html"
    assert main(["animate", str(EXAMPLES / "slotted-lever.toml"), "-o", str(target), "--positions", "48",
                 "--parts", "mechanism", "velocity", "acceleration", "centers", "paths", "functions"]) == 0
    return target


def _slide_to(browser: Any, k: int) -> None:
    browser.eval_on_selector("#position", "(s, k) => { s.value = k; s.dispatchEvent(new Event('input')); }", k)


def _values(browser: Any) -> dict[str, str]:
    return browser.evaluate("Object.fromEntries(Array.from(document.querySelectorAll('td[data-name]'))"
                            ".map(td => [td.dataset.name, td.dataset.value]))")


def test_the_slider_shows_row_k(browser: Any, page: Path) -> None:
    browser.goto(page.as_uri())
    result = sweep(load_scene(str(EXAMPLES / "slotted-lever.toml")), steps=48)
    assert browser.evaluate("document.getElementById('position').max") == "47"
    drawn = set()
    for k in (0, 7, 30, 47):
        _slide_to(browser, k)
        # one drawing: the frame's sheet, as `kinepoly draw` draws (its layers), captioned with its position
        assert browser.evaluate("document.querySelectorAll('#drawing svg').length") == 1
        assert browser.evaluate("document.querySelectorAll('#drawing svg g#velocity-polygon *').length") > 0
        assert f"position {k + 1} of 48" in browser.text_content("#drawing svg g#title")
        drawn.add(browser.inner_html("#drawing"))
        assert browser.evaluate("document.body.dataset.row") == str(k)
        shown = _values(browser)
        for name in ("theta_2", "omega_4", "alpha_4"):
            column = result.column(name)
            assert float(shown[name]) == column.values[k]
        assert browser.text_content("#where").startswith(f"position {k + 1} of 48: theta_2 = ")
    assert len(drawn) == 4
    assert browser.errors == []


def test_play_and_pause(browser: Any, page: Path, tmp_path: Path) -> None:
    browser.goto(page.as_uri())
    assert browser.evaluate("document.body.dataset.frame") == "0"
    browser.click("#play")
    assert browser.text_content("#play") == "Pause"
    browser.wait_for_function("Number(document.body.dataset.frame) >= 3")
    browser.click("#play")
    assert browser.text_content("#play") == "Play"
    stopped = browser.evaluate("document.body.dataset.frame")
    browser.wait_for_timeout(300)
    assert browser.evaluate("document.body.dataset.frame") == stopped
    browser.keyboard.press("ArrowRight")
    assert browser.evaluate("document.body.dataset.frame") == str(int(stopped) + 1)
    browser.screenshot(path=str(tmp_path / "motion.png"))
    assert (tmp_path / "motion.png").read_bytes().startswith(b"\x89PNG")
    assert browser.errors == []


def test_the_page_fetches_nothing(page: Path) -> None:
    text = page.read_text()
    for namespace in ("http://www.w3.org/2000/svg", "http://www.w3.org/1999/xlink", "http://www.w3.org/2001/xml-events"):
        text = text.replace(namespace, "")  # the SVG's namespaces: names, nothing fetched
    assert "http://" not in text and "https://" not in text
    assert "<script src" not in text and "<link" not in text
