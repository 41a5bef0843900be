"""``kinepoly bench SCENE [--json] [--plot FILE.png] [--sweep [N]] [--family N]``: error against run time.

The bench package measures (``bench.run``, ``bench.sweep``), draws (``bench.plot``) and words
(``bench.report``); this module prints the lines and writes the plot whole or not at all.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import IO, Any

from kinepoly.cli.files import write_atomically
from kinepoly.errors import SceneError

__all__ = ["DEFAULT_SWEEP", "add_arguments", "run"]

DEFAULT_SWEEP = 120
"""Inputs of a sweep when ``--sweep`` is given without a number."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML); it needs an [input] (a crank or a driven slider)")
    parser.add_argument("--json", action="store_true",
                        help='print {"methods": [{"name", "error", "time_s", ...}, ...]} as one JSON object')
    parser.add_argument("--plot", metavar="FILE.png",
                        help="draw the work-precision diagram (with --sweep: the error over the input)")
    parser.add_argument("--sweep", metavar="N", type=int, nargs="?", const=DEFAULT_SWEEP,
                        help=f"the error of each method at N inputs over a full turn of the input (a slider: its "
                             f"stroke), singular positions marked; N defaults to {DEFAULT_SWEEP}")
    parser.add_argument("--budget", metavar="SECONDS", type=float, default=0.25,
                        help="time spent repeating each method for its median (default 0.25 s)")
    parser.add_argument("--family", metavar="N", type=int,
                        help="a family of N members (each link's points times a factor of its own): "
                             "kinepoly.sweep_family against one sweep per member, timed, and against the reference")
    parser.add_argument("--spread", type=float, default=0.05,
                        help="with --family: the factors lie in [1 - SPREAD, 1 + SPREAD] (default 0.05)")
    parser.add_argument("--seed", type=int, default=0, help="with --family: the random seed of the factors")
    parser.add_argument("--positions", type=int, default=72,
                        help="with --family: rows of each member over the scene's range (default 72)")


def _family(args: argparse.Namespace, scene: Any) -> list[str]:
    """``--family N``: the family sweep against the loop and the reference (``bench.family``)."""
    from kinepoly.bench.family import run_family

    if args.family < 1:
        raise SceneError(f"--family {args.family}: expected at least 1 member")
    if not 0.0 <= args.spread < 1.0:
        raise SceneError(f"--spread {args.spread:g}: expected a fraction from 0 up to (not including) 1")
    if args.sweep is not None or args.plot:
        raise SceneError("--family: measured on its own; leave out --sweep and --plot")
    result = run_family(scene, args.family, args.positions, spread=args.spread, seed=args.seed)
    return [json.dumps(result.as_json(), indent=1, allow_nan=False)] if args.json else result.lines()


def _write_plot(path: str, image: bytes) -> None:
    def write(stream: IO[Any]) -> None:
        stream.write(image)

    write_atomically(path, write, binary=True)


def _plot_format(path: str) -> str:
    """The image format of ``--plot FILE``: its extension (as matplotlib reads it), PNG without one."""
    return Path(path).suffix.lstrip(".").lower() or "png"


def run(args: argparse.Namespace) -> int:
    """Load, solve, bench (or sweep), plot; print the lines; the exit status."""
    for line in _bench(args):
        print(line)
    return 0


def _bench(args: argparse.Namespace) -> list[str]:
    """Load, solve, bench (or sweep), plot; the lines to print."""
    from kinepoly.bench.report import bench_json, bench_text, sweep_json, sweep_text
    from kinepoly.scene.loader import load_scene
    from kinepoly.scene.spec import GivenInput
    from kinepoly.solution import solve

    try:
        import mpmath  # type: ignore[import-untyped]  # noqa: F401
    except ImportError:
        raise SceneError("kinepoly bench measures errors against an mpmath reference: install it with "
                         "pip install 'kinepoly[bench]'") from None
    scene = load_scene(args.scene)
    if isinstance(scene.input, GivenInput):
        raise SceneError(f"{scene.source}: given: kinepoly bench needs a scene driven by [input] (a crank or a "
                         "driven slider); a [given] scene has no input to vary")
    if args.sweep is not None and args.sweep < 2:
        raise SceneError(f"--sweep {args.sweep}: expected at least 2 inputs")
    if args.family is not None:
        return _family(args, scene)
    t0 = time.perf_counter()
    solution = solve(scene)
    if args.sweep is not None:
        from kinepoly.bench.sweep import run_sweep

        sweep = run_sweep(solution, args.sweep)
        if args.plot:
            from kinepoly.bench.plot import plot_sweep

            _write_plot(args.plot, plot_sweep(sweep, _plot_format(args.plot)))
        lines = [json.dumps(sweep_json(sweep), indent=1, allow_nan=False)] if args.json else sweep_text(sweep)
    else:
        from kinepoly.bench.run import run_bench

        result = run_bench(solution, budget_s=args.budget)
        if args.plot:
            from kinepoly.bench.plot import plot_work_precision

            _write_plot(args.plot, plot_work_precision(result, _plot_format(args.plot)))
        lines = [json.dumps(bench_json(result), indent=1, allow_nan=False)] if args.json else bench_text(result)
    if args.plot and not args.json:
        lines.append(f"wrote {args.plot} ({time.perf_counter() - t0:.1f} s in all)")
    return lines
