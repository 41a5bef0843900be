"""The whole command line under a fuzzer: mutated example scenes through every command, in-process.

``python tools/fuzz.py --cases 3000 [--seed 1] [--browser 20]`` (from the repository's root, with the
package importable) runs CASES cases and prints the counts; ``tests/hardening/test_fuzz_v2.py`` runs a
few dozen of the same cases in the suite. A case is one of ``examples/`` (four-bars to cams, gears,
[[input]] tables, relative_to, cylinders, compound hinges, triads) with a few numbers, names or lines
changed, maybe a table added, then run through ``solve`` and one or two of ``draw``, ``sweep``,
``handout``, ``animate``, ``variants``, ``check`` and ``bench``. Every run must end in a documented
exit status other than 70, with no traceback and no Python warning on standard error; every file
written must be valid (JSON without NaN, well-formed SVG with finite numbers, PDF, PNG, DXF that
ezdxf reads, CSV of even rows, HTML whose data parses and holds no ``<``), none written by a run
that failed, and no temporary file left. ``--browser N`` also opens every N-th web page in headless
chromium (playwright): no script error, the page's own script ran. ``--editor`` also runs ``kinepoly edit``'s
JSON API on every case (``run_editor``): the case's text put, answered as ``solve --json`` answers it, then
changes over the websocket (points dragged to random and extreme places, values that are not numbers, names
that are markup), every answer strict JSON and every sheet well-formed SVG without script, the file written
only by a save, exactly the editor's text, and no temporary file left.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import io
import json
import math
import random
import re
import signal
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Case", "Outcome", "cases", "run_case", "run_editor"]

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))

NUMBERS = ["0", "-0", "1e308", "-1e308", "5e-324", "1e154", "1e-300", "nan", "inf", "-inf", "1e30", "1e-30", "3",
           "360", "-720", '"x"', "true", "[]", "{}", '"300 rpm"', '"1e308 rpm"', '"4 cm"', '"-0.5 m/s"', "0.001",
           "1e6", "-1", "2", "90", "180", "7.5"]
NAMES = ["A", "B", "1", "2", "3", "", "@", "A@3", "a/b", "a\\\\b", "A\\\\1", "$x$", "<!--<script>", "</script>",
         "<&>", "\\u0001", "\\ufffe", "é", "中", "😀", " ", "ω13", "x" * 80]
EXTRA = [
    "[draw]\nkv = 1000\n", "[draw]\nka = 1e-30\n", '[find]\ninstant_centers = "all"\n', '[find]\nvelocity = ["Q"]\n',
    '[units]\nlength = "m"\n', "[[cams]]\ncam = \"2\"\nfollower = \"3\"\n",
    "[[gears]]\ngear = \"2\"\nwith = \"3\"\nratio = 0\n", "[[input]]\nlink = \"3\"\nomega = 1\n",
    "[[input]]\ncylinder = [\"2\", \"3\"]\n", '[guess]\nZZ = [1, 2]\n', "[vary]\nangle = [0, 1e308]\n",
    "[draw]\n" + ".".join(["a"] * 80) + " = 1\n",
]
COMMANDS = ("draw", "sweep", "handout", "animate", "variants", "check", "bench")
_WEIGHTS = (4, 4, 2, 3, 2, 3, 1)


@dataclass(frozen=True)
class Case:
    """One fuzz case: the scene's text, its name, and the commands to run after ``solve``."""

    name: str
    text: str
    commands: tuple[str, ...]


@dataclass
class Outcome:
    """What a case's runs did: each command's exit status, the problems found, the CPU seconds each took."""

    codes: dict[str, int] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)
    seconds: dict[str, float] = field(default_factory=dict)
    tally: Counter[str] = field(default_factory=Counter)
    """Counts of kinds of answers (the editor's websocket: changes made, refused, solved)."""


