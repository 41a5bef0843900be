"""Links added and removed by clicking on the editor's page, in chromium: a point on two links is a pin."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from tests.cli_support import run
from tests.editor.drive import drag, handle, screen, wait_settled
from tests.editor.server import Served, serving

from kinepoly.editor.document import Document, template_text


@pytest.fixture
def new_four_bar(tmp_path: Path) -> Iterator[tuple[Served, Path]]:
    path = tmp_path / "six.toml"
    with serving(Document(str(path), template_text("four-bar"))) as served:
        yield served, path


def _state(page: Any) -> dict[str, Any]:
    return dict(page.evaluate("() => window.kinepolyEditor.state"))


def _click(page: Any, at: tuple[float, float]) -> None:
    page.mouse.click(*screen(page, at))


def test_a_dyad_added_by_three_clicks_makes_a_six_bar_that_solves_and_drags(
        browser: Any, new_four_bar: tuple[Served, Path], capsys: pytest.CaptureFixture[str]) -> None:
    served, path = new_four_bar
    browser.errors.clear()
    browser.goto(served.url)
    browser.wait_for_selector("#sheet svg #handles")
    wait_settled(browser)
    browser.click("#add-pin")
    _click(browser, handle(browser, "C"))        # from the coupler point C
    _click(browser, (150, 130))                  # the new joint D
    _click(browser, (200, 0))                    # an empty place: a new frame pivot D0
    wait_settled(browser)
    state = _state(browser)
    assert state["ok"], state["errors"]
    assert handle(browser, "D") == pytest.approx((150, 130), abs=1.0)
    assert handle(browser, "D0") == pytest.approx((200, 0), abs=1.0)
    assert state["handles"]["points"]["D"]["links"] == ["5", "6"]  # a point on two links: a pin
    assert {"5", "6"} <= set(state["result"]["links"])
    drag(browser, handle(browser, "A"), [(10, 39), (0, 40), (-10, 39)])  # the six-bar follows the crank
    assert _state(browser)["ok"]
    browser.click("#save")
    browser.wait_for_function("() => document.querySelector('#status').textContent.startsWith('saved')")
    code, out, err = run(capsys, "solve", str(path), "--json")
    assert code == 0, err
    shown = {k: v for k, v in _state(browser)["result"].items() if k != "timing"}
    assert shown == {k: v for k, v in json.loads(out).items() if k != "timing"}
    for link in ("6", "5"):  # removed again, the four-bar is back as it was
        browser.click(f"#links button[data-link='{link}']")
        wait_settled(browser)
    state = _state(browser)
    assert state["ok"] and "D" not in state["text"]
    assert state["text"].replace("\n", "") != ""  # the template's text but for the crank's angle and the guess
    kept = [line for line in template_text("four-bar").splitlines() if not line.startswith(("angle =", "B ="))]
    assert kept == [line for line in state["text"].splitlines() if not line.startswith(("angle =", "B ="))]
    assert browser.errors == []


def test_a_slider_dyad_added_by_clicks_slides_on_the_frame(browser: Any, new_four_bar: tuple[Served, Path]) -> None:
    served, _ = new_four_bar
    browser.errors.clear()
    browser.goto(served.url)
    browser.wait_for_selector("#sheet svg #handles")
    wait_settled(browser)
    browser.click("#add-slider")
    _click(browser, handle(browser, "C"))
    _click(browser, (150, 60))
    _click(browser, (250, 60))                   # the slide: horizontal, through the joint
    wait_settled(browser)
    state = _state(browser)
    assert state["ok"], state["errors"]
    assert "[[sliders]]" in state["text"] and 'block = "6"' in state["text"] and "angle = 0" in state["text"]
    at = handle(browser, "D")
    drag(browser, handle(browser, "A"), [(10, 39), (0, 40)])
    moved = handle(browser, "D")
    assert moved[1] == pytest.approx(at[1], abs=0.05) and moved[0] != pytest.approx(at[0], abs=0.5)  # on its line
    browser.click("#add-pin")
    browser.keyboard.press("Escape")
    assert "cancelled" in browser.inner_text("#status")
    assert browser.errors == []
