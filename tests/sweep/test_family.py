"""``sweep_family``: a family of one scene's mechanism, the plan run once for every member.

Each member is checked against the same member swept alone (``sweep`` of ``member_scene``), and the four-bar
family against a numpy closed form of the four-bar written here (the textbook vector loop, differentiated by hand),
on fixed families and on hypothesis families of every example the family runs in one batch.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import kinepoly
from kinepoly.errors import SceneError
from kinepoly.scene.spec import Scene
from kinepoly.sweep import FamilyResult, SweepResult, member_scene, sweep, sweep_family
from kinepoly.sweep.table import csv_text

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
BATCHED = ["four-bar", "slider-crank", "five-bar", "shaper", "slotted-lever", "scotch-yoke", "toggle-press",
           "centers-six-bar", "motor-on-coupler", "dump-body", "excavator", "slotted-crank-slider"]
"""The examples whose plans are made of dyads, carried dyads and drive groups: their families run in one batch."""
TOLERANCE = 1e-12
"""Relative to the largest value of the same kind of column in the member swept alone."""
TRANSMISSION_DEG = 1e-6
"""A transmission angle is read as the arcsine of its direction lines' sine, whose slope grows without limit at 90
degrees: one last bit of the sine there moves it by up to sqrt(2 * 1.1e-16) rad = 8.5e-7 degrees."""


def _scene(name: str) -> Scene:
    return kinepoly.load_scene(EXAMPLES / f"{name}.toml")


def _alone(family: FamilyResult, scene: Scene, k: int, steps: int) -> SweepResult:
    """Member ``k`` swept alone over the family's range (the scene's own)."""
    values = family.input.values
    stop = float(values[-1])
    if family.member(k).periodic:  # the scene's full turn, whether the member turns fully or not
        stop = float(values[0]) + (360.0 if scene.units.angle == "deg" else 2.0 * math.pi)
    return sweep(family.member_scene(k), steps=steps, start=float(values[0]), stop=stop)


def _assert_member_is_alone(family: FamilyResult, scene: Scene, k: int, steps: int) -> None:
    alone = _alone(family, scene, k, steps)
    assert np.array_equal(alone.input.values, family.input.values)
    assert np.array_equal(alone.status, family.status[k])
    scale: dict[str, float] = {}
    for column in alone.columns:
        scale[column.kind] = max(scale.get(column.kind, 0.0), float(np.abs(column.values[column.valid]).max(initial=0)))
    assert [c.name for c in alone.columns] == [c.name for c in family.columns]
    # rows the member's own sweep marks near-singular (a dead point within a fraction of a degree) are compared by
    # status only: there a last-bit difference of a length (numpy's and Python's hypot) moves the rates far more
    # than at any other row
    compared = alone.status == 0
    for column in alone.columns:
        other = family.column(column.name)
        assert np.array_equal(other.valid[k], column.valid), column.name
        difference = np.abs(other.values[k] - column.values)
        if column.kind == "angle":
            full = 360.0 if scene.units.angle == "deg" else 2.0 * math.pi
            difference = np.minimum(difference, np.abs(difference - full))
        allowed = TOLERANCE * max(scale[column.kind], 1e-300)
        if column.kind == "transmission":  # arcsin of the lines' sine: near 90 degrees a last bit of the sine is
            allowed = max(allowed, TRANSMISSION_DEG * (1.0 if scene.units.angle == "deg" else math.pi / 180.0))
        assert (difference <= allowed)[column.valid & compared].all(), column.name
    member = family.member(k)
    assert np.array_equal(member.status, alone.status)
    assert member.warnings.keys() == alone.warnings.keys()
    assert [n.code for n in member.notices] == [n.code for n in alone.notices if n.code == "cannot-assemble"]


def _varied(scene: Scene, members: int, spread: float, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """Every point of every link moved by up to ``spread`` of its distance from its link's origin (and a little
    besides), one row per member."""
    out = {}
    for link in scene.links:
        for p in link.points:
            xy = np.array(p.local, np.float64)
            size = max(1.0, float(np.abs(xy).max()))
            out[f"{p.name}@{link.name}"] = xy + rng.uniform(-spread, spread, (members, 2)) * size
    return out


# -- the four-bar against a closed form --------------------------------------------------------------------------

def _four_bar(a2: np.ndarray, a3: np.ndarray, a4: np.ndarray, theta2: np.ndarray, a1: float, omega2: float,
              alpha2: float) -> dict[str, np.ndarray]:
    """theta3, theta4 (deg), omega and alpha of links 3 and 4 of the open four-bar: the vector loop
    a2 e^(i t2) + a3 e^(i t3) = a1 + a4 e^(i t4), B left of A -> B0."""
    a = a2 * np.exp(1j * theta2)
    d = a1 - a
    dist = np.abs(d)
    foot = (dist * dist + a3 * a3 - a4 * a4) / (2.0 * dist)
    height = np.sqrt(a3 * a3 - foot * foot)
    b = a + d / dist * (foot + 1j * height)
    t3, t4 = np.angle(b - a), np.angle(b - a1)
    # omega: a2 w2 i e2 + a3 w3 i e3 = a4 w4 i e4, solved by Cramer's rule on the real and imaginary parts
    e2, e3, e4 = np.exp(1j * theta2), np.exp(1j * t3), np.exp(1j * t4)
    det = (a3 * 1j * e3 * np.conj(a4 * 1j * e4)).imag
    rhs = -a2 * omega2 * 1j * e2
    w3 = (rhs * np.conj(-a4 * 1j * e4)).imag / -det * -1.0
    w4 = (a3 * 1j * e3 * np.conj(rhs)).imag / -det * -1.0
    # check the loop's derivative holds, whichever sign convention the Cramer lines above carry
    if not np.allclose(a2 * omega2 * 1j * e2 + a3 * w3 * 1j * e3, a4 * w4 * 1j * e4, rtol=0, atol=1e-9):
        w3, w4 = -w3, -w4
    rhs2 = -(a2 * (alpha2 * 1j - omega2 * omega2) * e2 - a3 * w3 * w3 * e3 + a4 * w4 * w4 * e4)
    al3 = (rhs2 * np.conj(-a4 * 1j * e4)).imag / -det * -1.0
    al4 = (a3 * 1j * e3 * np.conj(rhs2)).imag / -det * -1.0
    if not np.allclose(a2 * (alpha2 * 1j - omega2 ** 2) * e2 + a3 * (al3 * 1j - w3 ** 2) * e3,
                       a4 * (al4 * 1j - w4 ** 2) * e4, rtol=0, atol=1e-6):
        al3, al4 = -al3, -al4
    return {"theta_3": np.degrees(t3), "theta_4": np.degrees(t4), "omega_3": w3, "omega_4": w4, "alpha_3": al3,
            "alpha_4": al4}


def test_a_four_bar_family_against_its_closed_form() -> None:
    scene = _scene("four-bar")
    rng = np.random.default_rng(3)
    count = 40
    a2, a3, a4 = rng.uniform(30, 45, count), rng.uniform(110, 130, count), rng.uniform(75, 90, count)
    zero = np.zeros(count)
    points = {"A@2": np.c_[a2, zero], "B@3": np.c_[a3, zero], "B@4": np.c_[a4, zero]}
    family = sweep_family(scene, points, steps=90)
    assert family.batched and family.members == count and family.status.shape == (count, 90)
    theta2 = np.radians(family.input.values)
    expected = _four_bar(a2[:, None], a3[:, None], a4[:, None], theta2[None, :], 100.0, 10.0, 5.0)
    for name, values in expected.items():
        got = family.column(name).values
        difference = np.abs(got - values)
        if name.startswith("theta"):
            difference = np.minimum(difference, np.abs(difference - 360.0))
        assert difference.max() <= 1e-10 * np.abs(values).max(), name


def test_the_closed_form_of_the_test_is_the_engines_at_one_member() -> None:
    """The test's own closed form is checked by finite differences of its angles, so that it is a reference."""
    a2, a3, a4 = np.array(40.0), np.array(120.0), np.array(80.0)
    theta2 = np.radians(np.arange(0.0, 360.0, 7.0))
    h = 1e-6
    mid = _four_bar(a2, a3, a4, theta2, 100.0, 1.0, 0.0)
    ahead = _four_bar(a2, a3, a4, theta2 + h, 100.0, 1.0, 0.0)
    behind = _four_bar(a2, a3, a4, theta2 - h, 100.0, 1.0, 0.0)
    for link in ("3", "4"):
        rate = np.radians(ahead[f"theta_{link}"] - behind[f"theta_{link}"]) / (2 * h)
        assert np.allclose(rate, mid[f"omega_{link}"], rtol=0, atol=1e-6)
        second = (ahead[f"omega_{link}"] - behind[f"omega_{link}"]) / (2 * h)
        assert np.allclose(second, mid[f"alpha_{link}"], rtol=0, atol=1e-5)


