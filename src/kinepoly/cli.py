"""The command line: the only place that prints. ``main(argv) -> int`` so tests call it in-process.

Exit status: 0 solved; 1 an answer was wrong (``check``); 2 the scene or the command is wrong;
3 the mechanism cannot be assembled or is singular at that input; 70 an internal error.
"""

from __future__ import annotations

import argparse
import json
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


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status."""
    try:
        args = _parser().parse_args(argv)
    except SystemExit as stop:
        return int(stop.code or 0)
    try:
        return _solve(args)
    except KinepolyError as error:
        print(f"kinepoly: error: {error}", file=sys.stderr)
        return error.exit_code
    except Exception as error:  # noqa: BLE001 - the promise is: never a traceback
        print(f"kinepoly: internal error: {type(error).__name__}: {error}; please report it with the scene",
              file=sys.stderr)
        return EXIT_INTERNAL


def main_exit() -> None:
    """Console-script entry point."""
    sys.exit(main())
