"""Variants and kinepoly check of scenes with gears and cams.

A variant is written with its ``[[gears]]`` and ``[[cams]]`` as the user wrote them (never the
cams' equivalent links); its gear pairs' centres stay r2 + r3 (|r2 - r3|) apart; it solves, and its
own key passes check. The keys are also checked here against closed forms read off the written
text: the gear ratio -r2/r3, Willis' formula, the flat face's harmonic lift e omega cos(theta).
"""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path
from typing import Any

import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES, cam_rocker

import kinepoly
from kinepoly.homework import default_ranges, make_variants
from kinepoly.homework.higher_pairs import as_written
from kinepoly.homework.toml_out import scene_toml
from kinepoly.scene.loader import loads_scene

HIGHER_PAIRS = ("gear-pair", "planetary", "rack-pinion", "eccentric-cam-flat", "cam-roller-rocker", "metu-cam",
                "curve-on-curve", "spline-on-spline")


def _variants(capsys: pytest.CaptureFixture[str], folder: Path, name: str, *options: str) -> list[Path]:
    code, out, err = run(capsys, "variants", str(EXAMPLES / f"{name}.toml"), "-o", str(folder), *options)
    assert code == 0, out + err
    return sorted(p for p in folder.glob("*.toml") if not p.name.endswith(".answers.toml"))


def _key(scene: Path) -> dict[str, Any]:
    return tomllib.loads(scene.with_name(scene.stem + ".answers.toml").read_text())


def _centre_distance(table: dict[str, Any], a: str, b: str) -> float:
    """The distance of the points ``a`` and ``b`` on a link that holds both (the one that fixes it)."""
    for link in table["links"].values():
        if a in link["points"] and b in link["points"]:
            return math.dist(link["points"][a], link["points"][b])
    raise AssertionError(f"no link holds both {a} and {b}")


@pytest.mark.parametrize("name", HIGHER_PAIRS)
def test_variants_keep_the_pairs_as_written_and_pass_check(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                           name: str) -> None:
    original = tomllib.loads((EXAMPLES / f"{name}.toml").read_text())
    scenes = _variants(capsys, tmp_path, name, "--n", "4", "--seed", "3")
    assert len(scenes) == 4
    for scene in scenes:
        table = tomllib.loads(scene.read_text())
        assert sorted(table["links"]) == sorted(original["links"])  # no equivalent link written
        assert len(table.get("gears", [])) == len(original.get("gears", []))
        assert len(table.get("cams", [])) == len(original.get("cams", []))
        assert len(table.get("sliders", [])) == len(original.get("sliders", []))
        for gear in table.get("gears", []):
            one, two = gear["pitch"]
            if "center" in one and "center" in two:
                expected = abs(one["radius"] - two["radius"]) if gear.get("internal") else one["radius"] + two["radius"]
                assert _centre_distance(table, one["center"], two["center"]) == pytest.approx(expected, rel=1e-12)
        code, out, err = run(capsys, "check", str(scene), str(scene.with_name(scene.stem + ".answers.toml")))
        assert code == 0 and "score 1.00" in out, out + err


