"""The sweep's plots as one PNG: transmission functions of order 0, 1 and 2, point paths,
velocity and acceleration hodographs, transmission angles, and the centrodes of a chosen link;
for a cam its follower's s-v-a diagram and the pressure angle, for gears their ratios.

matplotlib is imported here only (``kinepoly solve`` never pays for it). Rows without a value
leave gaps in the curves (masked, never NaN); inputs where the mechanism cannot be assembled
are shaded grey, singular rows marked by thin red lines.
"""

from __future__ import annotations

import io
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from msgspec.structs import replace

from kinepoly.geom.tolerances import SIZE_FLOOR
from kinepoly.scene.link_point import LinkPoint
from kinepoly.sweep.result import CANNOT_ASSEMBLE, OK, SINGULAR, Column, SweepResult
from kinepoly.sweep.shown import shown_values

if TYPE_CHECKING:
    import numpy.typing as npt
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["plot_figure", "plot_png", "robust_window"]

_REACH = 3.0
"""Centrodes run off to infinity where the link stops turning; the panel shows this many sizes around."""


def _masked(col: Column) -> np.ma.MaskedArray[Any, Any]:
    """The column with its empty rows masked."""
    return np.ma.masked_array(col.values, mask=~col.valid)


def _wrapped(x: np.ndarray, col: Column, period: float) -> tuple[np.ndarray, np.ma.MaskedArray[Any, Any]]:
    """An angle column as the CSV has it, in (-180, 180] degrees (or (-pi, pi]), its line broken where it wraps.

    The plot and the CSV agree: an angle is never unwrapped. Where it passes +-180 between two
    rows, an empty point between them keeps the line from crossing the panel.
    """
    values = _masked(col)
    jumps = np.flatnonzero(col.valid[:-1] & col.valid[1:] & (np.abs(np.diff(col.values)) > period / 2))
    if jumps.size == 0:
        return x, values
    xs = np.insert(x.astype(float), jumps + 1, (x[jumps] + x[jumps + 1]) / 2)
    ys = np.insert(values.filled(np.nan), jumps + 1, np.nan)
    return xs, np.ma.masked_invalid(ys)


def _finite(values: list[np.ndarray]) -> np.ndarray:
    kept = [v[np.isfinite(v)] for v in values if v.size]
    return np.concatenate(kept) if kept else np.zeros(0)


def robust_window(values: list[np.ndarray], bulk: list[np.ndarray]) -> tuple[float, float] | None:
    """Near a dead point rates run off to infinity: the window that keeps the rest of the cycle readable.

    It is judged on ``bulk``, the values of the rows that are ``ok`` (all values where fewer than 20
    are): when the extremes exceed five times its 95th percentile of |value|, the window is its
    1st..99th percentiles with a margin; else None (the whole range fits).
    """
    data, core = _finite(values), _finite(bulk)
    core = core if core.size >= 20 else data
    if core.size < 20:
        return None
    typical = float(np.percentile(np.abs(core), 95))
    if typical <= 0.0 or float(np.abs(data).max()) <= 5.0 * typical:
        return None
    # the bulk: the values within five spreads of the median, the spread being what four in five of them
    # keep to (rates that run off near an open range's ends fill more than 1 % of the rows: percentiles 1..99
    # reached 1e7 there and flattened the rest to a line)
    centre = float(np.median(core))
    spread = float(np.percentile(np.abs(core - centre), 80))
    bulk_values = core[np.abs(core - centre) <= 5.0 * spread] if spread > 0.0 else core
    low, high = (float(x) for x in np.percentile(bulk_values, [1, 99]))
    margin = 0.15 * max(high - low, spread)
    return low - margin, high + margin


def _robust_limits(ax: Axes, values: list[np.ndarray], bulk: list[np.ndarray]) -> None:
    """The y axis limited to ``robust_window``, where there is one, and its label saying so."""
    window = robust_window(values, bulk)
    if window is not None:
        ax.set_ylim(*window)
        ax.set_ylabel(f"{ax.get_ylabel()}, clipped")


