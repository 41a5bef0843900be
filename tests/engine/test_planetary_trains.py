"""Planetary trains and differentials with every choice of driven and fixed members, against Willis' formula.

A simple train: the sun (z_s teeth), the planet (z_p) pinned to the arm at its centre, the ring (z_r = z_s + 2
z_p); pitch radii m z / 2. Relative to the arm it is an ordinary train, so (Willis)

    (w_r - w_a) / (w_s - w_a) = -z_s / z_r,   (w_p - w_a) / (w_s - w_a) = -z_s / z_p,

and the same for the angles turned from the reference mesh (all angles zero, the phases set so that the train
is assembled there) and for the angular accelerations. Written here from the tooth counts alone.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinepoly
from kinepoly.sweep import sweep

MEMBERS = ("sun", "arm", "ring")
_NAMES = {"sun": "2", "arm": "3", "ring": "5"}


def train(z_sun: int, z_planet: int, module: float, roles: dict[str, str],
          inputs: dict[str, tuple[float, float, float]]) -> str:
    """A scene: each of sun, arm and ring is "fixed" (part of the frame 1), "driven" (an input with the given
    angle in degrees, omega and alpha) or "free"; the planet is link 4."""
    r_sun, r_planet = module * z_sun / 2.0, module * z_planet / 2.0
    r_ring = r_sun + 2.0 * r_planet
    name = {m: "1" if roles[m] == "fixed" else _NAMES[m] for m in MEMBERS}
    points: dict[str, dict[str, str]] = {"1": {"O": "[0, 0]"}}
    for member in MEMBERS:
        points.setdefault(name[member], {})["O"] = "[0, 0]"
    points[name["arm"]]["C"] = f"[{r_sun + r_planet!r}, 0]"
    points["4"] = {"C": "[0, 0]", "Q": f"[{r_planet / 2.0!r}, 0]"}
    links = "\n".join(f'{link} = {{ points = {{ {", ".join(f"{p} = {v}" for p, v in pts.items())} }} }}'
                      for link, pts in sorted(points.items()))
    driven = "".join(f'\n[[input]]\nlink = "{name[m]}"\nangle = {inputs[m][0]!r}\nomega = {inputs[m][1]!r}\n'
                     f"alpha = {inputs[m][2]!r}\n" for m in MEMBERS if roles[m] == "driven")
    return f"""title = "planetary train"
[links]
{links}

[[gears]]
links = ["{name['sun']}", "4"]
pitch = [{{ center = "O", radius = {r_sun!r} }}, {{ center = "C", radius = {r_planet!r} }}]
phase = [0, 180]

