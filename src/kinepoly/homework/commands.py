"""``kinepoly check`` and ``kinepoly variants``: the files read, what is printed, what is written.

The edge of the homework package: everything else in it is pure. Output files are written
whole or not at all (kinepoly.render.output.write_atomically).

Exit status of ``check``: 0 every answer correct; 1 some answer wrong or missing; 2 an answers
file (or the scene, or the command) is wrong; 3 the scene cannot be assembled. With a folder the
class report is printed (or written) first; the status is then 2 if any file could not be read.
"""

from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import IO, Any

from kinepoly.errors import EXIT_OK, EXIT_SCENE, EXIT_WRONG_ANSWERS, SceneError
from kinepoly.homework.answers import Answers, load_answers
from kinepoly.homework.checking import Checker, CheckResult, check, make_checker
from kinepoly.homework.report import class_csv, result_json, result_text
from kinepoly.homework.variants import DEFAULT_MIN_TRANSMISSION_DEG, make_variants
from kinepoly.homework.vary import Range, read_vary
from kinepoly.render.output import write_atomically
from kinepoly.scene.loader import load_scene, parse_located
from kinepoly.scene.spec import Scene

__all__ = ["parse_range", "run_check", "run_variants"]


def _write(stream: IO[Any], text: str) -> None:
    stream.write(text)


def _emit(text: str, output: str | None) -> None:
    if output is None:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
        return
    try:
        write_atomically(output, lambda stream: _write(stream, text), binary=False)
    except OSError as exc:
        problem = (f"{output}: (file): cannot be written ({exc.strerror}); expected a path in a folder that "
                   "exists and can be written")
        raise SceneError([problem]) from None


def _scene_file(path: str) -> tuple[Scene, str]:
    """The scene and its text (for [vary] and an input given as "300 rpm")."""
    scene = load_scene(path)
    return scene, Path(path).read_text(encoding="utf-8")


def _warn(checker: Checker) -> None:
    for message in checker.reference.warnings:
        print(f"kinepoly: WARNING: the answers are checked against a solution that fails kinepoly's own "
              f"cross-check: {message}", file=sys.stderr)


def _answer_files(folder: Path) -> list[Path]:
    files = sorted(p for p in folder.iterdir() if p.suffix == ".toml" and p.is_file())
    if not files:
        raise SceneError([f"{folder}: (file): no .toml answers files in this folder; expected one file per student"])
    return files


def run_check(scene_path: str, answers_path: str, *, as_json: bool = False, output: str | None = None) -> int:
    """Check one answers file (a table, or JSON) or a folder of them (a class report as CSV, or JSON)."""
    scene, text = _scene_file(scene_path)
    if not Path(answers_path).is_dir():
        answers = load_answers(answers_path, scene)
        checker = make_checker(scene, [answers], text)
        _warn(checker)
        result = check(answers, checker)
        _emit(json.dumps(result_json(result, scene), indent=1, allow_nan=False) if as_json
              else result_text(result, scene), output)
        return EXIT_OK if result.is_all_correct else EXIT_WRONG_ANSWERS
    return _check_class(scene, text, Path(answers_path), as_json=as_json, output=output)


def _check_class(scene: Scene, text: str, folder: Path, *, as_json: bool, output: str | None) -> int:
    loaded: list[tuple[str, Answers | list[str]]] = []
    for path in _answer_files(folder):
        try:
            loaded.append((path.name, load_answers(path, scene)))
        except SceneError as error:
            loaded.append((path.name, error.problems))
    checker = make_checker(scene, [a for _, a in loaded if isinstance(a, Answers)], text)
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
        _emit(json.dumps({"scene": scene.source, "files": files}, indent=1, allow_nan=False), output)
    else:
        _emit(class_csv(rows), output)
    bad = [problem for _, r in rows if not isinstance(r, CheckResult) for problem in r]
    for problem in bad:
        print(f"kinepoly: error: {problem}", file=sys.stderr)
    if bad:
        return EXIT_SCENE
    return EXIT_OK if all(isinstance(r, CheckResult) and r.is_all_correct for _, r in rows) else EXIT_WRONG_ANSWERS


# --------------------------------------------------------------------------------------------
# variants


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
                 min_transmission_deg: float = DEFAULT_MIN_TRANSMISSION_DEG) -> int:
    """Make ``count`` variants with their keys in ``out_dir``; print what was written.

    ``options`` maps a [vary] key (``lengths``, ``angle``, ``omega``, ...) to its ``LO,HI`` text
    from the command line (None: not given); they override the scene's [vary] table.
    """
    if count < 1:
        raise SceneError([f"--n: {count} variants; expected at least 1"])
    if not 0.0 <= min_transmission_deg < 90.0:
        raise SceneError([f"--min-transmission: {min_transmission_deg:g}; expected degrees from 0 to below 90"])
    scene, text = _scene_file(scene_path)
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
        _emit(variant.scene_text, os.fspath(folder / f"{variant.name}.toml"))
        _emit(variant.answers_text, os.fspath(folder / f"{variant.name}.answers.toml"))
    print(f"{len(variants)} variants of {scene_path} (seed {seed}) in {out_dir}: NAME.toml and NAME.answers.toml")
    for variant in variants:
        shown = variant.min_transmission_deg
        angle = "-" if shown is None else f"{shown:.0f} deg"
        print(f"  {variant.name}  smallest transmission angle {angle}, {len(variant.answers)} answers")
    return EXIT_OK


def _option_range(key: str, text: str, scene: Scene) -> Range:
    low, high = parse_range(f"--{key.replace('_', '-')}", text)
    if key == "lengths":
        if low <= 0:
            raise SceneError([f"--lengths: {text!r}; expected factors above 0 like 0.9,1.1"])
        return Range(low, high)
    if key == "angle" and scene.units.angle == "deg":
        low, high = math.radians(low), math.radians(high)
    return Range(low, high)
