"""Randomised versions of a problem, each assemblable, well away from singular positions, with its key.

A variant draws, from :class:`~kinepoly.homework.vary.Ranges`, a factor for each link's
dimensions (the link's points and the slide lines it carries, scaled about its own origin) and
the input values, all rounded to numbers a student can draw. It is kept only if

* the mechanism assembles there in the *same assembly* as the original (the open four-bar stays
  open): every velocity construction of a dyad crosses its two direction lines with the same
  orientation as in the original; where a direct solve lands in the other assembly, the variant
  is reached by moving every number step by step from the original, each step starting from
  the last one's pose, and dropped if that path meets a dead point;
* every dyad's transmission angle (the acute angle between the two direction lines that give
  its middle joint: for a four-bar the angle between coupler and rocker, for a slider-crank
  between the coupler's normal and the slide) is at least ``min_transmission_deg``;
  a group without a two-line construction (a triad) has a velocity Jacobian whose condition
  number is at most ten times the original's;
* its solve carries no near-singular warning and its cross-check is clean.

The draws are judged a batch at a time through the family engine (``sweep.family.member_placer``: every draw a
member at its own input, the plan run once for all), in as few engine calls as the mechanism has dyads, plus one;
a draw is solved alone, by the path above, only where a direct solve would land it in the other assembly, or the
two assemblies weigh alike (``_judged``). Scenes with cams, gears or groups solved by Newton's method, which a
family does not run in one batch, are judged draw by draw by that path. Either way the same draws are kept.

Cams and gears are drawn and written as the user wrote them (``homework.higher_pairs``): a pair's
lengths take the factor of the link that carries them, and with gears every link takes the same one
(``GEARS_NOTE``), so that each pair's centre distance stays the sum (difference) of its radii.

Each variant is written as TOML with a ``[guess]`` of every moving point, so it is pinned to
that assembly, and read back and solved again: its answer key is taken from that solve, in the
canonical forms, so ``kinepoly check`` of a variant against its own key passes. The same seed
gives the same variants (Python's Mersenne Twister, one draw order).
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable
from pathlib import Path
from typing import Literal

import numpy as np
from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.dyad_assembly import guess_distances
from kinepoly.engine.groups import Dyad
from kinepoly.engine.transmission import transmission_angles
from kinepoly.errors import AssemblyError, KinepolyError, SceneError
from kinepoly.geom.tolerances import SAME_REL, TRACKED_REL
from kinepoly.geom.vec import norm, unit
from kinepoly.homework.answers import AnswerKey, Value
from kinepoly.homework.higher_pairs import (
    as_written,
    pair_extra_digits,
    pair_lengths,
    pair_owners,
    solvable,
    with_pair_lengths,
)
from kinepoly.homework.reference import asked_keys, values_of
from kinepoly.homework.toml_out import answers_toml, scene_toml
from kinepoly.homework.vary import Range, Ranges
from kinepoly.present.clean import roundoff, tidy
from kinepoly.scene.loader import loads_scene
from kinepoly.scene.reader_state import polar_point
from kinepoly.scene.spec import GivenInput, LinkInput, LinkSpec, PointSpec, Scene
from kinepoly.solution import Solution, solve
from kinepoly.sweep.family import Dimensions, MemberPlacer, member_placer

__all__ = ["DEFAULT_MIN_TRANSMISSION_DEG", "GEARS_NOTE", "Variant", "make_variants"]

DEFAULT_MIN_TRANSMISSION_DEG = 30.0
GEARS_NOTE = ("With gears every link takes the same factor (two decimals, 1 where the links' ranges share none), "
              "so that each pair's centres stay r2 + r3 (internal: |r2 - r3|) apart.")
_DRAWS_PER_VARIANT = 60
_STEP_DEG = 15.0  # the largest turn of the input per step of a path
_STEP_FACTOR = 0.05  # the largest relative change of a length per step
_CONDITION_GROWTH = 10.0
_TRACKED = TRACKED_REL  # a read-back variant's points lie this close (relative to its size) to the tracked pose
_LEAST_BATCH = 8  # the fewest draws judged together by the family engine
_ANGLE_MARGIN_DEG = 1e-6  # a transmission angle this close to the least is left to the solve to judge
_WEIGH_MARGIN = 1e-9
"""Two assemblies whose guessed points' squared distances differ by less than this times the square of (four times)
their reach are left to the solve to weigh (it weighs them alike within 1e-12 of a smaller square)."""

Vec = tuple[float, float]
Guess = tuple[tuple[str, Vec], ...]
"""Moving points where they are, by name: a variant's ``[guess]`` before rounding."""
Verdict = Guess | Literal[False] | None
"""A draw judged by the family: rejected (False), reached there (``Guess``), or left to the path of solves (None)."""


