"""The velocity and acceleration polygons as drawn: vectors, tips, direction lines, image triangles.

``polygon_figure`` reads the construction steps (physical units, pole at 0) and says what the
polygon shows and at which step each element appears; ``FigureDrawing`` draws that to a panel's
scale once and gives each sheet what it shows up to its step, the step's new elements under a highlight. Every vector's
drawn end is exactly ``pole + k * vector``.
"""

from __future__ import annotations

import bisect
import functools
import math
import re
from typing import Literal

from msgspec import Struct

from kinepoly.engine.steps import Step, Term, term_name
from kinepoly.geom.hull import diameter
from kinepoly.geom.lines import Line
from kinepoly.geom.tolerances import PAPER_AREA_FLOOR_MM2, SAME_REL, TINY_POSITIVE
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
from kinepoly.scene.link_point import point_of
from kinepoly.solution import Solution

__all__ = ["Figure", "FigureDrawing", "FigureVector", "figure_box", "polygon_figure"]

Kind = Literal["velocity", "acceleration"]
Point = tuple[float, float]
_SAME = SAME_REL
"""Two polygon points closer than this (relative to the polygon's size) are one point."""
TINY_FACTOR = 1.0
"""A vector drawn shorter than its head times this becomes a dot with a label."""


class FigureVector(Struct, frozen=True):
    label: str
    start: Vec
    end: Vec
    term: Term
    step: int


class FigureLine(Struct, frozen=True):
    line: Line
    step: int


class FigureTip(Struct, frozen=True):
    label: str
    value: Vec
    step: int


class FigureImage(Struct, frozen=True):
    """The image of a link with three or more points: shaded like the link (``index`` in scene order)."""

    link: str
    index: int
    tips: tuple[str, ...]
    step: int


class Figure(Struct, frozen=True):
    """What one polygon shows, in physical units; ``step`` numbers count from 1 over solution.steps."""

    kind: Kind
    tips: tuple[FigureTip, ...]
    vectors: tuple[FigureVector, ...]
    lines: tuple[FigureLine, ...]
    images: tuple[FigureImage, ...]
    pole_names: tuple[str, ...]


def _line_term_name(step: Step, index: int, symbol: str) -> str:
    """The name of the unknown term along the step's ``index``-th direction line: its direction's term where the
    step says its lines as data (a triad's line toward its Assur point carries two terms), else from its equation."""
    if len(step.directions) == len(step.lines) and step.directions[index].term:
        return step.directions[index].term
    sides = step.sides
    result = _subscript(sides[0][0])
    if len(sides) > index + 1:
        terms = sides[index + 1]
        if terms[-1] != "...":
            return terms[-1]
        return f"{symbol}_{result}/{_subscript(terms[0])}"
    return f"{symbol}_{result}"


def _subscript(term: str) -> str:
    """A term's subscript (``v_B/A`` -> ``B/A``); "" for text that names no term."""
    name = term_name(term)
    return "" if name is None else name.subscript


_ROLLING_TOPICS = ("rolling", "planet-centre")
"""Steps whose second line carries a relative term of two bodies rolling (pitch points, a planet's centre), not
a block's sliding."""


def _line_term_kind(kind: Kind, step: Step, line: Line, name: str) -> Term:
    label = line.label
    if kind == "velocity":
        return "sliding" if "parallel to slider" in label else "relative"
    if name.startswith("a^t") or label.startswith("a^t"):
        return "tangential"
    return "relative" if step.topic in _ROLLING_TOPICS else "sliding"


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
    size = max([norm(v) for v in polygon.tips.values()] + [TINY_POSITIVE])
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
                    vectors.append(FigureVector(name, line.through, value, _line_term_kind(kind, step, line, name),
                                                number))
        if step.kind in ("intersection", "image", "proportional"):
            lines += [FigureLine(line, number) for line in step.lines]
    pole_names = tuple(sorted(label for label in polygon.tips if label in ground_points
                              and norm(polygon.tips[label]) <= _SAME * size))
    tips = tuple(FigureTip(label, value, tip_step.get(label, tip_step.get(point_of(label), 0)))
                 for label, value in polygon.tips.items() if label not in pole_names)  # B@3 found with b, where
    # no step names it (a driven joint's carrier under its pin: the tip less the drive's term)
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
        same = [k for k, v in enumerate(out)
                if norm(v.start) <= _SAME * size and norm(sub(v.end, tip.value)) <= _SAME * size]
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
    """Runs of a vector name, or of ``a_A = a^n_A/A0`` (two names joined by =), or of a sum of two terms along
    one line (``a^t_B/E + a^t_S/B``)."""
    parts = re.split(r"( = | \+ )", label)
    runs: list[Run] = []
    x = 0.0
    for k, part in enumerate(parts):
        if k % 2:
            runs.append(Run(part, x, 0.0, size))
            x += text_width(part, size)
            continue
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


