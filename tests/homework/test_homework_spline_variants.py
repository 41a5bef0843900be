"""Variants and kinepoly check of spline cam scenes (``[[cams]]`` with a ``points`` profile).

A variant keeps its ``[[cams]]`` table with the profile's points, scaled with the cam as a circle's centre
and radius are (one factor for the whole curve); it loads, solves and its own key passes check. The keys
are checked against the bench's 50-digit reference of the variant as written (the spline rebuilt in
mpmath, ``bench.spline_pairs``: no engine code), and the lengths round-trip through the writer.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.cli_support import run
from tests.homework.test_homework_higher_pairs import _key, _variants
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.bench.reference import reference_values
from kinepoly.homework.higher_pairs import as_written, pair_lengths, with_pair_lengths
from kinepoly.homework.toml_out import scene_toml
from kinepoly.scene.loader import loads_scene

SPLINE_EXAMPLES = ("spline-cam-knife", "spline-cam-roller-rocker", "spline-cam-flat-rocker")


@pytest.mark.parametrize("name", SPLINE_EXAMPLES)
def test_a_spline_cam_variant_keeps_its_scaled_profile_solves_and_passes_check(
        name: str, capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    original = kinepoly.load_scene(EXAMPLES / f"{name}.toml").cams[0]
    files = _variants(capsys, tmp_path, name, "--n", "3", "--seed", "4", "--lengths", "0.8,1.2")
    assert len(files) == 3
    factors = []
    for path in files:
        text = path.read_text()
        assert "profile = { points = [" in text and "circle" not in text
        cam = kinepoly.load_scene(path).cams[0]
        assert cam.is_spline and len(cam.profile_points) == len(original.profile_points)
        assert (cam.kind, cam.point, cam.roller_radius == 0) == (original.kind, original.point,
                                                                 original.roller_radius == 0)
        # one factor for the whole curve: each point is the original's times it, to the written rounding
        ratios = [math.hypot(*p) / math.hypot(*q) for p, q in zip(cam.profile_points, original.profile_points,
                                                                   strict=True)]
        assert max(ratios) - min(ratios) < 2e-3  # the points keep two more decimals than other lengths
        factors.append(sum(ratios) / len(ratios))
        assert kinepoly.solve(kinepoly.load_scene(path)).inside is not None
        code, out, err = run(capsys, "check", str(path), str(path.with_name(path.stem + ".answers.toml")))
        assert code == 0, out + err
        assert "correct" in out and "wrong" not in out
    assert max(factors) - min(factors) > 0.01  # the profiles really were drawn apart


@pytest.mark.parametrize("name", ["spline-cam-knife", "spline-cam-roller-rocker"])
def test_the_variants_keys_are_the_splines_exact_motion(name: str, capsys: pytest.CaptureFixture[str],
                                                        tmp_path: Path) -> None:
    for path in _variants(capsys, tmp_path, name, "--n", "2", "--seed", "9"):
        solution = kinepoly.solve(kinepoly.load_scene(path))
        assert solution.inside is not None
        keys = ["points.W.velocity", "points.W.acceleration"]
        ref = reference_values(solution.inside.mechanism, solution.inside.pose, keys,
                               origin=solution.inside.frame.origin).values
        key = _key(path)
        for answer, quantity in (("v_W", keys[0]), ("a_W", keys[1])):
            exact = [float(x) for x in ref[quantity]]
            size = math.hypot(*exact)
            assert math.hypot(key[answer][0] - exact[0], key[answer][1] - exact[1]) <= 1e-5 * size + 1e-9


@pytest.mark.parametrize("name", SPLINE_EXAMPLES)
def test_a_spline_scene_is_written_with_its_points_and_reads_back_the_same(name: str) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    again = loads_scene(scene_toml(scene), "again.toml")
    assert [c.profile_points for c in again.cams] == [c.profile_points for c in scene.cams]
    assert [(c.kind, c.point, c.roller_radius, c.flat) for c in again.cams] == [
        (c.kind, c.point, c.roller_radius, c.flat) for c in scene.cams]


@settings(max_examples=20, deadline=None)
@given(factor=st.floats(0.5, 2.0), name=st.sampled_from(SPLINE_EXAMPLES))
def test_the_profiles_points_are_the_cams_lengths_in_order(factor: float, name: str) -> None:
    scene = as_written(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    lengths = pair_lengths(scene)
    cam = scene.cams[0]
    flat = [x for p in cam.profile_points for x in p]
    assert list(lengths[:len(flat)]) == flat
    scaled = with_pair_lengths(scene, [factor * x for x in lengths])
    assert scaled.cams[0].profile_points == tuple((factor * x, factor * y) for x, y in cam.profile_points)
    assert scaled.cams[0].roller_radius == factor * cam.roller_radius
    assert pair_lengths(scaled) == tuple(factor * x for x in lengths)
