"""A family of mechanisms: 1,000 randomised crank-rocker four-bars (one topology, the dimensions drawn at random) over
360 positions of the crank each, swept by ``kinepoly.sweep_family`` (the plan run once for every member), and as one
``sweep`` per member, against a numpy closed form over the whole family at once, all measured in the same run.

The closed form is ``bench_sweep.py``'s textbook vector loop, broadcast over (members, positions). The figures
printed: the time of each (the best of several rounds, the family and the closed form interleaved), their ratio to
the closed form (the issue's target for the family sweep: at most 2), and the agreement of each with the closed
form (the largest difference in theta, omega and alpha of links 3 and 4, relative to the largest magnitude of
each). Scenes are read before the clock starts.

    python benchmarks/family.py [--members 1000] [--seed 0] [--rounds 7]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_sweep import four_bar

from kinepoly.scene.loader import loads_scene
from kinepoly.sweep import sweep, sweep_family

POSITIONS = 360
A1, OMEGA2, ALPHA2 = 100.0, 10.0, 5.0


def members(count: int, seed: int) -> np.ndarray:
    """(a2, a3, a4) of ``count`` Grashof crank-rockers (the crank the shortest link) with frame a1 = 100."""
    rng = np.random.default_rng(seed)
    out: list[tuple[float, float, float]] = []
    while len(out) < count:
        a2, a3, a4 = rng.uniform(20.0, 45.0), rng.uniform(90.0, 140.0), rng.uniform(60.0, 110.0)
        if a2 + max(A1, a3, a4) < sum(sorted((A1, a3, a4))[:2]) - 1.0:
            out.append((a2, a3, a4))
    return np.array(out)


def closed_form(dims: np.ndarray, theta2: np.ndarray) -> dict[str, np.ndarray]:
    """theta, omega, alpha of links 3 and 4 over (members, positions): ``bench_sweep.four_bar`` with the
    members' lengths as columns."""
    a2, a3, a4 = (dims[:, k:k + 1] for k in range(3))
    loop = four_bar(a2, a3, a4, theta2[None, :], a1=A1, omega2=OMEGA2, alpha2=ALPHA2)
    return {"theta_3": np.degrees(loop["theta3"]), "theta_4": np.degrees(loop["theta4"]),
            **{name: loop[name] for name in ("omega_3", "omega_4", "alpha_3", "alpha_4")}}


def scene_text(a2: float, a3: float, a4: float) -> str:
    """The member as a scene, its [guess] at the closed form's assembly at the scene's input (60 deg)."""
    theta3 = float(closed_form(np.array([[a2, a3, a4]]), np.radians([60.0]))["theta_3"][0, 0])
    b = a2 * complex(math.cos(math.radians(60.0)), math.sin(math.radians(60.0))) + \
        a3 * complex(math.cos(math.radians(theta3)), math.sin(math.radians(theta3)))
    return (f'title = "four-bar member"\n[links]\n1 = {{ points = {{ A0 = [0, 0], B0 = [{A1!r}, 0] }} }}\n'
            f"2 = {{ points = {{ A0 = [0, 0], A = [{a2!r}, 0] }} }}\n"
            f"3 = {{ points = {{ A = [0, 0], B = [{a3!r}, 0] }} }}\n"
            f"4 = {{ points = {{ B0 = [0, 0], B = [{a4!r}, 0] }} }}\n"
            f'[input]\nlink = "2"\nangle = 60\nomega = {OMEGA2!r}\nalpha = {ALPHA2!r}\n'
            f"[guess]\nB = [{b.real!r}, {b.imag!r}]\n"
            '[find]\nomega = ["3", "4"]\nalpha = ["3", "4"]\n')


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--members", type=int, default=1000, help="how many four-bars (default 1000)")
    parser.add_argument("--seed", type=int, default=0, help="the random seed of their dimensions (default 0)")
    parser.add_argument("--rounds", type=int, default=7, help="rounds of the family and the closed form (default 7)")
    args = parser.parse_args()
    dims = members(args.members, args.seed)
    scenes = [loads_scene(scene_text(*map(float, row)), f"member-{k}.toml") for k, row in enumerate(dims)]
    theta2 = np.radians(np.arange(POSITIONS, dtype=np.float64))
    points = {"A@2": np.c_[dims[:, 0], np.zeros(len(dims))], "B@3": np.c_[dims[:, 1], np.zeros(len(dims))],
              "B@4": np.c_[dims[:, 2], np.zeros(len(dims))]}
    best_closed = best_family = math.inf
    family = sweep_family(scenes[0], points, steps=POSITIONS)  # the scene's plan prepared, as a repeated call finds it
    for _ in range(args.rounds):
        t0 = time.perf_counter()
        reference = closed_form(dims, theta2)
        t1 = time.perf_counter()
        family = sweep_family(scenes[0], points, steps=POSITIONS)
        t2 = time.perf_counter()
        best_closed, best_family = min(best_closed, t1 - t0), min(best_family, t2 - t1)
    t0 = time.perf_counter()
    results = [sweep(scene, steps=POSITIONS) for scene in scenes]
    looped = time.perf_counter() - t0
    looped_values = {name: np.array([result.column(name).values for result in results]) for name in reference}
    family_values = {name: family.column(name).values for name in reference}
    print(f"{args.members} four-bars x {POSITIONS} positions (theta, omega, alpha of links 3 and 4)")
    print(f"numpy closed form over the family at once   {best_closed * 1e3:9.1f} ms   1.00")
    print(f"kinepoly.sweep_family (the plan run once)   {best_family * 1e3:9.1f} ms   {best_family / best_closed:6.2f}"
          f"   (target: at most 2); agreement {_agreement(reference, family_values):.1e}")
    print(f"one kinepoly sweep per member (a loop)      {looped * 1e3:9.1f} ms   {looped / best_closed:6.1f}"
          f"   agreement {_agreement(reference, looped_values):.1e}")
    print(f"per member: family {best_family / args.members * 1e3:.4f} ms, loop {looped / args.members * 1e3:.3f} ms;"
          f" family against the loop: {_agreement(looped_values, family_values):.1e}")
    return 0


def _agreement(reference: dict[str, np.ndarray], got: dict[str, np.ndarray]) -> float:
    """The largest difference of ``got`` from ``reference`` relative to the largest magnitude of each quantity
    (angles compared modulo a turn)."""
    worst = 0.0
    for name, expected in reference.items():
        values = got[name]
        if name.startswith("theta"):
            values = np.where(values - expected > 180.0, values - 360.0,
                              np.where(expected - values > 180.0, values + 360.0, values))
        worst = max(worst, float(np.abs(values - expected).max() / np.abs(expected).max()))
    return worst


if __name__ == "__main__":
    raise SystemExit(main())
