"""How fast is ``kinepoly sweep``? The four-bar example over 3600 positions, measured in one run against:

- a hand-written numpy closed form of the same four-bar (the textbook vector loop: the coupler
  angle from the triangle A B0 B, omegas and alphas by Cramer's rule on the differentiated loop);
- a loop of ``kinepoly.solve`` over the same 3600 inputs (one construction and check per input);
- the Python peers from PyPI, when installed (``pip install mechanism pylinkage``, and numba for
  pylinkage's compiled path; they are not kinepoly's dependencies): ``mechanism`` (fsolve per
  position) and ``pylinkage`` (``step_fast_with_kinematics``).

Every method computes the positions, velocities and accelerations of every moving point (A, B,
and the coupler point C where the method has it) and the angles, omegas and alphas of links 3
and 4. Times are the best of several runs (the slow ones run once); the closed form and the sweep are
called in turn, call after call, and ratios are to the closed form measured in the same run, so that a
loaded machine moves both. The page faults per call are printed too: each new full-length array costs
fresh pages where the C library has handed freed memory back, a steady count where times are not.
Agreement: the largest difference from the sweep over all rows, relative to the largest magnitude of
that kind of quantity.
Three more figures tell what a sweep costs whatever its length: ``run_sweep`` over 36 rows (the
Python that runs once per call, next to which the numpy passes over the rows hardly count)
and ``prepare_sweep`` alone (the mechanism's indexes built on first use are not in it); and the
sweep against the closed form over ten times the positions, where that once-per-call Python is
spread over ten times the rows (the cost per row).

    python benchmarks/bench_sweep.py [--quick]
"""

from __future__ import annotations

import argparse
import math
import resource
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

import kinepoly
from kinepoly.sweep import SweepResult, prepare_sweep, run_sweep, sweep

SCENE = ROOT / "examples" / "four-bar.toml"
STEPS = 3600
FEW = 36
LONG = 10 * STEPS
A1, A2, A3, A4 = 100.0, 40.0, 120.0, 80.0  # frame, crank, coupler, rocker (examples/four-bar.toml)
B3, BETA3 = 60.0, math.radians(30.0)  # coupler point C: 60 from A at 30 degrees to AB
OMEGA2, ALPHA2 = 10.0, 5.0

Arrays = dict[str, np.ndarray]


def four_bar(a2: np.ndarray | float, a3: np.ndarray | float, a4: np.ndarray | float, theta2: np.ndarray,
             a1: float = A1, omega2: float = OMEGA2, alpha2: float = ALPHA2) -> Arrays:
    """The four-bar by the textbook vector loop, written directly in numpy (B left of A -> B0); the link
    lengths broadcast against ``theta2`` (one mechanism, or a family of them)."""
    e2 = np.exp(1j * theta2)
    a = a2 * e2
    to_b0 = a1 - a
    dist = np.abs(to_b0)
    gamma = np.arccos((a3 * a3 + dist * dist - a4 * a4) / (2 * a3 * dist))
    theta3 = np.angle(to_b0) + gamma
    e3 = np.exp(1j * theta3)
    b = a + a3 * e3
    theta4 = np.angle(b - a1)
    e4 = np.exp(1j * theta4)
    s34 = np.sin(theta3 - theta4)
    omega3 = omega2 * a2 * np.sin(theta4 - theta2) / (a3 * s34)
    omega4 = omega2 * a2 * np.sin(theta3 - theta2) / (a4 * s34)
    known = (1j * alpha2 - omega2**2) * a - omega3**2 * a3 * e3 + omega4**2 * a4 * e4
    return {"theta3": theta3, "theta4": theta4, "omega_3": omega3, "omega_4": omega4,
            "alpha_3": (known * np.conj(e4)).real / (a3 * s34), "alpha_4": (known * np.conj(e3)).real / (a4 * s34),
            "r_A": a, "r_B": b}


