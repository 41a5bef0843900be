"""A scene's text evaluated as the command line would: the ``solve --json`` object or the errors, and the drawing.

``evaluate`` loads the text (``scene.loader.loads_scene``, the file's name in every message),
solves it by the code ``kinepoly solve`` runs (``present.report.solved``) and lays out the sheet of
``kinepoly draw`` (``render.sheet``) on the editor's paper, kept as given so that the drawing does
not jump between papers while the user drags. ``handles`` are the named points of every solved
link, where the page lets the user grab them.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING, Any

from msgspec import Struct, field
from msgspec.structs import replace

from kinepoly.errors import KinepolyError

if TYPE_CHECKING:
    from kinepoly.render.sheet import Layout
    from kinepoly.solution import Solution

__all__ = ["PAPER", "Evaluation", "assembly_joints", "evaluate", "handles", "input_fields", "input_handle", "lengths",
           "redrawn", "step_svg"]

PAPER = (297.0, 210.0)
"""The editor's default sheet: A4 landscape, ``kinepoly draw``'s and ``solve``'s default paper."""

class Evaluation(Struct, frozen=True):
    """One text's answer: ``result`` (the ``solve --json`` object) or ``errors`` (the CLI's lines) and ``exit``."""

    text: str
    result: dict[str, Any] | None
    errors: tuple[str, ...] = ()
    exit: int = 0
    svg: str = ""
    view: dict[str, Any] = field(default_factory=dict)
    handles: dict[str, Any] = field(default_factory=dict)
    solution: Solution | None = None
    layout: Layout | None = None
    timing_ms: dict[str, float] = field(default_factory=dict)
    draft: bool = False
    """Whether ``svg`` is a draft: its labels at their first places, not searched clear
    (``render.labels.draft_place``)."""

    @property
    def ok(self) -> bool:
        return self.result is not None


def evaluate(text: str, source: str, *, paper: tuple[float, float] = PAPER, draw: bool = True,
             draft: bool = False, written: dict[Any, str] | None = None) -> Evaluation:
    """``text`` loaded, solved and (with ``draw``) drawn on ``paper`` (the polygon scales of ``solve --paper``);
    a user's error or an internal one as the CLI prints it. ``draft``: the sheet's labels at their first places
    (``render.sheet.build_sheet``'s draft), the sheet drawn while the user drags; ``redrawn`` draws it whole.
    ``written``: the SVG of the items drawn before (``render.svg.svg_text``'s ``made``), shared by the texts of one
    document: what a move leaves unchanged is not written again."""
    from kinepoly.errors import EXIT_INTERNAL, error_text, internal_error_text
    from kinepoly.present.report import solved
    from kinepoly.scene.loader import loads_scene

    t0 = time.perf_counter()
    try:
        scene = loads_scene(text, source)
        t1 = time.perf_counter()
        solution, result = solved(scene, paper, t1 - t0)
    except KinepolyError as error:  # the lines the command line prints, and its exit status
        return Evaluation(text, None, tuple(error_text(error).split("\n")), error.exit_code)
    except Exception as error:  # noqa: BLE001 - never a traceback: the page shows the message
        return Evaluation(text, None, tuple(internal_error_text(error).split("\n")), EXIT_INTERNAL)
    t2 = time.perf_counter()
    timing = {"solve": 1e3 * (t2 - t0)}
    if not draw:
        return Evaluation(text, result, solution=solution, timing_ms=timing)
    from kinepoly.render.sheet import layout_sheet

    layout = layout_sheet(solution, paper, grow=False)
    t3 = time.perf_counter()
    timing["layout"] = 1e3 * (t3 - t2)
    svg = _drawn(solution, layout, draft, timing, written)
    return Evaluation(text, result, svg=svg, view=_view(layout), handles=handles(solution), solution=solution,
                      layout=layout, timing_ms=timing, draft=draft)


def redrawn(evaluation: Evaluation, written: dict[Any, str] | None = None) -> Evaluation:
    """A draft ``evaluation`` drawn whole (its labels searched clear), as ``evaluate`` without ``draft`` draws it:
    the same layout, no new solve. Any other evaluation as it is."""
    if not evaluation.draft or evaluation.solution is None or evaluation.layout is None:
        return evaluation
    timing = {"solve": 0.0, "layout": 0.0}
    svg = _drawn(evaluation.solution, evaluation.layout, False, timing, written)
    return replace(evaluation, svg=svg, timing_ms=timing, draft=False)


def _drawn(solution: Solution, layout: Layout, draft: bool, timing: dict[str, float],
           written: dict[Any, str] | None) -> str:
    """The SVG of the sheet on ``layout`` (a draft's: labels unsearched); the milliseconds of its labels (the
    sheet built, its labels placed) and of its SVG added to ``timing``."""
    from kinepoly.render.sheet import build_sheet
    from kinepoly.render.svg import svg_text

    t0 = time.perf_counter()
    sheet = build_sheet(solution, (layout.width, layout.height), layout=layout, draft=draft)
    t1 = time.perf_counter()
    svg = svg_text(sheet, written)
    timing.update(labels=1e3 * (t1 - t0), svg=1e3 * (time.perf_counter() - t1))
    return svg


