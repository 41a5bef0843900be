"""``kinepoly solve SCENE [--json | --steps] [--paper A4] [--method polygons|loops]``: a readable table, the JSON
of the contract, or the steps.

``--method loops`` takes every rate from the loop-closure equations (``kinepoly.loops``) in place of the
polygons: the table and the JSON carry its values (the JSON a ``loops`` list too) and ``--steps`` prints
the derivation after the construction. A scene the loop method does not cover (gears, cams) exits 2.

The text comes from ``kinepoly.present.report``; a failed cross-check is also a warning on
standard error (the exit status stays 0: the construction's numbers are printed). The polygon
scales are those of ``kinepoly draw`` and ``kinepoly handout`` on the same ``--paper``.
"""

from __future__ import annotations

import argparse
import sys
import time

from kinepoly.cli.files import PAPER_HELP, paper_of

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("--json", action="store_true", help="print the result as one JSON object")
    parser.add_argument("--steps", action="store_true", help="print the construction step by step")
    parser.add_argument("--paper", default="A4", help="the paper of the drawing whose polygon scales kv and ka are "
                        "reported (as kinepoly draw and handout use them): " + PAPER_HELP)
    parser.add_argument("--method", choices=("polygons", "loops"), default="polygons",
                        help="where the printed rates come from: the velocity and acceleration polygons (default), "
                        "or the loop-closure equations in complex numbers, solved by Cramer's rule "
                        "(--steps prints their derivation; gears and cams are not covered: exit 2)")


def run(args: argparse.Namespace) -> int:
    """Load, solve, print; the exit status."""
    from kinepoly.present.report import solved, steps_text, table_text
    from kinepoly.present.scales import decide_scales
    from kinepoly.scene.loader import load_scene
    from kinepoly.solution import solve

    paper = paper_of(args.paper)
    t0 = time.perf_counter()
    scene = load_scene(args.scene)
    if args.json and args.method == "polygons":
        solution, result = solved(scene, paper, time.perf_counter() - t0)
    else:  # the table and the steps are made from the solution; the loop method makes its own JSON below
        solution, result = solve(scene, load_s=time.perf_counter() - t0), {}
    derivation: list[str] = []
    if args.method == "loops":
        from kinepoly.loops import loop_method_solution, loops_json
        from kinepoly.loops.text import derivation_lines
        from kinepoly.present.report import to_json

        solution, loops = loop_method_solution(solution)
        derivation = derivation_lines(loops)
        result = to_json(solution, decide_scales(solution, paper))
        result["method"] = "loops"
        result["loops"] = loops_json(loops)
    scales = decide_scales(solution, paper)
    if args.json:
        import json

        print(json.dumps(result, indent=1, allow_nan=False))
    elif args.steps:
        print(steps_text(solution, scales) if not derivation else "\n".join(derivation))
    else:
        print(table_text(solution, scales))
    for notice in solution.notices:
        if notice.code == "check-failed":
            print(f"kinepoly: WARNING: {notice.message}", file=sys.stderr)
    return 0
