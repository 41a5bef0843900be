"""The accuracy report of ``kinepoly solve``: local frame, estimates, the two relative errors, warnings, messages.

Every expected value is derived independently here (law of cosines, the course text's closed
forms, hand-built vectors), never copied from the code's output.
"""

from __future__ import annotations

import json
import math

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.bench.cases import four_bar, piston, slider_crank, slotted_lever_reversal, translated
from kinepoly.check import componentwise_error, estimate_errors, localize, normwise_error
from kinepoly.check.conditions import MIN_TRANSMISSION_DEG
from kinepoly.check.estimate import C_ACCELERATION, C_POSITION, C_VELOCITY, crossings
from kinepoly.cli import main
from kinepoly.errors import SingularityError
from kinepoly.geom.tolerances import UNIT_ROUNDOFF

U = UNIT_ROUNDOFF


# -- the local frame -------------------------------------------------------------------------------


def test_a_mechanism_near_its_origin_is_solved_where_it_is() -> None:
    scene = kinepoly.load_scene(EXAMPLES / "four-bar.toml")
    frame = localize(scene)
    assert frame.is_identity and frame.scene is scene and frame.origin == (0.0, 0.0)


def test_a_far_mechanism_is_solved_near_the_origin_and_reported_where_it_is() -> None:
    near = four_bar(100, 40, 120, 80, 60)
    far = translated(near, (1e6, -2e6))
    frame = localize(far)
    assert frame.origin == (1e6, -2e6)
    inside = {p.name: p.local for p in frame.scene.link("1").points}
    assert inside == {"A0": (0.0, 0.0), "B0": (100.0, 0.0)}
    a, b = kinepoly.solve(near), kinepoly.solve(far)
    for label in ("A", "B", "C"):
        pa, pb = a.position(label), b.position(label)
        assert pb[0] - 1e6 == pytest.approx(pa[0], abs=2e-10) and pb[1] + 2e6 == pytest.approx(pa[1], abs=3e-10)


def test_translating_by_a_million_costs_no_accuracy() -> None:
    """Velocities, accelerations and rates of the translated mechanism are the very same numbers."""
    near = kinepoly.solve(four_bar(100, 40, 120, 80, 60))
    for offset in ((1e6, 1e6), (-3e9, 7e8)):
        far = kinepoly.solve(translated(four_bar(100, 40, 120, 80, 60), offset))
        assert far.velocity is not None and near.velocity is not None
        assert far.velocity.tips == near.velocity.tips and far.velocity.omega == near.velocity.omega
        assert far.acceleration is not None and near.acceleration is not None
        assert far.acceleration.tips == near.acceleration.tips
        assert far.check.relative == near.check.relative


def test_the_pose_is_given_back_in_the_users_frames() -> None:
    far = translated(slider_crank(40, 120, 10, 60), (5e6, 5e6))
    solution = kinepoly.solve(far)
    for link, pose in solution.pose.links.items():
        for point in far.link(link).points:
            at = pose.world(point.local)
            assert math.dist(at, solution.position(point.name)) <= 1e-9


# -- estimates and the two measures of an error ----------------------------------------------------


def test_the_estimate_follows_the_conditioning() -> None:
    est = estimate_errors(100.0, (), ["position", "angle", "velocity", "omega", "acceleration", "alpha"])
    assert est.relative["position"] == est.relative["angle"] == C_POSITION * U * 100.0
    assert est.relative["velocity"] == est.relative["omega"] == C_VELOCITY * U * 1e4
    assert est.relative["acceleration"] == est.relative["alpha"] == C_ACCELERATION * U * 1e4
    assert estimate_errors(1e3, (), ["velocity"]).largest == pytest.approx(100 * est.relative["velocity"])


def test_a_flat_crossing_raises_the_estimate() -> None:
    solution = kinepoly.solve(piston(40, 120, 1e-4))
    flat = min(crossings(solution.steps), key=lambda c: abs(c.sin_angle))
    # the crank and the rod are 1e-4 rad (times 1 + a2/a3) from in line: so are their normals
    assert abs(flat.sin_angle) == pytest.approx(math.sin(1e-4 * (1 + 40 / 120)), rel=1e-3)
    assert solution.accuracy is not None
    assert solution.accuracy.estimate.relative["velocity"] >= 4 * U / abs(flat.sin_angle)


def test_normwise_and_componentwise_errors() -> None:
    assert normwise_error((3.0, 4.0), (0.0, 0.0), 10.0) == 0.5
    assert componentwise_error((1.0, 2.0), (1.0, 2.5)) == pytest.approx(0.2)
    assert componentwise_error((1e-30, 2.0), (0.0, 2.0)) is None  # the ratio is infinite: the measure fails
    assert componentwise_error((0.0, 2.0), (0.0, 2.0)) == 0.0


def test_every_quantity_carries_both_values_its_difference_and_estimate() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "slotted-lever.toml"))
    data = kinepoly.to_json(solution)
    json.dumps(data, allow_nan=False)
    check = data["check"]
    for key in ("reference", "max_rel_error", "relative", "condition_number", "differences"):  # the contract's keys
        assert key in check
    rows = check["quantities"]
    assert set(rows) == set(check["differences"])
    for key, row in rows.items():
        got, ref = row["construction"], row["analytic"]
        diff = math.dist(got, ref) if isinstance(got, list) else abs(got - ref)
        if row["kind"] == "angle":
            diff = abs(math.remainder(got - ref, 2 * math.pi))
        assert row["difference"] == pytest.approx(diff, abs=1e-12 * max(1.0, abs(row["difference"])))
        assert row["difference"] <= row["estimate"], key
        assert row["normwise"] <= check["estimate"][row["kind"]]
    assert set(check["normwise"]) == set(check["estimate"]) == set(check["componentwise"])


