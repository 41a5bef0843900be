"""A geared mechanism's default sweep covers its whole cycle: the turns of the input after which every gear
has turned a whole number of times and the mechanism is back where it started."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinepoly
from kinepoly.sweep import SweepResult, sweep

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _codes(result: SweepResult) -> list[str]:
    return [notice.code for notice in result.notices]


def test_the_geared_five_bar_sweeps_two_turns_and_its_coupler_curve_closes() -> None:
    # gears 30 and 60: link 5 turns -1/2 of a turn per turn of the input, so the five-bar repeats after 720
    scene = kinepoly.load_scene(EXAMPLES / "geared-five-bar.toml")
    result = sweep(scene, steps=360)
    x = result.input.values
    assert x[0] == 0.0 and x[-1] == pytest.approx(720.0 - 2.0)
    assert result.periodic and "cycle" in _codes(result)
    assert (result.status == 0).all()
    # link 5 rolls on link 2: theta_5 = -theta_2 / 2 (both 0 at the reference mesh), derived here
    theta5 = result.column("theta_5").values
    assert np.max(np.abs(np.remainder(theta5 + x / 2.0 + 180.0, 360.0) - 180.0)) < 1e-9
    # explicit rows at 0, 360 and 720: the curve closes at 720, not at 360
    rows = sweep(scene, steps=8, start=0.0, stop=720.0)
    assert list(rows.input.values) == [0.0, 90.0, 180.0, 270.0, 360.0, 450.0, 540.0, 630.0, 720.0]
    for point in ("P", "B"):
        at = rows.column(f"r_{point}_x").values + 1j * rows.column(f"r_{point}_y").values
        assert abs(at[8] - at[0]) < 1e-9 * 100.0
        assert abs(at[4] - at[0]) > 1.0
    for column in ("theta_3", "theta_4", "omega_3", "alpha_4"):
        values = rows.column(column).values
        assert values[8] == pytest.approx(values[0], rel=1e-9, abs=1e-9)


def test_a_fine_default_sweep_covers_the_cycle_too() -> None:
    # 3600 rows or more take a quicker way to a full turn when the mechanism turns fully: not with gears
    result = sweep(kinepoly.load_scene(EXAMPLES / "geared-five-bar.toml"), steps=3600)
    assert result.input.values[-1] == pytest.approx(720.0 - 0.2)


def test_the_default_sweep_of_the_five_bar_meets_the_explicit_one() -> None:
    # the default rows of the cycle are the rows of --from 0 --to 720 (both ends; the end left out by default)
    scene = kinepoly.load_scene(EXAMPLES / "geared-five-bar.toml")
    default = sweep(scene, steps=72)
    explicit = sweep(scene, steps=72, start=0.0, stop=720.0)
    assert np.array_equal(default.input.values, explicit.input.values[:-1])
    for name in ("r_P_x", "r_P_y", "theta_5", "alpha_3"):
        assert np.max(np.abs(default.column(name).values - explicit.column(name).values[:-1])) < 1e-9


@pytest.mark.parametrize(("name", "turns"), [("gear-pair", 3), ("planetary", 14), ("planetary-free-arm", 20),
                                              ("differential", 20)])
def test_the_cycle_is_the_least_common_multiple_of_the_gear_ratios(name: str, turns: int) -> None:
    # gear pair 40 / 60: link 3 turns -2/3 per turn -> 3 turns. Planetary (sun 30 fixed, planet 20, ring 70, arm
    # input): planet 1 + 30/20 = 5/2, ring 1 + 30/70 = 10/7 -> lcm(2, 7) = 14. Ring fixed, sun input: arm
    # 30/100 = 3/10, planet -3/4 -> lcm(10, 4) = 20; the differential, its first input turning, the same
    result = sweep(kinepoly.load_scene(EXAMPLES / f"{name}.toml"), steps=turns * 4)
    x = result.input.values
    assert x[-1] + (x[1] - x[0]) == pytest.approx(360.0 * turns)
    assert "cycle" in _codes(result)


def _pair(r2: float, r3: float) -> str:
    return f"""
