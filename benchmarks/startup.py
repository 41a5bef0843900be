"""What a whole process costs from start to exit: ``kinepoly --version``, ``import kinepoly`` and ``kinepoly solve``
of the four-bar example (table and ``--json``), against ``python -c 'import numpy'`` measured in the same run.

Each command runs as a fresh ``python`` process, the commands interleaved round by round (so that a load on the
machine falls on all of them alike), with the bytecode cached: the runs write and read their compiled modules under
a temporary ``PYTHONPYCACHEPREFIX`` (the source tree is left as it is), the message catalogues' cache under a
temporary ``XDG_CACHE_HOME``, and one warm-up round fills both first.
The figures are the median and the best of the rounds; the ratios are medians to the numpy import's median.

    python benchmarks/startup.py [--rounds 15]
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


def _environment(cache: str) -> dict[str, str]:
    env = {key: value for key, value in os.environ.items() if key != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, (str(ROOT / "src"), env.get("PYTHONPATH"))))
    env["PYTHONPYCACHEPREFIX"] = os.path.join(cache, "bytecode")
    env["XDG_CACHE_HOME"] = os.path.join(cache, "user")
    return env


def _seconds(arguments: tuple[str, ...], env: dict[str, str]) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, *arguments], cwd=ROOT, env=env, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rounds", type=int, default=15, help="runs of each command, interleaved")
    args = parser.parse_args()
    times: dict[str, list[float]] = {name: [] for name, _ in COMMANDS}
    with tempfile.TemporaryDirectory(prefix="kinepoly-startup-") as cache:
        env = _environment(cache)
        for _, arguments in COMMANDS:  # the warm-up round: every module compiled once, the catalogue cached
            _seconds(arguments, env)
        for _ in range(args.rounds):
            for name, arguments in COMMANDS:
                times[name].append(_seconds(arguments, env))
    reference = statistics.median(times[COMMANDS[0][0]])
    print(f"whole processes, bytecode cached, {args.rounds} interleaved rounds; ratios of medians to the numpy "
          f"import, same run")
    for name, seconds in times.items():
        median = statistics.median(seconds)
        print(f"{name:48s} median {median * 1e3:7.1f} ms  best {min(seconds) * 1e3:7.1f} ms  "
              f"{median / reference:5.2f} x numpy")
    return 0


if __name__ == "__main__":
    sys.exit(main())
