"""kinepoly animate and kinepoly.animate: frames are the sweep's rows at fixed scales, every format, errors."""

from __future__ import annotations

import io
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.cli import main
from kinepoly.motion.frames import PARTS, make_frames
from kinepoly.motion.video import FFMPEG_MISSING
from kinepoly.scene.loader import load_scene, loads_scene
from kinepoly.sweep.run import prepare_sweep, run_sweep


def _frames(name: str, positions: int, **options: float):  # type: ignore[no-untyped-def]
    prepared = prepare_sweep(load_scene(str(EXAMPLES / f"{name}.toml")))
    result = run_sweep(prepared, steps=positions, **options)
    return result, make_frames(result, prepared, PARTS)


@pytest.mark.parametrize("name", ["four-bar", "slotted-lever", "slider-crank"])
def test_frame_k_tips_are_row_k_of_the_sweep_at_the_scale(name: str) -> None:
    result, frames = _frames(name, 90)
    assert frames.count == result.rows == 90 and frames.skipped == ()
    for poly in (frames.velocity, frames.acceleration):
        assert poly is not None
        prefix = "v" if poly.kind == "velocity" else "a"
        checked = 0
        for j, label in enumerate(poly.labels):
            try:
                x, y = result.column(f"{prefix}_{label}_x"), result.column(f"{prefix}_{label}_y")
            except KeyError:
                continue
            for k, row in enumerate(frames.rows):
                if poly.valid[k]:
                    want = complex(x.values[row], y.values[row]) * poly.scale
                    assert abs(poly.tips[k, j] - want) <= 1e-9
                    checked += 1
        assert checked >= 90
        # one scale for the cycle, and the largest polygon fits its panel around its centre
        assert np.abs(poly.tips[poly.valid] - poly.center).max() <= 45.0


def test_the_mechanism_is_the_sweeps_positions() -> None:
    result, frames = _frames("four-bar", 36)
    assert result.positions is not None
    crank = next(link for link in frames.links if link.name == "2")
    a = crank.points.index("A")
    assert np.allclose(crank.xy[:, a], result.positions.point("A")[np.flatnonzero(result.shown)], atol=1e-12)
    path = next(t for t in frames.paths if t.name == "C")
    assert np.allclose(path.xy.real, result.column("r_C_x").values) and frames.centers


def test_a_gif_of_n_positions_has_n_frames(tmp_path: Path) -> None:
    target = tmp_path / "four-bar.gif"
    assert main(["animate", str(EXAMPLES / "four-bar.toml"), "-o", str(target), "--positions", "24",
                 "--fps", "12", "--parts", "mechanism", "velocity", "acceleration", "centers", "paths",
                 "functions"]) == 0
    with Image.open(target) as image:
        assert image.format == "GIF" and image.n_frames == 24
    assert [p.name for p in tmp_path.iterdir()] == ["four-bar.gif"]  # no temporary file left


_CRANK_ROCKER_TOO_LONG = """
title = "A crank too long: the four-bar closes only part of the turn"
[links]
1 = { points = { A0 = [0, 0], B0 = [100, 0] } }
2 = { points = { A0 = [0, 0], A = [70, 0] } }
3 = { points = { A = [0, 0], B = [60, 0] } }
4 = { points = { B0 = [0, 0], B = [50, 0] } }
[input]
link = "2"
angle = 60
omega = 10
alpha = 0
[guess]
B = [90, 50]
[find]
velocity = ["B"]
omega = ["3", "4"]
"""


