"""A family of the scene's mechanism: ``kinepoly.sweep_family`` (the plan run once for every member) against one
sweep per member, timed in the same run, and both against the 50-digit reference.

The members are the scene with every point of each link multiplied by a factor of its own, drawn uniformly from
[1 - spread, 1 + spread] (the same seed, the same family), and each slide line's ``through`` by its guide's.
The family and the loop are swept over the same rows
(the scene's range); the loop sweeps each member's own scene (``FamilyResult.member_scene``: its ``[guess]`` where
the family put the guessed points, so that it is in the family's assembly). At a few rows of a few members the
family's values are measured against the mpmath reference (``bench.reference``), started from the solve at that
row in the member's assembly.
"""

from __future__ import annotations

import math
import random
import time
from typing import Any

import numpy as np
from msgspec import Struct

from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import bench_keys, kind_errors
from kinepoly.bench.sweep import solve_at
from kinepoly.errors import KinepolyError
from kinepoly.scene.spec import LinkInput, Scene
from kinepoly.solution import solve
from kinepoly.sweep import FamilyResult, SweepResult, sweep, sweep_family
from kinepoly.sweep.rows import row_guesses

__all__ = ["FamilyBench", "family_points", "run_family"]

CHECKED_MEMBERS = 4
"""How many members are measured against the reference (the first ones)."""
CHECKED_ROWS = 5
"""How many rows of each of them (spread evenly over the rows that are ok)."""


class FamilyBench(Struct, frozen=True):
    """What ``run_family`` measured: the times (seconds, the best of ``rounds``), the agreement of the family with
    the loop (largest difference relative to each column kind's largest value), and the family's largest error
    per quantity kind against the reference over the rows checked."""

    title: str
    members: int
    rows: int
    spread: float
    seed: int
    batched: bool
    family_s: float
    loop_s: float
    agreement: float
    agreement_column: str
    errors: dict[str, float]
    checked: int

    def lines(self) -> list[str]:
        how = "the plan run once for every member" if self.batched else "member by member (Newton groups)"
        worst = ", ".join(f"{kind} {error:.1e}" for kind, error in sorted(self.errors.items())) or "none measured"
        where = f", in {self.agreement_column}" if self.agreement_column else ""
        return [
            f"{self.title}: a family of {self.members} members, each link's points times a factor in "
            f"[{1 - self.spread:g}, {1 + self.spread:g}] (seed {self.seed}), {self.rows} rows each",
            f"  {'kinepoly.sweep_family':<24}{self.family_s * 1e3:10.2f} ms   1.00   "
            f"{self.family_s / self.members * 1e6:9.1f} us per member ({how})",
            f"  {'one sweep per member':<24}{self.loop_s * 1e3:10.2f} ms  {self.loop_s / self.family_s:5.1f}   "
            f"{self.loop_s / self.members * 1e6:9.1f} us per member",
            f"  the family against each member swept alone: largest difference {self.agreement:.1e} (relative to "
            f"its kind's largest value{where})",
            f"  the family against the 50-digit reference at {self.checked} rows: {worst} (relative to each kind's "
            "size)"]

    def as_json(self) -> dict[str, Any]:
        return {"title": self.title, "members": self.members, "rows": self.rows, "spread": self.spread,
                "seed": self.seed, "batched": self.batched, "family_s": self.family_s, "loop_s": self.loop_s,
                "ratio": self.loop_s / self.family_s, "agreement": self.agreement,
                "agreement_column": self.agreement_column, "errors": self.errors,
                "checked_rows": self.checked}


def family_points(scene: Scene, members: int, spread: float,
                  seed: int) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """Every point of every link and every slide line, as ``sweep_family`` takes them: each link's points (and the
    ``through`` of the slides it guides) times a factor of its own per member, drawn from [1 - spread, 1 + spread]
    with ``seed`` (Python's Mersenne Twister, one draw order)."""
    rng = random.Random(seed)
    factors = [[rng.uniform(1.0 - spread, 1.0 + spread) for _ in scene.links] for _ in range(members)]
    column = {link.name: np.array([row[index] for row in factors]) for index, link in enumerate(scene.links)}
    points = {f"{p.name}@{link.name}": column[link.name][:, None] * np.array(p.local, np.float64)[None, :]
              for link in scene.links for p in link.points}
    slides = {s.name: column[s.guide][:, None] * np.array(s.through, np.float64)[None, :] for s in scene.sliders}
    return points, slides


