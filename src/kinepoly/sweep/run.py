"""``sweep``: one scene over many inputs, the position plan and the construction executed on arrays.

The plan is made once (backwards from ``[find]``, as ``kinepoly solve`` makes it); the assembly
is taken at the scene's own input as ``solve`` takes it and followed from there; then the
velocity and acceleration polygons are constructed for all rows at once. Each row gets a
status:

- ``ok``;
- ``near-singular``: two direction lines meet at less than ``NEAR_SINGULAR_SIN`` (values kept,
  with the warning ``solve`` would give);
- ``singular``: two direction lines are parallel (a dead point or a change point): positions
  are kept, velocities and accelerations are left empty;
- ``cannot-assemble``: a group does not close there: everything but the input is left empty.

No value of a row that is not valid is reported: columns carry a validity mask, and the CSV
leaves those cells empty (never NaN).
"""

from __future__ import annotations

import cmath
import math
import time
from collections.abc import Callable
from functools import cached_property, lru_cache

import numpy as np
import numpy.typing as npt
from msgspec import Struct, field
from msgspec.structs import replace

from kinepoly.check.estimate import polygon_estimate
from kinepoly.engine.acceleration import AccelerationResult, construct_acceleration
from kinepoly.engine.assembly import position_at_input
from kinepoly.engine.centrode import frame_centrodes
from kinepoly.engine.circle_diagram import pair_name
from kinepoly.engine.group import NEAR_SINGULAR_CONDITION, SINGULAR_CONDITION
from kinepoly.engine.groups import NewtonGroup, PositionPlan
from kinepoly.engine.plan import make_plan
from kinepoly.engine.policy import Continuity
from kinepoly.engine.polygon import JointSolve, LineCrossing
from kinepoly.engine.position import Failure, Positions, solve_positions
from kinepoly.engine.sliders import slider_motion
from kinepoly.engine.transmission import TransmissionPair, transmission_pairs
from kinepoly.engine.velocity import VelocityResult, construct_velocity
from kinepoly.errors import AssemblyError, KinepolyError, SceneError, SingularityError
from kinepoly.geom.arrays import DEGREES_PER_RADIAN, Bools, Points, Reals, trues
from kinepoly.geom.tolerances import NEAR_SINGULAR_SIN, PARALLEL_SIN, TINY_POSITIVE, UNIT_ROUNDOFF
from kinepoly.model.mechanism import Mechanism, build_mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice
from kinepoly.scene.link_point import point_of
from kinepoly.scene.spec import LinkInput, Scene, SliderInput
from kinepoly.solution import Asked, needed_links, what_is_asked
from kinepoly.sweep.columns import ColumnBuilder, Raw
from kinepoly.sweep.higher_pairs import higher_pair_columns
from kinepoly.sweep.inputs import (
    FULL_TURN_CHECK_ROWS,
    DefaultRange,
    InputGrid,
    default_range,
    full_turn_grid,
    input_grid,
    input_name,
    input_unit,
)
from kinepoly.sweep.result import CANNOT_ASSEMBLE as _CANNOT
from kinepoly.sweep.result import NEAR_SINGULAR as _NEAR
from kinepoly.sweep.result import ORDER, Column, Kind, SweepResult
from kinepoly.sweep.result import SINGULAR as _SINGULAR

__all__ = ["PreparedSweep", "cycle_turns", "execute_rows", "gap_notices", "prepare_sweep", "prepared_sweep",
           "run_sweep", "sweep"]


class _Flags(Struct):
    """Each row's level and the reasons, gathered as the stages run."""

    level: npt.NDArray[np.int8]
    reasons: list[tuple[Bools, object]] = field(default_factory=list)

    def raise_to(self, rows: Bools, level: int, reason: object) -> None:
        """Rows that are not yet at ``level`` (or worse) go to it, with ``reason``."""
        if rows.any():
            np.maximum(self.level, np.where(rows, level, 0).astype(np.int8), out=self.level)
            if (rows & (self.level == level)).any():
                self.reasons.append((rows, reason))

    def texts(self, shown: Bools) -> dict[int, str]:
        """The warning text of each shown row that has one, keyed by its place among the shown rows."""
        out: dict[int, list[str]] = {}
        place = np.cumsum(shown) - 1
        for rows, reason in self.reasons:
            for row in np.flatnonzero(rows & shown):
                text = reason(int(row)) if callable(reason) else str(reason)
                entry = out.setdefault(int(place[row]), [])
                if text not in entry:
                    entry.append(text)
        return {k: "; ".join(v) for k, v in out.items()}


