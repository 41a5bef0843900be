"""The construction's error as an input approaches a dead point, from 1e-1 to 1e-8 rad.

For a piston-driven slider-crank (crank 40, rod 120: its outer dead centre), a four-bar whose
input rocks (frame 100, input 60, coupler 70, rocker 50: the limit where coupler and rocker line
up) and a slotted lever at a slide reversal (frame 80, crank 40), it prints the condition number
k of the velocity equations, the flattest crossing of direction lines, the error estimate, the
construction's error against the 50-digit reference and its difference from the analytic check.

    python benchmarks/dead_point_approach.py
"""

from __future__ import annotations

import math

import kinepoly
from kinepoly.bench.cases import four_bar_limit, piston, slotted_lever_reversal
from kinepoly.bench.methods import construction_values
from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import kind_errors
from kinepoly.errors import SingularityError

CASES = {
    "piston-driven slider-crank": lambda d: piston(40, 120, d),
    "four-bar at the limit of its rocking input": lambda d: four_bar_limit(100, 60, 70, 50, d),
    "slotted lever at a slide reversal": lambda d: slotted_lever_reversal(80, 40, d),
}


def main() -> None:
    for title, make in CASES.items():
        print(title)
        print(f"{'distance':>9s} {'k':>9s} {'angle':>10s} {'estimate':>9s} {'error':>9s} {'vs analytic':>11s}")
        for n in range(1, 9):
            distance = 10.0**-n
            try:
                solution = kinepoly.solve(make(distance))
            except SingularityError as error:
                print(f"{distance:9.0e}  singular (exit 3): {str(error)[:90]}...")
                continue
            assert solution.inside is not None and solution.accuracy is not None
            keys = tuple(q.key for q in solution.check.quantities)
            reference = reference_values(solution.inside.mechanism, solution.inside.pose, list(keys),
                                         origin=solution.inside.frame.origin)
            truth = kind_errors(construction_values(solution, keys, solution.inside.frame.origin), reference,
                                dict(solution.check.scales))
            flat = min((abs(c.sin_angle) for c in solution.accuracy.estimate.worst_crossing.values()), default=1.0)
            print(f"{distance:9.0e} {solution.check.condition_number:9.2g} "
                  f"{math.degrees(math.asin(min(flat, 1.0))):8.2g}deg {solution.accuracy.estimate.largest:9.2g} "
                  f"{max(truth.values()):9.2g} {solution.check.max_rel_error:11.2g}")
        print()


if __name__ == "__main__":
    main()