def step_svg(evaluation: Evaluation, number: int) -> str | None:
    """The sheet of construction step ``number`` (1-based) on the evaluation's layout, as ``draw --steps`` writes it."""
    from kinepoly.render.sheet import build_sheet
    from kinepoly.render.svg import svg_text

    solution, layout = evaluation.solution, evaluation.layout
    if solution is None or layout is None or not 1 <= number <= len(solution.steps):
        return None
    return svg_text(build_sheet(solution, (layout.width, layout.height), step=number, layout=layout))


def _view(layout: Layout) -> dict[str, Any]:
    """Where the mechanism is drawn: paper mm = origin + scale * scene units; the SVG's y runs down from height."""
    panel = layout.panel("mechanism")
    assert panel is not None
    return {"width": layout.width, "height": layout.height, "origin": list(panel.origin), "scale": panel.scale}


def handles(solution: Solution) -> dict[str, Any]:
    """Every named point of a solved link: where it is and on which links; the input's point and how it drives."""
    scene, pose = solution.scene, solution.pose
    points: dict[str, dict[str, Any]] = {}
    made = {cam.center_point for cam in scene.cams}  # a cam's profile centre: the scene writes no such point
    for link in scene.links:
        if link.name not in pose.links or link.name in scene.equivalent_links:
            continue
        for point in link.points:
            entry = points.setdefault(point.name, {"at": list(pose.links[link.name].world(point.local)), "links": []})
            entry["links"].append(link.name)
    for name, entry in points.items():
        entry["frame"] = scene.ground in entry["links"]
        entry["written"] = name not in made
    guesses = {name: list(at) for name, at in scene.guess}
    from kinepoly.editor.structure import removable

    links = [{"name": link.name, "points": [p.name for p in link.points if p.name not in made]}
             for link in scene.links if link.name not in scene.equivalent_links]
    return {"points": points, "input": input_handle(solution), "guess": guesses, "fields": input_fields(solution),
            "lengths": lengths(solution), "links": links, "removable": removable(solution),
            "assembly": assembly_joints(solution)}


def assembly_joints(solution: Solution) -> list[str]:
    """The inner joint of each dyad of the plan none of whose links has a ``[guess]``: where its two assemblies
    differ, the point a guess would pick them by."""
    from kinepoly.engine.groups import Dyad

    scene = solution.scene
    guessed = {name for name, _ in scene.guess}
    return [group.inner.point for group in solution.plan.groups if isinstance(group, Dyad)
            and not any(p.name in guessed for link in group.links for p in scene.link(link).points)]


def input_fields(solution: Solution) -> dict[str, float] | None:
    """The single ``[input]``'s values in the scene's units, as its keys name them (the page's fields)."""
    from kinepoly.scene.spec import LinkInput, SliderInput

    given = solution.scene.input
    if solution.scene.more_inputs:
        return None
    if isinstance(given, LinkInput):
        angle = math.degrees(given.angle_rad) if solution.scene.units.angle == "deg" else given.angle_rad
        return {"angle": angle, "omega": given.omega, "alpha": given.alpha}
    if isinstance(given, SliderInput):
        return {"s": given.s, "s_dot": given.s_dot, "s_ddot": given.s_ddot}
    return None


def lengths(solution: Solution) -> list[dict[str, Any]]:
    """Each link's distances from its first point to its other points, in the scene's length unit."""
    out: list[dict[str, Any]] = []
    scene = solution.scene
    made = {cam.center_point for cam in scene.cams}
    for link in scene.links:
        if link.name in scene.equivalent_links or not link.points or link.points[0].name in made:
            continue
        first = link.points[0]
        for point in link.points[1:]:
            if point.name in made:
                continue
            size = math.hypot(point.local[0] - first.local[0], point.local[1] - first.local[1])
            out.append({"link": link.name, "from": first.name, "point": point.name, "length": size})
    return out


def input_handle(solution: Solution) -> dict[str, Any] | None:
    """The point the page drags to drive the input: a crank's point off its pivot, or a driven slider's point."""
    from kinepoly.scene.spec import LinkInput, SliderInput

    scene, pose, given = solution.scene, solution.pose, solution.scene.input
    if scene.more_inputs or scene.ground is None:
        return None
    if isinstance(given, LinkInput) and given.relative_to is None and given.link in pose.links:
        frame = {p.name for p in scene.link(scene.ground).points}
        link = scene.link(given.link)
        pivots = [p for p in link.points if p.name in frame]
        others = [p for p in link.points if p.name not in frame and math.hypot(*p.local) > 0.0]
        if len(pivots) != 1 or not others:
            return None
        at = pose.links[given.link].world(others[0].local)
        return {"kind": "angle", "point": others[0].name, "link": given.link, "at": list(at)}
    if isinstance(given, SliderInput):
        slider = next((s for s in scene.sliders if s.name == given.slider), None)
        if slider is None or slider.guide not in pose.links or slider.block not in pose.links:
            return None
        at = solution.position(slider.point)
        return {"kind": "stroke", "point": slider.point, "slider": slider.name, "at": list(at)}
    return None