def closed_form(theta2: np.ndarray) -> Arrays:
    """examples/four-bar.toml by ``four_bar``, with its coupler point C."""
    loop = four_bar(A2, A3, A4, theta2)
    theta3, a, b = loop["theta3"], loop["r_A"], loop["r_B"]
    omega3, omega4, alpha3, alpha4 = loop["omega_3"], loop["omega_4"], loop["alpha_3"], loop["alpha_4"]
    rc = B3 * np.exp(1j * (theta3 + BETA3))
    v_a, a_a = 1j * OMEGA2 * a, (1j * ALPHA2 - OMEGA2**2) * a
    return {"theta_3": np.degrees(theta3), "theta_4": np.degrees(loop["theta4"]), "omega_3": omega3,
            "omega_4": omega4, "alpha_3": alpha3, "alpha_4": alpha4, "r_A": a, "r_B": b, "r_C": a + rc, "v_A": v_a,
            "v_B": 1j * omega4 * (b - A1), "v_C": v_a + 1j * omega3 * rc, "a_A": a_a,
            "a_B": (1j * alpha4 - omega4**2) * (b - A1), "a_C": a_a + (1j * alpha3 - omega3**2) * rc}


def from_sweep(result: SweepResult) -> Arrays:
    out: Arrays = {}
    for col in result.columns:
        if col.name.endswith("_x"):
            out[col.name[:-2]] = col.values + 1j * result.column(col.name[:-2] + "_y").values
        elif not col.name.endswith("_y"):
            out[col.name] = col.values
    return out


def solve_loop(theta_deg: np.ndarray) -> Arrays:
    text = SCENE.read_text()
    rows: dict[str, list[complex]] = {}
    for value in theta_deg:
        scene = kinepoly.loads_scene(text.replace("angle = 60", f"angle = {float(value)!r}"))
        data = kinepoly.to_json(kinepoly.solve(scene))
        for link, v in data["links"].items():
            for key, name in (("angle", "theta"), ("omega", "omega"), ("alpha", "alpha")):
                rows.setdefault(f"{name}_{link}", []).append(v[key])
        for point, v in data["points"].items():
            for key, prefix in (("position", "r"), ("velocity", "v"), ("acceleration", "a")):
                rows.setdefault(f"{prefix}_{point}", []).append(complex(*v[key]))
    return {k: np.array(v) for k, v in rows.items()}


def pylinkage_run(steps: int) -> Callable[[], Arrays]:
    import pylinkage as pl

    step = 2 * math.pi / steps
    frame_a, frame_b = pl.Ground(0.0, 0.0, name="A0"), pl.Ground(A1, 0.0, name="B0")
    crank = pl.Crank(frame_a, radius=A2, angular_velocity=step, initial_angle=-step, name="A")
    rocker = pl.RRRDyad(crank.output, frame_b, distance1=A3, distance2=A4, x=136.0, y=71.0, name="B")
    linkage = pl.Linkage([frame_a, frame_b, crank, rocker], name="four-bar")
    linkage.set_input_velocity(crank, omega=OMEGA2, alpha=ALPHA2)

    def run() -> Arrays:
        pos, vel, acc = linkage.step_fast_with_kinematics(iterations=steps, dt=1.0)
        c = pos[:, :, 0] + 1j * pos[:, :, 1]
        v = vel[:, :, 0] + 1j * vel[:, :, 1]
        a = acc[:, :, 0] + 1j * acc[:, :, 1]
        return {"r_A": c[:, 2], "r_B": c[:, 3], "v_A": v[:, 2], "v_B": v[:, 3], "a_A": a[:, 2], "a_B": a[:, 3]}

    return run