class _RowCondition:
    """The condition number k of a row's dimensionless velocity equations, as the solve's check finds it
    (``check.analytic``), for the rows whose warning gives an error estimate (a few: near a dead point); None
    where the check does not close there. ``member``: the mechanism of a row (a family's member's);
    ``polygons``: the polygons the sweep builds ("velocity", and "acceleration" where it builds that too)."""

    def __init__(self, positions: Positions, inputs: Reals, member: Callable[[int], Mechanism],
                 polygons: tuple[str, ...]) -> None:
        self.positions = positions
        self.inputs = inputs
        self.member = member
        self.polygons = polygons
        self.found: dict[int, float | None] = {}

    def estimate(self, row: int, own: float, sine: float = 1.0) -> str:
        """A near-singular row's estimated relative error, in words: each polygon's, the larger of ``own`` (the
        row's crossing, or joint solve) and the solve's estimate with the row's k (``check.estimate``); ``own``
        alone where the check does not close."""
        k = self(row)
        if k is None:
            return f"relative error about {own:.1g}"
        return "relative error about " + ", ".join(
            f"{max(own, polygon_estimate(polygon, k, sine)):.1g} ({_PLURAL[polygon]})" for polygon in self.polygons)

    def __call__(self, row: int) -> float | None:
        if row not in self.found:
            from kinepoly.check.analytic import velocity_condition  # only a sweep that warns needs the check

            member = self.member(row)
            at_row = replace(member, scene=member.scene.at_input(float(self.inputs[row])))
            try:
                self.found[row] = velocity_condition(at_row, self.positions.row(row))
            except KinepolyError:
                self.found[row] = None
        return self.found[row]


def _crossing_flags(flags: _Flags, ok: Bools, every: bool, crossings: list[LineCrossing | JointSolve],
                    condition: _RowCondition, clear: set[int]) -> None:
    """Singular and near-singular rows, as ``PolygonBuilder.cross_lines`` (and ``construct.group``) tell them
    (``every``: whether every row is ``ok``), a near-singular row with its estimated error (``condition``).
    ``clear``: the identities of the sines found well clear of parallel at every row, added to as they are found (the
    acceleration polygon's crossing of the velocity polygon's lines has its very sine: ``Positions.chord_sine``)."""
    for crossing in crossings:
        if isinstance(crossing, JointSolve):
            where = f"group {crossing.group}"
            singular = ok & ~(crossing.condition <= SINGULAR_CONDITION)
            near = ok & ~singular & (crossing.condition > NEAR_SINGULAR_CONDITION)
            flags.raise_to(singular, _SINGULAR, f"singular: the joint equations of {where} are singular, so its "
                           "velocity and acceleration are not determined")
            flags.raise_to(near, _NEAR, _condition_text(where, crossing.condition, condition))
            continue
        if every and _clear_sine(crossing.sin_angle, clear) \
                and math.isfinite(np.add.reduce(crossing.along)):  # the lines cross well at every row (of one sense)
            continue
        sine = np.abs(crossing.sin_angle)
        where = f"group {crossing.group} at {crossing.what}"
        singular = ok & ~(sine > PARALLEL_SIN)
        flags.raise_to(singular, _SINGULAR, f"singular: the direction lines of {where} are parallel, so its "
                       "velocity and acceleration are not determined (a dead point or a change point)")
        flags.raise_to(ok & ~singular & (sine < NEAR_SINGULAR_SIN), _NEAR,
                       _near_text(where, sine, condition))
        flags.raise_to(ok & ~singular & ~np.isfinite(crossing.along), _SINGULAR,
                       f"singular: the {crossing.kind} of {crossing.what} overflowed")


