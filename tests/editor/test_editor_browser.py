"""The editor's page in a real browser (Debian's chromium driven by playwright): drag, see, save, come back."""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from tests.cli_support import run
from tests.editor.drive import drag, handle, screen, wait_settled
from tests.editor.server import Served, serving

from kinepoly.editor.document import Document, template_text
from kinepoly.editor.evaluate import evaluate


@pytest.fixture
def new_four_bar(tmp_path: Path) -> Iterator[tuple[Served, Path]]:
    """The editor of a new file started from the four-bar template."""
    path = tmp_path / "mine.toml"
    with serving(Document(str(path), template_text("four-bar"))) as served:
        yield served, path


def _open(page: Any, served: Served) -> None:
    page.errors.clear()
    page.goto(served.url)
    page.wait_for_selector("#sheet svg #handles")
    wait_settled(page)


def _layer(page: Any, name: str) -> str:
    return str(page.inner_html(f"#sheet svg g#{name}"))


def _state(page: Any) -> dict[str, Any]:
    return dict(page.evaluate("() => window.kinepolyEditor.state"))


def _without_timing(result: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in result.items() if k != "timing"}


def _turn(angle_deg: float, radius: float = 40.0) -> tuple[float, float]:
    return radius * math.cos(math.radians(angle_deg)), radius * math.sin(math.radians(angle_deg))


def test_drag_the_crank_and_a_pivot_and_save_what_solve_gives(browser: Any, new_four_bar: tuple[Served, Path],
                                                              capsys: pytest.CaptureFixture[str]) -> None:
    served, path = new_four_bar
    _open(browser, served)
    velocity, acceleration = _layer(browser, "velocity-polygon"), _layer(browser, "acceleration-polygon")
    drag(browser, _turn(60), [_turn(a) for a in range(70, 150, 10)])
    assert _state(browser)["result"]["links"]["3"]["angle"] != pytest.approx(22.7, abs=1)
    assert _layer(browser, "velocity-polygon") != velocity and _layer(browser, "acceleration-polygon") != acceleration
    turned = _layer(browser, "velocity-polygon")
    drag(browser, (100, 0), [(104, -3), (108, -6), (112, -8)])  # the rocker's frame pivot B0
    assert handle(browser, "B0") == pytest.approx((112, -8), abs=0.6)
    assert _layer(browser, "velocity-polygon") != turned
    assert "angle = 140" in _state(browser)["text"]
    browser.click("#save")
    browser.wait_for_function("() => document.querySelector('#status').textContent.startsWith('saved')")
    wait_settled(browser)
    assert not _state(browser)["dirty"]
    code, out, err = run(capsys, "solve", str(path), "--json")
    assert code == 0, err
    shown = _state(browser)["result"]
    assert _without_timing(shown) == _without_timing(json.loads(out))
    omega3 = browser.inner_text("#values tr:nth-child(2) td:nth-child(3)")
    assert float(omega3) == pytest.approx(shown["links"]["3"]["omega"], rel=1e-5)
    saved = path.read_text(encoding="utf-8")
    template = template_text("four-bar")
    comments = [line[line.index("#"):] for line in template.splitlines() if "#" in line]
    assert comments and all(comment in saved for comment in comments)
    assert browser.errors == []


