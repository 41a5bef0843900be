"""Two direction lines crossed two ways: homogeneous coordinates (``kinepoly.geom.intersect``)
against shapely/GEOS segments (``kinepoly.bench.methods.geos_crossing``), as their angle shrinks.

For each angle, 500 random pairs of lines (points in the unit square, random direction); the
error is |computed - exact| / |exact point|, the exact crossing computed in mpmath at 50 digits;
the time is per crossing, the best of five runs, measured in the same run for both.

    python benchmarks/crossings.py
"""

from __future__ import annotations

import math
import random
import time

import mpmath

from kinepoly.bench.methods import geos_crossing
from kinepoly.geom import Line, intersect


def main() -> None:
    mpmath.mp.dps = 50
    rng = random.Random(1)
    print(f"{'angle (rad)':>11s} {'homogeneous':>12s} {'GEOS':>10s} {'t homog.':>9s} {'t GEOS':>9s} {'ratio':>6s}")
    for angle in (1e-1, 1e-3, 1e-5, 1e-7, 1e-9):
        pairs = []
        for _ in range(500):
            p1, p2 = (rng.uniform(-1, 1), rng.uniform(-1, 1)), (rng.uniform(-1, 1), rng.uniform(-1, 1))
            t = rng.uniform(0, 2 * math.pi)
            pairs.append((Line(p1, (math.cos(t), math.sin(t))), Line(p2, (math.cos(t + angle), math.sin(t + angle)))))
        worst = {"homogeneous": 0.0, "GEOS": 0.0}
        for a, b in pairs:
            m = mpmath.matrix([[a.direction[0], -b.direction[0]], [a.direction[1], -b.direction[1]]])
            r = mpmath.lu_solve(m, mpmath.matrix([b.through[0] - a.through[0], b.through[1] - a.through[1]]))
            exact = (a.through[0] + r[0] * a.direction[0], a.through[1] + r[0] * a.direction[1])
            size = mpmath.sqrt(exact[0] ** 2 + exact[1] ** 2)
            for name, cross in (("homogeneous", intersect), ("GEOS", geos_crossing)):
                got = cross(a, b).point
                worst[name] = max(worst[name], float(mpmath.sqrt((got[0] - exact[0]) ** 2
                                                                 + (got[1] - exact[1]) ** 2) / size))
        times = {}
        for name, cross in (("homogeneous", intersect), ("GEOS", geos_crossing)):
            best = math.inf
            for _ in range(5):
                t0 = time.perf_counter()
                for a, b in pairs:
                    _ = cross(a, b).point
                best = min(best, (time.perf_counter() - t0) / len(pairs))
            times[name] = best
        print(f"{angle:11.0e} {worst['homogeneous']:12.2g} {worst['GEOS']:10.2g} {1e6 * times['homogeneous']:7.2f}us "
              f"{1e6 * times['GEOS']:7.2f}us {times['GEOS'] / times['homogeneous']:6.1f}")


if __name__ == "__main__":
    main()
