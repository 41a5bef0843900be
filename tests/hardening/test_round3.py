"""Issue 30's reproducers (hardening, round 3), one test each: each failed before its fix.

Script data in web pages; exit 70 on input that deserves a message; output files (an input given
as output, devices, modes, SIGTERM); bounded reading, depth and cost.
"""

from __future__ import annotations

import errno
import json
import os
import re
import signal
import stat
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

import pytest
from tests.cli_support import run
from tests.hardening.support import BASE, edit, run_on, well_formed_svg

# -- 1. script data in web pages -----------------------------------------------------------------------------------

HOSTILE = ["<!--<script>", "</script><script>window.pwned = 1</script>", "a & b > c", "]]><!--", "\u2028x"]


@pytest.mark.parametrize("text", HOSTILE)
def test_script_json_escapes_what_could_end_or_comment_the_element(text: str) -> None:
    from kinepoly.present.script_json import script_json

    data = script_json({"title": text, "names": [text]})
    assert not {"<", ">", "&"} & set(data)
    assert json.loads(data) == {"title": text, "names": [text]}


def test_script_json_refuses_nan() -> None:
    from kinepoly.present.script_json import script_json

    with pytest.raises(ValueError):
        script_json([float("nan")])


def _hostile_scene() -> str:
    title = "<!--<script> & </script><script>window.pwned = 1</script>"
    return edit('3 = { points = { A = [0, 0], B = [120, 0] } }',
                '"<!--<script>" = { points = { A = [0, 0], B = [120, 0] } }',
                before=f"title = {json.dumps(title)}\n").replace('"3"', '"<!--<script>"')


def test_the_animation_page_keeps_its_data_and_script_in_a_browser(browser: Any, capsys: pytest.CaptureFixture[str],
                                                                  tmp_path: Path) -> None:
    text = _hostile_scene()
    code, _, err = run_on(capsys, tmp_path, text, "animate", "-o", "{tmp}/m.html", "--positions", "12")
    assert code == 0, err
    page = (tmp_path / "m.html").read_text(encoding="utf-8")
    data = page.split('<script type="application/json" id="frames">')[1].split("</script>")[0]
    assert "<" not in data and ">" not in data and "&" not in data
    browser.goto((tmp_path / "m.html").as_uri())
    assert browser.evaluate("typeof window.kinepoly") == "object"  # the page's own script ran
    assert browser.evaluate("window.pwned === undefined")
    assert browser.evaluate("window.kinepoly.data.title") == json.loads(text.splitlines()[0].split("=", 1)[1])
    names = browser.evaluate("window.kinepoly.data.values.map(v => v.name)")
    assert any("<!--<script>" in name for name in names), names  # the link's name read back as it was written
    assert browser.evaluate("document.querySelectorAll('#drawing svg').length") >= 1
    assert browser.errors == []


def test_the_handout_page_shows_a_hostile_title_as_text_in_a_browser(browser: Any,
                                                                      capsys: pytest.CaptureFixture[str],
                                                                      tmp_path: Path) -> None:
    code, _, err = run_on(capsys, tmp_path, _hostile_scene(), "handout", "--html", "{tmp}/h.html")
    assert code == 0, err
    browser.goto((tmp_path / "h.html").as_uri())
    assert browser.evaluate("window.pwned === undefined")
    assert browser.text_content("h1").startswith("<!--<script> & </script>")
    assert browser.evaluate("document.querySelectorAll('main section').length") > 1
    assert browser.errors == []


# -- 2. input that deserves a message, not exit 70 -------------------------------------------------------------------

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _renamed(text: str, old: str, new: str) -> str:
    """``text`` with the point or link ``old`` renamed ``new`` (a TOML basic string) wherever it is written."""
    quoted = json.dumps(new)
    text = re.sub(rf'"{re.escape(old)}(@[^"]*)?"', lambda m: quoted[:-1] + (m.group(1) or "") + '"', text)
    return re.sub(rf"(?m)(?<=[{{,] ){re.escape(old)}(?= = )|^{re.escape(old)}(?= = )", lambda m: quoted, text)


