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
"""Intervals of a sweep without --positions: a full turn in 1 degree steps (each turn of a geared mechanism's
cycle so)."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("--from", dest="start", type=float, metavar="A",
                        help="first input (the scene's angle unit, or length for a slider input)")
    parser.add_argument("--to", dest="stop", type=float, metavar="B", help="last input (with --from)")
    parser.add_argument("--positions", type=int, default=None, metavar="N",
                        help="how many equal intervals: N + 1 rows from A to B, both ends included; N rows over a "
                             "full turn, or over a geared mechanism's whole cycle of turns (its end would repeat its "
                             f"start); default {DEFAULT_POSITIONS} per turn")
    parser.add_argument("--steps", dest="positions", type=int, help=argparse.SUPPRESS)  # the old name, still taken
    parser.add_argument("-o", "--output", metavar="FILE.csv", help="write the CSV here ('-' for standard output)")
    parser.add_argument("--plot", metavar="FILE.png", help="write the plots (PNG) here")
    parser.add_argument("--centrode", metavar="LINK", help="also report the fixed and moving centrodes of LINK")
    parser.add_argument("--series", action="store_true", help="a slider-crank driven by its crank: add the course "
                        "text's two-term series of s, s_dot, s_ddot beside the exact ones, and their errors (columns "
                        "s_series_14, s_series_error_14, ...; plotted with --plot)")
    parser.add_argument("--pole", nargs=2, type=float, metavar="INPUT",
                        help="with --centrode LINK, two inputs A B: the pole P12 of LINK's finite displacement from "
                        "input A to input B (the crossing of the perpendicular bisectors of A1A2 and B1B2), printed "
                        "on standard error")
    parser.add_argument("--pole-plot", metavar="FILE.png", help="with --pole: the mechanism at both inputs, the "
                        "bisectors, P12 and the instant center at A (PNG)")


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
        self.stream.write(f"\rkinepoly sweep [{'#' * filled}{'.' * (width - filled)}] "
                          f"{100 * done // max(total, 1):3d}%")
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
    if args.pole is not None and args.centrode is None:
        raise SceneError("--pole A B: give the link too, with --centrode LINK")
    if args.pole_plot is not None and args.pole is None:
        raise SceneError("--pole-plot: give the two inputs too, with --pole A B")
    if args.pole is not None and not all(math.isfinite(x) for x in args.pole):
        raise SceneError(f"--pole: expected two finite numbers, got {args.pole[0]} {args.pole[1]}")
    for flag, value in (("-o", args.output), ("--plot", args.plot), ("--pole-plot", args.pole_plot)):
        if value and value != "-" and not output_path(value, flag, [args.scene]).resolve().parent.is_dir():
            raise SceneError(f"{flag}: the folder of {value} does not exist")


def _summary(result: object) -> str:
    from kinepoly.sweep.result import STATUS, SweepResult

    assert isinstance(result, SweepResult)
    counts = {name: int((result.status == level).sum()) for level, name in enumerate(STATUS)}
    x = result.input.values
    unit = result.scene.units.angle if result.input.name.startswith("theta") else result.scene.units.length
    marked = ", ".join(f"{n} {name}" for name, n in counts.items() if n and name != "ok") or "none marked"
    span = ""
    if result.periodic:
        full = 360.0 if unit == "deg" else 2.0 * math.pi
        turns = round((float(x[-1] - x[0]) * len(x) / max(len(x) - 1, 1)) / full) if len(x) > 1 else 1
        span = " (a full turn)" if turns <= 1 else f" ({turns} full turns, the gears' whole cycle)"
    return (f"{result.scene.title}: {result.rows} positions of {result.input.name} from {x[0]:.6g} to {x[-1]:.6g} "
            f"{unit}{span}; {counts['ok']} ok, {marked}; "
            f"{len(result.columns)} quantities; {1e3 * result.timing.get('total_s', 0.0):.3g} ms")


def run(args: argparse.Namespace) -> int:
    """Load, sweep, write the CSV and the plots, print the CSV or a summary; the exit status."""
    from kinepoly.scene.loader import load_scene
    from kinepoly.sweep.run import cycle_turns, prepare_sweep, run_sweep
    from kinepoly.sweep.table import csv_text

    _check(args)
    scene = load_scene(args.scene)
    bar = _ProgressBar(sys.stderr) if sys.stderr.isatty() else None
    try:
        prepared = prepare_sweep(scene, args.centrode, args.series)
        steps = args.positions
        if steps is None:
            steps = DEFAULT_POSITIONS * (cycle_turns(prepared) if args.start is None else 1)
        result = run_sweep(prepared, steps=steps, start=args.start, stop=args.stop, progress=bar)
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
    if args.pole is not None:
        _pole(args, scene, result)
    return 0


def _pole(args: argparse.Namespace, scene: Any, result: Any) -> None:
    """The finite-rotation pole: its line on standard error, its drawing where asked."""
    from kinepoly.sweep.pole import pole_between

    found = pole_between(scene, args.centrode, args.pole[0], args.pole[1])
    name, pole = result.input.name, found.found
    unit = scene.units.length
    where = (f"({pole.pole.real:.6g}, {pole.pole.imag:.6g}) {unit}" if pole.pole is not None else
             "at infinity (the link is translated, not turned)")
    centre = found.instant_center
    limit = (f"; the instant center at {name} = {args.pole[0]:g} is ({centre.real:.6g}, {centre.imag:.6g})"
             if centre else "")
    print(f"kinepoly: finite-rotation pole P12 of link {args.centrode} from {name} = {args.pole[0]:g} to "
          f"{args.pole[1]:g}: {where}, the link turning {math.degrees(pole.turn):.6g} deg{limit}", file=sys.stderr)
    if args.pole_plot:
        from kinepoly.sweep.pole_plot import pole_png

        _write(args.pole_plot, pole_png(scene, found, name, unit))
