"""Fixtures of the editor's tests: a scene file copied into a temporary folder, and its editor served."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest
from tests.editor.server import Served, serving

from kinepoly.editor.document import Document

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture
def four_bar(tmp_path: Path) -> Path:
    """A copy of the project's four-bar (its comments included)."""
    path = tmp_path / "four-bar.toml"
    shutil.copy(EXAMPLES / "four-bar.toml", path)
    return path


@pytest.fixture
def served(four_bar: Path) -> Iterator[Served]:
    """The four-bar's editor on a free port, shut down after the test."""
    with serving(Document(str(four_bar))) as running:
        yield running
