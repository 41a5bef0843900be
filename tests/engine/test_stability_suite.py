"""The stability suite: stiff and extreme cases never give NaN, inf or an uncaught exception;
results scale exactly with lengths and speeds; errors stay within the estimate.

"Within the estimate" is checked two ways: the construction against the analytic solution
(what ``solve`` reports) and, on fewer cases, against the 50-digit mpmath reference.
"""

from __future__ import annotations

import json
import math
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.bench.cases import (
    four_bar,
    four_bar_limit,
    piston,
    random_case,
    scaled,
    slider_crank,
    slotted_lever,
    slotted_lever_reversal,
    translated,
)
from kinepoly.bench.methods import construction_values
from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import kind_errors
from kinepoly.check import normwise_error
from kinepoly.errors import KinepolyError, SingularityError
from kinepoly.scene.spec import Scene
from kinepoly.solution import Solution

DYAD_EXAMPLES = ["four-bar", "slider-crank", "slotted-lever", "shaper", "image-point"]


def _values(solution: Solution) -> dict[str, tuple[str, object]]:
    assert solution.accuracy is not None
    return {q.key: (q.kind, q.construction) for q in solution.accuracy.quantities}


def _all_finite(solution: Solution) -> None:
    json.dumps(kinepoly.to_json(solution), allow_nan=False)  # raises on NaN or inf


def _truth_within_estimate(solution: Solution) -> float:
    """The construction's error against the reference, over its estimate (<= 1 means bounded)."""
    assert solution.inside is not None and solution.accuracy is not None
    keys = tuple(q.key for q in solution.check.quantities)
    reference = reference_values(solution.inside.mechanism, solution.inside.pose, list(keys),
                                 origin=solution.inside.frame.origin)
    errors = kind_errors(construction_values(solution, keys, solution.inside.frame.origin), reference,
                         dict(solution.check.scales))
    return max(err / solution.accuracy.estimate.relative[kind] for kind, err in errors.items())


def _check_within_estimate(solution: Solution) -> None:
    assert solution.accuracy is not None
    for q in solution.accuracy.quantities:
        assert q.difference <= q.estimate, (q.key, q.difference, q.estimate)


# -- scaling: exact with powers of two, within the estimate otherwise ------------------------------


def _scale_of(kind: str, length: float, speed: float) -> float:
    return {"position": length, "angle": 1.0, "velocity": length * speed, "omega": speed,
            "acceleration": length * speed * speed, "alpha": speed * speed}[kind]


@pytest.mark.parametrize("name", DYAD_EXAMPLES)
@pytest.mark.parametrize("length,speed", [(2.0**-20, 1.0), (2.0**20, 1.0), (1.0, 2.0**-23), (1.0, 2.0**17),
                                          (2.0**-20, 2.0**17), (2.0**20, 2.0**-23)])
def test_results_scale_exactly_with_lengths_and_speeds(name: str, length: float, speed: float) -> None:
    """Lengths 2^-20 .. 2^20 (about 1e-6 .. 1e6), speeds 2^-23 .. 2^17 rad/s (1e-7 .. 1e5): every number
    scales by the power of two exactly, bit for bit."""
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    base = _values(kinepoly.solve(scene))
    got = _values(kinepoly.solve(scaled(scene, length, speed)))
    for key, (kind, value) in base.items():
        f = _scale_of(kind, length, speed)
        expected = (f * value[0], f * value[1]) if isinstance(value, tuple) else f * value  # type: ignore[index]
        assert got[key][1] == expected, key


@pytest.mark.parametrize("name", [*DYAD_EXAMPLES, "triad"])
@pytest.mark.parametrize("length,speed", [(1e-6, 1.0), (1e6, 1.0), (1.0, 1e-7), (1.0, 1e5), (1e-6, 1e5), (1e6, 1e-7)])
def test_results_scale_with_decimal_factors_within_the_estimate(name: str, length: float, speed: float) -> None:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    base = kinepoly.solve(scene)
    solution = kinepoly.solve(scaled(scene, length, speed))
    _all_finite(solution)
    assert solution.accuracy is not None
    got = _values(solution)
    for key, (kind, value) in _values(base).items():
        f = _scale_of(kind, length, speed)
        expected = (f * value[0], f * value[1]) if isinstance(value, tuple) else f * value  # type: ignore[index]
        err = normwise_error(got[key][1], expected, solution.check.scales[kind])  # type: ignore[arg-type]
        assert err <= 2 * solution.accuracy.estimate.relative[kind], (key, err)


