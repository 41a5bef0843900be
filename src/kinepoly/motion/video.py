"""The frames drawn with matplotlib, one figure whose artists move: GIF (pillow) and MP4 (ffmpeg).

matplotlib is imported inside the functions (``kinepoly solve`` never pays for it). The figure
is built once; each frame only moves its artists (links, blocks, polygon arrows, labels, the
traced paths, the cursor) and is read back as pixels, so a frame costs one canvas draw.
"""

from __future__ import annotations

import io
import os
import shutil
import subprocess
import tempfile
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

import numpy as np

from kinepoly.errors import OutputError
from kinepoly.motion.frames import NO_POLYGON, PANEL_MM, Frames, PolygonFrames

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["FFMPEG_MISSING", "Progress", "frame_images", "gif_bytes", "mp4_bytes", "value_text"]

Progress = Callable[[int, int], None]
FFMPEG_MISSING = ("writing .mp4 needs the program ffmpeg, which is not installed (on Debian or Ubuntu: "
                  "apt-get install ffmpeg); or write .gif or .html instead")
_COLORS = {"velocity": "#1f5fbf", "acceleration": "#c0392b", "sliding": "#d98200", "coriolis": "#1e8c3a",
           "absolute": None}
_LINK_COLORS = ("#333333", "#1f5fbf", "#c0392b", "#1e8c3a", "#8e44ad", "#d98200", "#16a085")


def value_text(name: str, value: float, unit: str) -> str:
    return f"{name} = {value:.4g} {unit}"


def _tip_name(label: str) -> str:
    point, _, on = label.partition("@")
    return point.lower() + on


class _Polygon:
    """The artists of one polygon panel."""

    def __init__(self, ax: Axes, poly: PolygonFrames) -> None:
        from matplotlib.patches import FancyArrowPatch

        self.poly = poly
        color = _COLORS[poly.kind]
        half, c = 0.5 * PANEL_MM, poly.center
        ax.set_xlim(c.real - half, c.real + half)
        ax.set_ylim(c.imag - half, c.imag + half)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        name = "Velocity" if poly.kind == "velocity" else "Acceleration"
        symbol = "kv" if poly.kind == "velocity" else "ka"
        ax.set_title(f"{name} polygon\n{symbol} = {poly.scale:g} mm per {poly.unit}", fontsize=8)
        ax.plot([0], [0], "o", color="black", ms=3)
        ax.annotate("o", (0, 0), xytext=(-8, -8), textcoords="offset points", fontsize=8)
        self.images = [ax.plot([], [], "-", color=color, lw=0.8, alpha=0.5)[0] for _ in poly.images]
        self.arrows = []
        for _, _, term in poly.vectors:
            arrow = FancyArrowPatch((0, 0), (0, 0), arrowstyle="-|>", mutation_scale=8, shrinkA=0, shrinkB=0,
                                    lw=1.1, color=_COLORS[term] or color)
            ax.add_patch(arrow)
            self.arrows.append(arrow)
        self.ax = ax
        self.color: str = color or "#000000"
        self.letters: list[tuple[Any, float, float, str, str]] = []
        self.marker = ax.text(c.real, c.imag - 0.8 * half, NO_POLYGON[2], fontsize=8, color="#888888", ha="center",
                              va="center", visible=False)

    def show(self, k: int) -> None:
        poly = self.poly
        valid = bool(poly.valid[k])
        tips = poly.tips[k]

        def at(j: int) -> tuple[float, float]:
            z = 0j if j < 0 else complex(tips[j])
            return (z.real, z.imag)

        for line, image in zip(self.images, poly.images):
            xy = [at(j) for j in image]
            line.set_data([p[0] for p in xy], [p[1] for p in xy])
            line.set_visible(valid)
        for arrow, (start, end, _) in zip(self.arrows, poly.vectors):
            a, b = at(start), at(end)
            arrow.set_positions(a, b)
            arrow.set_visible(valid and abs(complex(*a) - complex(*b)) > 0.3)
        self.letters = [(self.ax, *at(j), _tip_name(label), self.color) for j, label in enumerate(poly.labels)
                        if valid]
        self.marker.set_visible(not valid)


