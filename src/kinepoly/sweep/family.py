"""``sweep_family``: a scene's mechanism over a family of dimensions, each member swept over the same inputs.

A sweep is a batch over the input; a family is a batch over the dimensions too. The members share the
scene's topology (its links, joints, input and ``[find]``) and differ in the coordinates of some points
of their links, given as arrays over the members: ``{"B@3": [[120, 0], [118, 0], ...]}`` is point B of
link 3 in link 3's own frame, one row per member (``B`` alone where one link has B); and in the slide lines
of some sliders: ``slides={"14": [[0, 20], [0, 25], ...]}`` is the point the line of slider 14 passes through,
in its guide's frame (its angle stays the scene's); and in the pitch radii of some gear pairs:
``radii={"23": [[40, 60], [42, 63], ...]}`` (both gears' radii, one row per member; the caller keeps each pair's
centres r2 + r3 apart, as the scene itself must).

Where the position plan is made of dyads, carried dyads and drive groups, the plan runs once for every
row of every member (``model.family``): each member's rows follow, from the row at the scene's own
input, the assembly the scene's own solve takes there (the same label, ``engine.policy.FamilyContinuity``:
an open four-bar stays open). A mechanism with groups solved by Newton's method (triads, cylinders
inside larger groups, planet groups) is swept member by member, each member a scene of its own solved
as ``sweep`` solves it; so is a geared mechanism (a gear pair is placed by rolling). Scenes with cams are
refused: a cam's equivalent link is made from the pair's dimensions when the scene is read.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt
from msgspec import Struct, field
from msgspec.structs import replace

from kinepoly.engine.carry import drive_values
from kinepoly.engine.groups import PositionPlan
from kinepoly.engine.plan import make_plan
from kinepoly.engine.policy import FamilyContinuity
from kinepoly.engine.position import Positions, input_values, solve_positions
from kinepoly.engine.table import batched
from kinepoly.errors import KinepolyError, SceneError
from kinepoly.geom.arrays import Bools, Reals
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.family import FamilyMechanism
from kinepoly.model.mechanism import Mechanism, build_mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice
from kinepoly.scene.link_point import LinkPoint
from kinepoly.scene.spec import GearSpec, LinkSpec, PitchCircle, Scene
from kinepoly.sweep.inputs import InputGrid, input_grid, input_unit
from kinepoly.sweep.result import STATUS, Column, Kind, SweepResult
from kinepoly.sweep.run import (
    PreparedSweep,
    execute_rows,
    gap_notices,
    prepare_sweep,
    prepared_sweep,
    run_sweep,
    seed_poses,
)

__all__ = ["Dimensions", "FamilyColumn", "FamilyResult", "MemberPlacer", "member_placer", "member_scene",
           "read_dimensions", "sweep_family"]

_CHUNK_ROWS = 1 << 17
"""At most this many rows (members times rows each) run in one batch, under 0.1 GB of arrays at their peak; a
larger family runs in several batches of whole members (as fast per row: 1.8 million rows took 0.6 s in batches
of this size, 0.9 s in batches of a million)."""


class FamilyColumn(Struct, frozen=True):
    """One reported quantity of every member at every row: ``values[k, j]`` member k at input row j; 0.0 where
    ``valid`` is False."""

    name: str
    kind: Kind
    values: Reals
    valid: Bools


class FamilyResult(Struct, frozen=True, eq=False):
    """A family sweep: the input column (the same for every member), each quantity over (members, rows), each
    row's status per member, and how the family was run (``batched``: the plan once for every member)."""

    scene: Scene
    dimensions: Dimensions
    """What differs between the members: the points and slide lines as given."""
    input: Column
    columns: tuple[FamilyColumn, ...]
    status: npt.NDArray[np.int8]
    """(members, rows): the level of each row of each member (``sweep.result.STATUS``)."""
    batched: bool
    notices: tuple[Notice, ...] = ()
    """What the scene's own sweep says of the range (every member is swept over the scene's range)."""
    timing: dict[str, float] = field(default_factory=dict)
    _results: tuple[SweepResult, ...] = ()
    """Batched: the batches' results, ``_per`` members each; else each member's own sweep."""
    _per: int = 1
    _grid: InputGrid | None = None

    @property
    def members(self) -> int:
        return int(self.status.shape[0])

    def column(self, name: str) -> FamilyColumn:
        for col in self.columns:
            if col.name == name:
                return col
        raise KeyError(name)

    def member(self, k: int) -> SweepResult:
        """Member ``k`` as a sweep result of its own (columns, statuses, warnings), as ``sweep`` gives it for
        ``self.member_scene(k)`` over the family's range."""
        self._check(k)
        if not self.batched:
            return self._results[k]
        return _member_of_batch(self, self._results[k // self._per], k, k % self._per)

    def member_scene(self, k: int) -> Scene:
        """Member ``k`` as a scene of its own: the scene with the member's points, its ``[guess]`` moved to where
        the member has the guessed points at the scene's input, so that a solve or a sweep of it takes the
        member's assembly (the family's: the scene's own, by label)."""
        self._check(k)
        scene = self.dimensions.scene(self.scene, k)
        if not self.batched:
            return scene  # swept member by member: each from the scene's own [guess]
        grid, positions = self._grid, self._results[k // self._per].positions
        assert grid is not None and positions is not None
        row = (k % self._per) * len(grid.values) + grid.seed_row
        guess = []
        for name, xy in scene.guess:
            at = complex(positions.point(name)[row]) if positions.ok[row] else complex(*xy)
            guess.append((name, (at.real, at.imag)))
        return replace(scene, guess=tuple(guess))

    def _check(self, k: int) -> None:
        if not 0 <= k < self.members:
            raise IndexError(f"member {k} of a family of {self.members}")


class Dimensions(Struct, frozen=True, eq=False):
    """What differs between a family's members: points keyed (link, point) and slide lines' ``through`` keyed by
    slider, each an array of (members, 2)."""

    points: Mapping[tuple[str, str], Reals]
    slides: Mapping[str, Reals]
    count: int
    radii: Mapping[str, Reals] = field(default_factory=dict)
    """The gear pairs' pitch radii, keyed by pair, each (members, 2)."""

    def scene(self, scene: Scene, k: int) -> Scene:
        """Member ``k`` as a scene of its own: ``scene`` with member ``k``'s coordinates."""
        def row(xy: Reals) -> tuple[float, float]:
            return (float(xy[k, 0]), float(xy[k, 1]))

        def link_of(link: LinkSpec) -> LinkSpec:
            moved = tuple(replace(p, local=row(self.points[(link.name, p.name)]), polar=None)
                          if (link.name, p.name) in self.points else p for p in link.points)
            return replace(link, points=moved)
        def gear_of(gear: GearSpec) -> GearSpec:
            if gear.name not in self.radii:
                return gear
            circles = [curve for curve in gear.pitch if isinstance(curve, PitchCircle)]  # both (read_dimensions)
            first, second = (PitchCircle(curve.center, r)
                             for curve, r in zip(circles, row(self.radii[gear.name]), strict=True))
            return replace(gear, pitch=(first, second))
        sliders = tuple(replace(s, through=row(self.slides[s.name])) if s.name in self.slides else s
                        for s in scene.sliders)
        return replace(scene, links=tuple(link_of(link) for link in scene.links), sliders=sliders,
                                   gears=tuple(gear_of(gear) for gear in scene.gears))

    def part(self, first: int, stop: int) -> Dimensions:
        """Members ``first`` to ``stop`` (not included) alone."""
        return Dimensions({key: xy[first:stop] for key, xy in self.points.items()},
                          {key: xy[first:stop] for key, xy in self.slides.items()}, stop - first,
                          {key: r[first:stop] for key, r in self.radii.items()})

    def mechanism(self, base: Mechanism, rows_each: int, shared_inputs: bool = True) -> FamilyMechanism:
        """The members' mechanism over their rows, ``rows_each`` to a member (``shared_inputs``: every member over
        the same inputs; False: each row at an input of its own)."""
        return FamilyMechanism(base.scene, {key: xy[:, 0] + 1j * xy[:, 1] for key, xy in self.points.items()},
                               rows_each, {name: xy[:, 0] + 1j * xy[:, 1] for name, xy in self.slides.items()},
                               shared_inputs)


def member_scene(scene: Scene, points: Mapping[str, npt.ArrayLike], k: int,
                 slides: Mapping[str, npt.ArrayLike] | None = None,
                 radii: Mapping[str, npt.ArrayLike] | None = None) -> Scene:
    """Member ``k`` of a family as a scene of its own: ``scene`` with the varied points' (slide lines', pitch
    radii's) values of row ``k``."""
    return read_dimensions(scene, points, slides, radii).scene(scene, k)


def sweep_family(scene: Scene, points: Mapping[str, npt.ArrayLike] | None = None, *, steps: int,
                 start: float | None = None, stop: float | None = None,
                 slides: Mapping[str, npt.ArrayLike] | None = None,
                 radii: Mapping[str, npt.ArrayLike] | None = None) -> FamilyResult:
    """Sweep every member of the family over ``steps`` rows of the input from ``start`` to ``stop`` (the input's
    unit; without them, the range ``sweep`` takes for the scene itself: a full turn, or its input's range).

    ``points``: the varied points' local coordinates, each an array of (members, 2), keyed ``B@3`` (point B of
    link 3) or ``B`` where one link has B. ``slides``: the varied slide lines, each the point its line passes
    through in its guide's frame, an array of (members, 2), keyed by slider (``"14"``). ``radii``: the varied gear
    pairs' pitch radii, (members, 2), keyed by pair (``"23"``). Every member is the scene with those values.
    """
    t0 = time.perf_counter()
    if scene.cams:
        raise SceneError(f"{scene.source}: sweep_family: the scene has cams, whose equivalent links are made from "
                         "the pair's dimensions when the scene is read; sweep each member as a scene of its own")
    dimensions = read_dimensions(scene, points, slides, radii)
    count = dimensions.count
    prepared = prepared_sweep(scene)
    if (start is None) != (stop is None):
        raise SceneError("sweep_family: start and stop: give both, or neither for the scene's own range")
    with np.errstate(all="ignore"):
        grid = input_grid(prepared.mechanism, prepared.plan, prepared.seed, steps, start, stop,
                          prepared.default_range if start is None else None)
        if not batched(prepared.plan):
            ends = (prepared.default_range.start, prepared.default_range.stop) if start is None or stop is None \
                else (start, stop)
            return _member_by_member(scene, dimensions, steps, ends, grid, t0)
        t1 = time.perf_counter()
        per = max(1, _CHUNK_ROWS // len(grid.values))
        batches = tuple(_batch(prepared, dimensions.part(first, min(first + per, count)), grid)
                        for first in range(0, count, per))
    t2 = time.perf_counter()
    rows = int(grid.shown.sum())
    columns = tuple(FamilyColumn(c.name, c.kind, _joined([b.columns[j].values for b in batches], count, rows),
                                 _joined([b.columns[j].valid for b in batches], count, rows))
                    for j, c in enumerate(batches[0].columns))
    first_input = batches[0].input
    inputs = Column(first_input.name, "input", first_input.values[:rows], first_input.valid[:rows])
    timing = {"prepare_s": prepared.prepare_s, "range_s": t1 - t0, "execute_s": t2 - t1,
              "total_s": prepared.prepare_s + t2 - t0}
    return FamilyResult(scene, dimensions, inputs, columns, _joined([b.status for b in batches], count, rows), True,
                        grid.notices, timing, batches, per, grid)


class MemberPlacer(Struct, frozen=True, eq=False):
    """Places a family's members each at an input of its own (one row a member), in one run of the position plan;
    made once for a scene by ``member_placer``."""

    mechanism: Mechanism
    plan: PositionPlan
    seed: Mapping[str, LinkPose]
    """The scene's own assembly at its own input (its solve's), whose labels the members take."""

    def place(self, dimensions: Dimensions, inputs: Reals, flipped: frozenset[str] = frozenset()) -> Positions:
        """Member k with its dimensions at ``inputs[k]`` (the scene's first input: theta in radians, or s), every
        dyad on the label of the scene's own assembly but those named in ``flipped``, on the other; ``ok`` False
        where a member does not close so."""
        base = self.mechanism
        policy = FamilyContinuity(0, 1, False, base, self.seed, drive_values(base, input_values(base)), flipped)
        with np.errstate(all="ignore"):
            members = dimensions.mechanism(base, 1, shared_inputs=False)
            return solve_positions(members, self.plan, np.asarray(inputs, np.float64), policy)


def member_placer(scene: Scene, links: frozenset[str] | None = None) -> MemberPlacer | None:
    """A placer of ``scene``'s members, each at its own input, through the groups that place ``links`` (every
    link without them); None where a family cannot run in one batch: cams, gears, or groups solved by Newton's
    method in the plan."""
    if scene.cams:
        return None
    mechanism = build_mechanism(scene)
    plan = make_plan(mechanism, None if links is None else set(links))
    if not batched(plan):
        return None
    return MemberPlacer(mechanism, plan, seed_poses(mechanism, plan))


def _joined(parts: list[npt.NDArray[Any]], count: int, rows: int) -> npt.NDArray[Any]:
    """The batches' values of one quantity as (members, rows)."""
    return (parts[0] if len(parts) == 1 else np.concatenate(parts)).reshape(count, rows)


def _batch(prepared: PreparedSweep, dimensions: Dimensions, grid: InputGrid) -> SweepResult:
    """Every member's rows in one run of the plan and the construction."""
    n, count = len(grid.values), dimensions.count
    mechanism = dimensions.mechanism(prepared.mechanism, n)
    base = prepared.mechanism
    policy = FamilyContinuity(grid.seed_row, n, grid.periodic, base, prepared.seed,
                              drive_values(base, input_values(base)))
    internal = np.tile(grid.internal, count)
    positions = solve_positions(mechanism, prepared.plan, internal, policy)
    rows = InputGrid(np.tile(grid.values, count), internal, np.tile(grid.shown, count), grid.seed_row,
                     grid.periodic)
    members: dict[int, Mechanism] = {}

    def member(row: int) -> Mechanism:  # a row's own member, for the estimate of a near-singular row's error
        k = row // n
        if k not in members:
            members[k] = build_mechanism(dimensions.scene(base.scene, k))
        return members[k]
    return execute_rows(mechanism, prepared, rows, positions, gaps=False, member=member)


def _member_of_batch(family: FamilyResult, batch: SweepResult, k: int, local: int) -> SweepResult:
    """Member ``k``, the ``local``-th member of ``batch``."""
    grid = family._grid
    assert grid is not None
    rows = len(family.input.values)
    shown = slice(local * rows, (local + 1) * rows)
    columns = tuple(Column(c.name, c.kind, c.values[k], c.valid[k]) for c in family.columns)
    warnings = {row - local * rows: text for row, text in batch.warnings.items() if shown.start <= row < shown.stop}
    ok = np.ones(len(grid.values), np.bool_)
    ok[grid.shown] = family.status[k] < STATUS.index("cannot-assemble")
    notices = tuple(gap_notices(grid, ok, family.input.name, input_unit(family.scene)))
    scene = family.member_scene(k)
    return SweepResult(scene, family.input, columns, family.status[k], warnings, notices, grid.periodic,
                       float(grid.values[grid.seed_row]), grid.seed_row,
                       positions=_member_positions(batch, scene, local, len(grid.values)), shown=grid.shown)


def _member_positions(batch: SweepResult, scene: Scene, k: int, rows_each: int) -> Positions:
    """Member ``k``'s rows of the family's positions, on the member's own mechanism (its drawings and its rows'
    ``[guess]``, ``sweep.rows``, read them)."""
    assert batch.positions is not None
    rows = slice(k * rows_each, (k + 1) * rows_each)
    found = batch.positions
    poses = {link: ArrayPose(pose.origin[rows], pose.rotation[rows], pose.still) for link, pose in found.poses.items()}
    return Positions(Mechanism(scene), poses, found.ok[rows], values=tuple(v[rows] for v in found.values))


def _member_by_member(scene: Scene, dimensions: Dimensions, steps: int, ends: tuple[float, float], grid: InputGrid,
                      t0: float) -> FamilyResult:
    """A family whose plan has groups solved by Newton's method: each member swept as a scene of its own over the
    scene's range ``ends``, its assembly the one nearest the scene's ``[guess]`` (as ``solve`` takes it)."""
    members = []
    for k in range(dimensions.count):
        member = dimensions.scene(scene, k)
        try:
            members.append(run_sweep(prepare_sweep(member), steps=steps, start=ends[0], stop=ends[1]))
        except KinepolyError as error:
            raise type(error)(f"sweep_family: member {k}: {error}") from error
    names = [[c.name for c in m.columns] for m in members]
    if any(n != names[0] for n in names):
        raise SceneError(f"{scene.source}: sweep_family: the members report different quantities")
    columns = tuple(FamilyColumn(c.name, c.kind, np.stack([m.columns[j].values for m in members]),
                                 np.stack([m.columns[j].valid for m in members]))
                    for j, c in enumerate(members[0].columns))
    status = np.stack([m.status for m in members])
    return FamilyResult(scene, dimensions, members[0].input, columns, status, False, grid.notices,
                        {"total_s": time.perf_counter() - t0}, tuple(members))


def read_dimensions(scene: Scene, points: Mapping[str, npt.ArrayLike] | None,
                    slides: Mapping[str, npt.ArrayLike] | None = None,
                    radii: Mapping[str, npt.ArrayLike] | None = None) -> Dimensions:
    """The varied points keyed (link, point) and slide lines keyed by slider, each (members, 2); SceneError naming
    the key and what to change where one is not a point of one link (or a slider) of the scene, or not an array of
    (members, 2) finite numbers, or where they differ in their number of members."""
    if not points and not slides and not radii:
        raise SceneError("sweep_family: points: give at least one point (or slide line, or pitch radius) to vary, "
                         "as {'B@3': [[x, y], ...]}")
    counts: list[tuple[str, int]] = []
    varied: dict[tuple[str, str], Reals] = {}
    for key, value in (points or {}).items():
        name = LinkPoint.parse(key)
        owners = [link.name for link in scene.links if name.point in link.point_names]
        if name.link is None and len(owners) == 1:
            name = LinkPoint(name.point, owners[0])
        if name.link is None or name.link not in owners:
            which = ", ".join(f"{name.point}@{o}" for o in owners) or "none: no link has that point"
            raise SceneError(f"sweep_family: points: {key!r} is not a point of one link of the scene; the links' "
                             f"points of that name are: {which}")
        varied[(name.link, name.point)] = _coordinates("points", key, value, counts)
    lines: dict[str, Reals] = {}
    names = [s.name for s in scene.sliders]
    for key, value in (slides or {}).items():
        if key not in names:
            raise SceneError(f"sweep_family: slides: {key!r} is not a slider of the scene; its sliders are: "
                             f"{', '.join(names) or 'none'}")
        lines[key] = _coordinates("slides", key, value, counts)
    pitch: dict[str, Reals] = {}
    pairs = {gear.name: gear for gear in scene.gears}
    for key, value in (radii or {}).items():
        gear = pairs.get(key)
        if gear is None:
            raise SceneError(f"sweep_family: radii: {key!r} is not a gear pair of the scene; its pairs are: "
                             f"{', '.join(pairs) or 'none'}")
        if not all(isinstance(curve, PitchCircle) for curve in gear.pitch):
            raise SceneError(f"sweep_family: radii: {key!r} has a rack (a pitch line, no radius); expected a pair "
                             "of two pitch circles")
        pitch[key] = _coordinates("radii", key, value, counts)
        if not (pitch[key] > 0.0).all():
            raise SceneError(f"sweep_family: radii: {key!r}: member {int(np.flatnonzero(pitch[key] <= 0.0)[0]) // 2} "
                             "has a pitch radius that is not positive")
    return Dimensions(varied, lines, counts[0][1], pitch)


def _coordinates(table: str, key: str, value: npt.ArrayLike, counts: list[tuple[str, int]]) -> Reals:
    """``value`` as (members, 2) finite numbers, as many members as ``counts`` holds already (appended to it)."""
    try:
        xy = np.asarray(value, np.float64)
    except (TypeError, ValueError) as error:
        raise SceneError(f"sweep_family: {table}: {key!r}: expected an array of (members, 2) numbers ({error})") \
            from error
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] == 0:
        raise SceneError(f"sweep_family: {table}: {key!r}: expected an array of (members, 2) numbers, one [x, y] per "
                         f"member; got the shape {xy.shape}")
    if not np.isfinite(xy).all():
        raise SceneError(f"sweep_family: {table}: {key!r}: member {int(np.flatnonzero(~np.isfinite(xy))[0]) // 2} "
                         "has a coordinate that is not a finite number")
    if counts and xy.shape[0] != counts[0][1]:
        raise SceneError(f"sweep_family: {table}: {key!r} has {xy.shape[0]} members, {counts[0][0]!r} before it "
                         f"{counts[0][1]}: give every point, slide line and pair of radii one row per member")
    counts.append((key, xy.shape[0]))
    return xy