# -- every member as it is swept alone -----------------------------------------------------------------------------

@pytest.mark.parametrize("name", BATCHED)
def test_each_member_is_the_member_swept_alone(name: str) -> None:
    scene = _scene(name)
    family = sweep_family(scene, _varied(scene, 3, 0.01, np.random.default_rng(7)), steps=48)
    assert family.batched
    for k in range(3):
        _assert_member_is_alone(family, scene, k, 48)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(BATCHED), seed=st.integers(0, 2**32 - 1), spread=st.floats(0.0, 0.04),
       members=st.integers(1, 4), steps=st.integers(36, 72))
def test_random_families_are_their_members_swept_alone(name: str, seed: int, spread: float, members: int,
                                                       steps: int) -> None:
    """Over the scene's full turn, or the inner 90% of its range where that ends at dead points (a member's dead
    point lies elsewhere, perhaps a hair beyond the scene's end, where rounding is amplified without limit)."""
    scene = _scene(name)
    own = sweep(scene, steps=2)
    ends: dict[str, float] = {}
    if not own.periodic:
        low, high = float(own.input.values[0]), float(own.input.values[-1])
        ends = {"start": low + 0.05 * (high - low), "stop": high - 0.05 * (high - low)}
    family = sweep_family(scene, _varied(scene, members, spread, np.random.default_rng(seed)), steps=steps, **ends)
    for k in range(members):
        _assert_member_is_alone(family, scene, k, steps)


