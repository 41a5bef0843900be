"""Issue 13, item 1: one kv and one ka per scene and paper, the same in every output.

``kinepoly solve --json`` (and its table), the SVG of ``kinepoly draw``, the handout's pages (the
sheets its PDF is printed from) and its web page in every shipped language all write the scales of
``present.scales.decide_scales``; ``kinepoly check`` recognises a polygon length read off that
drawing and not divided by its kv or ka. The scales are read back from each output's text, not
from the objects that made it.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

import pytest
from tests.scenes import EXAMPLES

from kinepoly.cli import main
from kinepoly.handout import handout_html, handout_sheets, load_catalogue, packaged_languages
from kinepoly.homework import check, loads_answers, make_checker
from kinepoly.present.scales import A4, decide_scales, nice_scale, polygon_room
from kinepoly.render.primitives import Text
from kinepoly.scene.loader import load_scene, loads_scene
from kinepoly.solution import Solution, solve

NAMES = sorted(p.stem for p in EXAMPLES.glob("*.toml"))
_SCALE = re.compile(r"\b(k[va])\s*=\s*([0-9][0-9.,]*)")


def _numbers(text: str) -> dict[str, set[float]]:
    """Every ``kv = X`` and ``ka = X`` written in ``text`` (a decimal comma read as a point)."""
    found: dict[str, set[float]] = {"kv": set(), "ka": set()}
    for symbol, number in _SCALE.findall(text):
        found[symbol].add(float(number.rstrip(".,").replace(",", ".")))
    return found


def _expected(data: dict[str, Any]) -> dict[str, set[float]]:
    polygons = data.get("polygons", {})
    return {symbol: {polygons[kind]["scale"]} if kind in polygons else set()
            for symbol, kind in (("kv", "velocity"), ("ka", "acceleration"))}


def _solved_json(name: str, capsys: pytest.CaptureFixture[str], *options: str) -> dict[str, Any]:
    assert main(["solve", str(EXAMPLES / f"{name}.toml"), "--json", *options]) == 0
    data: dict[str, Any] = json.loads(capsys.readouterr().out)
    return data


def _sheet_text(sheet: Any) -> str:
    return "\n".join("".join(run.text for run in item.runs) for layer in sheet.layers for item in layer.items
                     if isinstance(item, Text))


@pytest.mark.slow  # every example drawn and handed out in every form: 4 to 8 s each
@pytest.mark.parametrize("name", NAMES)
def test_solve_draw_and_every_handout_write_the_same_kv_and_ka(name: str, tmp_path: Path,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    data = _solved_json(name, capsys)
    expected = _expected(data)
    assert expected["kv"] or expected["ka"]
    assert main(["solve", str(EXAMPLES / f"{name}.toml")]) == 0
    assert _numbers(capsys.readouterr().out) == expected, "solve's table"
    assert main(["draw", str(EXAMPLES / f"{name}.toml"), "-o", str(tmp_path / "d.svg")]) == 0
    capsys.readouterr()
    assert _numbers((tmp_path / "d.svg").read_text(encoding="utf-8")) == expected, "the SVG"
    solution = solve(load_scene(EXAMPLES / f"{name}.toml"))
    for code in packaged_languages():
        say = load_catalogue(code)
        _handout, sheets = handout_sheets(solution, say, "A4")
        for number, sheet in enumerate(sheets, 1):
            assert _numbers(_sheet_text(sheet)) == expected, f"PDF ({code}), page {number}"
        _page, html = handout_html(solution, say, "A4")
        assert _numbers(html) == expected, f"HTML ({code})"


def _first(data: dict[str, Any], level: str) -> tuple[str, float | tuple[float, float]] | None:
    """An answer key the scene reports at ``level`` (velocity or acceleration) and its value."""
    rate, point_key, symbol = ("omega", "velocity", "v") if level == "velocity" else ("alpha", "acceleration", "a")
    for label, entry in data.get("points", {}).items():
        value = entry.get(point_key)
        if value is not None and math.hypot(*value) > 0.0:
            return f"{symbol}_{label}", (value[0], value[1])
    for link, entry in data.get("links", {}).items():
        if entry.get(rate):
            return f"{rate}_{link}", float(entry[rate])
    return None


def _toml(value: float | tuple[float, float]) -> str:
    return f"[{value[0]!r}, {value[1]!r}]" if isinstance(value, tuple) else repr(value)


@pytest.mark.parametrize("name", NAMES)
def test_check_recognises_a_polygon_length_not_divided_by_that_kv_or_ka(name: str,
                                                                         capsys: pytest.CaptureFixture[str]) -> None:
    data = _solved_json(name, capsys)
    text = (EXAMPLES / f"{name}.toml").read_text(encoding="utf-8")
    scene = loads_scene(text, f"{name}.toml")
    tried = 0
    for level, symbol, code in (("velocity", "velocity", "kv-not-divided"),
                                ("acceleration", "acceleration", "ka-not-divided")):
        if symbol not in data.get("polygons", {}):
            continue
        found = _first(data, level)
        if found is None:
            continue
        key, value = found
        k = data["polygons"][symbol]["scale"]
        if k == 1.0:  # at 1 mm per unit a forgotten scale changes nothing: no mistake to recognise
            continue
        on_paper = (value[0] * k, value[1] * k) if isinstance(value, tuple) else value * k
        answers = loads_answers(f'"{key}" = {_toml(on_paper)}\n', scene, "answers.toml")
        result = check(answers, make_checker(scene, [answers], text))
        verdict = next(v for v in result.verdicts if v.key.text == key)
        assert verdict.diagnosis is not None, (key, on_paper)
        assert code in (verdict.diagnosis.code, *verdict.diagnosis.alternatives), (key, verdict.diagnosis)
        tried += 1
    assert tried >= 1


def test_a_paper_too_small_for_the_polygon_reduces_its_scale_and_solve_says_so(
        capsys: pytest.CaptureFixture[str]) -> None:
    a4 = _solved_json("four-bar", capsys)
    small = _solved_json("four-bar", capsys, "--paper", "100x100")
    reduced = [w for w in small["warnings"] if w["code"] == "scale-reduced"]
    assert not [w for w in a4["warnings"] if w["code"] == "scale-reduced"]
    assert reduced
    for kind, polygon in small["polygons"].items():
        if "wanted" in polygon:
            assert polygon["wanted"] == a4["polygons"][kind]["scale"] > polygon["scale"]
            symbol = "kv" if kind == "velocity" else "ka"
            assert any(f"{symbol} reduced from {polygon['wanted']:g} to {polygon['scale']:g}" in w["message"]
                       for w in reduced)
    assert main(["solve", str(EXAMPLES / "four-bar.toml"), "--paper", "100x100"]) == 0
    assert "scale-reduced" in capsys.readouterr().out


def _solution(extra: str = "") -> Solution:
    return solve(loads_scene((EXAMPLES / "four-bar.toml").read_text(encoding="utf-8") + extra, "four-bar.toml"))


def _extent(solution: Solution, kind: str) -> tuple[float, float]:
    """The polygon's drawn box (tips, the pole and the ends of the steps' vectors), by hand."""
    polygon = solution.velocity if kind == "velocity" else solution.acceleration
    assert polygon is not None
    points = [(0.0, 0.0), *polygon.tips.values()]
    points += [p for s in solution.steps if s.polygon == kind for v in s.vectors for p in (v.start, v.end)]
    return (max(p[0] for p in points) - min(p[0] for p in points),
            max(p[1] for p in points) - min(p[1] for p in points))


@pytest.mark.parametrize("paper", [A4, (420.0, 297.0), (160.0, 140.0), (120.0, 100.0)])
def test_the_scale_is_the_wanted_one_when_the_polygon_fits_else_the_largest_round_one_that_fits(
        paper: tuple[float, float]) -> None:
    solution = _solution()
    room = polygon_room(paper)
    for scale in decide_scales(solution, paper).polygons:
        w, h = _extent(solution, scale.kind)
        mantissa = scale.value / 10.0 ** math.floor(math.log10(scale.value) + 1e-12)
        assert any(math.isclose(mantissa, m) for m in (1.0, 2.0, 2.5, 5.0))
        fits = w * scale.wanted <= room[0] * (1 + 1e-12) and h * scale.wanted <= room[1] * (1 + 1e-12)
        assert scale.reduced is not fits
        assert w * scale.value <= room[0] * (1 + 1e-12) and h * scale.value <= room[1] * (1 + 1e-12)
        if scale.reduced:  # the next round number up would not fit
            larger = min(m * 10.0**e for m in (1.0, 2.0, 2.5, 5.0) for e in range(-8, 8)
                         if m * 10.0**e > scale.value * (1 + 1e-9))
            assert w * larger > room[0] or h * larger > room[1]


def test_draw_kv_and_ka_fix_the_scales() -> None:
    fixed = decide_scales(_solution("\n[draw]\nkv = 0.2\nka = 0.02\n"))
    assert fixed.as_dict() == {"velocity": 0.2, "acceleration": 0.02}
    assert all(p.given and not p.reduced for p in fixed.polygons)
    auto = decide_scales(_solution())
    solution = _solution()
    assert solution.velocity is not None
    tips = [(0.0, 0.0), *solution.velocity.tips.values()]
    assert auto.get("velocity") == nice_scale(max(math.dist(p, q) for p in tips for q in tips))
