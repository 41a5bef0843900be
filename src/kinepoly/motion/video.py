"""The frames as pixels, GIF (pillow) and MP4 (ffmpeg): each frame the drawing's own sheet (``motion.sheets``).

matplotlib is imported inside the functions (``kinepoly solve`` never pays for it).
"""

from __future__ import annotations

import io
import os
import shutil
import subprocess
import tempfile
from collections.abc import Callable, Iterator

import numpy as np

from kinepoly.errors import OutputError
from kinepoly.motion.frames import Frames
from kinepoly.motion.sheets import DEFAULT_DPI, frame_sheets, frame_solutions, sheet_pixels

__all__ = ["FFMPEG_MISSING", "Progress", "frame_images", "gif_bytes", "mp4_bytes"]

Progress = Callable[[int, int], None]
FFMPEG_MISSING = ("writing .mp4 needs the program ffmpeg, which is not installed (on Debian or Ubuntu: "
                  "apt-get install ffmpeg); or write .gif or .html instead")


def frame_images(frames: Frames, dpi: float = DEFAULT_DPI, progress: Progress | None = None) -> Iterator[np.ndarray]:
    """Each frame's pixels (RGB, height x width x 3): its sheet (``motion.sheets``) drawn by the drawing's writer."""
    if frames.scene is None:
        raise ValueError("these frames keep no scene (they were not made by kinepoly.motion.frames.make_frames)")
    solutions = frame_solutions(frames, frames.scene)
    for k, sheet in enumerate(frame_sheets(frames, solutions)):
        yield sheet_pixels(sheet, dpi)
        if progress is not None:
            progress(k + 1, frames.count)


def gif_bytes(frames: Frames, fps: float = 24.0, dpi: float = DEFAULT_DPI, progress: Progress | None = None) -> bytes:
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


def mp4_bytes(frames: Frames, fps: float = 24.0, dpi: float = DEFAULT_DPI, progress: Progress | None = None) -> bytes:
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