class Variant(Struct, frozen=True):
    """One variant: its name, scene and answer-key texts, and what makes it a good problem."""

    name: str
    scene_text: str
    answers_text: str
    scene: Scene
    answers: tuple[tuple[AnswerKey, Value], ...]
    min_transmission_deg: float | None


class _Numbers(Struct, frozen=True):
    """What a variant changes: every link's point coordinates, every slide's ``through``, the input values."""

    points: tuple[tuple[Vec, ...], ...]
    through: tuple[Vec, ...]
    inputs: tuple[tuple[str, float], ...]
    pairs: tuple[float, ...] = ()
    """The lengths the cams and gears carry (``homework.higher_pairs.pair_lengths``)."""


def _numbers(scene: Scene) -> _Numbers:
    inp = scene.input
    names = ("angle_rad", "omega", "alpha") if isinstance(inp, LinkInput) else ("s", "s_dot", "s_ddot")
    return _Numbers(tuple(tuple(p.local for p in link.points) for link in scene.links),
                    tuple(s.through for s in scene.sliders),
                    tuple((name, float(getattr(inp, name))) for name in names), pair_lengths(scene))


def _mix(a: Vec, b: Vec, t: float) -> Vec:
    return (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))


def _between(start: _Numbers, end: _Numbers, t: float, turn: float) -> _Numbers:
    """The numbers a fraction ``t`` of the way; the input angle turns by ``turn`` radians in all."""
    if t >= 1.0:
        return end
    inputs = tuple((name, a + t * (turn if name == "angle_rad" else b - a))
                   for (name, a), (_, b) in zip(start.inputs, end.inputs, strict=True))
    return _Numbers(tuple(tuple(_mix(p, q, t) for p, q in zip(ps, qs, strict=True))
                          for ps, qs in zip(start.points, end.points, strict=True)),
                    tuple(_mix(p, q, t) for p, q in zip(start.through, end.through, strict=True)), inputs,
                    tuple(a + t * (b - a) for a, b in zip(start.pairs, end.pairs, strict=True)))


def _as_polar(point: PointSpec, xy: Vec) -> tuple[float, float] | None:
    """A point the scene writes in polar form keeps it: its new radius (the drawn one, to roundoff) at its angle."""
    if point.polar is None:
        return None
    r = math.hypot(*xy)
    return (tidy(r, roundoff(r, 8.0)), point.polar[1])


def _written_scene(base: Scene, numbers: _Numbers, guess: tuple[tuple[str, Vec], ...],
                   title: str | None = None) -> Scene:
    """The variant as it is written: ``base`` (as the user wrote it, cams and gears too) with ``numbers``."""
    links = tuple(LinkSpec(link.name, tuple(PointSpec(p.name, xy, p.line, _as_polar(p, xy))
                                            for p, xy in zip(link.points, coords, strict=True)),
                           link.line) for link, coords in zip(base.links, numbers.points, strict=True))
    sliders = tuple(replace(s, through=xy) for s, xy in zip(base.sliders, numbers.through, strict=True))
    points = {p.name for link in base.links for p in link.points}
    return with_pair_lengths(replace(
        base, links=links, sliders=sliders, guess=tuple((name, at) for name, at in guess if name in points),
        title=title or base.title, input=replace(base.input, **dict(numbers.inputs))),
        numbers.pairs)


def _scene(base: Scene, numbers: _Numbers, guess: tuple[tuple[str, Vec], ...]) -> Scene:
    """The variant as it is solved: its cams replaced by their equivalent links."""
    return solvable(_written_scene(base, numbers, guess))


# --------------------------------------------------------------------------------------------
# Drawing the numbers


def _size(scene: Scene) -> float:
    lengths = [math.hypot(*p.local) for link in scene.links for p in link.points]
    lengths += [math.hypot(*s.through) for s in scene.sliders] + [abs(x) for x in pair_lengths(scene)]
    return max(lengths, default=0.0) or 1.0


