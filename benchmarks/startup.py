"""What a whole process costs from start to exit: ``kinepoly --version``, ``import kinepoly`` and ``kinepoly solve``
of the four-bar example (table and ``--json``), against ``python -c 'import numpy'`` measured in the same run.

Each command runs as a fresh ``python`` process, the commands interleaved round by round (so that a load on the
machine falls on all of them alike), with the bytecode cached: the runs write and read their compiled modules under
a temporary ``PYTHONPYCACHEPREFIX`` (the source tree is left as it is), the message catalogues' cache under a
temporary ``XDG_CACHE_HOME``, and one warm-up round fills both first.
The figures are the median and the best of the rounds; the ratios are medians to the numpy import's median, and
the difference of the medians follows in brackets (numpy's import itself varies with the machine's load: it
starts its threads).
``--baseline TREE`` times the kinepoly commands of another source tree too (an older checkout: its ``src/`` and
``examples/``), interleaved in the same rounds, so that a change is measured before and after in one run.

    python benchmarks/startup.py [--rounds 15] [--baseline TREE]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENE = "examples/four-bar.toml"

COMMANDS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("python -c 'import numpy'", ("-c", "import numpy")),
    ("python -c 'import kinepoly'", ("-c", "import kinepoly")),
    ("kinepoly --version", ("-m", "kinepoly", "--version")),
    (f"kinepoly solve {SCENE}", ("-m", "kinepoly", "solve", SCENE)),
    (f"kinepoly solve {SCENE} --json", ("-m", "kinepoly", "solve", SCENE, "--json")),
)
"""What is timed: a name and the arguments after ``python``; the first is the reference."""


def _environment(tree: Path, cache: str) -> dict[str, str]:
    env = {key: value for key, value in os.environ.items() if key not in ("PYTHONDONTWRITEBYTECODE", "PYTHONPATH")}
    env["PYTHONPATH"] = str(tree / "src")
    env["PYTHONPYCACHEPREFIX"] = os.path.join(cache, "bytecode")
    env["XDG_CACHE_HOME"] = os.path.join(cache, "user", tree.name)
    return env


def _seconds(arguments: tuple[str, ...], tree: Path, env: dict[str, str]) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, *arguments], cwd=tree, env=env, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rounds", type=int, default=15, help="runs of each command, interleaved")
    parser.add_argument("--baseline", type=Path, help="another source tree whose kinepoly commands are timed too")
    args = parser.parse_args()
    runs = [(name, arguments, ROOT) for name, arguments in COMMANDS]
    if args.baseline is not None:
        baseline = args.baseline.resolve()
        runs += [(f"baseline: {name}", arguments, baseline) for name, arguments in COMMANDS[1:]]
    times: dict[str, list[float]] = {name: [] for name, _, _ in runs}
    with tempfile.TemporaryDirectory(prefix="kinepoly-startup-") as cache:
        envs = {tree: _environment(tree, cache) for _, _, tree in runs}
        for _, arguments, tree in runs:  # the warm-up round: every module compiled once, the catalogue cached
            _seconds(arguments, tree, envs[tree])
        for _ in range(args.rounds):
            for name, arguments, tree in runs:
                times[name].append(_seconds(arguments, tree, envs[tree]))
    reference = statistics.median(times[COMMANDS[0][0]])
    print(f"whole processes, bytecode cached, {args.rounds} interleaved rounds; ratios of medians to the numpy "
          f"import, same run")
    for name, seconds in times.items():
        median = statistics.median(seconds)
        print(f"{name:58s} median {median * 1e3:7.1f} ms  best {min(seconds) * 1e3:7.1f} ms  "
              f"{median / reference:5.2f} x numpy  ({(median - reference) * 1e3:+7.1f} ms)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