def test_members_that_do_not_assemble_everywhere_are_marked_as_alone() -> None:
    """A crank longer than a Grashof crank-rocker allows: the member's rows that do not close are marked, as in
    its own sweep, with its own range in the warning."""
    scene = _scene("four-bar")
    points = {"A@2": [[40.0, 0.0], [75.0, 0.0], [90.0, 0.0]]}
    family = sweep_family(scene, points, steps=72)
    assert (family.status[0] == 0).all()
    for k in (1, 2):
        assert (family.status[k] == 3).any()
        _assert_member_is_alone(family, scene, k, 72)
        assert family.member(k).notices[0].message == _alone(family, scene, k, 72).notices[0].message


def test_every_member_takes_the_scenes_own_assembly() -> None:
    """The crossed four-bar (its [guess] below the frame): every member stays crossed."""
    text = (EXAMPLES / "four-bar.toml").read_text().replace("B = [110, 80]", "B = [110, -80]")
    scene = kinepoly.loads_scene(text, "crossed.toml")
    points = {"B@4": [[78.0, 0.0], [80.0, 0.0], [84.0, 0.0]]}
    family = sweep_family(scene, points, steps=36)
    for k in range(3):
        _assert_member_is_alone(family, scene, k, 36)
        y = family.column("r_B_y").values[k] if any(c.name == "r_B_y" for c in family.columns) else None
        if y is not None:
            assert y[family.input.values == 60.0][0] < 0.0


def test_a_member_is_a_sweep_result_that_writes_its_csv() -> None:
    scene = _scene("slider-crank")
    family = sweep_family(scene, _varied(scene, 2, 0.01, np.random.default_rng(1)), steps=24)
    member = family.member(1)
    alone = _alone(family, scene, 1, 24)
    assert csv_text(member).splitlines()[0] == csv_text(alone).splitlines()[0]
    assert len(csv_text(member).splitlines()) == len(csv_text(alone).splitlines())


def test_a_range_given_is_every_members() -> None:
    scene = _scene("slider-crank")
    family = sweep_family(scene, _varied(scene, 2, 0.01, np.random.default_rng(2)), steps=20, start=10.0,
                          stop=100.0)
    assert family.input.values[0] == 10.0 and family.input.values[-1] == 100.0
    for k in range(2):
        alone = sweep(family.dimensions.scene(scene, k), steps=20, start=10.0, stop=100.0)
        assert np.array_equal(alone.status, family.status[k])


# -- member by member: Newton groups ---------------------------------------------------------------------------

def test_a_family_with_newton_groups_is_swept_member_by_member() -> None:
    scene = _scene("triad-slot")
    points = _varied(scene, 2, 0.002, np.random.default_rng(5))
    family = sweep_family(scene, points, steps=12)
    assert not family.batched
    for k in range(2):
        _assert_member_is_alone(family, scene, k, 12)


