"""``kinepoly draw``: formats by extension, a folder gets all four, steps, bad paths exit 2, whole files only."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES

import kinepoly

FOUR_BAR = str(EXAMPLES / "four-bar.toml")


@pytest.mark.parametrize("ext, magic", [("svg", b"<?xml"), ("dxf", b"  0\nSECTION"), ("png", b"\x89PNG"),
                                        ("pdf", b"%PDF")])
def test_the_format_follows_the_extension(capsys: pytest.CaptureFixture[str], tmp_path: Path, ext: str,
                                          magic: bytes) -> None:
    target = tmp_path / f"drawing.{ext}"
    code, out, err = run(capsys, "draw", FOUR_BAR, "-o", str(target))
    assert code == 0, err
    assert target.read_bytes().startswith(magic)
    assert f"wrote {target}" in out
    assert [p.name for p in tmp_path.iterdir()] == [target.name]  # no temporary file left behind


def test_a_folder_gets_all_four_and_steps_one_svg_per_step(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, _, err = run(capsys, "draw", FOUR_BAR, "-o", f"{tmp_path}/out/", "--steps", str(tmp_path / "steps"))
    assert code == 0, err
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [f"four-bar.{e}"
                                                                    for e in ("dxf", "pdf", "png", "svg")]
    steps = sorted((tmp_path / "steps").iterdir())
    solution = kinepoly.solve(kinepoly.load_scene(FOUR_BAR))
    assert [p.name for p in steps] == [f"step-{n:02d}.svg" for n in range(1, len(solution.steps) + 1)]
    assert f"Step 3 of {len(solution.steps)}" in steps[2].read_text()


BAD = [
    ("unknown extension", ["-o", "{tmp}/drawing.jpg"], "unknown drawing format"),
    ("no extension", ["-o", "{tmp}/drawing"], "unknown drawing format"),
    ("missing folder", ["-o", "{tmp}/no/such/folder/drawing.svg"], "does not exist"),
    ("folder is a file", ["-o", "{tmp}/file.txt/"], "cannot create the folder"),
    ("steps folder is a file", ["--steps", "{tmp}/file.txt/steps"], "cannot create the folder"),
    ("nothing to write", [], "nothing to write"),
    ("bad paper", ["-o", "{tmp}/d.svg", "--paper", "B7"], "--paper B7"),
    ("bad dpi", ["-o", "{tmp}/d.png", "--dpi", "0"], "--dpi"),
]


@pytest.mark.parametrize("name, args, fragment", BAD, ids=[b[0] for b in BAD])
def test_a_bad_output_is_a_clear_message_and_exit_2(capsys: pytest.CaptureFixture[str], tmp_path: Path, name: str,
                                                     args: list[str], fragment: str) -> None:
    (tmp_path / "file.txt").write_text("x")
    code, _, err = run(capsys, "draw", FOUR_BAR, *[a.format(tmp=tmp_path) for a in args])
    assert code == 2
    assert err.startswith("kinepoly: error: ") and fragment in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file.txt"]


def test_a_bad_scene_is_exit_2_and_writes_nothing(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    scene = tmp_path / "bad.toml"
    scene.write_text("title = \n[links")
    code, _, err = run(capsys, "draw", str(scene), "-o", str(tmp_path / "d.svg"))
    assert code == 2 and f"{scene}:" in err
    assert not (tmp_path / "d.svg").exists()


def test_a_failure_while_writing_leaves_the_old_file_and_no_part(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    from kinepoly.render import mpl

    target = tmp_path / "drawing.png"
    target.write_bytes(b"old")

    def half_then_fail(sheet: object, stream: object, dpi: int = 150) -> None:
        stream.write(b"\x89PNG half")  # type: ignore[attr-defined]
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(mpl, "write_png", half_then_fail)
    code, _, err = run(capsys, "draw", FOUR_BAR, "-o", str(target))
    assert code == 2 and "No space left on device" in err
    assert target.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["drawing.png"]


def test_solve_does_not_import_the_drawing_libraries() -> None:
    code = (f"import sys, kinepoly.cli as c; c.main(['solve', {FOUR_BAR!r}]); "
            "print(sorted(m for m in ('matplotlib', 'ezdxf', 'svgwrite', 'shapely') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "[]"
