"""Issue 15's reproducers, one test each: the exit status, the message, and well-formed output (or none)."""

from __future__ import annotations

import json
import os
import signal
import stat
import subprocess
import sys
from pathlib import Path

import pytest
from tests.hardening.support import BASE, edit, run_on, well_formed_svg

from kinepoly.cli import EXIT_INTERRUPTED, main

# -- 1. characters no drawing can show -------------------------------------------------------------------------

UNSHOWABLE = [
    ("title", edit(before='title = "\\u0001"\n'), "title: the title has the character U+0001"),
    ("title backspace", edit(before='title = "a\\u0008b"\n'), "U+0008"),
    ("title vertical tab", edit(before='title = "\\u000b"\n'), "U+000B"),
    ("title noncharacter", edit(before='title = "x\\ufffe"\n'), "U+FFFE"),
    ("point name", edit("B = [120, 0] }", 'B = [120, 0], "P\\u0001" = [5, 5] }'),
     'links.3.points."P\\u0001": the point name has the character U+0001'),
    ("link name", edit("[input]", '"L\\u0008" = { points = { B = [1, 1] } }\n[input]'), "the link name has"),
]


@pytest.mark.parametrize("name, text, fragment", UNSHOWABLE, ids=[u[0] for u in UNSHOWABLE])
@pytest.mark.parametrize("command", [["solve"], ["draw", "-o", "{tmp}/x.svg"], ["handout", "-o", "{tmp}/h.pdf"]])
def test_a_character_that_cannot_be_shown_is_a_scene_error(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                          name: str, text: str, fragment: str,
                                                          command: list[str]) -> None:
    code, _, err = run_on(capsys, tmp_path, text, *command)
    assert code == 2, err
    assert fragment in err and "\x01" not in err and "\x08" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


@pytest.mark.parametrize("title", ["中文 😀", "$x$", "$\\frac{1}{$", "a & <b> \"c\" 'd'", "é\u0301 ω₁₃"])
def test_odd_but_printable_names_are_shown_as_written_in_every_format(capsys: pytest.CaptureFixture[str],
                                                                       tmp_path: Path, title: str) -> None:
    text = edit("B = [120, 0] }", f'B = [120, 0], {json.dumps(title, ensure_ascii=False)} = [30, 20] }}',
                before=f"title = {json.dumps(title, ensure_ascii=False)}\n")
    code, _, err = run_on(capsys, tmp_path, text, "draw", "-o", "{tmp}/out/")
    assert code == 0, err
    assert "Warning" not in err and "Glyph" not in err
    root = well_formed_svg(tmp_path / "out" / "s.svg")
    texts = "".join("".join(e.itertext()) for e in root.iter() if e.tag.endswith("text"))
    assert title in texts  # as written: "$x$" is not typeset as math
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["s.dxf", "s.pdf", "s.png", "s.svg"]
    code, _, err = run_on(capsys, tmp_path, text, "handout", "-o", "{tmp}/h.pdf", "--html", "{tmp}/h.html")
    assert code == 0, err
    assert (tmp_path / "h.pdf").read_bytes().startswith(b"%PDF")


# -- 2, 3, 4. polygon scales --------------------------------------------------------------------------------------

def test_a_scale_too_large_for_the_page_is_reduced_and_said(capsys: pytest.CaptureFixture[str],
                                                           tmp_path: Path) -> None:
    text = edit(after="[draw]\nkv = 1000\n")
    for command in (["draw", "-o", "{tmp}/x.svg"], ["draw", "-o", "{tmp}/x.png"], ["handout", "-o", "{tmp}/h.pdf"]):
        code, _, err = run_on(capsys, tmp_path, text, *command)
        assert code == 0, err
    root = well_formed_svg(tmp_path / "x.svg")
    assert "kv reduced from 1000" in "".join(root.itertext())


@pytest.mark.parametrize("value", ["5e-324", "1e308", "1e-31", "1e31"])
def test_a_scale_out_of_range_is_a_scene_error(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                               value: str) -> None:
    text = edit(after=f"[draw]\nkv = {value}\n")
    for command in (["solve", "--json"], ["draw", "-o", "{tmp}/x.svg"], ["handout", "-o", "{tmp}/h.pdf"]):
        code, _, err = run_on(capsys, tmp_path, text, *command)
        assert code == 2, err
        assert "draw.kv:" in err and "out of range" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


@pytest.mark.parametrize("value", ["1e30", "1e-30"])
def test_the_extreme_scales_in_range_solve_and_draw(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                   value: str) -> None:
    text = edit(after=f"[draw]\nkv = {value}\n")
    code, out, err = run_on(capsys, tmp_path, text, "solve", "--json")
    assert code == 0, err
    json.loads(out)
    code, _, err = run_on(capsys, tmp_path, text, "draw", "-o", "{tmp}/x.svg")
    assert code == 0, err
    well_formed_svg(tmp_path / "x.svg")


# -- 5, 6. guesses far away -----------------------------------------------------------------------------------------

@pytest.mark.parametrize("guess", ["[1e200, 80]", "[1e154, 1e154]", "[-1e300, 1e300]"])
def test_a_guess_far_away_still_picks_an_assembly(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                  guess: str) -> None:
    text = edit("B = [110, 80]", f"B = {guess}")
    code, out, err = run_on(capsys, tmp_path, text, "solve", "--json")
    assert code in (0, 2, 3), err
    assert "internal error" not in err
    if code == 0:
        json.loads(out)


# -- 7. rates so large that the polygons overflow ------------------------------------------------------------------

