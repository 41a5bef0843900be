"""The sweep as CSV text: the input first, then the asked quantities, the transmission angles,
each row's status and its warnings. Cells of a quantity a row does not have are left empty."""

from __future__ import annotations

import csv
import io

from kinepoly.sweep.result import STATUS, SweepResult

__all__ = ["csv_text"]


def _cells(values: list[float], valid: list[bool]) -> list[str]:
    return [format(v, ".15g") if ok else "" for v, ok in zip(values, valid, strict=True)]


def csv_text(result: SweepResult) -> str:
    """One header line, then one line per row; numbers with 15 significant digits."""
    columns = [result.input, *result.columns]
    cells = [_cells(c.values.tolist(), c.valid.tolist()) for c in columns]
    status = [STATUS[int(level)] for level in result.status.tolist()]
    warnings = [result.warnings.get(k, "") for k in range(result.rows)]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow([c.name for c in columns] + ["status", "warnings"])
    writer.writerows(zip(*cells, status, warnings, strict=True))
    return out.getvalue()
