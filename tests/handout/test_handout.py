"""``kinepoly handout``: catalogues complete, pages (1 + steps + 1) built from the steps' data, whole files, exit 2.

The steps' structured data (``Step.directions``) is checked against the geometry it describes;
the pages' equations against the steps'; the words of each language against its catalogue.
"""

from __future__ import annotations

import math
import re
import string
import tomllib
from importlib import resources
from pathlib import Path

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.cli import main
from kinepoly.errors import CatalogueError
from kinepoly.handout import handout_html, handout_sheets, load_catalogue, packaged_languages
from kinepoly.handout.notation import plain_of, typographic
from kinepoly.handout.step_pages import step_equation
from kinepoly.render.primitives import Sheet, Text
from kinepoly.solution import Solution

LANGUAGES = ("en", "tr", "ro")
NOTATION_TOPICS = ("relative", "intersection", "read", "coriolis", "given-normal")


def _solve(name: str) -> Solution:
    return kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))


@pytest.fixture(scope="module")
def four_bar() -> Solution:
    return _solve("four-bar")


@pytest.fixture(scope="module")
def sheets(four_bar: Solution) -> dict[str, tuple[object, list[Sheet]]]:
    return {lang: handout_sheets(four_bar, load_catalogue(lang)) for lang in LANGUAGES}


def _texts(sheet: Sheet, prefix: str, layer: str = "title") -> list[str]:
    return ["".join(r.text for r in item.runs) for item in sheet.layer(layer).items
            if isinstance(item, Text) and item.role.startswith(prefix)]


def _band(sheet: Sheet) -> str:
    return " ".join(_texts(sheet, "handout"))


# -- the catalogues ------------------------------------------------------------------------------
def _fields(message: str) -> set[str]:
    return {name for _, name, _, _ in string.Formatter().parse(message) if name}


def _flat(table: dict[str, object], prefix: str = "") -> dict[str, object]:
    out: dict[str, object] = {}
    for key, value in table.items():
        out.update(_flat(value, f"{prefix}{key}.") if isinstance(value, dict) else {f"{prefix}{key}": value})
    return out


def _catalogue_file(code: str) -> dict[str, object]:
    text = resources.files("kinepoly.present").joinpath("messages", f"{code}.toml").read_text(encoding="utf-8")
    return _flat(tomllib.loads(text))


def test_the_languages_shipped_are_english_turkish_romanian() -> None:
    assert packaged_languages() == ("en", "ro", "tr")


@pytest.mark.parametrize("code", LANGUAGES)
def test_every_language_has_every_key_and_only_the_placeholders_english_has(code: str) -> None:
    english, other = _catalogue_file("en"), _catalogue_file(code)
    assert set(other) == set(english)
    for key, message in other.items():
        assert isinstance(message, str) and message.strip(), key
        assert _fields(message) <= _fields(str(english[key])), key
    assert other["code"] == code


def test_a_teachers_catalogue_extends_a_language_or_is_checked_whole(tmp_path: Path) -> None:
    own = tmp_path / "mine.toml"
    own.write_text('extends = "en"\nlanguage = "English, my words"\ncode = "en"\n[polygon]\nvelocity = "v-polygon"\n')
    say = load_catalogue(messages=own)
    assert say.say("polygon.velocity") == "v-polygon" and say.say("polygon.acceleration") == "acceleration polygon"
    own.write_text('language = "Deutsch"\ncode = "de"\n\n[polygon]\nvelocity = "Geschwindigkeitsplan {lnik}"\n'
                   'speed = "x"\n')
    with pytest.raises(CatalogueError) as problem:
        load_catalogue(messages=own)
    message = str(problem.value)
    assert f"{own}:5: polygon.velocity: unknown placeholder {{lnik}}" in message
    assert f"{own}:6: polygon.speed: unknown key" in message
    assert "missing" in message and "step.intersection_velocity" in message