class _Scene:
    """The whole figure and a way to show frame k on it."""

    def __init__(self, frames: Frames, dpi: float) -> None:
        import matplotlib

        matplotlib.use("Agg")
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        self.frames = frames
        polygons = [p for p in (frames.velocity, frames.acceleration) if p is not None]
        functions = "functions" in frames.parts
        width = 4.2 + 2.9 * len(polygons)
        height = 3.7 + (1.6 if functions else 0.0)
        self.figure: Figure = Figure(figsize=(width, height), dpi=dpi)
        self.canvas = FigureCanvasAgg(self.figure)
        self.background: Any = None
        grid = self.figure.add_gridspec(2 if functions else 1, 1 + len(polygons),
                                        width_ratios=[4.2] + [2.9] * len(polygons),
                                        height_ratios=[3.4, 1.6] if functions else None,
                                        left=0.02, right=0.98, top=0.86, bottom=0.1, wspace=0.06, hspace=0.3)
        self.ax = self.figure.add_subplot(grid[0, 0])
        self._mechanism(self.ax)
        self.polygons = [_Polygon(self.figure.add_subplot(grid[0, 1 + j]), p) for j, p in enumerate(polygons)]
        self.cursor = None
        if functions:
            self.cursor = self._functions(self.figure.add_subplot(grid[1, :]))
        self.title = ""
        self.values = ""
        self._fonts(dpi)

    def _mechanism(self, ax: Axes) -> None:
        f = self.frames
        x0, y0, x1, y1 = f.box
        margin = 0.12 * max(x1 - x0, y1 - y0, 1e-9)
        ax.set_xlim(x0 - margin, x1 + margin)
        ax.set_ylim(y0 - margin, y1 + margin)
        ax.set_aspect("equal", adjustable="box")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(f"Mechanism ({f.length_unit})", fontsize=8)
        self.paths = [ax.plot([], [], "-", color="#999999", lw=0.7)[0] for _ in f.paths]
        self.links = []
        self.point_labels = []
        for j, link in enumerate(f.links):
            if link.ground:
                pts = link.xy[0]
                ax.plot(pts.real, pts.imag, "^", color="#333333", ms=7, mfc="white", zorder=4)
                continue
            color = _LINK_COLORS[j % len(_LINK_COLORS)]
            self.links.append((link, ax.plot([], [], "-o", color=color, lw=2.0, ms=3.5, mfc="white", zorder=3)[0]))
        seen: set[str] = set()
        for link in f.links:
            for p, name in enumerate(link.points):
                if name in seen:
                    continue
                seen.add(name)
                self.point_labels.append((link, p, name))
        self.guides = [ax.plot([], [], "-", color="#555555", lw=0.8)[0] for _ in f.sliders]
        self.blocks = [ax.plot([], [], "-", color="#333333", lw=1.4, zorder=4)[0] for _ in f.sliders]
        self.block_size = 0.06 * max(x1 - x0, y1 - y0, 1e-9)
        self.centers = [ax.plot([], [], "x", color="#8e44ad", ms=5)[0] for c in f.centers]
        self.reach = (x0 - margin, y0 - margin, x1 + margin, y1 + margin)

    def _functions(self, ax: Axes) -> Any:
        f = self.frames
        chosen, window = f.functions()
        x = f.inputs
        for v in chosen:
            ax.plot(x, np.ma.masked_array(v.values, mask=~v.valid), lw=1.0, label=f"{v.name} ({v.unit})")
        if window is not None:
            ax.set_ylim(*window)
        for row in f.skipped:
            ax.axvspan(x[row] - 0.5 * _step(x), x[row] + 0.5 * _step(x), color="#dddddd", lw=0)
        ax.set_xlabel(f"{f.input_name} ({f.input_unit})", fontsize=7)
        ax.tick_params(labelsize=7)
        if chosen:
            ax.legend(fontsize=7, loc="upper right")
        ax.grid(True, lw=0.3)
        return ax.axvline(x[0], color="black", lw=0.9)

    def show(self, k: int) -> None:
        f = self.frames
        row = int(f.rows[k])
        for link, line in self.links:
            pts = link.xy[k]
            closed = np.append(pts, pts[:1]) if len(pts) >= 3 else pts
            line.set_data(closed.real, closed.imag)
        self.letters: list[tuple[Any, float, float, str, str]] = []
        for link, p, name in self.point_labels:
            z = complex(link.xy[k, p])
            self.letters.append((self.ax, z.real, z.imag, name, "#000000"))
        for line, trace in zip(self.paths, f.paths):
            line.set_data(trace.xy[:k + 1].real, trace.xy[:k + 1].imag)
        for guide, block, s in zip(self.guides, self.blocks, f.sliders):
            a, b = complex(s.guide_a[k]), complex(s.guide_b[k])
            guide.set_data([a.real, b.real], [a.imag, b.imag])
            c, e = complex(s.block[k]), complex(s.direction[k])
            h = self.block_size
            corners = [c + h * e * (dx + 0.6j * dy) for dx, dy in ((-1, -1), (1, -1), (1, 1), (-1, 1), (-1, -1))]
            block.set_data([z.real for z in corners], [z.imag for z in corners])
        x0, y0, x1, y1 = self.reach
        for marker, center in zip(self.centers, f.centers):
            z = complex(center.xy[k])
            inside = bool(center.valid[k]) and x0 <= z.real <= x1 and y0 <= z.imag <= y1
            marker.set_data([z.real], [z.imag])
            marker.set_visible(inside)
            if inside:
                self.letters.append((self.ax, z.real, z.imag, center.name, "#8e44ad"))
        for polygon in self.polygons:
            polygon.show(k)
            polygon.marker.set_text(NO_POLYGON[int(f.status[row])])
            self.letters += polygon.letters
        if self.cursor is not None:
            self.cursor.set_xdata([f.inputs[row], f.inputs[row]])
        status = ("", " (near-singular)", " (singular: polygons not determined)", "")[int(f.status[row])]
        self.title = (f"{f.title}: {value_text(f.input_name, float(f.inputs[row]), f.input_unit)}, "
                            f"position {row + 1} of {len(f.inputs)}{status}")
        shown = [value_text(v.name, float(v.values[row]), v.unit) for v in f.values[1:] if v.valid[row]
                 and v.order >= 1 and not v.name.startswith("|")]
        self.values = "   ".join(shown[:5])

    def moving(self) -> list[Any]:
        """Every artist that changes from frame to frame (drawn over the still background)."""
        out: list[Any] = [*self.paths, *(line for _, line in self.links), *self.guides, *self.blocks,
                          *self.centers]
        for polygon in self.polygons:
            out += [*polygon.images, *polygon.arrows, polygon.marker]
        if self.cursor is not None:
            out.append(self.cursor)
        return out

    def pixels(self) -> np.ndarray:
        """The frame shown: the still background drawn once, then only the moving artists (blitting)."""
        if self.background is None:
            for artist in self.moving():
                artist.set_animated(True)
            self.canvas.draw()  # type: ignore[no-untyped-call]
            self.background = self.canvas.copy_from_bbox(self.figure.bbox)  # type: ignore[no-untyped-call]
        else:
            self.canvas.restore_region(self.background)  # type: ignore[no-untyped-call]
        for artist in self.moving():
            if artist.get_visible():
                self.figure.draw_artist(artist)
        rgba = np.asarray(self.canvas.buffer_rgba())  # type: ignore[no-untyped-call]
        return self._lettered(np.ascontiguousarray(rgba[:, :, :3]))

    def _fonts(self, dpi: float) -> None:
        from matplotlib import font_manager
        from PIL import ImageFont

        regular = font_manager.findfont("DejaVu Sans")
        self.title_font = ImageFont.truetype(regular, max(8, round(9 * dpi / 72)))
        self.values_font = ImageFont.truetype(regular, max(7, round(7.5 * dpi / 72)))
        self.label_font = ImageFont.truetype(regular, max(7, round(8 * dpi / 72)))
        self.dpi = dpi

    def _lettered(self, pixels: np.ndarray) -> np.ndarray:
        """The title and the values written over the frame (pillow draws a line of text far faster than Agg)."""
        from PIL import Image, ImageDraw

        image = Image.fromarray(pixels)
        draw = ImageDraw.Draw(image)
        width, height = image.size
        draw.text((width / 2, 3), self.title, fill="black", font=self.title_font, anchor="ma")
        draw.text((width / 2, height - 3), self.values, fill="black", font=self.values_font, anchor="md")
        shift = 2.0 * self.dpi / 72
        for ax, x, y, text, color in self.letters:
            px, py = ax.transData.transform((x, y))
            draw.text((px + shift, height - py - shift), text, fill=color, font=self.label_font, anchor="ld")
        return np.asarray(image)


