"""The handout's page of a cam's equivalent-linkage step, in every language: what the pair is replaced by,
where the link's ends are (against the scene's own numbers), why it is valid at this instant."""

from __future__ import annotations

import math

import pytest
from tests.render.clearance import conflicts
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.handout import handout_sheets, load_catalogue
from kinepoly.handout.content import Page, Paragraph, Table
from kinepoly.handout.notation import plain_of

LANGS = ("en", "tr", "ro")


def _page(name: str, lang: str) -> tuple[kinepoly.Solution, Page, int, list[object]]:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    handout, sheets = handout_sheets(solution, load_catalogue(lang))
    found = [(k, p) for k, p in enumerate(handout.pages) if p.kind == "step" and any(
        isinstance(part, Paragraph) and "K_A(−1)" in part.text for c in p.columns for part in c.parts)]
    assert len(found) == 1
    k, page = found[0]
    return solution, page, k, sheets


def _text(page: Page) -> str:
    return " ".join(plain_of(part.text) for c in page.columns for part in c.parts if isinstance(part, Paragraph))


def _table(page: Page) -> Table:
    return next(part for c in page.columns for part in c.parts if isinstance(part, Table))


@pytest.mark.parametrize("lang", LANGS)
def test_roller_page_names_the_link_its_ends_and_why(lang: str) -> None:
    solution, page, k, sheets = _page("cam-roller-rocker", lang)
    say = load_catalogue(lang)
    assert page.equation == f"K23W = {say.number(50.0)} mm"  # R + r = 40 + 10
    rows = _table(page).rows
    assert [r[:2] for r in rows] == [("K23", "2"), ("W", "3")]
    theta = math.radians(30.0)
    k_at = (15.0 * math.cos(theta), 15.0 * math.sin(theta))  # the disc's centre turned with the cam
    assert rows[0][2] == say.pair(*k_at)
    assert rows[1][2] == say.pair(*solution.position("W"))
    text = _text(page)
    for word in ("K23W", "K23", "C23", say.pair(*solution.contacts["23"].point)):
        assert word in text
    assert "eq23" not in text  # the construction's own name: the course texts say the equivalent link K23W
    raw = " ".join(part.text for c in page.columns for part in c.parts if isinstance(part, Paragraph))
    assert "v_W = v_K23 + v_W/K23" in raw and "a^n_W/K23" in raw  # the relations of a binary link
    assert not conflicts(sheets[k])  # type: ignore[arg-type]


@pytest.mark.parametrize("lang", LANGS)
def test_flat_face_page_names_the_block_and_its_slide(lang: str) -> None:
    _, page, k, sheets = _page("eccentric-cam-flat", lang)
    say = load_catalogue(lang)
    assert page.equation == f"K ∥ 3, d = {say.number(35.0)} mm"
    rows = _table(page).rows
    assert rows[0][:2] == ("K", "2") and rows[0][2] == say.pair(12 * math.cos(math.radians(40)),
                                                                  12 * math.sin(math.radians(40)))
    assert rows[1] == (say.say("higher_pairs.end_slide"), "3", f"d = {say.number(35.0)}")
    assert "Coriolis" in _text(page)
    assert "eq23" not in _text(page)  # the block at K on the face, as the course texts say
    assert not conflicts(sheets[k])  # type: ignore[arg-type]


def test_the_three_languages_say_different_words() -> None:
    texts = {lang: _text(_page("cam-roller-rocker", lang)[1]) for lang in LANGS}
    assert len(set(texts.values())) == 3
