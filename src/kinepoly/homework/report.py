"""What ``kinepoly check`` prints: the JSON object, a readable table, the class report CSV. Pure functions.

Values are shown in the scene's units: lengths as the scene's, a link's angle in the scene's
angle unit, omega in rad/s and alpha in rad/s^2 (ccw positive).
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Sequence
from typing import Any

from kinepoly.homework.answers import AnswerKey, Direction, Value
from kinepoly.homework.checking import CheckResult, Verdict
from kinepoly.scene.spec import Scene

__all__ = ["class_csv", "result_json", "result_text", "shown_value"]


def _number(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def shown_value(key: AnswerKey, value: Value | None, scene: Scene) -> Any:
    """A value as the JSON shows it: a number, [x, y], or {"direction": [x, y]}; theta in the scene's unit."""
    if value is None:
        return None
    if isinstance(value, Direction):
        return {"direction": [value.x, value.y]}
    if isinstance(value, tuple):
        return [value[0], value[1]]
    if key.kind == "theta" and scene.units.angle == "deg":
        return math.degrees(value)
    return value


def _verdict_json(verdict: Verdict, scene: Scene) -> dict[str, Any]:
    diagnosis = verdict.diagnosis
    return {
        "verdict": "correct" if verdict.is_correct else "wrong",
        "expected": shown_value(verdict.key, verdict.expected, scene),
        "given": shown_value(verdict.key, verdict.given, scene),
        "error": None if verdict.comparison is None else {k: _number(v) for k, v in verdict.comparison.error.items()},
        "diagnosis": None if diagnosis is None else {
            "code": diagnosis.code,
            "text": diagnosis.text,
            "value": shown_value(verdict.key, diagnosis.value, scene),
            "alternatives": list(diagnosis.alternatives),
        },
    }


def result_json(result: CheckResult, scene: Scene) -> dict[str, Any]:
    """``{"score": 0..1, "answers": {KEY: {"verdict", "expected", "given", "error", "diagnosis"}}}`` and context."""
    return {
        "scene": scene.source,
        "title": scene.title,
        "answers_file": result.source,
        "student": result.student,
        "units": {"length": scene.units.length, "angle": scene.units.angle},
        "tolerance": {"relative": result.tolerance.relative, "angle_deg": result.tolerance.angle_deg},
        "score": result.score,
        "correct": result.correct,
        "total": len(result.verdicts),
        "answers": {verdict.key.text: _verdict_json(verdict, scene) for verdict in result.verdicts},
    }


# --------------------------------------------------------------------------------------------
# Text


def _g(x: float) -> str:
    return f"{x:.4g}"


def _text(key: AnswerKey, value: Value | None, scene: Scene) -> str:
    if value is None:
        return "-"
    if isinstance(value, Direction):
        return f"at infinity, direction ({_g(value.x)}, {_g(value.y)})"
    if isinstance(value, tuple):
        return f"({_g(value[0])}, {_g(value[1])})"
    if key.kind in ("omega", "alpha") and value != 0.0:
        return f"{_g(value)} ({_g(abs(value))} {'ccw' if value > 0 else 'cw'})"
    if key.kind == "theta":
        return f"{_g(math.degrees(value))} deg" if scene.units.angle == "deg" else f"{_g(value)} rad"
    return _g(value)


def _error_text(verdict: Verdict) -> str:
    if verdict.comparison is None:
        return "-"
    error = verdict.comparison.error
    parts = []
    if "relative" in error:
        parts.append(f"{100 * error['relative']:.3g} %" if math.isfinite(error["relative"]) else "-")
    if "angle_deg" in error:
        parts.append(f"{error['angle_deg']:.3g} deg")
    return ", ".join(parts) or "-"


def _rows(header: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(row[c]) for row in [header, *rows]) for c in range(len(header))]
    return ["  ".join(value.ljust(width) for value, width in zip(row, widths, strict=True)).rstrip()
            for row in [header, ["-" * w for w in widths], *rows]]


def result_text(result: CheckResult, scene: Scene) -> str:
    """A table of the verdicts and, below it, the diagnosis of every wrong answer."""
    who = f" ({result.student})" if result.student else ""
    tol = result.tolerance
    summary = (f"{result.correct} of {len(result.verdicts)} correct, score {result.score:.2f} "
               f"(tolerance {100 * tol.relative:g} %, {tol.angle_deg:g} deg)")
    out = [f"{scene.title}: {result.source}{who}", summary, ""]
    rows = [[v.key.text, "correct" if v.is_correct else "missing" if v.given is None else "wrong",
             _text(v.key, v.expected, scene),
             _text(v.key, v.given, scene), _error_text(v)] for v in result.verdicts]
    out += _rows(["key", "verdict", "expected", "given", "error"], rows)
    wrong = [v for v in result.verdicts if v.diagnosis is not None]
    if wrong:
        out.append("")
    for verdict in wrong:
        diagnosis = verdict.diagnosis
        assert diagnosis is not None
        line = f"{verdict.key.text}: {diagnosis.text}"
        if diagnosis.value is not None:
            line += f" [{diagnosis.code}: that gives {_text(verdict.key, diagnosis.value, scene)}]"
        else:
            line += f" [{diagnosis.code}]"
        if diagnosis.alternatives:
            line += f"; it also fits: {', '.join(diagnosis.alternatives)}"
        out.append(line)
    return "\n".join(out)


# --------------------------------------------------------------------------------------------
# The class report


def _cell(verdict: Verdict | None) -> str:
    if verdict is None:
        return ""
    if verdict.is_correct:
        return "correct"
    assert verdict.diagnosis is not None
    if verdict.diagnosis.code == "not-answered":
        return "missing"
    return f"wrong: {verdict.diagnosis.code}"


def class_csv(rows: Sequence[tuple[str, CheckResult | Sequence[str]]]) -> str:
    """One row per answers file: file, student, score, correct, total, a cell per question, problems.

    A cell reads ``correct``, ``wrong: CODE`` (the diagnosis code), ``missing`` (asked by the
    scene's [find], not answered) or is empty (not asked and not answered). A file that could
    not be read has its problems in the last column and no score.
    """
    questions: dict[tuple[str, str | frozenset[str]], str] = {}
    for _, result in rows:
        if isinstance(result, CheckResult):
            for verdict in result.verdicts:
                questions.setdefault(verdict.key.question, verdict.key.text)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["file", "student", "score", "correct", "total", *questions.values(), "problems"])
    for name, result in rows:
        if not isinstance(result, CheckResult):
            writer.writerow([name, "", "", "", "", *([""] * len(questions)), " | ".join(result)])
            continue
        by_question = {verdict.key.question: verdict for verdict in result.verdicts}
        writer.writerow([name, result.student or "", f"{result.score:.3f}", result.correct, len(result.verdicts),
                         *(_cell(by_question.get(question)) for question in questions), ""])
    return buffer.getvalue()
