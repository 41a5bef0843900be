"""``kinepoly bench`` on gears and cams: the 50-digit reference against closed forms derived here.

The reference writes each pair from its own geometry (rolling with the phase rule, the contact of a
circle), not from the equivalent links; these closed forms are derived apart from both:

* an external pair on fixed centres, phases 0: theta3 = pi - (r2/r3) theta2 for theta2 in (-pi, pi]
  (the x-axes both point at the pitch point at theta2 = 0; 2 rolls back the shorter way);
* a pinion (centre O, radius r, phase -90 deg) on a rack's line r below it: its lowest point, where
  the rack's point sits at theta2 = 0, moves along +x as it turns counter-clockwise: s = r theta2;
* an eccentric disc (eccentricity e, radius R) under a flat face square to a vertical guide: the
  face sits at y = e sin(theta2) + R;
* Willis for a planetary train.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from msgspec.structs import replace
from tests.scenes import EXAMPLES, cam_rocker

import kinepoly
from kinepoly.bench.methods import Setting, construction_values, methods_for
from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import kind_errors
from kinepoly.cli import main
from kinepoly.model.pose import LinkPose, Pose
from kinepoly.scene.loader import loads_scene

HIGHER_PAIRS = ("gear-pair", "planetary", "rack-pinion", "eccentric-cam-flat", "cam-roller-rocker", "metu-cam")


def _gear_pair(r2: float, r3: float, theta2_deg: float, omega: float, alpha: float) -> str:
    return f"""
[links]
1 = {{ points = {{ O2 = [0, 0], O3 = [{r2 + r3!r}, 0] }} }}
2 = {{ points = {{ O2 = [0, 0] }} }}
3 = {{ points = {{ O3 = [0, 0], E = [{0.7 * r3!r}, 0] }} }}

[[gears]]
links = ["2", "3"]
pitch = [{{ center = "O2", radius = {r2!r} }}, {{ center = "O3", radius = {r3!r} }}]

[input]
link = "2"
angle = {theta2_deg!r}
omega = {omega!r}
alpha = {alpha!r}