# -- the structured data of the steps --------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(p.stem for p in EXAMPLES.glob("*.toml")))
def test_each_direction_line_is_what_its_data_says(name: str) -> None:
    """perpendicular to AB: the line is square to B - A; parallel to slider 14: along its slide; through the tip."""
    solution = _solve(name)
    mechanism = solution.inside.mechanism if solution.inside else solution.mechanism
    pose = solution.inside.pose if solution.inside else solution.pose

    def world(label: str) -> tuple[float, float]:
        if label in pose.marks:  # a point the construction found (a triad's Assur point)
            return pose.marks[label]
        owner = next(k for k in mechanism.links_of_point(label) if k in pose.links)
        return pose.links[owner].world(mechanism.local(owner, label))

    for step in solution.steps:
        if step.kind == "linear-solve":
            continue
        assert step.topic, step.equation
        if step.topic != "intersection":
            continue
        assert len(step.directions) == len(step.lines) == 2
        sides = [[t.strip() for t in side.split(" + ")] for side in step.equation.split(" = ")]
        polygon = solution.velocity if step.polygon == "velocity" else solution.acceleration
        assert polygon is not None
        for direction, line, side in zip(step.directions, step.lines, sides[1:], strict=True):
            assert direction.term == side[-1]  # the unknown term ends its side of the equation
            d = line.direction
            size = math.hypot(*d)
            if direction.relation == "perpendicular":
                first, second = re.findall(r"[A-Z][0-9]*", direction.reference)
                ax, ay = world(first)
                bx, by = world(second)
                assert abs(d[0] * (bx - ax) + d[1] * (by - ay)) <= 1e-12 * size * math.hypot(bx - ax, by - ay)
            elif direction.relation == "face":  # along a follower's flat face (a spline cam's block)
                face = next(c.flat for c in mechanism.scene.cams if c.follower == direction.reference)
                assert face is not None
                angle = pose.links[direction.reference].theta + face[1]
                assert abs(d[0] * math.sin(angle) - d[1] * math.cos(angle)) <= 1e-12 * size
            else:
                spec = mechanism.slider(direction.reference)
                angle = pose.links[spec.guide].theta + spec.angle_rad
                assert abs(d[0] * math.sin(angle) - d[1] * math.cos(angle)) <= 1e-12 * size
            if direction.after:
                laid = next(v for v in step.vectors if v.label == direction.after)
                start = laid.end
            else:
                label = next(k for k in polygon.tips if k.lower() == direction.through)
                start = polygon.tips[label]
            scale = max(math.hypot(*t) for t in polygon.tips.values())
            assert math.hypot(line.through[0] - start[0], line.through[1] - start[1]) <= 1e-12 * scale


# -- the pages -------------------------------------------------------------------------------------
@pytest.mark.parametrize("lang", LANGUAGES)
def test_a_page_for_the_problem_each_step_and_the_answers(four_bar: Solution,
                                                          sheets: dict[str, tuple[object, list[Sheet]]],
                                                          lang: str) -> None:
    _handout, pages = sheets[lang]
    assert len(pages) == 1 + len(four_bar.steps) + 1 == 15
    say = load_catalogue(lang)
    assert say.say("problem.title") in _band(pages[0])
    assert say.say("answers.title") in _band(pages[-1])
    for number, (step, sheet) in enumerate(zip(four_bar.steps, pages[1:-1], strict=True), 1):
        heading = _band(sheet)
        assert say.say("page.step", number=str(number), total="13", polygon=say.say(f"polygon.{step.polygon}")) \
            in heading
        equation = "".join(_texts(sheet, "handout equation"))
        assert equation == plain_of(step_equation(step, say, four_bar))
        if step.topic in NOTATION_TOPICS:
            assert equation == plain_of(typographic(step.equation))


def test_the_step_texts_are_the_languages_own(sheets: dict[str, tuple[object, list[Sheet]]]) -> None:
    english = " ".join(_band(s) for s in sheets["en"][1])
    turkish = " ".join(_band(s) for s in sheets["tr"][1])
    romanian = " ".join(_band(s) for s in sheets["ro"][1])
    assert "perpendicular to AB" in english and "perpendicular" not in turkish
    assert "AB doğrusuna dik" in turkish and "hız poligonu" in turkish and "teğetsel" in turkish
    assert "perpendiculară pe AB" in romanian and "poligonul vitezelor" in romanian
    for text in (turkish, romanian):
        assert "counter-clockwise" not in text and " the " not in text


def test_the_numbers_are_the_solutions(four_bar: Solution, sheets: dict[str, tuple[object, list[Sheet]]]) -> None:
    """ω13 as read in its step and in the answers; kv as written equals the scale the polygon is drawn at."""
    _, pages = sheets["tr"]
    say = load_catalogue("tr")
    read = next(k for k, s in enumerate(four_bar.steps, 1) if s.kind == "read" and s.result == "omega13")
    omega = four_bar.velocity.omega["3"] if four_bar.velocity else 0.0
    assert f"ω13 = {say.number(omega)} rad/s" in _band(pages[read])
    assert say.number(omega) in _band(pages[-1])
    kv = " ".join(_texts(pages[0], "scale velocity", "scales"))
    assert kv.startswith("kv = ") and "," in kv  # Turkish decimal comma
    scale = float(kv.split()[2].replace(",", "."))
    arrow = next(i for i in pages[-1].layer("velocity-polygon").items if i.role == "vector v_B")
    speed = math.hypot(*four_bar.velocity.tips["B"]) if four_bar.velocity else 0.0
    assert math.isclose(arrow.length, scale * speed, rel_tol=1e-9)  # type: ignore[union-attr]


