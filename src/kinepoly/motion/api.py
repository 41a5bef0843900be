"""``kinepoly.animate`` and ``kinepoly.draw``: the motion and the drawing for Python and notebooks.

``animate(scene, path)`` does what ``kinepoly animate`` does (the sweep once, the frames, then
the drawing as .gif, .mp4 or .html) and returns an ``Animation`` (its frames, its bytes; a
notebook shows it); with ``path`` the file is also written, whole or not at all.
``draw(solution, part=...)`` returns the drawing's SVG text, the whole sheet or one part of it.
"""

from __future__ import annotations

import base64
import os
import time
from pathlib import Path
from typing import TYPE_CHECKING

from msgspec import Struct, field

from kinepoly.errors import OutputError, SceneError
from kinepoly.motion.frames import DEFAULT_PARTS, Frames, make_frames
from kinepoly.scene.spec import Scene

if TYPE_CHECKING:
    from kinepoly.motion.video import Progress
    from kinepoly.solution import Solution

__all__ = ["DEFAULT_POSITIONS", "FORMATS", "MAX_DEFAULT_POSITIONS", "PART_LAYERS", "Animation", "animate", "draw",
           "motion_format"]

FORMATS = ("gif", "mp4", "html")
DEFAULT_POSITIONS = 72
"""Positions of an animation without ``positions``, per turn of the sweep."""
MAX_DEFAULT_POSITIONS = 720
"""The most positions a geared mechanism's cycle takes by default."""
PART_LAYERS = ("mechanism", "velocity-polygon", "acceleration-polygon", "instant-centers")
"""The parts ``draw`` can give alone: a layer of the sheet, cut to its panel."""
_PANEL = {"mechanism": "mechanism", "velocity-polygon": "velocity", "acceleration-polygon": "acceleration",
          "instant-centers": "mechanism"}


class Animation(Struct, frozen=True):
    """The motion made: its frames (the data drawn), the file's bytes and format, the time taken."""

    frames: Frames
    data: bytes
    format: str
    timing: dict[str, float] = field(default_factory=dict)

    def _repr_html_(self) -> str:
        if self.format == "gif":
            return f'<img src="data:image/gif;base64,{base64.b64encode(self.data).decode()}">'
        if self.format == "mp4":
            return (f'<video controls loop src="data:video/mp4;base64,{base64.b64encode(self.data).decode()}">'
                    "</video>")
        page = base64.b64encode(self.data).decode()
        return f'<iframe src="data:text/html;base64,{page}" style="width:100%;height:760px;border:0"></iframe>'


def motion_format(path: str | os.PathLike[str]) -> str:
    """The format a file name asks: .gif, .mp4 or .html (OutputError, exit 2, otherwise)."""
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix == "htm":
        suffix = "html"
    if suffix not in FORMATS:
        raise OutputError(f"{path}: expected a file ending in .gif, .mp4 or .html")
    return suffix


def _check(positions: int, fps: float, dpi: float) -> None:
    if not 2 <= positions <= 10000:
        raise SceneError(f"--positions {positions}: expected a number of positions from 2 to 10000")
    if not 0.1 <= fps <= 100:
        raise SceneError(f"--fps {fps:g}: expected frames per second from 0.1 to 100")
    if not 20 <= dpi <= 400:
        raise SceneError(f"--dpi {dpi:g}: expected a resolution from 20 to 400")


def animate(scene: Scene | str | os.PathLike[str], path: str | os.PathLike[str] | None = None, *,
            format: str | None = None, positions: int | None = None, start: float | None = None,
            stop: float | None = None,
            fps: float = 24.0, parts: tuple[str, ...] | None = None, dpi: float = 160.0,
            progress: Progress | None = None) -> Animation:
    """The mechanism moving over a sweep of ``positions`` positions, with its polygons at fixed scales.

    Without ``positions``: 72 per turn of the sweep (a geared mechanism's whole cycle has several), up to 720.

    ``scene``: a Scene or a scene file; ``path``: the file to write (its extension gives the
    format), or None to only return the Animation (``format`` then says which, GIF by default).
    """
    from kinepoly.scene.loader import load_scene
    from kinepoly.sweep.run import cycle_turns, prepare_sweep, run_sweep

    fmt = motion_format(path) if path is not None else (format or "gif")
    if fmt not in FORMATS:
        raise OutputError(f"format {fmt!r}: expected one of {', '.join(FORMATS)}")
    _check(72 if positions is None else positions, fps, dpi)
    if fmt == "mp4":
        from kinepoly.motion.video import ffmpeg

        ffmpeg()  # before the work: a missing program is said at once
    t0 = time.perf_counter()
    loaded = scene if isinstance(scene, Scene) else load_scene(str(scene))
    prepared = prepare_sweep(loaded)
    if positions is None:
        positions = min(DEFAULT_POSITIONS * (cycle_turns(prepared) if start is None else 1), MAX_DEFAULT_POSITIONS)
    result = run_sweep(prepared, steps=positions, start=start, stop=stop)
    frames = make_frames(result, prepared, parts if parts is not None else DEFAULT_PARTS)
    t1 = time.perf_counter()
    data = render(frames, fmt, fps=fps, dpi=dpi, progress=progress)
    t2 = time.perf_counter()
    if path is not None:
        from kinepoly.atomic import write_bytes

        write_bytes(path, data)
    return Animation(frames, data, fmt, {"sweep_s": t1 - t0, "drawing_s": t2 - t1, "total_s": t2 - t0})


def render(frames: Frames, fmt: str, *, fps: float = 24.0, dpi: float = 160.0,
           progress: Progress | None = None) -> bytes:
    """The frames drawn as ``fmt`` (gif, mp4 or html)."""
    if fmt == "html":
        from kinepoly.motion.html import html_page

        if progress is not None:
            progress(frames.count, frames.count)
        return html_page(frames, fps).encode()
    from kinepoly.motion.video import gif_bytes, mp4_bytes

    return (gif_bytes if fmt == "gif" else mp4_bytes)(frames, fps, dpi, progress)


def draw(solution: Solution, part: str | None = None, paper: str | tuple[float, float] = "A4") -> str:
    """The drawing of ``solution`` as SVG text: the whole sheet, or one part (a layer of it, cut to its panel)."""
    from kinepoly.render.primitives import Layer, Sheet
    from kinepoly.render.sheet import build_sheet, layout_sheet
    from kinepoly.render.svg import svg_text

    layout = layout_sheet(solution, paper)
    sheet = build_sheet(solution, paper, layout=layout)
    if part is None:
        return svg_text(sheet)
    if part not in PART_LAYERS:
        raise SceneError(f"part {part!r}: expected one of {', '.join(PART_LAYERS)} (or None for the whole sheet)")
    panel = layout.panel(_PANEL[part])
    layers = [layer for layer in sheet.layers if layer.name == part]
    if panel is None or not layers or not layers[0].items:
        raise SceneError(f"part {part!r}: this solution's drawing has none (not asked in [find])")
    x0, y0, x1, y1 = panel.rect
    if part == "instant-centers" and layout.panel("centers") is not None:
        other = layout.panel("centers")
        assert other is not None
        x0, y0 = min(x0, other.rect[0]), min(y0, other.rect[1])
        x1, y1 = max(x1, other.rect[2]), max(y1, other.rect[3])
    keep = {part, "mechanism"} if part == "instant-centers" else {part}
    cut = Sheet(sheet.width, sheet.height, sheet.title,
                tuple(Layer(layer.name, layer.items if layer.name in keep else ()) for layer in sheet.layers))
    return svg_text(cut, view=(x0, y0, x1, y1))
