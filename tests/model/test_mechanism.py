"""The mechanism a scene builds, against what the scene's text says read on its own (tomllib, not the loader).

Joints: a point name shared by k links is a hinge of k - 1 pins (a compound hinge), plus one joint per slider.
Gruebler's count 3(n - 1) - 2j - h equals the number of inputs for every example, and a scene that breaks it
is refused naming n, j and the count. A slider whose guide turns (not the frame, nor a link that slides on it)
is the one that has a Coriolis term.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest
from tests.scenes import EXAMPLES

from kinepoly.errors import MobilityError
from kinepoly.model.mechanism import Revolute, build_mechanism
from kinepoly.scene.loader import load_scene, loads_scene

_EXAMPLES = sorted(EXAMPLES.glob("*.toml"))


def _raw(path: Path) -> dict[str, object]:
    with path.open("rb") as stream:
        return tomllib.load(stream)


def _points_by_link(raw: dict[str, object]) -> dict[str, set[str]]:
    links = raw.get("links", {})
    assert isinstance(links, dict)
    out: dict[str, set[str]] = {}
    for name, link in links.items():
        points = link.get("points", {}) if isinstance(link, dict) else {}
        out[str(name)] = set(points)
    return out


@pytest.mark.parametrize("path", _EXAMPLES, ids=lambda p: p.stem)
def test_pins_are_the_shared_point_names_a_hinge_of_k_links_k_minus_1(path: Path) -> None:
    raw = _raw(path)
    by_link = _points_by_link(raw)
    if not by_link or raw.get("cams") or raw.get("gears"):  # higher pairs add the loader's equivalent links
        pytest.skip("no [links] table of points, or links the loader adds for a higher pair")
    mechanism = build_mechanism(load_scene(path))
    sharing: dict[str, int] = {}
    for points in by_link.values():
        for p in points:
            sharing[p] = sharing.get(p, 0) + 1
    expected = sum(k - 1 for k in sharing.values())
    assert len(mechanism.revolutes) == expected
    for pin in mechanism.revolutes:
        a, b = pin.links
        assert pin.point in by_link[a] and pin.point in by_link[b]
        assert pin.other(a) == b and pin.other(b) == a
    sliders = raw.get("sliders", [])
    assert isinstance(sliders, list)
    assert len(mechanism.joints) == expected + len(sliders)


@pytest.mark.parametrize("path", _EXAMPLES, ids=lambda p: p.stem)
def test_every_link_knows_its_own_joints_and_points(path: Path) -> None:
    mechanism = build_mechanism(load_scene(path))
    for link in mechanism.link_names:
        for joint in mechanism.joints_of(link):
            assert link in (joint.links if isinstance(joint, Revolute) else (joint.block, joint.guide))
        for p in mechanism.scene.link(link).points:
            assert mechanism.has_point(link, p.name) and mechanism.local(link, p.name) == p.local
            assert link in mechanism.links_of_point(p.name)
            assert mechanism.owner(p.name) == mechanism.links_of_point(p.name)[0]


@pytest.mark.parametrize(("name", "coriolis"), [("slider-crank", False), ("slotted-lever", True),
                                                ("scotch-yoke", False), ("shaper", True)])
def test_a_coriolis_term_exactly_where_a_block_slides_on_a_turning_guide(name: str, coriolis: bool) -> None:
    path = EXAMPLES / f"{name}.toml"
    raw = _raw(path)
    ground = str(raw.get("ground", "1"))
    mechanism = build_mechanism(load_scene(path))
    turning = [mechanism.has_turning_guide(s) for s in mechanism.sliders]
    assert any(turning) is coriolis
    for slider, turns in zip(mechanism.sliders, turning, strict=True):
        if slider.guide == ground:
            assert not turns
        # a block and its guide turn together: one omega for both
        assert slider.block in mechanism.turning_together(slider.guide)


def test_a_compound_hinge_counts_as_two_pins_in_the_mobility_message() -> None:
    text = """
[links]
1 = { points = { A0 = [0, 0], B0 = [100, 0] } }
2 = { points = { A0 = [0, 0], A = [30, 0] } }
3 = { points = { A = [0, 0], B = [90, 0] } }
4 = { points = { B0 = [0, 0], B = [80, 0] } }
5 = { points = { B = [0, 0], A0 = [50, 50] } }

[input]
link = "2"
angle = 60
omega = 1
"""
    with pytest.raises(MobilityError) as caught:
        build_mechanism(loads_scene(text))
    message = str(caught.value)
    n, j = 5, sum(k - 1 for k in (3, 2, 3, 2))  # A0 on 1, 2, 5; A on 2, 3; B on 3, 4, 5; B0 on 1, 4
    assert f"n = {n} links and j = {j} joints" in message
    assert f"3*({n} - 1) - 2*{j} = {3 * (n - 1) - 2 * j}" in message
    assert "pin A0 joins links 1, 2, 5: 2 joints" in message and "pin B joins links 3, 4, 5: 2 joints" in message