@pytest.mark.parametrize("ratio", [1e2, 1e3, 1e4, 1e5])
def test_link_ratios_to_1e5(ratio: float) -> None:
    """A crank 1/ratio of the other links (four-bar, slider-crank), and a slider-crank's rod ratio times its crank."""
    for scene in (four_bar(ratio, 1.0, ratio * 1.1, ratio, 37.0), slider_crank(1.0, ratio, 0.3, 37.0),
                  slider_crank(ratio * 0.3, ratio, ratio * 0.05, 200.0)):
        solution = kinepoly.solve(scene)
        _all_finite(solution)
        _check_within_estimate(solution)
    assert _truth_within_estimate(kinepoly.solve(four_bar(ratio, 1.0, ratio * 1.1, ratio, 37.0))) <= 1.0


# -- translation and many turns --------------------------------------------------------------------


@pytest.mark.parametrize("offset", [(1e6, 0.0), (1e6, -1e6), (-7e9, 3e9)])
def test_a_translated_mechanism_gives_the_same_numbers(offset: tuple[float, float]) -> None:
    for name in ("four-bar", "slotted-lever", "shaper"):
        scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
        base, far = _values(kinepoly.solve(scene)), kinepoly.solve(translated(scene, offset))
        _all_finite(far)
        for key, (kind, value) in _values(far).items():
            if kind == "position" and key.startswith("points."):
                assert isinstance(value, tuple)
                moved = base[key][1]
                assert isinstance(moved, tuple)
                assert math.dist(value, (moved[0] + offset[0], moved[1] + offset[1])) <= 4 * math.ulp(max(
                    abs(offset[0]), abs(offset[1])))
            else:
                assert value == base[key][1], key


@pytest.mark.parametrize("turns", [1, 1000, 10**6, 10**9])
def test_input_angles_after_many_turns(turns: int) -> None:
    """60 + 360 n degrees: the same position as 60 degrees, up to the rounding of the angle itself."""
    for make in (lambda a: four_bar(100, 40, 120, 80, a), lambda a: slider_crank(40, 120, 10, a),
                 lambda a: slotted_lever(80, 40, 15, a)):
        base, far = kinepoly.solve(make(60.0)), kinepoly.solve(make(60.0 + 360.0 * turns))
        _all_finite(far)
        _check_within_estimate(far)
        assert far.accuracy is not None
        angle = math.radians(60.0 + 360.0 * turns)
        slack = 8 * math.ulp(angle) * far.check.condition_number + far.accuracy.estimate.largest
        got = _values(far)
        for key, (kind, value) in _values(base).items():
            assert normwise_error(got[key][1], value, far.check.scales[kind]) <= slack, key  # type: ignore[arg-type]
    assert _truth_within_estimate(kinepoly.solve(four_bar(100, 40, 120, 80, 60.0 + 360.0 * turns))) <= 1.0


# -- dead points, nearly parallel lines, vanishing sliding speed -----------------------------------

DISTANCES = [10.0**-n for n in range(1, 9)]


def _near_dead_point(scene: Scene) -> Solution | None:
    """The solution, or None where the input is so near the dead point that it is singular (exit 3)."""
    try:
        solution = kinepoly.solve(scene)
    except SingularityError as error:
        text = str(error)
        assert "singular position" in text and "joint" in text and "in line" in text
        return None
    _all_finite(solution)
    _check_within_estimate(solution)
    return solution


@pytest.mark.parametrize("distance", DISTANCES)
def test_approaching_the_dead_centres_of_a_piston_driven_crank(distance: float) -> None:
    """1e-1 .. 1e-8 rad from the outer and inner dead centres: exact to the estimate, or a named singularity."""
    for outer in (True, False):
        solution = _near_dead_point(piston(40, 120, distance, outer=outer))
        if solution is None:
            assert distance < 1e-5  # only very near the dead centre is the position called singular
            continue
        assert _truth_within_estimate(solution) <= 1.0


@pytest.mark.parametrize("distance", DISTANCES)
def test_approaching_the_limit_of_a_rocking_input(distance: float) -> None:
    """A four-bar whose input link rocks, near the limit where coupler and rocker line up:
    the velocity direction lines there are nearly parallel."""
    scene = four_bar_limit(100, 60, 70, 50, distance)
    assert scene is not None
    solution = _near_dead_point(scene)
    assert solution is not None and solution.accuracy is not None
    flat = solution.accuracy.estimate.worst_crossing["velocity"]
    assert abs(flat.sin_angle) < 10 * math.sqrt(distance)  # the lines cross at an angle of order sqrt(distance)
    assert _truth_within_estimate(solution) <= 1.0


@pytest.mark.parametrize("distance", [*DISTANCES, 0.0])
def test_coriolis_with_a_vanishing_sliding_speed(distance: float) -> None:
    solution = _near_dead_point(slotted_lever_reversal(80, 40, distance))
    assert solution is not None and solution.acceleration is not None
    coriolis = solution.acceleration.coriolis["43"]
    assert math.hypot(*coriolis) <= 16000 * distance * 1.01 + 1e-9  # 2 |omega4| |v_rel|, by hand
    assert _truth_within_estimate(solution) <= 1.0


