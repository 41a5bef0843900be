"""A quiz as a QTI package for Canvas, written by text2qti (a maintained writer of Canvas QTI, BSD-3-Clause).

kinepoly writes the quiz in text2qti's plain-text format and text2qti makes the package
(``imsmanifest.xml``, the assessment's XML, the figures under ``images/``); its own checks run as it
reads the text. What text2qti can say shapes the package:

* it has no question with several numerical blanks, so a variant is a text region (the problem
  page's text and figure) followed by one numerical question per number asked, each titled with
  the variant and the seed, and its text naming the variant;
* a numerical question has one range of right answers and no answers of its own for the wrong
  ones, so the typical mistakes cannot each have their feedback: the incorrect-answer feedback lists
  every typical mistake's number with the mistake's name, so that a student finds theirs;
* it writes a range's ends to four decimals: a number of several significant digits stays exact
  enough, but the quantities should be asked in units where they are not tiny (mm, not m).

text2qti is an optional dependency (``pip install 'kinepoly[quiz]'``); without it this module says so.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

from kinepoly.errors import OutputError
from kinepoly.homework.quiz import Quantity, Question, Quiz
from kinepoly.present.catalogue import Catalogue

__all__ = ["TEXT2QTI_MISSING", "qti_package", "quiz_text", "text2qti_module"]

TEXT2QTI_MISSING = ("--quiz qti writes Canvas's QTI package with the Python package text2qti, which is not installed; "
                    "install it with: pip install 'kinepoly[quiz]' (or pip install text2qti), or write "
                    "--quiz moodle instead")
_SMALLEST = 1e-4
"""text2qti refuses a range whose end is nearer zero than this."""


def text2qti_module() -> Any:
    """text2qti's modules (``quiz``, ``qti``, ``config``, ``err``); OutputError (exit 2) saying how to install it."""
    try:
        import text2qti.config
        import text2qti.err
        import text2qti.qti
        import text2qti.quiz
    except ImportError:
        raise OutputError(TEXT2QTI_MISSING) from None
    return text2qti


def _one_line(text: str) -> str:
    return " ".join(text.split())


def _range(quantity: Quantity) -> str:
    low, high = quantity.value - quantity.tolerance, quantity.value + quantity.tolerance
    if abs(low) < _SMALLEST:
        low = -_SMALLEST if low <= 0.0 else _SMALLEST
    if abs(high) < _SMALLEST:
        high = _SMALLEST if high >= 0.0 else -_SMALLEST
    return f"[{low!r}, {high!r}]"


def _numerical(number: int, question: Question, quantity: Quantity, say: Catalogue) -> list[str]:
    from kinepoly.handout.notation import html_of

    items = [say.say("quiz.mistake_item", value=say.number(w.value), mistake=w.words) for w in quantity.wrong]
    wrong = say.say("quiz.mistakes", items="; ".join(items)) if items else say.say("quiz.wrong")
    return [f"Title: {question.title}: {quantity.key}{'' if quantity.part == 'value' else ' ' + quantity.part}",
            "Points: 1",
            f"{number}.  {question.name}: {_one_line(html_of(quantity.label))}",
            f"+   {_one_line(say.say('quiz.right'))}",
            f"-   {_one_line(wrong)}",
            f"=   {_range(quantity)}", ""]


def quiz_text(quiz: Quiz, say: Catalogue, figures: dict[str, Path]) -> str:
    """The quiz in text2qti's format; ``figures`` the files the figures were written to, by name."""
    lines = [f"Quiz title: {_one_line(quiz.title)}", ""]
    number = 0
    for question in quiz.questions:
        lines += [f"Text title: {_one_line(question.title)}",
                  f"Text: {_one_line(question.statement)}", "",
                  f"      ![{_one_line(say.say('quiz.figure'))}]({figures[question.figure_name].as_posix()})", ""]
        for quantity in question.quantities:
            number += 1
            lines += _numerical(number, question, quantity, say)
    return "\n".join(lines) + "\n"


def qti_package(quiz: Quiz, say: Catalogue) -> bytes:
    """The QTI package (a zip) that Canvas imports (Settings, Import Course Content, QTI .zip file)."""
    text2qti = text2qti_module()
    with tempfile.TemporaryDirectory(prefix="kinepoly-qti-") as folder:
        figures = {}
        for question in quiz.questions:
            path = Path(folder) / question.figure_name
            path.write_bytes(question.figure)
            figures[question.figure_name] = path
        text = quiz_text(quiz, say, figures)
        try:
            parsed = text2qti.quiz.Quiz(text, config=text2qti.config.Config(), source_name=f"{quiz.category}.qti.txt")
            package: bytes = text2qti.qti.QTI(parsed).zip_bytes()
        except text2qti.err.Text2qtiError as error:  # pragma: no cover - kinepoly's own text, checked by the tests
            raise OutputError(f"text2qti refused the quiz: {error}") from None
    return package
