"""The motion drawn by the drawing's own drawer: each frame the sheet of the solution at that position.

Every frame is a ``render.sheet`` sheet (the same mechanism, polygons, notation, styles and labels
as ``kinepoly draw``) on one layout shared by all frames (``render.sheet.motion_layout``: one scale
for the mechanism, one kv and one ka for the whole motion), 16:9 at a size a projector shows
(1600 x 900 pixels at the default resolution). The solution at a frame is the scene solved at that
row's input with the sweep's positions as its [guess], so that it takes the sweep's assembly (a
gear's turn, which a solve takes the shorter way, set to the sweep's through its phase). The
caption (title, input, position, status, values) stands in the title block's place; the traced
paths and the transmission functions are drawn with the sheet's primitives too.

Frames whose polygons the motion leaves out (a singular or near-singular position, ``Frames``)
show the mechanism and say so in each polygon's panel.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np
from msgspec.structs import replace

from kinepoly.errors import KinepolyError
from kinepoly.geom.tolerances import PAPER_SAME_MM, TINY_POSITIVE, TRACKED_REL, TRACKED_TURN_RAD
from kinepoly.handout.notation import quantity_name, runs_of, text_width, typographic
from kinepoly.motion.frames import NO_POLYGON, Frames
from kinepoly.present.clean import format_number
from kinepoly.render.labels import Hint, LabelCache
from kinepoly.render.layout import Panel
from kinepoly.render.polygons import Kind, figure_box, polygon_figure
from kinepoly.render.primitives import Item, Layer, Path, Sheet, Stroke, Text
from kinepoly.render.sheet import MARGIN_MM, Layout, build_sheet, motion_layout
from kinepoly.render.style import INK, LABEL_MM, MUTED_INK, PATH, RULE, SMALL_MM, THIN, link_label_color
from kinepoly.render.text import Run, runs_box
from kinepoly.scene.spec import GearSpec, LinkInput, Scene, SliderInput
from kinepoly.solution import Solution, solve

__all__ = ["DEFAULT_DPI", "SHEET_MM", "frame_sheets", "frame_solutions", "sheet_pixels"]

SHEET_MM = (254.0, 142.875)
"""A frame's sheet: 16:9, 10 x 5.625 inches."""
DEFAULT_DPI = 160.0
"""1600 x 900 pixels on ``SHEET_MM``."""
_FOOT_MM = 11.0
_FOOT_FUNCTIONS_MM = 30.0
_CAPTION_SHARE = 0.55
"""The caption's share of the foot's width where the functions are drawn beside it."""


def _input_at(scene: Scene, value: float) -> LinkInput | SliderInput:
    radians = isinstance(scene.input, LinkInput) and scene.units.angle == "deg"
    found = scene.at_input(math.radians(value) if radians else value).input
    assert isinstance(found, LinkInput | SliderInput)
    return found


def _swept(frames: Frames, k: int, scene: Scene) -> dict[str, complex]:
    """Every point of the moving links (the scene's own) where the sweep has it at frame ``k``."""
    return {p: complex(link.xy[k, j]) for link in frames.links if not link.ground
            and link.name not in scene.equivalent_links for j, p in enumerate(link.points)}


def _link_turn(solution: Solution, frames: Frames, k: int, link: str) -> float:
    """How much further the sweep has ``link`` turned than ``solution`` (0 for a link of fewer than two points)."""
    found = next((f for f in frames.links if f.name == link), None)
    if found is None or len(found.points) < 2:
        return 0.0
    a, b = found.points[:2]
    swept = complex(found.xy[k, 1] - found.xy[k, 0])
    solved = complex(*solution.position(b)) - complex(*solution.position(a))
    return float(np.angle(swept / solved)) if abs(swept) > 0 and abs(solved) > 0 else 0.0


