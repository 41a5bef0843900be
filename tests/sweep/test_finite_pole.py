"""The finite-rotation pole (RO 2.1): the crossing of the bisectors, its limit the instant center, the command."""

from __future__ import annotations

import cmath
from pathlib import Path

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from tests.cli_support import run
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.engine.finite_pole import bisectors_crossing
from kinepoly.errors import SceneError
from kinepoly.sweep.pole import pole_between

coords = st.floats(-500.0, 500.0)


@settings(max_examples=100, deadline=None)
@given(coords, coords, coords, coords, coords, coords, st.floats(-3.0, 3.0))
def test_the_bisectors_cross_at_the_centre_of_the_rotation(cx: float, cy: float, ax: float, ay: float, bx: float,
                                                           by: float, turn: float) -> None:
    """Two points turned about a centre by an angle: the bisectors of their chords cross at the centre."""
    centre, a, b = complex(cx, cy), complex(ax, ay), complex(bx, by)
    assume(abs(turn) > 1e-3 and abs(a - b) > 1.0 and abs(a - centre) > 1.0 and abs(b - centre) > 1.0)
    assume(abs(((a - centre) / (b - centre)).imag) > 1e-3 * abs((a - centre) / (b - centre)))  # not in line with it
    spin = cmath.exp(1j * turn)
    pole = bisectors_crossing(a, centre + spin * (a - centre), b, centre + spin * (b - centre))
    assert pole is not None
    assert abs(pole - centre) <= 1e-6 * (abs(centre) + abs(a) + abs(b))


def test_a_translation_has_no_pole_and_a_point_that_stays_is_it() -> None:
    assert bisectors_crossing(0j, 10 + 5j, 3 + 1j, 13 + 6j) is None
    assert bisectors_crossing(2 + 3j, 2 + 3j, 10j, -10 + 3j) == 2 + 3j


@pytest.mark.parametrize(("name", "link", "start", "sign"),
                         [("four-bar", "3", 60.0, 1), ("shaper", "5", 10.0, 1), ("slider-crank", "3", 30.0, 1),
                          ("triad", "6", 60.0, -1), ("triad", "3", 60.0, -1)])
def test_the_pole_tends_to_the_instant_center(name: str, link: str, start: float, sign: int) -> None:
    """As the second input closes on the first, P12 closes on the instant center at the first, in step with the
    distance between the inputs (the error of a chord for a tangent)."""
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    errors = []
    for step in (1.0, 0.1, 0.01):
        found = pole_between(scene, link, start, start + sign * step)
        assert found.found.pole is not None and found.instant_center is not None
        errors.append(abs(found.found.pole - found.instant_center))
    size = abs(found.instant_center) + 100.0
    assert errors[2] < 0.2 * errors[1] < 0.04 * errors[0] + 1e-9 * size
    assert errors[2] < 1e-2 * size


def test_a_link_pinned_to_the_frame_turns_about_its_pin() -> None:
    found = pole_between(kinepoly.load_scene(EXAMPLES / "four-bar.toml"), "4", 60.0, 100.0)
    assert found.found.pole == complex(100.0, 0.0)  # B0
    assert found.found.turn != 0.0


def test_two_equal_inputs_are_refused() -> None:
    with pytest.raises(SceneError, match="two different inputs"):
        pole_between(kinepoly.load_scene(EXAMPLES / "four-bar.toml"), "3", 60.0, 60.0)


def test_the_sweep_command_prints_and_draws_the_pole(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    png = tmp_path / "pole.png"
    code, _, err = run(capsys, "sweep", str(EXAMPLES / "shaper.toml"), "--centrode", "5", "--pole", "10", "40",
                       "--pole-plot", str(png), "-o", str(tmp_path / "s.csv"))
    assert code == 0 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    found = pole_between(kinepoly.load_scene(EXAMPLES / "shaper.toml"), "5", 10.0, 40.0).found.pole
    assert found is not None
    assert f"P12 of link 5 from theta_2 = 10 to 40: ({found.real:.6g}, {found.imag:.6g}) mm" in err
    code, _, err = run(capsys, "sweep", str(EXAMPLES / "shaper.toml"), "--pole", "10", "40")
    assert code == 2 and "--centrode" in err
