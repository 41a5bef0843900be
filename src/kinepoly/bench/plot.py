"""The bench's two figures, drawn with matplotlib (imported here only).

* the work-precision diagram: log error against log time per position, a point per method
  and the finite differences as a curve over their step (each point labelled with h);
* the sweep: log error against the input over its range (``kinepoly.sweep``'s), one line per
  method, the construction's error estimate dashed, singular positions as vertical lines, inputs
  that cannot be assembled shaded and near-singular ones shaded lightly.

Each returns the image's bytes (PNG, or the format asked); the command line writes the file.
"""

from __future__ import annotations

import io
import math
from typing import Any

from kinepoly.bench.run import BenchResult
from kinepoly.bench.sweep import Sweep

__all__ = ["plot_sweep", "plot_work_precision"]

_FLOOR = 1e-18
"""Errors below this (exactly zero, or below the reference's resolution in doubles) are drawn here."""

_STYLE = {"construction": ("o", "C0"), "analytic": ("s", "C1"), "closed form": ("D", "C2"), "series": ("^", "C4"),
          "GEOS": ("v", "C3"), "finite differences": ("x", "C7")}


def _family(name: str) -> str:
    for family, prefix in (("construction", "construction (poly"), ("analytic", "analytic"),
                           ("closed form", "closed form"), ("series", "series"), ("GEOS", "construction with GEOS"),
                           ("finite differences", "finite differences")):
        if name.startswith(prefix):
            return family
    return "other"


def _image(figure: Any, fmt: str) -> bytes:
    buffer = io.BytesIO()
    figure.savefig(buffer, format=fmt, dpi=130)
    return buffer.getvalue()


def _figure(width: float = 8.0, panels: int = 1) -> tuple[Any, list[Any]]:
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    figure = Figure(figsize=(width, 5.4), layout="constrained")
    if panels == 1:
        return figure, [figure.add_subplot()]
    grid = figure.add_gridspec(1, 2, width_ratios=(2.0, 1.0))
    return figure, [figure.add_subplot(grid[0, 0]), figure.add_subplot(grid[0, 1])]


def plot_work_precision(result: BenchResult, fmt: str = "png") -> bytes:
    """Error against time per position (both logarithmic); beside it the finite differences against their step."""
    answered = [m for m in result.methods if not m.failure]
    fd = [m for m in answered if m.family == "finite differences"]
    figure, axes = _figure(11.5, 2 if fd else 1)
    ax = axes[0]
    if fd:
        ax.plot([m.time_s for m in fd], [max(m.error, _FLOOR) for m in fd], "-x", color="C7", linewidth=0.8,
                label="central finite differences of the position, one point per step h")
        best = min(fd, key=lambda m: m.error)
        ax.annotate(f"best step h={best.step:g}", (best.time_s, max(best.error, _FLOOR)), textcoords="offset points",
                    xytext=(-6, -6), fontsize=7, color="0.35", va="top", ha="right")
    for m in answered:
        if m.family == "finite differences":
            continue
        marker, color = _STYLE.get(m.family, ("*", "k"))
        batch = f" (batch of {m.batch})" if m.batch > 1 else ""
        ax.plot([m.time_s], [max(m.error, _FLOOR)], marker, color=color, markersize=8, linestyle="none",
                label=f"{m.name}{batch}")
    ax.axhline(2.0**-53, color="0.6", linewidth=0.8, linestyle=":")
    times = [m.time_s for m in answered]
    ax.annotate("unit roundoff u = 2^-53", (math.sqrt(min(times) * max(times)), 2.0**-53),
                textcoords="offset points", xytext=(0, 3), fontsize=7, color="0.4", ha="center")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per position (s), median of repeats")
    ax.set_ylabel(f"normwise relative error (against a {result.reference_digits}-digit reference)")
    ax.set_title(f"{result.title}: error against run time at {result.where}", fontsize=10)
    if result.estimate is not None:
        ax.axhline(result.estimate, color="C0", linewidth=0.9, linestyle="--",
                   label="the construction's error estimate (from the conditioning)")
    ax.grid(True, which="major", linewidth=0.4, alpha=0.5)
    figure.legend(*ax.get_legend_handles_labels(), fontsize=7, loc="outside lower left", ncols=2)
    failed = [m for m in result.methods if m.failure and m.family == "finite differences"]
    if fd:
        side = axes[1]
        side.plot([m.step for m in fd], [max(m.error, _FLOOR) for m in fd], "-x", color="C7",
                  label="finite differences")
        construction = result.method("construction")
        side.axhline(max(construction.error, _FLOOR), color="C0", linewidth=1.0, label="construction")
        side.set_xscale("log")
        side.set_yscale("log")
        side.invert_xaxis()
        side.set_xlabel("step h (rad, or times the mechanism's size)")
        side.set_ylabel("normwise relative error")
        side.set_title("finite differences over their step:\ntruncation h^2 against rounding u/h^2", fontsize=9)
        side.grid(True, which="major", linewidth=0.4, alpha=0.5)
        side.legend(fontsize=7, loc="upper left")
        if failed:
            steps = [m.step for m in failed if m.step is not None]
            side.text(0.97, 0.97, f"no answer for h = {max(steps):g} .. {min(steps):g}:\nthe step reaches an\n"
                      "input that cannot\nbe assembled", transform=side.transAxes, fontsize=7, color="C3",
                      va="top", ha="right")
    return _image(figure, fmt)