def _mark_rows(ax: Axes, result: SweepResult) -> None:
    x = result.input.values
    step = float(np.median(np.abs(np.diff(x)))) if len(x) > 1 else 0.0
    for level, colour, alpha in ((CANNOT_ASSEMBLE, "0.6", 0.35), (SINGULAR, "tab:red", 0.25)):
        rows = result.status == level
        if not rows.any():
            continue
        edges = np.flatnonzero(np.diff(np.concatenate([[0], rows.astype(np.int8), [0]])))
        for a, b in zip(edges[::2], edges[1::2], strict=True):
            ax.axvspan(x[a] - step / 2, x[b - 1] + step / 2, color=colour, alpha=alpha, lw=0)


def _function_panel(ax: Axes, result: SweepResult, kinds: tuple[str, ...], slider_kind: str, title: str,
                    unit: str, slider_unit: str) -> None:
    x = result.input.values
    lines = 0
    shown: list[np.ndarray] = []
    bulk: list[np.ndarray] = []
    for col in result.columns:
        if col.kind in kinds:
            if col.kind == "angle":
                ax.plot(*_wrapped(x, col, 360.0 if result.scene.units.angle == "deg" else 2 * np.pi), lw=1.2,
                        label=col.name)
            else:
                ax.plot(x, _masked(col), lw=1.2, label=col.name)
            shown.append(col.values[col.valid])
            bulk.append(col.values[col.valid & (result.status == OK)])
            lines += 1
    sliders = [c for c in result.columns if c.kind == slider_kind and c.name != result.input.name]
    if sliders:
        target = ax.twinx() if lines else ax
        for col in sliders:
            target.plot(x, _masked(col), lw=1.2, ls="--", label=col.name)
        target.set_ylabel(slider_unit)
        if lines:  # the sliders' own axis windowed on their own ok rows (else on the panel's, below)
            _robust_limits(target, [c.values[c.valid] for c in sliders],
                           [c.values[c.valid & (result.status == OK)] for c in sliders])
            target.legend(loc="lower right", fontsize=7)
        else:
            shown += [c.values[c.valid] for c in sliders]
            bulk += [c.values[c.valid & (result.status == OK)] for c in sliders]
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(_input_label(result))
    ax.set_ylabel(unit if lines else slider_unit)
    _robust_limits(ax, shown, bulk)
    ax.grid(True, lw=0.3)
    if lines or sliders:
        ax.legend(loc="upper right", fontsize=7)
    _mark_rows(ax, result)


def _input_label(result: SweepResult) -> str:
    units = result.scene.units
    unit = units.angle if result.input.name.startswith("theta") else units.length
    return f"{result.input.name} ({unit})"


def _pairs(result: SweepResult, prefix: str) -> list[tuple[str, Column, Column]]:
    out = []
    for col in result.columns:
        if col.name.startswith(prefix) and col.name.endswith("_x"):
            name = col.name[len(prefix):-2]
            out.append((name, col, result.column(col.name[:-2] + "_y")))
    return out


def _closed(values: np.ndarray, valid: npt.NDArray[np.bool_], periodic: bool) -> tuple[np.ndarray, np.ndarray]:
    """A full turn's rows and its first row again at the end (the turn's end is its start: no gap there)."""
    if not periodic or len(values) < 2:
        return values, valid
    return np.append(values, values[0]), np.append(valid, valid[0] & valid[-1])