def _mutate(text: str, rng: random.Random) -> str:
    for _ in range(rng.choice([0, 0, 1, 1, 2])):
        numbers = list(re.finditer(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e-?\d+)?(?![\w.])", text))
        if numbers:
            m = rng.choice(numbers)
            text = text[:m.start()] + rng.choice(NUMBERS) + text[m.end():]
    for _ in range(rng.choice([0, 0, 0, 1])):
        names = list(re.finditer(r'(?m)(?<=[{,] )[A-Za-z]\w*(?= = )|"[^"\n]*"', text))
        if names:
            m = rng.choice(names)
            new = rng.choice(NAMES)
            if rng.random() < 0.5:  # rename it everywhere, so that the scene may still hold together
                old, quoted = m.group().strip('"'), f'"{new}"'
                text = re.sub(rf'(?<![\w"@]){re.escape(old)}(?![\w"])(?= = )|"{re.escape(old)}"',
                              lambda _: quoted, text)  # noqa: B023 - called here, at once
            else:
                text = text[:m.start()] + f'"{new}"' + text[m.end():]
    lines = text.splitlines(keepends=True)
    if rng.random() < 0.2 and lines:
        k = rng.randrange(len(lines))
        lines[k:k + 1] = [] if rng.random() < 0.5 else [lines[k], lines[k]]
    title = f'title = "{rng.choice(NAMES)}"\n' if rng.random() < 0.2 else ""
    body = "".join(lines)
    if title:
        body = re.sub(r"(?m)^title = .*\n", "", body)
    return title + body + (rng.choice(EXTRA) if rng.random() < 0.25 else "")


def cases(seed: int, count: int) -> Iterator[Case]:
    """``count`` cases, the same for the same seed."""
    rng = random.Random(seed)
    for k in range(count):
        base = rng.choice(EXAMPLES)
        text = base.read_text(encoding="utf-8")
        mutated = _mutate(text, rng) if rng.random() < 0.9 else text
        commands = tuple(dict.fromkeys(rng.choices(COMMANDS, weights=_WEIGHTS, k=rng.choice([1, 1, 2]))))
        yield Case(f"{k:05d}-{base.stem}", mutated, commands)


class _Timeout(BaseException):
    pass


def _alarm(signum: int, frame: object) -> None:
    raise _Timeout


def _main(argv: list[str]) -> tuple[int, str, str]:
    from kinepoly.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


def _check_svg(path: Path) -> None:
    root = ET.parse(path).getroot()
    for element in root.iter():
        for name, value in element.attrib.items():
            if name != "data-role" and re.search(r"\b(nan|inf)\b", value.lower()):
                raise ValueError(f"{name}={value!r}")
    box = root.attrib.get("viewBox")
    if box is not None and not all(math.isfinite(float(x)) for x in box.split()):
        raise ValueError(f"viewBox {box}")


def _check_html(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    if not text.startswith("<!DOCTYPE html>") or not text.rstrip().endswith("</html>"):
        raise ValueError("not a whole page")
    from html.parser import HTMLParser

    HTMLParser().feed(text)
    for data in re.findall(r'<script type="application/json"[^>]*>(.*?)</script>', text, re.DOTALL):
        if re.search(r"[<>&]", data):
            raise ValueError("<, > or & in the page's data")
        json.loads(data, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
    if text.count("<script") != text.count("</script>"):
        raise ValueError("script elements do not pair")


def _check_file(path: Path) -> None:
    """Raise when the file is not a valid one of its kind."""
    kind = path.suffix.lower()
    data = path.read_bytes()
    if not data:
        raise ValueError("empty")
    if kind == ".svg":
        _check_svg(path)
    elif kind == ".pdf":
        if not (data.startswith(b"%PDF") and b"%%EOF" in data[-64:]):
            raise ValueError("not a whole PDF")
    elif kind == ".png":
        if not data.startswith(b"\x89PNG\r\n\x1a\n"):
            raise ValueError("not a PNG")
    elif kind == ".gif":
        if not data.startswith(b"GIF8"):
            raise ValueError("not a GIF")
    elif kind == ".dxf":
        import ezdxf

        ezdxf.readfile(path)
    elif kind == ".csv":
        rows = list(csv.reader(io.StringIO(data.decode("utf-8"))))
        if len({len(r) for r in rows}) != 1:
            raise ValueError("rows of different lengths")
    elif kind == ".html":
        _check_html(path)
    elif kind in (".json", ".txt") and data.lstrip().startswith(b"{"):
        json.loads(data, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
    elif kind == ".toml":
        import tomllib

        tomllib.loads(data.decode("utf-8"))


def _argv(command: str, scene: Path, folder: Path, answers: Path) -> tuple[list[str], list[Path]]:
    """The command's arguments and the files (or folders) it may write."""
    if command == "draw":
        return ["draw", str(scene), "-o", f"{folder}/draw/"], [folder / "draw"]
    if command == "sweep":
        return (["sweep", str(scene), "--steps", "12", "-o", f"{folder}/s.csv", "--plot", f"{folder}/s.png"],
                [folder / "s.csv", folder / "s.png"])
    if command == "handout":
        return (["handout", str(scene), "-o", f"{folder}/h.pdf", "--html", f"{folder}/h.html"],
                [folder / "h.pdf", folder / "h.html"])
    if command == "animate":
        return (["animate", str(scene), "-o", f"{folder}/m.html", "--positions", "8", "--parts", "mechanism",
                 "velocity", "acceleration", "centers", "paths", "functions"], [folder / "m.html"])
    if command == "variants":
        return ["variants", str(scene), "--n", "2", "-o", f"{folder}/v"], [folder / "v"]
    if command == "check":
        return ["check", str(scene), str(answers), "--json", "-o", f"{folder}/c.json"], [folder / "c.json"]
    return ["bench", str(scene), "--json", "--budget", "0.001"], []


_ALLOWED = {"check": (0, 1, 2, 3)}


def run_case(case: Case, folder: Path, limit_s: float = 120.0) -> Outcome:
    """Run the case in ``folder`` (empty); what each command did and every problem found."""
    outcome = Outcome()
    scene = folder / "s.toml"
    scene.write_text(case.text, encoding="utf-8")
    answers = folder / "a.toml"
    inputs = {scene.name, answers.name}
    runs: list[tuple[str, list[str], list[Path]]] = [("solve", ["solve", "--json", str(scene)], [])]
    for command in case.commands:
        argv, made = _argv(command, scene, folder, answers)
        runs.append((command, argv, made))
    for command, argv, made in runs:
        if command == "check":
            _write_answers(answers, outcome, folder)
        before = {p.name for p in folder.iterdir()}
        start = time.process_time()
        previous = signal.signal(signal.SIGALRM, _alarm)
        signal.setitimer(signal.ITIMER_REAL, limit_s)
        try:
            code, out, err = _main(argv)
        except _Timeout:
            outcome.problems.append(f"{command}: no end within {limit_s:g} s")
            continue
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
        outcome.seconds[command] = time.process_time() - start
        outcome.codes[command] = code
        if code not in _ALLOWED.get(command, (0, 2, 3)):
            outcome.problems.append(f"{command}: exit {code}: {err.strip()[-300:]}")
        for bad in ("Traceback", "internal error", "Warning:", "RuntimeWarning"):
            if bad in err:
                outcome.problems.append(f"{command}: {bad!r} on standard error: {err.strip()[-300:]}")
        if command == "solve" and code == 0:
            try:
                json.loads(out, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
                (folder / "solve.json").write_text(out, encoding="utf-8")
                inputs.add("solve.json")
            except ValueError as error:
                outcome.problems.append(f"solve: the JSON is not valid: {error}")
        after = {p.name for p in folder.iterdir()}
        if code not in (0, 1):
            left = sorted(after - before)
            if left:
                outcome.problems.append(f"{command}: exit {code} left {left}")
        else:
            for path in made:
                for file in ([path] if path.is_file() else sorted(path.rglob("*")) if path.is_dir() else []):
                    try:
                        _check_file(file)
                    except Exception as error:  # noqa: BLE001 - every way a file is bad is a finding
                        outcome.problems.append(f"{command}: {file.name} is not valid: {type(error).__name__}: "
                                                f"{str(error)[:200]}")
    leftovers = [p.name for p in folder.rglob("*") if p.name.endswith(".part")]
    if leftovers:
        outcome.problems.append(f"temporary files left: {leftovers}")
    del inputs
    return outcome


_DRAGS: list[object] = [0, -1, 1e6, -1e6, 1e308, -1e308, 1e-300, 10**400, "nan", "NaN", "inf", "-Infinity", "1e999",
                        None, True, "12", [], {}, "</script>", '"<&>"']
_POINTS = ["A", "B", "<", '"', "</script>", "<!--", "", "A@3", "中"]


def _strict_json(text: str) -> object:
    """``text`` as JSON; ValueError where it is not, or holds NaN or an infinity."""
    return json.loads(text, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(f"{c} in the JSON")))


def _check_state(state: object, where: str, problems: list[str]) -> None:
    """The editor's state: its sheet well-formed SVG with finite numbers and no script; a refusal a message."""
    if not isinstance(state, dict):
        problems.append(f"{where}: the answer is not an object")
        return
    svg = state.get("svg")
    if isinstance(svg, str):
        try:
            with tempfile.NamedTemporaryFile("w", suffix=".svg", encoding="utf-8", delete=False) as stream:
                stream.write(svg)
            _check_svg(Path(stream.name))
            if re.search(r"<script|javascript:|\son\w+\s*=", svg, re.IGNORECASE):
                raise ValueError("a script in the sheet")
        except Exception as error:  # noqa: BLE001 - every way a sheet is bad is a finding
            problems.append(f"{where}: the sheet is not valid: {type(error).__name__}: {str(error)[:200]}")
        finally:
            Path(stream.name).unlink(missing_ok=True)
    for key in ("refused", "errors"):
        value = state.get(key)
        if any(bad in str(value) for bad in ("Traceback", "internal error")):
            problems.append(f"{where}: {key}: {str(value)[:300]}")


def _without_timing(result: object) -> object:
    return {k: v for k, v in result.items() if k != "timing"} if isinstance(result, dict) else result


def run_editor(case: Case, folder: Path, drags: int = 6) -> Outcome:
    """``kinepoly edit``'s JSON API on the case, in-process: the editor started on ``folder``/s.toml (the case's text
    on disk) showing its example's text, then the case's text PUT and compared with ``solve --json``'s object or
    errors and exit status for that file; ``drags`` changes over the websocket (points moved to random and extreme
    places, wrong values, names that are markup), each answer strict JSON and its sheet well-formed SVG with no
    script; the file untouched until saved, then holding exactly the editor's text and solving as the editor
    said, with no temporary file left. Outcome codes: ``edit-put`` (the HTTP status), ``edit-save``."""
    import warnings

    with warnings.catch_warnings():  # starlette's note that it would rather drive httpx2: httpx is what is here
        warnings.simplefilter("ignore")
        from starlette.testclient import TestClient

    from kinepoly.editor.document import Document
    from kinepoly.editor.server import make_app

    outcome = Outcome()
    problems = outcome.problems
    scene = folder / "s.toml"
    scene.write_text(case.text, encoding="utf-8")
    start = time.process_time()
    code, out, err = _main(["solve", "--json", str(scene)])
    base = (ROOT / "examples" / f"{case.name.split('-', 1)[1]}.toml").read_text(encoding="utf-8")
    rng = random.Random(case.name)
    on_disk = scene.stat()
    names_before = sorted(p.name for p in folder.iterdir())
    port = 8765
    document = Document(str(scene), text=base)
    with TestClient(make_app(document, "t0ken", port), base_url=f"http://127.0.0.1:{port}",
                    raise_server_exceptions=False) as client:
        answer = client.put("/t0ken/api/scene", json={"text": case.text})
        outcome.codes["edit-put"] = answer.status_code
        try:
            body = _strict_json(answer.text)
        except ValueError as error:
            problems.append(f"edit PUT: {answer.status_code}: the answer is not valid JSON: {error}: "
                            f"{answer.text[:300]}")
            body = None
        if answer.status_code == 200 and code == 0:
            if _without_timing(body) != _without_timing(_strict_json(out)):
                problems.append("edit PUT: the answer differs from solve --json's object")
        elif answer.status_code == 422 and code in (2, 3) and isinstance(body, dict):
            if body.get("exit") != code or "\n".join(body.get("errors", [])) != err.rstrip("\n"):
                problems.append(f"edit PUT: errors {body.get('errors')!r} exit {body.get('exit')}; solve exit "
                                f"{code}: {err.strip()[-300:]}")
        else:
            problems.append(f"edit PUT: {answer.status_code} where solve exits {code}: {answer.text[:300]}")
        with client.websocket_connect("/t0ken/ws", headers={"host": f"127.0.0.1:{port}"}) as socket:
            for seq in range(drags + 1):
                state = document.state()
                points = sorted((state.get("handles") or {}).get("points", {})) if isinstance(state, dict) else []
                x, y = (rng.choice(_DRAGS) if rng.random() < 0.4 else rng.uniform(-500, 500) for _ in range(2))
                name = rng.choice(points) if points and rng.random() < 0.8 else rng.choice(_POINTS)
                edit = rng.choice([
                    {"op": "move-point", "point": name, "to": [x, y]}, {"op": "drive", "to": [x, y]},
                    {"op": "guess", "point": name, "to": [x, y]},
                    {"op": "set", "key": ["input", rng.choice(["omega", "angle", "alpha", "s"])], "value": x},
                    {"op": "length", "link": rng.choice(["2", "3", "<"]), "point": name, "value": x},
                ])
                message = ({"op": "full"} if seq == drags else
                           {"op": "edit", "edit": edit, "merge": True, "draft": rng.random() < 0.5, "seq": seq})
                try:
                    socket.send_text(json.dumps(message))
                    reply = _strict_json(socket.receive_text())
                except Exception as error:  # noqa: BLE001 - a closed socket or bad JSON is a finding
                    problems.append(f"edit websocket {str(message)[:200]}: {type(error).__name__}: {str(error)[:300]}")
                    break
                kind = ("refused" if isinstance(reply, dict) and "refused" in reply else
                        "solved" if isinstance(reply, dict) and reply.get("ok") else "not solved")
                outcome.tally[f"edit websocket {'full' if seq == drags else 'edit'} {kind}"] += 1
                _check_state(reply, f"edit websocket {str(message)[:200]}", problems)
        for path in ("/t0ken/api/solution", "/t0ken/api/state", "/t0ken/api/drawing.svg", "/t0ken/api/steps/1.svg"):
            got = client.get(path)
            if got.status_code not in (200, 404, 422) or (got.status_code == 200 and path.endswith(".svg")
                                                          and "<script" in got.text):
                problems.append(f"edit GET {path}: {got.status_code}: {got.text[:300]}")
            elif got.status_code == 200 and path.endswith(".svg"):
                _check_state({"svg": got.text}, f"edit GET {path}", problems)
            elif got.status_code != 404:
                try:
                    _strict_json(got.text)
                except ValueError as error:
                    problems.append(f"edit GET {path}: not valid JSON: {error}")
        after = scene.stat()
        if (after.st_mtime_ns, after.st_ino, scene.read_text(encoding="utf-8")) != (
                on_disk.st_mtime_ns, on_disk.st_ino, case.text):
            problems.append("edit: the scene's file was written before a save")
        final = document.state()
        if final["ok"]:
            saved = client.post("/t0ken/api/save", json={"force": False})
            outcome.codes["edit-save"] = saved.status_code
            written = scene.read_text(encoding="utf-8")
            if saved.status_code != 200 or written != final["text"]:
                problems.append(f"edit save: {saved.status_code}: {saved.text[:200]}; the file holds the text: "
                                f"{written == final['text']}")
            again, again_out, again_err = _main(["solve", "--json", str(scene)])
            if again != 0 or _without_timing(_strict_json(again_out)) != _without_timing(final["result"]):
                problems.append(f"edit save: the saved file solves otherwise (exit {again}): {again_err[-300:]}")
    left = sorted({p.name for p in folder.iterdir()} - set(names_before))
    if left:
        problems.append(f"edit: files left: {left}")
    outcome.seconds["edit"] = time.process_time() - start
    return outcome


def _write_answers(answers: Path, outcome: Outcome, folder: Path) -> None:
    """An answers file from the solve's JSON (right, or with a velocity's x turned round: wrong), or a broken one
    when it did not solve."""
    solved = folder / "solve.json"
    if outcome.codes.get("solve") != 0 or not solved.exists():
        answers.write_text("omega_3 = 1\nv_Q = [1, 2]\nnonsense = true\n", encoding="utf-8")
        return
    text = solved.read_text(encoding="utf-8")
    sign = -1.0 if len(text) % 2 else 1.0
    data = json.loads(text)
    lines = [f"omega_{name} = {values['omega']!r}" for name, values in data.get("links", {}).items()
             if isinstance(values, dict) and isinstance(values.get("omega"), float)][:3]
    for name, values in list(data.get("points", {}).items())[:2]:
        v = values.get("velocity") if isinstance(values, dict) else None
        if isinstance(v, list) and len(v) == 2:
            lines.append(f'"v_{name}" = [{sign * v[0]!r}, {v[1]!r}]')
    answers.write_text("\n".join(lines or ["omega_3 = 1"]) + "\n", encoding="utf-8")


def _browse(pages: list[Path]) -> list[str]:
    """Open the pages in headless chromium: the problems found (a script error, the page's script not run)."""
    from playwright.sync_api import sync_playwright

    problems = []
    with sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path="/usr/bin/chromium", headless=True,
                                         args=["--headless", "--no-sandbox", "--disable-gpu"])
        try:
            for path in pages:
                page = browser.new_page()
                errors: list[str] = []
                page.on("pageerror", lambda error: errors.append(str(error)))  # noqa: B023 - the page is closed below
                page.goto(path.as_uri())
                ran = page.evaluate("typeof window.kinepoly === 'object' || !!document.querySelector('main')")
                if errors or not ran or page.evaluate("window.pwned !== undefined"):
                    problems.append(f"{path}: {errors or 'its script did not run'}")
                page.close()
        finally:
            browser.close()
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=200)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--browser", type=int, default=0, metavar="N", help="open every N-th web page in chromium")
    parser.add_argument("--editor", action="store_true",
                        help="also run kinepoly edit's JSON API on every case (run_editor)")
    parser.add_argument("--editor-only", action="store_true", help="run only the editor's API on every case")
    parser.add_argument("--slow", type=float, default=20.0, help="CPU seconds of one command counted as slow")
    args = parser.parse_args(argv)
    counts: Counter[str] = Counter()
    failures: list[str] = []
    slow: list[str] = []
    kept = Path(tempfile.mkdtemp(prefix="kinepoly-fuzz-pages-"))
    pages: list[Path] = []
    started = time.perf_counter()
    for k, case in enumerate(cases(args.seed, args.cases)):
        with tempfile.TemporaryDirectory() as work:
            outcome = Outcome() if args.editor_only else run_case(case, Path(work))
            if args.editor or args.editor_only:
                with tempfile.TemporaryDirectory() as editing:
                    edited = run_editor(case, Path(editing))
                outcome.codes.update(edited.codes)
                outcome.problems += edited.problems
                outcome.seconds.update(edited.seconds)
                counts.update(edited.tally)
            for command, code in outcome.codes.items():
                counts[f"{command} {'status' if command.startswith('edit') else 'exit'} {code}"] += 1
                counts["runs"] += 1
            for command, seconds in outcome.seconds.items():
                if seconds > args.slow:
                    slow.append(f"{case.name} {command} {seconds:.1f} s")
            for page in Path(work).glob("*.html"):
                if args.browser and len(pages) < 10_000 and counts["pages"] % args.browser == 0:
                    pages.append(Path(kept, f"{case.name}-{page.name}"))
                    pages[-1].write_bytes(page.read_bytes())
                counts["pages"] += 1
        counts["cases"] += 1
        if outcome.problems:
            failures += [f"{case.name}: {p}" for p in outcome.problems]
            (kept / f"{case.name}.toml").write_text(case.text, encoding="utf-8")
        if (k + 1) % 100 == 0:
            print(f"{k + 1} cases, {counts['runs']} runs, {counts['pages']} pages, {len(failures)} problems, "
                  f"{len(slow)} slow, {time.perf_counter() - started:.0f} s", flush=True)
    browsed = _browse(pages) if pages else []
    failures += browsed
    print(f"cases {counts['cases']}, command runs {counts['runs']}, web pages {counts['pages']} "
          f"({len(pages)} opened in chromium), {time.perf_counter() - started:.0f} s")
    for key in sorted(k for k in counts if " exit " in k or k.startswith("edit")):
        print(f"  {key}: {counts[key]}")
    print(f"problems: {len(failures)}; over {args.slow:g} s of CPU: {len(slow)}")
    for line in failures + slow:
        print("  " + line)
    print(f"failing scenes kept in {kept}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT / "src"))
    raise SystemExit(main(sys.argv[1:]))