def test_an_impossible_position_keeps_the_last_drawing_and_dragging_back_loses_nothing(
        browser: Any, new_four_bar: tuple[Served, Path]) -> None:
    served, _ = new_four_bar
    _open(browser, served)
    # a crank of 100 (its point A moved out along it, the coupler's A with it: AB 85.1): from theta12 = 111 deg
    # on, |AB0| > |AB| + |BB0| and the four-bar cannot close
    drag(browser, _turn(60), [_turn(60, r) for r in (55, 70, 85, 100)], shift=True)
    state = _state(browser)
    lengths = {(x["link"], x["point"]): x["length"] for x in state["handles"]["lengths"]}
    assert lengths["2", "A"] == pytest.approx(100, abs=0.5) and state["ok"]
    good_svg, good_text = browser.inner_html("#sheet"), state["text"]
    browser.mouse.move(*screen(browser, _turn(60, 100)))
    browser.mouse.down()  # one drag: out to 140 degrees, where it cannot close, and back
    for a in (80, 100, 120, 140):
        browser.mouse.move(*screen(browser, _turn(a, 100)))
        wait_settled(browser)
    state = _state(browser)
    assert not state["ok"] and state["exit"] == 3
    message = browser.inner_text("#message")
    assert "cannot assemble" in message and message.startswith(state["errors"][0])
    assert "stale" in (browser.get_attribute("#sheet", "class") or "")
    assert state["good_result"] is not None and state["svg"] != good_svg
    shown = browser.inner_html("#sheet")
    for a in (120, 100, 80, 60):
        browser.mouse.move(*screen(browser, _turn(a, 100)))
        wait_settled(browser)
    browser.mouse.up()
    assert browser.evaluate("() => window.kinepolyEditor.drag") is None  # released: the drawing was replaced meanwhile
    state = _state(browser)
    assert state["ok"] and not browser.is_visible("#message") and browser.inner_html("#sheet") != shown
    assert "stale" not in (browser.get_attribute("#sheet", "class") or "")
    assert state["handles"]["fields"]["angle"] == pytest.approx(60, abs=0.5)
    kept = [line for line in good_text.splitlines() if not line.startswith(("angle =", "B ="))]
    assert kept == [line for line in state["text"].splitlines() if not line.startswith(("angle =", "B ="))]
    assert browser.errors == []


def test_undo_redo_and_a_field(browser: Any, new_four_bar: tuple[Served, Path]) -> None:
    served, _ = new_four_bar
    _open(browser, served)
    first = _state(browser)["text"]
    browser.fill("#input-fields input[data-key=omega]", "-12")
    browser.dispatch_event("#input-fields input[data-key=omega]", "change")
    wait_settled(browser)
    assert "omega = -12" in _state(browser)["text"]
    assert _state(browser)["result"]["points"]["A"]["velocity"] == pytest.approx([12 * 40 * math.sin(math.pi / 3),
                                                                                   -12 * 40 * 0.5])
    browser.click("#undo")
    wait_settled(browser)
    assert _state(browser)["text"] == first
    browser.click("#redo")
    wait_settled(browser)
    assert "omega = -12" in _state(browser)["text"]
    browser.click("#steps li:nth-child(3)")
    browser.wait_for_function("() => document.querySelector('#step-image').complete && "
                              "document.querySelector('#step-image').naturalWidth > 0")
    assert browser.is_visible("#step-dialog")
    browser.click("#step-dialog button")
    assert browser.errors == []


def test_save_does_not_overwrite_a_file_changed_on_disk_without_asking(browser: Any, tmp_path: Path) -> None:
    path = tmp_path / "four-bar.toml"
    path.write_text(template_text("four-bar"), encoding="utf-8")
    with serving(Document(str(path))) as served:
        _open(browser, served)
        drag(browser, _turn(60), [_turn(80)])
        path.write_text("# someone else's\n" + template_text("four-bar"), encoding="utf-8")
        asked: list[str] = []

        def answer(dialog: Any) -> None:
            asked.append(dialog.message)
            dialog.dismiss()

        browser.once("dialog", answer)
        browser.click("#save")
        browser.wait_for_function("() => document.querySelector('#status').textContent.startsWith('not saved')")
        assert asked and "changed on disk" in asked[0]
        assert path.read_text(encoding="utf-8").startswith("# someone else's\n")
    assert [e for e in browser.errors if "status of 409" not in e] == []  # the browser logs the refused save


