"""Calibrate the constants of the error estimates (``kinepoly.check.estimate``).

Draws random mechanisms of every standard kind (``kinepoly.bench.cases.random_case``: four-bars,
slider-cranks driven by the crank or the piston, slotted levers; ordinary poses and inputs 1e-1 to
1e-8 rad short of a dead point; sizes 1e-3 to 1e3; speeds 1e-2 to 1e2 rad/s), solves each, and
measures the construction's error two ways: against the 50-digit reference and against the
analytic solution (what ``solve`` reports). It prints, for each class of quantity, the ratio of
the larger of the two to u k (positions) or u k^2 (velocities, accelerations), and how many
cases the current constants bound.

    python benchmarks/calibrate_estimates.py [--cases N] [--seed S]
"""

from __future__ import annotations

import argparse
import random
import time

import kinepoly
from kinepoly.bench.cases import random_case
from kinepoly.bench.methods import construction_values
from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import kind_errors
from kinepoly.check.estimate import C_ACCELERATION, C_POSITION, C_VELOCITY
from kinepoly.errors import SingularityError
from kinepoly.geom.tolerances import UNIT_ROUNDOFF as U

CLASS = {"position": "position", "angle": "position", "velocity": "velocity", "omega": "velocity",
         "acceleration": "acceleration", "alpha": "acceleration"}
CONSTANT = {"position": C_POSITION, "velocity": C_VELOCITY, "acceleration": C_ACCELERATION}


def _percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cases", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=11)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    ratios: dict[str, list[float]] = {c: [] for c in CONSTANT}
    bounded = {c: 0 for c in CONSTANT}
    all_bounded = solved = singular = 0
    kinds: dict[str, int] = {}
    t0 = time.perf_counter()
    for _ in range(args.cases):
        case = random_case(rng)
        kinds[case.kind] = kinds.get(case.kind, 0) + 1
        try:
            solution = kinepoly.solve(case.scene)
        except SingularityError:
            singular += 1
            continue
        assert solution.inside is not None and solution.accuracy is not None
        solved += 1
        keys = tuple(q.key for q in solution.check.quantities)
        reference = reference_values(solution.inside.mechanism, solution.inside.pose, list(keys),
                                     origin=solution.inside.frame.origin)
        truth = kind_errors(construction_values(solution, keys, solution.inside.frame.origin), reference,
                            dict(solution.check.scales))
        k = max(solution.check.condition_number, 1.0)
        every = True
        for cls in CONSTANT:
            err = max([max(truth.get(kind, 0.0), solution.check.relative.get(kind, 0.0))
                       for kind in CLASS if CLASS[kind] == cls] or [0.0])
            base = U * k if cls == "position" else U * k * k
            ratios[cls].append(err / base)
            within = all(max(truth.get(kind, 0.0), solution.check.relative.get(kind, 0.0))
                         <= solution.accuracy.estimate.relative.get(kind, 0.0) for kind in CLASS if CLASS[kind] == cls)
            bounded[cls] += within
            every &= within
        all_bounded += every
    print(f"{args.cases} random cases (seed {args.seed}) in {time.perf_counter() - t0:.0f} s: "
          + ", ".join(f"{n} {k}" for k, n in sorted(kinds.items())))
    print(f"solved {solved}; singular (exit 3, condition above 1e7) {singular}")
    print(f"{'class':13s} {'base':6s} {'median':>8s} {'p90':>8s} {'p99':>8s} {'max':>8s}  constant  bounded")
    for cls, values in ratios.items():
        base = "u k" if cls == "position" else "u k^2"
        print(f"{cls:13s} {base:6s} {_percentile(values, 0.5):8.2g} {_percentile(values, 0.9):8.2g} "
              f"{_percentile(values, 0.99):8.2g} {max(values):8.2g}  {CONSTANT[cls]:8g}  "
              f"{bounded[cls]}/{solved} ({100 * bounded[cls] / solved:.1f}%)")
    print(f"every quantity of the case within its estimate: {all_bounded}/{solved} ({100 * all_bounded / solved:.1f}%)")


if __name__ == "__main__":
    main()