def mechanism_run(theta: np.ndarray, first: Arrays) -> Arrays:
    import warnings

    from mechanism import Mechanism, Vector, get_joints

    j_o, j_a, j_b, j_c = get_joints("O A B C")
    va, vb = Vector((j_o, j_a), r=A2), Vector((j_a, j_b), r=A3)
    vc, vd = Vector((j_o, j_c), r=A1, theta=0.0, style="ground"), Vector((j_c, j_b), r=A4)

    def loop(x: np.ndarray, i: Any) -> Any:
        return va(i) + vb(x[0]) - vc() - vd(x[1])

    n = len(theta)
    guess = (np.radians([first["theta_3"][0], first["theta_4"][0]]),
             np.array([first["omega_3"][0], first["omega_4"][0]]), np.array([first["alpha_3"][0], first["alpha_4"][0]]))
    model = Mechanism(vectors=(va, vb, vc, vd), origin=j_o, loops=loop, pos=theta, vel=np.full(n, OMEGA2),
                      acc=np.full(n, ALPHA2), guess=guess)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model.iterate()

    def point(j: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return (np.array(j.x_positions) + 1j * np.array(j.y_positions),
                np.array(j.x_velocities) + 1j * np.array(j.y_velocities),
                np.array(j.x_accelerations) + 1j * np.array(j.y_accelerations))

    (ra, v_a, a_a), (rb, v_b, a_b) = point(j_a), point(j_b)
    return {"theta_3": np.degrees(vb.pos.thetas), "theta_4": np.degrees(vd.pos.thetas), "omega_3": vb.vel.omegas,
            "omega_4": vd.vel.omegas, "alpha_3": vb.acc.alphas, "alpha_4": vd.acc.alphas, "r_A": ra, "r_B": rb,
            "v_A": v_a, "v_B": v_b, "a_A": a_a, "a_B": a_b}


def agreement(reference: Arrays, other: Arrays) -> float:
    """Largest difference over all rows and shared quantities, each kind relative to its largest magnitude."""
    worst = 0.0
    for key, values in other.items():
        if key not in reference:
            continue
        ref = np.asarray(reference[key])
        if key.startswith("theta"):
            diff = np.abs((np.asarray(values) - ref + 180.0) % 360.0 - 180.0) / 360.0
        else:
            kind = [k for k in reference if k.split("_")[0] == key.split("_")[0]]
            scale = max(float(np.abs(reference[k]).max()) for k in kind)
            diff = np.abs(np.asarray(values) - ref) / scale
        worst = max(worst, float(diff.max()))
    return worst


def best(run: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = run()
        times.append(time.perf_counter() - t)
    return min(times), out


def interleaved(runs: dict[str, Callable[[], Any]], repeat: int) -> dict[str, tuple[float, float, Any]]:
    """Each run called in turn, ``repeat`` times over, so that a machine whose load or clock changes slows them
    alike: each one's best time, its page faults per call (the C library's fresh pages for new arrays: a count
    that the machine's load does not move) and its last result."""
    times: dict[str, list[float]] = {name: [] for name in runs}
    faults = dict.fromkeys(runs, 0)
    out: dict[str, Any] = {}
    for _ in range(repeat):
        for name, run in runs.items():
            before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
            t = time.perf_counter()
            out[name] = run()
            times[name].append(time.perf_counter() - t)
            faults[name] += resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before
    return {name: (min(times[name]), faults[name] / repeat, out[name]) for name in runs}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats; the slow methods on 360 positions")
    args = parser.parse_args()
    repeat = 30 if args.quick else 300
    scene = kinepoly.load_scene(SCENE)
    theta_deg = np.linspace(0.0, 360.0, STEPS, endpoint=False)
    theta = np.radians(theta_deg)
    prepared = prepare_sweep(scene)
    for _ in range(20):  # warm up: imports, caches, the CPU's clock
        sweep(scene, steps=STEPS)
        closed_form(theta)
    timed = interleaved({"closed": lambda: closed_form(theta), "sweep": lambda: sweep(scene, steps=STEPS),
                         "run": lambda: run_sweep(prepared, steps=STEPS)}, 3 * repeat)
    (t_closed, f_closed, closed), (t_sweep, f_sweep, result), (t_run, _, _) = (timed[k] for k in ("closed", "sweep",
                                                                                                  "run"))
    ratio_sweep, ratio_run = t_sweep / t_closed, t_run / t_closed
    # the cost per row apart from the Python run once per call: ten times the rows, both methods
    theta_long = np.radians(np.linspace(0.0, 360.0, LONG, endpoint=False))
    timed_long = interleaved({"closed": lambda: closed_form(theta_long), "sweep": lambda: sweep(scene, steps=LONG)},
                             max(5, repeat // 2))
    (t_closed_long, f_closed_long, _), (t_sweep_long, f_sweep_long, _) = timed_long["closed"], timed_long["sweep"]
    swept = from_sweep(result)
    assert np.array_equal(result.input.values, theta_deg)
    rows: list[tuple[str, float | None, str, float | None]] = [
        ("hand-written numpy closed form", t_closed, "", agreement(swept, closed)),
        ("kinepoly sweep(scene), all in", t_sweep, "", 0.0),
        ("kinepoly run_sweep(prepared plan)", t_run, "", 0.0),
    ]
    slow_rows = 360 if args.quick else STEPS
    scale = STEPS / slow_rows
    slow_theta = theta_deg[:: STEPS // slow_rows]
    subset = {k: v[:: STEPS // slow_rows] for k, v in swept.items()}
    t0 = time.perf_counter()
    looped = solve_loop(slow_theta)
    rows.append((f"loop of kinepoly.solve ({slow_rows} inputs, x{scale:g})", (time.perf_counter() - t0) * scale, "",
                 agreement(subset, looped)))
    t_one, _ = best(lambda: kinepoly.solve(scene), max(30, repeat // 3))
    rows.append(("one kinepoly.solve (one position, the analytic check included)", t_one, "", None))
    # what a sweep costs whatever its length (Python, not numpy passes): few rows, the plan prepared or not
    t_few, _ = best(lambda: run_sweep(prepared, steps=FEW, start=0.0, stop=360.0), repeat)
    t_prepare, _ = best(lambda: prepare_sweep(scene), repeat)
    rows.append((f"kinepoly run_sweep(prepared plan), {FEW} rows: the cost per call", t_few, "", None))
    rows.append(("kinepoly prepare_sweep(scene) alone", t_prepare, "", None))
    try:
        import numba  # noqa: F401

        accel = "with numba"
    except ImportError:
        accel = "numba not installed: pure Python"
    try:
        run = pylinkage_run(STEPS)
        run()  # compiles
        t_pl, out = best(run, max(3, repeat // 30))
        rows.append((f"pylinkage step_fast_with_kinematics ({accel})", t_pl, "", agreement(swept, out)))
    except Exception as error:  # noqa: BLE001 - a peer that fails is reported, not fatal
        rows.append((f"pylinkage: {type(error).__name__}: {error}", None, "", None))
    try:
        t0 = time.perf_counter()
        out = mechanism_run(np.radians(slow_theta), subset)
        rows.append((f"mechanism Mechanism.iterate, fsolve ({slow_rows} inputs, x{scale:g})",
                     (time.perf_counter() - t0) * scale, "", agreement(subset, out)))
    except Exception as error:  # noqa: BLE001
        rows.append((f"mechanism: {type(error).__name__}: {error}", None, "", None))
    print(f"four-bar of {SCENE.name}: positions, velocities and accelerations of A, B, C and links 3, 4 "
          f"over {STEPS} positions of theta_2 (the first three: best of {3 * repeat} calls each, called in turn; "
          "ratios to the closed form in the same run)")
    print(f"{'method':62s} {'time':>11s} {'/closed':>9s} {'/sweep':>9s} {'agreement':>10s}")
    for name, seconds, _, agree in rows:
        if seconds is None:
            print(f"{name}")
            continue
        agree_text = "-" if agree is None else f"{agree:.1e}"
        print(f"{name:62s} {seconds * 1e3:8.3f} ms {seconds / t_closed:9.2f} "
              f"{seconds / t_sweep:9.2f} {agree_text:>10s}")
    print(f"target: sweep / closed form <= 1.3; measured {ratio_sweep:.2f} (all in), {ratio_run:.2f} (prepared plan); "
          f"the sweep's own split: {result.timing}")
    print(f"over {LONG} positions: sweep {t_sweep_long * 1e3:.3f} ms, closed form {t_closed_long * 1e3:.3f} ms, "
          f"ratio {t_sweep_long / t_closed_long:.2f} (the cost per row, the Python run once per call spread thin)")
    print(f"page faults per call (fresh pages of memory for new arrays; the machine's load does not move them): "
          f"{STEPS} positions sweep {f_sweep:.0f}, closed form {f_closed:.0f}; {LONG} positions sweep "
          f"{f_sweep_long:.0f}, closed form {f_closed_long:.0f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
