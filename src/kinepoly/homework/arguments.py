"""The command-line arguments of ``kinepoly check`` and ``kinepoly variants``.

Kept free of heavy imports: ``kinepoly solve`` builds this parser too. The work is done in
kinepoly.homework.commands, imported when one of these commands runs.
"""

from __future__ import annotations

import argparse

__all__ = ["add_check_arguments", "add_variants_arguments", "run"]

_RANGES = (
    ("lengths", "each link's dimensions times a factor in LO,HI (e.g. 0.9,1.1), drawn link by link"),
    ("angle", "a link input's angle range LO,HI in the scene's angle unit"),
    ("omega", "a link input's omega range LO,HI in rad/s"),
    ("alpha", "a link input's alpha range LO,HI in rad/s^2"),
    ("s", "a slider input's s range LO,HI in the scene's length unit"),
    ("s_dot", "a slider input's s_dot range LO,HI"),
    ("s_ddot", "a slider input's s_ddot range LO,HI"),
)


def add_check_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = ("Check a student's answers against the scene: a verdict per answer, and for a wrong "
                          "one the likely mistake. Exit 0 when every answer is correct, 1 otherwise, 2 for a bad "
                          "answers file. A folder of answers files gives a class report as CSV.")
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("answers", help="an answers file (TOML), or a folder of them for a class report")
    parser.add_argument("--json", action="store_true", help="print one JSON object instead of a table (or CSV)")
    parser.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of printing it")


def add_variants_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = ("Randomised versions of a problem, each assemblable in the original's assembly, every "
                          "transmission angle at least --min-transmission, each with its answer key. Ranges come "
                          "from the scene's [vary] table; the options below override it.")
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("--n", type=int, default=30, help="how many variants (default 30)")
    parser.add_argument("--seed", type=int, default=0, help="the random seed: the same seed, the same variants")
    parser.add_argument("-o", "--output", metavar="DIR", required=True,
                        help="the folder for NAME.toml and NAME.answers.toml")
    parser.add_argument("--min-transmission", type=float, default=30.0, metavar="DEG",
                        help="the least transmission angle of every dyad, in degrees (default 30)")
    for key, text in _RANGES:
        parser.add_argument(f"--{key.replace('_', '-')}", dest=f"vary_{key}", metavar="LO,HI", help=text)


def run(args: argparse.Namespace) -> int:
    """Run ``check`` or ``variants`` (``args.command``); the exit status."""
    from kinepoly.homework.commands import run_check, run_variants

    if args.command == "check":
        return run_check(args.scene, args.answers, as_json=args.json, output=args.output)
    options = {key: getattr(args, f"vary_{key}") for key, _ in _RANGES}
    return run_variants(args.scene, args.n, args.seed, args.output, options, args.min_transmission)