def test_a_point_named_with_a_slash_is_a_scene_error(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, _, err = run_on(capsys, tmp_path, _renamed(BASE, "B", "a/b"), "solve")
    assert code == 2, err
    assert 'links.3.points.a/b: bad point name; expected a name without "/"' in err


def test_a_backslash_in_a_point_name_is_written_as_it_is(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = _renamed((EXAMPLES / "slotted-lever.toml").read_text(encoding="utf-8"), "A", "A\\1")
    code, out, err = run_on(capsys, tmp_path, text, "solve", "--steps")
    assert code == 0, err
    assert "A\\1@4" in out
    code, _, err = run_on(capsys, tmp_path, text, "handout", "--html", "{tmp}/h.html")
    assert code == 0, err


def test_a_link_named_at_is_a_scene_error(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = _renamed((EXAMPLES / "cam-roller-rocker.toml").read_text(encoding="utf-8"), "2", "@")
    for command in (["solve"], ["handout", "-o", "{tmp}/h.pdf"]):
        code, _, err = run_on(capsys, tmp_path, text, *command)
        assert code == 2, err
        assert 'links.@: bad link name; expected a name without "@"' in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_a_byte_order_mark_is_read_by_check_as_by_solve(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    scene = tmp_path / "s.toml"
    scene.write_text("\ufeff" + BASE, encoding="utf-8")
    (tmp_path / "a.toml").write_text("\ufeffomega_3 = 1\n", encoding="utf-8")
    for argv in (["solve", str(scene)], ["check", str(scene), str(tmp_path / "a.toml")],
                 ["variants", str(scene), "--n", "2", "-o", str(tmp_path / "v")]):
        code, _, err = run(capsys, *argv)
        assert code in (0, 1), (argv, err)


def test_a_spline_point_far_away_is_a_scene_error(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = (EXAMPLES / "spline-cam-knife.toml").read_text(encoding="utf-8")
    text = text.replace("[55.000000, 0.000000]", "[55.000000, -1e308]", 1)
    code, _, err = run_on(capsys, tmp_path, text, "solve")
    assert code == 2, err
    assert "cams.1.profile.points: the area or the spline of these points overflows double precision" in err
    assert "Warning" not in err


def test_a_rate_too_small_for_any_scale_draws_its_polygon_as_a_dot(capsys: pytest.CaptureFixture[str],
                                                                  tmp_path: Path) -> None:
    text = edit("omega = 10", "omega = 5e-324")
    code, out, err = run_on(capsys, tmp_path, text, "solve", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["polygons"]["velocity"]["scale"] == 1e300
    code, _, err = run_on(capsys, tmp_path, text, "draw", "-o", "{tmp}/d.svg")
    assert code == 0, err
    well_formed_svg(tmp_path / "d.svg")


def test_a_cam_turning_at_1e308_rpm_overflows_with_a_message(capsys: pytest.CaptureFixture[str],
                                                            tmp_path: Path) -> None:
    text = re.sub(r"(?m)^omega = .*$", 'omega = "1e308 rpm"', (EXAMPLES / "metu-cam.toml").read_text(encoding="utf-8"),
                  count=1)
    for command in (["solve"], ["draw", "-o", "{tmp}/d.svg"]):
        code, _, err = run_on(capsys, tmp_path, text, *command)
        assert code == 3 and "overflowed" in err, err


@pytest.mark.parametrize("command", [["draw", "-o", "{tmp}/%s.svg"], ["draw", "-o", "{tmp}/%s/"],
                                     ["sweep", "-o", "{tmp}/%s.csv"], ["handout", "-o", "{tmp}/%s.pdf"],
                                     ["handout", "--html", "{tmp}/%s.html"], ["check", "{tmp}/s.toml", "-o",
                                                                               "{tmp}/%s.txt"]])
def test_an_output_name_too_long_is_an_output_error(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                    command: list[str]) -> None:
    argv = [a.replace("%s", "x" * 300) for a in command]
    code, _, err = run_on(capsys, tmp_path, BASE, *argv)
    assert code == 2, err
    assert "File name too long" in err and "internal error" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_the_longest_name_the_file_system_holds_is_written(capsys: pytest.CaptureFixture[str],
                                                           tmp_path: Path) -> None:
    name = "x" * (os.pathconf(tmp_path, "PC_NAME_MAX") - 4) + ".csv"  # its temporary name would be longer
    code, _, err = run_on(capsys, tmp_path, BASE, "sweep", "--steps", "12", "-o", f"{{tmp}}/{name}")
    assert code == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([name, "s.toml"])


def test_an_animation_page_with_no_polygon_anywhere(browser: Any, capsys: pytest.CaptureFixture[str],
                                                    tmp_path: Path) -> None:
    text = re.sub(r"(?m)^omega = .*$", 'omega = "1e308 rpm"',
                  (EXAMPLES / "cam-roller-rocker.toml").read_text(encoding="utf-8"), count=1)
    code, _, err = run_on(capsys, tmp_path, text, "animate", "-o", "{tmp}/m.html", "--positions", "12",
                          "--parts", "mechanism", "velocity", "functions")
    assert code == 0, err
    assert "12 positions are singular" in err
    browser.goto((tmp_path / "m.html").as_uri())
    assert browser.evaluate("typeof window.kinepoly") == "object"
    assert browser.errors == []


def test_a_full_disk_under_sweep_is_a_message(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    def full(fd: int) -> None:
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fsync", full)
    for command in (["sweep", "--steps", "12", "-o", "{tmp}/x.csv"],
                    ["sweep", "--steps", "12", "--plot", "{tmp}/x.png"]):
        code, _, err = run_on(capsys, tmp_path, BASE, *command)
        assert code == 2, err
        assert "cannot write" in err and "No space left on device" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


# -- 3. files --------------------------------------------------------------------------------------------------------

def _links(tmp_path: Path) -> list[str]:
    (tmp_path / "a.toml").write_text("omega_3 = 1\n", encoding="utf-8")
    os.symlink(tmp_path / "s.toml", tmp_path / "soft.toml")
    os.link(tmp_path / "s.toml", tmp_path / "hard.toml")
    return ["s.toml", "soft.toml", "hard.toml"]


@pytest.mark.parametrize("command", [["sweep", "--steps", "12", "-o"], ["sweep", "--steps", "12", "--plot"],
                                     ["check", "{tmp}/a.toml", "-o"], ["check", "{tmp}/a.toml", "--json", "-o"]])
def test_an_output_that_is_an_input_is_refused(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                               command: list[str]) -> None:
    (tmp_path / "s.toml").write_text(BASE, encoding="utf-8")
    for name in _links(tmp_path):
        code, _, err = run_on(capsys, tmp_path, BASE, *command, f"{{tmp}}/{name}")
        assert code == 2, err
        assert f"{name}: is the input" in err and "writing it would replace it" in err
        assert (tmp_path / "s.toml").read_text(encoding="utf-8") == BASE
    code, _, err = run_on(capsys, tmp_path, BASE, "check", "{tmp}/a.toml", "-o", "{tmp}/a.toml")
    assert code == 2 and "a.toml: is the input" in err
    assert (tmp_path / "a.toml").read_text(encoding="utf-8") == "omega_3 = 1\n"


def test_a_fifo_is_written_to_not_replaced(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    got: list[bytes] = []

    def reader() -> None:
        with open(fifo, "rb") as stream:
            got.append(stream.read())

    thread = threading.Thread(target=reader, daemon=True)
    thread.start()
    code, _, err = run_on(capsys, tmp_path, BASE, "sweep", "--steps", "12", "-o", str(fifo))
    thread.join(5)  # the reader ends at the writer's close
    if thread.is_alive() and stat.S_ISFIFO(os.stat(fifo).st_mode):  # nothing opened the FIFO: let the reader go
        try:
            os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        except OSError:  # the reader closed between the two looks: it has ended
            pass
    thread.join(10)
    assert code == 0, err
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert got and got[0].startswith(b"theta_2,") and got[0].count(b"\n") == 13


@pytest.mark.parametrize("command", [["sweep", "--steps", "12", "-o", "{tmp}/x.csv"], ["draw", "-o", "{tmp}/x.svg"],
                                     ["check", "{tmp}/a.toml", "-o", "{tmp}/x.txt"],
                                     ["handout", "--html", "{tmp}/x.html"]])
def test_new_files_follow_the_umask_and_old_files_keep_their_mode(capsys: pytest.CaptureFixture[str],
                                                                  tmp_path: Path, command: list[str]) -> None:
    (tmp_path / "a.toml").write_text("omega_3 = 1\n", encoding="utf-8")
    target = tmp_path / Path(command[-1]).name
    old = os.umask(0o077)
    try:
        code, _, err = run_on(capsys, tmp_path, BASE, *command)
    finally:
        os.umask(old)
    assert code in (0, 1), err
    assert stat.S_IMODE(target.stat().st_mode) == 0o600  # a teacher's answer key is not world-readable
    target.chmod(0o640)
    code, _, err = run_on(capsys, tmp_path, BASE, *command)
    assert code in (0, 1), err
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


@pytest.mark.skipif(sys.platform == "win32", reason="SIGTERM to a process")
@pytest.mark.parametrize("command", [["sweep", "--steps", "12", "-o"], ["draw", "-o"]])
def test_sigterm_while_writing_leaves_no_temporary_file(tmp_path: Path, command: list[str]) -> None:
    from kinepoly.cli import EXIT_TERMINATED

    (tmp_path / "s.toml").write_text(BASE, encoding="utf-8")
    target = tmp_path / ("x.csv" if command[0] == "sweep" else "x.svg")
    script = ("import os, signal, kinepoly.cli.files as f\n"
              "def killed(fd):\n    os.kill(os.getpid(), signal.SIGTERM)\n"
              "f.os.fsync = killed\nfrom kinepoly.cli import main\n"
              f"raise SystemExit(main({[command[0], str(tmp_path / 's.toml'), *command[1:], str(target)]!r}))\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, check=False)
    assert done.returncode == EXIT_TERMINATED == 128 + signal.SIGTERM, done.stderr
    assert done.stderr.strip().endswith("kinepoly: terminated") and "Traceback" not in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


# -- 4. bounded memory and time --------------------------------------------------------------------------------------

@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero")
@pytest.mark.parametrize("command", [["solve", "/dev/zero"], ["check", "{tmp}/s.toml", "/dev/zero"],
                                     ["handout", "{tmp}/s.toml", "--messages", "/dev/zero", "-o", "{tmp}/h.pdf"]])
def test_an_endless_input_is_refused_at_the_documented_size(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                            command: list[str]) -> None:
    (tmp_path / "s.toml").write_text(BASE, encoding="utf-8")
    code, _, err = run(capsys, *[a.format(tmp=tmp_path) for a in command])
    assert code == 2, err
    assert "/dev/zero: (file): longer than 8 MiB, the most kinepoly reads of a file" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_a_file_just_under_the_size_is_read(tmp_path: Path) -> None:
    from kinepoly.scene.source import MAX_INPUT_BYTES, read_text

    path = tmp_path / "s.toml"
    path.write_text(BASE + "#" * (MAX_INPUT_BYTES - len(BASE) - 1) + "\n", encoding="utf-8")
    assert read_text(str(path)).startswith(BASE)


def test_a_dotted_key_ten_thousand_deep_is_refused_in_linear_memory(capsys: pytest.CaptureFixture[str],
                                                                   tmp_path: Path) -> None:
    import tracemalloc

    from kinepoly.scene.lines import scan_lines

    text = BASE + "[draw]\n" + ".".join(["a"] * 10_000) + " = 1\n"
    tracemalloc.start()
    try:
        scan_lines(text)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 100 * len(text)  # about 1 GB before: every prefix of the key was mapped
    code, _, err = run_on(capsys, tmp_path, text, "solve")
    assert code == 2, err
    assert f"s.toml:{BASE.count(chr(10)) + 2}: draw.a.a...: a dotted key 10000 levels deep; expected at most 64" in err
    deep = BASE + "[draw]\n" + ".".join(["a"] * 64) + " = 1\n"  # as deep as allowed: an unknown key, no more
    code, _, err = run_on(capsys, tmp_path, deep, "solve")
    assert code == 2 and "draw.a: unknown key" in err, err


def test_ten_thousand_unknown_names_stop_after_the_first_problems(capsys: pytest.CaptureFixture[str],
                                                                  tmp_path: Path,
                                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    import difflib

    from kinepoly.scene.problems import SHOWN

    looked: list[str] = []
    close_matches = difflib.get_close_matches

    def counted(word: str, *args: Any, **kwargs: Any) -> list[str]:
        looked.append(word)
        return close_matches(word, *args, **kwargs)

    monkeypatch.setattr(difflib, "get_close_matches", counted)
    text = BASE + "".join(f"G{k} = [1, 2]\n" for k in range(10_000))
    code, _, err = run_on(capsys, tmp_path, text, "solve")
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == SHOWN + 1 == 21
    assert lines[0].startswith("kinepoly: error: ") and "guess.G0: no point \"G0\"" in lines[0]
    assert lines[-1] == f"{tmp_path / 's.toml'}: (file): and 9980 more problems, not shown; expected these fixed first"
    assert len(looked) == SHOWN  # a did-you-mean for the problems shown only


def _extra_points(text: str, link_line: str, count: int, spread: float) -> str:
    """``text`` with ``count`` points Q0.. added to the link written ``link_line`` (ending in " }"), within
    ``spread`` of the origin."""
    points = ", ".join(f"Q{k} = [{spread * ((k * 37) % 101) / 101:.3f}, {spread * ((k * 61) % 103) / 103:.3f}]"
                       for k in range(count))
    assert link_line in text
    return text.replace(link_line, link_line.removesuffix(" }") + ", " + points + " }")


def test_check_of_a_cam_with_points_not_asked_about_costs_per_point(capsys: pytest.CaptureFixture[str],
                                                                     tmp_path: Path,
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    from kinepoly.engine import polygon

    calls = 0
    key = polygon._key

    def counted(*args: Any) -> Any:
        nonlocal calls
        calls += 1
        return key(*args)

    monkeypatch.setattr(polygon, "_key", counted)
    (tmp_path / "a.toml").write_text("omega_3 = -4.1152\nalpha_3 = 78.32\nv_W = [90.99, 229.5]\n"
                                     "a_W = [-787.1, -4743]\nI_23 = [12.8, 5.973]\n", encoding="utf-8")
    cam = (EXAMPLES / "cam-roller-rocker.toml").read_text(encoding="utf-8")
    per_point = []
    for count in (50, 100):
        calls = 0
        code, out, err = run_on(capsys, tmp_path, _extra_points(cam, "W = [-60, 0] }", count, 60.0), "check",
                                "{tmp}/a.toml")
        assert code == 0 and "5 of 5 correct" in out, out + err
        per_point.append(calls / count)
    assert per_point[1] <= 1.2 * per_point[0], per_point  # before: each image chose among all pairs of known tips


def test_finding_the_crowded_labels_costs_what_the_labels_do(monkeypatch: pytest.MonkeyPatch) -> None:
    import math

    from kinepoly.render import labels

    measured = 0
    dist = math.dist

    def counted(a: Any, b: Any) -> float:
        nonlocal measured
        measured += 1
        return dist(a, b)

    monkeypatch.setattr(math, "dist", counted)
    per_label = []
    for count in (500, 1000):
        requests = [labels.Request("polygon", (0.0, 0.0, 200.0, 200.0), (), (100 + (k % 7) / 7, 100 + (k % 11) / 11))
                    for k in range(count)]
        measured = 0
        crowded = labels._crowd(requests)
        assert len(crowded) == count  # every one among many others
        per_label.append(measured / count)
    assert per_label[1] <= 1.1 * per_label[0], per_label  # before: each label measured to every other


def test_one_labels_search_stops_at_its_budget() -> None:
    from shapely.geometry import box

    from kinepoly.render import labels
    from kinepoly.render.text import Run

    placed = labels._Placed()
    for k in range(12_000):  # specks of other labels all round the spot: few places free, every test a look
        x, y = 40.0 + 120.0 * ((k * 0.6180339887) % 1.0), 40.0 + 120.0 * ((k * 0.7548776662) % 1.0)
        placed.append(box(x, y, x + 0.01, y + 0.01))
    placer = labels.Placer((0.0, 0.0, 200.0, 200.0), [], [], placed)
    before = placed.scanned
    items = placer.at_point((100.0, 100.0), (Run("P", 0.0, 0.0, 2.5),), role="P")
    assert items and placer.crowded == ["P"]
    assert placed.scanned - before <= labels._SEARCH_BUDGET + 500  # the last test may look beyond it a little


# -- 5. found by the fuzzer (tools/fuzz.py) --------------------------------------------------------------------------

def test_a_sweep_plot_of_values_near_the_end_of_double_precision_says_nothing_on_stderr(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = (EXAMPLES / "metu-cam.toml").read_text(encoding="utf-8").replace("center = [20, 0]", "center = [20, 1e308]")
    assert "1e308" in text
    code, _, err = run_on(capsys, tmp_path, text, "sweep", "--steps", "12", "--plot", "{tmp}/p.png")
    assert code == 0, err
    assert "Warning" not in err
    assert (tmp_path / "p.png").read_bytes().startswith(b"\x89PNG")


def test_a_sweep_plot_of_a_point_named_in_chinese_says_nothing_on_stderr(capsys: pytest.CaptureFixture[str],
                                                                         tmp_path: Path) -> None:
    text = _renamed(BASE, "B", "中")
    code, _, err = run_on(capsys, tmp_path, text, "sweep", "--steps", "12", "--plot", "{tmp}/p.png")
    assert code == 0, err
    assert "Warning" not in err and "Glyph" not in err