@pytest.mark.parametrize("omega", ["1e154", "1e155", "1e300", "1e308"])
@pytest.mark.parametrize("find", ["", '[find]\ninstant_centers = "all"\n'])
def test_overflowing_rates_are_a_clear_error(capsys: pytest.CaptureFixture[str], tmp_path: Path, omega: str,
                                             find: str) -> None:
    text = edit("omega = 10", f"omega = {omega}", after=find)
    for command in (["solve"], ["solve", "--json"], ["draw", "-o", "{tmp}/x.svg"]):
        code, out, err = run_on(capsys, tmp_path, text, *command)
        assert "nan" not in out and "inf" not in out and "Warning" not in err
        if find and omega != "1e308":  # only omega asked, no polygon: its values are still numbers
            assert code == 0, err
            continue
        assert code == 3 and "overflowed" in err, err
    if not find or omega == "1e308":
        assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


# -- 8. mathtext, and a folder of four files written all or none ---------------------------------------------------

def test_a_dollar_name_draws_in_every_format(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = edit("B = [120, 0] }", 'B = [120, 0], "$\\\\frac{1}{$" = [10, 10] }')
    for command in (["draw", "-o", "{tmp}/x.png"], ["draw", "-o", "{tmp}/x.pdf"], ["draw", "-o", "{tmp}/out/"],
                    ["handout", "-o", "{tmp}/h.pdf"]):
        code, _, err = run_on(capsys, tmp_path, text, *command)
        assert code == 0, (command, err)
    assert len(list((tmp_path / "out").iterdir())) == 4


def test_a_folder_is_written_all_or_none(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                         monkeypatch: pytest.MonkeyPatch) -> None:
    from kinepoly.render import mpl

    def broken(*args: object, **kwargs: object) -> None:
        raise ValueError("a renderer failed")

    monkeypatch.setattr(mpl, "write_pdf", broken)
    code, _, err = run_on(capsys, tmp_path, BASE, "draw", "-o", "{tmp}/out/")
    assert code == 70 and "a renderer failed" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]  # not even the folder


# -- 9. folders made only for a scene that solves; file modes; Ctrl-C; long healthy chains ---------------------------

@pytest.mark.parametrize("option", [["-o", "{tmp}/out/"], ["--steps", "{tmp}/steps"]])
def test_a_failed_draw_makes_no_folder(capsys: pytest.CaptureFixture[str], tmp_path: Path, option: list[str]) -> None:
    code, _, err = run_on(capsys, tmp_path, edit("B = [120, 0] }", "B = [1, 0] }"), "draw", *option)
    assert code == 3, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_sweep_and_draw_write_the_same_file_mode(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    assert run_on(capsys, tmp_path, BASE, "sweep", "--steps", "24", "-o", "{tmp}/x.csv",
                  "--plot", "{tmp}/x.png")[0] == 0
    assert run_on(capsys, tmp_path, BASE, "draw", "-o", "{tmp}/d.svg")[0] == 0
    modes = {p.name: stat.S_IMODE(p.stat().st_mode) for p in tmp_path.iterdir() if p.name != "s.toml"}
    umask = os.umask(0o022)
    os.umask(umask)
    assert set(modes.values()) == {0o666 & ~umask}, modes  # new files follow the umask (issue 30)


def test_ctrl_c_is_a_message_not_a_traceback(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    import kinepoly.solution

    def interrupted(*args: object, **kwargs: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(kinepoly.solution, "solve", interrupted)
    (tmp_path / "s.toml").write_text(BASE)
    code = main(["solve", str(tmp_path / "s.toml")])
    err = capsys.readouterr().err
    assert code == EXIT_INTERRUPTED and err == "kinepoly: interrupted\n"


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process")
def test_ctrl_c_in_a_process(tmp_path: Path) -> None:
    (tmp_path / "s.toml").write_text(BASE)
    script = ("import signal, kinepoly.solution as s\n"
              "def slow(*a, **k):\n    signal.raise_signal(signal.SIGINT)\n"
              "s.solve = slow\nfrom kinepoly.cli import main\nraise SystemExit(main(['solve', "
              f"{str(tmp_path / 's.toml')!r}]))\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, check=False,
                          env={**os.environ, "PYTHONWARNINGS": "ignore"})
    assert done.returncode == EXIT_INTERRUPTED and "Traceback" not in done.stderr
    assert signal.SIGINT == 2


def test_a_long_chain_of_healthy_loops_gives_no_warning(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from kinepoly.bench.chain import chain_text

    code, out, err = run_on(capsys, tmp_path, chain_text(60), "solve", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["warnings"] == []
    assert data["check"]["condition_number"] < 1e3


@pytest.mark.parametrize(("scene", "old", "new"), [
    ("four-bar", "B = [110, 80]", "B = [110, -1e308]"),
    ("triad", "C = [101, 21]", "C = [-322.1, -1e308]"),
    ("triad", "C = [101, 21]", "C = [1e200, 1e200]"),
])
def test_a_guess_at_the_edge_of_the_floats_is_no_internal_error(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                                scene: str, old: str, new: str) -> None:
    # a [guess] whose squared distance overflows a float (found by fuzzing the editor's drags) made exit 70
    text = BASE if scene == "four-bar" else (Path(__file__).resolve().parents[2] / "examples" /
                                             f"{scene}.toml").read_text(encoding="utf-8")
    assert old in text
    code, out, err = run_on(capsys, tmp_path, text.replace(old, new), "solve", "--json")
    assert code in (0, 3), err
    assert "internal error" not in err and "Traceback" not in err
    if code == 0:
        json.loads(out, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
