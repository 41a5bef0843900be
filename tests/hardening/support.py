"""The four-bar of issue 15's reproducers, a way to change it, and checks of what a run leaves behind."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from tests.cli_support import run

__all__ = ["BASE", "edit", "run_on", "well_formed_svg"]

BASE = """\
[links]
1 = { points = { A0 = [0, 0], B0 = [100, 0] } }
2 = { points = { A0 = [0, 0], A = [40, 0] } }
3 = { points = { A = [0, 0], B = [120, 0] } }
4 = { points = { B0 = [0, 0], B = [80, 0] } }
[input]
link = "2"
angle = 60
omega = 10
[guess]
B = [110, 80]
"""


def edit(old: str = "", new: str = "", *, before: str = "", after: str = "") -> str:
    """BASE with ``old`` replaced by ``new`` (once), ``before`` put first and ``after`` appended."""
    assert not old or old in BASE
    return before + (BASE.replace(old, new, 1) if old else BASE) + after


def run_on(capsys: pytest.CaptureFixture[str], tmp_path: Path, text: str, *argv: str) -> tuple[int, str, str]:
    """Write ``text`` to tmp_path/s.toml and run ``kinepoly ARGV[0] s.toml ARGV[1:]`` (``{tmp}`` in argv is
    tmp_path)."""
    scene = tmp_path / "s.toml"
    scene.write_text(text, encoding="utf-8")
    command, *rest = argv
    return run(capsys, command, str(scene), *[a.format(tmp=tmp_path) for a in rest])


def well_formed_svg(path: Path) -> ET.Element:
    """The SVG's root (raises ParseError when it is not well-formed XML); every number in it finite."""
    root = ET.parse(path).getroot()
    for element in root.iter():
        for name, value in element.attrib.items():
            assert "nan" not in value.lower() and "inf" not in value.lower() or name == "data-role", (name, value)
    assert all(math.isfinite(float(x)) for x in root.attrib["viewBox"].split())
    return root