def _step(x: np.ndarray) -> float:
    return float(np.median(np.abs(np.diff(x)))) if len(x) > 1 else 1.0


def frame_images(frames: Frames, dpi: float = 80.0, progress: Progress | None = None) -> Iterator[np.ndarray]:
    """Each frame's pixels (RGB, height x width x 3)."""
    scene = _Scene(frames, dpi)
    for k in range(frames.count):
        scene.show(k)
        yield scene.pixels()
        if progress is not None:
            progress(k + 1, frames.count)


def gif_bytes(frames: Frames, fps: float = 24.0, dpi: float = 80.0, progress: Progress | None = None) -> bytes:
    """The animated GIF: one frame per position the mechanism reaches, one palette for all, looping."""
    from PIL import Image

    images = []
    palette = None
    for pixels in frame_images(frames, dpi, progress):
        image = Image.fromarray(pixels)
        if palette is None:
            palette = image.quantize(colors=96, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
            images.append(palette)
        else:
            images.append(image.quantize(palette=palette, dither=Image.Dither.NONE))
    buffer = io.BytesIO()
    images[0].save(buffer, format="GIF", save_all=True, append_images=images[1:], duration=round(1000.0 / fps),
                   loop=0, optimize=False, disposal=1)
    return buffer.getvalue()


def ffmpeg() -> str:
    """The ffmpeg program; OutputError (exit 2) naming it when it is not installed."""
    found = shutil.which("ffmpeg")
    if found is None:
        raise OutputError(FFMPEG_MISSING)
    return found


def mp4_bytes(frames: Frames, fps: float = 24.0, dpi: float = 80.0, progress: Progress | None = None) -> bytes:
    """The MP4 (H.264, yuv420p): the frames' pixels piped to ffmpeg."""
    program = ffmpeg()
    images = frame_images(frames, dpi, progress)
    first = next(images)
    height, width = first.shape[:2]
    with tempfile.TemporaryDirectory(prefix="kinepoly-mp4-") as folder:
        target = os.path.join(folder, "out.mp4")
        command = [program, "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
                   f"{width}x{height}", "-r", f"{fps:g}", "-i", "-", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                   "-pix_fmt", "yuv420p", "-c:v", "libx264", target]
        with subprocess.Popen(command, stdin=subprocess.PIPE, stderr=subprocess.PIPE) as process:
            assert process.stdin is not None
            try:
                process.stdin.write(first.tobytes())
                for pixels in images:
                    process.stdin.write(pixels.tobytes())
            finally:
                process.stdin.close()
            error = process.stderr.read().decode(errors="replace") if process.stderr else ""
            if process.wait() != 0:
                raise OutputError(f"ffmpeg failed: {error.strip()}")
        with open(target, "rb") as stream:
            return stream.read()
