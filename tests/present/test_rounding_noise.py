"""Issue 13, item 3: no human-readable output prints rounding noise as a value.

A number printed next to others on one line whose magnitude is below 1e-9 of the line's
largest is taken for noise (a simple, robust proxy of "below its error estimate"); so is any
exponent of e-10 .. e-19 outside the lines that report errors themselves.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES

from kinepoly.present.clean import Noise, clean

EXAMPLE_FILES = sorted(EXAMPLES.glob("*.toml"))
_NUMBER = re.compile(r"[-−]?\d+(?:[.,]\d+)?(?:e[-+]?\d+)?")
_ERROR_LINE = re.compile(r"error|estimate|relative|run time|^[a-z_]+\s+[\d.e-]+\s+", re.IGNORECASE)


def _numbers(line: str) -> list[float]:
    out = []
    for text in _NUMBER.findall(line):
        try:
            out.append(float(text.replace("−", "-").replace(",", ".")))
        except ValueError:
            continue
    return out


def noisy_lines(text: str) -> list[str]:
    """Lines with a number 0 < |x| < 1e-9 times the line's largest, or an exponent e-10 .. e-19."""
    bad = []
    for line in text.splitlines():
        if _ERROR_LINE.search(line):
            continue
        values = [abs(v) for v in _numbers(line) if math.isfinite(v)]
        top = max(values, default=0.0)
        if re.search(r"\de-1\d", line) or any(0.0 < v < 1e-9 * top for v in values):
            bad.append(line)
    return bad


def test_clean_sets_values_below_the_estimate_to_zero() -> None:
    assert clean(1.42109e-14, 200.0, 4e-15) == 0.0
    assert clean(-9.1147e-15, 1.0, 1e-14) == 0.0
    assert clean(20.1393, 200.0, 4e-15) == 20.1393
    assert math.copysign(1.0, clean(-0.0, 1.0, 1e-15)) == 1.0
    assert math.isinf(clean(math.inf, 1.0, 1.0))
    noise = Noise({"direction": 1e-15})
    assert noise.pair((1.0, -6.12323e-17), "direction") == (1.0, 0.0)


def test_the_detector_finds_the_reported_noise() -> None:
    assert noisy_lines("I26     (1.42109e-14, 20.1393)  Kennedy step 6")
    assert noisy_lines("D  (2858.58, -4.54747e-13)")
    assert not noisy_lines("D  (2858.58, 0)  2858.58")


@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=lambda p: p.stem)
def test_the_table_prints_no_noise(capsys: pytest.CaptureFixture[str], path: Path) -> None:
    code, out, _ = run(capsys, "solve", str(path))
    assert code == 0
    assert noisy_lines(out) == []


@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=lambda p: p.stem)
def test_the_steps_print_no_noise(capsys: pytest.CaptureFixture[str], path: Path) -> None:
    code, out, _ = run(capsys, "solve", str(path), "--steps")
    assert code == 0
    assert noisy_lines(out) == []


@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=lambda p: p.stem)
def test_the_drawing_text_prints_no_noise(capsys: pytest.CaptureFixture[str], tmp_path: Path, path: Path) -> None:
    target = tmp_path / "out.svg"
    code, _, _ = run(capsys, "draw", str(path), "-o", str(target))
    assert code == 0
    texts = re.findall(r"<text[^>]*>(.*?)</text>", target.read_text(encoding="utf-8"), flags=re.DOTALL)
    words = "\n".join(re.sub(r"<[^>]+>", "", t) for t in texts)
    assert noisy_lines(words) == []


def test_the_json_keeps_the_computed_floats(capsys: pytest.CaptureFixture[str]) -> None:
    """The JSON is for programs: each center's place is the float the engine computed, to the last bit (no
    rounding for people), and some of them have more digits than a person is shown."""
    import json

    import kinepoly

    path = EXAMPLES / "centers-six-bar.toml"
    code, out, _ = run(capsys, "solve", str(path), "--json")
    assert code == 0
    x = json.loads(out)["instant_centers"]
    centers = kinepoly.solve(kinepoly.load_scene(path)).centers
    assert centers is not None
    finite = {name: c.place.position for name, c in centers.centers.items() if c.place.position is not None}
    assert finite and all(x[name]["position"] == list(position) for name, position in finite.items())
    assert any(len(repr(v)) > 12 for position in finite.values() for v in position), "unrounded floats are kept"

