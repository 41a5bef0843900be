"""``kinepoly check SCENE ANSWERS [--json] [-o FILE]``: the files read, what is printed, what is written.

The homework package does the checking (pure); this module reads the files, prints the report
or writes it whole or not at all (``cli.files.emit``).

Exit status: 0 every answer correct; 1 some answer wrong or missing; 2 an answers file (or the
scene, or the command) is wrong; 3 the scene cannot be assembled. With a folder the class report
is printed (or written) first; the status is then 2 if any file could not be read.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from kinepoly.cli.files import PAPER_HELP, emit, output_path, paper_of, scene_file
from kinepoly.errors import EXIT_OK, EXIT_SCENE, EXIT_WRONG_ANSWERS, SceneError

if TYPE_CHECKING:
    from kinepoly.homework.answers import Answers
    from kinepoly.homework.checking import Checker, CheckResult
    from kinepoly.scene.spec import Scene

__all__ = ["add_arguments", "run", "run_check"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = ("Check a student's answers against the scene: a verdict per answer, and for a wrong "
                          "one the likely mistake. A folder of answers files gives a class report as CSV.\n\n"
                          "exit status: 0 every answer is correct; 1 an answer is wrong; 2 a bad scene, answers file "
                          "or command; 3 the mechanism cannot be assembled or is singular at the scene's input")
    parser.add_argument("scene", help="the scene file (TOML)")
    parser.add_argument("answers", help="an answers file (TOML), or a folder of them for a class report")
    parser.add_argument("--json", action="store_true", help="print one JSON object instead of a table (or CSV)")
    parser.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE instead of printing it")
    parser.add_argument("--paper", default="A4", help="the paper the students drew on (kinepoly draw's or handout's): "
                        "its kv and ka are those a polygon length not divided by them is recognised with; "
                        + PAPER_HELP)


def run(args: argparse.Namespace) -> int:
    """Run ``kinepoly check``; the exit status."""
    return run_check(args.scene, args.answers, as_json=args.json, output=args.output, paper=paper_of(args.paper))


def _warn(checker: Checker) -> None:
    for message in checker.reference.warnings:
        print(f"kinepoly: WARNING: the answers are checked against a solution that fails kinepoly's own "
              f"cross-check: {message}", file=sys.stderr)


def _answer_files(folder: Path) -> list[Path]:
    files = sorted(p for p in folder.iterdir() if p.suffix == ".toml" and p.is_file())
    if not files:
        raise SceneError([f"{folder}: (file): no .toml answers files in this folder; expected one file per student"])
    return files


def run_check(scene_path: str, answers_path: str, *, as_json: bool = False, output: str | None = None,
              paper: tuple[float, float] | None = None) -> int:
    """Check one answers file (a table, or JSON) or a folder of them (a class report as CSV, or JSON).

    ``paper`` (width, height in mm) is the drawing's: its kv and ka are those the diagnoses use (A4 when None).
    """
    from kinepoly.homework.answers import load_answers
    from kinepoly.homework.checking import check, make_checker
    from kinepoly.homework.report import result_json, result_text
    from kinepoly.present.scales import A4

    drawn = A4 if paper is None else paper

    if output is not None:
        folder = Path(answers_path)
        read = [scene_path, *(map(str, folder.iterdir()) if folder.is_dir() else [answers_path])]
        output_path(output, "-o", read)
    scene, text = scene_file(scene_path)
    if not Path(answers_path).is_dir():
        answers = load_answers(answers_path, scene)
        checker = make_checker(scene, [answers], text, drawn)
        _warn(checker)
        result = check(answers, checker)
        emit(json.dumps(result_json(result, scene), indent=1, allow_nan=False) if as_json
             else result_text(result, scene), output)
        return EXIT_OK if result.is_all_correct else EXIT_WRONG_ANSWERS
    return _check_class(scene, text, Path(answers_path), as_json=as_json, output=output, paper=drawn)


def _check_class(scene: Scene, text: str, folder: Path, *, as_json: bool, output: str | None,
                 paper: tuple[float, float]) -> int:
    from kinepoly.homework.answers import Answers, load_answers
    from kinepoly.homework.checking import CheckResult, check, make_checker
    from kinepoly.homework.report import class_csv, result_json

    loaded: list[tuple[str, Answers | list[str]]] = []
    for path in _answer_files(folder):
        try:
            loaded.append((path.name, load_answers(path, scene)))
        except SceneError as error:
            loaded.append((path.name, error.problems))
    checker = make_checker(scene, [a for _, a in loaded if isinstance(a, Answers)], text, paper)
    _warn(checker)
    rows: list[tuple[str, CheckResult | Sequence[str]]] = []
    for name, answers in loaded:
        if isinstance(answers, Answers):
            try:
                rows.append((name, check(answers, checker)))
            except SceneError as error:
                rows.append((name, error.problems))
        else:
            rows.append((name, answers))
    if as_json:
        files = {name: result_json(r, scene) if isinstance(r, CheckResult) else {"problems": list(r)}
                 for name, r in rows}
        emit(json.dumps({"scene": scene.source, "files": files}, indent=1, allow_nan=False), output)
    else:
        emit(class_csv(rows), output)
    bad = [problem for _, r in rows if not isinstance(r, CheckResult) for problem in r]
    for problem in bad:
        print(f"kinepoly: error: {problem}", file=sys.stderr)
    if bad:
        return EXIT_SCENE
    return EXIT_OK if all(isinstance(r, CheckResult) and r.is_all_correct for _, r in rows) else EXIT_WRONG_ANSWERS
