"""``kinepoly bench SCENE [--json] [--plot FILE.png] [--sweep [N]]``: error against run time.

The CLI adds the arguments and prints the lines ``run_bench_command`` returns; the only file
written is the plot (whole or not at all).
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import time
from typing import Any

from kinepoly.errors import SceneError

__all__ = ["DEFAULT_SWEEP", "add_arguments", "bench_json", "bench_text", "run_bench_command", "sweep_json",
           "sweep_text"]

DEFAULT_SWEEP = 120
"""Inputs of a sweep when ``--sweep`` is given without a number."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML); it needs an [input] (a crank or a driven slider)")
    parser.add_argument("--json", action="store_true",
                        help='print {"methods": [{"name", "error", "time_s", ...}, ...]} as one JSON object')
    parser.add_argument("--plot", metavar="FILE.png",
                        help="draw the work-precision diagram (with --sweep: the error over the input)")
    parser.add_argument("--sweep", metavar="N", type=int, nargs="?", const=DEFAULT_SWEEP,
                        help=f"the error of each method at N inputs over a full turn of the input (a slider: its "
                             f"stroke), singular positions marked; N defaults to {DEFAULT_SWEEP}")
    parser.add_argument("--budget", metavar="SECONDS", type=float, default=0.25,
                        help="time spent repeating each method for its median (default 0.25 s)")


def _seconds(value: float) -> str:
    for factor, unit in ((1.0, "s"), (1e-3, "ms"), (1e-6, "us"), (1e-9, "ns")):
        if value >= factor:
            return f"{value / factor:.3g} {unit}"
    return f"{value:.3g} s"


def _rows(header: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[c]) for r in [header, *rows]) for c in range(len(header))]

    def line(row: list[str]) -> str:
        return "  ".join(v.ljust(w) if k == 0 else v.rjust(w) for k, (v, w) in enumerate(zip(row, widths, strict=True)))

    return [line(header), "  ".join("-" * w for w in widths), *(line(r) for r in rows)]


def bench_text(result: Any) -> list[str]:
    """The bench as a table, with time ratios against the construction measured in the same run."""
    base = result.method("construction").time_s
    rows = []
    failures = []
    for m in result.methods:
        if m.failure:
            rows.append([m.name, "fails", "", "", "", "", ""])
            failures.append(f"{m.name}: {m.failure}")
            continue
        batch = f"x{m.batch}" if m.batch > 1 else "1"
        rows.append([m.name, f"{m.error:.2g}", _seconds(m.time_s), f"{m.time_s / base:.3g}", batch,
                     str(m.repeats), str(m.quantities)])
    return [f"{result.title}: error against run time at {result.where}",
            (f"reference: mpmath, {result.reference_digits} digits ({_seconds(result.reference_s)}); error: normwise "
             "relative, the worst kind of quantity; time: median of repeats, per position"),
            (f"the construction's error estimate (from the conditioning): {result.estimate:.2g}"
             if result.estimate is not None else ""), "",
            *_rows(["method", "error", "time/position", "time/construction", "batch", "repeats", "quantities"], rows),
            *(["", "no answer:"] + [f"  {f}" for f in failures] if failures else [])]


def bench_json(result: Any) -> dict[str, Any]:
    methods = []
    for m in result.methods:
        entry: dict[str, Any] = {"name": m.name, "family": m.family,
                                 "error": m.error if math.isfinite(m.error) else None,
                                 "time_s": m.time_s if math.isfinite(m.time_s) else None,
                                 "errors": _finite(m.errors), "batch": m.batch, "repeats": m.repeats,
                                 "quantities": m.quantities}
        if m.step is not None:
            entry["step"] = m.step
        if m.failure:
            entry["failure"] = m.failure
        methods.append(entry)
    return {"scene": result.title, "input": result.where, "estimate": result.estimate,
            "reference": {"digits": result.reference_digits, "time_s": result.reference_s}, "methods": methods}


