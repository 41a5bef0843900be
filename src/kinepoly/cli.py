"""The command line: the only place that prints. ``main(argv) -> int`` so tests call it in-process.

Exit status: 0 solved; 1 an answer was wrong (``check``); 2 the scene or the command is wrong;
3 the mechanism cannot be assembled or is singular at that input; 70 an internal error.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections.abc import Sequence

from kinepoly.errors import EXIT_SCENE, KinepolyError

__all__ = ["EXIT_INTERNAL", "main", "main_exit"]

EXIT_INTERNAL = 70


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # type: ignore[override]
        self.print_usage(sys.stderr)
        raise SystemExit(_usage_exit(f"{self.prog}: {message}"))


def _usage_exit(message: str) -> int:
    print(f"kinepoly: error: {message}", file=sys.stderr)
    return EXIT_SCENE


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="kinepoly", description="Velocity and acceleration polygons of planar mechanisms, "
                     "constructed as the graphical method draws them and checked analytically.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    solve = sub.add_parser("solve", help="solve a scene: a table, the JSON of the contract, or the steps")
    solve.add_argument("scene", help="the scene file (TOML)")
    solve.add_argument("--json", action="store_true", help="print the result as one JSON object")
    solve.add_argument("--steps", action="store_true", help="print the construction step by step")
    from kinepoly.draw_command import add_arguments

    add_arguments(sub.add_parser("draw", help="draw the mechanism and its polygons: SVG, DXF, PNG, PDF, "
                                 "and the construction step by step"))
    from kinepoly.homework.arguments import add_check_arguments, add_variants_arguments

    add_check_arguments(sub.add_parser("check", help="check a student's answers and diagnose the mistakes"))
    add_variants_arguments(sub.add_parser("variants", help="randomised versions of a problem with answer keys"))
    from kinepoly.bench.command import add_arguments as add_bench_arguments

    add_bench_arguments(sub.add_parser("bench", help="error against run time of the construction and other "
                                       "methods (closed forms, finite differences, GEOS), against a 50-digit "
                                       "reference; --sweep over a full turn"))
    from kinepoly.sweep.command import add_arguments as add_sweep_arguments

    add_sweep_arguments(sub.add_parser("sweep", help="the input over a turn or a range: a CSV of the asked "
                                       "quantities, their plots, centrodes"))
    from kinepoly.handout.command import add_arguments as add_handout_arguments

    add_handout_arguments(sub.add_parser("handout", help="a teaching handout: the problem, the construction step "
                                         "by step, the answers; PDF or one web page; en, tr, ro or your own"))
    return parser


def _solve(args: argparse.Namespace) -> int:
    from kinepoly.report import steps_text, table_text, to_json
    from kinepoly.scene.loader import load_scene
    from kinepoly.solution import solve

    t0 = time.perf_counter()
    scene = load_scene(args.scene)
    solution = solve(scene, load_s=time.perf_counter() - t0)
    if args.json:
        print(json.dumps(to_json(solution), indent=1, allow_nan=False))
    elif args.steps:
        print(steps_text(solution))
    else:
        print(table_text(solution))
    for notice in solution.notices:
        if notice.code == "check-failed":
            print(f"kinepoly: WARNING: {notice.message}", file=sys.stderr)
    return 0


def _draw(args: argparse.Namespace) -> int:
    from kinepoly.draw_command import run_draw

    for line in run_draw(args):
        print(line)
    return 0


def _bench(args: argparse.Namespace) -> int:
    from kinepoly.bench.command import run_bench_command

    for line in run_bench_command(args):
        print(line)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status."""
    try:
        args = _parser().parse_args(argv)
    except SystemExit as stop:
        return int(stop.code or 0)
    try:
        if args.command == "draw":
            return _draw(args)
        if args.command == "bench":
            return _bench(args)
        if args.command == "handout":
            from kinepoly.handout.command import run_handout

            for line in run_handout(args):
                print(line)
            return 0
        if args.command == "sweep":
            from kinepoly.sweep.command import run_command

            return run_command(args)
        if args.command in ("check", "variants"):
            from kinepoly.homework.arguments import run

            return run(args)
        return _solve(args)
    except KinepolyError as error:
        print(f"kinepoly: error: {error}", file=sys.stderr)
        return error.exit_code
    except BrokenPipeError:  # the reader (``| head``) left early: what it read is all it wanted
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    except Exception as error:  # noqa: BLE001 - the promise is: never a traceback
        print(f"kinepoly: internal error: {type(error).__name__}: {error}; please report it with the scene",
              file=sys.stderr)
        return EXIT_INTERNAL


def main_exit() -> None:
    """Console-script entry point."""
    sys.exit(main())