def _rounder(exponent: int) -> Callable[[float], float]:
    """Round to a multiple of 10^exponent (by decimal places, so 0.3 stays 0.3)."""
    return lambda x: round(x, -exponent) + 0.0 if exponent < 0 else float(round(x / 10**exponent) * 10**exponent)


def _length_exponent(scene: Scene) -> int:
    """Lengths are rounded to 10^e of the scene's unit: about 60 to 600 steps across the mechanism."""
    return round(math.log10(_size(scene)) - 2.3)


def _value_exponent(drawn: Range) -> int:
    largest = max(abs(drawn.low), abs(drawn.high))
    return math.floor(math.log10(largest)) - 1 if largest > 0 else 0


def _factors(rng: random.Random, scene: Scene, ranges: Ranges) -> dict[str, float]:
    """A factor per link; with gears one for all (of two decimals, in every link's range, 1 if there is
    none), so that the pairs' centre distances stay r2 + r3 (|r2 - r3|)."""
    if not scene.gears:
        return {link.name: rng.uniform(ranges.factors[link.name].low, ranges.factors[link.name].high)
                for link in scene.links}
    low = math.ceil(100 * max(r.low for r in ranges.factors.values()) - SAME_REL) / 100
    high = math.floor(100 * min(r.high for r in ranges.factors.values()) + SAME_REL) / 100
    factor = round(rng.uniform(low, high), 2) if low <= high else 1.0
    return {link.name: factor for link in scene.links}


def _length_rounder(scene: Scene, extra_digits: int = 0) -> Callable[[float], float]:
    """Lengths to a grid a student can draw (``extra_digits`` finer); with gears the scaled lengths exactly (a
    factor of two decimals times the scene's), so that a sum of radii stays the distance it was."""
    if scene.gears:
        return lambda x: float(f"{x:.12g}") + 0.0
    return _rounder(_length_exponent(scene) - extra_digits)


def _drawn_point(point: PointSpec, factor: float, length: Callable[[float], float]) -> Vec:
    """A point's coordinates times ``factor``, each rounded by ``length``; a polar point's radius rounded, its
    angle kept (a coupler point written { polar = [60, 20] } stays at 20 degrees)."""
    if point.polar is not None:
        return polar_point(length(factor * point.polar[0]), point.polar[1])
    return (length(factor * point.local[0]), length(factor * point.local[1]))


def _draw(rng: random.Random, scene: Scene, ranges: Ranges) -> _Numbers:
    length = _length_rounder(scene)
    factors = _factors(rng, scene, ranges)
    points = tuple(tuple(_drawn_point(p, factors[link.name], length) for p in link.points) for link in scene.links)
    through = tuple((length(factors[s.guide] * s.through[0]), length(factors[s.guide] * s.through[1]))
                    for s in scene.sliders)
    inputs = []
    for name, value in _numbers(scene).inputs:
        drawn = ranges.inputs.get(name, Range(value, value))
        x = rng.uniform(drawn.low, drawn.high)
        if name == "angle_rad":
            x = math.radians(round(math.degrees(x))) if scene.units.angle == "deg" else round(x, 2)
        elif name == "s":
            x = length(x)
        else:
            x = _rounder(_value_exponent(drawn))(x)
        inputs.append((name, x + 0.0))  # never -0.0
    pairs = tuple(_length_rounder(scene, extra)(factors[owner] * x) for owner, x, extra in
                  zip(pair_owners(scene), pair_lengths(scene), pair_extra_digits(scene), strict=True))
    return _Numbers(points, through, tuple(inputs), pairs)


# --------------------------------------------------------------------------------------------
# Judging a solved variant