def test_gear_pair_variants_keep_the_ratio(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    for scene in _variants(capsys, tmp_path, "gear-pair", "--n", "5", "--seed", "5"):
        table, key = tomllib.loads(scene.read_text()), _key(scene)
        r2, r3 = (p["radius"] for p in table["gears"][0]["pitch"])
        omega2, alpha2 = table["input"]["omega"], table["input"]["alpha"]
        assert key["omega_3"] == pytest.approx(-omega2 * r2 / r3, rel=1e-5)
        assert key["alpha_3"] == pytest.approx(-alpha2 * r2 / r3, rel=1e-5, abs=1e-9)


def test_planetary_variants_obey_willis(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    # sun fixed: (w3 - w2) / (0 - w2) = -r_sun / r_planet, (w4 - w2) / (0 - w2) = -r_sun / r_ring
    for scene in _variants(capsys, tmp_path, "planetary", "--n", "4", "--seed", "2"):
        table, key = tomllib.loads(scene.read_text()), _key(scene)
        sun, planet = (p["radius"] for p in table["gears"][0]["pitch"])
        ring = table["gears"][1]["pitch"][1]["radius"]
        assert ring == pytest.approx(sun + 2 * planet, rel=1e-12)
        w2 = table["input"]["omega"]
        assert key["omega_3"] == pytest.approx(w2 * (1 + sun / planet), rel=1e-5)
        assert key["omega_4"] == pytest.approx(w2 * (1 + sun / ring), rel=1e-5)


def test_flat_face_variants_lift_harmonically(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    # the disc's centre K = e (cos t, sin t) (e its distance from the pivot, along the cam's x-axis): the face
    # on the vertical guide through the pivot rises at e omega cos(t) (the face's points all move with it)
    for scene in _variants(capsys, tmp_path, "eccentric-cam-flat", "--n", "4", "--seed", "9"):
        table, key = tomllib.loads(scene.read_text()), _key(scene)
        cx, cy = table["cams"][0]["profile"]["circle"]["center"]
        assert cy == 0
        t = math.radians(table["input"]["angle"])
        rise = cx * table["input"]["omega"] * math.cos(t)
        assert key["v_T"] == pytest.approx([0.0, rise], rel=1e-5, abs=1e-4 * abs(cx * table["input"]["omega"]))


def test_gears_keep_their_dimensions_when_the_links_share_no_factor(capsys: pytest.CaptureFixture[str],
                                                                    tmp_path: Path) -> None:
    scene = kinepoly.load_scene(EXAMPLES / "gear-pair.toml")
    ranges = default_ranges(scene)
    ranges = type(ranges)({**ranges.factors, "1": type(ranges.factors["1"])(1.0, 1.0),
                           "2": type(ranges.factors["1"])(1.2, 1.3)}, ranges.inputs)
    for variant in make_variants(scene, ranges, 3, 1):
        table = tomllib.loads(variant.scene_text)
        assert [p["radius"] for p in table["gears"][0]["pitch"]] == [40, 60]
        assert table["links"]["1"]["points"] == {"O2": [0, 0], "O3": [100, 0]}


def test_a_loaded_cam_scene_is_written_with_its_cams_not_its_equivalent_links() -> None:
    scene = kinepoly.load_scene(EXAMPLES / "cam-roller-rocker.toml")
    assert scene.equivalent_links  # the loader replaced the cam
    text = scene_toml(scene)
    assert "eq23" not in text and "K23" not in text
    assert ('[[cams]]\ncam = "2"\nfollower = "3"\nprofile = { circle = { center = [15, 0], radius = 40 } }\n'
            'roller = { center = "W", radius = 10 }\n') in text
    written = as_written(scene)
    assert [link.name for link in written.links] == ["1", "2", "3"]
    assert [p.name for p in written.link("2").points] == ["O"]  # the disc's centre the loader added is gone
    again = loads_scene(text)
    assert [(c.center, c.radius, c.roller_radius, c.point) for c in again.cams] == [((15.0, 0.0), 40.0, 10.0, "W")]


def test_check_names_a_reversed_gear_ratio(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    scene = _variants(capsys, tmp_path, "gear-pair", "--n", "1", "--seed", "4")[0]
    key = scene.with_name(scene.stem + ".answers.toml")
    given = _key(scene)
    wrong = tmp_path / "wrong.toml"
    wrong.write_text(f"omega_3 = {-given['omega_3']!r}\nalpha_3 = {given['alpha_3']!r}\n")
    code, out, _ = run(capsys, "check", str(scene), str(wrong))
    assert code == 1
    assert re.search(r"^omega_3 +wrong", out, re.MULTILINE) and re.search(r"^alpha_3 +correct", out, re.MULTILINE)
    assert "sign-reversed" in out
    assert run(capsys, "check", str(scene), str(key))[0] == 0


def test_check_marks_answers_derived_by_hand_on_a_gear_and_a_cam(capsys: pytest.CaptureFixture[str],
                                                                 tmp_path: Path) -> None:
    # gear-pair.toml: r2 = 40, r3 = 60, theta2 = 20 deg, omega 12, alpha 1; theta3 = 180 - 20 r2/r3 (phases 0);
    # E 45 from O3 = (100, 0); I23 the pitch point (40, 0)
    ratio = 40.0 / 60.0
    theta3 = math.radians(180.0 - 20.0 * ratio)
    w3, a3 = -12.0 * ratio, -1.0 * ratio
    arm = 45.0 * complex(math.cos(theta3), math.sin(theta3))
    v, a = w3 * 1j * arm, (a3 * 1j - w3 * w3) * arm
    gears = tmp_path / "gears.answers.toml"
    gears.write_text(f"omega_3 = {w3!r}\nalpha_3 = {a3!r}\nv_E = [{v.real!r}, {v.imag!r}]\n"
                     f"a_E = [{a.real!r}, {a.imag!r}]\nI_23 = [40, 0]\n")
    code, out, err = run(capsys, "check", str(EXAMPLES / "gear-pair.toml"), str(gears))
    assert code == 0 and "5 of 5 correct" in out, out + err
    # eccentric-cam-flat.toml: e = 12, R = 35, theta = 40 deg, omega 15; the face (and T, S) at
    # y = e sin(theta) + R on the vertical guide through O; I23 on the horizontal through O (I13 at infinity)
    # under the disc's centre, where the common normal (vertical through K) crosses it
    e, big_r, t, w = 12.0, 35.0, math.radians(40.0), 15.0
    rise, lift = e * w * math.cos(t), -e * w * w * math.sin(t)
    cam = tmp_path / "cam.answers.toml"
    cam.write_text(f"v_T = [0, {rise!r}]\na_T = [0, {lift!r}]\nv_S = [0, {rise!r}]\na_S = [0, {lift!r}]\n"
                   f"s_13 = {e * math.sin(t) + big_r!r}\ns_dot_13 = {rise!r}\ns_ddot_13 = {lift!r}\n"
                   f"I_23 = [{e * math.cos(t)!r}, 0]\n")
    code, out, err = run(capsys, "check", str(EXAMPLES / "eccentric-cam-flat.toml"), str(cam))
    assert code == 0 and "8 of 8 correct" in out, out + err
    cam.write_text(f"v_T = [0, {-rise!r}]\n")  # the follower said to fall while it rises
    code, out, _ = run(capsys, "check", str(EXAMPLES / "eccentric-cam-flat.toml"), str(cam))
    assert code == 1 and re.search(r"^v_T +wrong", out, re.MULTILINE)


@pytest.mark.parametrize("follower, line", [("knife", 'knife = "W"'), ("inside", 'contact = "inside"')])
def test_variants_write_a_knife_edge_and_a_roller_in_a_groove(follower: str, line: str) -> None:
    scene = loads_scene(cam_rocker(follower), f"{follower}.toml")
    for variant in make_variants(scene, default_ranges(scene), 3, 2):
        assert line in variant.scene_text and "eq23" not in variant.scene_text
        again = loads_scene(variant.scene_text)
        cam = again.cams[0]
        assert (cam.kind, cam.inside) == (("knife", False) if follower == "knife" else ("roller", True))
        w = complex(*kinepoly.to_json(kinepoly.solve(again))["points"]["W"]["position"])
        theta = again.input.angle_rad  # type: ignore[union-attr]
        k = complex(*cam.center) * complex(math.cos(theta), math.sin(theta))  # the cam turns about O = (0, 0)
        reach = cam.radius - cam.roller_radius if cam.inside else cam.radius  # W's distance from the disc's centre
        assert abs(abs(w - k) - reach) < 1e-9 * reach