def _geared(scene: Scene, solution: Solution, frames: Frames, k: int) -> Scene | None:
    """``scene`` with each gear's phase set so that the solve turns its gears as the sweep did, or None when it
    already does. A solve takes a gear's turn from the scene's input the shorter way; a sweep carries it on."""
    gears = list(scene.gears)
    changed = False
    for g, gear in enumerate(gears):
        phase = list(gear.phase)
        for side, link in enumerate(gear.links):
            turn = _link_turn(solution, frames, k, link)
            if abs(turn) > TRACKED_TURN_RAD:
                phase[side] -= turn
                changed = True
        gears[g] = GearSpec(gear.name, gear.links, gear.pitch, gear.internal, (phase[0], phase[1]), gear.line)
    return replace(scene, gears=tuple(gears)) if changed else None


def _matches(solution: Solution, swept: dict[str, complex], size: float) -> bool:
    return all(abs(complex(*solution.position(p)) - z) <= TRACKED_REL * size for p, z in swept.items())


def frame_solutions(frames: Frames, scene: Scene) -> list[Solution]:
    """The solution at each frame, on the sweep's assembly."""
    centers = "centers" in frames.parts
    find = scene.find if centers and scene.find.instant_centers else replace(
        scene.find, instant_centers="all" if centers else ())
    x0, y0, x1, y1 = frames.box
    size = max(x1 - x0, y1 - y0, TINY_POSITIVE)
    out = []
    for k in range(frames.count):
        row = int(frames.rows[k])
        swept = _swept(frames, k, scene)
        at = replace(scene, input=_input_at(scene, float(frames.inputs[row])), find=find,
                                 guess=tuple((p, (z.real, z.imag)) for p, z in swept.items()))
        other = int(frames.rows[k - 1 if k > 0 else min(1, frames.count - 1)])
        toward = _input_at(scene, float(frames.inputs[other]))
        step = (toward.angle_rad - at.input.angle_rad
                if isinstance(toward, LinkInput) and isinstance(at.input, LinkInput)
                else toward.s - at.input.s if isinstance(toward, SliderInput) and isinstance(at.input, SliderInput)
                else 0.0)
        solution = _solve(at, step)
        if scene.gears and not _matches(solution, swept, size):
            geared = _geared(at, solution, frames, k)
            if geared is not None:
                solution = _solve(geared, step)
        out.append(solution)
    return out


def _solve(scene: Scene, toward: float) -> Solution:
    """The solution of ``scene``; at a dead point, where the solve refuses a position whose rates are not
    determined, the input moved a little ``toward`` the frame before it (the polygons are left out there); where
    no nudge helps (rates beyond double precision), the position alone, without polygons."""
    try:
        return solve(scene)
    except KinepolyError:
        inp = scene.input
        assert isinstance(inp, LinkInput | SliderInput)
        for nudge in (1e-6, 1e-4, 1e-2):
            moved = (replace(inp, angle_rad=inp.angle_rad + nudge * toward) if isinstance(inp, LinkInput)
                     else replace(inp, s=inp.s + nudge * toward))
            try:
                return solve(replace(scene, input=moved))
            except KinepolyError:
                continue
        # rates beyond double precision at every nudge: the mechanism where it stands, its polygons left out
        still = (replace(inp, omega=0.0, alpha=0.0) if isinstance(inp, LinkInput)
                 else replace(inp, s_dot=0.0, s_ddot=0.0))
        return replace(solve(replace(scene, input=still)), velocity=None, acceleration=None)


def _figures(solution: Solution, layout: Layout) -> tuple[Any, ...]:
    """The polygons of ``solution`` that fit their panels of ``layout`` (a near-singular position's may not)."""
    kinds: tuple[Kind, Kind] = ("velocity", "acceleration")
    out = []
    for kind in kinds:
        panel = layout.panel(kind)
        if panel is None or (solution.velocity if kind == "velocity" else solution.acceleration) is None:
            continue
        figure = polygon_figure(solution, kind)
        x0, y0, x1, y1 = figure_box(figure)
        r = panel.drawing_rect
        corners = (panel.paper((x0, y0)), panel.paper((x1, y1)))
        slack = PAPER_SAME_MM
        if all(r[0] - slack <= x <= r[2] + slack and r[1] - slack <= y <= r[3] + slack for x, y in corners):
            out.append(figure)
    return tuple(out)