[[gears]]
links = ["4", "{name['ring']}"]
pitch = [{{ center = "C", radius = {r_planet!r} }}, {{ center = "O", radius = {r_ring!r} }}]
internal = true
phase = [0, 0]
{driven}
[find]
velocity = ["Q", "C"]
acceleration = ["Q", "C"]
omega = [{", ".join(f'"{n}"' for n in sorted({*name.values(), "4"} - {"1"}))}]
alpha = [{", ".join(f'"{n}"' for n in sorted({*name.values(), "4"} - {"1"}))}]
"""


def willis(z_sun: int, z_planet: int, known: dict[str, float]) -> dict[str, float]:
    """The rates (or angles, or accelerations) of sun, arm, ring and planet from two of the first three."""
    z_ring = z_sun + 2 * z_planet
    k = -z_sun / z_ring  # (w_r - w_a) = k (w_s - w_a)
    s, a, r = known.get("sun"), known.get("arm"), known.get("ring")
    if s is None:
        assert a is not None and r is not None
        s = a + (r - a) / k
    elif a is None:
        assert r is not None
        a = (r - k * s) / (1.0 - k)
    elif r is None:
        r = a + k * (s - a)
    return {"sun": s, "arm": a, "ring": r, "planet": a - z_sun / z_planet * (s - a)}


CHOICES = [
    *({m: ("driven" if m == d else "fixed" if m == f else "free") for m in MEMBERS}
      for d in MEMBERS for f in MEMBERS if d != f),
    *({m: ("free" if m == f else "driven") for m in MEMBERS} for f in MEMBERS),  # differentials: two inputs
]


def _label(roles: dict[str, str]) -> str:
    return "-".join(f"{m}:{roles[m]}" for m in MEMBERS)


def _check(z_sun: int, z_planet: int, module: float, roles: dict[str, str],
           inputs: dict[str, tuple[float, float, float]]) -> None:
    text = train(z_sun, z_planet, module, roles, inputs)
    data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(text)))
    assert data["check"]["max_rel_error"] < 1e-12
    given_members = {m: inputs[m] for m in MEMBERS if roles[m] == "driven"}
    given_members.update({m: (0.0, 0.0, 0.0) for m in MEMBERS if roles[m] == "fixed"})
    link = {m: _NAMES[m] for m in MEMBERS} | {"planet": "4"}
    squared = 0.0  # the largest omega squared: the normal terms an alpha is read from are of that size
    for index, key in enumerate(("angle", "omega", "alpha")):
        value = {m: math.radians(v[0]) if index == 0 else v[index] for m, v in given_members.items()}
        want = willis(z_sun, z_planet, value)
        scale = max(1.0, *(abs(v) for v in want.values()), squared if index == 2 else 0.0)
        if index == 1:
            squared = max(v * v for v in want.values())
        for member, expected in want.items():
            if member in MEMBERS and roles[member] == "fixed":
                continue
            got = data["links"][link[member]][key]
            got = math.radians(got) if index == 0 else got
            if index == 0:  # angles modulo a turn
                got = expected + math.remainder(got - expected, math.tau)
            assert got == pytest.approx(expected, rel=1e-12, abs=1e-12 * scale), (_label(roles), member, key)


@pytest.mark.parametrize("roles", CHOICES, ids=_label)
def test_every_choice_of_driven_and_fixed_members_by_willis(roles: dict[str, str]) -> None:
    inputs = {"sun": (25.0, 10.0, 2.0), "arm": (-15.0, 3.0, -1.5), "ring": (40.0, -4.0, 0.5)}
    _check(30, 20, 2.0, roles, inputs)


def _rate(bound: float) -> st.SearchStrategy[float]:
    return st.floats(-bound, bound).filter(lambda x: x == 0.0 or abs(x) > 1e-3)


_MOTION = st.tuples(st.floats(-50.0, 50.0), _rate(30.0), _rate(10.0))


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(CHOICES), st.integers(8, 60), st.integers(8, 60), st.floats(0.5, 5.0), _MOTION, _MOTION,
       _MOTION)
def test_random_trains_by_willis(roles: dict[str, str], z_sun: int, z_planet: int, module: float,
                                 sun: tuple[float, float, float], arm: tuple[float, float, float],
                                 ring: tuple[float, float, float]) -> None:
    _check(z_sun, z_planet, module, roles, {"sun": sun, "arm": arm, "ring": ring})


@pytest.mark.parametrize("roles", [c for c in CHOICES if c["arm"] == "free"], ids=_label)
def test_an_undriven_arm_over_a_sweep_by_willis(roles: dict[str, str]) -> None:
    # the first input turns a whole turn, the others held at their angles: the arm and the planet follow
    # continuously (no jump by a tooth), turning by Willis' ratios; every row's rates and accelerations are
    # Willis' with the scene's rates
    inputs = {"sun": (25.0, 10.0, 2.0), "arm": (-15.0, 3.0, -1.5), "ring": (40.0, -4.0, 0.5)}
    scene = kinepoly.loads_scene(train(30, 20, 2.0, roles, inputs))
    result = sweep(scene, steps=721)
    assert (result.status == 0).all()
    first = next(m for m in MEMBERS if roles[m] == "driven")
    theta = np.radians(result.input.values)
    held = {m: 0.0 for m in MEMBERS if m != first and roles[m] != "free"}
    per_turn = willis(30, 20, {first: 1.0, **held})
    rates = willis(30, 20, {m: inputs[m][1] if roles[m] == "driven" else 0.0 for m in MEMBERS if roles[m] != "free"})
    accelerations = willis(30, 20, {m: inputs[m][2] if roles[m] == "driven" else 0.0 for m in MEMBERS
                                    if roles[m] != "free"})
    for link, member in (("3", "arm"), ("4", "planet")):
        angle = np.unwrap(np.radians(result.column(f"theta_{link}").values))
        turned = angle - angle[0]  # continuous: no jump by a tooth
        assert np.max(np.abs(turned - per_turn[member] * (theta - theta[0]))) < 1e-11
        assert np.max(np.abs(result.column(f"omega_{link}").values - rates[member])) < 1e-12 * 30
        assert np.max(np.abs(result.column(f"alpha_{link}").values - accelerations[member])) < 1e-12 * 30


@pytest.mark.parametrize("roles", [c for c in CHOICES if c["arm"] == "free"], ids=_label)
def test_an_undriven_arms_accelerations_by_finite_differences_in_time(roles: dict[str, str]) -> None:
    # every input moves for a time t at its omega and alpha: theta(t) = theta0 + omega t + alpha t^2 / 2;
    # the arm's and the planet's angles at t = -h, 0, h give their omega and alpha by central differences
    inputs = {"sun": (25.0, 10.0, 2.0), "arm": (-15.0, 3.0, -1.5), "ring": (40.0, -4.0, 0.5)}
    h = 1e-3

    def at(t: float) -> dict[str, dict[str, float]]:
        moved = {m: (v[0] + math.degrees(v[1] * t + v[2] * t * t / 2.0), v[1] + v[2] * t, v[2])
                 for m, v in inputs.items()}
        links: dict[str, dict[str, float]] = kinepoly.to_json(
            kinepoly.solve(kinepoly.loads_scene(train(30, 20, 2.0, roles, moved))))["links"]
        return links

    before, now, after = at(-h), at(0.0), at(h)
    for link in ("3", "4"):
        a, b, c = (math.radians(x[link]["angle"]) for x in (before, now, after))
        a, c = b + math.remainder(a - b, math.tau), b + math.remainder(c - b, math.tau)
        assert (c - a) / (2 * h) == pytest.approx(now[link]["omega"], rel=1e-6, abs=1e-6)
        assert (c - 2 * b + a) / (h * h) == pytest.approx(now[link]["alpha"], rel=1e-4, abs=1e-4)


def test_the_undriven_arms_polygons_are_drawn_through_the_pitch_points() -> None:
    # the planet's tips at both pitch points are the sun's and the ring's there; C (midway between the pitch
    # points: 20 of 40 mm) lies midway between them in the polygon, and the arm's omega is read from c
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "examples" / "planetary-free-arm.toml"
    solution = kinepoly.solve(kinepoly.load_scene(path))
    velocity = [s for s in solution.steps if s.polygon == "velocity"]
    assert [s.topic for s in velocity].count("pitch-point") == 2
    assert not any(s.kind == "linear-solve" for s in velocity)
    acceleration = [s for s in solution.steps if s.polygon == "acceleration"]
    assert not any(s.kind == "linear-solve" for s in acceleration)
    # c' on both of its lines: the arm's tangential line after the normal term, and the line of centres
    # through the point dividing the known gears' tips as C divides the pitch points (here halfway)
    (centre,) = [s for s in acceleration if s.topic == "planet-centre"]
    tip = complex(*centre.value)
    assert solution.acceleration is not None
    size = max(abs(complex(*v)) for v in solution.acceleration.tips.values())
    for line in centre.lines:
        through, direction = complex(*line.through), complex(*line.direction)
        assert abs(((tip - through) * direction.conjugate()).imag) / abs(direction) < 1e-12 * size
    assert complex(*centre.lines[0].through) == pytest.approx(complex(*centre.vectors[0].end), abs=1e-12 * size)
    assert dict(centre.params)["ratio"] == pytest.approx(0.5, rel=1e-14)
    assert [s.topic for s in acceleration].count("rolling") == 1
    points = kinepoly.to_json(solution)["polygons"]["velocity"]["points"]
    assert points["p24@4"] == pytest.approx(points["p24@2"], abs=1e-12)
    assert points["p41@4"] == pytest.approx([0.0, 0.0], abs=1e-12)
    middle = [(a + b) / 2.0 for a, b in zip(points["p24@4"], points["p41@4"], strict=True)]
    assert points["c"] == pytest.approx(middle, rel=1e-12, abs=1e-12)
    # omega_13 = 10 x 30 / 100 (Willis), omega_14 = 3 - 1.5 x 7
    assert kinepoly.to_json(solution)["links"]["3"]["omega"] == pytest.approx(3.0, rel=1e-14)
    assert kinepoly.to_json(solution)["links"]["4"]["omega"] == pytest.approx(-7.5, rel=1e-14)


def test_a_group_with_gears_that_is_no_planet_on_its_arm_is_refused_clearly() -> None:
    # the ring's centre 5 mm off the arm's pivot: exit 2 (a SceneError) naming the pairs and what is built
    text = train(30, 20, 2.0, {"sun": "driven", "arm": "free", "ring": "fixed"}, {"sun": (25.0, 10.0, 2.0)})
    text = text.replace('1 = { points = { O = [0, 0] } }', '1 = { points = { O = [0, 0], O5 = [5, 0] } }')
    text = text.replace('{ center = "O", radius = 70.0 }', '{ center = "O5", radius = 70.0 }')
    assert "O5" in text.split("[[gears]]")[2]
    with pytest.raises(kinepoly.SceneError, match=r"gears\.24: links 3, 4 hold gears \(24, 41\).*not on the arm's "
                                                  r"pivot O.*planet on an arm"):
        kinepoly.solve(kinepoly.loads_scene(text))


def test_a_stepped_planet_between_two_suns_by_willis() -> None:
    # the planet has two pitch circles on its pin: 20 on the driven sun (30), 10 on a fixed second sun (40).
    # Relative to the arm two external meshes: (w_B - w_a) / (w_A - w_a) = (30 / 20) (10 / 40) = 3/8, w_B = 0,
    # so w_a = -3/5 w_A and w_p = w_a - (30 / 20) (w_A - w_a); the same for alpha; C lies beyond both pitch points
    text = """title = "stepped planet"
