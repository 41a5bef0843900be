"""The command line, in-process: exit codes, messages, no tracebacks, the JSON contract's shape."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES, four_bar, slider_crank

import kinepoly

FOUR_BAR = (EXAMPLES / "four-bar.toml").read_text()


def write(tmp_path: Path, text: str | bytes, name: str = "scene.toml") -> str:
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    return str(path)


BAD_SCENES: list[tuple[str, str | bytes, int, str]] = [
    ("syntax", "title = \n[links", 2, "TOML syntax error"),
    ("unknown key", FOUR_BAR.replace("omega = 10", "omgea = 10"), 2, 'did you mean "omega"'),
    ("wrong type", FOUR_BAR.replace("angle = 60", 'angle = "sixty"'), 2, "input.angle"),
    ("nan", FOUR_BAR.replace("omega = 10", "omega = nan"), 2, "input.omega"),
    ("inf", FOUR_BAR.replace("alpha = 5", "alpha = inf"), 2, "input.alpha"),
    ("missing input", FOUR_BAR.split("[input]")[0], 2, "input"),
    ("unknown link", FOUR_BAR.replace('link = "2"', 'link = "9"'), 2, "input.link"),
    ("unknown point", FOUR_BAR.replace('velocity = ["A", "B", "C"]', 'velocity = ["A", "Q"]'), 2, "find.velocity"),
    ("compound hinge over-constrains", FOUR_BAR.replace("4 = { points = { B0 = [0, 0], B = [80, 0] } }",
                                                        "4 = { points = { B0 = [0, 0], B = [80, 0], A = [5, 5] } }"),
     2, "pin A joins links 2, 3, 4: 2 joints"),
    ("zero-length link", FOUR_BAR.replace("A = [40, 0]", "A = [0, 0]"), 2, "links.2"),
    ("wrong mobility", FOUR_BAR.replace("4 = { points = { B0 = [0, 0], B = [80, 0] } }",
                                        "4 = { points = { B0 = [0, 0], B = [80, 0], A0 = [9, 9] } }"), 2, ""),
    ("mobility two", FOUR_BAR.replace("[input]", '5 = { points = { B0 = [0, 0] } }\n[input]').replace(
        "1 = { points = { A0 = [0, 0], B0 = [100, 0] } }", "1 = { points = { A0 = [0, 0] } }"), 2, ""),
    ("cannot assemble", four_bar(100, 40, 20, 20, 60, 10, 0, guess_b=(110, 80)), 3, ">"),
    ("empty file", "", 2, "empty"),
    ("binary garbage", b"\x00\x01\x02\xff\xfe garbage", 2, ""),
    ("not utf-8", b"title = \"\xff\xfe\"\n", 2, ""),
    ("dead point", slider_crank(40, 120, 0, 0, 10, 0).split("[input]")[0]
     + '[input]\nslider = "14"\ns = 160\ns_dot = 100\n', 3, "singular"),
    ("change point", four_bar(10, 10, 10, 10, 0, 1, 0, guess_b=(10, 20)), 3, "the pins A and B0 coincide"),
    ("change point, denormal input", four_bar(10, 10, 10, 10, 2.2250738585e-313, 1, 0, guess_b=(10, 20)), 3,
     "coincide"),
    ("non-rigid given", (EXAMPLES / "image-point.toml").read_text().replace("velocity = [0, -100]",
                                                                             "velocity = [5, -100]"), 2, "rigid"),
    ("negative kv", FOUR_BAR + "\n[draw]\nkv = -1\n", 2, "draw.kv"),
]


@pytest.mark.parametrize("name, text, code, fragment", BAD_SCENES, ids=[b[0] for b in BAD_SCENES])
def test_bad_input_gets_a_clear_message_and_its_exit_code(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                           name: str, text: str | bytes, code: int,
                                                           fragment: str) -> None:
    path = write(tmp_path, text)
    got, out, err = run(capsys, "solve", path)
    assert got == code, err
    assert out == ""
    assert "Traceback" not in err
    assert err.startswith("kinepoly: error: ")
    assert fragment in err
    if code == 2 and name not in {"wrong mobility", "mobility two", "non-rigid given",
                                  "compound hinge over-constrains"}:
        assert f"{path}:" in err  # FILE:LINE: names the file


def test_cannot_assemble_names_group_joint_and_inequality(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, _, err = run(capsys, "solve", write(tmp_path, four_bar(100, 40, 20, 20, 60, 10, 0, guess_b=(110, 80))))
    assert code == 3
    assert "joint B of group 3-4 (RRR)" in err and "theta12 = 60 deg" in err
    assert "> |AB| + |BB0| = 20 + 20 = 40" in err


def test_missing_file_and_bad_command(capsys: pytest.CaptureFixture[str]) -> None:
    assert run(capsys, "solve", "/no/such/scene.toml")[0] == 2
    assert run(capsys, "frobnicate")[0] == 2
    assert run(capsys)[0] == 2


def test_the_console_script_and_module_run_without_traceback(tmp_path: Path) -> None:
    run_ = subprocess.run([sys.executable, "-m", "kinepoly", "solve", str(EXAMPLES / "four-bar.toml")],
                          capture_output=True, text=True, check=False)
    assert run_.returncode == 0
    assert "cross-check against the analytic solution" in run_.stdout


def test_json_follows_the_contract(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "solve", str(EXAMPLES / "slider-crank.toml"), "--json")
    assert code == 0
    data = json.loads(out)
    assert set(data["links"]) == {"3"} and set(data["links"]["3"]) == {"angle", "omega", "alpha"}
    assert set(data["points"]) == {"A", "B", "C"}
    assert data["polygons"]["velocity"]["scale"] == 0.1 and data["polygons"]["acceleration"]["scale"] == 0.01
    for kind in ("velocity", "acceleration"):
        k = data["polygons"][kind]["scale"]
        assert data["polygons"][kind]["points"]["o"] == [0.0, 0.0]
        for name in ("A", "B", "C"):
            tip = data["polygons"][kind]["points"][name.lower()]
            vec = data["points"][name][kind]
            assert math.hypot(tip[0] - k * vec[0], tip[1] - k * vec[1]) <= 1e-12 * (1 + math.hypot(*tip))
    assert data["check"]["reference"] == "analytic" and data["check"]["max_rel_error"] <= 1e-12
    assert data["timing"]["total_s"] > 0
    assert "instant_centers" not in data and "sliders" not in data
    assert {s["polygon"] for s in data["steps"]} == {"velocity", "acceleration"}
    assert -180 < data["links"]["3"]["angle"] <= 180


def test_velocity_only_scene_has_no_acceleration_anywhere(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = four_bar(100, 40, 120, 80, 60, 10, 5, guess_b=(110, 80), find='[find]\nvelocity = ["C"]\nomega = ["4"]')
    code, out, _ = run(capsys, "solve", write(tmp_path, text), "--json")
    data = json.loads(out)
    assert code == 0
    assert "acceleration" not in data["polygons"]
    assert all(step["polygon"] == "velocity" for step in data["steps"])
    assert set(data["points"]) == {"C"} and set(data["points"]["C"]) == {"position", "velocity"}
    assert set(data["links"]["4"]) == {"angle", "omega"}


def test_only_the_groups_on_the_path_are_solved() -> None:
    # the shaper asks only for omega of the lever: the ram's group is left out entirely
    text = (EXAMPLES / "shaper.toml").read_text().split("[find]")[0] + '[find]\nomega = ["4"]\n'
    solution = kinepoly.solve(kinepoly.loads_scene(text))
    assert solution.plan.describe() == ["input: link(s) 2", "group 3-4 (RPR)"]
    assert set(solution.pose.links) == {"1", "2", "3", "4"}
    assert not any(step.kind == "coriolis" for step in solution.steps)


def test_no_coriolis_where_no_block_slides_on_a_turning_guide() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "slider-crank.toml"))
    assert not any(step.kind == "coriolis" for step in solution.steps)
    shaper = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "shaper.toml"))
    assert sum(step.kind == "coriolis" for step in shaper.steps) == 1  # block 3 on lever 4, not ram 6 on the frame


def test_default_assembly_is_taken_and_named_without_a_guess(capsys: pytest.CaptureFixture[str],
                                                             tmp_path: Path) -> None:
    text = FOUR_BAR.replace("[guess]\nB = [110, 80]", "")
    code, out, _ = run(capsys, "solve", write(tmp_path, text), "--json")
    data = json.loads(out)
    assert code == 0
    [warning] = data["warnings"]
    assert warning["code"] == "default-assembly" and "[guess] B = " in warning["message"]
    flipped = json.loads(run(capsys, "solve", write(tmp_path, text + "\n[guess]\nB = [70, -74]\n", "b.toml"),
                             "--json")[1])
    assert flipped["points"]["B"]["position"][1] < 0 < data["points"]["B"]["position"][1]
    assert flipped["warnings"] == []


def test_steps_and_table(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "solve", str(EXAMPLES / "slotted-lever.toml"), "--steps")
    assert code == 0 and "[acceleration, coriolis] a^c_A@4/A = 2 omega x v_A@4/A" in out
    code, out, _ = run(capsys, "solve", str(EXAMPLES / "four-bar.toml"))
    assert code == 0 and "max relative error" in out and "run time" in out


def test_public_api_all_is_sorted_and_importable() -> None:
    assert kinepoly.__all__ == sorted(kinepoly.__all__)
    for name in kinepoly.__all__:
        assert getattr(kinepoly, name) is not None
    solution = kinepoly.solve(kinepoly.loads_scene(FOUR_BAR))
    assert kinepoly.to_json(solution)["links"]["3"]["omega"] == pytest.approx(-0.3955515802631714, rel=1e-12)


@pytest.mark.parametrize("omega, alpha", [(1e-200, 0.0), (0.0, 1e-300), (1e-150, 1e-300)])
def test_vanishing_speeds_solve_without_underflow(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                  omega: float, alpha: float) -> None:
    code, out, err = run(capsys, "solve", write(tmp_path, four_bar(100, 40, 120, 80, 60, omega, alpha,
                                                                    guess_b=(110, 80))), "--json")
    assert code == 0, err
    data = json.loads(out)
    # every result scales with the input speed: omega13 / omega12 is the four-bar's velocity ratio
    if omega:
        assert data["links"]["3"]["omega"] / omega == pytest.approx(-0.03955515802631714, rel=1e-9)
    assert data["check"]["max_rel_error"] <= 1e-12