title = "gears"
input = {{ link = "2", angle = 10, omega = 5, alpha = 0 }}
[links]
1 = {{ points = {{ O2 = [0, 0], O3 = [{r2 + r3!r}, 0] }} }}
2 = {{ points = {{ O2 = [0, 0] }} }}
3 = {{ points = {{ O3 = [0, 0], E = [{r3 / 2!r}, 0] }} }}
[[gears]]
links = ["2", "3"]
pitch = [{{ center = "O2", radius = {r2!r} }}, {{ center = "O3", radius = {r3!r} }}]
"""


def test_no_cycle_within_the_bound_is_said_and_one_turn_swept() -> None:
    # radii 30 and 30 pi / 2: link 3 turns -2 / pi per turn, no fraction with a denominator up to 100
    result = sweep(kinepoly.loads_scene(_pair(30.0, 15.0 * math.pi)), steps=36)
    assert result.input.values[-1] == pytest.approx(350.0)
    assert "no-cycle" in _codes(result)
    # 30 and 30 x 101 / 100: 101 turns, beyond the bound
    result = sweep(kinepoly.loads_scene(_pair(30.0, 30.3)), steps=36)
    assert result.input.values[-1] == pytest.approx(350.0)
    assert "no-cycle" in _codes(result)


def test_a_rack_never_comes_back_and_a_linkage_without_gears_sweeps_one_turn() -> None:
    rack = sweep(kinepoly.load_scene(EXAMPLES / "rack-pinion.toml"), steps=36)
    assert rack.input.values[-1] == pytest.approx(350.0) and "no-cycle" in _codes(rack)
    plain = sweep(kinepoly.load_scene(EXAMPLES / "four-bar.toml"), steps=36)
    assert plain.input.values[-1] == pytest.approx(350.0) and not plain.notices


def test_the_commands_take_their_default_positions_per_turn_of_the_cycle(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from tests.cli_support import run

    from kinepoly.sweep import cycle_turns, prepare_sweep

    five_bar = kinepoly.load_scene(EXAMPLES / "geared-five-bar.toml")
    assert cycle_turns(prepare_sweep(five_bar)) == 2
    assert cycle_turns(prepare_sweep(kinepoly.load_scene(EXAMPLES / "four-bar.toml"))) == 1
    out = tmp_path / "five.csv"
    code, _, err = run(capsys, "sweep", str(EXAMPLES / "geared-five-bar.toml"), "-o", str(out))
    assert code == 0 and "[cycle]" in err
    rows = out.read_text().splitlines()[1:]
    assert len(rows) == 720 and rows[-1].startswith("719,")  # 1 degree apart over both turns
    made = kinepoly.animate(five_bar, format="html")
    assert len(made.frames.inputs) == 144  # 72 per turn


@settings(max_examples=25, deadline=None)
@given(st.integers(8, 80), st.integers(8, 80))
def test_a_random_gear_pairs_cycle_is_its_teeth_over_their_gcd(z2: int, z3: int) -> None:
    # link 3 turns -z2/z3 per turn of link 2: back after z3 / gcd(z2, z3) turns (module 1: radii z / 2)
    turns = z3 // math.gcd(z2, z3)
    result = sweep(kinepoly.loads_scene(_pair(z2 / 2.0, z3 / 2.0)), steps=8 * turns)  # 45 degrees apart
    x = result.input.values
    assert x[-1] + (x[1] - x[0]) == pytest.approx(360.0 * turns)
    assert ("cycle" in _codes(result)) == (turns > 1)
    # phases 0 and 0: at the reference mesh link 3 is at 180 degrees (its x-axis away from the pitch point),
    # and it turns -z2/z3 of the input from there; derived here
    theta3 = result.column("theta_3").values
    assert np.max(np.abs(np.remainder(theta3 + z2 / z3 * x, 360.0) - 180.0)) < 1e-9
