"""A sweep's columns as people see them (the plots' curves and axes, the animation's table).

The number rule of ``present.clean`` with the sweep's error estimate: a sweep accepts a row whose
error is below ``LOUD_ERROR`` relative to the size of its kind, so a value of a kind (lengths,
speeds, accelerations, angles, omega, alpha) within ``LOUD_ERROR`` times the largest value of that
kind in the sweep is 0, and a column whose values all lie within that estimate of one short decimal
is that decimal (a rate held constant: 40, not 40 ± 1e-11). The CSV is data and keeps the computed
values (as the JSON does).
"""

from __future__ import annotations

import math

import numpy as np

from kinepoly.geom.tolerances import LOUD_ERROR
from kinepoly.present.clean import tidy
from kinepoly.scene.spec import LinkInput, Scene, SliderInput
from kinepoly.sweep.run import Column, SweepResult

__all__ = ["SWEEP_RELATIVE", "shown_values", "tidy_column"]

SWEEP_RELATIVE = LOUD_ERROR
"""The relative error estimate of a value of a sweep, against the largest of its kind."""

_DIMENSION = {"angle": "angle", "transmission": "angle", "pressure": "angle", "omega": "omega", "alpha": "alpha",
              "position": "length", "slider": "length", "centrode": "length", "centrode-local": "length",
              "velocity": "speed", "slider-rate": "speed", "acceleration": "accel", "slider-acceleration": "accel",
              "coriolis": "accel", "ratio": "ratio"}


def tidy_column(values: np.ndarray, error: np.ndarray | float) -> np.ndarray:
    """The number rule on one column, ``error`` the estimate of each value: a value within it of 0 is 0; where
    every finite value lies within its estimate of one short decimal, that decimal throughout."""
    error = np.broadcast_to(np.asarray(error, np.float64), np.shape(values))
    out = np.where(np.abs(values) <= error, 0.0, values) + 0.0
    finite = np.isfinite(out)
    if finite.any():
        low, high = float(out[finite].min()), float(out[finite].max())
        least = float(error[finite].min())
        if high - low <= 2.0 * least:
            centre = tidy(0.5 * (low + high), least)
            if max(abs(low - centre), abs(high - centre)) <= least:
                out = np.where(finite, centre, out)
    return out


def _natural_sizes(scene: Scene) -> dict[str, float]:
    """The size of each kind the input sets, whatever the rows give: the mechanism's size, the input's rates."""
    size = max((math.hypot(*p.local) for link in scene.links for p in link.points), default=0.0)
    inp = scene.input
    omega = alpha = 0.0
    if isinstance(inp, LinkInput):
        omega, alpha = abs(inp.omega), abs(inp.alpha)
    elif isinstance(inp, SliderInput) and size > 0.0:
        omega, alpha = abs(inp.s_dot) / size, abs(inp.s_ddot) / size
    alpha = max(alpha, omega * omega)
    return {"length": size, "angle": 180.0 if scene.units.angle == "deg" else math.pi, "omega": omega,
            "alpha": alpha, "speed": size * omega, "accel": size * alpha}


def _dimension(result: SweepResult, col: Column) -> str:
    if col.kind == "input":
        return "length" if result.input.name.startswith("s") else "angle"
    return _DIMENSION.get(col.kind, col.name)


def shown_values(result: SweepResult) -> dict[str, np.ndarray]:
    """Every column's values (0 where a row has none) by the number rule, by column name; the estimate of a
    value is ``SWEEP_RELATIVE`` times the largest value of its kind in its row (each row is a solve of its own),
    or of the size the input sets for that kind (the mechanism's size, the input's rates), whichever is larger."""
    columns = [result.input, *result.columns]
    largest: dict[str, np.ndarray] = {key: np.full(len(result.input.values), size)
                                      for key, size in _natural_sizes(result.scene).items()}
    for col in columns:
        size = np.where(col.valid & np.isfinite(col.values), np.abs(col.values), 0.0)
        key = _dimension(result, col)
        largest[key] = np.maximum(largest[key], size) if key in largest else size
    out = {}
    for col in columns:
        error = SWEEP_RELATIVE * largest[_dimension(result, col)]
        values = np.zeros(len(col.values))
        values[col.valid] = tidy_column(col.values[col.valid], error[col.valid])
        out[col.name] = values
    return out
