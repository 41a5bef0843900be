"""One palette and one notation in every picture: drawings, handouts and animations.

The colours of a sheet come from ``render.style`` (and the drawer's own modules): ``motion/`` and
``handout/`` name none of their own. An animation's frame is the drawing's sheet of the solution at
that position: every colour on it is one the drawing uses, its polygons are the drawing's (the same
vectors, the same notation), and its caption writes quantities as the course does (omega13, typeset).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import numpy as np
import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.handout.notation import quantity_name, runs_of, typographic
from kinepoly.motion.frames import make_frames
from kinepoly.motion.sheets import SHEET_MM, frame_sheets, frame_solutions, sheet_pixels
from kinepoly.present.clean import format_number
from kinepoly.render import style
from kinepoly.render.primitives import Arrow, Circle, Sheet, Text
from kinepoly.render.primitives import Path as SheetPath
from kinepoly.render.sheet import build_sheet
from kinepoly.sweep.run import prepare_sweep, run_sweep

SRC = Path(kinepoly.__file__).resolve().parent
_COLOUR = re.compile(r"^#(?:[0-9a-fA-F]{3}){1,2}$")


@pytest.mark.parametrize("package", ["motion", "handout"])
def test_motion_and_handouts_name_no_colour_of_their_own(package: str) -> None:
    found = []
    for module in sorted((SRC / package).glob("*.py")):
        for node in ast.walk(ast.parse(module.read_text())):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and _COLOUR.match(node.value):
                found.append(f"{module.name}:{node.lineno}: {node.value}")
    assert not found, found  # a colour of a picture is render.style's (a web page's CSS is its chrome, not a picture)


def _colours(sheet: Sheet) -> set[str]:
    out = set()
    for item in sheet.items():
        if isinstance(item, SheetPath | Circle):
            out |= {c for c in (item.stroke.color if item.stroke else None, item.fill) if c}
        elif isinstance(item, Arrow | Text):
            out.add(item.color)
    return out


@pytest.mark.parametrize("name", ["eccentric-cam-flat", "gear-pair", "kc0-six-bar"])
def test_an_animation_frame_is_the_drawing_of_its_position(name: str) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    prepared = prepare_sweep(scene)
    frames = make_frames(run_sweep(prepared, steps=8), prepared, ("mechanism", "velocity", "acceleration", "paths",
                                                                    "functions"))
    solutions = frame_solutions(frames, scene)
    sheets = list(frame_sheets(frames, solutions))
    assert len(sheets) == frames.count
    palette = {style.INK, style.MUTED_INK, style.PATH.color, style.THIN.color, style.RULE.color}
    palette |= {style.link_label_color(k) for k in range(16)}
    k = next(k for k, s in enumerate(sheets) if s.layer("velocity-polygon").items)
    drawing = build_sheet(solutions[k], SHEET_MM)
    assert _colours(sheets[k]) <= _colours(drawing) | palette
    # the polygons are the drawing's: its vectors, named alike (one too short to draw at the motion's scale left out)
    for layer in ("velocity-polygon", "acceleration-polygon"):
        def vectors(sheet: Sheet) -> set[str]:
            return {i.role for i in sheet.layer(layer).items if isinstance(i, Arrow)}  # noqa: B023
        assert vectors(sheets[k]) and vectors(sheets[k]) <= vectors(drawing)
    # the caption names quantities as the course does, typeset by the notation module
    row = int(frames.rows[k])
    ground = scene.ground or ""
    caption = [i for i in sheets[k].layer("title").items if isinstance(i, Text) and i.role == "caption values"]
    words = " ".join(i.string for i in caption)
    assert "omega_" not in words and "_" not in words
    asked = [v for v in frames.values[1:] if v.valid[row] and v.order >= 1 and not v.name.startswith("|")]
    assert asked
    first = typographic(quantity_name(asked[0].name, ground))
    assert "".join(r.text for r in runs_of(first, style.LABEL_MM)) in words
    for v in asked:  # each value as the sweep has it: a rate is not zeroed against the 1e13 of a dead point's rows
        ok = v.valid & (frames.status == 0)
        if abs(v.values[row]) > 1e-6 * float(np.abs(v.values[ok]).max()):
            assert f"= {format_number(float(v.values[row])).replace('^2', '²')}" in words, (v.name, words)
    assert sheet_pixels(sheets[k]).shape == (900, 1600, 3)  # a size a projector shows


@pytest.mark.parametrize("name", ["gear-pair", "planetary", "dump-body", "kc0-six-bar"])
def test_each_frame_is_solved_where_the_sweep_has_it(name: str) -> None:
    """The solution a frame draws has every point where the sweep put it: the sweep's assembly, a gear turned on
    past half a turn as the sweep turned it (a solve alone takes the shorter way), a dead point's frame a hair off."""
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    prepared = prepare_sweep(scene)
    frames = make_frames(run_sweep(prepared, steps=24), prepared)
    size = max(frames.box[2] - frames.box[0], frames.box[3] - frames.box[1])
    for k, solution in enumerate(frame_solutions(frames, scene)):
        ok = frames.status[frames.rows[k]] == 0
        for link in frames.links:
            if link.ground or link.name in scene.equivalent_links:
                continue
            for j, point in enumerate(link.points):  # at a dead point the position moves as the root of the nudge
                assert abs(complex(*solution.position(point)) - link.xy[k, j]) <= (1e-9 if ok else 1e-3) * size, \
                    (k, point)
