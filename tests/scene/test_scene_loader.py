"""Tests of the scene loader: the examples, unit conversion, every kind of bad input, properties."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from kinepoly.errors import SceneError
from kinepoly.scene.loader import load_scene, loads_scene
from kinepoly.scene.spec import FindSpec, GivenInput, LinkInput, Scene, SliderInput

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
EXAMPLE_NAMES = [
    "slider-crank",
    "four-bar",
    "slotted-lever",
    "image-point",
    "shaper",
    "centers-six-bar",
]

# A small valid scene; the bad-input cases below change single lines, so line numbers hold.
BASE = """\
title = "test"

[links]
1 = { points = { A0 = [0, 0] } }
2 = { points = { A0 = [0, 0], A = [40, 0] } }
3 = { points = { B = [0, 0], A = [120, 0] } }
4 = { points = { B = [0, 0] } }

[[sliders]]
block = "4"
guide = "1"
point = "B"
line = { through = [0, 10], angle = 0 }

[input]
link = "2"
angle = 60
omega = 10
"""

GIVEN_BASE = """\
[links]
3 = { points = { A = [0, 0], B = [80, 0], S = [30, 40] } }

[given.A]
velocity = [0, 300]
acceleration = [-50, 0]

[given.B]
velocity = [0, -100]
acceleration = [-2050, 120]
"""


def edit(text: str, old: str, new: str) -> str:
    assert text.count(old) == 1, old
    return text.replace(old, new)


def problems_of(text: str, source: str = "scene.toml") -> list[str]:
    with pytest.raises(SceneError) as caught:
        loads_scene(text, source)
    return caught.value.problems


def example(name: str) -> Scene:
    return load_scene(EXAMPLES / f"{name}.toml")


def line_of(name: str, fragment: str) -> int:
    lines = (EXAMPLES / f"{name}.toml").read_text().splitlines()
    return next(i for i, line in enumerate(lines, start=1) if fragment in line)


# --------------------------------------------------------------------------------------------
# The examples


@pytest.mark.parametrize("name", EXAMPLE_NAMES)
def test_every_example_loads(name: str) -> None:
    scene = example(name)
    assert scene.links
    assert scene.source == str(EXAMPLES / f"{name}.toml")
    assert scene.title


def test_examples_folder_has_the_six() -> None:
    assert set(EXAMPLE_NAMES) <= {p.stem for p in EXAMPLES.glob("*.toml")}


def test_slider_crank_values() -> None:
    scene = example("slider-crank")
    assert scene.ground == "1"
    c = scene.link("3").point("C")
    assert c.local[0] == pytest.approx(43.30127018922193, rel=1e-12)
    assert c.local[1] == pytest.approx(-25.0, rel=1e-12)
    assert c.line == line_of("slider-crank", "3 = {")
    (slider,) = scene.sliders
    assert (slider.name, slider.block, slider.guide, slider.point) == ("14", "4", "1", "B")
    assert slider.through == (0.0, 10.0)
    assert slider.angle_rad == 0.0
    assert slider.line == line_of("slider-crank", "[[sliders]]")
    assert isinstance(scene.input, LinkInput)
    assert scene.input.link == "2"
    assert scene.input.angle_rad == pytest.approx(math.pi / 3, rel=1e-15)
    assert (scene.input.omega, scene.input.alpha) == (10.0, 0.0)
    assert scene.guess == (("B", (150.0, 10.0)),)
    assert (scene.draw.kv, scene.draw.ka) == (0.1, 0.01)
    assert scene.find.velocity == ("A", "B", "C")
    assert scene.find.omega == ("3",)
    assert not scene.find.is_default


def test_slotted_lever_line_is_vertical() -> None:
    (slider,) = example("slotted-lever").sliders
    assert slider.angle_rad == pytest.approx(math.pi / 2, rel=1e-15)
    assert slider.name == "43"
    assert slider.through == (15.0, 0.0)


def test_shaper_has_two_named_sliders() -> None:
    scene = example("shaper")
    assert [s.name for s in scene.sliders] == ["43", "16"]
    assert scene.find.velocity == ("A", "A@4", "C", "D")


def test_image_point_is_a_given_scene() -> None:
    scene = example("image-point")
    assert scene.ground is None
    assert isinstance(scene.input, GivenInput)
    a, b = scene.input.points
    assert (a.name, a.velocity, a.acceleration) == ("A", (0.0, 300.0), (-50.0, 0.0))
    assert (b.name, b.velocity, b.acceleration) == ("B", (0.0, -100.0), (-2050.0, 120.0))
    assert a.line == line_of("image-point", "[given.A]")


def test_centers_six_bar_asks_all_centers() -> None:
    scene = example("centers-six-bar")
    assert scene.find.instant_centers == "all"
    d = scene.link("4").point("D")
    assert d.local == pytest.approx((60 * math.cos(math.radians(40)), 60 * math.sin(math.radians(40))), rel=1e-12)


# --------------------------------------------------------------------------------------------
# Units, defaults and sugar


def test_units_cm_with_unit_strings() -> None:
    text = edit(BASE, 'title = "test"', 'units = { length = "cm" }')
    text = edit(text, "A = [40, 0] }", 'A = ["40 mm", 0] }')
    text = edit(text, "omega = 10", 'omega = "300 rpm"')
    scene = loads_scene(text)
    assert scene.units.length == "cm"
    assert scene.link("2").point("A").local == (4.0, 0.0)
    assert isinstance(scene.input, LinkInput)
    assert scene.input.omega == pytest.approx(10 * math.pi, rel=1e-12)


def test_angle_units_and_strings() -> None:
    text = edit(BASE, 'title = "test"', 'units = { angle = "rad" }')
    text = edit(text, "angle = 60", "angle = 0.5")
    text = edit(text, "angle = 0 }", 'angle = "90 deg" }')
    scene = loads_scene(text)
    assert isinstance(scene.input, LinkInput)
    assert scene.input.angle_rad == 0.5
    assert scene.sliders[0].angle_rad == pytest.approx(math.pi / 2, rel=1e-15)
    assert loads_scene(edit(BASE, "angle = 60", 'angle = "0.5 rad"')).input == LinkInput("2", 0.5, 10.0, 0.0, 15)


def test_rates_as_strings() -> None:
    text = edit(BASE, "omega = 10", 'omega = "90 deg/s"\nalpha = "2 rad/s^2"')
    scene = loads_scene(text)
    assert isinstance(scene.input, LinkInput)
    assert scene.input.omega == pytest.approx(math.pi / 2, rel=1e-15)
    assert scene.input.alpha == 2.0


def test_slider_input_with_units() -> None:
    text = edit(BASE, 'link = "2"\nangle = 60\nomega = 10\n', 's_dot = "-0.5 m/s"\nslider = "14"\ns = "130 mm"\n')
    scene = loads_scene(text)
    assert scene.input == SliderInput("14", 130.0, -500.0, 0.0, 15)


def test_default_find_title_and_ground() -> None:
    scene = loads_scene(edit(BASE, 'title = "test"', ""))
    assert scene.title == "untitled"
    assert scene.ground == "1"
    assert scene.find == FindSpec(
        velocity=("A", "A0", "B"),
        acceleration=("A", "A0", "B"),
        omega=("2", "3", "4"),
        alpha=("2", "3", "4"),
        sliders=("14",),
        instant_centers=(),
        is_default=True,
    )


def test_title_defaults_to_file_stem(tmp_path: Path) -> None:
    path = tmp_path / "my-crank.toml"
    path.write_text(edit(BASE, 'title = "test"', ""))
    assert load_scene(path).title == "my-crank"
    assert load_scene(str(path)).source == str(path)


def test_find_keeps_order_and_normalises_pairs() -> None:
    text = (
        BASE
        + '\n[find]\nvelocity = ["B", "A", "B", "A@4"]\nomega = ["4", "3"]\ninstant_centers = ["1-3", "31", "24"]\n'
    )
    find = loads_scene(text).find
    assert find.velocity == ("B", "A", "A@4")
    assert find.omega == ("4", "3")
    assert find.acceleration == ()
    assert find.instant_centers == ("13", "31", "24")
    assert not find.is_default


def test_named_slider_and_long_link_names() -> None:
    text = """\
