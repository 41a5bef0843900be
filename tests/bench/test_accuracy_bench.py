"""``kinepoly bench``: the reference, the closed forms, the course text's series, the command's output.

The closed forms are checked against the 50-digit reference (which shares no derivative with
them) and against the course text's own formulas; the series against the exact slider-crank
and the size of the dropped binomial term.
"""

from __future__ import annotations

import json
import math
import random
import sys
from pathlib import Path

import numpy as np
import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.bench.cases import four_bar, piston, slider_crank, slotted_lever
from kinepoly.bench.closed_forms import closed_form
from kinepoly.bench.methods import Setting, construction_values, methods_for
from kinepoly.bench.motion import Trig, evaluate
from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import kind_errors
from kinepoly.check.series import slider_crank_series
from kinepoly.cli import main
from kinepoly.scene.spec import Scene


def _closed_form_error(scene: Scene) -> tuple[str, float]:
    solution = kinepoly.solve(scene)
    assert solution.inside is not None
    mech, pose, origin = solution.inside.mechanism, solution.inside.pose, solution.inside.frame.origin
    form = closed_form(mech, pose)
    assert form is not None
    keys = [q.key for q in solution.check.quantities]
    t = getattr(mech.scene.input, "angle_rad", None)
    t = mech.scene.input.s if t is None else t  # type: ignore[union-attr]
    values = evaluate(mech, form.motion(np.array([t])), keys, Trig(np.cos, np.sin), origin)
    one = {k: (tuple(float(x[0]) for x in v) if isinstance(v, tuple) else float(v[0])) for k, v in values.items()}
    reference = reference_values(mech, pose, keys, origin=origin)
    errors = kind_errors(one, reference, dict(solution.check.scales))
    return form.name, max(errors.values())


def test_the_closed_forms_agree_with_the_reference_on_random_mechanisms() -> None:
    rng = random.Random(7)
    seen: dict[str, float] = {}
    for n in range(24):
        scale = 10.0 ** rng.uniform(-2, 2)
        kind = n % 4
        if kind == 0:
            scene = four_bar(scale, scale * rng.uniform(0.15, 0.3), scale * rng.uniform(0.9, 1.1),
                             scale * rng.uniform(0.7, 0.9), rng.uniform(0, 360), upper=rng.random() < 0.5)
        elif kind == 1:
            scene = slider_crank(scale * 0.3, scale, scale * rng.uniform(-0.2, 0.2), rng.uniform(0, 360),
                                 ahead=rng.random() < 0.5)
        elif kind == 2:
            scene = piston(scale * 0.3, scale, rng.uniform(0.05, 3.0), outer=rng.random() < 0.5,
                           upper=rng.random() < 0.5)
        else:
            scene = slotted_lever(scale, scale * rng.uniform(0.2, 0.6), scale * rng.uniform(-0.1, 0.1),
                                  rng.uniform(0, 360))
        name, error = _closed_form_error(scene)
        seen[name] = max(seen.get(name, 0.0), error)
    assert len(seen) == 4
    assert all(error < 1e-12 for error in seen.values()), seen


def test_the_slotted_lever_matches_the_course_texts_transmission_functions() -> None:
    """Lever pivot at the origin, crank pivot l0 above it (the course text's figure):
    omega3 = omega1 l1 (l1 + l0 sin phi1) / (l1^2 + 2 l0 l1 sin phi1 + l0^2) and its epsilon3."""
    l0, l1, w1, e1 = 70.0, 30.0, 12.0, 3.0
    for phi in (0.3, 1.9, 4.0):
        text = f"""
[links]
1 = {{ points = {{ O = [0, 0], A0 = [0, {l0}] }} }}
2 = {{ points = {{ A0 = [0, 0], A = [{l1}, 0] }} }}
3 = {{ points = {{ A = [0, 0] }} }}
4 = {{ points = {{ O = [0, 0] }} }}
[[sliders]]
block = "3"
guide = "4"
point = "A"
line = {{ through = [0, 0], angle = 0 }}
[input]
link = "2"
angle = {math.degrees(phi)!r}
omega = {w1}
alpha = {e1}
[guess]
A = [{l1 * math.cos(phi)!r}, {l0 + l1 * math.sin(phi)!r}]
[find]
omega = ["4"]
alpha = ["4"]
"""
        scene = kinepoly.loads_scene(text)
        phi = scene.input.angle_rad  # type: ignore[union-attr]
        solution = kinepoly.solve(scene)
        den = l1 * l1 + 2 * l0 * l1 * math.sin(phi) + l0 * l0
        omega3 = w1 * l1 * (l1 + l0 * math.sin(phi)) / den
        eps3 = (e1 * l1 * (l1 + l0 * math.sin(phi)) / den
                - w1 * w1 * l0 * l1 * (l1 * l1 - l0 * l0) * math.cos(phi) / den**2)
        assert solution.velocity is not None and solution.acceleration is not None
        assert solution.velocity.omega["4"] == pytest.approx(omega3, rel=1e-13)
        assert solution.acceleration.alpha["4"] == pytest.approx(eps3, rel=1e-12, abs=1e-12 * w1 * w1)
        assert solution.inside is not None
        form = closed_form(solution.inside.mechanism, solution.inside.pose)
        assert form is not None
        motion = form.motion(np.array([phi]))
        assert float(motion["4"].omega[0]) == pytest.approx(omega3, rel=1e-13)
        assert float(motion["4"].alpha[0]) == pytest.approx(eps3, rel=1e-12, abs=1e-12 * w1 * w1)


