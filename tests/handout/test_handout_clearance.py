"""No label touches another label, a line, an arrow or a symbol on any page of the handouts, and no text
leaves the page: every example and layout scene in English, the six-bars, the Whitworth and the toggle
press also in Turkish and Romanian (the longest words). The measure is tests/render/clearance.py."""

from __future__ import annotations

from pathlib import Path

import pytest
from tests.render.builds import chain
from tests.render.clearance import conflicts
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.handout import handout_sheets, load_catalogue

LAYOUT_SCENES = Path(__file__).resolve().parent.parent / "render" / "scenes"
SCENES = sorted(EXAMPLES.glob("*.toml")) + sorted(LAYOUT_SCENES.glob("*.toml"))
CROWDED = ("centers-six-bar", "triad", "stephenson", "whitworth", "toggle-press")
CASES = [(p, "en") for p in SCENES] + [(p, lang) for p in SCENES if p.stem in CROWDED for lang in ("tr", "ro")]


@pytest.mark.parametrize(("path", "lang"), CASES, ids=lambda v: v.stem if isinstance(v, Path) else v)
def test_no_label_touches_anything_on_any_page(path: Path, lang: str) -> None:
    solution = kinepoly.solve(kinepoly.load_scene(path))
    handout, sheets = handout_sheets(solution, load_catalogue(lang))
    assert len(sheets) == len(handout.pages) >= 3
    found = [f"page {k}: {c}" for k, sheet in enumerate(sheets, 1) for c in conflicts(sheet)]
    assert not found, "\n".join(dict.fromkeys(found))


def test_no_two_labels_overlap_on_any_page_of_a_long_chains_handout() -> None:
    """A chain of seven four-bar loops: many polygon tips and short vectors cluster, and no place near them is free
    of the lines; its labels lie clear of each other on every page, the answers page's whole drawing too (before:
    366 overlaps on 45 of its 67 pages)."""
    handout, sheets = handout_sheets(chain(7), load_catalogue("en"))
    assert len(sheets) == len(handout.pages) > 60
    found = [f"page {k}: {c}" for k, sheet in enumerate(sheets, 1) for c in conflicts(sheet)
             if c.other.startswith("text ")]
    assert not found, "\n".join(dict.fromkeys(found))


@pytest.mark.slow  # about 12 s of CPU (the conflicts of 139 pages measured)
def test_no_two_labels_overlap_on_any_page_of_a_fifteen_loop_chains_handout() -> None:
    """A chain of fifteen four-bar loops, the scaling benchmark's longest handout: on A4 asked it is printed on A3,
    and its labels lie clear of each other and of each other's leaders on every one of its pages (before: 107
    overlaps on 14 of its 139 pages, the acceleration polygon's last steps and answers, and 207 labels on leaders)."""
    handout, sheets = handout_sheets(chain(15), load_catalogue("en"))
    assert len(sheets) == len(handout.pages) > 130
    found = [f"page {k}: {c}" for k, sheet in enumerate(sheets, 1) for c in conflicts(sheet)
             if c.other.startswith(("text ", "Path 'leader "))]
    assert not found, "\n".join(dict.fromkeys(found))