def _summary(sweep: Any) -> list[dict[str, Any]]:
    out = []
    for name in sweep.methods:
        errs = [(p.errors[name], p.t) for p in sweep.points if p.status == "ok" and math.isfinite(p.errors.get(name,
                                                                                                            math.nan))]
        if not errs:
            continue
        worst = max(errs)
        out.append({"name": name, "error": worst[0], "median_error": statistics.median(e for e, _ in errs),
                    "worst_at": sweep.shown(worst[1]), "positions": len(errs)})
    return out


def _finite(errors: dict[str, float]) -> dict[str, float | None]:
    return {k: (v if math.isfinite(v) else None) for k, v in errors.items()}


def sweep_json(sweep: Any) -> dict[str, Any]:
    return {"scene": sweep.title, "methods": _summary(sweep),
            "sweep": {"input": sweep.input_name, "unit": sweep.input_unit,
                      "singular": [sweep.shown(t) for t in sweep.singular],
                      "points": [{"input": sweep.shown(p.t), "status": p.status, "errors": _finite(p.errors),
                                  **({"estimate": p.estimate} if p.estimate is not None else {}),
                                  **({"message": p.message} if p.message else {})} for p in sweep.points]}}


def sweep_text(sweep: Any) -> list[str]:
    counts = {s: sum(1 for p in sweep.points if p.status == s) for s in ("ok", "singular", "cannot-assemble")}
    rows = [[m["name"], f"{m['median_error']:.2g}", f"{m['error']:.2g}", f"{m['worst_at']:.6g}"]
            for m in _summary(sweep)]
    within = [p for p in sweep.points if p.status == "ok" and p.estimate is not None]
    name = sweep.methods[0]
    bounded = sum(1 for p in within if p.errors[name] <= p.estimate)
    singular = ", ".join(f"{sweep.shown(t):.6g}" for t in sweep.singular) or "none"
    return [(f"{sweep.title}: error over {sweep.input_name} ({len(sweep.points)} inputs: {counts['ok']} solved, "
             f"{counts['singular']} singular, {counts['cannot-assemble']} cannot be assembled)"),
            f"singular positions ({sweep.input_unit}): {singular}",
            f"the construction's error is within its estimate at {bounded} of {len(within)} solved inputs", "",
            *_rows(["method", "median error", "worst error", f"worst at ({sweep.input_unit})"], rows)]


def run_bench_command(args: argparse.Namespace) -> list[str]:
    """Load, solve, bench (or sweep), plot; the lines to print."""
    from kinepoly.scene.loader import load_scene
    from kinepoly.scene.spec import GivenInput
    from kinepoly.solution import solve

    try:
        import mpmath  # type: ignore[import-untyped]  # noqa: F401
    except ImportError:
        raise SceneError("kinepoly bench measures errors against an mpmath reference: install it with "
                         "pip install 'kinepoly[bench]'") from None
    scene = load_scene(args.scene)
    if isinstance(scene.input, GivenInput):
        raise SceneError(f"{scene.source}: given: kinepoly bench needs a scene driven by [input] (a crank or a "
                         "driven slider); a [given] scene has no input to vary")
    if args.sweep is not None and args.sweep < 2:
        raise SceneError(f"--sweep {args.sweep}: expected at least 2 inputs")
    t0 = time.perf_counter()
    solution = solve(scene)
    if args.sweep is not None:
        from kinepoly.bench.sweep import run_sweep

        sweep = run_sweep(solution, args.sweep)
        if args.plot:
            from kinepoly.bench.plot import plot_sweep

            plot_sweep(sweep, args.plot)
        lines = [json.dumps(sweep_json(sweep), indent=1, allow_nan=False)] if args.json else sweep_text(sweep)
    else:
        from kinepoly.bench.run import run_bench

        result = run_bench(solution, budget_s=args.budget)
        if args.plot:
            from kinepoly.bench.plot import plot_work_precision

            plot_work_precision(result, args.plot)
        lines = [json.dumps(bench_json(result), indent=1, allow_nan=False)] if args.json else bench_text(result)
    if args.plot and not args.json:
        lines.append(f"wrote {args.plot} ({time.perf_counter() - t0:.1f} s in all)")
    return lines
