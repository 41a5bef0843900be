"""A frame's caption gives every value it names whole: each rate and acceleration asked, name, value and unit on one
line, inside the strip and the sheet. Mechanisms with many links have more values than one line holds: the strip
takes a second line, and where even more are asked the type gets smaller rather than a value being cut."""

from __future__ import annotations

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.handout.notation import quantity_name, runs_of, typographic
from kinepoly.motion.frames import make_frames
from kinepoly.motion.sheets import SHEET_MM, frame_sheets, frame_solutions
from kinepoly.present.clean import format_number
from kinepoly.render import style
from kinepoly.render.primitives import Sheet, Text
from kinepoly.render.sheet import MARGIN_MM
from kinepoly.render.text import text_width
from kinepoly.sweep.run import prepare_sweep, run_sweep


def _lines(sheet: Sheet) -> list[Text]:
    return [i for i in sheet.layer("title").items if isinstance(i, Text) and i.role == "caption values"]


def _typeset(text: str, size: float) -> str:
    return "".join(r.text for r in runs_of(typographic(text), size))


@pytest.mark.parametrize(("name", "parts"), [("platform-lift", None), ("triad", None), ("four-bar", None),
                                             ("crank-rocker-cylinder", ("mechanism", "velocity", "acceleration",
                                                                        "functions"))])
def test_every_value_is_in_the_caption_whole(name: str, parts: tuple[str, ...] | None) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    prepared = prepare_sweep(scene)
    frames = make_frames(run_sweep(prepared, steps=6), prepared, *(() if parts is None else (parts,)))
    ground = scene.ground or ""
    for k, sheet in enumerate(frame_sheets(frames, frame_solutions(frames, scene))):
        row = int(frames.rows[k])
        lines = _lines(sheet)
        assert lines
        sizes = {r.size for line in lines for r in line.runs}
        size = max(sizes)
        assert size >= 0.5 * style.LABEL_MM
        if parts is None and name == "four-bar":
            assert size == style.LABEL_MM and len(lines) == 1  # a four-bar's few values: one line, full size
        texts = ["".join(r.text for r in line.runs) for line in lines]
        asked = [v for v in frames.values[1:] if v.valid[row] and v.order >= 1 and not v.name.startswith("|")]
        assert asked
        for v in asked:  # the name, its value and its unit in one line, as typeset
            unit = "°" if v.unit == "deg" else " " + v.unit
            whole = _typeset(f"{quantity_name(v.name, ground)} = {format_number(float(v.values[row]))}{unit}", size)
            assert sum(whole in text for text in texts) == 1, (k, v.name, texts)
        for line in lines:  # each line inside the sheet's border, and below the one before it
            right = line.x + max(r.dx + text_width(r.text, r.size) for r in line.runs)
            assert MARGIN_MM < line.x and right <= SHEET_MM[0] - MARGIN_MM - 3.0 + 1e-9, (k, right)
        assert all(a.y > b.y for a, b in zip(lines, lines[1:], strict=False))