def test_kennedy_steps_get_pages_and_the_centers_grow(tmp_path: Path) -> None:
    solution = _solve("centers-six-bar")
    assert solution.centers is not None
    _, pages = handout_sheets(solution, load_catalogue("en"))
    kennedy = len(solution.centers.steps)
    assert len(pages) == 1 + len(solution.steps) + kennedy + 1
    shown = [sum(1 for i in p.layer("instant-centers").items if i.role.startswith("kennedy")) for p in pages]
    first = 1 + len(solution.steps)
    assert shown[0] == 0 and shown[first] > 0
    assert all(a <= b for a, b in zip(shown[first:-1], shown[first + 1:-1], strict=False))
    label = "I13"
    assert f"Found: {label} at" in _band(pages[first])


# -- the command -------------------------------------------------------------------------------------
def _pdf_pages(data: bytes) -> int:
    return len(re.findall(rb"/Type\s*/Page[^s]", data))


def test_the_command_writes_the_pdf_and_the_page_whole(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    pdf, page = tmp_path / "h.pdf", tmp_path / "h.html"
    code = main(["handout", str(EXAMPLES / "slider-crank.toml"), "-o", str(pdf), "--html", str(page), "--lang", "ro"])
    out, err = capsys.readouterr()
    assert code == 0, err
    steps = len(_solve("slider-crank").steps)
    assert pdf.read_bytes().startswith(b"%PDF") and _pdf_pages(pdf.read_bytes()) == steps + 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["h.html", "h.pdf"]  # no temporary file left
    text = page.read_text(encoding="utf-8")
    assert text.count('<section class="page"') == steps + 2 and '<html lang="ro">' in text
    assert not re.search(r"""(src|href)\s*=|<link|@import|url\(\s*['"]?http""", text)  # nothing fetched
    assert f"wrote {pdf}" in out and f"wrote {page}" in out


def test_a_failed_write_leaves_the_old_file(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str],
                                            tmp_path: Path) -> None:
    target = tmp_path / "h.pdf"
    target.write_bytes(b"old")

    def broken(sheets: object, stream: object, title: str) -> None:
        stream.write(b"%PDF-half")  # type: ignore[attr-defined]
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("kinepoly.render.mpl.write_pdf_pages", broken)
    code = main(["handout", str(EXAMPLES / "four-bar.toml"), "-o", str(target)])
    _, err = capsys.readouterr()
    assert code == 2 and "No space left on device" in err
    assert target.read_bytes() == b"old" and [p.name for p in tmp_path.iterdir()] == ["h.pdf"]


BAD = [
    ("nothing to write", [], "nothing to write"),
    ("pdf extension", ["-o", "{tmp}/h.png"], "expected a file ending in .pdf"),
    ("html extension", ["--html", "{tmp}/h.txt"], "expected a file ending in .html"),
    ("missing folder", ["-o", "{tmp}/no/h.pdf"], "does not exist"),
    ("unknown language", ["-o", "{tmp}/h.pdf", "--lang", "xx"], "--lang xx: no such language"),
    ("missing catalogue", ["-o", "{tmp}/h.pdf", "--messages", "{tmp}/none.toml"], "cannot read the catalogue"),
    ("bad catalogue", ["-o", "{tmp}/h.pdf", "--messages", "{tmp}/bad.toml"], "not a valid TOML file"),
    ("bad paper", ["-o", "{tmp}/h.pdf", "--paper", "B7"], "--paper B7"),
]


@pytest.mark.parametrize("name, args, fragment", BAD, ids=[b[0] for b in BAD])
def test_bad_options_exit_2_with_what_to_change(capsys: pytest.CaptureFixture[str], tmp_path: Path, name: str,
                                                args: list[str], fragment: str) -> None:
    (tmp_path / "bad.toml").write_text("language = \n")
    code = main(["handout", str(EXAMPLES / "four-bar.toml"), *(a.format(tmp=tmp_path) for a in args)])
    _, err = capsys.readouterr()
    assert code == 2
    assert fragment in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_the_html_holds_every_page_and_the_step_texts(four_bar: Solution) -> None:
    handout, text = handout_html(four_bar, load_catalogue("tr"))
    sections = re.findall(r'<section class="page" id="page-(\d+)"[^>]*>', text)
    assert [int(s) for s in sections] == list(range(1, len(handout.pages) + 1))
    assert text.count("<svg") == 1 and 'id="mechanism"' not in text  # one drawing for every page, no id twice
    assert 'data-equation="' + typographic(four_bar.steps[2].equation) in text
