"""Issue 13, item 7: the sweep's plot shows the CSV's numbers.

Angles are wrapped in (-180, 180] in both (as ``kinepoly solve`` prints them): the plot draws the
CSV's values and breaks the line where an angle wraps, never unwrapping it. The centrode panel
promises the instant center "where the centrodes touch" only where it is drawn.
"""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest
from tests.scenes import EXAMPLES
from tests.sweep_support import ask_everything

import kinepoly
from kinepoly.sweep import sweep
from kinepoly.sweep.plots import plot_figure
from kinepoly.sweep.table import csv_text


def _axes_lines(fig: object) -> dict[str, object]:
    return {line.get_label(): line for ax in fig.axes if ax.get_visible()  # type: ignore[attr-defined]
            for line in ax.get_lines()}


def test_an_angle_that_wraps_is_plotted_as_the_csv_writes_it() -> None:
    import matplotlib.pyplot as plt

    result = sweep(kinepoly.loads_scene(ask_everything((EXAMPLES / "slider-crank.toml").read_text())), steps=120)
    rows = list(csv.DictReader(io.StringIO(csv_text(result))))
    written = np.array([float(row["theta_3"]) for row in rows])
    assert (np.abs(np.diff(written)) > 180.0).any(), "the example's theta_3 passes +-180"
    assert ((written > -180.0) & (written <= 180.0)).all()
    fig = plot_figure(result)
    try:
        line = _axes_lines(fig)["theta_3"]
        ys = np.ma.masked_invalid(np.asarray(line.get_ydata(), dtype=float))  # type: ignore[attr-defined]
        xs = np.asarray(line.get_xdata(), dtype=float)  # type: ignore[attr-defined]
        drawn = ys.compressed()
        assert np.allclose(drawn, written, rtol=0, atol=1e-9)  # the same numbers, none unwrapped
        assert np.allclose(xs[~ys.mask], [float(row[result.input.name]) for row in rows])
        segments = np.split(ys.filled(np.nan), np.flatnonzero(np.isnan(ys.filled(np.nan))))
        for segment in segments:  # no stroke of the line crosses the panel where the angle wraps
            values = segment[~np.isnan(segment)]
            assert (np.abs(np.diff(values)) <= 180.0).all()
    finally:
        plt.close(fig)


def _legend(fig: object) -> list[str]:
    return [text.get_text() for ax in fig.axes if ax.get_legend() is not None  # type: ignore[attr-defined]
            for text in ax.get_legend().get_texts()]


@pytest.mark.parametrize("name, link", [("four-bar", "3"), ("slider-crank", "3")])
def test_the_centrode_legend_promises_the_touching_center_only_where_it_is_drawn(name: str, link: str) -> None:
    import matplotlib.pyplot as plt

    result = sweep(kinepoly.loads_scene((EXAMPLES / f"{name}.toml").read_text()), steps=90, centrode=link)
    fig = plot_figure(result)
    try:
        ax = next(a for a in fig.axes if a.get_title().startswith(f"centrodes of link {link}"))
        x0, x1 = ax.get_xlim()
        y0, y1 = ax.get_ylim()
        labels = _legend(fig)
        marker = [ln for ln in ax.get_lines() if str(ln.get_label()).startswith("I")
                  and "at the scene's input" in str(ln.get_label())]
        assert len(marker) == 1
        xs, ys = np.asarray(marker[0].get_xdata(), float), np.asarray(marker[0].get_ydata(), float)
        inside = xs.size == 1 and x0 <= xs[0] <= x1 and y0 <= ys[0] <= y1
        touching = [t for t in labels if "where the centrodes touch" in t]
        outside = [t for t in labels if "outside the plot" in t]
        assert bool(touching) == inside and bool(outside) != inside
    finally:
        plt.close(fig)
