"""The inputs a sweep visits: the rows shown, the seed row (the scene's own input) and the range.

Without ``--from``/``--to`` the range is a full turn of the input link, 0 to 360 degrees with
the end left out (it repeats the start), when the mechanism closes all the way round (with gears, its whole
cycle: the turns of the input after which every link is back where it started, ``_cycle``); else it
is the stretch of input around the scene's own input where it closes (a rocker's swing, a
slider's stroke), its ends found to about 1e-10 of the step by repeated subdivision (where a group
is closed by Newton's method, put inside by 1e-7 rad, or 1e-7 of the mechanism's size for a
slider, so that the end rows close when walked to: ``_newton_margin``). A slider
input that closes further than ten times the mechanism's size either way stops there, and so
does a range where a point runs off further than ten times the mechanism's size (a slider
driven toward an asymptote): both with an ``open-range`` notice.

``steps`` is the number of equal intervals the range is cut into, so that round inputs stay
round: from A to B there are ``steps + 1`` rows, both ends included (``--from 0 --to 90
--positions 90``: 91 rows 1 degree apart); a full turn (the default one, or B = A + 360
degrees) has ``steps`` rows, for its last would repeat its first (``--positions 360``: 0, 1,
..., 359).

The scene's own input is always a row, for that is where the assembly is chosen: when it is not
on the grid it is slipped in between two rows (and not shown); when it lies outside the range
the rows from it to the range are added (and not shown), so that the assembly is followed to
the range continuously.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import NamedTuple

import numpy as np
from msgspec import Struct, field

from kinepoly.engine.centrode import mechanism_size
from kinepoly.engine.groups import NewtonGroup, PositionPlan
from kinepoly.engine.policy import Continuity
from kinepoly.engine.position import Positions, solve_positions
from kinepoly.errors import AssemblyError, SceneError
from kinepoly.geom.arrays import RADIANS_PER_DEGREE, Bools, Reals, trues
from kinepoly.geom.tolerances import ANGLE_SAME_RAD, NEWTON_CLOSED_REL, ROUNDING_REL, SAME_REL
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice
from kinepoly.scene.spec import LinkInput, PitchCircle, Scene, SliderInput

__all__ = ["CYCLE_TURNS", "FULL_TURN_CHECK_ROWS", "MAX_STEPS", "DefaultRange", "InputGrid", "default_range",
           "full_turn_grid", "input_grid", "input_name", "input_unit"]

MAX_STEPS = 2_000_000
"""The most rows a sweep takes (memory grows with rows times quantities)."""

FULL_TURN_CHECK_ROWS = 3600
"""Whether the input link turns fully is judged on this many rows (or on the sweep's own, if more)."""

CYCLE_TURNS = 100
"""The most turns of the input a geared mechanism's default sweep covers to come back where it started."""

_BRIDGE_MAX = 100_000
_ZOOM = 32
_ZOOM_ROUNDS = 6
_NEWTON_EDGE = 100.0


class InputGrid(Struct, frozen=True):
    """Every row the sweep computes: the input in the scene's unit (``values``) and in radians or
    length (``internal``); ``shown`` marks the rows reported; ``seed_row`` is the scene's input."""

    values: Reals
    internal: Reals
    shown: Bools
    seed_row: int
    periodic: bool
    notices: tuple[Notice, ...] = ()
    near_dead: dict[int, str] = field(default_factory=dict)
    """Rows at an end of the range put just inside a dead point (``_newton_margin``), with their warning."""


def input_unit(scene: Scene) -> str:
    """The unit of the swept input: the scene's angle unit for a link, its length unit for a slider."""
    return scene.units.angle if isinstance(scene.input, LinkInput) else scene.units.length


def input_name(mechanism: Mechanism) -> str:
    """``theta_2`` for link 2's angle, ``theta_23`` for link 3's angle on link 2 (a motor), ``s_14`` for
    slider 14: the first column of the CSV."""
    inp = mechanism.scene.input
    if isinstance(inp, LinkInput):
        return f"theta_{inp.relative_to}{inp.link}" if inp.relative_to else f"theta_{inp.link}"
    assert isinstance(inp, SliderInput)
    return f"s_{inp.slider}"


def _seed_value(mechanism: Mechanism) -> float:
    inp = mechanism.scene.input
    if isinstance(inp, LinkInput):
        return math.degrees(inp.angle_rad) if mechanism.scene.units.angle == "deg" else inp.angle_rad
    assert isinstance(inp, SliderInput)
    return inp.s


def _full_turn(mechanism: Mechanism) -> float | None:
    if not isinstance(mechanism.scene.input, LinkInput):
        return None
    return 360.0 if mechanism.scene.units.angle == "deg" else 2.0 * math.pi


def _internal(mechanism: Mechanism, values: Reals) -> Reals:
    if isinstance(mechanism.scene.input, LinkInput) and mechanism.scene.units.angle == "deg":
        return np.multiply(values, RADIANS_PER_DEGREE)  # np.radians(values), bit for bit
    return np.asarray(values, np.float64)


def _with_seed(shown: Reals, seed: float, periodic: bool, full: float | None) -> tuple[Reals, Bools, int]:
    """Rows: ``shown`` with the seed slipped in (or bridged to), the mask of shown rows, the seed row."""
    first, last = float(shown[0]), float(shown[-1])  # the ends as plain numbers: the same arithmetic, less of numpy's
    if full is not None and not periodic:  # the same link position may lie inside the range a turn away
        low, high = min(first, last), max(first, last)
        middle = 0.5 * (low + high)
        seed = seed + full * round((middle - seed) / full)
    if periodic and full is not None:  # the turn's own copy of the seed: from the lowest row, one turn up
        low = min(first, last)
        seed = low + (seed - low) % full
    interval = float(shown[1]) - first if len(shown) > 1 else 1.0
    step = abs(interval)
    nearest = min(max(round((seed - first) / interval) if len(shown) > 1 else 0, 0),
                  len(shown) - 1)  # the rows are evenly spaced: the one nearest the seed by arithmetic
    if abs(float(shown[nearest]) - seed) <= SAME_REL * step:
        return shown, trues(len(shown)), nearest
    ascending = shown[-1] >= shown[0]
    low, high = (shown[0], shown[-1]) if ascending else (shown[-1], shown[0])
    if periodic or low < seed < high:
        ordered = shown if ascending else shown[::-1]
        at = int(np.searchsorted(ordered, seed))
        at = at if ascending else len(shown) - at
        values = np.concatenate((shown[:at], (float(seed),), shown[at:]))  # np.insert's values, a tenth of its cost
        mask = np.ones(len(values), np.bool_)
        mask[at] = False
        return values, mask, at
    first_end = abs(seed - shown[0]) <= abs(seed - shown[-1])
    end = float(shown[0] if first_end else shown[-1])
    count = min(_BRIDGE_MAX, max(1, math.ceil(abs(end - seed) / step)))
    bridge = np.linspace(seed, end, count + 1)[:-1]
    if first_end:
        return np.concatenate([bridge, shown]), np.concatenate([np.zeros(count, np.bool_),
                                                                np.ones(len(shown), np.bool_)]), 0
    values = np.concatenate([shown, bridge[::-1]])
    return values, np.concatenate([np.ones(len(shown), np.bool_), np.zeros(count, np.bool_)]), len(values) - 1


def _evaluate(mechanism: Mechanism, plan: PositionPlan, values: Reals, seed_row: int, seed: dict[str, LinkPose],
              periodic: bool, run_only: bool = False) -> Positions:
    """The positions at ``values``; ``run_only``: only the rows that close without a gap about the seed row are
    wanted (a row-by-row walk stops at the first row that does not close: a Newton group's range search solves
    its run and one row each way, not the rows beyond)."""
    return solve_positions(mechanism, plan, _internal(mechanism, values),
                           Continuity(seed_row, seed, periodic, run_only=run_only))


class _Reach(Struct, frozen=True):
    """Where the sweep may go: every point within ``radius`` of ``center`` (ten times the mechanism's size)."""

    center: complex
    radius: float

    def within(self, mechanism: Mechanism, found: Positions) -> Bools:
        """Rows that close with every point of the mechanism within reach."""
        inside = found.ok.copy()
        for link in found.poses:
            for p in mechanism.scene.link(link).points:
                distance = np.abs(np.asarray(found.world(link, p.name)) - self.center)
                inside &= np.where(np.isfinite(distance), distance, np.inf) <= self.radius
        return inside


def _reach(mechanism: Mechanism, seed: dict[str, LinkPose], size: float) -> _Reach:
    points = [pose.world(p.local) for link, pose in seed.items() for p in mechanism.scene.link(link).points]
    center = complex(sum(q[0] for q in points), sum(q[1] for q in points)) / max(len(points), 1)
    return _Reach(center, 10.0 * size)


def _geared_links(mechanism: Mechanism) -> set[str]:
    """The gears' links and the links that carry a gear on a pin at its pitch centre (a planet's arm)."""
    out: set[str] = set()
    for gear in mechanism.scene.gears:
        out.update(gear.links)
        for curve in gear.pitch:
            if isinstance(curve, PitchCircle):
                out.update(x for x in mechanism.links_of_point(curve.center))
    return out


def _turns_per_turn(mechanism: Mechanism, plan: PositionPlan, values: Reals, seed_row: int,
                    seed: dict[str, LinkPose], full: float) -> dict[str, float]:
    """How many turns each geared link (``_geared_links``) makes while the input makes one (over ``values``, a
    turn from 0, and its end): its gear ratio to the input."""
    rows = np.append(values, values[0] + full)
    found = _evaluate(mechanism, plan, rows, seed_row, seed, periodic=False)
    out = {}
    geared = _geared_links(mechanism)
    for link, pose in found.poses.items():
        if link in geared:
            angle = np.unwrap(np.angle(np.broadcast_to(pose.rotation, rows.shape)))
            out[link] = float(angle[-1] - angle[0]) / (2.0 * math.pi)
    return out


def _returns(mechanism: Mechanism, plan: PositionPlan, values: Reals, seed_row: int, seed: dict[str, LinkPose],
             full: float, turns: int) -> bool:
    """Whether every link is back at its start pose after ``turns`` turns of the input (``values`` a turn from 0)."""
    rows = np.concatenate([*(values + k * full for k in range(turns)), [values[0] + turns * full]])
    found = _evaluate(mechanism, plan, rows, seed_row, seed, periodic=False)
    size = mechanism_size(mechanism, seed)
    for pose in found.poses.values():
        origin = np.broadcast_to(pose.origin, rows.shape)
        rotation = np.broadcast_to(pose.rotation, rows.shape)
        if abs(origin[-1] - origin[0]) > SAME_REL * size or abs(rotation[-1] - rotation[0]) > ANGLE_SAME_RAD:
            return False
    return bool(found.ok.all())


def _cycle(mechanism: Mechanism, plan: PositionPlan, values: Reals, seed_row: int, seed: dict[str, LinkPose],
           full: float) -> tuple[int, list[Notice]]:
    """How many turns of the input bring a geared mechanism back to where it started: each link's turns per
    turn of the input (its gear ratio to the input) as a fraction p/q, the least common multiple of the q's
    (1 without gears; with a notice saying so, 1 where there is none within ``CYCLE_TURNS``)."""
    if not mechanism.scene.gears:
        return 1, []
    per_turn = _turns_per_turn(mechanism, plan, values, seed_row, seed, full)
    turns = 1
    for link, ratio in sorted(per_turn.items()):
        fraction = Fraction(ratio).limit_denominator(CYCLE_TURNS)
        if abs(ratio - float(fraction)) > SAME_REL * max(1.0, abs(ratio)):
            return 1, [Notice("no-cycle", f"link {link} turns {ratio:.10g} times per turn of the input, no fraction "
                              f"with a denominator up to {CYCLE_TURNS}: the gears bring the mechanism back after no "
                              f"whole number of turns up to {CYCLE_TURNS}; the sweep covers one turn (its curves "
                              "do not close)")]
        turns = math.lcm(turns, fraction.denominator)
        if turns > CYCLE_TURNS:
            return 1, [Notice("no-cycle", f"the gears bring the mechanism back after {turns} turns of the input at "
                              f"the least, more than {CYCLE_TURNS}; the sweep covers one turn (its curves do not "
                              "close)")]
    if not _returns(mechanism, plan, values, seed_row, seed, full, turns):
        return 1, [Notice("no-cycle", f"after {turns} turn{'s' if turns > 1 else ''} of the input, when every gear has "
                          "turned a whole number of times, the mechanism is not back where it started (a rack runs "
                          "on); the sweep covers one turn (its curves do not close)")]
    if turns == 1:
        return 1, []
    ratios = ", ".join(f"link {link} {Fraction(r).limit_denominator(CYCLE_TURNS)}"
                       for link, r in sorted(per_turn.items())
                       if Fraction(r).limit_denominator(CYCLE_TURNS).denominator > 1)
    return turns, [Notice("cycle", f"the gears bring the mechanism back after {turns} turns of the input (turns per "
                          f"turn of the input: {ratios}); the sweep covers them all, its whole cycle")]


def _newton_margin(mechanism: Mechanism, size: float) -> float:
    """How far inside the last input where a Newton group closes a range's end is put, in the input's unit.

    Beyond a dead point by less than about ``NEWTON_CLOSED_REL`` radians (or ``NEWTON_CLOSED_REL`` times the
    mechanism's size for a slider), Newton's method still meets its tolerance from a start close enough: the
    subdivision's last input may lie there, where a sweep's rows, walked from a whole step away, do
    not close. ``_NEWTON_EDGE`` times that is well inside, and still far below a printed digit.
    """
    if isinstance(mechanism.scene.input, LinkInput):
        radians = _NEWTON_EDGE * NEWTON_CLOSED_REL
        return math.degrees(radians) if mechanism.scene.units.angle == "deg" else radians
    return _NEWTON_EDGE * NEWTON_CLOSED_REL * size


def _edge(mechanism: Mechanism, plan: PositionPlan, inside: float, outside: float,
          seed: dict[str, LinkPose], reach: _Reach | None = None, margin: float = 0.0) -> float:
    """The last input from ``inside`` toward ``outside`` where the mechanism still closes (and, with
    ``reach``, every point stays within it), less ``margin`` toward ``inside`` where it stops closing."""
    start = inside
    for _ in range(_ZOOM_ROUNDS):
        values = np.linspace(inside, outside, _ZOOM + 1)
        found = _evaluate(mechanism, plan, values, 0, seed, periodic=False, run_only=True)
        ok = found.ok if reach is None else reach.within(mechanism, found)
        last = int(np.argmin(ok)) - 1 if not ok.all() else len(values) - 1
        if last < 0:
            break
        inside, seed = float(values[last]), found.row(last)
        if last == len(values) - 1:
            break
        outside = float(values[last + 1])
    return inside + math.copysign(min(margin, abs(inside - start)), start - inside)  # never past the start


def _run_around(ok: Bools, row: int, periodic: bool) -> tuple[int, int]:
    """How many rows before and after ``row`` close without a gap (cyclically when periodic)."""
    n = len(ok)
    before = after = 0
    while before < n - 1 and (periodic or row - before - 1 >= 0) and ok[(row - before - 1) % n]:
        before += 1
    while after < n - 1 - before and (periodic or row + after + 1 < n) and ok[(row + after + 1) % n]:
        after += 1
    return before, after


def _default_range(mechanism: Mechanism, plan: PositionPlan, seed: dict[str, LinkPose], size: float) -> tuple[
        float, float, bool, list[Notice], tuple[float, float]]:
    """(start, stop, full turn?, notices, how far each end is put inside a dead point by ``_newton_margin``)."""
    seed_value = _seed_value(mechanism)
    full = _full_turn(mechanism)
    coarse = 360 if any(isinstance(g, NewtonGroup) for g in plan.groups) else FULL_TURN_CHECK_ROWS
    if full is not None:
        shown = np.linspace(0.0, full, coarse, endpoint=False)
        values, _, seed_row = _with_seed(shown, seed_value, True, full)
        found = _evaluate(mechanism, plan, values, seed_row, seed, periodic=True)
        if found.ok.all():
            turns, said = _cycle(mechanism, plan, values, seed_row, seed, full)
            return 0.0, turns * full, True, said, (0.0, 0.0)
        seed_value = float(values[seed_row])
    else:
        reach = 10.0 * size
        shown = np.linspace(seed_value - reach, seed_value + reach, 4001)
        values, _, seed_row = _with_seed(shown, seed_value, False, None)
        found = _evaluate(mechanism, plan, values, seed_row, seed, periodic=False, run_only=True)
    if not found.ok[seed_row]:
        raise AssemblyError(f"the scene's own input ({seed_value:.6g}) does not close in the sweep's arrays; "
                            "give --from and --to")
    periodic = full is not None
    bounds = _reach(mechanism, seed, size)
    ok = bounds.within(mechanism, found)
    ok[seed_row] = True
    before, after = _run_around(ok, seed_row, periodic)
    n = len(values)
    margin = _newton_margin(mechanism, size) if any(isinstance(g, NewtonGroup) for g in plan.groups) else 0.0
    notices: list[Notice] = []
    ends: list[float] = []
    pulled: list[float] = []
    for sign, count in ((-1, before), (1, after)):
        row = (seed_row + sign * count) % n
        inside = float(values[row])
        if periodic:  # unwrap the input to a continuous value on the seed's side
            inside = seed_value + sign * ((sign * (inside - seed_value)) % full)  # type: ignore[operator]
        next_row = row + sign
        if not periodic and not 0 <= next_row < n:
            notices.append(Notice("open-range", f"the mechanism still closes at {inside:.6g}, ten times its size "
                                  f"({size:.6g}) from the scene's input; the sweep stops there (give --from and "
                                  "--to to go further)"))
            ends.append(inside)
            pulled.append(0.0)
            continue
        outside = inside + sign * abs(float(values[1] - values[0]))
        runs_off = bool(found.ok[next_row % n] and not ok[next_row % n])  # it still closes there, but runs off
        end_margin = 0.0 if runs_off else margin  # a dead point only where it stops closing
        edge = _edge(mechanism, plan, inside, outside, found.row(row), bounds, end_margin)
        if runs_off:
            notices.append(Notice("open-range", f"the mechanism still closes at {edge:.6g}, but a point runs off "
                                  f"beyond ten times its size ({size:.6g}); the sweep stops there (give --from "
                                  "and --to to go further)"))
        ends.append(edge)
        pulled.append(end_margin)
    return ends[0], ends[1], False, notices, (pulled[0], pulled[1])


def full_turn_grid(mechanism: Mechanism, steps: int) -> InputGrid | None:
    """A full turn of the input link in ``steps`` rows, ``steps`` equal intervals (None for a slider input)."""
    full = _full_turn(mechanism)
    if full is None:
        return None
    _check_steps(steps)
    values, mask, seed_row = _with_seed(_even(0.0, full, steps, False), _seed_value(mechanism), True, full)
    return InputGrid(values, _internal(mechanism, values), mask, seed_row, True)


def _even(start: float, stop: float, count: int, endpoint: bool) -> Reals:
    """``np.linspace(start, stop, count, endpoint=endpoint)``, the same values, without its Python (a sweep's every
    call makes its rows so)."""
    step = (float(stop) - float(start)) / (count - 1 if endpoint else count)
    if step == 0.0 or count < 2:  # linspace's own care of a step that underflows
        return np.linspace(start, stop, count, endpoint=endpoint)
    rows = np.arange(count, dtype=np.float64)
    rows *= step
    if start != 0.0 or (step < 0.0 and math.copysign(1.0, start) > 0.0):  # adding a zero changes no row, but for
        rows += start  # a first row of -0.0 (a step down) that +0.0 makes +0.0
    if endpoint:
        rows[-1] = stop
    return rows


def _check_steps(steps: int) -> None:
    if not 2 <= steps <= MAX_STEPS:
        raise SceneError(f"--positions: expected a whole number of intervals from 2 to {MAX_STEPS}, got {steps}")


def _is_full_turn(start: float, stop: float, full: float | None) -> bool:
    """Whether ``start`` to ``stop`` is one whole turn (either way), up to rounding of the inputs."""
    return full is not None and abs(abs(stop - start) - full) <= ROUNDING_REL * full


class DefaultRange(NamedTuple):
    """The range of ``default_range``: its ends, whether it is a full turn, what to say of it, and how far each end
    is put inside a dead point."""

    start: float
    stop: float
    periodic: bool
    notices: tuple[Notice, ...]
    pulled: tuple[float, float]


def default_range(mechanism: Mechanism, plan: PositionPlan, seed: dict[str, LinkPose]) -> DefaultRange:
    """The input's range a sweep without ``--from`` and ``--to`` covers: a full turn (or a geared mechanism's cycle),
    else the range about the scene's input where the mechanism closes. It does not depend on how many rows are
    asked: a prepared sweep finds it once for all its calls."""
    start, stop, periodic, notices, pulled = _default_range(mechanism, plan, seed, mechanism_size(mechanism, seed))
    return DefaultRange(start, stop, periodic, tuple(notices), pulled)


def input_grid(mechanism: Mechanism, plan: PositionPlan, seed: dict[str, LinkPose], steps: int,
               start: float | None, stop: float | None, found: DefaultRange | None = None) -> InputGrid:
    """The rows of a sweep of ``steps`` equal intervals from ``start`` to ``stop`` (the scene's input unit):
    ``steps + 1`` shown rows, or ``steps`` over a full turn (its end would repeat its start). Without ``start`` and
    ``stop``, the ``default_range`` (``found``, when the caller has it already)."""
    _check_steps(steps)
    full = _full_turn(mechanism)
    notices: list[Notice] = []
    pulled = (0.0, 0.0)
    if start is None or stop is None:
        found = found if found is not None else default_range(mechanism, plan, seed)
        start, stop, periodic, notices, pulled = found.start, found.stop, found.periodic, list(found.notices), \
            found.pulled
    else:
        if start == stop:
            raise SceneError(f"--from and --to: the range from {start:.6g} to {stop:.6g} is empty; give two different "
                             "inputs (`kinepoly solve` gives a single position)")
        periodic = _is_full_turn(start, stop, full)
    shown = _even(start, stop, steps if periodic else steps + 1, not periodic)
    values, mask, seed_row = _with_seed(shown, _seed_value(mechanism), periodic, full)
    near_dead: dict[int, str] = {}
    if pulled != (0.0, 0.0):
        shown_rows = mask.nonzero()[0]
        unit = mechanism.scene.units.angle if full is not None else mechanism.scene.units.length
        near_dead = {int(shown_rows[k]): f"near-singular: an end of the range, {margin:.2g} {unit} inside the dead "
                     "point beyond which a group closed by Newton's method does not close"
                     for k, margin in ((0, pulled[0]), (-1, pulled[1])) if margin > 0.0}
    return InputGrid(values, _internal(mechanism, values), mask, seed_row, periodic, tuple(notices), near_dead)
