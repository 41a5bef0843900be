"""``kinepoly variants SCENE --n 30 --seed 7 -o DIR``: randomised versions of a problem with their keys.

The homework package makes the variants (pure); this module reads the scene and its ``[vary]``
table, takes the ranges given on the command line, writes ``NAME.toml`` and
``NAME.answers.toml`` whole or not at all and prints what it wrote. With ``--quiz moodle`` (``qti``)
it writes beside them ``STEM.moodle.xml`` (``STEM.qti.zip``), a question per variant
(``homework.quiz``), made in memory before any file is written.
"""

from __future__ import annotations

import argparse
import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

from kinepoly.atomic import write_bytes
from kinepoly.cli.files import emit, scene_file
from kinepoly.errors import EXIT_OK, OutputError, SceneError

if TYPE_CHECKING:
    from kinepoly.homework.quiz import Quiz, QuizTolerance
    from kinepoly.homework.variants import Variant
    from kinepoly.homework.vary import Range
    from kinepoly.present.catalogue import Catalogue
    from kinepoly.scene.spec import Scene

__all__ = ["QUIZ_KINDS", "add_arguments", "parse_range", "run", "run_variants"]

QUIZ_KINDS = {"moodle": "moodle.xml", "qti": "qti.zip"}
"""What ``--quiz`` writes: the file's ending beside the variants (``STEM.moodle.xml``, ``STEM.qti.zip``)."""

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
                        help="the folder for NAME.toml and NAME.answers.toml (and --quiz's file)")
    parser.add_argument("--min-transmission", type=float, default=30.0, metavar="DEG",
                        help="the least transmission angle of every dyad, in degrees (default 30)")
    for key, text in _RANGES:
        parser.add_argument(f"--{key.replace('_', '-')}", dest=f"vary_{key}", metavar="LO,HI", help=text)
    parser.add_argument("--quiz", choices=tuple(QUIZ_KINDS), help=(
        "also write the variants as a quiz a learning platform imports, a question per variant with the typical "
        "mistakes' numbers as wrong answers: moodle (STEM.moodle.xml, Moodle XML) or qti (STEM.qti.zip, Canvas; "
        "needs pip install 'kinepoly[quiz]')"))
    parser.add_argument("--tolerance", default="2%", metavar="TOL", help=(
        "the quiz's tolerance: a percentage of each value like 2%%, or the length a hand construction holds on the "
        "paper at the drawn scales like 0.5mm (default 2%%)"))
    parser.add_argument("--lang", default="en", help="the quiz's language: en, tr or ro (default en)")


def run(args: argparse.Namespace) -> int:
    """Run ``kinepoly variants``; the exit status."""
    options = {key: getattr(args, f"vary_{key}") for key, _ in _RANGES}
    return run_variants(args.scene, args.n, args.seed, args.output, options, args.min_transmission,
                        quiz=args.quiz, tolerance=args.tolerance, lang=args.lang)


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
                 min_transmission_deg: float = 30.0, *, quiz: str | None = None, tolerance: str = "2%",
                 lang: str = "en") -> int:
    """Make ``count`` variants with their keys in ``out_dir``; print what was written.

    ``options`` maps a [vary] key (``lengths``, ``angle``, ``omega``, ...) to its ``LO,HI`` text
    from the command line (None: not given); they override the scene's [vary] table. ``quiz``
    (``moodle`` or ``qti``) also writes the quiz, at ``tolerance`` (``2%``, ``0.5mm``), in ``lang``.
    """
    if count < 1:
        raise SceneError([f"--n: {count} variants; expected at least 1"])
    if not 0.0 <= min_transmission_deg < 90.0:
        raise SceneError([f"--min-transmission: {min_transmission_deg:g}; expected degrees from 0 to below 90"])
    asked = _quiz_options(quiz, tolerance, lang)  # every option checked before the variants are made
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
    made = None if asked is None else _made_quiz(variants, Path(scene_path).stem, seed, *asked)
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
    if made is not None and asked is not None:
        content, questions = made
        _write_quiz(folder / f"{questions.category}.{QUIZ_KINDS[asked[0]]}", content, questions, asked[1].text)
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


def _quiz_options(kind: str | None, tolerance: str, lang: str) -> tuple[str, QuizTolerance, Catalogue] | None:
    """The quiz asked for, its tolerance and catalogue; exit 2 for a bad one, or for qti without text2qti."""
    if kind is None:
        return None
    if kind not in QUIZ_KINDS:  # argparse's choices say it on the command line; this, from Python
        raise OutputError(f"--quiz {kind}: not a kind of quiz; expected one of {', '.join(QUIZ_KINDS)}")
    from kinepoly.homework.quiz import parse_tolerance
    from kinepoly.present.catalogue import load_catalogue

    parsed = parse_tolerance(tolerance)
    say = load_catalogue(lang)
    if kind == "qti":
        from kinepoly.homework.canvas import text2qti_module

        text2qti_module()
    return kind, parsed, say


def _made_quiz(variants: list[Variant], stem: str, seed: int, kind: str, tolerance: QuizTolerance,
               say: Catalogue) -> tuple[bytes, Quiz]:
    """The quiz and its file's bytes, made before any file is written."""
    from kinepoly.homework.quiz import make_quiz

    quiz = make_quiz(variants, stem, seed, tolerance, say)
    if kind == "moodle":
        from kinepoly.homework.moodle import moodle_xml

        return moodle_xml(quiz, say), quiz
    from kinepoly.homework.canvas import qti_package

    return qti_package(quiz, say), quiz


def _write_quiz(path: Path, content: bytes, quiz: Quiz, tolerance: str) -> None:
    write_bytes(path, content)
    count = sum(len(q.quantities) for q in quiz.questions)
    print(f"quiz {path}: {len(quiz.questions)} questions, {count} numbers, tolerance {tolerance}, "
          f"language {quiz.language}, question bank category {quiz.category}")
    for question in quiz.questions:
        for quantity in question.quantities:
            name = quantity.key if quantity.part == "value" else f"{quantity.key} {quantity.part}"
            codes = ", ".join(dict.fromkeys(w.code for w in quantity.wrong)) or "none"
            left = "; ".join(f"{o.code} (= {'the right value' if o.with_ == 'right' else o.with_})"
                             for o in quantity.omitted)
            print(f"  {question.name} {name}: mistakes {codes}" + (f"; left out, within the tolerance: {left}"
                                                                    if left else ""))
