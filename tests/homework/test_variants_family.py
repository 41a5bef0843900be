"""kinepoly variants judges its draws through the family engine (``homework.variants._judged``): every draw ends
as the path of solves from the original (``_reach``, the judge of scenes with cams) would end it, the same draws
accepted and the same variants written, on drawn seeds, ranges and least transmission angles."""

from __future__ import annotations

import random

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.homework import variants
from kinepoly.homework.higher_pairs import as_written
from kinepoly.homework.vary import Range, Ranges, default_ranges

FAMILY_SCENES = ("four-bar", "slider-crank", "slotted-lever", "scotch-yoke", "shaper", "centers-six-bar",
                 "toggle-press", "dump-body", "motor-on-coupler", "five-bar")


def _written(scene: kinepoly.Scene, numbers: variants._Numbers, reached: variants.Guess,
             original: variants._Solved, least: float) -> str | None:
    made = variants._written(scene, "v-01", 1, numbers, reached, "a variant", original, least)
    return None if made is None else made.scene_text + made.answers_text


def _by_the_path(scene: kinepoly.Scene, numbers: variants._Numbers, original: variants._Solved,
                 least: float) -> str | None:
    """The draw as the path of solves alone makes it (None: rejected)."""
    solved = variants._reach(scene, variants._numbers(scene), numbers, original)
    if solved is None or not variants._is_good(solved, original, least):
        return None
    return _written(scene, numbers, solved.guess(), original, least)


def _by_the_family(scene: kinepoly.Scene, numbers: variants._Numbers, verdict: variants.Verdict,
                   original: variants._Solved, least: float) -> str | None:
    """The draw as ``make_variants`` makes it from the family's verdict."""
    if verdict is False:
        return None
    if verdict is None:
        return _by_the_path(scene, numbers, original, least)
    return _written(scene, numbers, verdict, original, least)


@pytest.mark.parametrize("name", FAMILY_SCENES)
def test_the_family_judges_the_examples_without_cams(name: str) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    original = variants._solved(scene)
    assert original is not None
    assert variants._family(as_written(scene), original) is not None


@pytest.mark.parametrize("name", ["cam-roller-rocker", "gear-pair", "triad", "kc0-six-bar", "crank-rocker-cylinder"])
def test_cams_gears_and_newton_groups_keep_the_path_of_solves(name: str) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    original = variants._solved(scene)
    assert original is not None
    assert variants._family(as_written(scene), original) is None


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(FAMILY_SCENES), seed=st.integers(0, 10**6), low=st.floats(0.6, 1.0),
       high=st.floats(1.0, 1.4), least=st.sampled_from([0.0, 20.0, 30.0, 45.0, 60.0]))
def test_the_family_ends_every_draw_as_the_path_of_solves_does(name: str, seed: int, low: float, high: float,
                                                               least: float) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    original = variants._solved(scene)
    assert original is not None
    scene = as_written(scene)
    family = variants._family(scene, original)
    assert family is not None
    ranges = default_ranges(scene)
    ranges = Ranges({link: Range(low, high) for link in ranges.factors}, ranges.inputs)
    rng = random.Random(seed)
    batch = [variants._draw(rng, scene, ranges) for _ in range(6)]
    verdicts = variants._judged(family, scene, batch, least)
    for numbers, verdict in zip(batch, verdicts, strict=True):
        old = _by_the_path(scene, numbers, original, least)
        assert _by_the_family(scene, numbers, verdict, original, least) == old
        if verdict is False:
            assert old is None  # a draw the family rejects, the path rejects


def test_a_draw_whose_direct_solve_lands_in_the_other_assembly_is_left_to_the_path() -> None:
    """The shaper with its lengths 0.7 to 1.3: a direct solve from the original's pose lands a draw in the other
    assembly of a dyad; the family weighs the two as the solve does and leaves it to the path of solves, which
    reaches it, so the variant is the path's."""
    scene = as_written(kinepoly.load_scene(EXAMPLES / "shaper.toml"))
    original = variants._solved(scene)
    assert original is not None
    family = variants._family(scene, original)
    assert family is not None
    ranges = default_ranges(scene)
    ranges = Ranges({link: Range(0.7, 1.3) for link in ranges.factors}, ranges.inputs)
    rng = random.Random(1)
    batch = [variants._draw(rng, scene, ranges) for _ in range(200)]
    verdicts = variants._judged(family, scene, batch, 30.0)
    elsewhere = []
    for numbers, verdict in zip(batch, verdicts, strict=True):
        direct = variants._solved(variants._scene(scene, numbers, original.guess()))
        if direct is not None and direct.signature != original.signature:
            elsewhere.append((numbers, verdict))
    assert elsewhere
    for numbers, verdict in elsewhere:
        assert verdict is None or verdict is False
        old = _by_the_path(scene, numbers, original, 30.0)
        assert _by_the_family(scene, numbers, verdict, original, 30.0) == old


