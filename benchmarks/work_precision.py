"""Error against run time for the standard examples and a near-dead-centre case (``kinepoly bench``).

For each scene every method's error is measured against the 50-digit mpmath reference and its
time per position is the median of repeats; the last column is the ratio to the construction's
time measured in the same run, so a loaded machine moves both alike.

    python benchmarks/work_precision.py [--budget SECONDS] [--docs]

``--docs`` also redraws the four figures of docs/accuracy.md (work-precision and sweep, for the
four-bar example and for the piston-driven slider-crank near its dead centre).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import kinepoly
from kinepoly.bench.plot import plot_sweep, plot_work_precision
from kinepoly.bench.report import bench_text, sweep_text
from kinepoly.bench.run import run_bench
from kinepoly.bench.sweep import run_sweep

ROOT = Path(__file__).resolve().parent.parent
SCENES = [ROOT / "examples" / "four-bar.toml", ROOT / "examples" / "slider-crank.toml",
          ROOT / "examples" / "slotted-lever.toml", ROOT / "benchmarks" / "scenes" / "piston-near-dead-centre.toml"]
FIGURES = {"four-bar": ROOT / "examples" / "four-bar.toml",
           "dead-centre": ROOT / "benchmarks" / "scenes" / "piston-near-dead-centre.toml"}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--budget", type=float, default=0.5, help="seconds of repeats per method (default 0.5)")
    parser.add_argument("--docs", action="store_true", help="redraw the figures of docs/accuracy.md")
    parser.add_argument("--sweep", type=int, default=120, help="inputs of the sweeps drawn with --docs")
    args = parser.parse_args()
    figures = {path: name for name, path in FIGURES.items()}
    for path in SCENES:
        t0 = time.perf_counter()
        solution = kinepoly.solve(kinepoly.load_scene(path))
        result = run_bench(solution, budget_s=args.budget)
        print("\n".join(bench_text(result)))
        print(f"({time.perf_counter() - t0:.1f} s)\n")
        if args.docs and path in figures:  # the figures show the very run printed above
            name = figures[path]
            (ROOT / "docs" / f"accuracy-{name}.png").write_bytes(plot_work_precision(result))
            sweep = run_sweep(solution, args.sweep)
            (ROOT / "docs" / f"accuracy-{name}-sweep.png").write_bytes(plot_sweep(sweep))
            print("\n".join(sweep_text(sweep)) + "\n")
            print(f"wrote docs/accuracy-{name}.png and docs/accuracy-{name}-sweep.png\n")


if __name__ == "__main__":
    main()
