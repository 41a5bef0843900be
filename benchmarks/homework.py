"""How long kinepoly check and kinepoly variants take, as multiples of one solve of the same scene.

Run: python3 benchmarks/homework.py. Every time is the best of a few runs, all measured in this
run, so the ratios hold on any machine: checking one file costs a few solves (the scene, the
scene asking everything, the input angle taken in radians), a class costs about the same as one
student plus the comparing, and a variant costs a few solves (drawn, written, read back).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

import kinepoly
from kinepoly.homework import check, default_ranges, loads_answers, make_checker, make_variants

ANSWERS = """omega_4 = "1.28 ccw"
alpha_4 = 58.1
v_A = [-346.4, 200]
"v_A@4" = [-346.4, 200]
a_A = [-2000, -3464]
"a_A@4" = [-1914, -3543]
"""


def best(work: Callable[[], object], repeat: int = 5) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        work()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    text = (ROOT / "examples" / "slotted-lever.toml").read_text()
    scene = kinepoly.loads_scene(text, "slotted-lever.toml")
    answers = loads_answers(ANSWERS, scene)
    solve_s = best(lambda: kinepoly.solve(scene), 20)

    def one() -> object:
        return check(answers, make_checker(scene, [answers], text))

    def class_of_30() -> object:
        checker = make_checker(scene, [answers] * 30, text)
        return [check(answers, checker) for _ in range(30)]

    rows = [
        ("one solve (the reference)", solve_s, 1),
        ("check one answers file", best(one), 1),
        ("check a class of 30 files", best(class_of_30), 30),
        ("make 30 variants", best(lambda: make_variants(scene, default_ranges(scene), 30, 7), 3), 30),
    ]
    print(f"slotted lever; one solve takes {1e3 * solve_s:.3g} ms here")
    print(f"{'what':<28} {'total ms':>9} {'per item ms':>12} {'solves per item':>16}")
    for what, seconds, items in rows:
        print(f"{what:<28} {1e3 * seconds:9.3g} {1e3 * seconds / items:12.3g} {seconds / items / solve_s:16.3g}")


if __name__ == "__main__":
    main()