def _clear_sine(sine: Reals, clear: set[int]) -> bool:
    """Whether two lines cross at a sine of one sense beyond ``NEAR_SINGULAR_SIN`` at every row (the identity of
    each sine so found kept in ``clear``, each sine judged once)."""
    if id(sine) in clear:
        return True
    if np.minimum.reduce(sine) >= NEAR_SINGULAR_SIN or np.maximum.reduce(sine) <= -NEAR_SINGULAR_SIN:
        clear.add(id(sine))
        return True
    return False


def _near_text(where: str, sine: Reals, condition: _RowCondition) -> object:
    """The warning of a row whose lines cross at ``sine``, with the estimate of its error: the crossing's own
    rounding, and the position's, which near a dead point the nearly parallel lines amplify (the same text for the
    velocity and the acceleration polygon's crossing of the same lines, so that the row says it once)."""
    def text(row: int) -> str:
        s = float(sine[row])
        return (f"near-singular: the direction lines of {where} meet at {math.degrees(math.asin(min(1.0, s))):.3g} "
                f"deg; {condition.estimate(row, 4.0 * UNIT_ROUNDOFF / max(s, TINY_POSITIVE), s)}")
    return text


_PLURAL = {"velocity": "velocities", "acceleration": "accelerations"}


def _condition_text(where: str, joints: Reals, condition: _RowCondition) -> object:
    """The warning of a row whose joint equations have the condition number ``joints``, with the estimate of its
    error: the joint solve's own, or the velocity equations' where that is larger."""
    def text(row: int) -> str:
        c = float(joints[row])
        return (f"near-singular: the joint equations of {where} have condition number {c:.2g}; "
                f"{condition.estimate(row, c * UNIT_ROUNDOFF)}")
    return text


def _overflow_flags(flags: _Flags, ok: Bools, out: ColumnBuilder) -> None:
    """Rows where a value is not a number (rates whose squares overflow): singular, never printed.

    Every value of a higher order is computed from those of the lower ones, so a non-finite value
    anywhere shows in the highest order's columns: when their sums are finite, nothing is to mark.
    """
    if cmath.isfinite(complex(sum(map(np.add.reduce, out.tops)))):  # non-finite where any of the sums is
        return
    for name, kind, values, extra in out.raw:
        rows = ok & ~np.isfinite(values) & (True if extra is None else extra)
        if rows.any():
            flags.raise_to(rows, _SINGULAR if ORDER[kind] > 0 else _CANNOT,
                           f"singular: {name} overflowed (beyond the range of double precision)")


class _Layout(Struct, frozen=True):
    """What every call of a prepared sweep reads alike, found once for all its calls: the polygons it builds, each
    asked link's (link, theta, omega, alpha) and each asked point's (label, point, r, v, a) column names (a point's
    as its x and y columns), None where not reported, and the dyads' transmission angles with their columns."""

    input_column: str
    degrees: bool
    velocity: bool
    """Whether the velocity polygon is built (and ``acceleration``: the acceleration polygon too)."""
    acceleration: bool
    polygons: tuple[str, ...]
    """The polygons whose error a near-singular row's warning estimates (``_RowCondition``)."""
    links: tuple[tuple[str, str | None, str | None, str | None], ...]
    points: tuple[tuple[str, str, tuple[str, str], tuple[str, str] | None, tuple[str, str] | None], ...]
    transmissions: tuple[tuple[str, TransmissionPair], ...]
    newton: bool
    """Whether a group of the plan is solved by Newton's method."""


def _xy(name: str) -> tuple[str, str]:
    return f"{name}_x", f"{name}_y"


