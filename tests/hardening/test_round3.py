"""Issue 30's reproducers (hardening, round 3), one test each: each failed before its fix.

Script data in web pages; exit 70 on input that deserves a message; output files (an input given
as output, devices, modes, SIGTERM); bounded reading, depth and cost.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from tests.hardening.support import BASE, edit, run_on

from kinepoly.present.script_json import script_json

# -- 1. script data in web pages -----------------------------------------------------------------------------------

HOSTILE = ["<!--<script>", "</script><script>window.pwned = 1</script>", "a & b > c", "]]><!--", "\u2028x"]


@pytest.mark.parametrize("text", HOSTILE)
def test_script_json_escapes_what_could_end_or_comment_the_element(text: str) -> None:
    data = script_json({"title": text, "names": [text]})
    assert not {"<", ">", "&"} & set(data)
    assert json.loads(data) == {"title": text, "names": [text]}


def test_script_json_refuses_nan() -> None:
    with pytest.raises(ValueError):
        script_json([float("nan")])


def _hostile_scene() -> str:
    title = "<!--<script> & </script><script>window.pwned = 1</script>"
    return edit('3 = { points = { A = [0, 0], B = [120, 0] } }',
                '"<!--<script>" = { points = { A = [0, 0], B = [120, 0] } }',
                before=f"title = {json.dumps(title)}\n").replace('"3"', '"<!--<script>"')


def test_the_animation_page_keeps_its_data_and_script_in_a_browser(browser: Any, capsys: pytest.CaptureFixture[str],
                                                                  tmp_path: Path) -> None:
    text = _hostile_scene()
    code, _, err = run_on(capsys, tmp_path, text, "animate", "-o", "{tmp}/m.html", "--positions", "12")
    assert code == 0, err
    page = (tmp_path / "m.html").read_text(encoding="utf-8")
    data = page.split('<script type="application/json" id="frames">')[1].split("</script>")[0]
    assert "<" not in data and ">" not in data and "&" not in data
    browser.goto((tmp_path / "m.html").as_uri())
    assert browser.evaluate("typeof window.kinepoly") == "object"  # the page's own script ran
    assert browser.evaluate("window.pwned === undefined")
    assert browser.evaluate("window.kinepoly.data.title") == json.loads(text.splitlines()[0].split("=", 1)[1])
    assert "<!--<script>" in browser.evaluate("window.kinepoly.data.links.map(l => l.name)")
    assert browser.evaluate("document.querySelectorAll('#panels svg').length") >= 1
    assert browser.errors == []


def test_the_handout_page_shows_a_hostile_title_as_text_in_a_browser(browser: Any,
                                                                      capsys: pytest.CaptureFixture[str],
                                                                      tmp_path: Path) -> None:
    code, _, err = run_on(capsys, tmp_path, _hostile_scene(), "handout", "--html", "{tmp}/h.html")
    assert code == 0, err
    browser.goto((tmp_path / "h.html").as_uri())
    assert browser.evaluate("window.pwned === undefined")
    assert browser.text_content("h1").startswith("<!--<script> & </script>")
    assert browser.evaluate("document.querySelectorAll('main section').length") > 1
    assert browser.errors == []
