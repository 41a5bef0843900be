"""``kinepoly sweep SCENE [--positions N] [--from A --to B] [-o FILE.csv] [--plot FILE.png] [--centrode LINK]``.

Files are written whole or not at all (``cli.files.write_atomically``).
The CSV goes to ``-o FILE`` (``-o -`` or no ``-o`` and no ``--plot``: standard output). A
progress bar is drawn on standard error only when it is a terminal.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from typing import IO, Any, TextIO

from kinepoly.cli.files import output_path, write_atomically
from kinepoly.errors import OutputError, SceneError

__all__ = ["DEFAULT_POSITIONS", "add_arguments", "run"]

DEFAULT_POSITIONS = 360
"""Intervals of a sweep without --positions: a full turn in 1 degree steps."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("--from", dest="start", type=float, metavar="A",
                        help="first input (the scene's angle unit, or length for a slider input)")
    parser.add_argument("--to", dest="stop", type=float, metavar="B", help="last input (with --from)")
    parser.add_argument("--positions", type=int, default=DEFAULT_POSITIONS, metavar="N",
                        help="how many equal intervals: N + 1 rows from A to B, both ends included; N rows over a "
                             "full turn (its end would repeat its start)")
    parser.add_argument("--steps", dest="positions", type=int, help=argparse.SUPPRESS)  # the old name, still taken
    parser.add_argument("-o", "--output", metavar="FILE.csv", help="write the CSV here ('-' for standard output)")
    parser.add_argument("--plot", metavar="FILE.png", help="write the plots (PNG) here")
    parser.add_argument("--centrode", metavar="LINK", help="also report the fixed and moving centrodes of LINK")


class _ProgressBar:
    """A bar on a terminal's standard error, redrawn at most ten times a second."""

    def __init__(self, stream: TextIO) -> None:
        self.stream = stream
        self.last = 0.0
        self.drawn = False

    def __call__(self, done: int, total: int) -> None:
        now = time.monotonic()
        if now - self.last < 0.1 and done < total:
            return
        self.last = now
        width = 30
        filled = int(width * done / max(total, 1))
        self.stream.write(f"\rkinepoly sweep [{'#' * filled}{'.' * (width - filled)}] {100 * done // max(total, 1):3d}%")
        self.stream.flush()
        self.drawn = True

    def close(self) -> None:
        if self.drawn:
            self.stream.write("\r" + " " * 60 + "\r")
            self.stream.flush()


def _write(path: str, data: bytes) -> None:
    def write(stream: IO[Any]) -> None:
        stream.write(data)

    try:
        write_atomically(path, write, binary=True)
    except OSError as error:
        raise OutputError(f"cannot write {path}: {error.strerror or error}") from error


def _check(args: argparse.Namespace) -> None:
    for flag, value in (("--from", args.start), ("--to", args.stop)):
        if value is not None and not math.isfinite(value):
            raise SceneError(f"{flag}: expected a finite number, got {value}")
    if (args.start is None) != (args.stop is None):
        raise SceneError("--from and --to: give both, or neither for the full turn (or the input's whole range)")
    for flag, value in (("-o", args.output), ("--plot", args.plot)):
        if value and value != "-" and not output_path(value, flag, [args.scene]).resolve().parent.is_dir():
            raise SceneError(f"{flag}: the folder of {value} does not exist")


def _summary(result: object) -> str:
    from kinepoly.sweep.run import STATUS, SweepResult

    assert isinstance(result, SweepResult)
    counts = {name: int((result.status == level).sum()) for level, name in enumerate(STATUS)}
    x = result.input.values
    unit = result.scene.units.angle if result.input.name.startswith("theta") else result.scene.units.length
    marked = ", ".join(f"{n} {name}" for name, n in counts.items() if n and name != "ok") or "none marked"
    return (f"{result.scene.title}: {result.rows} positions of {result.input.name} from {x[0]:.6g} to {x[-1]:.6g} "
            f"{unit}{' (a full turn)' if result.periodic else ''}; {counts['ok']} ok, {marked}; "
            f"{len(result.columns)} quantities; {1e3 * result.timing.get('total_s', 0.0):.3g} ms")


def run(args: argparse.Namespace) -> int:
    """Load, sweep, write the CSV and the plots, print the CSV or a summary; the exit status."""
    from kinepoly.scene.loader import load_scene
    from kinepoly.sweep.run import sweep
    from kinepoly.sweep.table import csv_text

    _check(args)
    scene = load_scene(args.scene)
    bar = _ProgressBar(sys.stderr) if sys.stderr.isatty() else None
    try:
        result = sweep(scene, steps=args.positions, start=args.start, stop=args.stop, centrode=args.centrode,
                       progress=bar)
    finally:
        if bar is not None:
            bar.close()
    text = csv_text(result)
    to_stdout = args.output == "-" or (args.output is None and args.plot is None)
    if args.plot:
        from kinepoly.sweep.plots import plot_png

        _write(args.plot, plot_png(result))
    if args.output and args.output != "-":
        _write(args.output, text.encode())
    if to_stdout:
        sys.stdout.write(text)
    else:
        print(_summary(result))
    for notice in result.notices:
        print(f"kinepoly: warning [{notice.code}]: {notice.message}", file=sys.stderr)
    return 0