# -- bad input ------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize(("points", "message"), [
    ({}, "give at least one point"),
    ({"Q@3": [[1.0, 2.0]]}, "'Q@3' is not a point of one link of the scene; the links' points of that name are: none"),
    ({"B": [[1.0, 2.0]]}, "'B' is not a point of one link of the scene; the links' points of that name are: B@3, B@4"),
    ({"B@2": [[1.0, 2.0]]}, "'B@2' is not a point of one link"),
    ({"B@3": [1.0, 2.0]}, "expected an array of (members, 2) numbers, one [x, y] per member; got the shape (2,)"),
    ({"B@3": [["a", 2.0]]}, "expected an array of (members, 2) numbers"),
    ({"B@3": [[math.nan, 2.0]]}, "member 0 has a coordinate that is not a finite number"),
    ({"B@3": [[120.0, 0.0]], "B@4": [[80.0, 0.0], [81.0, 0.0]]}, "'B@4' has 2 members, 'B@3' before it 1"),
])
def test_bad_points_are_refused_by_name(points: dict[str, object], message: str) -> None:
    with pytest.raises(SceneError) as error:
        sweep_family(_scene("four-bar"), points, steps=12)  # type: ignore[arg-type]
    assert message in str(error.value)


def test_a_range_needs_both_ends() -> None:
    with pytest.raises(SceneError, match="give both"):
        sweep_family(_scene("four-bar"), {"B@3": [[120.0, 0.0]]}, steps=12, start=10.0)


@pytest.mark.parametrize("name", ["cam-roller-rocker", "eccentric-cam-flat"])
def test_cams_are_refused_with_what_to_do(name: str) -> None:
    scene = _scene(name)
    link = scene.links[1]
    with pytest.raises(SceneError, match="sweep each member as a scene of its own"):
        sweep_family(scene, {f"{link.points[0].name}@{link.name}": [list(link.points[0].local)]}, steps=12)


# -- slide lines ----------------------------------------------------------------------------------------------------

def _offset_slider_crank(a2: np.ndarray, a3: float, c: np.ndarray, theta: np.ndarray,
                         omega: float) -> dict[str, np.ndarray]:
    """x, v_x, a_x of the block of the offset slider-crank (alpha 0): s = a2 cos t + sqrt(a3^2 - (a2 sin t - c)^2),
    differentiated by hand."""
    u = a2 * np.sin(theta) - c
    d = np.sqrt(a3 * a3 - u * u)
    cos, sin = a2 * np.cos(theta), a2 * np.sin(theta)
    first = -sin - u * cos / d
    second = -cos - (cos * cos - u * sin) / d - (u * cos) ** 2 / d ** 3
    return {"r_B_x": cos + d, "v_B_x": omega * first, "a_B_x": omega * omega * second}


def test_a_family_of_slide_offsets_against_its_closed_form() -> None:
    scene = _scene("slider-crank")
    offsets = np.linspace(-20.0, 20.0, 9)
    family = sweep_family(scene, slides={"14": np.c_[np.zeros(9), offsets]}, steps=72)
    assert family.batched and (family.status == 0).all()
    theta = np.radians(family.input.values)
    expected = _offset_slider_crank(np.array(40.0), 120.0, offsets[:, None], theta[None, :], 10.0)
    for name, values in expected.items():
        assert np.abs(family.column(name).values - values).max() <= 1e-12 * np.abs(values).max(), name
    assert np.abs(family.column("r_B_y").values - offsets[:, None]).max() <= 1e-12 * 120.0  # the block on its line


def test_the_closed_form_of_the_offset_slider_crank_by_finite_differences() -> None:
    theta, h = np.radians(np.arange(0.0, 360.0, 10.0)), 1e-5
    at = {k: _offset_slider_crank(np.array(40.0), 120.0, np.array(7.0), theta + k * h, 1.0)["r_B_x"] for k in (-1, 1)}
    mid = _offset_slider_crank(np.array(40.0), 120.0, np.array(7.0), theta, 1.0)
    assert np.allclose((at[1] - at[-1]) / (2 * h), mid["v_B_x"], rtol=0, atol=1e-8)
    v = {k: _offset_slider_crank(np.array(40.0), 120.0, np.array(7.0), theta + k * h, 1.0)["v_B_x"] for k in (-1, 1)}
    assert np.allclose((v[1] - v[-1]) / (2 * h), mid["a_B_x"], rtol=0, atol=1e-6)


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(["slider-crank", "shaper", "slotted-crank-slider", "scotch-yoke"]),
       seed=st.integers(0, 2**32 - 1), members=st.integers(1, 3))
