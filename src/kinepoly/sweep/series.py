"""The course text's approximate slider-crank beside the exact one in a sweep (``kinepoly sweep --series``).

The series is ``check.series``' (two terms of the binomial expansion of cos phi2, RO 2.2.1); the exact
values are the sweep's own (``engine.sliders``). For each of s, s_dot and s_ddot the sweep gains the
series' column (``s_series_14``) and its error against the exact one (``s_series_error_14`` = series - exact).
"""

from __future__ import annotations

import numpy as np

from kinepoly.check.series import slider_crank_links, slider_crank_series
from kinepoly.engine.acceleration import AccelerationResult
from kinepoly.engine.position import Positions
from kinepoly.engine.sliders import slider_motion
from kinepoly.engine.velocity import VelocityResult
from kinepoly.errors import SceneError
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import LinkInput

__all__ = ["SeriesColumn", "check_series", "series_columns"]

SeriesColumn = tuple[str, str, np.ndarray, np.ndarray]
"""(name, kind, values, valid)."""

_KINDS = (("s", "slider", "series-error"), ("s_dot", "slider-rate", "series-rate-error"),
          ("s_ddot", "slider-acceleration", "series-acceleration-error"))


def check_series(mechanism: Mechanism) -> None:
    """Raise SceneError unless the scene is a slider-crank driven by its crank (the series' mechanism)."""
    parts = slider_crank_links(mechanism)
    inp = mechanism.scene.input
    if parts is None or not isinstance(inp, LinkInput) or inp.link != parts[0]:
        raise SceneError(f"{mechanism.scene.source}: --series: the course text's series is that of a slider-crank "
                         "driven by its crank (four links: frame, crank, rod, block sliding on the frame); this scene "
                         "is not one")


def series_columns(mechanism: Mechanism, positions: Positions, seed_row: int, velocity: VelocityResult | None,
                   acceleration: AccelerationResult | None, exact_too: bool) -> list[SeriesColumn]:
    """The series' s, s_dot, s_ddot and their errors against the exact ones, over the sweep's rows; with
    ``exact_too`` the exact ones as well (when the scene's [find] does not ask for the slider)."""
    parts = slider_crank_links(mechanism)
    assert parts is not None
    crank, spec = parts[0], parts[6]
    keys = [f"sliders.{spec.name}.{key}" for key in ("s", "s_dot", "s_ddot")]
    series = slider_crank_series(mechanism, Pose(positions.row(seed_row)), keys)
    assert series is not None
    values = series.values(np.asarray(positions.poses[crank].theta()))
    exact = slider_motion(positions, spec, velocity, acceleration)
    out: list[SeriesColumn] = []
    for key, kind, error_kind in _KINDS:
        reference = getattr(exact, key)
        if reference is None:
            continue
        approximate = np.asarray(values[f"sliders.{spec.name}.{key}"], dtype=float)
        valid = positions.ok & np.isfinite(reference)
        if exact_too:
            out.append((f"{key}_{spec.name}", kind, np.asarray(reference, dtype=float), valid))
        out.append((f"{key}_series_{spec.name}", kind, approximate, valid))
        out.append((f"{key}_series_error_{spec.name}", error_kind, approximate - reference, valid))
    return out
