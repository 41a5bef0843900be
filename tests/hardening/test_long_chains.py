"""Issue 15: long mechanisms. A label naming many coinciding points is broken into lines that stay in its
panel; a handout's labels are placed once, on the whole drawing, and each page shows them there; a sheet
the mechanism overfills is still drawn (exit 0), with what was done said on the sheet and on stderr."""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.hardening.support import edit, run_on
from tests.render.clearance import conflicts
from tests.render.test_render_labels_once import _counting
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.bench.chain import chain_text
from kinepoly.handout import handout_sheets, load_catalogue
from kinepoly.render.labels import wrapped
from kinepoly.render.primitives import Text
from kinepoly.render.sheet import build_sheet, step_sheets
from kinepoly.render.text import Run, runs_box, text_width
from kinepoly.scene.loader import loads_scene


def _names(count: int, between: str = ", ") -> tuple[Run, ...]:
    """``o, g1, g2, ...`` as the polygons join the names of coinciding tips (or ``o = g1 = ...``, of equal
    vectors), a subscript each."""
    runs, x = [Run("o", 0.0, 0.0, 2.5)], text_width("o", 2.5)
    for k in range(1, count):
        runs += [Run(between, x, 0.0, 2.5), Run("g", x + text_width(between, 2.5), 0.0, 2.5)]
        x += text_width(between + "g", 2.5)
        runs.append(Run(str(k), x, -0.6, 1.75))
        x += text_width(str(k), 1.75)
    return tuple(runs)


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 120), st.floats(12.0, 200.0), st.sampled_from([", ", " = "]))
def test_a_long_label_is_broken_into_lines_no_wider_than_asked(count: int, width: float, between: str) -> None:
    runs = _names(count, between)
    out = wrapped(runs, width)
    assert "".join(r.text for r in out) == "".join(r.text for r in runs)  # every name, in order
    lines = Counter(round(r.dy, 6) for r in out if r.dy == 0.0 or r.text == "o" or r.text == "g")
    x0, _, x1, _ = runs_box(out)
    widest_name = max(text_width(between + "g", 2.5) + text_width(str(k), 1.75) for k in range(max(count, 2)))
    assert x1 - x0 <= max(width, widest_name) + 1e-9
    assert x0 == pytest.approx(runs_box(runs)[0])  # the first line starts where the label did
    if runs_box(runs)[2] - runs_box(runs)[0] <= width:
        assert out == runs
    else:
        assert len(lines) >= 2
        # a line's names stay together: a subscript is on its name's line
        for k, run in enumerate(out):
            if run.text.isdigit():
                assert run.dy == pytest.approx(out[k - 1].dy - 0.6)


def test_a_handout_places_its_labels_once_on_the_whole_drawing(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every label on every page placed anew would be ~ 3,000 placements for the 5-loop chain. The whole
    drawing's labels are placed once on each paper tried (A4, then A3), in each polygon (a role such as
    ``tip p1`` names a tip of both), and on a page only a label whose text differs there (a group of
    coinciding tips not yet complete)."""
    solution = kinepoly.solve(loads_scene(chain_text(5), "chain-5.toml"))
    calls = _counting(monkeypatch)
    _, sheets = handout_sheets(solution, load_catalogue("en"), "A4")
    shown = sum(1 for sheet in sheets for item in sheet.items() if isinstance(item, Text) and item.anchor is not None)
    assert sum(calls.values()) <= 4 * len(calls), calls.most_common(5)
    assert sum(calls.values()) * 10 < shown, (sum(calls.values()), shown)


@pytest.mark.parametrize("name", ["shaper", "triad", "centers-six-bar"])
def test_every_step_sheet_shows_a_label_where_the_others_do(name: str) -> None:
    """A label with the same text for the same thing is at one place on every sheet (the whole drawing's)."""
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    places: dict[tuple[str, str], set[tuple[float, float]]] = {}
    for sheet in [*step_sheets(solution), build_sheet(solution)]:
        for item in sheet.items():
            if isinstance(item, Text) and item.anchor is not None:
                places.setdefault((item.role, item.string), set()).add((round(item.x, 6), round(item.y, 6)))
    moved = {key: spots for key, spots in places.items() if len(spots) > 1}
    assert len(moved) <= len(places) // 20, moved


@pytest.mark.parametrize("paper", ["A4", "A0"])
def test_a_chain_of_15_loops_is_drawn_with_every_label_on_its_page(paper: str, tmp_path: Path,
                                                                   capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run_on(capsys, tmp_path, chain_text(15), "draw", "-o", "{tmp}/c.svg", "--paper", paper)
    assert code == 0, err
    solution = kinepoly.solve(loads_scene(chain_text(15), "chain-15.toml"))
    sheet = build_sheet(solution, paper)
    assert not [c for c in conflicts(sheet) if c.other == "the page's edge"]
    # the 15 couplers move alike: their tips coincide, and the labels crowding there are said
    touching = {c.role for c in conflicts(sheet)}
    said = re.search(r"kinepoly draw: (\d+) labels found no free place on (\S+)", err)
    assert said is not None and said.group(2) == paper
    assert 0.75 * len(touching) <= int(said.group(1)) <= len(touching)  # the placer's count, near the measure's


def test_a_scale_too_large_for_the_page_is_reduced_and_said_on_stderr(tmp_path: Path,
                                                                      capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run_on(capsys, tmp_path, edit(after="[draw]\nkv = 1000\n"), "draw", "-o", "{tmp}/d.pdf")
    assert code == 0, err
    assert "kinepoly draw: kv reduced from 1000 to" in err and (tmp_path / "d.pdf").read_bytes().startswith(b"%PDF")