def _value_text(name: str, value: float, unit: str, ground: str) -> str:
    """``omega13 = 12.5 rad/s`` in the notation's plain form (``handout.notation`` typesets it)."""
    amount = format_number(value)
    return f"{quantity_name(name, ground)} = {amount}{'°' if unit == 'deg' else ' ' + unit}"


def _runs(text: str, size: float, room: float, bold: bool = False) -> tuple[Run, ...]:
    """``text`` typeset at ``size``, or smaller where it would be wider than ``room``."""
    text = typographic(text)
    runs = runs_of(text, size, bold)
    width = runs_box(runs, bold)[2]
    return runs if width <= room else runs_of(text, size * room / width, bold)


_VALUES_GAP = "    "
"""Between two values of a caption."""
_CAPTION_ROW_MM = 4.0
"""How far apart the caption's lines of values are."""
_CAPTION_ROWS = 2
"""The most lines of values a caption's strip grows to hold at full size (``_foot``); more are set smaller."""
_SMALLEST_SHARE = 0.5
"""The smallest type the values are set in, a share of ``LABEL_MM``, where even that many lines cannot hold them."""


def _packed(values: list[str], size: float, room: float) -> list[str]:
    """``values`` (``name = value unit`` each) in lines no wider than ``room`` at ``size``, one after another as
    many as fit (a value never broken from its name, nor a line left with half of one)."""
    lines: list[str] = []
    for value in values:
        trial = f"{lines[-1]}{_VALUES_GAP}{value}" if lines else value
        if lines and runs_box(runs_of(typographic(trial), size))[2] <= room:
            lines[-1] = trial
        else:
            lines.append(value)
    return lines


def _value_lines(values: list[str], room: float, rows: int) -> tuple[list[str], float]:
    """The caption's values in at most ``rows`` lines no wider than ``room``, and the size to set them at:
    ``LABEL_MM`` where they fit, else as much smaller as they need (down to ``_SMALLEST_SHARE`` of it, below which
    the last values are left out)."""
    size = LABEL_MM
    lines = _packed(values, size, room)
    while len(lines) > rows and size > _SMALLEST_SHARE * LABEL_MM:
        size = max(0.95 * size, _SMALLEST_SHARE * LABEL_MM)
        lines = _packed(values, size, room)
    return lines[:rows], size


def _caption_values(frames: Frames, k: int, ground: str) -> list[str]:
    """The values a frame's caption gives (by the number rule): each rate and acceleration asked, where valid."""
    row = int(frames.rows[k])
    return [_value_text(v.name, float(v.values[row]), v.unit, ground) for v in frames.values[1:]
            if v.valid[row] and v.order >= 1 and not v.name.startswith("|")]


def _ground(frames: Frames) -> str:
    return frames.scene.ground or "" if frames.scene is not None else ""


def _caption_room(rect: tuple[float, float, float, float], share: float) -> float:
    """How wide the caption's lines may be in the foot strip ``rect`` (its left ``share``)."""
    return share * (rect[2] - rect[0]) - 6.0


def _foot(frames: Frames) -> float:
    """The foot strip's height without the functions: room for the title and as many lines of values as the widest
    frame's caption takes at full size, up to ``_CAPTION_ROWS``."""
    room = _caption_room((MARGIN_MM, 0.0, SHEET_MM[0] - MARGIN_MM, 0.0), 1.0)  # the strip: between the margins
    ground = _ground(frames)
    rows = max((len(_packed(_caption_values(frames, k, ground), LABEL_MM, room)) for k in range(frames.count)),
               default=1)
    return _FOOT_MM + _CAPTION_ROW_MM * (min(max(rows, 1), _CAPTION_ROWS) - 1)


def _caption(frames: Frames, k: int, rect: tuple[float, float, float, float], share: float) -> list[Item]:
    """The title, where the input stands and the values there, in the foot strip (its left ``share``)."""
    row = int(frames.rows[k])
    x0, y0, x1, y1 = rect
    room = _caption_room(rect, share)
    ground = _ground(frames)
    status = ("", " (near-singular)", " (singular: polygons not determined)", "")[int(frames.status[row])]
    where = _value_text(frames.input_name, float(frames.inputs[row]), frames.input_unit, ground)
    head = f"{frames.title}: {where}, position {row + 1} of {len(frames.inputs)}{status}"
    items: list[Item] = [Text(x0 + 3.0, y1 - 4.6, _runs(head, 3.2, room, True), INK, "caption title",
                              None, True)]
    lines, size = _value_lines(_caption_values(frames, k, ground), room,
                               max(1, int((y1 - y0 - 6.0) / _CAPTION_ROW_MM)))
    for n, line in enumerate(lines):
        items.append(Text(x0 + 3.0, y1 - 8.8 - _CAPTION_ROW_MM * n, _runs(line, size, room), INK, "caption values"))
    return items


