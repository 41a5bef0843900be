"""``kinepoly variants SCENE --n 30 --seed 7 -o DIR``: randomised versions of a problem with their keys.

The homework package makes the variants (pure); this module reads the scene and its ``[vary]``
table, takes the ranges given on the command line, writes ``NAME.toml`` and
``NAME.answers.toml`` whole or not at all and prints what it wrote.
"""

from __future__ import annotations

import argparse
import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

from kinepoly.cli.files import emit, scene_file
from kinepoly.errors import EXIT_OK, SceneError

if TYPE_CHECKING:
    from kinepoly.homework.vary import Range
    from kinepoly.scene.spec import Scene

__all__ = ["add_arguments", "parse_range", "run", "run_variants"]

_RANGES = (
    ("lengths", "each link's dimensions times a factor in LO,HI (e.g. 0.9,1.1), drawn link by link"),
    ("angle", "a link input's angle range LO,HI in the scene's angle unit"),
    ("omega", "a link input's omega range LO,HI in rad/s"),
    ("alpha", "a link input's alpha range LO,HI in rad/s^2"),
    ("s", "a slider input's s range LO,HI in the scene's length unit"),
    ("s_dot", "a slider input's s_dot range LO,HI"),
    ("s_ddot", "a slider input's s_ddot range LO,HI"),
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
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
    """Run ``kinepoly variants``; the exit status."""
    options = {key: getattr(args, f"vary_{key}") for key, _ in _RANGES}
    return run_variants(args.scene, args.n, args.seed, args.output, options, args.min_transmission)


def parse_range(option: str, text: str) -> tuple[float, float]:
    """``LO,HI`` of a command-line option as two numbers, LO <= HI; SceneError (exit 2) otherwise."""
    parts = text.split(",")
    try:
        low, high = (float(part) for part in parts)
    except ValueError:
        raise SceneError([f"{option}: {text!r} is not a range; expected two numbers LO,HI like 20,160"]) from None
    if not (math.isfinite(low) and math.isfinite(high)) or low > high:
        raise SceneError([f"{option}: {text!r} is not a range; expected finite numbers LO,HI with LO <= HI"])
    return low, high


def run_variants(scene_path: str, count: int, seed: int, out_dir: str, options: dict[str, str | None],
                 min_transmission_deg: float = 30.0) -> int:
    """Make ``count`` variants with their keys in ``out_dir``; print what was written.

    ``options`` maps a [vary] key (``lengths``, ``angle``, ``omega``, ...) to its ``LO,HI`` text
    from the command line (None: not given); they override the scene's [vary] table.
    """
    if count < 1:
        raise SceneError([f"--n: {count} variants; expected at least 1"])
    if not 0.0 <= min_transmission_deg < 90.0:
        raise SceneError([f"--min-transmission: {min_transmission_deg:g}; expected degrees from 0 to below 90"])
    from kinepoly.homework.variants import GEARS_NOTE, make_variants
    from kinepoly.homework.vary import read_vary
    from kinepoly.scene.loader import parse_located

    scene, text = scene_file(scene_path)
    table, report = parse_located(text, scene_path)
    overrides = {key: _option_range(key, value, scene) for key, value in options.items() if value is not None}
    ranges = read_vary(report, table.get("vary"), scene, overrides)
    report.raise_if_any()
    variants = make_variants(scene, ranges, count, seed, stem=Path(scene_path).stem,
                             min_transmission_deg=min_transmission_deg)
    folder = Path(out_dir)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise SceneError([f"{out_dir}: (file): cannot make the folder ({exc.strerror}); expected a writable path"]) \
            from None
    for variant in variants:
        emit(variant.scene_text, os.fspath(folder / f"{variant.name}.toml"))
        emit(variant.answers_text, os.fspath(folder / f"{variant.name}.answers.toml"))
    print(f"{len(variants)} variants of {scene_path} (seed {seed}) in {out_dir}: NAME.toml and NAME.answers.toml")
    if scene.gears:
        print(f"  {GEARS_NOTE}")
    for variant in variants:
        shown = variant.min_transmission_deg
        angle = "-" if shown is None else f"{shown:.0f} deg"
        print(f"  {variant.name}  smallest transmission angle {angle}, {len(variant.answers)} answers")
    return EXIT_OK


def _option_range(key: str, text: str, scene: Scene) -> Range:
    from kinepoly.homework.vary import Range

    low, high = parse_range(f"--{key.replace('_', '-')}", text)
    if key == "lengths":
        if low <= 0:
            raise SceneError([f"--lengths: {text!r}; expected factors above 0 like 0.9,1.1"])
        return Range(low, high)
    if key == "angle" and scene.units.angle == "deg":
        low, high = math.radians(low), math.radians(high)
    return Range(low, high)
