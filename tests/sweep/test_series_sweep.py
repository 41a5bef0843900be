"""The course text's slider-crank series in a sweep (``--series``): beside the exact columns, with the error the
text drops, the fourth power of (k + lambda sin phi1) in the position."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES, slider_crank

import kinepoly
from kinepoly.errors import SceneError
from kinepoly.sweep.run import sweep


def _columns(text: str) -> dict[str, np.ndarray]:
    result = sweep(kinepoly.loads_scene(text), steps=720, series=True)
    assert (result.status == 0).all()
    return {c.name: c.values for c in result.columns} | {"input": result.input.values}


@pytest.mark.parametrize("crank", [20.0, 30.0, 40.0])
def test_the_position_error_is_the_dropped_fourth_order_term(crank: float) -> None:
    """Without offset u = lambda sin phi1 and the series drops l (sqrt(1 - u^2) - 1 + u^2 / 2) = -l u^4 / 8 - ...:
    the error column is that, row by row, and its largest value l lambda^4 / 8 to within a factor 1 + lambda^2."""
    rod = 120.0
    cols = _columns(slider_crank(crank, rod, 0.0, 30.0, 10.0, 0.0))
    lam = crank / rod
    u = lam * np.sin(np.radians(cols["input"]))
    dropped = rod * (np.sqrt(1.0 - u * u) - 1.0 + u * u / 2.0)
    error = cols["s_series_error_14"]
    assert np.allclose(error, -dropped, rtol=1e-6, atol=1e-9 * rod)
    largest = float(np.abs(error).max())
    assert rod * lam**4 / 8.0 <= largest <= rod * lam**4 / 8.0 * (1.0 + lam**2)
    assert np.allclose(cols["s_series_14"] - cols["s_14"], error)


def test_halving_the_crank_divides_the_errors_by_the_powers_of_lambda() -> None:
    """Position error ~ lambda^4, velocity error ~ lambda^3 (relative to omega r), acceleration likewise: halving the
    crank (lambda and r halved) divides them by about 2^4, 2^4 and 2^4 (r lambda^3 each)."""
    big = _columns(slider_crank(40.0, 160.0, 0.0, 30.0, 10.0, 0.0))
    small = _columns(slider_crank(20.0, 160.0, 0.0, 30.0, 10.0, 0.0))
    for key in ("s", "s_dot", "s_ddot"):
        ratio = np.abs(big[f"{key}_series_error_14"]).max() / np.abs(small[f"{key}_series_error_14"]).max()
        assert 14.0 < ratio < 18.0, key


def test_an_offset_slider_crank_stays_within_the_texts_bound() -> None:
    cols = _columns(slider_crank(40.0, 120.0, 10.0, 30.0, 10.0, 5.0))
    lam, k = 40.0 / 120.0, 10.0 / 120.0
    assert np.abs(cols["s_series_error_14"]).max() <= 120.0 * (k + lam) ** 4 / 8.0 * (1.0 + (k + lam) ** 2)
    assert np.abs(cols["s_series_error_14"]).max() >= 0.5 * 120.0 * (k + lam) ** 4 / 8.0


def test_only_a_crank_driven_slider_crank(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    with pytest.raises(SceneError, match="--series"):
        sweep(kinepoly.load_scene(EXAMPLES / "four-bar.toml"), steps=10, series=True)
    code, _, err = run(capsys, "sweep", str(EXAMPLES / "shaper.toml"), "--series")
    assert code == 2 and "--series" in err
    png = tmp_path / "s.png"
    code, _, _ = run(capsys, "sweep", str(EXAMPLES / "slider-crank.toml"), "--series", "--plot", str(png), "-o",
                     str(tmp_path / "s.csv"))
    assert code == 0 and png.stat().st_size > 0
    header = (tmp_path / "s.csv").read_text().splitlines()[0].split(",")
    assert {"s_14", "s_series_14", "s_series_error_14", "s_ddot_series_error_14"} <= set(header)
