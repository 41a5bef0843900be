"""How fast does ``kinepoly edit`` follow a drag? From the pointer's move to the polygons redrawn, in chromium.

The editor's page is opened in headless chromium (Debian's, driven by playwright, as the tests do)
on a copy of an example; the mouse drags the crank's point through a sweep of angles, each move
waiting for its redraw. The page records, for every move, the milliseconds from the pointer event
to the first task after the frame that shows the new sheet (``window.kinepolyEditor.timings``),
and when the server's answer arrived. Each scene is dragged twice in the same run: as the page
drags (a draft sheet per move, its labels at their first places, and the whole sheet on release),
and, as the reference, with drafts off (the whole sheet, its labels searched clear, at every move:
how the page dragged before drafts). Printed for each: the median and 95th percentile of that time;
what the server spent (its own timing of the solve, the layout, the labels' placement and the SVG);
what was left for the edit of the text, the websocket and the JSON; the page's work from the answer's
arrival (parsing it, replacing the sheet and the tables, painting); the
drafts' figures as ratios to the reference's; the time from the release to the whole sheet shown;
and, measured in the same run on the same machine, ``evaluate`` called in-process (the solve and
drawing the server makes for each move, with no browser), whole and draft, with its processor time
(what the move costs on an idle machine, nearly whatever else runs).

    python benchmarks/bench_editor.py [--moves 60] [--scenes four-bar centers-six-bar]
"""

from __future__ import annotations

import argparse
import math
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))
sys.path.insert(0, str(ROOT))

from tests.chromium import ARGS, chromium
from tests.editor.drive import handle, screen, wait_settled
from tests.editor.server import serving

from kinepoly.editor.document import Document
from kinepoly.editor.edits import apply_edit
from kinepoly.editor.evaluate import evaluate


def _percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, math.ceil(q * len(ordered)) - 1))]


def _in_process(path: Path, moves: int, draft: bool) -> tuple[list[float], list[float]]:
    """The reference: the server's work for each move (the edit, the solve, the drawing), with no browser: its
    wall-clock and its processor milliseconds (the latter hardly moved by other processes on the machine)."""
    text = path.read_text(encoding="utf-8")
    current = evaluate(text, str(path))
    times, cpu = [], []
    pivot = current.handles["points"][current.handles["input"]["point"]]["at"]
    radius = math.hypot(*pivot) or 1.0
    for k in range(moves):
        t0, c0 = time.perf_counter(), time.process_time()
        angle = math.radians(60 + 90 * k / moves)
        assert current.solution is not None
        text = apply_edit(text, {"op": "drive", "to": [radius * math.cos(angle), radius * math.sin(angle)]},
                          current.solution)
        new = evaluate(text, str(path), draft=draft)
        times.append(1e3 * (time.perf_counter() - t0))
        cpu.append(1e3 * (time.process_time() - c0))
        current = new if new.ok else current
    return times, cpu


def _crank(page: Any) -> tuple[tuple[float, float], float]:
    """The crank's pivot (the frame point of the input link) and the length to its point, in the scene."""
    handles = page.evaluate("() => window.kinepolyEditor.good.handles")
    point = handles["input"]["point"]
    link = handles["input"]["link"]
    pivot = next(p["at"] for name, p in handles["points"].items() if p["frame"] and link in p["links"])
    at = handles["points"][point]["at"]
    return (pivot[0], pivot[1]), math.hypot(at[0] - pivot[0], at[1] - pivot[1])


