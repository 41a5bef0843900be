"""docs/python.md runs: its Python blocks, in order, in one namespace, in a copy of the project's examples."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
from PIL import Image
from tests.scenes import EXAMPLES

DOC = EXAMPLES.parent / "docs" / "python.md"


def test_the_python_doc_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    shutil.copytree(EXAMPLES, tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(encoding="utf-8"), re.DOTALL)
    assert len(blocks) >= 4
    namespace: dict[str, object] = {}
    for block in blocks:
        exec(compile(block, str(DOC), "exec"), namespace)  # noqa: S102 - the doc's own examples
    solution, turn, made = namespace["solution"], namespace["turn"], namespace["made"]
    assert solution._repr_svg_().lstrip().startswith("<?xml")  # type: ignore[attr-defined]
    assert turn._repr_png_().startswith(b"\x89PNG")  # type: ignore[attr-defined]
    with Image.open(tmp_path / "slotted-lever.gif") as gif:
        assert gif.n_frames == 36
    assert (tmp_path / "four-bar.html").read_text().startswith("<!DOCTYPE html>")
    assert "<img" in made._repr_html_()  # type: ignore[attr-defined]
