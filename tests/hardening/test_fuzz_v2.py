"""The whole command line under the fuzzer (``tools/fuzz.py``), a fixed few dozen cases in the suite.

Mutated examples (cams, gears, [[input]] tables, relative_to, cylinders, compound hinges, triads,
four-bars) through ``solve`` and one or two of ``draw``, ``sweep``, ``handout``, ``animate``,
``variants``, ``check`` and ``bench``: each run a documented exit status other than 70, no
traceback or warning, every file written valid, nothing written by a failed run, no temporary
file left. Then ``kinepoly edit``'s JSON API on some of the same cases (``run_editor``): the text
put answered as ``solve --json`` answers it, changes over the websocket with extreme and wrong
values, every answer strict JSON, every sheet well-formed SVG without script, the file written
only by a save and then exactly. ``python tools/fuzz.py --cases 3000 [--editor]`` runs thousands.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from tools.fuzz import Case, _check_state, cases, run_case, run_editor

from kinepoly.editor.document import Document

CASES = list(cases(seed=1, count=36))


def test_the_cases_cover_every_command_and_many_examples() -> None:
    commands = {command for case in CASES for command in case.commands}
    assert commands >= {"draw", "sweep", "handout", "animate", "variants", "check"}
    assert len({case.name.split("-", 1)[1] for case in CASES}) >= 15


@pytest.mark.parametrize("case", CASES, ids=[case.name for case in CASES])
def test_a_fuzz_case_ends_well(tmp_path: Path, case: Case) -> None:
    outcome = run_case(case, tmp_path)
    assert outcome.problems == [], case.text
    assert "solve" in outcome.codes


EDITED = CASES[::4]


def test_the_edited_cases_come_from_many_examples() -> None:
    assert len(EDITED) == 9
    assert len({case.name.split("-", 1)[1] for case in EDITED}) >= 8


@pytest.mark.parametrize("case", EDITED, ids=[case.name for case in EDITED])
def test_the_editor_api_answers_a_fuzz_case_as_the_command_line(tmp_path: Path, case: Case) -> None:
    outcome = run_editor(case, tmp_path)
    assert outcome.problems == [], case.text
    assert outcome.codes["edit-put"] in (200, 422)
    assert sum(outcome.tally.values()) == 7


def test_the_editor_checks_find_a_file_written_before_a_save(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    replace = Document.replace

    def writing(self: Document, text: str) -> object:
        self.path.write_text(text + "\n", encoding="utf-8")
        return replace(self, text)

    monkeypatch.setattr(Document, "replace", writing)
    outcome = run_editor(CASES[0], tmp_path, drags=0)
    assert any("written before a save" in p for p in outcome.problems), outcome.problems


@pytest.mark.parametrize("svg", ["<svg><script>alert(1)</script></svg>", "<svg><g onload='x()'/></svg>", "<svg>",
                                 '<svg viewBox="0 0 nan 1"/>', '<svg><path d="M 0 inf"/></svg>'])
def test_the_editor_checks_find_a_bad_sheet(svg: str) -> None:
    problems: list[str] = []
    _check_state({"svg": svg}, "here", problems)
    assert len(problems) == 1 and "the sheet is not valid" in problems[0]


def test_the_editor_checks_find_an_internal_error() -> None:
    problems: list[str] = []
    _check_state({"refused": "kinepoly: internal error: OverflowError"}, "here", problems)
    assert problems