def _mirror(p: tuple[float, float], a: tuple[float, float], b: tuple[float, float]) -> tuple[float, float]:
    """``p`` reflected in the line ``ab`` (the test's own arithmetic, to know where the other assembly is)."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)
    foot = (a[0] + t * dx, a[1] + t * dy)
    return 2 * foot[0] - p[0], 2 * foot[1] - p[1]


def test_the_other_assembly_is_taken_by_dragging_the_guess_across(browser: Any,
                                                                  new_four_bar: tuple[Served, Path]) -> None:
    served, _ = new_four_bar
    _open(browser, served)
    browser.fill("#text", template_text("four-bar").replace("[guess]\nB = [110, 80]\n", ""))
    browser.click("#apply")
    wait_settled(browser)
    assert _state(browser)["ok"] and not _state(browser)["handles"]["guess"]
    browser.click("#guesses button[data-guess=B]")  # a guess where B is: its ring appears on B
    wait_settled(browser)
    b = handle(browser, "B")
    assert _state(browser)["handles"]["guess"]["B"] == pytest.approx(list(b), abs=0.01)
    other = _mirror(b, handle(browser, "A"), handle(browser, "B0"))
    ring = 3.2 / _state(browser)["view"]["scale"]  # the ring's radius on the paper, in the scene
    drag(browser, (b[0] + ring, b[1]),
         [((b[0] + other[0]) / 2 + ring, (b[1] + other[1]) / 2), (other[0] + ring, other[1])])
    assert handle(browser, "B") == pytest.approx(other, abs=0.5)
    assert _state(browser)["ok"] and browser.errors == []


def test_a_drag_shows_draft_sheets_and_the_release_or_a_pause_the_whole_one(browser: Any,
                                                                            new_four_bar: tuple[Served, Path]) -> None:
    served, _ = new_four_bar
    _open(browser, served)
    source = served.document.source
    assert _state(browser)["draft"] is False
    browser.evaluate("() => { window.kinepolyEditor.pauseMs = 60000; }")  # no pause while the test looks
    browser.mouse.move(*screen(browser, _turn(60)))
    browser.mouse.down()
    for a in (75, 90, 105):
        browser.mouse.move(*screen(browser, _turn(a)))
        wait_settled(browser)
        state = _state(browser)
        assert state["ok"] and state["draft"] is True and "draft" in (browser.get_attribute("#sheet", "class") or "")
    # the draft is the sheet of the text as dragged, its labels at their first places: not the whole sheet
    assert state["svg"] == evaluate(state["text"], source, draft=True).svg != evaluate(state["text"], source).svg
    browser.mouse.up()
    wait_settled(browser)
    released = _state(browser)
    whole = evaluate(released["text"], source).svg
    assert released["text"] == state["text"] and released["draft"] is False and released["svg"] == whole
    assert httpx.get(served.url + "api/drawing.svg").text == whole
    assert "draft" not in (browser.get_attribute("#sheet", "class") or "")
    assert browser.evaluate("() => window.kinepolyEditor.fullTimings.length") == 1
    # a drag that pauses gets the whole sheet without being released
    browser.evaluate("() => { window.kinepolyEditor.pauseMs = 150; }")
    browser.mouse.move(*screen(browser, _turn(105)))  # onto the crank's point, on the whole sheet
    browser.mouse.down()
    browser.mouse.move(*screen(browser, _turn(120)))
    browser.wait_for_function("() => window.kinepolyEditor.fullTimings.length === 2")
    wait_settled(browser)
    paused = _state(browser)
    assert browser.evaluate("() => window.kinepolyEditor.drag") is not None  # still held
    assert paused["draft"] is False and paused["svg"] == evaluate(paused["text"], source).svg
    assert "angle = 120" in paused["text"]
    browser.mouse.up()
    wait_settled(browser)
    assert browser.evaluate("() => window.kinepolyEditor.fullTimings.length") == 2  # nothing left to draw whole
    assert browser.errors == []


def test_a_drag_never_queues_a_stale_move(browser: Any, new_four_bar: tuple[Served, Path]) -> None:
    served, _ = new_four_bar
    _open(browser, served)
    browser.mouse.move(*screen(browser, _turn(60)))
    browser.mouse.down()
    places = [screen(browser, _turn(a)) for a in range(65, 125, 5)]
    # twelve moves in one task, faster than any answer: the first is sent, each later one replaces the one waiting
    waiting = browser.evaluate("""(places) => places.map(([x, y]) => {
        document.querySelector('#sheet').dispatchEvent(new PointerEvent('pointermove', {clientX: x, clientY: y,
            bubbles: true, pointerId: 1}));
        return window.kinepolyEditor.pending.length;
    })""", places)
    assert waiting == [0] + [1] * 11
    browser.mouse.up()
    wait_settled(browser)
    state = _state(browser)
    assert "angle = 120" in state["text"] and state["draft"] is False
    assert len(browser.evaluate("() => window.kinepolyEditor.timings")) == 2  # the ten stale moves never sent
    assert browser.errors == []
