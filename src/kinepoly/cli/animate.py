"""``kinepoly animate SCENE -o FILE [--from A --to B] [--positions N] [--fps F] [--parts ...] [--dpi D]``.

The mechanism moving over a sweep with its velocity and acceleration polygons at scales fixed
for the whole cycle: ``.gif`` (matplotlib and pillow), ``.mp4`` (needs ffmpeg) or ``.html`` (one
self-contained page: play/pause, a slider, the values). The sweep runs once, then every frame is
drawn. Positions the mechanism cannot reach are skipped and reported on standard error. The
file is written whole or not at all; a progress bar is drawn on standard error when it is a terminal.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

from kinepoly.errors import OutputError, SceneError

__all__ = ["add_arguments", "run"]

_PARTS = ("mechanism", "velocity", "acceleration", "centers", "paths", "functions")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("-o", "--output", required=True, metavar="FILE",
                        help="the animation: FILE.gif, FILE.mp4 (needs ffmpeg) or FILE.html")
    parser.add_argument("--from", dest="start", type=float, metavar="A",
                        help="first input (the scene's angle unit, or length for a slider input)")
    parser.add_argument("--to", dest="stop", type=float, metavar="B", help="last input (with --from)")
    parser.add_argument("--positions", type=int, default=None, metavar="N",
                        help="how many positions (frames; a full turn in N equal steps), default 72 per turn "
                             "(a geared mechanism's whole cycle: up to 720)")
    parser.add_argument("--fps", type=float, default=24.0, metavar="F", help="frames per second, default 24")
    parser.add_argument("--parts", nargs="+", metavar="PART", default=None,
                        help=f"what each frame shows, some of: {', '.join(_PARTS)} "
                             "(default: mechanism velocity acceleration paths)")
    parser.add_argument("--dpi", type=float, default=160.0,
                        help="pixels per inch of the frames of .gif and .mp4 (their sheet is 10 x 5.625 inches), "
                             "default 160: 1600 x 900")


class _Bar:
    """A bar on a terminal's standard error."""

    def __init__(self) -> None:
        self.drawn = False

    def __call__(self, done: int, total: int) -> None:
        width = 30
        filled = int(width * done / max(total, 1))
        sys.stderr.write(f"\rkinepoly animate [{'#' * filled}{'.' * (width - filled)}] {done}/{total} frames")
        sys.stderr.flush()
        self.drawn = True

    def close(self) -> None:
        if self.drawn:
            sys.stderr.write("\r" + " " * 70 + "\r")
            sys.stderr.flush()


def _check(args: argparse.Namespace) -> list[str]:
    from kinepoly.motion.api import motion_format

    for flag, value in (("--from", args.start), ("--to", args.stop), ("--fps", args.fps)):
        if value is not None and not math.isfinite(value):
            raise SceneError(f"{flag}: expected a finite number, got {value}")
    if (args.start is None) != (args.stop is None):
        raise SceneError("--from and --to: give both, or neither for the full turn (or the input's whole range)")
    parts = [p for given in (args.parts or []) for p in given.replace(",", " ").split()]
    unknown = [p for p in parts if p not in _PARTS]
    if unknown:
        raise SceneError(f"--parts: expected some of {', '.join(_PARTS)}, got {', '.join(unknown)}")
    motion_format(args.output)
    if not Path(args.output).resolve().parent.is_dir():
        raise OutputError(f"-o: the folder of {args.output} does not exist")
    return parts


def run(args: argparse.Namespace) -> int:
    """Sweep, draw every frame, write the file; report what was skipped. The exit status."""
    from kinepoly.motion.api import animate

    parts = _check(args)
    bar = _Bar() if sys.stderr.isatty() else None
    try:
        made = animate(args.scene, args.output, positions=args.positions, start=args.start, stop=args.stop,
                       fps=args.fps, parts=tuple(parts) if parts else None, dpi=args.dpi, progress=bar)
    finally:
        if bar is not None:
            bar.close()
    frames = made.frames
    size = Path(args.output).stat().st_size
    print(f"wrote {args.output}: {frames.count} frames of {len(frames.inputs)} positions, "
          f"{size / 1024:.0f} KiB, in {made.timing['total_s']:.2f} s (sweep {made.timing['sweep_s']:.2f} s)")
    if frames.skipped:
        values = ", ".join(f"{frames.inputs[r]:.6g}" for r in frames.skipped)
        print(f"kinepoly: warning [cannot-assemble]: {len(frames.skipped)} of {len(frames.inputs)} positions "
              f"cannot be reached and are skipped: {frames.input_name} = {values} {frames.input_unit}",
              file=sys.stderr)
    singular = [int(r) for r in frames.rows if frames.status[r] == 2]
    if singular:
        print(f"kinepoly: warning [singular]: {len(singular)} positions are singular (a dead or change point): "
              "the mechanism is drawn there without its polygons", file=sys.stderr)
    return 0