def _layout(mechanism: Mechanism, plan: PositionPlan, asked: Asked, centrode: str | None, series: bool) -> _Layout:
    scene, input_column = mechanism.scene, input_name(mechanism)
    find = scene.find
    higher = bool(scene.cams or scene.gears)  # a follower's s-v-a and the gear ratios need the polygons
    accelerations = bool(asked.needs_acceleration or scene.cams or series)
    velocity = bool(asked.needs_velocity or centrode is not None or higher or series)
    links = tuple((link, None if f"theta_{link}" == input_column else f"theta_{link}",
                   f"omega_{link}" if link in asked.omega else None, f"alpha_{link}" if link in asked.alpha else None)
                  for link in dict.fromkeys((*asked.omega, *asked.alpha)))
    points = tuple((label, point_of(label), _xy(f"r_{label}"), _xy(f"v_{label}") if label in find.velocity else None,
                    _xy(f"a_{label}") if label in find.acceleration else None)
                   for label in dict.fromkeys((*find.velocity, *find.acceleration)))
    return _Layout(input_column, scene.units.angle == "deg", velocity, velocity and accelerations,
                   ("velocity", "acceleration") if accelerations else ("velocity",), links, points,
                   tuple((f"mu_{pair.point}", pair) for pair in transmission_pairs(mechanism, plan)),
                   any(isinstance(group, NewtonGroup) for group in plan.groups))


def _columns(out: ColumnBuilder, layout: _Layout, asked: Asked, velocity: VelocityResult | None,
             acceleration: AccelerationResult | None) -> None:
    mech, positions = out.mechanism, out.positions
    raw: list[Raw] = []
    sources: list[tuple[Kind, Reals | Points]] = []
    rates = velocity.polygon if velocity is not None else None
    rates_of_rates = acceleration.polygon if acceleration is not None else None
    for link, theta, omega, alpha in layout.links:
        if theta is not None:
            angle = positions.poses[link].theta(degrees=layout.degrees)
            raw += ((theta, "angle", angle, None),)
            sources += (("angle", angle),)
        if omega is not None and rates is not None:
            rate = rates.rate_of(link)
            assert rate is not None, "every link of the plan has its rate"
            raw += ((omega, "omega", rate, None),)
            sources += (("omega", rate),)
        if alpha is not None and rates_of_rates is not None:
            rate = rates_of_rates.rate_of(link)
            assert rate is not None, "every link of the plan has its rate"
            raw += ((alpha, "alpha", rate, None),)
            sources += (("alpha", rate),)
    tips = rates.tips if rates is not None else None
    tips_of_rates = rates_of_rates.tips if rates_of_rates is not None else None
    for label, point, r, v, a in layout.points:
        at = positions.point(point)
        raw += ((r[0], "position", at.real, None), (r[1], "position", at.imag, None))
        sources += (("position", at),)
        if v is not None and tips is not None:
            at = tips[label]
            raw += ((v[0], "velocity", at.real, None), (v[1], "velocity", at.imag, None))
            sources += (("velocity", at),)
        if a is not None and tips_of_rates is not None:
            at = tips_of_rates[label]
            raw += ((a[0], "acceleration", at.real, None), (a[1], "acceleration", at.imag, None))
            sources += (("acceleration", at),)
    out.extend(raw, sources)
    if not asked.sliders:
        return
    input_column = layout.input_column
    driven = {drive.spec.slider: drive.spec for drive in mech.drives if isinstance(drive.spec, SliderInput)}
    for name in asked.sliders:
        motion = slider_motion(positions, mech.slider(name), velocity, acceleration)
        given = driven.get(name)  # a driven slider's values are given, not recomputed (50, not 49.99999999999999)
        if f"s_{name}" != input_column:
            out.add(f"s_{name}", "slider", motion.s if given is None else np.full(len(motion.s), given.s))
        if motion.s_dot is not None:
            out.add(f"s_dot_{name}", "slider-rate",
                    motion.s_dot if given is None else np.full(len(motion.s_dot), given.s_dot))
        if motion.s_ddot is not None and motion.coriolis is not None:
            out.add(f"s_ddot_{name}", "slider-acceleration",
                    motion.s_ddot if given is None else np.full(len(motion.s_ddot), given.s_ddot))
            if mech.slider(name).guide != mech.ground:  # a guide on the frame cannot turn: no Coriolis term
                out.pair(f"coriolis_{name}", "coriolis", motion.coriolis)


