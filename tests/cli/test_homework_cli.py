"""kinepoly check on the command line: exit codes, the JSON object, the table, the class report, no tracebacks."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES, four_bar

import kinepoly

SLOTTED = str(EXAMPLES / "slotted-lever.toml")
RIGHT = """student = "Ana Pop"
omega_4 = "1.28 ccw"
alpha_4 = 42.6
v_A = [-346.4, 200]
"v_A@4" = [-44.4, -76.8]
a_A = { magnitude = 4000, angle = 240 }
"a_A@4" = [-1377, -2612]
"""


def write(folder: Path, name: str, text: str) -> str:
    path = folder / name
    path.write_text(text)
    return str(path)


def test_all_correct_exits_0_and_the_readme_example_is_all_correct(capsys: pytest.CaptureFixture[str],
                                                                    tmp_path: Path) -> None:
    code, out, err = run(capsys, "check", SLOTTED, write(tmp_path, "ana.toml", RIGHT))
    assert code == 0, out + err
    assert "6 of 6 correct, score 1.00" in out and "(Ana Pop)" in out
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    block = readme[readme.index("An answers file is TOML"):]
    block = block[block.index("```toml") + 7:]
    block = block[: block.index("```")]
    code, out, err = run(capsys, "check", SLOTTED, write(tmp_path, "readme.toml", block))
    assert code == 0, out + err


def test_a_wrong_answer_exits_1_with_its_diagnosis_in_json(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    answers = RIGHT.replace("alpha_4 = 42.6", "alpha_4 = -42.6")
    code, out, _ = run(capsys, "check", SLOTTED, write(tmp_path, "bob.toml", answers), "--json")
    assert code == 1
    data = json.loads(out)
    assert data["score"] == pytest.approx(5 / 6) and data["correct"] == 5 and data["total"] == 6
    assert set(data["answers"]) == {"omega_4", "alpha_4", "v_A", "v_A@4", "a_A", "a_A@4"}
    for entry in data["answers"].values():
        assert set(entry) == {"verdict", "expected", "given", "error", "diagnosis"}
    wrong = data["answers"]["alpha_4"]
    assert wrong["verdict"] == "wrong" and wrong["given"] == -42.6
    assert wrong["expected"] == pytest.approx(42.587, abs=1e-3)
    assert wrong["diagnosis"]["code"] == "sign-reversed"
    assert wrong["error"]["relative"] == pytest.approx(2.0, rel=1e-3)
    right = data["answers"]["v_A"]
    assert right["verdict"] == "correct" and right["diagnosis"] is None and len(right["expected"]) == 2
    code, out, _ = run(capsys, "check", SLOTTED, str(tmp_path / "bob.toml"))
    assert code == 1 and "alpha_4: the sense reversed (cw for ccw) [sign-reversed" in out


def test_a_bad_answers_file_exits_2_with_file_line_key(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = write(tmp_path, "bad.toml", RIGHT + "omega_9 = 3\n")
    code, out, err = run(capsys, "check", SLOTTED, path)
    assert code == 2 and out == "" and "Traceback" not in err
    assert f"{path}:8: omega_9: no link" in err
    assert run(capsys, "check", SLOTTED, str(tmp_path / "none.toml"))[0] == 2
    assert run(capsys, "check", SLOTTED)[0] == 2  # usage


def test_a_scene_that_cannot_assemble_exits_3(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    scene = write(tmp_path, "s.toml", four_bar(100, 40, 20, 20, 60, 10, 0, guess_b=(110, 80)))
    code, _, err = run(capsys, "check", scene, write(tmp_path, "a.toml", "omega_3 = 1\n"))
    assert code == 3 and "cannot" in err


def test_output_to_a_file(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    target = tmp_path / "report.json"
    code, out, _ = run(capsys, "check", SLOTTED, write(tmp_path, "ana.toml", RIGHT), "--json", "-o", str(target))
    assert code == 0 and out == ""
    assert json.loads(target.read_text())["score"] == 1.0
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []  # no temporary left behind
    code, _, err = run(capsys, "check", SLOTTED, str(tmp_path / "ana.toml"), "-o", str(tmp_path / "no" / "r.txt"))
    assert code == 2 and "cannot be written" in err


def test_a_folder_gives_a_class_report(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    folder = tmp_path / "class"
    folder.mkdir()
    write(folder, "ana.toml", RIGHT)
    write(folder, "bob.toml", RIGHT.replace('student = "Ana Pop"', 'student = "Bob"').replace(
        '"v_A@4" = [-44.4, -76.8]', '"v_A@4" = [-346.4, 200]').replace('"a_A@4" = [-1377, -2612]\n', ""))
    write(folder, "notes.txt", "not an answers file")
    code, out, err = run(capsys, "check", SLOTTED, str(folder))
    assert code == 1, err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [r["file"] for r in rows] == ["ana.toml", "bob.toml"]
    ana, bob = rows
    assert ana["student"] == "Ana Pop" and ana["score"] == "1.000" and ana["problems"] == ""
    assert bob["v_A@4"] == "wrong: other-point" and bob["a_A@4"] == "missing" and bob["omega_4"] == "correct"
    assert (bob["correct"], bob["total"]) == ("4", "6")

    write(folder, "cara.toml", "omega_4 = [1]\n")
    code, out, err = run(capsys, "check", SLOTTED, str(folder))
    assert code == 2
    cara = list(csv.DictReader(io.StringIO(out)))[2]
    assert cara["file"] == "cara.toml" and cara["score"] == "" and "omega_4" in cara["problems"]
    assert f"{folder / 'cara.toml'}:1: omega_4" in err

    code, out, _ = run(capsys, "check", SLOTTED, str(folder), "--json")
    files = json.loads(out)["files"]
    assert files["ana.toml"]["score"] == 1.0 and "problems" in files["cara.toml"]
    empty = tmp_path / "empty"
    empty.mkdir()
    code, _, err = run(capsys, "check", SLOTTED, str(empty))
    assert code == 2 and "no .toml answers files" in err


def test_the_class_is_solved_once(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str],
                                  tmp_path: Path) -> None:
    from kinepoly.homework import reference

    calls = []
    real = reference.solve

    def counting(scene: kinepoly.Scene) -> kinepoly.Solution:
        calls.append(scene)
        return real(scene)

    monkeypatch.setattr(reference, "solve", counting)
    for k in range(6):
        write(tmp_path, f"s{k}.toml", RIGHT)
    assert run(capsys, "check", SLOTTED, str(tmp_path))[0] == 0
    assert len(calls) <= 3  # the scene, the scene asking everything, the input angle in radians


def test_the_package_exports_its_functions_even_after_its_modules_are_imported() -> None:
    from kinepoly import homework
    from kinepoly.homework import checking

    assert homework.check is checking.check and callable(homework.make_variants)
    assert homework.__all__ == sorted(homework.__all__)
    with pytest.raises(AttributeError):
        homework.no_such_name  # noqa: B018