def _paths(frames: Frames, k: int, panel: Panel) -> list[Item]:
    """The paths of the points asked, traced up to frame ``k``."""
    out: list[Item] = []
    for trace in frames.paths:
        xy = trace.xy[:k + 1]
        if len(xy) >= 2:
            points = tuple(panel.paper((float(z.real), float(z.imag))) for z in xy)
            out.append(Path(points, PATH, role=f"path {trace.name}"))
    return out


def _no_polygon(frames: Frames, k: int, layout: Layout, figures: tuple[Any, ...]) -> list[Item]:
    """What a polygon panel says where the frame leaves its polygon out."""
    row = int(frames.rows[k])
    drawn = {f.kind for f in figures}
    out: list[Item] = []
    for kind in ("velocity", "acceleration"):
        panel = layout.panel(kind)
        if panel is None or kind in drawn:
            continue
        text = NO_POLYGON[2] if int(frames.status[row]) == 2 else NO_POLYGON[1]
        x0, y0, x1, y1 = panel.drawing_rect
        out.append(Text(x0 + 2.0, (y0 + y1) / 2, _runs(text, LABEL_MM, x1 - x0 - 4.0), MUTED_INK,
                        f"no polygon {kind}"))
    return out


def _functions(frames: Frames, k: int, rect: tuple[float, float, float, float]) -> list[Item]:
    """The transmission functions over the sweep and a cursor at the position shown, in the foot's right part."""
    chosen, window = frames.functions()
    if not chosen:
        return []
    x0, y0, x1, y1 = rect
    box = (x0 + _CAPTION_SHARE * (x1 - x0), y0 + 3.0, x1 - 3.0, y1 - 5.0)
    xs = np.asarray(frames.inputs, float)
    every = np.concatenate([v.values[v.valid] for v in chosen] + [np.zeros(1)])
    low, high = window if window is not None else (float(every.min()), float(every.max()))
    high = high if high > low else low + 1.0
    left, right = float(xs.min()), float(xs.max())
    right = right if right > left else left + 1.0

    def at(x: float, y: float) -> tuple[float, float]:
        return (box[0] + (x - left) / (right - left) * (box[2] - box[0]),
                box[1] + (min(max(y, low), high) - low) / (high - low) * (box[3] - box[1]))

    items: list[Item] = [Path(((box[0], box[1]), (box[2], box[1]), (box[2], box[3]), (box[0], box[3])), THIN,
                              closed=True, role="functions frame")]
    if low < 0.0 < high:
        items.append(Path((at(left, 0.0), at(right, 0.0)), THIN, role="functions zero"))
    for j, v in enumerate(chosen):
        ink = Stroke(link_label_color(j + 1), 0.3)
        run: list[tuple[float, float]] = []
        for x, y, ok in zip(xs, v.values, v.valid, strict=True):
            if ok and math.isfinite(float(y)):
                run.append(at(float(x), float(y)))
                continue
            if len(run) >= 2:
                items.append(Path(tuple(run), ink, role=f"function {v.name}"))
            run = []
        if len(run) >= 2:
            items.append(Path(tuple(run), ink, role=f"function {v.name}"))
        ground = frames.scene.ground or "" if frames.scene is not None else ""
        step = (box[2] - box[0]) / len(chosen)
        items.append(Text(box[0] + 1.0 + step * j, box[3] + 1.0,
                          _runs(f"{quantity_name(v.name, ground)} ({v.unit})", SMALL_MM, step - 2.0),
                          link_label_color(j + 1), f"function name {v.name}"))
    x = float(xs[int(frames.rows[k])])
    items.append(Path((at(x, low), at(x, high)), RULE, role="functions cursor"))
    for y, text in ((box[3] - SMALL_MM, format_number(high)), (box[1], format_number(low))):
        items.append(Text(box[0] - 1.0 - text_width(text, SMALL_MM), y, runs_of(text, SMALL_MM), INK,
                          "functions end"))  # the window's ends, left of the chart
    return items