@pytest.mark.parametrize("offset", [0.0, 10.0, -25.0])
@pytest.mark.parametrize("ahead", [True, False])
def test_the_series_drops_exactly_the_binomial_tail(offset: float, ahead: bool) -> None:
    """x_exact - x_series = -l (z^4/8 + z^6/16 + ...), z = k + lambda sin phi: between l z^4 / 8 and
    l z^4 / (8 (1 - z^2)). The course text's sign convention (line at y = -e) is the scene's offset reversed."""
    r, coupler, w = 40.0, 120.0, 10.0
    for theta in np.linspace(0.0, 350.0, 8):
        solution = kinepoly.solve(slider_crank(r, coupler, offset, float(theta), w, 0.0, ahead=ahead))
        assert solution.inside is not None
        keys = ["sliders.14.s", "sliders.14.s_dot"]
        series = slider_crank_series(solution.inside.mechanism, solution.inside.pose, keys)
        assert series is not None
        got = series.values(np.array([math.radians(float(theta))]))
        exact = solution.slider("14")
        sign = 1.0 if ahead else -1.0
        z = abs(offset / coupler - r / coupler * math.sin(math.radians(float(theta))))
        drop = sign * (exact.s - float(got["sliders.14.s"][0]))  # type: ignore[index]
        assert (-coupler * z**4 / (8 * (1 - z * z)) * (1 + 1e-9) - 1e-12
                <= drop <= -coupler * z**4 / 8 * (1 - 1e-9) + 1e-12)


def test_the_reference_agrees_with_the_construction_on_every_example() -> None:
    for name in ("four-bar", "slider-crank", "slotted-lever", "shaper", "triad"):
        solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
        assert solution.inside is not None
        keys = tuple(q.key for q in solution.check.quantities)
        reference = reference_values(solution.inside.mechanism, solution.inside.pose, list(keys))
        errors = kind_errors(construction_values(solution, keys, (0.0, 0.0)), reference, dict(solution.check.scales))
        assert solution.accuracy is not None
        assert all(err <= solution.accuracy.estimate.relative[kind] for kind, err in errors.items()), name
        assert max(errors.values()) < 1e-12, name


def test_finite_differences_follow_their_theory() -> None:
    """Truncation ~ h^2 for large steps, rounding ~ u / h^2 for small ones: a V with its floor near u^(1/2)."""
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / "four-bar.toml"))
    setting = Setting(solution, tuple(q.key for q in solution.check.quantities))
    assert solution.inside is not None
    keys = list(setting.keys)
    reference = reference_values(setting.mechanism, setting.pose, keys)
    errors = {}
    for method in methods_for(setting, (1e-1, 1e-2, 1e-4, 1e-7)):
        if method.family == "finite differences":
            values = method.values(method.compute(np.array([solution.inside.mechanism.scene.input.angle_rad]),  # type: ignore[union-attr]
                                                  None), 0)
            errors[method.step] = max(kind_errors(values, reference, dict(solution.check.scales)).values())
    assert 3e-3 < errors[1e-2] / errors[1e-1] < 3e-2  # h^2
    assert errors[1e-4] < 1e-6 and errors[1e-7] > 1e2 * errors[1e-4]  # rounding takes over