def plot_sweep(sweep: Sweep, fmt: str = "png") -> bytes:
    """Each method's error over the input; singular positions and unassembled inputs marked."""
    figure, axes = _figure(10.0)
    ax = axes[0]
    xs = [sweep.shown(p.t) for p in sweep.points]
    for name in sweep.methods:
        family = _family(name)
        _, color = _STYLE.get(family, ("*", "k"))
        ys = [max(p.errors[name], _FLOOR) if p.measured and name in p.errors and math.isfinite(p.errors[name])
              else math.nan for p in sweep.points]
        ax.plot(xs, ys, "-", color=color, linewidth=1.0 if family != "construction" else 1.6, label=name)
    estimate = [p.estimate if p.measured and p.estimate else math.nan for p in sweep.points]
    ax.plot(xs, estimate, "--", color="C0", linewidth=1.0, label="the construction's error estimate")
    step = (xs[1] - xs[0]) if len(xs) > 1 else 1.0
    labelled: set[str] = set()
    for p, x in zip(sweep.points, xs, strict=True):
        if p.status in ("cannot-assemble", "near-singular"):
            label = "cannot be assembled" if p.status == "cannot-assemble" else "near-singular"
            ax.axvspan(x - step / 2, x + step / 2, color="0.85" if p.status == "cannot-assemble" else "0.94",
                       linewidth=0, label=None if label in labelled else label)
            labelled.add(label)
    for n, t in enumerate(sweep.singular):
        ax.axvline(sweep.shown(t), color="C3", linestyle="--", linewidth=0.9,
                   label="singular position (dead centre)" if n == 0 else None)
    for p, x in zip(sweep.points, xs, strict=True):
        if p.status == "singular":
            ax.axvline(x, color="C3", linestyle=":", linewidth=0.9)
    ax.set_yscale("log")
    marks = [sweep.shown(t) for t in sweep.singular]
    low, high = min(xs + marks), max(xs + marks)
    ax.set_xlim(low - 0.01 * (high - low) - step / 2, high + 0.01 * (high - low) + step / 2)
    ax.set_xlabel(f"{sweep.input_name} ({sweep.input_unit})")
    ax.set_ylabel("normwise relative error (50-digit reference)")
    ax.set_title(f"{sweep.title}: error over the input", fontsize=10)
    ax.grid(True, which="major", linewidth=0.4, alpha=0.5)
    figure.legend(*ax.get_legend_handles_labels(), fontsize=7, loc="outside lower left", ncols=3)
    return _image(figure, fmt)