class _Solved(Struct, frozen=True):
    solution: Solution

    @property
    def crossings(self) -> dict[str, float]:
        """Each dyad's velocity intersection: the signed sine of the angle from its first line to its second
        (a triad's construction lines are not transmission angles of a dyad and are left out)."""
        out = {}
        for step in self.solution.steps:
            triad = any(key == "triad" for key, _ in step.params) or step.topic == "assur-tip"
            if step.polygon == "velocity" and step.kind == "intersection" and len(step.lines) == 2 and not triad:
                (a, b), (c, d) = (unit(line.direction) if norm(line.direction) > 0 else (0.0, 0.0)
                                  for line in step.lines)
                out[step.result] = a * d - b * c
        return out

    @property
    def signature(self) -> tuple[tuple[str, bool], ...]:
        return tuple(sorted((name, sine > 0) for name, sine in self.crossings.items()))

    @property
    def min_transmission_deg(self) -> float | None:
        sines = [abs(s) for s in self.crossings.values()]
        return math.degrees(math.asin(min(1.0, min(sines)))) if sines else None

    @property
    def has_linear_solve(self) -> bool:
        return any(step.kind == "linear-solve" for step in self.solution.steps)

    @property
    def condition(self) -> float:
        return float(self.solution.check.condition_number)

    def guess(self) -> Guess:
        """Every point of a moving, solved link (but not of the frame), where it is."""
        scene, pose = self.solution.scene, self.solution.pose
        frame = set(scene.link(scene.ground).point_names) if scene.ground else set()
        names = [p.name for link in scene.links if link.name != scene.ground and link.name in pose.links
                 for p in link.points if p.name not in frame]
        return tuple((name, self.solution.position(name)) for name in dict.fromkeys(names))


def _solved(scene: Scene) -> _Solved | None:
    try:
        solution = solve(scene)
    except KinepolyError:
        return None
    return _Solved(solution)


def _is_good(solved: _Solved, original: _Solved, min_transmission_deg: float) -> bool:
    codes = {notice.code for notice in solved.solution.notices}
    if codes & {"near-singular", "check-failed"} or solved.signature != original.signature:
        return False
    transmission = solved.min_transmission_deg
    if transmission is not None and transmission < min_transmission_deg:
        return False
    return not solved.has_linear_solve or solved.condition <= _CONDITION_GROWTH * max(original.condition, 1.0)


def _steps(start: _Numbers, end: _Numbers, turn: float) -> int:
    worst = abs(math.degrees(turn)) / _STEP_DEG
    for ps, qs in zip(start.points, end.points, strict=True):
        for p, q in zip(ps, qs, strict=True):
            size = max(math.hypot(*p), math.hypot(*q))
            if size > 0:
                worst = max(worst, math.dist(p, q) / size / _STEP_FACTOR)
    for (name, a), (_, b) in zip(start.inputs, end.inputs, strict=True):
        if name != "angle_rad" and max(abs(a), abs(b)) > 0:
            worst = max(worst, abs(b - a) / max(abs(a), abs(b)) / (2 * _STEP_FACTOR))
    return max(2, math.ceil(worst))


def _track(base: Scene, start: _Numbers, end: _Numbers, original: _Solved, turn: float) -> _Solved | None:
    """Move every number from ``start`` to ``end`` in small steps, each solved from the last pose."""
    count = _steps(start, end, turn)
    solved = original
    for k in range(1, count + 1):
        step = _solved(_scene(base, _between(start, end, k / count, turn), solved.guess()))
        if step is None or step.signature != original.signature:
            return None
        solved = step
    return solved


def _reach(base: Scene, start: _Numbers, end: _Numbers, original: _Solved) -> _Solved | None:
    """The variant ``end`` in the original's assembly: directly if that lands there, else along a path."""
    if not original.has_linear_solve:
        direct = _solved(_scene(base, end, original.guess()))
        if direct is None:
            return None  # dyads in closed form: what does not close here closes on no path either
        if direct.signature == original.signature:
            return direct
    turn = 0.0
    angles = [value for name, value in zip((n for n, _ in start.inputs), (v for _, v in end.inputs), strict=True)
              if name == "angle_rad"]
    if angles:
        turn = math.remainder(angles[0] - dict(start.inputs)["angle_rad"], 2.0 * math.pi)
    for way in (turn, turn - math.copysign(2.0 * math.pi, turn)) if turn else (turn,):
        tracked = _track(base, start, end, original, way)
        if tracked is not None:
            return tracked
    return None


# --------------------------------------------------------------------------------------------
# Judging many draws at once, through the family engine


class _Family(Struct, frozen=True, eq=False):
    """What judging a scene's draws as one family needs: the placer of its members (``sweep.family``), the dyads
    of its plan, and the original's moving points (a direct solve's ``[guess]``) by name, in the solve's order."""

    placer: MemberPlacer
    dyads: tuple[Dyad, ...]
    guess: tuple[tuple[str, Vec], ...]