def _centrode(out: ColumnBuilder, link: str, velocity: VelocityResult, seed_row: int,
              level: npt.NDArray[np.int8]) -> list[Notice]:
    """The columns of the instant center of ``link`` with the frame, in the frame and in the link."""
    ground = out.mechanism.ground or ""
    found = frame_centrodes(velocity, link, seed_row)
    name = f"I_{pair_name((ground, link))}"
    out.pair(name, "centrode", found.fixed, found.finite)
    out.pair(f"{name}_local", "centrode-local", found.moving, found.finite)
    if not (found.finite | (level > _NEAR)).any():
        return [Notice("centrode-at-infinity", f"link {link} does not turn, so its instant center with the "
                       "frame is at infinity at every row: it has no centrodes")]
    return []


def gap_notices(grid: InputGrid, ok: Bools, name: str, unit: str) -> list[Notice]:
    shown = grid.values[grid.shown]
    fails = ~ok[grid.shown]
    if not fails.any():
        return []
    edges = np.flatnonzero(np.diff(np.concatenate([[0], fails.astype(np.int8), [0]])))
    ranges = [f"{shown[a]:.6g} to {shown[b - 1]:.6g}" for a, b in zip(edges[::2], edges[1::2], strict=True)]
    text = (f"the mechanism cannot be assembled for {name} from {', '.join(ranges)} {unit} "
            f"({int(fails.sum())} of {len(shown)} rows; see each row's warning)")
    if any(a > 0 and b < len(shown) for a, b in zip(edges[::2], edges[1::2], strict=True)) or len(ranges) > 1:
        text += ("; no motion of the input carries the mechanism across, so beyond such a range the sweep "
                 "resumes on the assembly on the same side as before it")
    return [Notice("cannot-assemble", text)]


Progress = Callable[[int, int], None]
"""Called with (rows done, rows in all) by the loops that take long (Newton groups)."""


def seed_poses(mechanism: Mechanism, plan: PositionPlan) -> dict[str, LinkPose]:
    """The assembly ``kinepoly solve`` takes at the scene's own input: the sweep follows it from there."""
    try:
        return position_at_input(mechanism, plan).row(0)
    except (AssemblyError, SingularityError) as error:
        raise type(error)(f"{error}; kinepoly sweep takes its assembly where kinepoly solve does, at the "
                          "scene's own input, so that input must be a position where the mechanism closes "
                          "in one definite way (change [input])") from error


class PreparedSweep(Struct, frozen=True, dict=True):
    """What a sweep needs once per scene: the mechanism, what is asked, the plan; the seed assembly (the
    solve's at the scene's own input) is solved when first asked for."""

    mechanism: Mechanism
    asked: Asked
    plan: PositionPlan
    centrode: str | None
    prepare_s: float
    series: bool = False
    """Add the course text's slider-crank series beside the exact slider columns (``sweep.series``)."""

    @cached_property
    def seed(self) -> dict[str, LinkPose]:
        return seed_poses(self.mechanism, self.plan)

    @cached_property
    def layout(self) -> _Layout:
        """What every call reads alike (the polygons built, the columns' names, the transmission angles), found
        once for all calls."""
        return _layout(self.mechanism, self.plan, self.asked, self.centrode, self.series)

    @cached_property
    def default_range(self) -> DefaultRange:
        """The range a sweep without ``start`` and ``stop`` covers, found once for every call (``sweep.inputs``)."""
        return default_range(self.mechanism, self.plan, self.seed)


def prepare_sweep(scene: Scene, centrode: str | None = None, series: bool = False) -> PreparedSweep:
    """Build the mechanism, plan backwards from ``[find]`` and take the assembly at the scene's input."""
    t0 = time.perf_counter()
    mechanism = build_mechanism(scene)
    if not isinstance(scene.input, (LinkInput, SliderInput)):
        raise SceneError(f"{scene.source}: given: kinepoly sweep varies the input of [input]; a [given] scene "
                         "has none to vary (give an [input] link or slider)")
    if centrode is not None and (centrode not in mechanism.link_names or centrode == mechanism.ground):
        links = ", ".join(n for n in mechanism.link_names if n != mechanism.ground)
        raise SceneError(f"--centrode: expected a moving link of the scene ({links}), got {centrode!r}")
    asked = what_is_asked(mechanism)
    wanted_links = needed_links(mechanism, asked) | ({centrode} if centrode else set())
    if series:
        from kinepoly.sweep.series import check_series

        check_series(mechanism)
        wanted_links |= set(mechanism.link_names)
    plan = make_plan(mechanism, wanted_links)
    return PreparedSweep(mechanism, asked, plan, centrode, time.perf_counter() - t0, series)