def bench(page: Any, example: str, moves: int, drafts: bool) -> dict[str, Any]:
    """One drag of ``example``'s crank through a quarter turn in ``moves`` awaited moves; ``drafts``: as the page
    drags (draft sheets, the whole one on release), else the whole sheet at every move."""
    folder = Path(tempfile.mkdtemp())
    path = folder / f"{example}.toml"
    shutil.copy(ROOT / "examples" / f"{example}.toml", path)
    try:
        with serving(Document(str(path))) as served:
            page.goto(served.url)
            page.wait_for_selector("#sheet svg #handles")
            wait_settled(page)
            page.evaluate(f"() => {{ window.kinepolyEditor.drafts = {'true' if drafts else 'false'}; }}")
            (px, py), r = _crank(page)
            point = page.evaluate("() => window.kinepolyEditor.good.handles.input.point")
            start = handle(page, point)
            a0 = math.atan2(start[1] - py, start[0] - px)
            page.mouse.move(*screen(page, start))
            page.mouse.down()
            for k in range(1, moves + 1):  # a quarter turn, each move awaited
                a = a0 + math.radians(90) * k / moves
                page.mouse.move(*screen(page, (px + r * math.cos(a), py + r * math.sin(a))))
                wait_settled(page)
            page.mouse.up()
            page.wait_for_function(f"() => window.kinepolyEditor.timings.length >= {moves}")
            if drafts:
                page.wait_for_function("() => window.kinepolyEditor.fullTimings.length >= 1")
            timings = page.evaluate("() => window.kinepolyEditor.timings")
            whole = page.evaluate("() => window.kinepolyEditor.fullTimings")
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return {"timings": timings, "whole": whole}


def _figures(timings: list[dict[str, Any]]) -> dict[str, Any]:
    timings = [t for t in timings if t["ok"]]
    total = [t["ms"] for t in timings]
    server = [sum(t["server"].values()) for t in timings]
    return {
        "count": len(total), "median": statistics.median(total), "p95": _percentile(total, 0.95),
        "parts": {key: statistics.median(t["server"][key] for t in timings)
                  for key in ("solve", "layout", "labels", "svg")},
        "server": statistics.median(server),
        "transport": statistics.median(t["received"] - s for t, s in zip(timings, server, strict=True)),
        "browser": statistics.median(t["ms"] - t["received"] for t in timings),
    }


def _line(name: str, f: dict[str, Any]) -> None:
    print(f"  {name}: {f['count']} drag moves, drag to redrawn polygons: median {f['median']:.1f} ms, "
          f"95th percentile {f['p95']:.1f} ms")
    print("    of the median move: server " + ", ".join(f"{k} {v:.1f}" for k, v in f["parts"].items())
          + f" (sum {f['server']:.1f} ms); the text's edit, websocket and JSON {f['transport']:.1f} ms;"
          f" the page parsing the answer, replacing the sheet and painting {f['browser']:.1f} ms")


def report(example: str, drafted: dict[str, Any], whole: dict[str, Any], moves: int) -> None:
    path = ROOT / "examples" / f"{example}.toml"
    (full_ms, full_cpu), (draft_ms, draft_cpu) = (_in_process(path, moves, draft) for draft in (False, True))
    new, old = _figures(drafted["timings"]), _figures(whole["timings"])
    print(f"{example}:")
    _line("as the page drags (draft sheets, the whole one on release)", new)
    _line("reference, drafts off (the whole sheet at every move)", old)
    print(f"  drafts / reference: median {new['median'] / old['median']:.2f}, 95th percentile "
          f"{new['p95'] / old['p95']:.2f}, server {new['server'] / old['server']:.2f}")
    release = [t["ms"] for t in drafted["whole"]]
    if release:
        print(f"  release to the whole sheet shown: {statistics.median(release):.1f} ms")
    print(f"  in-process (edit, solve, draw): whole sheet median {statistics.median(full_ms):.1f} ms "
          f"({statistics.median(full_cpu):.1f} ms of processor time), draft {statistics.median(draft_ms):.1f} ms "
          f"({statistics.median(draft_cpu):.1f} ms of processor time)")


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moves", type=int, default=60)
    parser.add_argument("--scenes", nargs="+", default=["four-bar", "centers-six-bar"])
    args = parser.parse_args(argv)
    executable = chromium()
    if executable is None:
        print("bench_editor: chromium is not installed (apt-get install chromium)", file=sys.stderr)
        return 2
    from playwright.sync_api import sync_playwright

    with sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path=executable, headless=True, args=ARGS)
        try:
            page = browser.new_page(viewport={"width": 1400, "height": 1000})
            for example in args.scenes:
                drafted = bench(page, example, args.moves, drafts=True)
                whole = bench(page, example, args.moves, drafts=False)
                report(example, drafted, whole, args.moves)
        finally:
            browser.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
