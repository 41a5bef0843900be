"""What a sweep call costs whatever its length, and what each row adds: the four-bar example, in one run against
the numpy closed form of ``bench_sweep.py`` over the same rows.

- ``cold``: a scene not swept before (each call a scene of its own, as a variants class set or the editor's drag
  gives), 36 rows: the mechanism and plan built, the seed assembly solved, the rows executed;
- ``repeated``: the same scene again (``kinepoly.sweep.sweep`` keeps a scene's prepared sweep: its plan, seed
  assembly and default range found once), 36 rows;
- each with the default range (a full turn, checked on a coarse grid) and with ``--from``/``--to`` given;
- ``per row``: (3600 rows - 36 rows) / 3564 with the range given;
- the repeated 36-row call's stages (the sweep's own ``timing``: the rows found, then executed), and the Python
  function calls it makes (a count, free of the machine's load).

Times are the best of several rounds; ratios are to the closed form measured in the same run.

    python benchmarks/fixed_cost.py [--rounds 5]
"""

from __future__ import annotations

import argparse
import cProfile
import math
import pstats
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_sweep import closed_form

from kinepoly.scene.loader import loads_scene
from kinepoly.scene.spec import Scene
from kinepoly.sweep import sweep
from kinepoly.sweep.result import SweepResult

SCENE = ROOT / "examples" / "four-bar.toml"
FEW, MANY = 36, 3600
CALLS = 100


def _per_call(work: Callable[[int], object], calls: int, rounds: int) -> float:
    best = math.inf
    for r in range(rounds):
        t0 = time.perf_counter()
        for k in range(calls):
            work(r * calls + k)
        best = min(best, (time.perf_counter() - t0) / calls)
    return best


def _stages(work: Callable[[], SweepResult], calls: int) -> dict[str, float]:
    """The least of each stage's time (``SweepResult.timing``) over ``calls`` calls."""
    best: dict[str, float] = {}
    for _ in range(calls):
        for stage, seconds in work().timing.items():
            best[stage] = min(best.get(stage, math.inf), seconds)
    return best


def _function_calls(work: Callable[[], object]) -> int:
    profile = cProfile.Profile()
    profile.enable()
    work()
    profile.disable()
    return int(pstats.Stats(profile).total_calls)  # type: ignore[attr-defined]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rounds", type=int, default=5, help="rounds of each measurement; the best is kept")
    args = parser.parse_args()
    text = SCENE.read_text()
    fresh: list[Scene] = [loads_scene(text, f"four-bar-{k}.toml") for k in range(2 * args.rounds * CALLS)]
    same = loads_scene(text, "four-bar.toml")
    later = args.rounds * CALLS  # the second cold measurement's scenes: none swept before either
    theta_few = np.radians(np.linspace(0.0, 350.0, FEW + 1))
    theta_many = np.radians(np.linspace(0.0, 359.9, MANY + 1))
    figures = {
        "closed form, 36 rows": _per_call(lambda k: closed_form(theta_few), CALLS, args.rounds),
        "closed form, 3600 rows": _per_call(lambda k: closed_form(theta_many), CALLS // 10, args.rounds),
        "cold call, 36 rows, default range": _per_call(lambda k: sweep(fresh[k], steps=FEW), CALLS, args.rounds),
        "cold call, 36 rows, range given": _per_call(
            lambda k: sweep(fresh[later + k], steps=FEW, start=0.0, stop=350.0), CALLS, args.rounds),
        "repeated call, 36 rows, default range": _per_call(lambda k: sweep(same, steps=FEW), CALLS, args.rounds),
        "repeated call, 36 rows, range given": _per_call(
            lambda k: sweep(same, steps=FEW, start=0.0, stop=350.0), CALLS, args.rounds),
        "repeated call, 3600 rows, range given": _per_call(
            lambda k: sweep(same, steps=MANY, start=0.0, stop=359.9), CALLS // 10, args.rounds),
    }
    reference = figures["closed form, 36 rows"]
    print(f"four-bar.toml sweeps, best of {args.rounds} rounds; ratios to the closed form over 36 rows, same run")
    for name, seconds in figures.items():
        print(f"{name:42s} {seconds * 1e3:8.3f} ms  {seconds / reference:8.1f} x closed form (36 rows)")
    per_row = (figures["repeated call, 3600 rows, range given"] - figures["repeated call, 36 rows, range given"]) \
        / (MANY - FEW)
    closed_row = (figures["closed form, 3600 rows"] - reference) / (MANY - FEW)
    print(f"{'per row (3600 - 36 rows), range given':42s} {per_row * 1e6:8.3f} us  {per_row / closed_row:8.1f} x "
          f"closed form per row ({closed_row * 1e6:.3f} us)")
    for given, start, stop in (("default range", None, None), ("range given", 0.0, 350.0)):
        def call(start: float | None = start, stop: float | None = stop) -> SweepResult:
            return sweep(same, steps=FEW, start=start, stop=stop)
        stages = _stages(call, args.rounds * CALLS)
        print(f"repeated call, 36 rows, {given}: rows found {stages['range_s'] * 1e3:.3f} ms, executed "
              f"{stages['execute_s'] * 1e3:.3f} ms (least of each); {_function_calls(call)} Python function calls")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
