"""Homework: check a student's answers against a scene, diagnose the mistakes, make problem variants.

::

    from kinepoly import load_scene
    from kinepoly.homework import check, load_answers, make_checker

    scene = load_scene("examples/slotted-lever.toml")
    answers = load_answers("ana.toml", scene)                 # FILE:LINE errors like a scene's
    result = check(answers, make_checker(scene, [answers]))   # verdicts, score, diagnoses
    [(v.key.text, v.is_correct, v.diagnosis and v.diagnosis.code) for v in result.verdicts]

The command line: ``kinepoly check SCENE ANSWERS [--json]`` and
``kinepoly variants SCENE --n 30 --seed 7 -o DIR [--quiz moodle|qti]`` (``kinepoly.cli.check``,
``kinepoly.cli.variants``: they read and write the files; everything here is pure). The names below are imported when
first used, so that importing one module of this package does not import them all.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from kinepoly.homework.answers import Answers, Tolerance, load_answers, loads_answers
    from kinepoly.homework.checking import Checker, CheckResult, Verdict, check, make_checker
    from kinepoly.homework.diagnose import Diagnosis
    from kinepoly.homework.report import class_csv, result_json, result_text
    from kinepoly.homework.variants import Variant, make_variants
    from kinepoly.homework.vary import Ranges, default_ranges, read_vary

_HOME = {
    "Answers": "answers", "Tolerance": "answers", "load_answers": "answers", "loads_answers": "answers",
    "CheckResult": "checking", "Checker": "checking", "Verdict": "checking", "check": "checking",
    "make_checker": "checking", "Diagnosis": "diagnose", "class_csv": "report", "result_json": "report",
    "result_text": "report",
    "Variant": "variants", "make_variants": "variants", "Ranges": "vary", "default_ranges": "vary",
    "read_vary": "vary",
}

__all__ = [
    "Answers",
    "CheckResult",
    "Checker",
    "Diagnosis",
    "Ranges",
    "Tolerance",
    "Variant",
    "Verdict",
    "check",
    "class_csv",
    "default_ranges",
    "load_answers",
    "loads_answers",
    "make_checker",
    "make_variants",
    "read_vary",
    "result_json",
    "result_text",
]


def __getattr__(name: str) -> Any:
    if name in _HOME:
        return getattr(importlib.import_module(f"kinepoly.homework.{_HOME[name]}"), name)
    raise AttributeError(f"module 'kinepoly.homework' has no attribute {name!r}")