def _family(scene: Scene, original: _Solved) -> _Family | None:
    """The family engine's judge of ``scene``'s draws; None where it cannot judge them: cams, gears, groups solved
    by Newton's method, or a dyad whose velocity construction the original's solve does not show (its assembly
    and transmission angle are then none of the variant's checks)."""
    if original.has_linear_solve:
        return None
    placer = member_placer(scene, frozenset(original.solution.pose.links))
    if placer is None:
        return None
    dyads = tuple(group for group in placer.plan.groups if isinstance(group, Dyad))
    if len(dyads) != len(original.crossings):
        return None
    return _Family(placer, dyads, original.guess())


def _dimensions(base: Scene, batch: list[_Numbers]) -> Dimensions:
    """The draws' link points and slide lines as one family, a member a draw."""
    points = {(link.name, p.name): np.array([numbers.points[i][j] for numbers in batch], np.float64)
              for i, link in enumerate(base.links) for j, p in enumerate(link.points)}
    slides = {s.name: np.array([numbers.through[i] for numbers in batch], np.float64)
              for i, s in enumerate(base.sliders)}
    return Dimensions(points, slides, len(batch))


def _judged(family: _Family, base: Scene, batch: list[_Numbers], min_transmission_deg: float) -> list[Verdict]:
    """Each draw of ``batch`` judged as the path of solves (``_reach``) would judge it, in a few engine calls.

    Every draw is placed at its own input in the original's assembly (each dyad on the original's label, the
    family's ``FamilyContinuity``); and, once per dyad, with that dyad alone on its other label. A direct solve
    from the original's pose (``_reach``'s first) weighs a dyad's two assemblies by how near their guessed points
    lie to that pose (``guess_distances``) and takes the nearer. So a draw is

    * rejected (False) where it does not close in the original's assembly, or a transmission angle there is below
      ``min_transmission_deg``: no solve reaches it in the original's assembly (its crossings' signs are the
      labels), or the one that does fails the angle;
    * reached (its moving points) where, dyad after dyad, the original's assembly is clearly the nearer: the
      direct solve lands there;
    * left to the path of solves (None) where the two weigh nearly alike or the other is nearer.

    What the solve of the written variant checks (notices, every angle, the pose) is checked after, as for any.
    """
    placer = family.placer
    dimensions = _dimensions(base, batch)
    inputs = np.array([numbers.inputs[0][1] for numbers in batch], np.float64)
    found = placer.place(dimensions, inputs)
    rejected = ~found.ok
    for transmission in transmission_angles(found, placer.plan):
        rejected |= np.degrees(transmission.angle) < min_transmission_deg - _ANGLE_MARGIN_DEG
    guess = dict(family.guess)
    far = max((math.hypot(*xy) for _, xy in family.guess), default=0.0)
    unsure = np.zeros(len(batch), np.bool_)
    for dyad in family.dyads:
        if dyad.one_assembly:
            continue  # nothing to choose
        other = placer.place(dimensions, inputs, frozenset({dyad.name}))
        mine = guess_distances(guess, found.mechanism, {link: found.poses[link] for link in dyad.links})
        theirs = guess_distances(guess, other.mechanism, {link: other.poses[link] for link in dyad.links})
        scale = 4.0 * (far + np.sqrt(mine) + np.sqrt(theirs))
        unsure |= ~(mine + _WEIGH_MARGIN * scale * scale < theirs)
    verdicts: list[Verdict] = []
    for k in range(len(batch)):
        if rejected[k]:
            verdicts.append(False)
        elif unsure[k]:
            verdicts.append(None)
        else:
            verdicts.append(tuple((name, (float(found.point(name)[k].real), float(found.point(name)[k].imag)))
                                  for name, _ in family.guess))
    return verdicts


# --------------------------------------------------------------------------------------------
# The variants


def _key(solved: _Solved) -> tuple[tuple[AnswerKey, Value], ...]:
    values = values_of(solved.solution)
    return tuple((key, values[key]) for key in asked_keys(values))


def _same_pose(first: _Solved, reached: Guess, size: float) -> bool:
    points = dict(first.guess())
    return all(math.dist(points[name], spot) <= _TRACKED * size for name, spot in reached if name in points)


