"""What ``kinepoly solve`` prints of the instant centers: JSON, table rows, steps. Pure functions.

``report`` calls these; they read only ``Solution.centers`` (``engine.centers.InstantCenters``).
"""

from __future__ import annotations

from typing import Any

from kinepoly.engine.centers import InstantCenter, InstantCenters, KennedyLine, KennedyStep
from kinepoly.engine.circle_diagram import center_label
from kinepoly.geom.vec import Vec
from kinepoly.present.clean import Noise
from kinepoly.present.phrasing import Context, center_omega_sentence, english, kennedy_sentence

__all__ = ["centers_json", "centers_steps_text", "centers_table", "kennedy_steps_json"]


def _pair(v: Vec) -> list[float]:
    return [float(v[0]) + 0.0, float(v[1]) + 0.0]


def _fmt(x: float) -> str:
    return f"{x:.6g}"


def _where(center: InstantCenter) -> dict[str, list[float]]:
    """The contract's value of a center: {"position": [x, y]} or {"direction": [ux, uy]} at infinity."""
    if center.position is not None:
        return {"position": _pair(center.position)}
    assert center.direction is not None
    return {"direction": _pair(center.direction)}


def centers_json(centers: InstantCenters) -> dict[str, dict[str, list[float]]]:
    """``instant_centers`` of the result: every asked center under the key the scene used."""
    return {key: _where(centers.centers[name]) for key, name in centers.asked}


def _line_json(line: KennedyLine) -> dict[str, Any]:
    out: dict[str, Any] = {"label": line.label, "centers": list(line.centers)}
    if line.is_common_normal:
        out["contact"] = line.contact
    if line.through is None or line.direction is None:
        out["at_infinity"] = True
    else:
        out["through"] = _pair(line.through)
        out["direction"] = _pair(line.direction)
    return out


def _step_json(centers: InstantCenters, step: KennedyStep, context: Context) -> dict[str, Any]:
    center = centers.centers[step.center]
    used = [name for line in step.lines for name in line.centers]
    return {
        "polygon": "instant-centers",
        "kind": "kennedy",
        "equation": step.equation,
        "text": kennedy_sentence(step, english(), context),
        "result": center.label,
        "center": _where(center),
        "known": [{"term": center_label(name), "known": centers.centers[name].found} for name in dict.fromkeys(used)]
        + [{"term": line.label, "known": "common normal at the contact"}
           for line in step.lines if line.is_common_normal],
        "lines": [_line_json(line) for line in step.lines],
        "vectors": [],
    }


def kennedy_steps_json(centers: InstantCenters, context: Context) -> list[dict[str, Any]]:
    """One step of kind ``kennedy`` per derived center, in the order found; lines in the scene's lengths.

    ``context`` is the solution the centers belong to, for the words of ``text`` (English).
    """
    return [_step_json(centers, step, context) for step in centers.steps]


def _place_text(center: InstantCenter, noise: Noise) -> str:
    if center.position is not None:
        x, y = noise.pair(center.position, "position")
        return f"({_fmt(x)}, {_fmt(y)})"
    assert center.direction is not None
    ux, uy = noise.pair(center.direction, "direction")
    return f"at infinity, direction ({_fmt(ux)}, {_fmt(uy)})"


def _found_text(centers: InstantCenters, center: InstantCenter) -> str:
    for edge in centers.diagram.edges:
        if edge.name == center.name and edge.number > 0:
            return f"{center.found}: {edge.via}"
    return center.found


def centers_table(centers: InstantCenters, unit: str, relative: float | None, noise: Noise | None = None) -> list[str]:
    """Rows of the asked centers, then the omegas they give and how they agree with the others.

    ``noise`` sets coordinates below their error estimate to 0 (``present.clean``)."""
    noise = noise if noise is not None else Noise()
    rows = [[center_label(key), _place_text(centers.centers[name], noise), _found_text(centers, centers.centers[name])]
            for key, name in centers.asked]
    widths = [max(len(r[c]) for r in [["center", f"position ({unit})", "found"], *rows]) for c in range(3)]
    out = ["  ".join(v.ljust(w) for v, w in zip(row, widths, strict=True)).rstrip()
           for row in [["center", f"position ({unit})", "found"], ["-" * w for w in widths], *rows]]
    if centers.omegas:
        values = ", ".join(f"{o.symbol} = {_fmt(noise.value(o.omega, 'omega'))}" for o in centers.omegas)
        agree = ("" if relative is None
                 else f"; against the polygon and the analytic solution: {relative:.2g} (relative)")
        out.append(f"omega from the instant centers (rad/s): {values}{agree}")
    return out


def centers_steps_text(centers: InstantCenters, first_number: int, context: Context) -> list[str]:
    """The Kennedy steps numbered from ``first_number``, then the omegas the centers give (in English)."""
    out: list[str] = []
    for n, step in enumerate(centers.steps, first_number):
        out.append(f"{n:>2}. [instant centers, kennedy] {step.equation}")
        out.append(f"    {kennedy_sentence(step, english(), context)}")
        out.append("    known: " + "; ".join([f"{center_label(name)} ({centers.centers[name].found})"
                                             for name in dict.fromkeys(c for ln in step.lines for c in ln.centers)]
                                            + [f"{ln.label} (common normal at the contact {ln.contact})"
                                               for ln in step.lines if ln.is_common_normal]))
    if centers.omegas:
        out += ["", "angular velocities from the instant centers (a check of the polygon):"]
        out += [f"    {o.equation}: {center_omega_sentence(o, english(), context)}" for o in centers.omegas]
    return out
