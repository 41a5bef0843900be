"""The whole command line under the fuzzer (``tools/fuzz.py``), a fixed few dozen cases in the suite.

Mutated examples (cams, gears, [[input]] tables, relative_to, cylinders, compound hinges, triads,
four-bars) through ``solve`` and one or two of ``draw``, ``sweep``, ``handout``, ``animate``,
``variants``, ``check`` and ``bench``: each run a documented exit status other than 70, no
traceback or warning, every file written valid, nothing written by a failed run, no temporary
file left. ``python tools/fuzz.py --cases 3000`` runs thousands of the same kind.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from tools.fuzz import Case, cases, run_case

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
