"""Issue 25, the small things a teacher meets: a zero input rate without a sense, a sheet for every step
``solve --steps`` numbers, ``-o`` into the folder ``--steps`` makes, sweep curves of a full turn closed, a
sliders' rate axis windowed like its panel, a one-line ``repr`` of a solution."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.handout.problem import problem_page
from kinepoly.present.catalogue import load_catalogue
from kinepoly.present.report import steps_text
from kinepoly.render.sheet import step_count
from kinepoly.sweep import sweep


def _page_text(path: Path, lang: str) -> str:
    solution = kinepoly.solve(kinepoly.load_scene(path))
    page = problem_page(solution, load_catalogue(lang), {})
    return "\n".join(part.text for column in page.columns for part in column.parts if hasattr(part, "text"))


@pytest.mark.parametrize("lang", ["en", "tr", "ro"])
def test_a_zero_input_rate_has_no_sense(lang: str) -> None:
    """The slider-crank's crank turns at a constant rate: alpha12 = 0 rad/s², not "0 rad/s² zero."; omega
    keeps its sense."""
    text = _page_text(EXAMPLES / "slider-crank.toml", lang)
    zero = load_catalogue(lang).say("sense.zero")
    ccw = load_catalogue(lang).say("sense.ccw")
    assert "α12 = 0 rad/s²." in text, text
    assert f"rad/s² {zero}" not in text and f"rad/s² ({zero})" not in text and ccw in text


def test_a_non_zero_input_rate_keeps_its_sense() -> None:
    text = _page_text(EXAMPLES / "four-bar.toml", "en")  # omega 10, alpha 5
    assert "ω12 = 10 rad/s counter-clockwise, α12 = 5 rad/s² counter-clockwise." in text


def test_draw_steps_writes_a_sheet_for_every_step_solve_numbers(capsys: pytest.CaptureFixture[str],
                                                                  tmp_path: Path) -> None:
    """centers-six-bar: 8 polygon steps and 8 Kennedy steps, 16 in solve --steps; draw --steps wrote 8."""
    path = EXAMPLES / "centers-six-bar.toml"
    solution = kinepoly.solve(kinepoly.load_scene(path))
    numbered = re.findall(r"^ ?(\d+)\. ", steps_text(solution), flags=re.MULTILINE)
    assert len(numbered) == step_count(solution) > len(solution.steps)
    code, _, err = run(capsys, "draw", str(path), "--steps", str(tmp_path / "steps"))
    assert code == 0, err
    sheets = sorted((tmp_path / "steps").iterdir())
    assert [p.name for p in sheets] == [f"step-{n:02d}.svg" for n in range(1, len(numbered) + 1)]
    last = sheets[-1].read_text(encoding="utf-8")
    assert f"Step {len(numbered)} of {len(numbered)}" in last and "kennedy" in last


def test_the_drawing_goes_into_the_folder_steps_makes(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    folder = tmp_path / "new"
    code, _, err = run(capsys, "draw", str(EXAMPLES / "four-bar.toml"), "-o", str(folder / "x.svg"),
                       "--steps", str(folder))
    assert code == 0, err
    assert (folder / "x.svg").is_file() and (folder / "step-01.svg").is_file()
    code, _, err = run(capsys, "draw", str(EXAMPLES / "four-bar.toml"), "-o", str(tmp_path / "other" / "x.svg"),
                       "--steps", str(folder))
    assert code == 2 and "does not exist" in err  # another missing folder is still refused


def _lines(ax: object) -> list[tuple[np.ndarray, np.ndarray]]:
    return [(np.ma.filled(line.get_xdata(orig=True).astype(float), np.nan),  # type: ignore[attr-defined]
             np.ma.filled(line.get_ydata(orig=True).astype(float), np.nan))  # type: ignore[attr-defined]
            for line in ax.get_lines()  # type: ignore[attr-defined]
            if len(line.get_xdata()) > 2 and not line.get_label().startswith("_")]  # the curves, not the skeleton


def test_the_curves_of_a_full_turn_are_closed() -> None:
    """A full turn's N rows end one step before its start: a path or hodograph drawn through them only had a gap."""
    import matplotlib.pyplot as plt

    from kinepoly.sweep.plots import plot_figure

    result = sweep(kinepoly.load_scene(EXAMPLES / "four-bar.toml"), steps=24)
    assert result.periodic
    fig = plot_figure(result)
    try:
        titles = {ax.get_title(): ax for ax in fig.axes}
        for title in ("point paths (the mechanism at the scene's input)", "velocity hodographs",
                      "acceleration hodographs"):
            curves = _lines(titles[title])
            assert curves, title
            for xs, ys in curves:
                assert len(xs) == result.rows + 1 and xs[0] == xs[-1] and ys[0] == ys[-1], title
    finally:
        plt.close(fig)


@pytest.mark.slow  # a Newton sweep of the triad-slot
def test_the_sliders_rate_axis_is_windowed_like_its_panel() -> None:
    """triad-slot's s_dot_46 and s_ddot_46 run to 4e5 and 2e13 at the range's ends: their own axis (a twin of the
    omega panel's) flattened the curve into a line; it is windowed on the ok rows as the panel is."""
    import matplotlib.pyplot as plt

    from kinepoly.sweep.plots import plot_figure

    result = sweep(kinepoly.load_scene(EXAMPLES / "triad-slot.toml"), steps=90)
    fig = plot_figure(result)
    try:
        ok = result.status == 0
        for name in ("s_dot_46", "s_ddot_46"):
            col = result.column(name)
            typical = float(np.percentile(np.abs(col.values[col.valid & ok]), 99))
            assert float(np.abs(col.values[col.valid]).max()) > 20 * typical, "the case runs off"
            axis = next(ax for ax in fig.axes if any(line.get_label() == name for line in ax.get_lines()))
            low, high = axis.get_ylim()
            assert max(abs(low), abs(high)) < 3 * typical, (name, low, high, typical)
    finally:
        plt.close(fig)


def test_the_repr_of_a_solution_is_one_line() -> None:
    """It printed every array of the solution: 35 kB for a cam."""
    for name in ("kc0-six-bar.toml", "eccentric-cam-flat.toml"):
        solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / name))
        text = repr(solution)
        assert "\n" not in text and len(text) < 300 and solution.scene.title in text


def test_the_rate_panels_of_an_all_ok_open_range_keep_the_stroke_readable() -> None:
    """slotted-crank-slider: every row ok, the range stopped where the slider runs off; its rates grow to 1e5 over
    more than 1 % of the rows, so a window of percentiles 1..99 reached those and flattened the rest. The window
    holds the middle 80 % of the rows and is a fraction of that 1..99 span."""
    import matplotlib.pyplot as plt

    from kinepoly.sweep.plots import plot_figure

    result = sweep(kinepoly.load_scene(EXAMPLES / "slotted-crank-slider.toml"), steps=360)
    assert (result.status == 0).all() and any(n.code == "open-range" for n in result.notices)
    fig = plot_figure(result)
    try:
        for name in ("s_dot_14", "s_dot_23", "s_ddot_14"):
            values = result.column(name).values
            axis = next(ax for ax in fig.axes if any(line.get_label() == name for line in ax.get_lines()))
            low, high = axis.get_ylim()
            p1, p10, p90, p99 = np.percentile(values, [1, 10, 90, 99])
            assert low <= p10 and p90 <= high, (name, low, high, p10, p90)
            assert high - low <= 0.2 * (p99 - p1), (name, low, high, p1, p99)
    finally:
        plt.close(fig)