[find]
velocity = ["E"]
acceleration = ["E"]
omega = ["3"]
alpha = ["3"]
"""


def _reference(scene_text: str) -> tuple[kinepoly.Solution, dict[str, object]]:
    solution = kinepoly.solve(loads_scene(scene_text))
    assert solution.inside is not None
    keys = [q.key for q in solution.check.quantities if not q.key.startswith("instant_centers.")]
    reference = reference_values(solution.inside.mechanism, solution.inside.pose, keys,
                                 origin=solution.inside.frame.origin)
    return solution, reference.values


@settings(max_examples=25, deadline=None)
@given(r2=st.floats(5, 80), ratio=st.floats(0.3, 3.0), theta2=st.floats(-179.5, 179.5),
       omega=st.floats(-20, 20).map(lambda x: round(x, 3)), alpha=st.floats(-5, 5).map(lambda x: round(x, 3)))
def test_the_reference_rolls_a_gear_pair_as_its_closed_form(r2: float, ratio: float, theta2: float, omega: float,
                                                             alpha: float) -> None:
    r3 = r2 * ratio
    _, ref = _reference(_gear_pair(r2, r3, theta2, omega, alpha))
    theta3 = math.pi - (r2 / r3) * math.radians(theta2)
    w3, a3 = -(r2 / r3) * omega, -(r2 / r3) * alpha
    arm = 0.7 * r3 * complex(math.cos(theta3), math.sin(theta3))
    e = complex(r2 + r3) + arm
    v, a = w3 * 1j * arm, a3 * 1j * arm - w3 * w3 * arm
    size = r2 + r3
    assert float(ref["links.3.omega"]) == pytest.approx(w3, rel=1e-12, abs=1e-12 * abs(omega))  # type: ignore[arg-type]
    assert float(ref["links.3.alpha"]) == pytest.approx(a3, rel=1e-12, abs=1e-12 * (abs(alpha) + 1))  # type: ignore[arg-type]
    got_e = ref["points.E.position"]
    assert isinstance(got_e, tuple)
    assert abs(complex(float(got_e[0]), float(got_e[1])) - e) < 1e-12 * size
    got_v, got_a = ref["points.E.velocity"], ref["points.E.acceleration"]
    assert isinstance(got_v, tuple) and isinstance(got_a, tuple)
    assert abs(complex(float(got_v[0]), float(got_v[1])) - v) < 1e-12 * size * (abs(omega) + 1)
    assert abs(complex(float(got_a[0]), float(got_a[1])) - a) < 1e-12 * size * (omega * omega + abs(alpha) + 1)


def test_the_reference_slides_the_rack_and_turns_the_planetary_train_by_their_closed_forms() -> None:
    # rack-pinion.toml: r = 25, theta2 = 30 deg, omega 4, alpha -3; at theta2 = 0 the pinion's x-axis
    # turned -90 deg points down at P = (0, -25), where the rack's point R is (s13 = 0); turning
    # counter-clockwise the pinion's lowest point moves in +x: s13 = r theta2, s_dot = r omega, s_ddot = r alpha
    _, ref = _reference((EXAMPLES / "rack-pinion.toml").read_text())
    r, theta = 25.0, math.radians(30.0)
    assert float(ref["sliders.13.s"]) == pytest.approx(r * theta, rel=1e-14)  # type: ignore[arg-type]
    assert float(ref["sliders.13.s_dot"]) == pytest.approx(r * 4.0, rel=1e-14)  # type: ignore[arg-type]
    assert float(ref["sliders.13.s_ddot"]) == pytest.approx(-r * 3.0, rel=1e-14)  # type: ignore[arg-type]
    # planetary.toml: Willis, sun fixed (30), planet (20), ring (70), arm omega 10, alpha 2
    _, ref = _reference((EXAMPLES / "planetary.toml").read_text())
    assert float(ref["links.3.omega"]) == pytest.approx(10.0 * (1 + 30 / 20), rel=1e-14)  # type: ignore[arg-type]
    assert float(ref["links.4.omega"]) == pytest.approx(10.0 * (1 + 30 / 70), rel=1e-14)  # type: ignore[arg-type]
    assert float(ref["links.4.alpha"]) == pytest.approx(2.0 * (1 + 30 / 70), rel=1e-14)  # type: ignore[arg-type]


def test_the_reference_lifts_the_flat_face_of_an_eccentric_cam_harmonically() -> None:
    # eccentric-cam-flat.toml: e = 12, R = 35, theta2 = 40 deg, omega 15, alpha 0: T = (0, e sin + R)
    _, ref = _reference((EXAMPLES / "eccentric-cam-flat.toml").read_text())
    e, big_r, theta, w = 12.0, 35.0, math.radians(40.0), 15.0
    t, v, a = ref["points.T.position"], ref["points.T.velocity"], ref["points.T.acceleration"]
    assert isinstance(t, tuple) and isinstance(v, tuple) and isinstance(a, tuple)
    assert [float(x) for x in t] == pytest.approx([0.0, e * math.sin(theta) + big_r], abs=1e-13)
    assert [float(x) for x in v] == pytest.approx([0.0, e * w * math.cos(theta)], abs=1e-12)
    assert [float(x) for x in a] == pytest.approx([0.0, -e * w * w * math.sin(theta)], abs=1e-11)


def test_the_reference_refuses_gear_angles_off_the_phase_rule() -> None:
    # the driven gear turned 0.01 rad off its rolled angle: no whole turns of 40 and 60 give that arc
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "gear-pair.toml"))
    assert solution.inside is not None
    links = dict(solution.inside.pose.links)
    links["3"] = replace(links["3"], theta=links["3"].theta + 0.01)
    keys = ["links.3.omega"]
    with pytest.raises(RuntimeError, match=r"gears\.23: the construction's gear angles are 0\.6 of rolled arc"):
        reference_values(solution.inside.mechanism, Pose(links), keys)
    assert isinstance(links["3"], LinkPose)


@pytest.mark.parametrize("name", HIGHER_PAIRS)
def test_the_construction_agrees_with_the_reference_on_every_higher_pair_example(name: str) -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    assert solution.inside is not None and solution.accuracy is not None
    keys = tuple(q.key for q in solution.check.quantities if not q.key.startswith("instant_centers."))
    reference = reference_values(solution.inside.mechanism, solution.inside.pose, list(keys),
                                 origin=solution.inside.frame.origin)
    errors = kind_errors(construction_values(solution, keys, solution.inside.frame.origin), reference,
                         dict(solution.check.scales))
    assert all(err <= solution.accuracy.estimate.relative[kind] for kind, err in errors.items()), errors
    assert max(errors.values()) < 1e-13


def test_finite_differences_follow_the_gears_phase_through_half_a_turn() -> None:
    # at theta2 = 180 deg the input gear's rolled angle passes half a turn: the positions a step before
    # and after, each rolled its own shorter way, would be a turn of gear 2 apart (gear 3: 240 deg)
    text = _gear_pair(40.0, 60.0, 180.0, 12.0, 1.0)
    solution = kinepoly.solve(loads_scene(text))
    assert solution.inside is not None
    setting = Setting(solution, tuple(q.key for q in solution.check.quantities))
    reference = reference_values(setting.mechanism, setting.pose, list(setting.keys))
    for method in methods_for(setting, (1e-4,)):
        if method.family == "finite differences":
            values = method.values(method.compute(np.array([math.pi]), None), 0)
            assert max(kind_errors(values, reference, dict(solution.check.scales)).values()) < 1e-6


@pytest.mark.parametrize("name", HIGHER_PAIRS)
def test_bench_prints_its_table_on_every_higher_pair_example(name: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", str(EXAMPLES / f"{name}.toml"), "--json", "--budget", "0.002"]) == 0
    data = json.loads(capsys.readouterr().out)
    methods = {m["family"]: m for m in data["methods"]}
    assert {"construction", "analytic", "GEOS", "finite differences"} <= set(methods)
    assert methods["construction"]["error"] < 1e-13 and methods["construction"]["time_s"] > 0
    assert methods["construction"]["error"] <= data["estimate"]


def test_a_bench_sweep_of_the_planetary_train_is_exact_at_every_input(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", str(EXAMPLES / "planetary.toml"), "--sweep", "8", "--json", "--budget", "0.002"]) == 0
    sweep = json.loads(capsys.readouterr().out)["sweep"]
    assert [p["status"] for p in sweep["points"]] == ["ok"] * 8
    worst = max(max(p["errors"].values()) for p in sweep["points"])
    assert worst < 1e-6  # finite differences at their best step; the construction far below


@pytest.mark.parametrize("follower", ["knife", "inside"])
def test_a_knife_edge_and_a_roller_in_a_groove_touch_the_disc_in_the_reference(follower: str) -> None:
    # the reference's contact row (|W - K| = R, or R - r inside) against the construction and against the
    # four-bar closed form of the same motion (the bench's Freudenstein solution, apart from both)
    solution = kinepoly.solve(loads_scene(cam_rocker(follower)))
    assert solution.inside is not None
    setting = Setting(solution, tuple(q.key for q in solution.check.quantities
                                      if not q.key.startswith("instant_centers.")))
    reference = reference_values(setting.mechanism, setting.pose, list(setting.keys))
    t = np.array([math.radians(30.0)])
    families = {}
    for method in methods_for(setting, ()):
        if method.family in ("construction", "closed form"):
            values = method.values(method.compute(t, None), 0)
            families[method.family] = max(kind_errors(values, reference, dict(solution.check.scales)).values())
    assert set(families) == {"construction", "closed form"}
    assert max(families.values()) < 1e-13