def test_slides_and_points_together_are_their_members_swept_alone(name: str, seed: int, members: int) -> None:
    scene = _scene(name)
    rng = np.random.default_rng(seed)
    size = max(abs(v) for link in scene.links for p in link.points for v in p.local)
    slides = {s.name: np.array(s.through) + rng.uniform(-0.02, 0.02, (members, 2)) * size for s in scene.sliders}
    family = sweep_family(scene, _varied(scene, members, 0.01, rng), steps=48, slides=slides)
    for k in range(members):
        _assert_member_is_alone(family, scene, k, 48)


def test_a_slider_that_is_not_the_scenes_is_refused() -> None:
    with pytest.raises(SceneError, match="'41' is not a slider of the scene; its sliders are: 14"):
        sweep_family(_scene("slider-crank"), slides={"41": [[0.0, 5.0]]}, steps=12)


def test_a_members_scene_is_the_scene_with_its_row_of_coordinates() -> None:
    scene = _scene("slider-crank")
    member = member_scene(scene, {"A@3": [[118.0, 0.0], [122.0, 1.0]]}, 1, slides={"14": [[0.0, 5.0], [0.0, -5.0]]})
    assert member.link("3").point("A").local == (122.0, 1.0) and member.link("3").point("A").polar is None
    assert member.link("3").point("C") == scene.link("3").point("C")
    assert member.link("2") == scene.link("2") and member.sliders[0].through == (0.0, -5.0)
    assert member.sliders[0].angle_rad == scene.sliders[0].angle_rad and member.guess == scene.guess


@pytest.mark.parametrize("name", ["four-bar", "shaper", "centers-six-bar"])
def test_a_members_positions_are_its_own_sweeps(name: str) -> None:
    """A member's link poses (its drawings' skeleton, its rows' [guess]) are those of the member swept alone."""
    from kinepoly.sweep.rows import row_guesses

    scene = _scene(name)
    family = sweep_family(scene, _varied(scene, 2, 0.01, np.random.default_rng(11)), steps=24)
    for k in range(2):
        member, alone = family.member(k), _alone(family, scene, k, 24)
        size = max(abs(complex(at)) for _, points in alone.skeleton for at in points)
        for (link, mine), (other, theirs) in zip(member.skeleton, alone.skeleton, strict=True):
            assert link == other and max(abs(a - b) for a, b in zip(mine, theirs, strict=True)) <= 1e-12 * size
        for mine_row, their_row in zip(row_guesses(member), row_guesses(alone), strict=True):
            assert (mine_row is None) == (their_row is None)
            for (name_a, a), (name_b, b) in zip(mine_row or (), their_row or (), strict=True):
                assert name_a == name_b and abs(complex(*a) - complex(*b)) <= 1e-12 * size


# -- gears ------------------------------------------------------------------------------------------------------------

def test_a_family_of_gear_pairs_turns_at_its_ratio() -> None:
    """Two gears on frame pivots, scaled together (radii r2, r3 and the centres r2 + r3 apart): omega_3 is
    -omega_2 r2 / r3 in every member, and the pin E at 45 from O3 runs at |omega_3| 45."""
    scene = _scene("gear-pair")
    r2 = np.array([30.0, 40.0, 50.0])
    r3 = np.array([70.0, 60.0, 50.0])
    family = sweep_family(scene, {"O3@1": np.c_[r2 + r3, np.zeros(3)]}, steps=24,
                          radii={"23": np.c_[r2, r3]})
    assert not family.batched and (family.status == 0).all()
    omega = family.column("omega_3").values
    assert np.allclose(omega, (-12.0 * r2 / r3)[:, None], rtol=1e-12, atol=0.0)
    speed = np.hypot(family.column("v_E_x").values, family.column("v_E_y").values)
    assert np.allclose(speed, np.abs(omega) * 45.0, rtol=1e-12, atol=0.0)
    for k in range(3):
        _assert_member_is_alone(family, scene, k, 24)


@pytest.mark.parametrize(("radii", "message"), [
    ({"32": [[40.0, 60.0]]}, "'32' is not a gear pair of the scene; its pairs are: 23"),
    ({"23": [[40.0, 0.0]]}, "member 0 has a pitch radius that is not positive"),
    ({"23": [[40.0, 60.0, 1.0]]}, "expected an array of (members, 2) numbers"),
])
def test_bad_radii_are_refused_by_name(radii: dict[str, object], message: str) -> None:
    with pytest.raises(SceneError) as error:
        sweep_family(_scene("gear-pair"), radii=radii, steps=12)  # type: ignore[arg-type]
    assert message in str(error.value)