[links]
1 = { points = { O = [0, 0] } }
2 = { points = { O = [0, 0] } }
3 = { points = { O = [0, 0], C = [50, 0] } }
4 = { points = { C = [0, 0], Q = [12, 0] } }
[[gears]]
links = ["2", "4"]
pitch = [{ center = "O", radius = 30 }, { center = "C", radius = 20 }]
phase = [0, 180]
[[gears]]
links = ["4", "1"]
pitch = [{ center = "C", radius = 10 }, { center = "O", radius = 40 }]
phase = [180, 0]
[input]
link = "2"
angle = 20
omega = 10
alpha = 4
"""
    solution = kinepoly.solve(kinepoly.loads_scene(text))
    data = kinepoly.to_json(solution)
    for key, sun in (("omega", 10.0), ("alpha", 4.0)):
        arm = -0.6 * sun
        assert data["links"]["3"][key] == pytest.approx(arm, rel=1e-13)
        assert data["links"]["4"][key] == pytest.approx(arm - 1.5 * (sun - arm), rel=1e-13)
    assert data["links"]["3"]["angle"] == pytest.approx(-12.0, rel=1e-13)  # -3/5 of 20 degrees
    (centre,) = [s for s in solution.steps if s.topic == "planet-centre"]
    assert dict(centre.params)["ratio"] == pytest.approx(2.0, rel=1e-14)  # |P24 C| = 20 = 2 |P24 P41|
    assert data["check"]["max_rel_error"] < 1e-13


def test_a_planet_on_a_free_arm_drives_further_links() -> None:
    # an epicyclic crank: the ring fixed, the sun driven, a rod from the planet's pin Q to a slider on y = 10.
    # The planet and its arm are placed first (Willis), then the rod and the block as a dyad: the arm at
    # 0.3 theta_s, the planet at -0.75 theta_s (both 0 at the reference mesh), B derived here from Q
    text = train(30, 20, 2.0, {"sun": "driven", "arm": "free", "ring": "fixed"}, {"sun": (30.0, 10.0, 2.0)})
    text = text.replace('[[gears]]', '''5 = { points = { Q = [0, 0], B = [120, 0] } }
6 = { points = { B = [0, 0] } }

[[sliders]]
block = "6"
guide = "1"
point = "B"
line = { through = [0, 10], angle = 0 }

[[gears]]''', 1).replace('velocity = ["Q", "C"]', 'velocity = ["Q", "C", "B"]')
    text += "\n[guess]\nB = [170, 10]\n"
    scene = kinepoly.loads_scene(text)
    solution = kinepoly.solve(scene)
    assert [line for line in solution.plan.describe() if "planet" in line] == ["group 3-4 (planet on its arm)"]
    data = kinepoly.to_json(solution)
    arm, planet = math.radians(0.3 * 30.0), math.radians(-0.75 * 30.0)
    q = 50.0 * complex(math.cos(arm), math.sin(arm)) + 10.0 * complex(math.cos(planet), math.sin(planet))
    assert data["points"]["Q"]["position"] == pytest.approx([q.real, q.imag], rel=1e-13)
    b = q.real + math.sqrt(120.0**2 - (10.0 - q.imag) ** 2)
    assert data["points"]["B"]["position"] == pytest.approx([b, 10.0], rel=1e-13)
    assert data["check"]["max_rel_error"] < 1e-12
    result = sweep(scene, steps=720)
    assert (result.status == 0).all()
