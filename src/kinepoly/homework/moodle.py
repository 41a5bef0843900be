"""A quiz as Moodle XML: a question bank category for the scene, an embedded-answers (cloze) question per variant.

Each question's text is the problem page's HTML, the figure (a PNG carried in the XML as base64,
``@@PLUGINFILE@@``), then one NUMERICAL blank per number asked::

    {1:NUMERICAL:=23.8:0.476#Right.~%0%12.1:0.476#Not right: ... the Coriolis term ... left out}

The right number comes first: Moodle grades a response by the first answer whose tolerance holds
it, so a mistake's range never takes a right answer. A direction near ±180 degrees is right on
both sides (a second full-mark answer 360 degrees away). The XML is written with ``xml.etree``;
the embedded-answers syntax, which is Moodle's own text inside the question, is escaped as its
documentation says (backslash before ``} # ~ / " \\``).
"""

from __future__ import annotations

import base64
import html
import io
import xml.etree.ElementTree as ET

from kinepoly.homework.quiz import Quantity, Question, Quiz
from kinepoly.present.catalogue import Catalogue

__all__ = ["MOODLE_CATEGORY_ROOT", "cloze_number", "moodle_xml"]

MOODLE_CATEGORY_ROOT = "$course$/top/kinepoly"
"""Where the questions go in the course's question bank: a category per scene below it."""

_PENALTY = "0.3333333"


def cloze_number(x: float) -> str:
    """A number as the blanks write it: eight significant digits, a point for the decimal mark."""
    return f"{x + 0.0:.8g}"


def _tolerance(x: float) -> str:
    return f"{x:.6g}"


def _escaped(text: str) -> str:
    """Words inside a blank: HTML-escaped (no ``&#``), then the blank's own special characters."""
    out = html.escape(text, quote=False)
    for mark in '\\}#~/"':
        out = out.replace(mark, "\\" + mark)
    return out


def _blank(quantity: Quantity, say: Catalogue) -> str:
    tolerance = _tolerance(quantity.tolerance)
    answers = [f"={cloze_number(quantity.value)}:{tolerance}#{_escaped(say.say('quiz.right'))}"]
    if quantity.angle and abs(quantity.value) + quantity.tolerance > 180.0:
        other = quantity.value - 360.0 if quantity.value > 0 else quantity.value + 360.0
        answers.append(f"%100%{cloze_number(other)}:{tolerance}#{_escaped(say.say('quiz.right'))}")
    for wrong in quantity.wrong:
        words = say.say("quiz.mistake", mistake=wrong.words)
        answers.append(f"%0%{cloze_number(wrong.value)}:{tolerance}#{_escaped(words)}")
    return "{1:NUMERICAL:" + "~".join(answers) + "}"


def _question_html(question: Question, say: Catalogue) -> str:
    from kinepoly.handout.notation import html_of

    figure = (f'<p><img src="@@PLUGINFILE@@/{html.escape(question.figure_name)}" '
              f'alt="{html.escape(say.say("quiz.figure"))}" style="max-width:100%;height:auto"></p>')
    blanks = "".join(f"<p>{html_of(q.label)} {_blank(q, say)}</p>" for q in question.quantities)
    return f"{question.statement}{figure}<h3>{html.escape(say.say('quiz.answers'))}</h3>{blanks}"


def _text(parent: ET.Element, tag: str, text: str, **attributes: str) -> ET.Element:
    element = ET.SubElement(parent, tag, attributes)
    ET.SubElement(element, "text").text = text
    return element


def moodle_xml(quiz: Quiz, say: Catalogue) -> bytes:
    """The quiz as a Moodle XML file (UTF-8): import it in the course's question bank, format Moodle XML."""
    root = ET.Element("quiz")
    category = ET.SubElement(root, "question", type="category")
    _text(category, "category", f"{MOODLE_CATEGORY_ROOT}/{quiz.category}")
    _text(category, "info", html.escape(quiz.title), format="html")
    for question in quiz.questions:
        element = ET.SubElement(root, "question", type="cloze")
        _text(element, "name", question.title)
        text = _text(element, "questiontext", _question_html(question, say), format="html")
        figure = ET.SubElement(text, "file", name=question.figure_name, path="/", encoding="base64")
        figure.text = base64.b64encode(question.figure).decode("ascii")
        _text(element, "generalfeedback", "", format="html")
        ET.SubElement(element, "penalty").text = _PENALTY
        ET.SubElement(element, "hidden").text = "0"
        ET.SubElement(element, "idnumber").text = question.name
    ET.indent(root)
    buffer = io.BytesIO()
    ET.ElementTree(root).write(buffer, encoding="UTF-8", xml_declaration=True)
    return buffer.getvalue() + b"\n"
