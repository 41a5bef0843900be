"""The velocity and acceleration polygons as drawn: vectors, tips, direction lines, image triangles.

``polygon_figure`` reads the construction steps (physical units, pole at 0) and says what the
polygon shows and at which step each element appears; ``polygon_items`` draws that to a panel's
scale, up to a step, with the step's new elements under a highlight. Every vector's drawn end
is exactly ``pole + k * vector``.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Literal

from kinepoly.engine.steps import Step, Term
from kinepoly.geom.hull import diameter
from kinepoly.geom.lines import Line
from kinepoly.geom.vec import Vec, norm, sub
from kinepoly.render.labels import Request
from kinepoly.render.layout import Panel
from kinepoly.render.primitives import Arrow, Circle, Item, Path, Stroke
from kinepoly.render.style import (
    DIRECTION_LINE,
    HALO,
    HEAD_HALF_WIDTH_MM,
    HEAD_LENGTH_MM,
    LABEL_MM,
    TERM_COLORS,
    VECTOR_WIDTH_MM,
    link_color,
)
from kinepoly.render.text import Run, text_width, tip_runs, vector_runs
from kinepoly.solution import Solution

__all__ = ["Figure", "FigureVector", "figure_box", "polygon_figure", "polygon_items"]

Kind = Literal["velocity", "acceleration"]
Point = tuple[float, float]
_SAME = 1e-9
"""Two polygon points closer than this (relative to the polygon's size) are one point."""
TINY_FACTOR = 1.0
"""A vector drawn shorter than its head times this becomes a dot with a label."""


@dataclass(frozen=True)
class FigureVector:
    label: str
    start: Vec
    end: Vec
    term: Term
    step: int


@dataclass(frozen=True)
class FigureLine:
    line: Line
    step: int


@dataclass(frozen=True)
class FigureTip:
    label: str
    value: Vec
    step: int


@dataclass(frozen=True)
class FigureImage:
    """The image of a link with three or more points: shaded like the link (``index`` in scene order)."""

    link: str
    index: int
    tips: tuple[str, ...]
    step: int


@dataclass(frozen=True)
class Figure:
    """What one polygon shows, in physical units; ``step`` numbers count from 1 over solution.steps."""

    kind: Kind
    tips: tuple[FigureTip, ...]
    vectors: tuple[FigureVector, ...]
    lines: tuple[FigureLine, ...]
    images: tuple[FigureImage, ...]
    pole_names: tuple[str, ...]


def _terms(equation: str) -> list[list[str]]:
    return [[t.strip() for t in side.split(" + ")] for side in equation.split(" = ")]


def _line_term_name(step: Step, index: int, symbol: str) -> str:
    """The name of the unknown term along the step's ``index``-th direction line, from its equation."""
    sides = _terms(step.equation)
    result = sides[0][0].partition("_")[2]
    if len(sides) > index + 1:
        terms = sides[index + 1]
        if terms[-1] != "...":
            return terms[-1]
        first = terms[0].partition("_")[2]
        return f"{symbol}_{result}/{first}"
    return f"{symbol}_{result}"


def _line_term_kind(kind: Kind, line: Line) -> Term:
    label = line.label
    if kind == "velocity":
        return "sliding" if "parallel to slider" in label else "relative"
    return "tangential" if label.startswith("a^t") else "sliding"


def _step_tips(step: Step) -> list[str]:
    if step.kind in ("read", "coriolis"):
        return []
    return [name.strip() for name in step.result.split(",")]


def polygon_figure(solution: Solution, kind: Kind) -> Figure:
    """What the polygon of ``kind`` shows and when each part appears, from the construction steps."""
    polygon = solution.velocity if kind == "velocity" else solution.acceleration
    assert polygon is not None
    symbol = "v" if kind == "velocity" else "a"
    mech = solution.mechanism
    ground_points = set(mech.scene.link(mech.ground).point_names) if mech.ground else set()
    size = max([norm(v) for v in polygon.tips.values()] + [1e-300])
    by_lower = {label.lower(): label for label in polygon.tips}
    tip_step: dict[str, int] = {}
    vectors: list[FigureVector] = []
    lines: list[FigureLine] = []
    seen: set[tuple[str, Vec, Vec]] = set()
    for number, step in enumerate(solution.steps, 1):
        if step.polygon != kind:
            continue
        for name in _step_tips(step):
            if name in by_lower and by_lower[name] not in tip_step:
                tip_step[by_lower[name]] = number
        drawn = list(step.vectors)
        for v in drawn:
            key = (v.label, v.start, v.end)
            if key not in seen:
                seen.add(key)
                vectors.append(FigureVector(v.label, v.start, v.end, v.term, number))
        if step.kind == "intersection" and step.value:
            value = (step.value[0], step.value[1])
            for k, line in enumerate(step.lines):
                name = _line_term_name(step, k, symbol)
                key = (name, line.through, value)
                if key not in seen:
                    seen.add(key)
                    vectors.append(FigureVector(name, line.through, value, _line_term_kind(kind, line), number))
        if step.kind in ("intersection", "image", "proportional"):
            lines += [FigureLine(line, number) for line in step.lines]
    pole_names = tuple(sorted(label for label in polygon.tips if label in ground_points
                              and norm(polygon.tips[label]) <= _SAME * size))
    tips = tuple(FigureTip(label, value, tip_step.get(label, 0)) for label, value in polygon.tips.items()
                 if label not in pole_names)
    tip_steps = {t.label: t.step for t in tips}
    vectors = _with_absolutes(vectors, tips, symbol, size)
    images = []
    for link, members in polygon.members.items():
        if link == mech.ground:
            continue
        labels = tuple(dict.fromkeys(label for label, _ in members))
        if len(labels) >= 3:
            images.append(FigureImage(link, mech.link_names.index(link), labels,
                                      max(tip_steps.get(label, 0) for label in labels)))
    return Figure(kind, tips, tuple(vectors), tuple(lines), tuple(images), pole_names)


def _with_absolutes(vectors: list[FigureVector], tips: tuple[FigureTip, ...], symbol: str,
                    size: float) -> list[FigureVector]:
    """Add o -> tip for every tip; where a term vector already runs from the pole to that tip, name it so."""
    out = list(vectors)
    for tip in tips:
        absolute = f"{symbol}_{tip.label}"
        same = [k for k, v in enumerate(out) if norm(v.start) <= _SAME * size and norm(sub(v.end, tip.value)) <= _SAME * size]
        if not same:
            out.append(FigureVector(absolute, (0.0, 0.0), tip.value, "absolute", tip.step))
            continue
        for k in same:
            v = out[k]
            if v.term == "sliding" or (v.term == "relative" and symbol == "v"):
                out[k] = FigureVector(absolute, v.start, v.end, "absolute", v.step)
            elif v.label != absolute and not v.label.startswith(absolute + " ="):
                out[k] = FigureVector(f"{absolute} = {v.label}", v.start, v.end, v.term, v.step)
    unique: list[FigureVector] = []  # coincident tips (gears rolling) name one arrow, drawn once
    for v in out:
        if not any(u.label == v.label and u.start == v.start and u.end == v.end for u in unique):
            unique.append(v)
    return unique


def figure_box(figure: Figure) -> tuple[float, float, float, float]:
    """Bounding box of every drawn point of the figure (physical units), the pole included."""
    points: list[Vec] = [(0.0, 0.0), *(t.value for t in figure.tips)]
    for v in figure.vectors:
        points += [v.start, v.end]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    return (min(xs), min(ys), max(xs), max(ys))


def _labelled_runs(label: str, size: float) -> tuple[Run, ...]:
    """Runs of a vector name, or of ``a_A = a^n_A/A0`` (two names joined by =)."""
    parts = label.split(" = ")
    runs: list[Run] = []
    x = 0.0
    for k, part in enumerate(parts):
        if k:
            runs.append(Run(" = ", x, 0.0, size))
            x += text_width(" = ", size)
        piece = vector_runs(part, size)
        runs += [Run(r.text, r.dx + x, r.dy, r.size) for r in piece]
        x = max(r.dx + text_width(r.text, r.size) for r in runs)
    return tuple(runs)


def _clip_line(line: Line, panel: Panel, area: object) -> list[tuple[Point, Point]]:
    from shapely.geometry import LineString

    through = panel.paper(line.through)
    d = line.direction
    n = norm(d)
    if n == 0.0:
        return []
    reach = 4.0 * max(panel.rect[2] - panel.rect[0], panel.rect[3] - panel.rect[1])
    u = (d[0] / n, d[1] / n)
    long = LineString([(through[0] - reach * u[0], through[1] - reach * u[1]),
                       (through[0] + reach * u[0], through[1] + reach * u[1])])
    piece = long.intersection(area)
    parts = getattr(piece, "geoms", [piece])
    out = []
    for part in parts:
        if part.geom_type == "LineString" and part.length > 0.5:
            coords = list(part.coords)
            out.append(((float(coords[0][0]), float(coords[0][1])), (float(coords[-1][0]), float(coords[-1][1]))))
    return out


def neighbourhood(figure: Figure, panel: Panel) -> object:
    """Where direction lines are drawn: the polygon's hull, grown, inside the panel."""
    from shapely.geometry import MultiPoint, box

    points = [panel.paper(p) for p in [(0.0, 0.0), *(t.value for t in figure.tips)]]
    points += [panel.paper(p) for v in figure.vectors for p in (v.start, v.end)]
    hull = MultiPoint(points).convex_hull
    extent = max(hull.bounds[2] - hull.bounds[0], hull.bounds[3] - hull.bounds[1])
    grown = hull.buffer(max(6.0, 0.12 * extent))
    return grown.intersection(box(*panel.drawing_rect))


@functools.lru_cache(maxsize=32)
def _direction_segments(figure: Figure, panel: Panel) -> tuple[tuple[tuple[Point, Point], ...], ...]:
    """Each direction line of ``figure`` clipped to where it is drawn (``neighbourhood``): made once per
    figure and panel, however many step sheets and handout pages draw it."""
    area = neighbourhood(figure, panel)
    return tuple(tuple(_clip_line(fl.line, panel, area)) for fl in figure.lines)


def polygon_items(figure: Figure, panel: Panel, upto: int | None = None) -> tuple[list[Item], list[Request]]:
    """Draw ``figure`` to ``panel``'s scale: everything of steps <= ``upto`` (all when None), the
    elements of step ``upto`` highlighted."""
    layer = f"{figure.kind}-polygon"
    prime = figure.kind == "acceleration"
    shown = (lambda step: True) if upto is None else (lambda step: step <= upto)
    current = (lambda step: False) if upto is None else (lambda step: step == upto)
    halos: list[Item] = []
    items: list[Item] = []
    requests: list[Request] = []
    region = panel.drawing_rect
    tips = {t.label: t for t in figure.tips}
    for image in figure.images:
        if not shown(image.step):
            continue
        corners = _ring(tuple(panel.paper(tips[label].value) if label in tips else panel.origin
                              for label in image.tips))
        if _area(corners) < 0.02 * max(_span(corners) ** 2, 1e-12):
            continue
        color = link_color(image.index)
        items.append(Path(corners, Stroke(color, 0.15), fill=color, fill_opacity=0.45, closed=True,
                          role=f"image {image.link}"))
    for fl, segments in zip(figure.lines, _direction_segments(figure, panel), strict=True):
        if not shown(fl.step):
            continue
        for a, b in segments:
            items.append(Path((a, b), DIRECTION_LINE, role=f"direction {fl.line.label}"))
            if current(fl.step):
                halos.append(Path((a, b), HALO, role="highlight"))
    dots: list[Item] = []
    tiny: dict[tuple[float, float], list[tuple[str, str]]] = {}
    """The vectors too short to draw, by where they end: named in one label there (with the tip's, if one is)."""
    for v in figure.vectors:
        if not shown(v.step):
            continue
        start, end = panel.paper(v.start), panel.paper(v.end)
        length = math.hypot(end[0] - start[0], end[1] - start[1])
        color = TERM_COLORS[v.term]
        runs = _labelled_runs(v.label, LABEL_MM)
        if length == 0.0 or norm(sub(v.end, v.start)) == 0.0:
            continue
        if length < TINY_FACTOR * HEAD_LENGTH_MM * 1.5:
            dots.append(Circle(end, 0.55, None, fill=color, role=f"vector {v.label}"))
            tiny.setdefault(_spot(end), []).append((v.label, color))
        else:
            items.append(Arrow(start, end, color, VECTOR_WIDTH_MM, HEAD_LENGTH_MM, HEAD_HALF_WIDTH_MM,
                               role=f"vector {v.label}"))
            requests.append(Request(layer, region, runs, start, end, color=color, role=f"vector {v.label}",
                                    priority=4))
        if current(v.step):
            halos.append(Path((start, end), HALO, role="highlight"))
    items += dots
    pole = panel.paper((0.0, 0.0))
    items.append(Circle(pole, 0.8, Stroke("#000000", 0.25), fill="#ffffff", role="pole"))
    pole_label = ", ".join(["o", *(name.lower() for name in figure.pole_names)])
    requests.append(Request(layer, region, _with_vectors(_joined_tip_runs(["o", *figure.pole_names], prime),
                                                         tiny.pop(_spot(pole), [])), pole,
                            role=f"tip {pole_label}", priority=3, gap=0.8))
    groups: dict[tuple[float, float], list[FigureTip]] = {}
    for tip in figure.tips:
        if shown(tip.step):
            p = panel.paper(tip.value)
            groups.setdefault((round(p[0], 2), round(p[1], 2)), []).append(tip)
    for group in groups.values():
        p = panel.paper(group[0].value)
        if math.hypot(p[0] - pole[0], p[1] - pole[1]) < 0.05:
            continue
        items.append(Circle(p, 0.45, None, fill="#000000", role=f"tip {group[0].label.lower()}"))
        if any(current(t.step) for t in group):
            halos.append(Circle(p, 1.8, None, fill=HALO.color, role="highlight"))
        runs = _with_vectors(_joined_tip_runs([t.label for t in group], prime), tiny.pop(_spot(p), []))
        requests.append(Request(layer, region, runs, p, role="tip " + ", ".join(t.label.lower() for t in group),
                                priority=3, gap=0.6))
    for spot, named in tiny.items():
        label = ", ".join(name for name, _ in named)
        requests.append(Request(layer, region, _with_vectors((), named), spot, color=named[0][1],
                                role=f"vector {label}", priority=3, gap=0.6))
    return halos + items, requests


def _spot(p: Point) -> tuple[float, float]:
    """Where a tip or a short vector's end is drawn, to a hundredth of a millimetre (one spot, one label)."""
    return (round(p[0], 2), round(p[1], 2))


def _with_vectors(runs: tuple[Run, ...], named: list[tuple[str, str]]) -> tuple[Run, ...]:
    """A tip's runs followed by the names of the short vectors ending there: ``a′, a_A, a^n_A/A0``."""
    out = list(runs)
    x = max((r.dx + text_width(r.text, r.size) for r in out), default=0.0)
    for name, _ in named:
        if out:
            out.append(Run(", ", x, 0.0, LABEL_MM))
            x += text_width(", ", LABEL_MM)
        out += [Run(r.text, r.dx + x, r.dy, r.size) for r in _labelled_runs(name, LABEL_MM)]
        x = max(r.dx + text_width(r.text, r.size) for r in out)
    return tuple(out)


def _area(points: tuple[Point, ...]) -> float:
    return abs(sum(points[k - 1][0] * p[1] - p[0] * points[k - 1][1] for k, p in enumerate(points))) / 2


def _span(points: tuple[Point, ...]) -> float:
    return diameter(points)


def _joined_tip_runs(labels: list[str], prime: bool) -> tuple[Run, ...]:
    runs: list[Run] = []
    x = 0.0
    for k, label in enumerate(labels):
        if k:
            runs.append(Run(", ", x, 0.0, LABEL_MM))
            x += text_width(", ", LABEL_MM)
        piece = tip_runs(label, LABEL_MM, prime)
        runs += [Run(r.text, r.dx + x, r.dy, r.size) for r in piece]
        x = max(r.dx + text_width(r.text, r.size) for r in runs)
    return tuple(runs)


def _ring(points: tuple[Point, ...]) -> tuple[Point, ...]:
    """The points in counter-clockwise order about their centroid (a simple polygon)."""
    cx = sum(p[0] for p in points) / len(points)
    cy = sum(p[1] for p in points) / len(points)
    return tuple(sorted(points, key=lambda p: math.atan2(p[1] - cy, p[0] - cx)))