_SPREAD = 2.0
"""A polygon more than this many times the median size of the motion's is left out rather than shrink them all."""


def _extent(solution: Solution) -> float:
    kinds: tuple[Kind, Kind] = ("velocity", "acceleration")
    sizes = []
    for kind in kinds:
        if (solution.velocity if kind == "velocity" else solution.acceleration) is not None:
            x0, y0, x1, y1 = figure_box(polygon_figure(solution, kind))
            sizes.append(max(x1 - x0, y1 - y0))
    return max(sizes, default=0.0)


def _sizing(frames: Frames, solutions: list[Solution]) -> list[Solution]:
    """The solutions the layout's scales fit: the ok positions' (every one with polygons where none is ok),
    but for those whose polygons are more than ``_SPREAD`` times the median size (near a dead point): drawn at
    a scale that holds those, every other polygon would shrink to a dot."""
    drawn = [s for k, s in enumerate(solutions) if (s.velocity is not None or s.acceleration is not None)
             and all(p is None or bool(p.valid[k]) for p in (frames.velocity, frames.acceleration))]
    ok = [s for k, s in enumerate(solutions) if s in drawn and int(frames.status[int(frames.rows[k])]) == 0] or drawn
    if not ok:
        return solutions
    sizes = {id(s): _extent(s) for s in ok}
    limit = _SPREAD * float(np.median(list(sizes.values())))
    return [s for s in ok if sizes[id(s)] <= limit] or ok


def frame_sheets(frames: Frames, solutions: list[Solution]) -> Iterator[Sheet]:
    """Each frame's sheet, on one layout."""
    functions = "functions" in frames.parts
    foot = _FOOT_FUNCTIONS_MM if functions else _foot(frames)
    layout = motion_layout(_sizing(frames, solutions), SHEET_MM, foot)
    mechanism = layout.panel("mechanism")
    assert mechanism is not None
    taken: dict[str, Hint] = {}
    for k, solution in enumerate(solutions):
        shown = all(p is None or bool(p.valid[k]) for p in (frames.velocity, frames.acceleration))
        figures = _figures(solution, layout) if shown else ()
        labels = LabelCache(taken)  # each label tried first where it was on the frame before: it stays while it can
        frame = replace(layout, figures=figures, labels=labels)
        sheet = build_sheet(solution, SHEET_MM, layout=frame, title_block=False)
        taken = labels.taken
        extra: dict[str, list[Item]] = {
            "mechanism": _paths(frames, k, mechanism) if "paths" in frames.parts else [],
            "title": _caption(frames, k, layout.title_rect, _CAPTION_SHARE if functions else 1.0)
            + _no_polygon(frames, k, layout, figures)
            + (_functions(frames, k, layout.title_rect) if functions else []),
        }
        layers = tuple(Layer(layer.name, tuple(extra.get(layer.name, [])) + layer.items) for layer in sheet.layers)
        yield Sheet(sheet.width, sheet.height, f"{frames.title}: position {int(frames.rows[k]) + 1}", layers)


def sheet_pixels(sheet: Sheet, dpi: float = DEFAULT_DPI) -> np.ndarray:
    """The sheet drawn as pixels (RGB, height x width x 3) by the drawing's matplotlib writer."""
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from kinepoly.render.mpl import figure_of

    with matplotlib.rc_context({"lines.scale_dashes": False, "font.family": "DejaVu Sans"}):
        figure = figure_of(sheet)
        figure.set_dpi(dpi)
        canvas = FigureCanvasAgg(figure)
        canvas.draw()  # type: ignore[no-untyped-call]
        rgba = np.asarray(canvas.buffer_rgba())  # type: ignore[no-untyped-call]
    return np.ascontiguousarray(rgba[:, :, :3])