def run_family(scene: Scene, members: int, rows: int, *, spread: float = 0.05, seed: int = 0,
               rounds: int = 3) -> FamilyBench:
    """Time the family and the loop over ``rows`` rows of the scene's range, and measure both (see the module)."""
    points, slides = family_points(scene, members, spread, seed)
    family = sweep_family(scene, points, steps=rows, slides=slides)  # the plan prepared, as a repeated call finds it
    best = math.inf
    for _ in range(rounds):
        t0 = time.perf_counter()
        family = sweep_family(scene, points, steps=rows, slides=slides)
        best = min(best, time.perf_counter() - t0)
    start, stop = _ends(scene, family)
    scenes = [family.member_scene(k) for k in range(members)]
    t0 = time.perf_counter()
    alone = [sweep(member, steps=rows, start=start, stop=stop) for member in scenes]
    loop_s = time.perf_counter() - t0
    errors, checked = _reference_errors(family, alone, scenes)
    return FamilyBench(scene.title, members, len(family.input.values), spread, seed, family.batched, best, loop_s,
                       *_agreement(family, alone), errors, checked)


def _ends(scene: Scene, family: FamilyResult) -> tuple[float, float]:
    """The family's range, as ``sweep`` takes it for a member (a full turn whether the member turns fully or not)."""
    values = family.input.values
    stop = float(values[-1])
    if isinstance(scene.input, LinkInput) and family.member(0).periodic:
        stop = float(values[0]) + (360.0 if scene.units.angle == "deg" else 2.0 * math.pi)
    return float(values[0]), stop


def _agreement(family: FamilyResult, alone: list[SweepResult]) -> tuple[float, str]:
    """The largest difference between the family and the loop over the rows both find ok, relative to the largest
    value of its column's kind, and the column where it is."""
    worst, where = 0.0, ""
    for k, result in enumerate(alone):
        scale: dict[str, float] = {}
        for column in result.columns:
            scale[column.kind] = max(scale.get(column.kind, 0.0), float(np.abs(column.values[column.valid]).max(
                initial=0.0)))
        ok = (result.status == 0) & (family.status[k] == 0)
        for column in result.columns:
            mine = family.column(column.name).values[k]
            difference = np.abs(mine - column.values)[ok & column.valid]
            if column.kind == "angle":
                full = 360.0 if family.scene.units.angle == "deg" else 2.0 * math.pi
                difference = np.minimum(difference, np.abs(difference - full))
            if difference.size and scale[column.kind] > 0.0 and float(difference.max()) / scale[column.kind] > worst:
                worst, where = float(difference.max()) / scale[column.kind], column.name
    return worst, where


def _reference_errors(family: FamilyResult, alone: list[SweepResult],
                      scenes: list[Scene]) -> tuple[dict[str, float], int]:
    """The family's largest error per kind against the reference, at ``CHECKED_ROWS`` ok rows of each of the first
    ``CHECKED_MEMBERS`` members."""
    errors: dict[str, float] = {}
    checked = 0
    degrees = family.scene.units.angle == "deg"
    for k in range(min(CHECKED_MEMBERS, family.members)):
        solution = solve(scenes[k])
        keys = bench_keys(solution)
        assert solution.inside is not None
        mechanism, origin = solution.inside.mechanism, solution.inside.frame.origin
        guesses = row_guesses(alone[k])
        ok = [int(n) for n in np.flatnonzero(family.status[k] == 0) if guesses[n] is not None]
        for n in [ok[int(i)] for i in np.linspace(0, len(ok) - 1, min(CHECKED_ROWS, len(ok))).round()] if ok else []:
            value = float(family.input.values[n])
            t = math.radians(value) if isinstance(family.scene.input, LinkInput) and degrees else value
            try:
                got = solve_at(solution, t, guesses[n])
                assert got.inside is not None
                reference = reference_values(mechanism, got.inside.pose, list(keys), t=t, origin=origin)
            except KinepolyError:
                continue
            values = _values(family, k, n, keys, degrees)
            for kind, error in kind_errors(values, reference, dict(got.check.scales)).items():
                errors[kind] = max(errors.get(kind, 0.0), error)
            checked += 1
    return errors, checked


def _values(family: FamilyResult, k: int, row: int, keys: tuple[str, ...], degrees: bool) -> dict[str, Any]:
    """The family's values of member ``k`` at ``row`` under the bench's keys (the columns it has of them)."""
    names = {c.name for c in family.columns}
    out: dict[str, Any] = {}

    def at(name: str) -> float:
        return float(family.column(name).values[k, row])

    for key in keys:
        kind, name, what = key.split(".")
        if kind == "points":
            prefix = {"position": "r", "velocity": "v", "acceleration": "a"}[what]
            if f"{prefix}_{name}_x" in names:
                out[key] = (at(f"{prefix}_{name}_x"), at(f"{prefix}_{name}_y"))
        elif kind == "links":
            column = {"omega": "omega", "alpha": "alpha", "angle": "theta"}[what] + f"_{name}"
            if column in names:
                out[key] = math.radians(at(column)) if what == "angle" and degrees else at(column)
    return out
