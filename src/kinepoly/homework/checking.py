"""Checking answers against a scene: one verdict per question, with a diagnosis for each wrong answer.

The questions are the keys the file answers plus, when the scene has a ``[find]``, every key that
``[find]`` asks for (an unanswered one is wrong, with the diagnosis ``not-answered``). The scene is
solved and recomputed with each mistake once (a :class:`Checker`), so a whole class costs about as
much as one student.
"""

from __future__ import annotations

import tomllib
from collections.abc import Iterable

from msgspec import Struct

from kinepoly.errors import SceneError
from kinepoly.homework.answers import Answer, AnswerKey, Answers, Tolerance, Value
from kinepoly.homework.compare import Comparison, compare
from kinepoly.homework.diagnose import Diagnosis, Recomputed, diagnose, recompute
from kinepoly.homework.reference import Reference, prepare
from kinepoly.present.scales import A4
from kinepoly.scene.spec import Scene

__all__ = ["CheckResult", "Checker", "Verdict", "check", "make_checker"]


class Verdict(Struct, frozen=True):
    """One question: the expected value, the given one (None: not answered), how they compare, why wrong."""

    key: AnswerKey
    expected: Value
    given: Value | None
    comparison: Comparison | None
    diagnosis: Diagnosis | None
    line: int = 0

    @property
    def is_correct(self) -> bool:
        return self.comparison is not None and self.comparison.is_correct


class CheckResult(Struct, frozen=True):
    """One answers file checked: a verdict per question, in the order of the scene's [find], then the
    answers to questions it does not ask, in file order."""

    source: str
    student: str | None
    tolerance: Tolerance
    verdicts: tuple[Verdict, ...]

    @property
    def correct(self) -> int:
        return sum(verdict.is_correct for verdict in self.verdicts)

    @property
    def score(self) -> float:
        return self.correct / len(self.verdicts) if self.verdicts else 0.0

    @property
    def is_all_correct(self) -> bool:
        return all(verdict.is_correct for verdict in self.verdicts)


class Checker(Struct, frozen=True):
    """A scene solved for the questions, and recomputed with every whole-problem mistake."""

    reference: Reference
    recomputed: tuple[Recomputed, ...]


def make_checker(scene: Scene, answer_files: Iterable[Answers] = (), scene_text: str | None = None,
                 paper: tuple[float, float] = A4) -> Checker:
    """Solve ``scene`` for its [find] and every key the answer files answer; raises KinepolyError as ``solve``.

    ``scene_text`` is the scene's TOML as written: with it an input omega written as "300 rpm"
    or "573 deg/s" is also tried as 300 (573) rad/s. ``paper`` is the drawing's and the handout's
    (width, height in mm): a polygon length read off them and not divided by their kv or ka is diagnosed.
    """
    keys = dict.fromkeys(answer.key for answers in answer_files for answer in answers.answers)
    reference = prepare(scene, keys, paper)
    written = tomllib.loads(scene_text).get("input") if scene_text is not None else None
    return Checker(reference, recompute(reference, written if isinstance(written, dict) else None))


def _unavailable(answers: Answers, checker: Checker) -> list[str]:
    problems = []
    for answer in answers.answers:
        if checker.reference.expected(answer.key) is not None:
            continue
        where = f"{answers.source}:{answer.line}" if answer.line else answers.source
        if answer.key.kind == "center" and not checker.reference.has_centers:
            why = ("this kinepoly does not compute instant centers yet (kinepoly solve --json has no "
                   "instant_centers); expected no I_ answers until it does, or check them by hand")
        else:
            why = "kinepoly cannot compute this for the scene; expected a question the scene can answer"
        problems.append(f"{where}: {answer.key.text}: {why}")
    return problems


def _verdict(answer: Answer, checker: Checker, tolerance: Tolerance) -> Verdict:
    reference = checker.reference
    expected = reference.expected(answer.key)
    assert expected is not None
    comparison = compare(answer.key.kind, expected, answer.value, tolerance, reference.floor(answer.key))
    diagnosis = None
    if not comparison.is_correct:
        diagnosis = diagnose(reference, checker.recomputed, answer.key, answer.value, tolerance)
    return Verdict(answer.key, expected, answer.value, comparison, diagnosis, answer.line)


def check(answers: Answers, checker: Checker) -> CheckResult:
    """Judge every answer and every unanswered question of the scene's [find].

    Raises SceneError (exit 2) naming the file and line of an answer that cannot be checked
    (an instant center while this kinepoly computes none).
    """
    problems = _unavailable(answers, checker)
    if problems:
        raise SceneError(problems)
    given = {answer.key.question: _verdict(answer, checker, answers.tolerance) for answer in answers.answers}
    verdicts = []
    for key in checker.reference.asked:
        if key.question in given:
            verdicts.append(given.pop(key.question))
            continue
        expected = checker.reference.expected(key)
        assert expected is not None
        verdicts.append(Verdict(key, expected, None, None,
                                Diagnosis("not-answered", "not answered; the scene's [find] asks for it")))
    return CheckResult(answers.source, answers.student, answers.tolerance, (*verdicts, *given.values()))
