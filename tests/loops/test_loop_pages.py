"""The handout's loop-closure pages (``kinepoly handout --loops``): a page per loop after the answers, in the
catalogue's language, with the loop's equation, its derivatives and the systems with their solutions."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.handout.build import handout_content
from kinepoly.handout.content import Paragraph
from kinepoly.handout.loop_pages import loop_pages
from kinepoly.loops import loop_method_solution
from kinepoly.present.catalogue import load_catalogue


def _text(page: object) -> str:
    return "\n".join(part.text for column in page.columns for part in column.parts  # type: ignore[attr-defined]
                     if isinstance(part, Paragraph))


@pytest.mark.parametrize("code", ["en", "tr", "ro"])
def test_a_page_per_loop_after_the_answers(code: str) -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "shaper.toml"))
    loops = loop_method_solution(solution)[1]
    say = load_catalogue(code)
    scales = {"mechanism": 1.0, "velocity": 0.1, "acceleration": 0.01}
    plain = handout_content(solution, say, scales)
    handout = handout_content(solution, say, scales, loops)
    assert handout.pages[: len(plain.pages)] == plain.pages
    pages = handout.pages[len(plain.pages):]
    assert pages == loop_pages(loops, say) and len(pages) == 2
    first, second = (_text(page) for page in pages)
    assert "N = j − n + 1 = 7 − 6 + 1 = 2" in first and "N = j" not in second
    assert "60 e^(i θ12) − s43 e^(i θ14) = 0" in first  # the handout's notation: digits lowered when typeset
    assert "2 i ω14 s\u030743 e^(i θ14)" in first and "a^c" in first
    assert "Δ" in first and "s\u030743 = " in first and "α15 = " in second
    assert say.number(loops.omega["5"]) in second


def test_the_handout_command_adds_the_pages(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    out = tmp_path / "h.pdf"
    code, printed, _ = run(capsys, "handout", str(EXAMPLES / "four-bar.toml"), "--loops", "-o", str(out),
                           "--lang", "tr")
    assert code == 0 and out.stat().st_size > 0
    _, plain, _ = run(capsys, "handout", str(EXAMPLES / "four-bar.toml"), "-o", str(tmp_path / "p.pdf"), "--lang", "tr")

    def pages(text: str) -> int:
        return int(re.search(r"\((\d+) pages", text).group(1))  # type: ignore[union-attr]

    assert pages(printed) == pages(plain) + 1  # the four-bar has one loop
    code, _, err = run(capsys, "handout", str(EXAMPLES / "metu-cam.toml"), "--loops", "-o", str(tmp_path / "c.pdf"))
    assert code == 2 and "does not cover" in err and not (tmp_path / "c.pdf").exists()


def test_the_web_page_has_the_loop_pages_too(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    page = tmp_path / "h.html"
    code, printed, _ = run(capsys, "handout", str(EXAMPLES / "shaper.toml"), "--loops", "--html", str(page))
    _, plain, _ = run(capsys, "handout", str(EXAMPLES / "shaper.toml"), "--html", str(tmp_path / "p.html"))
    assert code == 0
    assert int(re.search(r"\((\d+) pages", printed).group(1)) == int(re.search(r"\((\d+) pages", plain).group(1)) + 2  # type: ignore[union-attr]
    assert "Loop-closure method, loop" in page.read_text()