def test_instant_centers_near_infinity() -> None:
    """A parallelogram's coupler translates: I13 is at infinity (a direction); nearly so, it is far away."""
    exact = kinepoly.to_json(kinepoly.solve(four_bar(100, 40, 100, 40, 60, upper=True, centers='"13"')))
    assert set(exact["instant_centers"]["13"]) == {"direction"}
    for excess in (1e-12, 1e-9, 1e-6):
        solution = kinepoly.solve(four_bar(100, 40, 100 * (1 + excess), 40, 60, upper=True, centers='"13"'))
        data = kinepoly.to_json(solution)
        json.dumps(data, allow_nan=False)
        center = data["instant_centers"]["13"]
        if "position" in center:
            assert math.hypot(*center["position"]) > 1e3 * 100


# -- the assembly is followed over a full turn ------------------------------------------------------


def test_a_parallelogram_never_flips_to_its_anti_parallelogram_over_a_full_turn() -> None:
    """The bench's sweep takes its rows from kinepoly.sweep: the change points are its singular rows, and each
    row solved with the sweep's guess stays a parallelogram."""
    from kinepoly.bench.sweep import run_sweep, solve_at
    from kinepoly.sweep import prepare_sweep
    from kinepoly.sweep import run_sweep as sweep_rows
    from kinepoly.sweep.rows import row_guesses

    solution = kinepoly.solve(four_bar(100, 40, 100, 40, 30, upper=True))
    bench = run_sweep(solution, 36)
    assert bench.singular == pytest.approx([0.0, math.pi], abs=1e-12)  # all four links in line at 0 and 180 deg
    assert all(p.measured and p.errors[bench.methods[0]] < 1e-11 for p in bench.points if p.status == "ok")
    result = sweep_rows(prepare_sweep(solution.scene), steps=36)
    singular = 0
    for row, guess in enumerate(row_guesses(result)):
        t = math.radians(float(result.input.values[row]))
        if result.status_name(row) == "singular":
            assert min(abs(math.remainder(t, math.pi)), 1.0) < 1e-9
            singular += 1
            continue
        got = solve_at(solution, t, guess)
        assert abs(math.remainder(got.angle("3"), 2 * math.pi)) < 1e-9  # the coupler stays parallel to the frame
        assert abs(math.remainder(got.angle("4") - t, 2 * math.pi)) < 1e-9  # the rocker turns with the crank
    assert singular == 2


# -- random cases: at least 99% within the estimate ------------------------------------------------


def test_random_cases_stay_within_the_estimate() -> None:
    """Every standard kind, ordinary poses to 1e-8 rad from a dead point, scale 1e-3 .. 1e3."""
    rng = random.Random(20261121)
    bounded = total = singular = 0
    for _ in range(300):
        case = random_case(rng)
        try:
            solution = kinepoly.solve(case.scene)
        except SingularityError:
            assert case.distance is not None and case.distance < 1e-5
            singular += 1
            continue
        _all_finite(solution)
        assert solution.accuracy is not None
        total += 1
        bounded += all(q.difference <= q.estimate for q in solution.accuracy.quantities)
    assert bounded >= 0.99 * total and total >= 250


def test_random_cases_against_the_reference_stay_within_the_estimate() -> None:
    rng = random.Random(5)
    ratios = []
    while len(ratios) < 40:
        try:
            solution = kinepoly.solve(random_case(rng).scene)
        except SingularityError:
            continue
        ratios.append(_truth_within_estimate(solution))
    assert sum(r <= 1.0 for r in ratios) >= 0.99 * len(ratios)


@settings(max_examples=40, deadline=None)
@given(kind=st.sampled_from(["four-bar", "slider-crank", "slotted-lever"]),
       exponent=st.floats(-6, 6), speed_exponent=st.floats(-7, 5), theta=st.floats(-720, 720),
       x=st.floats(-1e6, 1e6), y=st.floats(-1e6, 1e6))
def test_never_nan_inf_or_an_uncaught_exception(kind: str, exponent: float, speed_exponent: float, theta: float,
                                                x: float, y: float) -> None:
    scene = {"four-bar": lambda: four_bar(100, 40, 120, 80, theta),
             "slider-crank": lambda: slider_crank(40, 120, 10, theta),
             "slotted-lever": lambda: slotted_lever(80, 40, 15, theta)}[kind]()
    scene = translated(scaled(scene, 10.0**exponent, 10.0**speed_exponent), (x, y))
    try:
        solution = kinepoly.solve(scene)
    except KinepolyError as error:
        assert error.exit_code == 3  # a dead point or a pose that cannot close: named, never a crash
        return
    _all_finite(solution)
    _check_within_estimate(solution)
