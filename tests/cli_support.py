"""Running kinepoly's command line inside a test: its exit status and what it printed."""

from __future__ import annotations

import pytest

from kinepoly.cli import main

__all__ = ["run"]


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    """``kinepoly ARGV``: the exit status, the standard output and the standard error."""
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err
