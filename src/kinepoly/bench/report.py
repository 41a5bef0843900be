"""What ``kinepoly bench`` prints: the bench and the sweep as tables or JSON. Pure functions.

The command line (``kinepoly.cli.bench``) prints these lines and writes the plot.
"""

from __future__ import annotations

import math
import statistics
from typing import Any

__all__ = ["bench_json", "bench_text", "sweep_json", "sweep_text"]


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
        errs = [(p.errors[name], p.t) for p in sweep.points if p.measured and math.isfinite(p.errors.get(name,
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
    counts = {s: sum(1 for p in sweep.points if p.status == s)
              for s in ("ok", "near-singular", "singular", "cannot-assemble")}
    rows = [[m["name"], f"{m['median_error']:.2g}", f"{m['error']:.2g}", f"{m['worst_at']:.6g}"]
            for m in _summary(sweep)]
    within = [p for p in sweep.points if p.measured and p.estimate is not None]
    name = sweep.methods[0]
    bounded = sum(1 for p in within if p.errors[name] <= p.estimate)
    singular = ", ".join(f"{sweep.shown(t):.6g}" for t in sweep.singular) or "none"
    return [(f"{sweep.title}: error over {sweep.input_name} ({len(sweep.points)} inputs: {counts['ok']} ok, "
             f"{counts['near-singular']} near-singular, {counts['singular']} singular, "
             f"{counts['cannot-assemble']} cannot be assembled)"),
            f"singular positions ({sweep.input_unit}): {singular}",
            f"the construction's error is within its estimate at {bounded} of {len(within)} measured inputs", "",
            *_rows(["method", "median error", "worst error", f"worst at ({sweep.input_unit})"], rows)]
