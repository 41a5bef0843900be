"""A sweep's columns as people see them (the plots' curves and axes, the animation's table).

The number rule of ``present.clean`` with the sweep's error estimate: a sweep accepts a row whose
error is below ``LOUD_ERROR`` relative to the size of its kind, so a value within ``LOUD_ERROR``
times that size (``shown_values`` says which) is 0, and a column whose values all lie within that
estimate of one short decimal is that decimal (a rate held constant: 40, not 40 ± 1e-11). The CSV
is data and keeps the computed values (as the JSON does).
"""

from __future__ import annotations

import math

import numpy as np

from kinepoly.geom.tolerances import LOUD_ERROR
from kinepoly.present.clean import tidy
from kinepoly.scene.spec import LinkInput, Scene, SliderInput
from kinepoly.sweep.result import Column, SweepResult

__all__ = ["SWEEP_RELATIVE", "shown_values", "tidy_column"]

SWEEP_RELATIVE = LOUD_ERROR
"""The relative error estimate of a value of a sweep, against the size of its kind (``shown_values``)."""

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
    """The size of each kind the input sets, whatever the rows give: the mechanism's size, the input's rates (a
    ratio of two rates is of size 1)."""
    size = max((math.hypot(*p.local) for link in scene.links for p in link.points), default=0.0)
    inp = scene.input
    omega = alpha = 0.0
    if isinstance(inp, LinkInput):
        omega, alpha = abs(inp.omega), abs(inp.alpha)
    elif isinstance(inp, SliderInput) and size > 0.0:
        omega, alpha = abs(inp.s_dot) / size, abs(inp.s_ddot) / size
    alpha = max(alpha, omega * omega)
    return {"length": size, "angle": 180.0 if scene.units.angle == "deg" else math.pi, "omega": omega,
            "alpha": alpha, "speed": size * omega, "accel": size * alpha, "ratio": 1.0}


def _dimension(result: SweepResult, col: Column) -> str:
    if col.kind == "input":
        return "length" if result.input.name.startswith("s") else "angle"
    return _DIMENSION.get(col.kind, col.name)


def shown_values(result: SweepResult) -> dict[str, np.ndarray]:
    """Every column's values (0 where a row has none) by the number rule, by column name.

    The estimate of a value is ``SWEEP_RELATIVE`` times the size of its kind that the input sets (the
    mechanism's size, the input's rates: ``_natural_sizes``) or, for a component of a vector, that
    vector's length in its row (a component beside a large one: ``D (2858.58, -4.5e-13)``), whichever
    is larger. A value is never judged against another quantity's size: near a dead point one rate
    runs to 1e13 while another, honest, stays in the thousands."""
    columns = [result.input, *result.columns]
    natural = _natural_sizes(result.scene)
    names = {col.name: col for col in columns}
    out = {}
    for col in columns:
        size = np.full(len(col.values), natural.get(_dimension(result, col), 0.0))
        if col.name.endswith(("_x", "_y")):
            other = names.get(col.name[:-1] + ("y" if col.name.endswith("_x") else "x"))
            if other is not None and other.kind == col.kind:
                size = np.maximum(size, np.hypot(col.values, other.values))
        error = SWEEP_RELATIVE * np.where(np.isfinite(size), size, 0.0)
        values = np.zeros(len(col.values))
        values[col.valid] = tidy_column(col.values[col.valid], error[col.valid])
        out[col.name] = values
    return out
