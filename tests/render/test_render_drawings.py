"""drawings/ holds the current drawing of every example: a test fails when one is stale or missing.

Regenerate with ``python3 tools/regenerate_drawings.py`` from the repository's root.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from tests.scenes import EXAMPLES
from tools.compare_drawings import PNG_RMS_TOLERANCE, canonical_dxf, canonical_svg, png_rms
from tools.regenerate_drawings import DRAWN_FORMATS, draw_example, stale

DRAWINGS = EXAMPLES.parent / "drawings"


@pytest.mark.slow  # every example drawn in every format: the slowest test of all
def test_committed_drawings_are_current() -> None:
    problems = stale(EXAMPLES, DRAWINGS)
    assert not problems, "stale drawings; run python3 tools/regenerate_drawings.py:\n" + "\n".join(problems)


def test_every_example_has_its_three_drawings() -> None:
    for scene in EXAMPLES.glob("*.toml"):
        for fmt in DRAWN_FORMATS:
            assert (DRAWINGS / f"{scene.stem}.{fmt}").is_file()


def test_the_comparison_sees_a_changed_drawing(tmp_path: Path) -> None:
    """The canonical comparisons are not blind: a drawing of another scene differs in every format."""
    draw_example(EXAMPLES / "four-bar.toml", tmp_path)
    moved = tmp_path / "other"
    moved.mkdir()
    text = (EXAMPLES / "four-bar.toml").read_text().replace("angle = 60", "angle = 61")
    (moved / "four-bar.toml").write_text(text)
    draw_example(moved / "four-bar.toml", moved)
    assert canonical_svg((tmp_path / "four-bar.svg").read_text()) != canonical_svg((moved / "four-bar.svg").read_text())
    assert canonical_dxf(tmp_path / "four-bar.dxf") != canonical_dxf(moved / "four-bar.dxf")
    assert png_rms(tmp_path / "four-bar.png", moved / "four-bar.png") > PNG_RMS_TOLERANCE
    assert png_rms(tmp_path / "four-bar.png", tmp_path / "four-bar.png") == pytest.approx(0.0)


def _four_bar_copy(tmp_path: Path) -> tuple[Path, Path]:
    """A folder of examples holding the four-bar and a folder of its committed drawings, under ``tmp_path``."""
    examples, drawings = tmp_path / "examples", tmp_path / "drawings"
    examples.mkdir()
    drawings.mkdir()
    (examples / "four-bar.toml").write_text((EXAMPLES / "four-bar.toml").read_text())
    for fmt in DRAWN_FORMATS:
        (drawings / f"four-bar.{fmt}").write_bytes((DRAWINGS / f"four-bar.{fmt}").read_bytes())
    return examples, drawings


def test_regenerating_writes_only_the_drawings_that_differ(tmp_path: Path) -> None:
    """The regenerator replaces a missing or stale file and leaves a current one untouched, byte for byte."""
    from tools.regenerate_drawings import main

    examples, drawings = _four_bar_copy(tmp_path)
    current = (drawings / "four-bar.dxf").read_bytes() + b"999\nmoved header\n"  # a DXF comment: same entities
    (drawings / "four-bar.dxf").write_bytes(current)
    (drawings / "four-bar.png").unlink()
    assert main(["--examples", str(examples), "--drawings", str(drawings)]) == 0
    assert (drawings / "four-bar.png").is_file()
    assert (drawings / "four-bar.dxf").read_bytes() == current
    assert (drawings / "four-bar.svg").read_bytes() == (DRAWINGS / "four-bar.svg").read_bytes()
    assert stale(examples, drawings) == []


def test_a_png_whose_svg_is_stale_is_stale_too(tmp_path: Path) -> None:
    """A label that changed moves few pixels, under the PNG's tolerance; the SVG tells, and the PNG goes with it."""
    examples, drawings = _four_bar_copy(tmp_path)
    svg = (drawings / "four-bar.svg").read_text()
    (drawings / "four-bar.svg").write_text(svg.replace(">o<", ">q<", 1))
    problems = stale(examples, drawings)
    assert any("four-bar.svg" in p for p in problems)
    assert any("four-bar.png: stale (its SVG differs)" in p for p in problems), problems
