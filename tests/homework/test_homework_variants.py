"""kinepoly variants: every variant solves and passes check against its own key; the same seed gives the same
variants; the assembly and the transmission angle are judged here from the variants' own geometry."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES, four_bar

import kinepoly
from kinepoly.homework import Variant, default_ranges, make_variants


def make(capsys: pytest.CaptureFixture[str], folder: Path, scene: Path | str, *options: str) -> list[Path]:
    code, _, err = run(capsys, "variants", str(scene), "-o", str(folder), *options)
    assert code == 0, err
    return sorted(p for p in folder.glob("*.toml") if not p.name.endswith(".answers.toml"))


@pytest.mark.parametrize("name, count", [("four-bar", 12), ("slider-crank", 12), ("slotted-lever", 12),
                                         ("shaper", 10), ("centers-six-bar", 8), ("triad", 3)])
def test_every_variant_passes_check_against_its_own_key(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                        name: str, count: int) -> None:
    scenes = make(capsys, tmp_path, EXAMPLES / f"{name}.toml", "--n", str(count), "--seed", "7")
    assert [p.name for p in scenes] == [f"{name}-{k:02d}.toml" for k in range(1, count + 1)]
    for scene in scenes:
        key = scene.with_name(scene.stem + ".answers.toml")
        code, out, err = run(capsys, "check", str(scene), str(key))
        assert code == 0, out + err
        assert "score 1.00" in out
        warnings = kinepoly.to_json(kinepoly.solve(kinepoly.load_scene(scene)))["warnings"]
        assert not {w["code"] for w in warnings} & {"default-assembly", "near-singular", "check-failed"}


def test_the_same_seed_gives_the_same_variants() -> None:
    scene = kinepoly.load_scene(EXAMPLES / "slotted-lever.toml")
    first = make_variants(scene, default_ranges(scene), 6, 11)
    again = make_variants(scene, default_ranges(scene), 6, 11)
    other = make_variants(scene, default_ranges(scene), 6, 12)
    assert [v.scene_text for v in first] == [v.scene_text for v in again]
    assert [v.answers_text for v in first] == [v.answers_text for v in again]
    assert [v.scene_text for v in first] != [v.scene_text for v in other]
    assert len({v.scene_text.split("\n", 2)[2] for v in first}) == 6  # six different problems


def positions(scene: kinepoly.Scene) -> dict[str, complex]:
    data = kinepoly.to_json(kinepoly.solve(scene))
    return {label: complex(*entry["position"]) for label, entry in data["points"].items()}


def cross(a: complex, b: complex) -> float:
    return a.real * b.imag - a.imag * b.real


def acute(a: complex, b: complex) -> float:
    angle = abs(math.degrees(math.atan2(cross(a, b), a.real * b.real + a.imag * b.imag)))
    return min(angle, 180.0 - angle)


NEAR_PARALLELOGRAM = four_bar(100, 60, 100, 60, 30, 10, 0, guess_b=(150, 50),
                              find='[find]\nvelocity = ["A", "B"]\nacceleration = ["B"]')


@pytest.mark.parametrize("text", [(EXAMPLES / "four-bar.toml").read_text(), NEAR_PARALLELOGRAM],
                         ids=["example", "near-parallelogram"])
def test_four_bar_variants_stay_in_their_assembly_with_transmission_angles_of_30_degrees(text: str) -> None:
    # near a parallelogram a direct solve often lands in the other assembly: those variants are reached
    # step by step from the original, or dropped
    original = kinepoly.loads_scene(text)
    b0 = complex(*original.link("1").point("B0").local)
    p = positions(original)
    side = cross(b0 - p["A"], p["B"] - p["A"]) > 0
    variants = make_variants(original, default_ranges(original), 20, 3)
    for variant in variants:
        b0 = complex(*variant.scene.link("1").point("B0").local)
        p = positions(variant.scene)
        assert (cross(b0 - p["A"], p["B"] - p["A"]) > 0) == side  # the same assembly
        transmission = acute(p["B"] - p["A"], p["B"] - b0)  # between coupler and rocker
        assert transmission >= 30.0 - 1e-9
        assert variant.min_transmission_deg == pytest.approx(transmission, abs=1e-9)
        assert_key_is_the_loop_equations(variant, p, b0)


def assert_key_is_the_loop_equations(variant: Variant, p: dict[str, complex], b0: complex) -> None:
    """The variant's lengths and input close the loop at its points, and its key solves i w2 r_A + i w3 r_AB =
    i w4 r_B0B (the velocity loop equation, solved here)."""
    scene = variant.scene
    assert isinstance(scene.input, kinepoly.scene.spec.LinkInput)
    length = {k: abs(complex(*scene.link(k).point(q).local) - complex(*scene.link(k).point(o).local))
              for k, o, q in (("2", "A0", "A"), ("3", "A", "B"), ("4", "B0", "B"))}
    assert abs(p["A"]) == pytest.approx(length["2"]) and abs(p["B"] - p["A"]) == pytest.approx(length["3"])
    assert abs(p["B"] - b0) == pytest.approx(length["4"])
    assert math.degrees(math.atan2(p["A"].imag, p["A"].real)) % 360 == pytest.approx(
        math.degrees(scene.input.angle_rad) % 360)
    w2 = scene.input.omega
    r_ab, r_bb = p["B"] - p["A"], p["B"] - b0
    rhs = -1j * w2 * p["A"]
    m = [[(1j * r_ab).real, (-1j * r_bb).real], [(1j * r_ab).imag, (-1j * r_bb).imag]]
    det = m[0][0] * m[1][1] - m[0][1] * m[1][0]
    w3 = (rhs.real * m[1][1] - m[0][1] * rhs.imag) / det
    w4 = (m[0][0] * rhs.imag - m[1][0] * rhs.real) / det
    derived = {"omega_3": w3, "omega_4": w4, "v_B": 1j * w4 * r_bb, "v_A": 1j * w2 * p["A"]}
    key = {k.text: value for k, value in variant.answers}
    checked = [name for name in derived if name in key]
    assert checked
    for name in checked:
        got = key[name]
        value = complex(*got) if isinstance(got, tuple) else got
        assert abs(value - derived[name]) <= 1e-9 * max(1.0, abs(derived[name]))


def test_slider_crank_variants_keep_the_block_ahead_and_the_coupler_near_the_slide() -> None:
    original = kinepoly.load_scene(EXAMPLES / "slider-crank.toml")
    p = positions(original)
    ahead = (p["B"] - p["A"]).real > 0
    for variant in make_variants(original, default_ranges(original), 20, 5):
        p = positions(variant.scene)
        coupler = p["B"] - p["A"]
        assert (coupler.real > 0) == ahead
        assert acute(coupler, 1 + 0j) <= 60.0 + 1e-9  # the coupler's normal and the slide cross at 30 deg or more


def test_ranges_from_vary_and_options(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = (EXAMPLES / "four-bar.toml").read_text() + (
        '\n[vary]\nangle = [40, 50]\nomega = ["48 rpm", "48 rpm"]\nalpha = [0, 0]\nlengths = [0.8, 1.2]\n'
        'links = { "1" = [1, 1], "3" = [1, 1] }\n')
    scene_path = tmp_path / "bar.toml"
    scene_path.write_text(text)
    assert run(capsys, "solve", str(scene_path))[0] == 0  # the loader accepts [vary]
    for path in make(capsys, tmp_path / "a", scene_path, "--n", "8"):
        scene = kinepoly.load_scene(path)
        assert isinstance(scene.input, kinepoly.scene.spec.LinkInput)
        assert 40 <= math.degrees(scene.input.angle_rad) <= 50 and scene.input.alpha == 0
        assert scene.input.omega == pytest.approx(5.0)  # 48 rpm = 5.03 rad/s, rounded to two digits
        assert scene.link("1").point("B0").local == (100, 0) and scene.link("3").point("B").local == (120, 0)
        assert 0.8 * 40 - 0.5 <= scene.link("2").point("A").local[0] <= 1.2 * 40 + 0.5
    for path in make(capsys, tmp_path / "b", scene_path, "--n", "4", "--angle", "70,75", "--lengths", "1,1"):
        scene = kinepoly.load_scene(path)
        assert isinstance(scene.input, kinepoly.scene.spec.LinkInput)
        assert 70 <= math.degrees(scene.input.angle_rad) <= 75
        assert scene.link("2").point("A").local == (40, 0)


def test_a_slider_input_varies_s(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = (EXAMPLES / "slider-crank.toml").read_text().split("[input]")[0] + (
        '[input]\nslider = "14"\ns = 130\ns_dot = -500\n[guess]\nA = [20, 35]\n'
        '[find]\nvelocity = ["A", "C"]\nomega = ["3", "2"]\n[vary]\ns = [120, 140]\ns_dot = [-600, -400]\n')
    scene_path = tmp_path / "driven.toml"
    scene_path.write_text(text)
    for path in make(capsys, tmp_path / "out", scene_path, "--n", "5", "--seed", "1"):
        scene = kinepoly.load_scene(path)
        assert isinstance(scene.input, kinepoly.scene.spec.SliderInput)
        assert 120 - 1 <= scene.input.s <= 140 + 1 and -600 <= scene.input.s_dot <= -400
        key = path.with_name(path.stem + ".answers.toml")
        assert run(capsys, "check", str(path), str(key))[0] == 0


BAD_VARY = [
    ("[vary]\nangel = [1, 2]\n", "vary.angel", 'did you mean "angle"?'),
    ("[vary]\nangle = [50, 40]\n", "vary.angle", "runs backwards"),
    ("[vary]\nangle = 40\n", "vary.angle", "expected a range [low, high]"),
    ("[vary]\nomega = [1, \"x\"]\n", "vary.omega", "expected an angular velocity"),
    ("[vary]\nlengths = [0, 1]\n", "vary.lengths", "is not above 0"),
    ("[vary]\nlinks = { \"9\" = [1, 1] }\n", "vary.links.9", 'no link "9"'),
    ("[vary]\ns = [1, 2]\n", "vary.s", "not a key for a link input"),
]


@pytest.mark.parametrize("vary, where, what", BAD_VARY, ids=[b[0] for b in BAD_VARY])
def test_a_bad_vary_table_names_file_line_and_key(capsys: pytest.CaptureFixture[str], tmp_path: Path, vary: str,
                                                  where: str, what: str) -> None:
    text = (EXAMPLES / "four-bar.toml").read_text()
    line = text.count("\n") + 2  # [vary] opens the line after the scene, its key is on the next
    path = tmp_path / "s.toml"
    path.write_text(text + vary)
    code, out, err = run(capsys, "variants", str(path), "-o", str(tmp_path / "out"))
    assert code == 2 and out == "" and "Traceback" not in err
    assert f"{path}:{line}: {where}: " in err and what in err
    assert not (tmp_path / "out").exists()


def test_the_loader_checks_that_vary_is_a_table(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = tmp_path / "s.toml"
    path.write_text("vary = 3\n" + (EXAMPLES / "four-bar.toml").read_text())
    code, _, err = run(capsys, "solve", str(path))
    assert code == 2 and f"{path}:1: vary: expected a [vary] table" in err


def test_variants_that_cannot_be_made(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    out = str(tmp_path / "out")
    code, _, err = run(capsys, "variants", str(EXAMPLES / "image-point.toml"), "-o", out)
    assert code == 2 and "[given] scene" in err
    short = tmp_path / "short.toml"  # coupler 12 and rocker 8 cannot span the 60 to 140 mm from A to B0
    short.write_text((EXAMPLES / "four-bar.toml").read_text()
                     + '[vary]\nlinks = { "3" = [0.1, 0.1], "4" = [0.1, 0.1] }\n')
    code, _, err = run(capsys, "variants", str(short), "-o", out, "--n", "2")
    assert code == 3 and "only 0 of 2 variants in 120 draws" in err
    for bad in (["--angle", "x"], ["--angle", "5,1"], ["--n", "0"], ["--min-transmission", "95"]):
        code, _, err = run(capsys, "variants", str(EXAMPLES / "four-bar.toml"), "-o", out, *bad)
        assert code == 2 and err.startswith("kinepoly: error: ") and "Traceback" not in err
    assert not Path(out).exists()
