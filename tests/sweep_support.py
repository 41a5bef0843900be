"""Helpers for the sweep tests: ask for everything, and solve one row with ``kinepoly.solve``."""

from __future__ import annotations

import math
import re

import kinepoly
from kinepoly.geom.lines import ParallelLinesError
from kinepoly.model.mechanism import build_mechanism
from kinepoly.sweep import SweepResult

__all__ = ["ask_everything", "compare_row", "row_scene"]

_FIND = re.compile(r"(?ms)^\[find\].*?(?=^\[|\Z)")
_GUESS = re.compile(r"(?ms)^\[guess\].*?(?=^\[|\Z)")


def _quoted(names: list[str]) -> str:
    return "[" + ", ".join(f'"{n}"' for n in names) + "]"


def ask_everything(text: str) -> str:
    """The scene with a [find] that asks every point, every turning link and every slider."""
    text = _FIND.sub("", text)
    mech = build_mechanism(kinepoly.loads_scene(text))
    points = list(dict.fromkeys(p.name for link in mech.scene.links if link.name != mech.ground
                                for p in link.points))
    links = [n for n in mech.link_names if not mech.turns_with_ground(n)]
    return (text + f"\n[find]\nvelocity = {_quoted(points)}\nacceleration = {_quoted(points)}\n"
            f"omega = {_quoted(links)}\nalpha = {_quoted(links)}\nsliders = "
            f"{_quoted([s.name for s in mech.sliders])}\n")


def row_scene(text: str, result: SweepResult, row: int) -> str:
    """The scene at the sweep's row: its input there, and every point guessed where the sweep put it."""
    value = float(result.input.values[row])
    if result.input.name.startswith("theta"):
        text = re.sub(r"(?m)^angle = .*$", f"angle = {value!r}", text, count=1)
    else:
        text = re.sub(r"(?m)^s = .*$", f"s = {value!r}", text, count=1)
    guesses = []
    for col in result.columns:
        if col.name.startswith("r_") and col.name.endswith("_x") and "@" not in col.name and col.valid[row]:
            y = result.column(col.name[:-2] + "_y").values[row]
            guesses.append(f"{col.name[2:-2]} = [{float(col.values[row])!r}, {float(y)!r}]")
    return _GUESS.sub("", text) + "\n[guess]\n" + "\n".join(guesses) + "\n"


def _reference(solution: kinepoly.Solution) -> dict[str, float]:
    data = kinepoly.to_json(solution)
    out: dict[str, float] = {}
    for link, v in data.get("links", {}).items():
        for key, name in (("angle", "theta"), ("omega", "omega"), ("alpha", "alpha")):
            if key in v:
                out[f"{name}_{link}"] = v[key]
    for point, v in data.get("points", {}).items():
        for key, prefix in (("position", "r"), ("velocity", "v"), ("acceleration", "a")):
            if key in v:
                out[f"{prefix}_{point}_x"], out[f"{prefix}_{point}_y"] = v[key]
    for name, v in data.get("sliders", {}).items():
        out[f"s_{name}"] = v["s"]
        for key in ("s_dot", "s_ddot"):
            if key in v:
                out[f"{key}_{name}"] = v[key]
        if "coriolis" in v and solution.mechanism.slider(name).guide != solution.mechanism.ground:
            out[f"coriolis_{name}_x"], out[f"coriolis_{name}_y"] = v["coriolis"]  # the sweep leaves a frame guide's out
    return out


def compare_row(text: str, result: SweepResult, row: int) -> float:
    """The largest normwise relative difference between the sweep's row and ``kinepoly.solve`` there.

    Each kind of quantity is scaled by its natural size over the whole sweep; angles are compared in
    radians, absolutely; within 5.7 degrees of a dead point (the row's smallest transmission angle mu)
    the difference is divided by (0.1 / sin mu)^3, the growth of the rounding errors of both there.
    Raises AssertionError when a status disagrees.
    """
    status = result.status_name(row)
    try:
        solution = kinepoly.solve(kinepoly.loads_scene(row_scene(text, result, row)))
    except kinepoly.AssemblyError:
        assert status in ("cannot-assemble", "near-singular"), (row, status)
        return 0.0
    except kinepoly.SingularityError:
        assert status in ("singular", "near-singular"), (row, status, result.warnings.get(row))
        return 0.0
    except ParallelLinesError:  # solve's construction meets a zero-length direction (a pin on a pivot)
        assert status in ("cannot-assemble", "singular"), (row, status)
        return 0.0
    assert status != "cannot-assemble", (row, result.warnings.get(row))
    if any(n.code == "default-assembly" for n in solution.notices):
        return 0.0  # no guessed point tells the assemblies apart (a slot through its pivot): no definite row
    if any(n.code == "near-singular" for n in solution.notices):
        assert status in ("near-singular", "singular"), (row, status)
    worst = 0.0
    # near a dead point both computations lose digits (errors grow like 1/sin(mu)^3 for accelerations):
    # compare there within that bound, elsewhere to 1e-10
    sines = [math.sin(math.radians(float(c.values[row])) if result.scene.units.angle == "deg" else float(c.values[row]))
             for c in result.columns if c.kind == "transmission" and c.valid[row]]
    loosen = max(1.0, (0.1 / max(min(sines, default=1.0), 1e-12)) ** 3)
    # and never tighter than the solve's own error estimate allows (each side may be off by it)
    if solution.accuracy is not None:
        loosen = max(loosen, 2.0 * solution.accuracy.estimate.largest / 1e-10)
    for key, want in _reference(solution).items():
        if key == result.input.name:
            continue
        col = result.column(key)
        if not col.valid[row]:
            assert status == "singular" and col.order > 0, (key, row, status)
            continue
        got = float(col.values[row])
        if col.kind == "angle":
            turn = 360.0 if result.scene.units.angle == "deg" else 2 * math.pi
            worst = max(worst, abs(math.remainder(got - want, turn)) * (2 * math.pi / turn))
            continue
        worst = max(worst, abs(got - want) / max(_natural_scale(result, col.kind), 1e-300) / loosen)
    return worst


_FAMILY = {"position": "position", "slider": "position", "velocity": "velocity", "slider-rate": "velocity",
           "acceleration": "acceleration", "slider-acceleration": "acceleration", "coriolis": "acceleration",
           "omega": "omega", "alpha": "alpha"}


def _natural_scale(result: SweepResult, kind: str) -> float:
    """The size of a kind of quantity over the whole sweep, and what the other kinds imply for it
    (as ``kinepoly.solve`` scales its check): alpha at least omega^2, velocities at least size x omega."""
    largest: dict[str, float] = {}
    for c in result.columns:
        family = _FAMILY.get(c.kind)
        if family is not None:
            largest[family] = max(largest.get(family, 0.0), float(abs(c.values[c.valid]).max(initial=0.0)))
    size, omega, alpha = (largest.get(k, 0.0) for k in ("position", "omega", "alpha"))
    implied = {"position": size, "omega": omega, "alpha": max(alpha, omega * omega),
               "velocity": max(largest.get("velocity", 0.0), size * omega),
               "acceleration": max(largest.get("acceleration", 0.0), size * (omega * omega + alpha))}
    return implied[_FAMILY[kind]]