def test_componentwise_error_misleads_where_the_coriolis_term_passes_through_zero() -> None:
    """Near a slide reversal a component of the Coriolis term is nearly zero: against the 50-digit
    reference its componentwise error is large (100% at 1e-9 rad) while the normwise one stays at u."""
    from kinepoly.bench.reference import reference_values

    for distance, at_least in ((1e-6, 1e-6), (1e-9, 0.5)):
        solution = kinepoly.solve(slotted_lever_reversal(80, 40, distance))
        assert solution.inside is not None and solution.accuracy is not None
        key = "sliders.43.coriolis"
        ref = reference_values(solution.inside.mechanism, solution.inside.pose, [key]).values[key]
        truth = (float(ref[0]), float(ref[1]))
        got = next(q.construction for q in solution.accuracy.quantities if q.key == key)
        assert isinstance(got, tuple)
        normwise = normwise_error(got, truth, solution.check.scales["acceleration"])
        componentwise = componentwise_error(got, truth)
        assert normwise <= solution.accuracy.estimate.relative["acceleration"] and normwise < 1e-15
        assert componentwise is not None and componentwise >= at_least
        # by hand: v_rel = omega2 a2 a1 sin(theta) / rho = 800 theta, omega4 = omega2 a2 (a2 - a1) / rho^2 = -10
        # (rho = a1 - a2 = 40): |2 omega4 x v_rel| = 16000 theta, square to A B0, which is theta off the x-axis
        assert math.hypot(*truth) == pytest.approx(16000 * distance, rel=1e-5)
        assert abs(truth[0]) == pytest.approx(16000 * distance * distance, rel=1e-3)


# -- warnings with stable codes ------------------------------------------------------------------


def _transmission_four_bar(a1: float, a2: float, a3: float, a4: float, theta_deg: float) -> float:
    """Law of cosines: the angle at B between coupler AB and rocker B0B, folded into [0, 90] degrees."""
    t = math.radians(theta_deg)
    diag2 = a1 * a1 + a2 * a2 - 2 * a1 * a2 * math.cos(t)
    mu = math.degrees(math.acos((a3 * a3 + a4 * a4 - diag2) / (2 * a3 * a4)))
    return min(mu, 180 - mu)


@pytest.mark.parametrize("theta", [0.0, 45.0, 90.0, 150.0, 180.0, 260.0])
def test_the_transmission_angle_warning_follows_the_textbook_angle(theta: float) -> None:
    dims = (100.0, 45.0, 110.0, 60.0)
    solution = kinepoly.solve(four_bar(*dims, theta))
    expected = _transmission_four_bar(*dims, theta)
    warned = [n for n in solution.notices if n.code == "transmission-angle"]
    assert bool(warned) == (expected < MIN_TRANSMISSION_DEG)
    if warned:
        assert f"{expected:.3g} deg" in warned[0].message and "at B" in warned[0].message


def test_a_slider_cranks_transmission_angle_is_its_rods_angle_to_the_slides_normal() -> None:
    # crank 40 at 90 deg, rod 50, line through the pivot: sin(rod to slide) = 40 / 50
    solution = kinepoly.solve(slider_crank(40, 50, 0, 90))
    expected = 90 - math.degrees(math.asin(40 / 50))
    warned = [n for n in solution.notices if n.code == "transmission-angle"]
    assert expected < MIN_TRANSMISSION_DEG and warned and f"{expected:.3g} deg" in warned[0].message


def test_near_singular_warns_when_the_estimate_passes_one_in_a_billion() -> None:
    seen = []
    for distance in (1e-1, 1e-2, 1e-3, 1e-5):
        solution = kinepoly.solve(piston(40, 120, distance))
        assert solution.accuracy is not None
        warns = solution.accuracy.estimate.largest > 1e-9
        notices = [n for n in solution.notices if n.code == "near-singular"]
        assert bool(notices) == warns
        seen.append(warns)
        if notices:
            assert "s14 = " in notices[0].message and "condition number" in notices[0].message
    assert seen[0] is False and seen[-1] is True


# -- singular positions: exit 3, naming the joint and the position, saying why -----------------------


def _run(capsys: pytest.CaptureFixture[str], tmp_path: object, text: str) -> tuple[int, str]:
    from pathlib import Path

    path = Path(str(tmp_path)) / "scene.toml"
    path.write_text(text)
    code = main(["solve", str(path)])
    return code, capsys.readouterr().err


PISTON = """
[links]
1 = { points = { A0 = [0, 0] } }
2 = { points = { A0 = [0, 0], A = [40, 0] } }
3 = { points = { B = [0, 0], A = [120, 0] } }
4 = { points = { B = [0, 0] } }
[[sliders]]
block = "4"
guide = "1"
point = "B"
line = { through = [0, 0], angle = 0 }
[input]
slider = "14"
s = S
s_dot = -500
s_ddot = 0
[guess]
A = [40, 1]
"""


@pytest.mark.parametrize("s", ["160", "80", "159.999999999999", "80.000000000001"])
def test_a_piston_driven_crank_at_its_dead_centre_exits_3_and_says_where_and_why(
        s: str, capsys: pytest.CaptureFixture[str], tmp_path: object) -> None:
    code, err = _run(capsys, tmp_path, PISTON.replace("S", s))
    assert code == 3
    assert "singular position" in err and "joint A" in err and f"s14 = {s} mm" in err
    assert "in line" in err and "Traceback" not in err


def test_a_four_bar_at_its_change_point_is_singular_with_the_joint_named() -> None:
    with pytest.raises(SingularityError, match=r"theta12 = 0 deg.*joint B.*parallel"):
        kinepoly.solve(four_bar(100, 40, 100, 40, 0.0))