DRIVEN_SLIDER_CRANK = (EXAMPLES / "slider-crank.toml").read_text().split("[input]")[0] + (
    '[input]\nslider = "14"\ns = 130\ns_dot = -500\n[guess]\nA = [20, 35]\n'
    '[find]\nvelocity = ["A", "C"]\nomega = ["3", "2"]\n')


@pytest.mark.parametrize("name, lengths, least, seed", [
    ("four-bar", (0.7, 1.3), 45.0, 3), ("centers-six-bar", (0.7, 1.3), 40.0, 5), ("shaper", (0.6, 1.4), 30.0, 1),
    ("toggle-press", (0.5, 1.5), 30.0, 2), ("driven slider-crank", (0.8, 1.2), 30.0, 4)])
def test_make_variants_writes_what_the_path_of_solves_writes(monkeypatch: pytest.MonkeyPatch, name: str,
                                                             lengths: tuple[float, float], least: float,
                                                             seed: int) -> None:
    scene = (kinepoly.loads_scene(DRIVEN_SLIDER_CRANK, "driven.toml") if name == "driven slider-crank"
             else kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    ranges = default_ranges(scene)
    ranges = Ranges({link: Range(*lengths) for link in ranges.factors}, ranges.inputs)
    original = variants._solved(scene)
    assert original is not None and variants._family(as_written(scene), original) is not None
    made = variants.make_variants(scene, ranges, 8, seed, min_transmission_deg=least)
    monkeypatch.setattr(variants, "_family", lambda *_: None)
    alone = variants.make_variants(scene, ranges, 8, seed, min_transmission_deg=least)
    assert [(v.scene_text, v.answers_text) for v in made] == [(v.scene_text, v.answers_text) for v in alone]


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(FAMILY_SCENES), seed=st.integers(0, 10**6), which=st.integers(0, 1))
def test_the_family_weighs_the_assemblies_as_a_direct_solve_does(name: str, seed: int, which: int) -> None:
    """From a pose of the other assembly of one dyad (its inner joint mirrored), a direct solve lands some draws
    there: the family leaves every such draw to the path of solves, and what it reaches itself is the direct
    solve's pose."""
    import msgspec
    import numpy as np

    scene = as_written(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    original = variants._solved(scene)
    assert original is not None
    family = variants._family(scene, original)
    assert family is not None
    dyad = family.dyads[which % len(family.dyads)]
    start = variants._numbers(scene)
    own = np.array([start.inputs[0][1]])
    mirrored = family.placer.place(variants._dimensions(scene, [start]), own, frozenset({dyad.name}))
    if not mirrored.ok[0]:
        return
    away = tuple((n, (float(mirrored.point(n)[0].real), float(mirrored.point(n)[0].imag))) for n, _ in family.guess)
    weighed = msgspec.structs.replace(family, guess=away)
    ranges = default_ranges(scene)
    ranges = Ranges({link: Range(0.95, 1.05) for link in ranges.factors}, ranges.inputs)
    rng = random.Random(seed)
    batch = [variants._draw(rng, scene, ranges) for _ in range(8)]
    for numbers, verdict in zip(batch, variants._judged(weighed, scene, batch, 0.0), strict=True):
        direct = variants._solved(variants._scene(scene, numbers, away))
        if direct is None or direct.signature != original.signature:
            assert verdict is None or verdict is False
        elif verdict:
            size = variants._size(scene)
            points = dict(direct.guess())
            assert all(abs(complex(*points[n]) - complex(*xy)) <= 1e-9 * size for n, xy in verdict)
