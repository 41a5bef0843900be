"""How long kinepoly check and kinepoly variants take, as multiples of one solve of the same scene.

Run: python3 benchmarks/homework.py. Every time is the best of a few runs, all measured in this
run, so the ratios hold on any machine: checking one file costs a few solves (the scene, the
scene asking everything, the input angle taken in radians), a class costs about the same as one
student plus the comparing, and a variant costs a few solves (drawn, written, read back).

Then ``kinepoly variants --n 30`` (``run_variants``, the files written to a temporary folder) of the four-bar and
of two six-bars, its draws judged through the family engine (a few engine calls for all of them) and by the path
of solves from the original that scenes with cams keep (a solve or more per draw), interleaved, with their ratio,
how many scenes each solved (the path: one or more per draw, and one per variant written; the family: the one
per variant written, and the draws it leaves to the path), and whether the two wrote the same files.
"""

from __future__ import annotations

import contextlib
import io
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from unittest import mock

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

import kinepoly
from kinepoly.cli.variants import run_variants
from kinepoly.homework import check, default_ranges, loads_answers, make_checker, make_variants, variants

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


def variants_class(scene: Path, by_the_path: bool, lengths: str | None, least: float) -> tuple[dict[str, str], int]:
    """``kinepoly variants SCENE --n 30 --seed 7 [--lengths LO,HI] [--min-transmission DEG]``: the files it
    writes, by name, and how many scenes it solved."""
    solved = variants._solved
    count = [0]

    def counted(scene: kinepoly.Scene) -> object:
        count[0] += 1
        return solved(scene)

    with tempfile.TemporaryDirectory() as folder, contextlib.redirect_stdout(io.StringIO()), \
            mock.patch.object(variants, "_solved", counted):
        with mock.patch.object(variants, "_family", lambda *_: None) if by_the_path else contextlib.nullcontext():
            run_variants(str(scene), 30, 7, folder, {"lengths": lengths}, least)
        return {p.name: p.read_text() for p in sorted(Path(folder).iterdir())}, count[0]


def variants_family(rounds: int = 3) -> None:
    print(f"\nkinepoly variants --n 30 --seed 7: draws judged by the family engine or by the path of solves "
          f"(best of {rounds}, interleaved)")
    print(f"{'scene':<16} {'options':<38} {'path ms':>8} {'family ms':>10} {'ratio':>6} {'solves':>13}  same files")
    for name, lengths, least in (("four-bar", None, 30.0), ("centers-six-bar", None, 30.0), ("shaper", None, 30.0),
                                 ("four-bar", "0.7,1.3", 45.0), ("centers-six-bar", "0.7,1.3", 45.0)):
        scene = ROOT / "examples" / f"{name}.toml"
        options = "" if lengths is None else f"--lengths {lengths} --min-transmission {least:g}"
        times: dict[bool, list[float]] = {True: [], False: []}
        made: dict[bool, tuple[dict[str, str], int]] = {}
        for _ in range(rounds):
            for by_the_path in (True, False):
                start = time.perf_counter()
                made[by_the_path] = variants_class(scene, by_the_path, lengths, least)
                times[by_the_path].append(time.perf_counter() - start)
        old, new = min(times[True]), min(times[False])
        solves = f"{made[True][1]} -> {made[False][1]}"
        print(f"{name:<16} {options:<38} {1e3 * old:8.0f} {1e3 * new:10.0f} {old / new:6.2f} {solves:>13}  "
              f"{made[True][0] == made[False][0]}")


if __name__ == "__main__":
    main()
    variants_family()
