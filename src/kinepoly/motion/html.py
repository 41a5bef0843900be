"""The motion as one self-contained web page: each frame the drawing's own sheet as SVG, a small script stepping them.

The frames are the sheets ``motion.sheets`` makes (the drawer of every drawing, written by
``render.svg``); nothing is fetched: the frames, the values at every row and the script are in the
page, the data embedded by ``script_json`` (``<``, ``>`` and ``&`` escaped, so that no text of a
scene can close the script). Controls: play/pause, a slider over the positions reached, the arrow
keys; the table shows the asked quantities at the position shown. Hooks for tests: ``#position``
(the slider, frame index), ``#where`` (the position's label), each value's cell
``td[data-name=NAME]`` with its exact number in ``data-value`` (empty where it has none),
``document.body.dataset.row`` (the sweep's row shown), ``#drawing svg`` (the frame's sheet).
"""

from __future__ import annotations

import html
import math
from collections.abc import Iterator
from typing import Any

from kinepoly.assets import static_text
from kinepoly.handout.notation import html_of, quantity_name, typographic
from kinepoly.motion.frames import Frames
from kinepoly.motion.sheets import frame_sheets, frame_solutions
from kinepoly.present.script_json import script_json
from kinepoly.render.svg import svg_text
from kinepoly.sweep.result import STATUS

__all__ = ["frames_data", "html_page"]


def _number(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def _sheets(frames: Frames) -> Iterator[str]:
    """Each frame's sheet as SVG (the XML declaration left out: the SVG stands inside the page)."""
    if frames.scene is None:
        raise ValueError("these frames keep no scene (they were not made by kinepoly.motion.frames.make_frames)")
    made: dict[Any, str] = {}  # what the frames share is written once
    for sheet in frame_sheets(frames, frame_solutions(frames, frames.scene)):
        text = svg_text(sheet, made)
        yield text[text.index("<svg"):]


def frames_data(frames: Frames) -> dict[str, Any]:
    """The page's data: JSON-ready."""
    return {
        "title": frames.title, "input": {"name": frames.input_name, "unit": frames.input_unit},
        "rows": [int(r) for r in frames.rows], "count": len(frames.inputs), "skipped": list(frames.skipped),
        "inputs": [float(x) for x in frames.inputs], "status": [STATUS[int(s)] for s in frames.status],
        "values": [{"name": v.name, "unit": v.unit, "order": v.order, "label": html_of(typographic(quantity_name(
                        v.name, frames.scene.ground or "" if frames.scene is not None else ""))),
                    "values": [_number(float(x)) if ok else None for x, ok in zip(v.values, v.valid, strict=True)]}
                   for v in frames.values],
        "sheets": list(_sheets(frames)),
    }


def html_page(frames: Frames, fps: float = 24.0) -> str:
    """The page: data, style and script inline (the package's ``static/animation.css`` and ``.js``); it draws frame 0
    on load."""
    data = script_json(frames_data(frames))
    title = html.escape(frames.title)
    style, script = static_text("kinepoly.motion", "animation.css"), static_text("kinepoly.motion", "animation.js")
    return (f'<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n<title>{title}: motion</title>\n'
            f"<style>\n{style}</style>\n</head>\n"
            f'<body data-fps="{fps:g}" data-playing="no">\n<h1>{title}</h1>\n<div id="drawing"></div>\n'
            '<div id="controls"><button id="play" type="button">Play</button>'
            '<input id="position" type="range" min="0" max="0" step="1" value="0" aria-label="position">'
            '<span id="where"></span></div>\n<p id="skipped"></p>\n'
            '<table><thead><tr><th>quantity</th><th>value</th><th>unit</th></tr></thead>'
            '<tbody id="values"></tbody></table>\n'
            f'<script type="application/json" id="frames">{data}</script>\n<script>\n{script}</script>\n'
            "</body>\n</html>\n")
