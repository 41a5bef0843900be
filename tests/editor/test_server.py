"""The editor's JSON API over HTTP and its websocket: the answers are the command line's, and the guards hold."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import httpx
import pytest
from tests.cli_support import run
from tests.editor.conftest import EXAMPLES
from tests.editor.server import Served
from websockets.exceptions import InvalidStatus
from websockets.sync.client import connect

from kinepoly.editor import TEMPLATES
from kinepoly.editor.document import template_text


def _without_timing(result: dict[str, object]) -> dict[str, object]:
    return {k: v for k, v in result.items() if k != "timing"}


def _solve_json(capsys: pytest.CaptureFixture[str], path: Path) -> dict[str, object]:
    code, out, err = run(capsys, "solve", str(path), "--json")
    assert code == 0, err
    return _without_timing(json.loads(out))


def test_replace_answers_the_solve_json_of_that_text(served: Served, four_bar: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    text = (four_bar.read_text(encoding="utf-8").replace("angle = 60", "angle = 137.5")
            .replace("omega = 10", "omega = -7"))
    answer = httpx.put(served.url + "api/scene", json={"text": text})
    assert answer.status_code == 200
    four_bar.write_text(text, encoding="utf-8")  # the same text where the command line reads it
    assert _without_timing(answer.json()) == _solve_json(capsys, four_bar)
    assert httpx.get(served.url + "api/scene").json()["text"] == text
    assert _without_timing(httpx.get(served.url + "api/solution").json()) == _solve_json(capsys, four_bar)


@pytest.mark.parametrize(("change", "exit_code"), [
    (lambda t: t.replace("angle = 60", "angle = 60\nangle = 61"), 2),               # a TOML error
    (lambda t: t.replace('link = "2"', 'link = "9"'), 2),                            # a scene error
    (lambda t: t.replace("B0 = [100, 0]", "B0 = [400, 0]"), 3),                       # cannot assemble
    (lambda t: t.replace('link = "2"', 'link = "9"').replace("omega = 10", 'omega = "ten"'), 2),  # two problems
])
def test_a_wrong_scene_is_answered_with_the_cli_messages(served: Served, four_bar: Path, change: object,
                                                         exit_code: int, capsys: pytest.CaptureFixture[str]) -> None:
    assert callable(change)
    text = change(four_bar.read_text(encoding="utf-8"))
    answer = httpx.put(served.url + "api/scene", json={"text": text})
    assert answer.status_code == 422
    four_bar.write_text(text, encoding="utf-8")
    code, _, err = run(capsys, "solve", str(four_bar), "--json")
    assert (answer.json()["exit"], code) == (exit_code, exit_code)
    assert "\n".join(answer.json()["errors"]) == err.rstrip("\n")
    assert str(four_bar) in err or exit_code == 3


def test_the_token_is_required_on_every_request_and_the_websocket(served: Served) -> None:
    base = f"http://127.0.0.1:{served.port}/"
    for path in ("", "api/scene", "static/editor.js", "api/drawing.svg", "x" + served.token + "/api/scene",
                 served.token[:-1] + "/api/scene"):
        assert httpx.get(base + path).status_code == 403, path
    assert httpx.put(base + "api/scene", json={"text": ""}).status_code == 403
    assert httpx.get(served.url + "api/scene").status_code == 200
    with pytest.raises(InvalidStatus):
        connect(f"ws://127.0.0.1:{served.port}/ws")
    with pytest.raises(InvalidStatus):
        connect(f"ws://127.0.0.1:{served.port}/{served.token}x/ws")


def test_another_host_or_origin_is_refused(served: Served) -> None:
    api = served.url + "api/scene"
    for host in ("evil.example", f"evil.example:{served.port}", "127.0.0.1", f"127.0.0.2:{served.port}"):
        assert httpx.get(api, headers={"Host": host}).status_code == 403, host
    assert httpx.get(api, headers={"Host": f"localhost:{served.port}"}).status_code == 200
    text = httpx.get(api).json()["text"]
    assert httpx.put(api, json={"text": text}, headers={"Origin": "http://evil.example"}).status_code == 403
    assert httpx.put(api, json={"text": text}, headers={"Sec-Fetch-Site": "cross-site"}).status_code == 403
    assert httpx.put(api, json={"text": text}, headers={"Origin": f"http://127.0.0.1:{served.port}"}).status_code == 200
    assert httpx.put(api, content=json.dumps({"text": text}), headers={"Content-Type": "text/plain"}).status_code == 400
    for headers in ({"Origin": "http://evil.example"}, {"Host": "evil.example"}):
        with pytest.raises(InvalidStatus):
            connect(f"ws://127.0.0.1:{served.port}/{served.token}/ws", additional_headers=headers,
                    origin=headers.get("Origin"))  # type: ignore[arg-type]


def _live(served: Served, *messages: dict[str, object]) -> list[dict[str, object]]:
    with connect(f"ws://127.0.0.1:{served.port}/{served.token}/ws") as socket:
        replies = []
        for seq, message in enumerate(messages):
            socket.send(json.dumps({**message, "seq": seq}))
            reply = json.loads(socket.recv())
            assert reply["seq"] == seq
            replies.append(reply)
    return replies


def test_edits_over_the_websocket_save_a_file_that_solves_to_what_was_shown(
        served: Served, four_bar: Path, capsys: pytest.CaptureFixture[str]) -> None:
    before = four_bar.read_text(encoding="utf-8")
    replies = _live(served,
                    {"op": "edit", "edit": {"op": "drive", "to": [-20, 30]}},
                    {"op": "edit", "edit": {"op": "drive", "to": [-30, 10]}, "merge": True},
                    {"op": "edit", "edit": {"op": "move-point", "point": "B0", "to": [95, -10]}},
                    {"op": "edit", "edit": {"op": "set", "key": ["input", "omega"], "value": 12.5}},
                    {"op": "edit", "edit": {"op": "length", "link": "3", "point": "B", "value": 125}})
    assert all(r["ok"] for r in replies)
    last = replies[-1]
    assert last["handles"]["points"]["B0"]["at"] == [95, -10]  # type: ignore[index]
    assert httpx.post(served.url + "api/save", json={}).json() == {"saved": str(four_bar)}
    saved = four_bar.read_text(encoding="utf-8")
    assert saved == last["text"] != before
    assert _without_timing(last["result"]) == _solve_json(capsys, four_bar)  # type: ignore[arg-type]
    comments = [line[line.index("#"):] for line in before.splitlines() if "#" in line]
    assert comments and all(comment in saved for comment in comments)  # every comment kept, in order
    assert [saved.index(c) for c in comments] == sorted(saved.index(c) for c in comments)
    assert "B0 = [95, -10]" in saved and "omega = 12.5" in saved and "B = [125, 0]" in saved
    assert os.listdir(four_bar.parent) == [four_bar.name]  # no temporary file left


def test_undo_takes_a_whole_drag_back_and_redo_brings_it(served: Served, four_bar: Path) -> None:
    before = four_bar.read_text(encoding="utf-8")
    replies = _live(served,
                    {"op": "edit", "edit": {"op": "drive", "to": [-20, 30]}},
                    {"op": "edit", "edit": {"op": "drive", "to": [-30, 10]}, "merge": True},
                    {"op": "undo"}, {"op": "redo"}, {"op": "undo"}, {"op": "undo"})
    assert replies[2]["text"] == before and not replies[2]["can_undo"] and replies[2]["can_redo"]
    assert replies[3]["text"] == replies[1]["text"] != before
    assert replies[5]["text"] == before


def test_a_mechanism_dragged_where_it_cannot_close_keeps_the_last_drawing_and_comes_back(served: Served) -> None:
    # a crank of 75 makes the four-bar a non-Grashof one: at theta12 = 0, |AB| - |B0B| = 40 > |AB0| = 25
    first, far, back = _live(served,
                             {"op": "edit", "edit": {"op": "length", "link": "2", "point": "A", "value": 75}},
                             {"op": "edit", "edit": {"op": "drive", "to": [80, 0]}},
                             {"op": "edit", "edit": {"op": "drive", "to": [0, 75]}})
    assert first["ok"] and "A = [75, 0]" in first["text"]  # type: ignore[operator]
    assert not far["ok"] and far["exit"] == 3 and "cannot assemble" in far["errors"][0]  # type: ignore[index]
    assert far["svg"] == first["svg"] and far["good_result"] == first["result"]  # the last good drawing kept
    assert "angle = 0" in far["text"] and "A = [75, 0]" in far["text"]  # type: ignore[operator]
    assert back["ok"] and "angle = 90" in back["text"]  # type: ignore[operator]
    assert back["result"]["links"]["3"]["angle"] != first["result"]["links"]["3"]["angle"]  # type: ignore[index]


def test_a_refused_edit_says_why_and_changes_nothing(served: Served) -> None:
    (reply,) = _live(served, {"op": "edit", "edit": {"op": "move-point", "point": "Z", "to": [1, 2]}})
    assert "no solved link has a point 'Z'" in reply["refused"]  # type: ignore[operator]
    assert not reply["can_undo"]


def test_save_refuses_a_file_changed_on_disk_unless_forced(served: Served, four_bar: Path) -> None:
    _live(served, {"op": "edit", "edit": {"op": "set", "key": ["input", "alpha"], "value": 0}})
    four_bar.write_text(four_bar.read_text(encoding="utf-8") + "# changed by someone else\n", encoding="utf-8")
    refused = httpx.post(served.url + "api/save", json={})
    assert refused.status_code == 409 and refused.json()["changed_on_disk"]
    assert four_bar.read_text(encoding="utf-8").endswith("# changed by someone else\n")
    assert httpx.post(served.url + "api/save", json={"force": True}).status_code == 200
    assert "alpha = 0" in four_bar.read_text(encoding="utf-8")
    assert httpx.post(served.url + "api/save", json={}).status_code == 200  # saved by the editor: its own now


def test_the_drawing_and_a_step_sheet_are_the_draw_commands(served: Served, four_bar: Path, tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    drawing = httpx.get(served.url + "api/drawing.svg")
    assert drawing.headers["content-type"].startswith("image/svg+xml")
    code, _, err = run(capsys, "draw", str(four_bar), "-o", str(tmp_path / "out.svg"), "--steps", str(tmp_path / "s"))
    assert code == 0, err
    assert drawing.text == (tmp_path / "out.svg").read_text(encoding="utf-8")  # A4 holds the four-bar as drawn
    assert (httpx.get(served.url + "api/steps/3.svg").text
            == (tmp_path / "s" / "step-03.svg").read_text(encoding="utf-8"))
    assert httpx.get(served.url + "api/steps/99.svg").status_code == 404


@pytest.mark.parametrize("name", TEMPLATES)
def test_each_template_is_an_example_and_solves(name: str, tmp_path: Path) -> None:
    example = {"six-bar": "centers-six-bar", "cam": "cam-roller-rocker"}.get(name, name)
    text = template_text(name)
    assert text == (EXAMPLES / f"{example}.toml").read_text(encoding="utf-8")
    from kinepoly.editor.evaluate import evaluate

    assert evaluate(text, f"{name}.toml").ok


def test_the_edit_command_serves_a_new_file_from_a_template_and_stops_on_interrupt(tmp_path: Path) -> None:
    scene = tmp_path / "new.toml"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(Path(__file__).resolve().parents[2] / "src"),
                                                         os.environ.get("PYTHONPATH", "")])}
    with subprocess.Popen([sys.executable, "-m", "kinepoly", "edit", str(scene), "--template", "slider-crank",
                           "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          env=env) as process:
        try:
            assert process.stdout is not None
            line = process.stdout.readline()
            url = line.split(" at ")[1].split()[0]
            assert url.startswith("http://127.0.0.1:") and "slider-crank template" in line
            assert httpx.get(url + "api/scene").json()["text"] == template_text("slider-crank")
            assert not scene.exists()  # written when saved, not before
            assert httpx.post(url + "api/save", json={}).status_code == 200
            assert scene.read_text(encoding="utf-8") == template_text("slider-crank")
        finally:
            process.send_signal(signal.SIGINT)
            try:
                _, err = process.communicate(timeout=30)
            except subprocess.TimeoutExpired:  # never left running
                process.kill()
                _, err = process.communicate()
                pytest.fail(f"kinepoly edit did not stop on Ctrl-C: {err}")
    assert process.returncode == 0, err
    assert "stopped" in err and "Traceback" not in err


@pytest.mark.parametrize(("argv", "message"), [
    (["edit", "{tmp}/no/such/folder/x.toml", "--no-browser"], "does not exist"),
    (["edit", "{tmp}/x.toml", "--no-browser", "--port", "70000"], "expected a port between 0 and 65535"),
    (["edit", "{tmp}", "--no-browser"], "is a folder"),
])
def test_the_edit_command_refuses_what_it_cannot_do(argv: list[str], message: str, tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, *(a.replace("{tmp}", str(tmp_path)) for a in argv))
    assert code == 2 and message in err and "Traceback" not in err


def test_a_cam_is_driven_by_its_profile_centre_which_cannot_be_moved_as_a_point(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from tests.editor.server import serving

    from kinepoly.editor.document import Document

    path = tmp_path / "cam.toml"
    with serving(Document(str(path), template_text("cam"))) as served:
        first, driven, refused = _live(served, {"op": "state"},
                                       {"op": "edit", "edit": {"op": "drive", "to": [0, 15]}},
                                       {"op": "edit", "edit": {"op": "move-point", "point": "K23", "to": [0, 20]}})
        assert first["handles"]["input"]["point"] == "K23"  # type: ignore[index]
        assert not first["handles"]["points"]["K23"]["written"]  # type: ignore[index]
        assert {x["link"] for x in first["handles"]["lengths"]} == {"1", "3"}  # type: ignore[index, union-attr]
        assert driven["ok"] and "angle = 90" in driven["text"]  # type: ignore[operator]
        assert "K23" in refused["refused"] and refused["text"] == driven["text"]  # type: ignore[operator]
        assert httpx.post(served.url + "api/save", json={}).status_code == 200
    assert _without_timing(driven["result"]) == _solve_json(capsys, path)  # type: ignore[arg-type]


def test_the_answers_are_those_of_solve_on_the_editors_paper(tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    from tests.editor.server import serving

    from kinepoly.editor.document import Document

    path = tmp_path / "slotted-lever.toml"
    path.write_text(template_text("slotted-lever"), encoding="utf-8")
    with serving(Document(str(path), paper=(420.0, 297.0))) as served:
        answer = httpx.get(served.url + "api/solution").json()
    code, out, err = run(capsys, "solve", str(path), "--json", "--paper", "A3")
    assert code == 0, err
    assert _without_timing(answer) == _without_timing(json.loads(out))


def test_the_guess_follows_its_point_as_the_mechanism_is_dragged(served: Served) -> None:
    first, second = _live(served, {"op": "edit", "edit": {"op": "drive", "to": [-20, 30]}},
                          {"op": "edit", "edit": {"op": "drive", "to": [-30, 10]}, "merge": True})
    b = first["handles"]["points"]["B"]["at"]  # type: ignore[index]
    assert f"B = [{round(b[0], 2):g}, {round(b[1], 2):g}]" in second["text"]  # type: ignore[operator]
    assert "B = [133.88, 72.47]" in first["text"]  # type: ignore[operator]  # where the file's solve has B


def test_the_page_and_the_templates_are_package_data_and_the_server_a_dependency() -> None:
    import tomllib

    root = Path(__file__).resolve().parents[2]
    project = tomllib.loads((root / "pyproject.toml").read_text(encoding="utf-8"))
    globs = project["tool"]["setuptools"]["package-data"]["kinepoly.editor"]
    folder = root / "src" / "kinepoly" / "editor"
    shipped = {p for glob in globs for p in folder.glob(glob)}
    assert shipped == {*folder.glob("static/*"), *folder.glob("templates/*")} and len(shipped) == 3 + len(TEMPLATES)
    needed = {d.split(">")[0].split("=")[0].strip() for d in project["project"]["dependencies"]}
    assert {"starlette", "uvicorn", "websockets", "tomlkit"} <= needed  # the README's plain install runs the editor


def test_a_text_that_is_not_toml_is_kept_and_a_drag_on_it_is_refused_with_the_reason(served: Served) -> None:
    text = httpx.get(served.url + "api/scene").json()["text"]
    broken, dragged, undone = _live(served, {"op": "text", "text": text + "[input\n"},
                                    {"op": "edit", "edit": {"op": "drive", "to": [0, 40]}}, {"op": "undo"})
    assert not broken["ok"] and broken["text"] == text + "[input\n" and "TOML" in broken["errors"][0]  # type: ignore[index]
    assert "not TOML" in dragged["refused"] and dragged["text"] == broken["text"]  # type: ignore[operator]
    assert undone["ok"] and undone["text"] == text
    answer = httpx.post(served.url + "api/change", json={"op": "edit", "edit": {"op": "fly"}})
    assert answer.status_code == 400 and "unknown edit 'fly'" in answer.json()["error"]


def test_a_scene_with_a_byte_order_mark_keeps_it(served: Served) -> None:
    text = "\ufeff" + httpx.get(served.url + "api/scene").json()["text"]
    _, driven = _live(served, {"op": "text", "text": text}, {"op": "edit", "edit": {"op": "drive", "to": [0, 40]}})
    assert driven["ok"] and driven["text"].startswith("\ufeff# Four-bar")  # type: ignore[union-attr]


def test_a_driven_slider_runs_to_the_pointers_foot_on_its_line(tmp_path: Path,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    import math

    from tests.editor.server import serving

    from kinepoly.editor.document import Document

    path = tmp_path / "dump-body.toml"
    path.write_text((EXAMPLES / "dump-body.toml").read_text(encoding="utf-8"), encoding="utf-8")
    with serving(Document(str(path))) as served:
        (first,) = _live(served, {"op": "state"})
        handles = first["handles"]
        assert handles["input"]["kind"] == "stroke" and handles["input"]["point"] == "D"  # type: ignore[index]
        assert handles["fields"] == {"s": 520, "s_dot": 40, "s_ddot": 0}  # type: ignore[index]
        d, c0 = handles["points"]["D"]["at"], handles["points"]["C0"]["at"]  # type: ignore[index]
        size = math.dist(d, c0)
        along = ((d[0] - c0[0]) / size, (d[1] - c0[1]) / size)  # the barrel's axis runs from C0 through D
        off = (d[0] + 30 * along[0] - 50 * along[1], d[1] + 30 * along[1] + 50 * along[0])  # 30 along, 50 aside
        (driven,) = _live(served, {"op": "edit", "edit": {"op": "drive", "to": list(off)}})
        assert driven["ok"] and "s = 550" in driven["text"]  # type: ignore[operator]
        assert httpx.post(served.url + "api/save", json={}).status_code == 200
    assert _without_timing(driven["result"]) == _solve_json(capsys, path)  # type: ignore[arg-type]
    assert driven["result"]["sliders"]["34"]["s"] == pytest.approx(550)  # type: ignore[index]


def test_a_file_that_does_not_solve_opens_with_its_errors_and_is_mended_through_the_api(tmp_path: Path) -> None:
    from tests.editor.server import serving

    from kinepoly.editor.document import Document

    path = tmp_path / "broken.toml"
    good = template_text("four-bar")
    path.write_text(good.replace("angle = 60", "angle = ?"), encoding="utf-8")
    with serving(Document(str(path))) as served:
        state = httpx.get(served.url + "api/state").json()
        assert not state["ok"] and "svg" not in state and state["errors"][0].startswith(f"kinepoly: error: {path}:")
        assert httpx.get(served.url + "api/drawing.svg").status_code == 404
        assert httpx.put(served.url + "api/scene", json={"text": good}).status_code == 200
        assert httpx.get(served.url + "api/drawing.svg").status_code == 200


def test_draft_moves_answer_draft_sheets_and_full_draws_the_last_whole(served: Served, four_bar: Path,
                                                                       tmp_path: Path,
                                                                       capsys: pytest.CaptureFixture[str]) -> None:
    first, moved, full, state = _live(
        served,
        {"op": "edit", "edit": {"op": "drive", "to": [-20, 30]}, "draft": True},
        {"op": "edit", "edit": {"op": "drive", "to": [-30, 10]}, "merge": True, "draft": True},
        {"op": "full"}, {"op": "state"})
    assert first["draft"] is moved["draft"] is True and moved["ok"]
    assert full["draft"] is False and full["text"] == moved["text"] and full["can_undo"]
    assert full["svg"] != moved["svg"] and full["svg"] == state["svg"]
    assert full["result"] == moved["result"] and full["handles"] == moved["handles"]  # only the sheet redrawn
    four_bar.write_text(str(full["text"]), encoding="utf-8")
    code, _, err = run(capsys, "draw", str(four_bar), "-o", str(tmp_path / "out.svg"))
    assert code == 0, err
    assert full["svg"] == (tmp_path / "out.svg").read_text(encoding="utf-8")  # the whole sheet: kinepoly draw's
    assert httpx.get(served.url + "api/drawing.svg").text == full["svg"]
    (undone,) = _live(served, {"op": "undo"})
    assert undone["draft"] is False and not undone["can_undo"]  # the drag was one step