ground = "frame"
[links]
frame = { points = { O = [0, 0] } }
crank = { points = { O = [0, 0], A = [40, 0] } }
rod = { points = { A = [0, 0], B = [100, 0] } }
block = { points = { B = [0, 0] } }
[[sliders]]
block = "block"
guide = "frame"
point = "B"
line = { through = [0, 0], angle = 0 }
[input]
link = "crank"
angle = 30
omega = 1
[find]
instant_centers = ["frame-rod"]
sliders = ["frame-block"]
"""
    scene = loads_scene(text)
    assert scene.sliders[0].name == "frame-block"
    assert scene.find.instant_centers == ("frame-rod",)
    assert scene.find.sliders == ("frame-block",)


# --------------------------------------------------------------------------------------------
# Bad input: one problem each, with its exact place


GIVEN_ONE = """\
[links]
3 = { points = { A = [0, 0], B = [80, 0] } }

[given.A]
velocity = [0, 300]
"""

BAD_SCENES = {
    "syntax-error": (
        edit(BASE, "angle = 60", "angle = = 60"),
        "scene.toml:17: input.angle: ",
        "TOML syntax error at column",
    ),
    "syntax-error-in-header": (
        BASE + "[find\n",
        "scene.toml:19: find: ",
        "Expected ']' at the end of a table declaration",
    ),
    "unknown-key-did-you-mean": (
        edit(BASE, 'link = "2"', 'lnik = "2"'),
        "scene.toml:16: input.lnik: ",
        'unknown key; did you mean "link"?',
    ),
    "unknown-top-key": (
        edit(BASE, 'title = "test"', 'titel = "test"'),
        "scene.toml:1: titel: ",
        'did you mean "title"?',
    ),
    "unknown-slider-key": (
        edit(BASE, 'point = "B"', 'piont = "B"'),
        "scene.toml:12: sliders.1.piont: ",
        'did you mean "point"?',
    ),
    "unknown-line-key": (
        edit(BASE, "through = [0, 10]", "thru = [0, 10]"),
        "scene.toml:13: sliders.1.line.thru: ",
        'did you mean "through"?',
    ),
    "wrong-type-point": (
        edit(BASE, "A = [120, 0] }", 'A = "120" }'),
        "scene.toml:6: links.3.points.A: ",
        'expected [x, y] or { polar = [r, angle] }, got "120"',
    ),
    "bool-is-not-a-number": (
        edit(BASE, "omega = 10", "omega = true"),
        "scene.toml:18: input.omega: ",
        "got true",
    ),
    "name-must-be-string": (
        edit(BASE, 'link = "2"', "link = 2"),
        "scene.toml:16: input.link: ",
        'a string like "2", got 2',
    ),
    "nan": (
        edit(BASE, "omega = 10", "omega = nan"),
        "scene.toml:18: input.omega: ",
        "nan is not a finite number",
    ),
    "inf": (
        edit(BASE, "A = [40, 0]", "A = [inf, 0]"),
        "scene.toml:5: links.2.points.A.x: ",
        "inf is not a finite number",
    ),
    "missing-input": (BASE.split("[input]")[0], "scene.toml: input: ", "missing; expected an [input] table"),
    "input-and-given": (
        BASE + "\n[given.A]\nvelocity = [0, 1]\n",
        "scene.toml:20: given: ",
        "both [input] and [given]",
    ),
    "input-link-is-ground": (
        edit(BASE, 'link = "2"', 'link = "1"'),
        "scene.toml:16: input.link: ",
        "is the ground",
    ),
    "unknown-link-in-slider": (
        edit(BASE, 'block = "4"', 'block = "5"'),
        "scene.toml:10: sliders.1.block: ",
        'no link "5"',
    ),
    "unknown-point-in-slider": (
        edit(BASE, 'point = "B"', 'point = "C"'),
        "scene.toml:12: sliders.1.point: ",
        'no point "C" in link "4" (the block)',
    ),
    "zero-length-link": (
        edit(BASE, "A = [120, 0] }", "A = [0, 0] }"),
        "scene.toml:6: links.3.points.A: ",
        "a zero-length link",
    ),
    "empty-file": ("", "scene.toml: (file): ", "the file is empty"),
    "only-comments": ("# nothing here\n", "scene.toml: (file): ", "only comments"),
    "bad-unit-string": (
        edit(BASE, "omega = 10", 'omega = "300 rmp"'),
        "scene.toml:18: input.omega: ",
        'unknown unit "rmp"',
    ),
    "unit-of-wrong-kind": (
        edit(BASE, "A = [40, 0]", 'A = ["40 deg", 0]'),
        "scene.toml:5: links.2.points.A.x: ",
        'unknown unit "deg" for a length',
    ),
    "bad-scene-unit": (
        edit(BASE, 'title = "test"', 'units = { length = "mmm" }'),
        "scene.toml:1: units.length: ",
        'did you mean "mm"?',
    ),
    "unknown-find-point": (
        BASE + '\n[find]\nvelocity = ["Z"]\n',
        "scene.toml:21: find.velocity: ",
        'no point "Z"',
    ),
    "unknown-coincident-link": (
        BASE + '\n[find]\nvelocity = ["A@9"]\n',
        "scene.toml:21: find.velocity: ",
        'no link "9"',
    ),
    "ground-in-omega": (
        BASE + '\n[find]\nomega = ["1"]\n',
        "scene.toml:21: find.omega: ",
        'link "1" is the ground',
    ),
    "bad-instant-center-pair": (
        BASE + '\n[find]\ninstant_centers = ["123"]\n',
        "scene.toml:21: find.instant_centers: ",
        '"123" is not a pair of links',
    ),
    "same-link-twice": (
        BASE + '\n[find]\ninstant_centers = ["22"]\n',
        "scene.toml:21: find.instant_centers: ",
        "twice",
    ),
    "negative-kv": (BASE + "\n[draw]\nkv = -1\n", "scene.toml:21: draw.kv: ", "-1 is not positive"),
    "given-one-point": (GIVEN_ONE, "scene.toml:4: given: ", "expected at least two"),
    "given-unknown-point": (
        edit(GIVEN_BASE, "[given.B]", "[given.Q]"),
        "scene.toml:8: given.Q: ",
        'no point "Q"',
    ),
    "given-partial-acceleration": (
        edit(GIVEN_BASE, "acceleration = [-2050, 120]\n", ""),
        "scene.toml:8: given.B.acceleration: ",
        "expected acceleration on every given point or on none",
    ),
    "unknown-guess-point": (
        BASE + "\n[guess]\nBB = [1, 2]\n",
        "scene.toml:21: guess.BB: ",
        'did you mean "B"?',
    ),
    "duplicate-slider-name": (
        BASE + '\n[[sliders]]\nblock = "4"\nguide = "1"\npoint = "B"\nline = { through = [0, 0], angle = 0 }\n',
        "scene.toml:20: sliders.2: ",
        'duplicate slider name "14"',
    ),
    "missing-slider-line": (
        edit(BASE, "line = { through = [0, 10], angle = 0 }", ""),
        "scene.toml:9: sliders.1.line: ",
        "missing; expected line = { through",
    ),
    "unknown-input-slider": (
        edit(BASE, 'link = "2"\nangle = 60\nomega = 10\n', 'slider = "41"\ns = 100\ns_dot = 0\n'),
        "scene.toml:16: input.slider: ",
        'no slider "41"; expected one of "14"',
    ),
}


@pytest.mark.parametrize(("text", "prefix", "fragment"), list(BAD_SCENES.values()), ids=list(BAD_SCENES))
def test_bad_scene(text: str, prefix: str, fragment: str) -> None:
    problems = problems_of(text)
    matching = [p for p in problems if p.startswith(prefix)]
    assert matching, problems
    assert any(fragment in p for p in matching), problems


def test_binary_garbage(tmp_path: Path) -> None:
    path = tmp_path / "garbage.toml"
    path.write_bytes(b"title = 1\n\x89PNG\x1a\x00\x00\x00\rIHDR")
    with pytest.raises(SceneError) as caught:
        load_scene(path)
    assert caught.value.problems == [f"{path}:2: (file): binary data (a NUL byte); expected a scene "
                                     ".toml file in UTF-8 text"]


def test_not_utf8(tmp_path: Path) -> None:
    path = tmp_path / "latin1.toml"
    path.write_bytes('[links]\ntitle = "Kurbelschwinge für"\n'.encode("latin-1"))
    with pytest.raises(SceneError) as caught:
        load_scene(path)
    (problem,) = caught.value.problems
    assert problem.startswith(f"{path}:2: (file): not UTF-8 text (byte 0xfc")


def test_missing_file(tmp_path: Path) -> None:
    path = tmp_path / "nowhere.toml"
    with pytest.raises(SceneError) as caught:
        load_scene(path)
    assert caught.value.problems == [f"{path}: (file): no such file; expected the path of a scene .toml file"]


def test_problem_format() -> None:
    (problem,) = problems_of(edit(BASE, 'link = "2"', 'lnik = "2"\nlink = "2"'), "scene.toml")
    assert problem == 'scene.toml:16: input.lnik: unknown key; did you mean "link"?'
    assert re.fullmatch(r"[^:]+:\d+: [\w.]+: .+; .+", problem)


def test_three_problems_in_one_pass() -> None:
    text = edit(BASE, 'title = "test"', 'titel = "test"')
    text = edit(text, 'block = "4"', 'block = "5"')
    text = edit(text, "omega = 10", "omega = nan")
    problems = problems_of(text)
    assert len(problems) == 3, problems
    assert [p.split(":")[1] for p in problems] == ["1", "10", "18"]


def test_second_slider_maps_to_its_own_lines() -> None:
    text = BASE + '\n[[sliders]]\nblock = "3"\nguide = "2"\npoint = "Q"\nline = { through = [0, 0], angle = 0 }\n'
    problems = problems_of(text)
    assert any(p.startswith('scene.toml:23: sliders.2.point: no point "Q"') for p in problems), problems


# --------------------------------------------------------------------------------------------
# Properties

finite = st.floats(allow_nan=False, allow_infinity=False)


def toml_string(text: str) -> str:
    """``text`` as a TOML basic string."""
    out = []
    for char in text:
        if char in '"\\':
            out.append("\\" + char)
        elif ord(char) < 0x20 or ord(char) == 0x7F:
            out.append(f"\\u{ord(char):04x}")
        else:
            out.append(char)
    return '"' + "".join(out) + '"'


@given(px=finite, py=finite, qx=finite, qy=finite)
def test_point_coordinates_round_trip(px: float, py: float, qx: float, qy: float) -> None:
    text = edit(BASE, "A = [40, 0] }", f"A = [40, 0], P = [{px!r}, {py!r}] }}")
    text = edit(text, "A = [120, 0] }", f"A = [120, 0], Q = [{qx!r}, {qy!r}] }}")
    scene = loads_scene(text)
    for got, want in zip(scene.link("2").point("P").local + scene.link("3").point("Q").local, (px, py, qx, qy),
                         strict=True):
        assert math.isclose(got, want, rel_tol=1e-12, abs_tol=0.0)


@given(word=st.text().filter(lambda s: not any(c.isdigit() for c in s)))
def test_string_without_digits_for_a_number_is_a_scene_error(word: str) -> None:
    with pytest.raises(SceneError):
        loads_scene(edit(BASE, "omega = 10", f"omega = {toml_string(word)}"))


@settings(suppress_health_check=[HealthCheck.too_slow])
@given(word=st.text(), where=st.sampled_from(["omega = 10", "angle = 60", "angle = 0 }", "A = [40, 0]"]))
def test_any_string_for_a_number_never_crashes(word: str, where: str) -> None:
    value = toml_string(word)
    replacement = {
        "omega = 10": f"omega = {value}",
        "angle = 60": f"angle = {value}",
        "angle = 0 }": f"angle = {value} }}",
        "A = [40, 0]": f"A = [{value}, 0]",
    }[where]
    try:
        loads_scene(edit(BASE, where, replacement))
    except SceneError as exc:
        assert exc.problems


@given(text=st.text())
def test_any_text_is_a_scene_or_a_scene_error(text: str) -> None:
    try:
        loads_scene(text)
    except SceneError as exc:
        assert all(p.startswith("<string>") for p in exc.problems)


@given(
    lines=st.lists(st.sampled_from(BASE.splitlines() + ["[[sliders]]", "[given.A]", "x = [", "]", '"""', "a.b = 1"]))
)
def test_shuffled_scene_lines_never_crash(lines: list[str]) -> None:
    try:
        loads_scene("\n".join(lines))
    except SceneError as exc:
        assert exc.problems


def test_syntax_error_at_end_of_file_names_the_last_line() -> None:
    (problem,) = problems_of(BASE + "[find]\nvelocity = [\n\n")
    assert problem.startswith("scene.toml:20: find.velocity: TOML syntax error at the end of the file")


def test_inch_lengths_in_a_millimetre_scene() -> None:
    scene = loads_scene(edit(BASE, "A = [40, 0]", 'A = ["1.5 in", "-2 cm"]'))
    assert scene.link("2").point("A").local == pytest.approx((38.1, -20.0), rel=1e-15)


def test_polar_points_on_the_axes_are_exact() -> None:
    scene = loads_scene(edit(BASE, "A = [40, 0]", "A = { polar = [40, 90] }"))
    assert scene.link("2").point("A").local == (0.0, 40.0)


def test_a_point_of_three_links_is_a_compound_hinge_not_a_problem() -> None:
    text = (Path(__file__).parents[2] / "examples" / "toggle-press.toml").read_text()
    scene = loads_scene(text)
    owners = [link.name for link in scene.links if "K" in link.point_names]
    assert owners == ["3", "4", "5"]
