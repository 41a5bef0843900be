"""PNG through matplotlib: each primitive of the sheet becomes one artist, nothing is decided.

PDF is written directly (``render.pdf``); ``write_pdf`` and ``write_pdf_pages`` pass the sheets on.

No pyplot (no global figure state): a ``Figure`` on an Agg or PDF canvas whose axes span the
page in millimetres.
"""

from __future__ import annotations

import contextlib
import warnings
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any

from kinepoly.render.primitives import Arrow, Circle, Path, Sheet, Stroke, Text

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["DEFAULT_DPI", "figure_of", "write_pdf", "write_pdf_pages", "write_png"]

DEFAULT_DPI = 150
_PT_PER_MM = 72.0 / 25.4


def _rgba(color: str, opacity: float = 1.0) -> tuple[float, float, float, float]:
    return (int(color[1:3], 16) / 255, int(color[3:5], 16) / 255, int(color[5:7], 16) / 255, opacity)


def _line_style(stroke: Stroke) -> dict[str, Any]:
    style: dict[str, Any] = {"color": stroke.color, "linewidth": stroke.width * _PT_PER_MM,
                             "solid_capstyle": "butt", "dash_capstyle": "butt", "solid_joinstyle": "miter"}
    if stroke.dash:  # in points, as the line width: with ``lines.scale_dashes`` off (``_RC``) they are not scaled by it
        style["linestyle"] = (0, tuple(d * _PT_PER_MM for d in stroke.dash))
    return style


def _draw(ax: Axes, item: Path | Circle | Arrow | Text, zorder: float) -> None:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Circle as CirclePatch
    from matplotlib.patches import Polygon

    if isinstance(item, Path):
        if item.closed and item.fill is not None:
            ax.add_patch(Polygon(list(item.points), closed=True, facecolor=_rgba(item.fill, item.fill_opacity),
                                 edgecolor="none", linewidth=0, zorder=zorder))
        if item.stroke is not None:
            points = list(item.points) + ([item.points[0]] if item.closed else [])
            xs, ys = [p[0] for p in points], [p[1] for p in points]
            ax.add_line(Line2D(xs, ys, zorder=zorder, **_line_style(item.stroke)))
    elif isinstance(item, Circle):
        stroke = item.stroke
        ax.add_patch(CirclePatch(item.center, item.radius,
                                 facecolor=_rgba(item.fill) if item.fill else "none",
                                 edgecolor=stroke.color if stroke else "none",
                                 linewidth=stroke.width * _PT_PER_MM if stroke else 0, zorder=zorder))
    elif isinstance(item, Arrow):
        (sx, sy), (ex, ey) = item.start, item.shaft_end
        ax.add_line(Line2D([sx, ex], [sy, ey], zorder=zorder, **_line_style(Stroke(item.color, item.width))))
        ax.add_patch(Polygon(list(item.head), closed=True, facecolor=item.color, edgecolor="none", zorder=zorder))
    else:
        for run in item.runs:
            ax.text(item.x + run.dx, item.y + run.dy, run.text, fontsize=run.size * _PT_PER_MM,
                    family="DejaVu Sans", weight="bold" if item.bold else "normal", color=item.color,
                    ha="left", va="baseline", zorder=zorder, parse_math=False)  # "$x$" as written


def figure_of(sheet: Sheet) -> Figure:
    """A matplotlib Figure of the sheet, page-sized, 1 data unit = 1 mm."""
    import matplotlib

    with matplotlib.rc_context(_RC):  # the lines take their dashes as made (``lines.scale_dashes`` off)
        return _figure(sheet)


def _figure(sheet: Sheet) -> Figure:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(sheet.width / 25.4, sheet.height / 25.4))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    ax.set_xlim(0.0, sheet.width)
    ax.set_ylim(0.0, sheet.height)
    ax.set_axis_off()
    fig.patch.set_facecolor("white")
    z = 0.0
    for layer in sheet.layers:
        for item in layer.items:
            z += 1.0
            _draw(ax, item, z)
    return fig


_RC: dict[Any, Any] = {"lines.scale_dashes": False, "svg.hashsalt": "kinepoly", "text.antialiased": True,
       "font.family": "DejaVu Sans"}
"""matplotlib settings of every file: dashes in mm as given, fixed ids."""


@contextlib.contextmanager
def _quiet_warnings() -> Iterator[None]:
    """No "Glyph ... missing from font" warning on standard error: such a letter is drawn as the font's box."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=r"Glyph \d+ .*missing from font", category=UserWarning)
        yield


def write_png(sheet: Sheet, target: Any, dpi: int = DEFAULT_DPI) -> None:
    """Write the sheet as PNG to a path or a binary file object."""
    import matplotlib

    with matplotlib.rc_context(_RC), _quiet_warnings():
        figure_of(sheet).savefig(target, format="png", dpi=dpi, metadata={"Software": None})


def write_pdf(sheet: Sheet, target: Any) -> None:
    """Write the sheet as a one-page PDF (fonts embedded) to a path or a binary file object (``render.pdf``)."""
    from kinepoly.render.pdf import write_pdf_pages as write

    write([sheet], target, sheet.title)


def write_pdf_pages(sheets: Sequence[Sheet], target: Any, title: str) -> None:
    """Write the sheets as one PDF, a page each (fonts embedded), to a path or a binary file object (``render.pdf``)."""
    from kinepoly.render.pdf import write_pdf_pages as write

    write(sheets, target, title)