def cycle_turns(prepared: PreparedSweep) -> int:
    """How many turns of the input the default sweep covers: a geared mechanism's whole cycle, else 1 (the
    commands' default positions are so many per turn)."""
    mechanism = prepared.mechanism
    if not mechanism.scene.gears or not isinstance(mechanism.scene.input, LinkInput):
        return 1
    with np.errstate(all="ignore"):
        grid = input_grid(mechanism, prepared.plan, prepared.seed, 2, None, None, prepared.default_range)
    if not grid.periodic:
        return 1
    shown = grid.values[grid.shown]
    full = 360.0 if mechanism.scene.units.angle == "deg" else 2.0 * math.pi
    return max(1, round(2.0 * float(shown[1] - shown[0]) / full))


def run_sweep(prepared: PreparedSweep, *, steps: int, start: float | None = None, stop: float | None = None,
              progress: Progress | None = None) -> SweepResult:
    """Execute a prepared sweep over ``steps`` rows from ``start`` to ``stop`` (the input's unit)."""
    if (start is None) != (stop is None):
        raise SceneError("--from and --to: give both, or neither for the full turn (or the input's whole range)")
    t0 = time.perf_counter()
    mechanism, plan = prepared.mechanism, prepared.plan
    with np.errstate(all="ignore"):
        grid, positions = None, None
        quick = start is None and steps >= FULL_TURN_CHECK_ROWS and not mechanism.scene.gears  # gears: their cycle
        trial = full_turn_grid(mechanism, steps) if quick else None
        if trial is not None and not prepared.layout.newton:
            policy = Continuity(trial.seed_row, lambda: prepared.seed, True, progress, dict(mechanism.scene.guess))
            positions = solve_positions(mechanism, plan, trial.internal, policy)
            grid, positions = (trial, positions) if positions.every_ok() else (None, None)
        if grid is None:
            grid = input_grid(mechanism, plan, prepared.seed, steps, start, stop,
                              prepared.default_range if start is None else None)
        t1 = time.perf_counter()
        if positions is None:
            positions = solve_positions(mechanism, plan, grid.internal,
                                        Continuity(grid.seed_row, prepared.seed, grid.periodic, progress))
        result = execute_rows(mechanism, prepared, grid, positions)
    t2 = time.perf_counter()
    result.timing.update({"prepare_s": prepared.prepare_s, "range_s": t1 - t0, "execute_s": t2 - t1,
                          "total_s": prepared.prepare_s + t2 - t0})  # its own dict, filled once it is done
    return result


def sweep(scene: Scene, *, steps: int, start: float | None = None, stop: float | None = None,
          centrode: str | None = None, progress: Progress | None = None, series: bool = False) -> SweepResult:
    """Sweep the scene's input over ``steps`` rows from ``start`` to ``stop`` (the input's unit).

    Without ``start`` and ``stop``: a full turn, or the input's range where the mechanism closes.
    ``centrode`` names a link whose instant center with the frame is reported (both centrodes).
    """
    return run_sweep(prepared_sweep(scene, centrode, series), steps=steps, start=start, stop=stop, progress=progress)


def prepared_sweep(scene: Scene, centrode: str | None = None, series: bool = False) -> PreparedSweep:
    """A scene's prepared sweep kept for the calls that follow on the same scene (a scene is a frozen value): its
    mechanism, plan, seed assembly and default range are found once, so a repeated call pays only its rows. The
    scene swept last (this very object) is found again without hashing it."""
    last = _last_prepared[0]
    if last is not None and last[0] is scene and last[1] == centrode and last[2] == series:
        return last[3]
    prepared = _prepared(scene, centrode, series)
    _last_prepared[0] = (scene, centrode, series, prepared)
    return prepared


_last_prepared: list[tuple[Scene, str | None, bool, PreparedSweep] | None] = [None]
"""The scene swept last (this very object) and its prepared sweep: found again without hashing the scene, whose
hash takes every value it holds."""