def test_unreachable_positions_are_skipped_and_reported(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    scene = tmp_path / "short.toml"
    scene.write_text(_CRANK_ROCKER_TOO_LONG)
    prepared = prepare_sweep(loads_scene(_CRANK_ROCKER_TOO_LONG))
    result = run_sweep(prepared, steps=36, start=0.0, stop=350.0)
    frames = make_frames(result, prepared)
    unreachable = [int(r) for r in np.flatnonzero(result.status == 3)]
    assert unreachable and list(frames.skipped) == unreachable
    assert result.rows == 37  # 36 equal intervals from 0 to 350, both ends
    assert frames.count == result.rows - len(unreachable) and not set(frames.rows) & set(unreachable)
    target = tmp_path / "short.gif"
    assert main(["animate", str(scene), "-o", str(target), "--positions", "36", "--from", "0", "--to", "350"]) == 0
    err = capsys.readouterr().err
    assert f"{len(unreachable)} of {result.rows} positions cannot be reached and are skipped" in err
    with Image.open(target) as image:
        assert image.n_frames == frames.count


@pytest.mark.parametrize("argv", [
    ["-o", "{tmp}/x.avi"],
    ["-o", "{tmp}/x.gif", "--positions", "1"],
    ["-o", "{tmp}/x.gif", "--fps", "0"],
    ["-o", "{tmp}/x.gif", "--parts", "mechanism", "wheels"],
    ["-o", "{tmp}/x.gif", "--from", "10"],
    ["-o", "{tmp}/no/such/folder/x.gif"],
    ["-o", "{tmp}/x.gif", "--positions", "many"],
])
def test_bad_options_exit_2(argv: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    args = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(["animate", str(EXAMPLES / "four-bar.toml"), *args]) == 2
    err = capsys.readouterr().err
    assert "kinepoly: error:" in err and "Traceback" not in err
    assert not any(tmp_path.iterdir())


def test_a_scene_that_cannot_assemble_exits_3(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    scene = tmp_path / "apart.toml"
    scene.write_text(_CRANK_ROCKER_TOO_LONG.replace("angle = 60", "angle = 180"))
    assert main(["animate", str(scene), "-o", str(tmp_path / "x.gif")]) == 3
    assert "Traceback" not in capsys.readouterr().err


def test_mp4_without_ffmpeg_names_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                     capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(shutil, "which", lambda name, *a, **k: None)
    assert main(["animate", str(EXAMPLES / "four-bar.toml"), "-o", str(tmp_path / "x.mp4")]) == 2
    err = capsys.readouterr().err
    assert FFMPEG_MISSING in err and "apt-get install ffmpeg" in err
    assert not any(tmp_path.iterdir())


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="ffmpeg is not installed")
def test_mp4_with_ffmpeg(tmp_path: Path) -> None:
    target = tmp_path / "x.mp4"
    assert main(["animate", str(EXAMPLES / "four-bar.toml"), "-o", str(target), "--positions", "12"]) == 0
    assert target.read_bytes()[4:8] == b"ftyp"


def test_mp4_pipes_the_frames_to_ffmpeg(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """With a stand-in ffmpeg (a script that counts the frames it is given), the frames reach it."""
    fake = tmp_path / "ffmpeg"
    fake.write_text("#!/bin/sh\nfor last; do :; done\nwc -c > \"$last\"\n")
    fake.chmod(0o755)
    monkeypatch.setattr(shutil, "which", lambda name, *a, **k: str(fake) if name == "ffmpeg" else None)
    made = kinepoly.animate(EXAMPLES / "four-bar.toml", tmp_path / "x.mp4", positions=6)
    width, height = 1600, 900  # a frame a projector shows: the sheet of 10 x 5.625 inches at 160 dpi
    assert made.format == "mp4" and int(made.data) % 6 == 0 and int(made.data) // 6 >= width * height


def test_the_python_api_is_the_command(tmp_path: Path) -> None:
    made = kinepoly.animate(str(EXAMPLES / "slotted-lever.toml"), tmp_path / "lever.html", positions=10)
    assert made.frames.count == 10 and (tmp_path / "lever.html").read_bytes() == made.data
    gif = kinepoly.animate(load_scene(str(EXAMPLES / "slider-crank.toml")), positions=8)
    assert gif.format == "gif" and Image.open(io.BytesIO(gif.data)).n_frames == 8
    assert gif._repr_html_().startswith('<img src="data:image/gif;base64,')


def test_draw_gives_the_sheet_or_one_part() -> None:
    solution = kinepoly.solve(load_scene(str(EXAMPLES / "slotted-lever.toml")))
    whole = kinepoly.draw(solution)
    assert whole == solution._repr_svg_() and 'id="velocity-polygon"' in whole
    part = kinepoly.draw(solution, part="velocity-polygon")
    assert part.lstrip().startswith("<?xml") and 'viewBox="0 0 ' not in part
    groups = dict(re.findall(r'<g [^>]*id="([a-z-]+)"[^>]*?(/?)>', part))
    assert groups["velocity-polygon"] == "" and groups["mechanism"] == "/"  # only the part asked has items
    with pytest.raises(kinepoly.SceneError, match="expected one of"):
        kinepoly.draw(solution, part="wheels")
    with pytest.raises(kinepoly.SceneError, match="has none"):
        kinepoly.draw(solution, part="instant-centers")


def test_a_sweep_shows_as_its_plots() -> None:
    from kinepoly.sweep.run import sweep

    assert sweep(load_scene(str(EXAMPLES / "four-bar.toml")), steps=12)._repr_png_().startswith(b"\x89PNG")


def test_singular_rows_keep_the_mechanism_and_leave_the_polygons_out() -> None:
    """A rocker's whole swing ends at its dead points: those frames are drawn, without polygons."""
    prepared = prepare_sweep(loads_scene(_CRANK_ROCKER_TOO_LONG))
    result = run_sweep(prepared, steps=40)
    frames = make_frames(result, prepared)
    singular = result.status == 2
    assert singular.any() and frames.count == result.rows == 41 and frames.skipped == ()  # 40 intervals
    assert frames.velocity is not None
    assert list(frames.velocity.valid) == list(~singular)
    assert np.isfinite(frames.velocity.tips).all() and np.abs(frames.velocity.tips - frames.velocity.center).max() <= 45


def test_the_scale_fits_the_ok_frames_and_near_singular_ones_beyond_it_are_left_out() -> None:
    """kc0-six-bar's two end rows sit a hair inside dead points, with rates a thousand times the rest: kv and ka
    are the round scales that fit the ok frames (as ``fitting_scale`` of their largest reach), and the end
    frames, whose polygons would run off the panel, keep the mechanism and leave their polygons out."""
    from kinepoly.motion.frames import fitting_scale

    result, frames = _frames("kc0-six-bar", 24)
    ok = result.status == 0
    assert list(np.flatnonzero(~ok)) == [0, result.rows - 1] and frames.count == result.rows
    for poly in (frames.velocity, frames.acceleration):
        assert poly is not None
        prefix = "v" if poly.kind == "velocity" else "a"
        tips = np.stack([result.column(f"{prefix}_{p}_x").values + 1j * result.column(f"{prefix}_{p}_y").values
                         for p in "BDH"], axis=1)
        inside = np.append(tips[ok].ravel(), 0j)
        reach = 0.5 * max(np.ptp(inside.real), np.ptp(inside.imag))
        assert poly.scale <= fitting_scale(reach)  # the other tips of the polygon may reach further
        assert np.abs(tips[~ok]).max() * poly.scale > 45.0  # the end frames would leave the panel
        assert list(poly.valid) == list(ok)
        # the largest ok polygon fills its panel to within the round scale's step (at most 2.5 times)
        assert 45.0 / 2.5 - 6.0 < np.abs(poly.tips[poly.valid] - poly.center).max() <= 45.0
    chosen, window = frames.functions()  # the functions panel: a window on the ok rows, the ends run off it
    assert [v.name for v in chosen] == ["omega_1", "omega_2", "omega_3", "omega_4"] and window is not None
    rates = np.concatenate([v.values for v in chosen])
    inside = np.concatenate([v.values[ok] for v in chosen])
    assert window[0] <= inside.min() and inside.max() <= window[1] and np.abs(rates).max() > 5 * max(np.abs(window))
    assert _frames("four-bar", 36)[1].functions()[1] is None  # nothing runs off: the whole range