def _written(base: Scene, name: str, index: int, numbers: _Numbers, reached: Guess,
             header: str, original: _Solved, min_transmission_deg: float) -> Variant | None:
    """The variant ``numbers`` written with ``reached`` (its moving points where it is reached, in the original's
    assembly) as its ``[guess]``, read back and solved: None unless that solve is good and in the same pose."""
    spot = _rounder(_length_exponent(base) - 1)
    guess = tuple((point, (spot(x), spot(y))) for point, (x, y) in reached)
    title = f"{base.title} (variant {index})"
    text = scene_toml(_written_scene(base, numbers, guess, title), header)
    scene = loads_scene(text, f"{name}.toml")
    again = _solved(scene)
    if again is None or not _is_good(again, original, min_transmission_deg) or not _same_pose(
            again, reached, _size(scene)):
        return None
    answers = _key(again)
    key_header = (f"Answer key of {name}.toml (canonical forms; check with: kinepoly check {name}.toml "
                  f"{name}.answers.toml)")
    return Variant(name, text, answers_toml(answers, scene.units, key_header), scene, answers,
                   again.min_transmission_deg)


def make_variants(scene: Scene, ranges: Ranges, count: int, seed: int, *, stem: str | None = None,
                  min_transmission_deg: float = DEFAULT_MIN_TRANSMISSION_DEG) -> list[Variant]:
    """``count`` variants of ``scene`` drawn from ``ranges`` with ``seed``; the same arguments, the same variants.

    Raises SceneError for a ``[given]`` scene, and AssemblyError (exit 3) when the ranges do not
    give ``count`` good variants in ``60 * count`` draws (the message says how many were found).
    """
    if isinstance(scene.input, GivenInput):
        problem = (f"{scene.source}: given: variants of a [given] scene are not made (its given velocities "
                   "must stay those of a rigid body); expected a scene with an [input]")
        raise SceneError([problem])
    original = _solved(scene)
    if original is None:
        solve(scene)  # raises the error that says why
        raise AssemblyError(f"{scene.source}: the scene itself cannot be solved")  # pragma: no cover
    scene = as_written(scene)  # drawn and written with its [[cams]], not their equivalent links
    stem = stem or Path(scene.source).stem or "variant"
    width = max(2, len(str(count)))
    rng = random.Random(seed)
    start = _numbers(scene)
    family = _family(scene, original)
    seen: set[_Numbers] = set()
    variants: list[Variant] = []
    draws, limit = 0, _DRAWS_PER_VARIANT * count
    ahead: list[tuple[_Numbers, Verdict]] = []  # drawn, in the order drawn, and judged together
    while len(variants) < count and draws < limit:
        if not ahead:
            size = 1 if family is None else min(limit - draws, max(_LEAST_BATCH, 2 * (count - len(variants))))
            batch = [_draw(rng, scene, ranges) for _ in range(size)]
            ahead = list(zip(batch, [None] * size if family is None else
                             _judged(family, scene, batch, min_transmission_deg), strict=True))[::-1]
        numbers, verdict = ahead.pop()
        draws += 1
        if numbers in seen:
            continue
        seen.add(numbers)
        if verdict is False:
            continue
        reached = verdict
        if reached is None:  # the family cannot tell (or cannot run it): the path of solves from the original
            solved = _reach(scene, start, numbers, original)
            if solved is None or not _is_good(solved, original, min_transmission_deg):
                continue
            reached = solved.guess()
        index = len(variants) + 1
        name = f"{stem}-{index:0{width}d}"
        header = (f"Variant {index} of {Path(scene.source).name}, made by kinepoly variants (seed {seed}); "
                  f"its answer key is {name}.answers.toml" + (f"\n{GEARS_NOTE}" if scene.gears else ""))
        variant = _written(scene, name, index, numbers, reached, header, original, min_transmission_deg)
        if variant is not None:
            variants.append(variant)
    if len(variants) < count:
        raise AssemblyError(
            f"{scene.source}: vary: only {len(variants)} of {count} variants in {draws} draws assemble in the "
            f"original's assembly with every transmission angle at least {min_transmission_deg:g} deg; expected "
            "narrower [vary] ranges (angle, lengths) around the scene's own values, or a lower --min-transmission")
    return variants