@lru_cache(maxsize=8)
def _prepared(scene: Scene, centrode: str | None, series: bool) -> PreparedSweep:
    """The prepared sweeps of the last few scenes (``prepared_sweep``)."""
    return prepare_sweep(scene, centrode, series)


def execute_rows(mechanism: Mechanism, prepared: PreparedSweep, grid: InputGrid, positions: Positions,
                 gaps: bool = True, member: Callable[[int], Mechanism] | None = None) -> SweepResult:
    """The polygons and the columns of the rows ``grid`` over the positions found there (``mechanism``: the
    prepared one, or a family's, ``model.family``); ``gaps``: say where the input's range does not assemble
    (a family says it member by member); ``member``: the mechanism of a row, where it is not ``mechanism`` (a
    family's member's, for the error estimates of near-singular rows)."""
    scene, centrode, plan, asked, layout = mechanism.scene, prepared.centrode, prepared.plan, prepared.asked, \
        prepared.layout
    flags = _Flags(np.zeros(len(grid.values), np.int8))
    for failure in positions.failures:
        flags.raise_to(failure.rows, _CANNOT, _failure_text(failure))
    for rough in positions.near:
        flags.raise_to(rough.rows & positions.ok, _NEAR, rough.why)
    for row, why in grid.near_dead.items():
        end = np.zeros(len(grid.values), np.bool_)
        end[row] = True
        flags.raise_to(end & positions.ok, _NEAR, why)
    ok = positions.ok
    every_ok = positions.every_ok()
    velocity = acceleration = None
    condition = _RowCondition(positions, grid.internal, member or (lambda _: mechanism), layout.polygons)
    if layout.velocity:
        velocity = construct_velocity(positions, plan, asked.velocity)
        clear: set[int] = set()  # the sines judged clear (the crossings hold them: their identities stay theirs)
        _crossing_flags(flags, ok, every_ok, velocity.polygon.crossings, condition, clear)
        if layout.acceleration:
            acceleration = construct_acceleration(velocity, plan, asked.acceleration)
            _crossing_flags(flags, ok, every_ok, acceleration.polygon.crossings, condition, clear)
    name = layout.input_column
    out = ColumnBuilder(mechanism, positions)
    _columns(out, layout, asked, velocity, acceleration)
    followers = higher_pair_columns(out, velocity, acceleration, name) if scene.cams or scene.gears else ()
    notices = list(grid.notices)
    if centrode is not None and velocity is not None:
        notices += _centrode(out, centrode, velocity, grid.seed_row, flags.level)
    if prepared.series:
        from kinepoly.sweep.series import series_columns

        slider = mechanism.sliders[0].name
        for column, kind, values, valid in series_columns(mechanism, positions, grid.seed_row, velocity, acceleration,
                                                          slider not in asked.sliders):
            out.add(column, kind, values, valid)  # type: ignore[arg-type]
    for column, pair in layout.transmissions:
        angle = pair.radians(positions)
        if layout.degrees:
            angle *= DEGREES_PER_RADIAN  # np.degrees(angle), bit for bit, in place: the angle is its own array
        out.add(column, "transmission", angle)
    if not every_ok and gaps:
        notices += gap_notices(grid, ok, name, input_unit(scene))
    _overflow_flags(flags, ok, out)
    shown = grid.shown
    every = bool(np.logical_and.reduce(shown))
    input_column = Column(name, "input", grid.values if every else grid.values[shown],
                          trues(len(grid.values) if every else np.count_nonzero(shown)))
    return SweepResult(scene, input_column, out.columns(flags.level if flags.reasons else None, shown, every),
                       flags.level if every else flags.level[shown], flags.texts(shown) if flags.reasons else {},
                       tuple(notices), grid.periodic, float(grid.values[grid.seed_row]), grid.seed_row,
                       positions=positions, shown=shown, followers=followers)


def _failure_text(failure: Failure) -> object:
    joint = f"joint {failure.joint} of " if failure.joint else ""

    def text(row: int) -> str:
        return f"cannot assemble {joint}group {failure.group}: {failure.why(row)}"
    return text
