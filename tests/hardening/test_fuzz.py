"""Mutated, broken and random scenes through ``solve --json``, ``draw`` and ``handout``, in-process.

Every run ends in exit 0, 2 or 3 (never 70, never a traceback); a JSON without NaN or infinity;
an SVG that is well-formed XML; and on failure nothing left behind. Bounded in time: a few dozen
examples, each with a deadline.
"""

from __future__ import annotations

import json
import re
from datetime import timedelta
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tests.hardening.support import BASE, well_formed_svg

from kinepoly.cli import main

NUMBERS = st.one_of(
    st.sampled_from(["0", "-0", "1e308", "-1e308", "5e-324", "1e154", "1e155", "1e-300", "nan", "inf", "-inf",
                     "1e200", "1e30", "1e-30", "3", "360", "-720", '"x"', "true", "[]", "{}", '"300 rpm"']),
    st.floats(allow_nan=False, allow_infinity=False, width=64).map(repr),
)
NAMES = st.one_of(
    st.sampled_from(["A", "B", "C", "A0", "B0", "1", "2", "3", "4", "5", "", "@", "A@3", "$x$", "$\\\\frac{1}{$",
                     "<&>", '\\"', "\\u0001", "\\u0008", "\\u000b", "\\ufffe", "\\u00e9", "中", "😀", " ", "ω13"]),
    st.text(alphabet=st.characters(blacklist_categories=("Cs",), blacklist_characters='"\\\n\r'), max_size=6),
)
EXTRA = st.sampled_from([
    "", "", "", "", "[draw]\nkv = 1000\n", "[draw]\nka = 1e-30\n", "[draw]\nkv = 5e-324\n", "[draw]\nkv = 1e308\n",
    '[find]\nvelocity = ["B"]\n', '[find]\ninstant_centers = "all"\n', '[find]\nacceleration = ["A@3"]\n',
    "[units]\nlength = \"m\"\n", "[input.x]\n", "[[sliders]]\nblock = \"4\"\nguide = \"1\"\npoint = \"B\"\n",
])


@st.composite
def scenes(draw: st.DrawFn) -> str:
    """BASE with a few numbers, names and lines changed, maybe a table added."""
    text = BASE
    for _ in range(draw(st.sampled_from([0, 1, 1, 2, 3]))):
        numbers = list(re.finditer(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", text))
        if numbers:
            m = draw(st.sampled_from(numbers))
            text = text[:m.start()] + draw(NUMBERS) + text[m.end():]
    for _ in range(draw(st.sampled_from([0, 0, 1, 2]))):
        names = list(re.finditer(r"\b(?:A0|B0|A|B|[1-4])\b(?= =)|\"[^\"]*\"", text))
        if names:
            m = draw(st.sampled_from(names))
            text = text[:m.start()] + '"' + draw(NAMES) + '"' + text[m.end():]
    lines = text.splitlines(keepends=True)
    if draw(st.integers(0, 3)) == 0 and lines:
        k = draw(st.integers(0, len(lines) - 1))
        lines[k:k + 1] = [] if draw(st.booleans()) else [lines[k], lines[k]]
    title = draw(st.one_of(st.just(""), st.just(""), st.just(""), NAMES.map(lambda n: f'title = "{n}"\n')))
    return title + "".join(lines) + draw(EXTRA)


def _run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code in (0, 2, 3), f"exit {code}: {err}"
    assert "Traceback" not in err and "internal error" not in err and "Warning" not in err, err
    return code, out, err


@pytest.mark.slow  # about 19 s: 60 random scenes, some with a handout
@settings(max_examples=60, deadline=timedelta(seconds=120), derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(text=scenes(), with_handout=st.integers(0, 3))
def test_any_scene_is_a_result_or_a_clear_message(capsys: pytest.CaptureFixture[str],
                                                  tmp_path_factory: pytest.TempPathFactory, text: str,
                                                  with_handout: int) -> None:
    folder = tmp_path_factory.mktemp("fuzz")
    scene = folder / "s.toml"
    scene.write_text(text, encoding="utf-8")
    code, out, _ = _run(capsys, "solve", "--json", str(scene))
    if code == 0:
        json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} in the JSON"))
    draw_code, _, _ = _run(capsys, "draw", str(scene), "-o", f"{folder}/out/")
    assert draw_code == code
    if code == 0:
        well_formed_svg(folder / "out" / "s.svg")
        assert sorted(p.name for p in (folder / "out").iterdir()) == ["s.dxf", "s.pdf", "s.png", "s.svg"]
    else:
        assert sorted(p.name for p in folder.iterdir()) == ["s.toml"]
    if with_handout == 0:  # a quarter of the examples: the handout is the slowest
        handout_code, _, _ = _run(capsys, "handout", str(scene), "-o", f"{folder}/h.pdf",
                                  "--html", f"{folder}/h.html")
        assert handout_code == code
        made = sorted(p.name for p in folder.iterdir() if p.suffix in (".pdf", ".html"))
        assert made == (["h.html", "h.pdf"] if code == 0 else [])
    assert not [p for p in Path(folder).rglob("*.part")]