class FigureDrawing:
    """``figure`` drawn to ``panel``'s scale once; ``at(upto)`` gives what a sheet of step ``upto`` shows.

    Each element is drawn once with the step at which it appears (and its highlight); a sheet picks
    those of steps <= ``upto``. Only the labels that join several names at one spot (coinciding tips,
    the short vectors ending there, arrows drawn one on another) depend on which of those names are shown
    yet; each such label is made once for every set of names it shows. Equal things are one object on every
    sheet.
    """

    def __init__(self, figure: Figure, panel: Panel) -> None:
        self.figure, self.panel = figure, panel
        self._layer = f"{figure.kind}-polygon"
        self._prime = figure.kind == "acceleration"
        self._region = panel.drawing_rect
        self._images: list[tuple[int, Item]] = []
        tips = {t.label: t for t in figure.tips}
        for image in figure.images:
            corners = _ring(tuple(panel.paper(tips[label].value) if label in tips else panel.origin
                                  for label in image.tips))
            if _area(corners) < 0.02 * max(_span(corners) ** 2, PAPER_AREA_FLOOR_MM2):
                continue
            color = link_color(image.index)
            self._images.append((image.step, Path(corners, Stroke(color, 0.15), fill=color, fill_opacity=0.45,
                                                  closed=True, role=f"image {image.link}")))
        self._lines = [(fl.step, Path((a, b), DIRECTION_LINE, role=f"direction {fl.line.label}"),
                        Path((a, b), HALO, role="highlight"))
                       for fl, segments in zip(figure.lines, _direction_segments(figure, panel), strict=True)
                       for a, b in segments]
        self._vectors: list[tuple[int, Item, Request | None, Item, tuple[tuple[float, float], str, str] | None]] = []
        """Per vector drawn: its step, its arrow (or dot), its label (None for a dot), its highlight, and for a
        vector too short to draw, where it ends, its name and colour (named in the label there)."""
        for v in figure.vectors:
            start, end = panel.paper(v.start), panel.paper(v.end)
            length = math.hypot(end[0] - start[0], end[1] - start[1])
            if length == 0.0 or norm(sub(v.end, v.start)) == 0.0:
                continue
            color = TERM_COLORS[v.term]
            halo = Path((start, end), HALO, role="highlight")
            if length < TINY_FACTOR * HEAD_LENGTH_MM * 1.5:
                dot = Circle(end, 0.55, None, fill=color, role=f"vector {v.label}")
                self._vectors.append((v.step, dot, None, halo, (_spot(end), v.label, color)))
            else:
                arrow = Arrow(start, end, color, VECTOR_WIDTH_MM, HEAD_LENGTH_MM, HEAD_HALF_WIDTH_MM,
                              role=f"vector {v.label}")
                request = Request(self._layer, self._region, _labelled_runs(v.label, LABEL_MM), start, end, color=color,
                                  role=f"vector {v.label}", priority=4)
                self._vectors.append((v.step, arrow, request, halo, None))
        self._pole_point = panel.paper((0.0, 0.0))
        self._pole = Circle(self._pole_point, 0.8, Stroke("#000000", 0.25), fill="#ffffff", role="pole")
        self._tips = [(tip, panel.paper(tip.value)) for tip in figure.tips]
        self._steps = sorted({step for step, _ in self._images} | {step for step, _, _ in self._lines}
                             | {v[0] for v in self._vectors} | {tip.step for tip, _ in self._tips})
        self._made: dict[tuple[object, ...], Item | Request] = {}
        """The joined labels, tip dots and their highlights made so far, by what they show."""

    def _label(self, names: tuple[str, ...], short: tuple[tuple[str, str], ...], at: Point, gap: float) -> Request:
        """The label at a spot: the tips' names there (the pole's with ``o``), then the short vectors' ending there."""
        key = ("label", names, short, at)
        found = self._made.get(key)
        if not isinstance(found, Request):
            runs = _with_vectors(_joined_tip_runs(list(names), self._prime) if names else (), list(short))
            if names:
                role, color = "tip " + ", ".join(name.lower() for name in names), "#000000"
            else:
                role, color = "vector " + ", ".join(name for name, _ in short), short[0][1]
            found = self._made[key] = Request(self._layer, self._region, runs, at, color=color, role=role,
                                              priority=3, gap=gap)
        return found

    def _shaft_label(self, group: tuple[Request, ...]) -> Request:
        """The label of the arrows drawn one on another: the first's, or their names joined (``a_P11, a_Q11``; an
        arrow's own equal names, ``v_Q3 = v_P3``, listed so too)."""
        labels = tuple(dict.fromkeys(request.role.removeprefix("vector ") for request in group))
        if len(labels) == 1:
            return group[0]
        names = tuple(dict.fromkeys(name for label in labels for name in label.split(" = ")))
        first = group[0]
        key = ("shaft", names, first.anchor, first.end)
        found = self._made.get(key)
        if not isinstance(found, Request):
            runs = _with_vectors((), [(name, first.color) for name in names])
            found = self._made[key] = Request(self._layer, self._region, runs, first.anchor, first.end,
                                              color=first.color, role="vector " + ", ".join(names), priority=4)
        return found

    def _dot(self, tip: FigureTip, at: Point, highlight: bool) -> Item:
        """The dot of the tips at one spot, named by the first of them; or its highlight."""
        key = ("highlight" if highlight else "dot", tip.label)
        found = self._made.get(key)
        if not isinstance(found, Circle):
            found = self._made[key] = (Circle(at, 1.8, None, fill=HALO.color, role="highlight") if highlight else
                                       Circle(at, 0.45, None, fill="#000000", role=f"tip {tip.label.lower()}"))
        return found

    def stage(self, upto: int | None) -> tuple[int, bool]:
        """What ``at(upto)`` shows, as (how many of the steps that add an element it shows, whether the last of
        them is highlighted): two sheets of equal stage show the figure alike."""
        if upto is None:
            return (len(self._steps), False)
        return (bisect.bisect_right(self._steps, upto), upto in self._steps)

    def at(self, upto: int | None = None) -> tuple[list[Item], list[Request]]:
        """Everything of steps <= ``upto`` (all when None), the elements of step ``upto`` highlighted: the
        items (the highlights first) and the label requests."""
        last = math.inf if upto is None else upto
        halos: list[Item] = []
        items: list[Item] = [item for step, item in self._images if step <= last]
        for step, segment, glow in self._lines:
            if step <= last:
                items.append(segment)
                if step == upto:
                    halos.append(glow)
        requests: list[Request] = []
        dots: list[Item] = []
        tiny: dict[tuple[float, float], list[tuple[str, str]]] = {}
        """The vectors too short to draw, by where they end: named in one label there (with the tip's, if one is)."""
        shafts: dict[tuple[Point, Point], list[Request]] = {}
        """The labels of the arrows drawn, by where they start and end: arrows drawn one on another (a long chain's
        converging points) are named in one label."""
        for step, drawn, request, halo, short in self._vectors:
            if step > last:
                continue
            if request is not None:
                items.append(drawn)
                shafts.setdefault((_spot(request.anchor), _spot(request.end or request.anchor)), []).append(request)
            elif short is not None:
                dots.append(drawn)
                tiny.setdefault(short[0], []).append(short[1:])
            if step == upto:
                halos.append(halo)
        requests += [self._shaft_label(tuple(group)) for group in shafts.values()]
        items += dots
        pole = self._pole_point
        items.append(self._pole)
        names = ("o", *(name for name in self.figure.pole_names if name.lower() != "o"))  # a frame point O is the pole
        requests.append(self._label(names, tuple(tiny.pop(_spot(pole), [])), pole, 0.8))
        groups: dict[tuple[float, float], list[tuple[FigureTip, Point]]] = {}
        for tip, p in self._tips:
            if tip.step <= last:
                groups.setdefault((round(p[0], 2), round(p[1], 2)), []).append((tip, p))
        for group in groups.values():
            first, p = group[0]
            if math.hypot(p[0] - pole[0], p[1] - pole[1]) < 0.05:
                continue
            items.append(self._dot(first, p, False))
            if any(tip.step == upto for tip, _ in group):
                halos.append(self._dot(first, p, True))
            requests.append(self._label(tuple(tip.label for tip, _ in group), tuple(tiny.pop(_spot(p), [])), p, 0.6))
        for spot, ending in tiny.items():
            requests.append(self._label((), tuple(ending), spot, 0.6))
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