def test_a_rack_has_no_radius_to_vary() -> None:
    with pytest.raises(SceneError, match="has a rack"):
        sweep_family(_scene("rack-pinion"), radii={kinepoly.load_scene(EXAMPLES / "rack-pinion.toml").gears[0].name:
                                                  [[40.0, 60.0]]}, steps=12)


def test_a_large_family_runs_in_batches_of_whole_members(monkeypatch: pytest.MonkeyPatch) -> None:
    """Batches of two members (a small limit of rows) give the one batch's values, statuses and members."""
    from kinepoly.sweep import family as module

    scene = _scene("four-bar")
    points = {"A@2": [[40.0, 0.0], [75.0, 0.0], [38.0, 0.0], [42.0, 0.0], [90.0, 0.0]]}
    whole = sweep_family(scene, points, steps=36)
    monkeypatch.setattr(module, "_CHUNK_ROWS", 80)  # two members of 36 rows a batch
    parts = sweep_family(scene, points, steps=36)
    assert len(parts._results) == 3 and parts._per == 2 and len(whole._results) == 1
    assert np.array_equal(parts.status, whole.status)
    for a, b in zip(parts.columns, whole.columns, strict=True):
        assert a.name == b.name and np.array_equal(a.values, b.values) and np.array_equal(a.valid, b.valid)
    for k in range(5):
        one, other = parts.member(k), whole.member(k)
        assert one.warnings == other.warnings and one.notices == other.notices
        assert one.skeleton == other.skeleton and parts.member_scene(k) == whole.member_scene(k)


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(["four-bar", "slider-crank", "shaper", "centers-six-bar", "dump-body"]),
       seed=st.integers(0, 10**6), members=st.integers(1, 6))
def test_members_each_at_its_own_input_are_their_solves(name: str, seed: int, members: int) -> None:
    """``member_placer``: member k with its own points and slide lines at its own input is the solve of its scene
    at that input, in the scene's own assembly (the solve's, from [guess] at the family's); flipped, its dyad in the
    other assembly."""
    import msgspec

    from kinepoly.engine.groups import Dyad
    from kinepoly.scene.spec import LinkInput
    from kinepoly.sweep.family import Dimensions, member_placer

    scene = _scene(name)
    placer = member_placer(scene)
    assert placer is not None
    rng = np.random.default_rng(seed)
    factors = {link.name: rng.uniform(0.95, 1.05, members) for link in scene.links}
    points = {(link.name, p.name): np.outer(factors[link.name], p.local) for link in scene.links for p in link.points}
    slides = {s.name: np.outer(factors[s.guide], s.through) for s in scene.sliders}
    dimensions = Dimensions(points, slides, members)
    link_input = isinstance(scene.input, LinkInput)
    own = scene.input.angle_rad if isinstance(scene.input, LinkInput) else getattr(scene.input, "s", 0.0)
    inputs = own + (rng.uniform(-0.2, 0.2, members) if link_input else rng.uniform(-2.0, 2.0, members))
    found = placer.place(dimensions, inputs)
    dyad = next(g for g in placer.plan.groups if isinstance(g, Dyad))
    flipped = placer.place(dimensions, inputs, frozenset({dyad.name}))
    names = [p.name for link in scene.links if link.name != scene.ground for p in link.points]
    for k in range(members):
        if not found.ok[k]:
            continue
        at = {n: complex(found.point(n)[k]) for n in names}
        member = dimensions.scene(scene, k)
        given = {"angle_rad": float(inputs[k])} if link_input else {"s": float(inputs[k])}
        member = msgspec.structs.replace(member, input=msgspec.structs.replace(scene.input, **given),
                                     guess=tuple((n, (z.real, z.imag)) for n, z in at.items()))
        solved = kinepoly.solve(member)
        size = max(abs(z) for z in at.values())
        for n, z in at.items():
            assert abs(complex(*solved.position(n)) - z) <= 1e-9 * size, (n, k)
        inner = dyad.inner.point if hasattr(dyad.inner, "point") else None
        if inner is not None and flipped.ok[k]:
            assert abs(complex(flipped.point(inner)[k]) - at[inner]) > 1e-6 * size