def _bench_json(capsys: pytest.CaptureFixture[str], *args: str) -> dict[str, object]:
    assert main(["bench", *args, "--json", "--budget", "0.005"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert isinstance(data, dict)
    return data


def test_bench_prints_every_method_with_its_error_and_time(capsys: pytest.CaptureFixture[str]) -> None:
    data = _bench_json(capsys, str(EXAMPLES / "slider-crank.toml"))
    methods = {m["name"]: m for m in data["methods"]}  # type: ignore[attr-defined]
    construction = next(m for m in methods.values() if "construction" in m["name"] and m["family"] == "construction")
    assert construction["error"] < 1e-14 and construction["time_s"] > 0
    families = {m["family"] for m in methods.values()}
    assert families == {"construction", "analytic", "closed form", "series", "GEOS", "finite differences"}
    series = next(m for m in methods.values() if m["family"] == "series")
    assert 1e-5 < series["error"] < 1e-2  # lambda = 1/3: the dropped term is about (1/3)^4 / 8 of the rod
    closed = next(m for m in methods.values() if m["family"] == "closed form")
    assert closed["error"] < 1e-14 and closed["batch"] > 1


def test_bench_plots_the_work_precision_diagram(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    target = tmp_path / "wp.png"
    assert main(["bench", str(EXAMPLES / "four-bar.toml"), "--plot", str(target), "--budget", "0.005"]) == 0
    out = capsys.readouterr().out
    assert "construction (polygons, homogeneous crossings)" in out and "time/construction" in out
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert [p.name for p in tmp_path.iterdir()] == ["wp.png"]  # no temporary file left behind


def test_a_sweep_marks_the_dead_centres_of_a_piston_stroke(capsys: pytest.CaptureFixture[str],
                                                           tmp_path: Path) -> None:
    scene = tmp_path / "piston.toml"
    scene.write_text((Path(__file__).resolve().parents[2] / "benchmarks" / "scenes" / "piston-near-dead-centre.toml")
                     .read_text())
    data = _bench_json(capsys, str(scene), "--sweep", "10")
    sweep = data["sweep"]
    assert isinstance(sweep, dict)
    singular = sorted(sweep["singular"])
    assert singular == pytest.approx([80.0, 160.0], abs=1e-6)  # a3 - a2 and a3 + a2: crank and rod in line
    statuses = [p["status"] for p in sweep["points"]]  # the stroke is kinepoly sweep's: dead centre to dead centre
    assert set(statuses[1:-1]) == {"ok"} and "ok" not in (statuses[0], statuses[-1])
    assert all(p["errors"] for p in sweep["points"] if p["status"] == "ok")
    assert all(80.0 - 1e-6 < p["input"] < 160.0 + 1e-6 for p in sweep["points"])
    target = tmp_path / "sweep.png"
    assert main(["bench", str(scene), "--sweep", "6", "--plot", str(target)]) == 0
    assert "singular positions (mm): 80" in capsys.readouterr().out and target.exists()


def test_bench_refuses_a_given_scene_and_a_missing_mpmath(capsys: pytest.CaptureFixture[str],
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    assert main(["bench", str(EXAMPLES / "image-point.toml")]) == 2
    assert "needs a scene driven by [input]" in capsys.readouterr().err
    monkeypatch.setitem(sys.modules, "mpmath", None)
    assert main(["bench", str(EXAMPLES / "four-bar.toml")]) == 2
    assert "pip install 'kinepoly[bench]'" in capsys.readouterr().err


def test_bench_reports_the_steps_that_reach_past_a_dead_centre(capsys: pytest.CaptureFixture[str]) -> None:
    path = Path(__file__).resolve().parents[2] / "benchmarks" / "scenes" / "piston-near-dead-centre.toml"
    data = _bench_json(capsys, str(path))
    fd = [m for m in data["methods"] if m["family"] == "finite differences"]  # type: ignore[attr-defined]
    failed = [m for m in fd if "failure" in m]
    assert failed and all("cannot assemble" in m["failure"] and m["error"] is None for m in failed)
    answered = [m for m in data["methods"] if m.get("error") is not None]  # type: ignore[attr-defined]
    assert all(math.isfinite(m["error"]) for m in answered)
    construction = next(m for m in answered if m["family"] == "construction")
    assert construction["error"] <= data["estimate"]  # type: ignore[operator]