def _curve_panel(ax: Axes, pairs: list[tuple[str, Column, Column]], title: str, unit: str,
                 ok: npt.NDArray[np.bool_] | None = None, periodic: bool = False) -> None:
    """The curves of ``pairs``; a hodograph (``ok``: the rows that are ok) about its pole, windowed on those rows;
    ``periodic``: each curve closed (a full turn)."""
    points: list[np.ndarray] = []
    bulk: list[np.ndarray] = []
    for name, cx, cy in pairs:
        valid = cx.valid & cy.valid
        points.append(cx.values[valid] + 1j * cy.values[valid])
        if ok is not None:
            bulk.append(cx.values[valid & ok] + 1j * cy.values[valid & ok])
        xs, shown = _closed(cx.values, valid, periodic)
        ys, _ = _closed(cy.values, valid, periodic)
        line = ax.plot(np.ma.masked_array(xs, ~shown), np.ma.masked_array(ys, ~shown), lw=1.2, label=name)
        if valid.any():
            first = int(np.flatnonzero(valid)[0])
            ax.plot([cx.values[first]], [cy.values[first]], "o", ms=3, color=line[0].get_color())
    if ok is not None:
        ax.plot([0], [0], "k+", ms=8)
        ax.annotate("o", (0, 0), textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    clipped = ok is not None and _hodograph_window(ax, points, bulk, unit)
    if ok is not None:
        ax.locator_params(axis="x", nbins=5)  # a square panel: wide numbers on x would touch (-12500-10000)
    ax.set_aspect("equal", adjustable="box" if clipped else "datalim")
    ax.grid(True, lw=0.3)
    if pairs:
        ax.legend(loc="best", fontsize=7)


def _hodograph_window(ax: Axes, curves: list[np.ndarray], bulk: list[np.ndarray], unit: str) -> bool:
    """A square window on the bulk of the hodographs (their ``ok`` rows, all where fewer than 20 are) when
    some run off to infinity (a dead point)."""
    points, core = _finite(curves), _finite(bulk)
    core = core if core.size >= 20 else points
    if core.size < 20:
        return False
    if float(np.abs(points).max()) <= 5.0 * float(np.percentile(np.abs(core), 95)):
        return False
    center = complex(float(np.median(core.real)), float(np.median(core.imag)))
    reach = 1.15 * float(np.percentile(np.abs(core - center), 98))
    ax.set_xlim(center.real - reach, center.real + reach)
    ax.set_ylim(center.imag - reach, center.imag + reach)
    ax.locator_params(axis="x", nbins=5)  # a square panel: wide numbers on x would touch
    ax.set_xlabel(f"x ({unit}), clipped")
    ax.set_ylabel(f"y ({unit}), clipped")
    return True


def _draw_skeleton(ax: Axes, result: SweepResult, only: str | None = None) -> None:
    ground = result.scene.ground
    for link, points in result.skeleton:
        if only is not None and link != only:
            continue
        if len(points) < 2 or link == ground:
            for p in points:
                ax.plot([p.real], [p.imag], "k^" if link == ground else "ks", ms=5, mfc="white")
            continue
        xs = [p.real for p in points] + ([points[0].real] if len(points) > 2 else [])
        ys = [p.imag for p in points] + ([points[0].imag] if len(points) > 2 else [])
        ax.plot(xs, ys, "-", color="0.25", lw=1.6, alpha=0.8)
        ax.plot([p.real for p in points], [p.imag for p in points], "o", color="0.25", ms=3)


def _paths_panel(ax: Axes, result: SweepResult) -> None:
    paths = [p for p in _pairs(result, "r_") if LinkPoint.parse(p[0]).link is None]  # A@4 runs where A runs
    _curve_panel(ax, paths, "point paths (the mechanism at the scene's input)", result.scene.units.length,
                 periodic=result.periodic)
    _draw_skeleton(ax, result)


def _kind_panel(ax: Axes, result: SweepResult, kind: str, title: str, angles: bool) -> None:
    """Every column of ``kind`` over the input; ``angles``: in the angle unit, 0 to 90 degrees."""
    x = result.input.values
    unit = result.scene.units.angle
    # an angle at 90 degrees (a slot through its pivot) runs along the frame's top edge: drawn over it, not clipped
    for col in result.columns:
        if col.kind == kind:
            ax.plot(x, _masked(col), lw=1.2, label=col.name, clip_on=not angles, zorder=3 if angles else 2)
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(_input_label(result))
    if angles:
        ax.set_ylabel(unit)
        ax.set_ylim(0, 90 if unit == "deg" else np.pi / 2)
    ax.grid(True, lw=0.3)
    ax.legend(loc="best", fontsize=7)
    _mark_rows(ax, result)


def _centrode_panel(ax: Axes, result: SweepResult) -> None:
    fixed = [c for c in result.columns if c.kind == "centrode"]
    local = [c for c in result.columns if c.kind == "centrode-local"]
    name = fixed[0].name[:-2]
    link = name.split("_", 1)[1]
    link = link.split("-", 1)[1] if "-" in link else link[len(result.scene.ground or ""):]
    fx, fy = fixed
    lx, ly = local
    center, reach = _window(result)
    fixed_points = fx.values + 1j * fy.values
    near = fx.valid & fy.valid & (np.abs(fixed_points - center) < reach)
    ax.plot(np.ma.masked_array(fx.values, ~near), np.ma.masked_array(fy.values, ~near), lw=1.4,
            label=f"fixed centrode of link {link}")
    pose = _seed_pose(result, link)
    if pose is not None:
        origin, rotation = pose
        moving = origin + rotation * (lx.values + 1j * ly.values)
        shown = fx.valid & fy.valid & (np.abs(moving - center) < reach)
        ax.plot(np.ma.masked_array(moving.real, ~shown), np.ma.masked_array(moving.imag, ~shown), lw=1.4, ls="--",
                label=f"moving centrode (link {link} at the scene's input)")
        _draw_skeleton(ax, result, only=link)
    seed = _seed_row(result)
    if seed is not None and fx.valid[seed]:
        at = complex(fx.values[seed], fy.values[seed])
        if abs(at - center) < reach:
            touch = ", where the centrodes touch" if pose is not None else ""
            ax.plot([at.real], [at.imag], "ko", ms=5, mfc="none", label=f"{name} at the scene's input{touch}")
        else:  # said in the legend, not promised on the plot
            ax.plot([], [], " ", label=f"{name} at the scene's input lies outside the plot, at "
                                       f"({at.real:.4g}, {at.imag:.4g}) {result.scene.units.length}")
    ax.set_xlim(center.real - reach, center.real + reach)
    ax.set_ylim(center.imag - reach, center.imag + reach)
    ax.locator_params(axis="x", nbins=5)  # a square panel: wide numbers on x would touch
    ax.set_title(f"centrodes of link {link}: {name} (within {_REACH:g} x the mechanism's size)", fontsize=9)
    unit = result.scene.units.length
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    ax.set_aspect("equal", adjustable="box")
    ax.grid(True, lw=0.3)
    ax.legend(loc="best", fontsize=7)


_SVA_TITLES = ("displacement", "velocity", "acceleration")


def _sva_panel(ax: Axes, result: SweepResult, pair: str, names: tuple[str, ...]) -> None:
    """A cam designer's s-v-a diagram: the follower's displacement, velocity and acceleration stacked over
    the cam's angle, in the cell of ``ax`` (hidden: three axes sharing its x take its place)."""
    fig = ax.figure
    cell = ax.get_subplotspec()
    assert cell is not None
    ax.set_visible(False)
    grid = cell.subgridspec(len(names), 1, hspace=0.08)
    x = result.input.values
    units = result.scene.units
    first: Axes | None = None
    for k, name in enumerate(names):
        sub = fig.add_subplot(grid[k, 0], sharex=first)
        first = first or sub
        col = result.column(name)
        if col.kind == "angle":
            sub.plot(*_wrapped(x, col, 360.0 if units.angle == "deg" else 2 * np.pi), lw=1.2)
        else:
            sub.plot(x, _masked(col), lw=1.2)
        sub.set_ylabel(f"{name}\n({_unit_of(col, result)})", fontsize=7)
        sub.tick_params(labelsize=7)
        sub.axhline(0.0, color="0.5", lw=0.4)
        sub.grid(True, lw=0.3)
        _mark_rows(sub, result)
        if k < len(names) - 1:
            sub.tick_params(labelbottom=False)
        else:
            sub.set_xlabel(_input_label(result))
        if k == 0:
            sub.set_title(f"cam {pair}: follower's s-v-a diagram ({', '.join(_SVA_TITLES[:len(names)])})",
                          fontsize=9)


def _unit_of(col: Column, result: SweepResult) -> str:
    length, angle = result.scene.units.length, result.scene.units.angle
    return {"angle": angle, "omega": "rad/s", "alpha": "rad/s^2", "slider": length, "slider-rate": f"{length}/s",
            "slider-acceleration": f"{length}/s^2", "pressure": angle}.get(col.kind, "")


def _seed_row(result: SweepResult) -> int | None:
    rows = np.flatnonzero(result.input.values == result.seed_value)
    return int(rows[0]) if rows.size else None


def _window(result: SweepResult) -> tuple[complex, float]:
    """The middle of the mechanism at the scene's input, and ``_REACH`` times its size."""
    points = [p for _, pts in result.skeleton for p in pts]
    if not points:
        return 0j, 1.0
    center = complex(np.mean([p.real for p in points]), np.mean([p.imag for p in points]))
    size = max(max(abs(p - center) for p in points), SIZE_FLOOR)
    return center, _REACH * size


def _seed_pose(result: SweepResult, link: str) -> tuple[complex, complex] | None:
    """The link's pose at the scene's input, from two of its points (local and frame)."""
    spec = result.scene.link(link)
    points = dict(result.skeleton).get(link)
    if points is None or not spec.points:
        return None
    local = [complex(*p.local) for p in spec.points]
    if len(local) == 1:
        return points[0] - local[0], 1.0 + 0j
    rotation = (points[1] - points[0]) / (local[1] - local[0])
    rotation /= abs(rotation)
    return points[0] - rotation * local[0], rotation


def _as_shown(result: SweepResult) -> SweepResult:
    """The sweep with its columns by the number rule (``sweep.shown``): no rounding noise drawn on its own axis."""
    shown = shown_values(result)
    return replace(result, columns=tuple(col._replace(values=shown[col.name]) for col in result.columns))


def plot_png(result: SweepResult, dpi: int = 110) -> bytes:
    """All the sweep's plots on one sheet, as PNG bytes."""
    import warnings

    import matplotlib.pyplot as plt

    from kinepoly.render.mpl import _quiet_warnings  # a letter the font lacks (a point named 中) drawn as a box

    with _quiet_warnings(), warnings.catch_warnings(), np.errstate(all="ignore"):
        # values near the end of double precision (a cam's centre at 1e308) overflow matplotlib's own tick
        # arithmetic, which says so on standard error; the plot is drawn all the same
        warnings.simplefilter("ignore", RuntimeWarning)
        fig = plot_figure(result)
        try:
            buffer = io.BytesIO()
            fig.savefig(buffer, format="png", dpi=dpi)
            return buffer.getvalue()
        finally:
            plt.close(fig)


def plot_figure(result: SweepResult) -> Figure:
    """All the sweep's plots on one matplotlib figure (the caller closes it)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    result = _as_shown(result)
    units = result.scene.units
    length = units.length
    panels: list[Callable[[Axes], None]] = [
        lambda ax: _function_panel(ax, result, ("angle",), "slider", "order 0: positions", units.angle, length),
        lambda ax: _function_panel(ax, result, ("omega",), "slider-rate", "order 1: velocities", "rad/s",
                                   f"{length}/s"),
        lambda ax: _function_panel(ax, result, ("alpha",), "slider-acceleration", "order 2: accelerations",
                                   "rad/s^2", f"{length}/s^2"),
        lambda ax: _paths_panel(ax, result),
    ]
    if _pairs(result, "v_"):
        panels.append(lambda ax: _curve_panel(ax, _pairs(result, "v_"), "velocity hodographs", f"{length}/s",
                                              result.status == OK, result.periodic))
    if _pairs(result, "a_"):
        panels.append(lambda ax: _curve_panel(ax, _pairs(result, "a_"), "acceleration hodographs",
                                              f"{length}/s^2", result.status == OK, result.periodic))
    if any(c.kind == "transmission" for c in result.columns):
        panels.append(lambda ax: _kind_panel(ax, result, "transmission", "transmission angles (0 dead point, 90 best)",
                                             True))
    if any(c.kind == "centrode" for c in result.columns):
        panels.append(lambda ax: _centrode_panel(ax, result))
    for pair, names in result.followers:
        if names:
            panels.append(lambda ax, pair=pair, names=names: _sva_panel(ax, result, pair, names))  # type: ignore[misc]
    if any(c.kind == "pressure" for c in result.columns):
        panels.append(lambda ax: _kind_panel(ax, result, "pressure",
                                             "pressure angles: common normal to the follower's motion", True))
    for kind, what, unit in (("series-error", "s", length), ("series-rate-error", "s_dot", f"{length}/s"),
                             ("series-acceleration-error", "s_ddot", f"{length}/s^2")):
        if any(c.kind == kind for c in result.columns):
            title = f"error of the course's series: {what} (series - exact, {unit})"
            panels.append(lambda ax, kind=kind, title=title: _kind_panel(ax, result, kind, title, False))  # type: ignore[misc]
    if any(c.kind == "ratio" for c in result.columns):
        panels.append(lambda ax: _kind_panel(ax, result, "ratio",
                                             "angular velocity ratios (ratio_b_a = omega_b / omega_a)", False))
    cols = 3
    rows = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.3 * rows), squeeze=False)
    for ax, panel in zip(axes.flat, panels, strict=False):
        panel(ax)
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    fig.suptitle(f"{result.scene.title}: sweep of {result.input.name} over {result.rows} positions", fontsize=11)
    fig.tight_layout()
    return fig
