"""``kinepoly sweep``: rows equal ``kinepoly solve``, branches followed, gaps marked, CSV, plots, CLI."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from tests.cli_support import run
from tests.scenes import EXAMPLES, four_bar, slider_crank
from tests.sweep_support import ask_everything, compare_row

import kinepoly
import kinepoly.sweep
from kinepoly.sweep import prepare_sweep, run_sweep, sweep
from kinepoly.sweep.plots import plot_figure, plot_png
from kinepoly.sweep.table import csv_text

EXAMPLE_NAMES = ["four-bar", "slider-crank", "slotted-lever", "shaper", "centers-six-bar", "triad", "kc0-six-bar"]


@pytest.mark.parametrize("name", EXAMPLE_NAMES)
def test_every_row_equals_solve_at_that_input(name: str) -> None:
    text = ask_everything((EXAMPLES / f"{name}.toml").read_text())
    result = sweep(kinepoly.loads_scene(text), steps=19)
    assert result.rows == (19 if result.periodic else 20)  # 19 intervals: a range has both ends
    assert max(compare_row(text, result, k) for k in range(result.rows)) < 1e-10


TRIAD_WITH_SLIDER = """
title = "Triad with a block on the frame (a Newton group with a slider)"
[links]
1 = { points = { A0 = [0, 0], E = [150, 100] } }
2 = { points = { A0 = [0, 0], A = [30, 0] } }
3 = { points = { D = [0, 0], B = [40.0, 30.0], C = [30.0, -30.0] } }
4 = { points = { E = [0, 0], B = [44.721359549995796, 0] } }
5 = { points = { C = [0, 0] } }
6 = { points = { A = [0, 0], D = [60.01602943086692, 0] } }
[[sliders]]
block = "5"
guide = "1"
point = "C"
line = { through = [140, 0], angle = 151.7 }
[input]
link = "2"
angle = 60
omega = 5
alpha = 2
[guess]
D = [71, 49]
B = [109, 81]
C = [101, 21]
"""


def test_newton_group_with_a_slider_rows_equal_solve() -> None:
    text = ask_everything(TRIAD_WITH_SLIDER)
    result = sweep(kinepoly.loads_scene(text), steps=14)  # 14 intervals: 15 rows
    assert not result.periodic  # the crank swings between two dead points of the triad
    assert result.status_name(0) == "near-singular" and result.status_name(14) == "near-singular"
    assert (result.status[1:-1] == 0).all()
    assert max(compare_row(text, result, k) for k in range(result.rows)) < 1e-10


def test_the_scene_input_is_a_row_and_takes_the_solve_assembly() -> None:
    text = (EXAMPLES / "four-bar.toml").read_text()
    scene = kinepoly.loads_scene(text)
    result = sweep(scene, steps=360)
    assert result.periodic and result.input.values[0] == 0.0 and result.input.values[-1] == 359.0
    row = int(np.flatnonzero(result.input.values == 60.0)[0])
    solution = kinepoly.to_json(kinepoly.solve(scene))
    for axis, k in (("x", 0), ("y", 1)):
        assert result.column(f"v_C_{axis}").values[row] == pytest.approx(solution["points"]["C"]["velocity"][k],
                                                                          rel=1e-12)
    assert result.column("omega_3").values[row] == pytest.approx(solution["links"]["3"]["omega"], rel=1e-12)


def test_a_seed_between_rows_is_not_shown() -> None:
    result = sweep(kinepoly.loads_scene((EXAMPLES / "four-bar.toml").read_text()), steps=6, start=0.0, stop=90.0)
    assert result.input.values.tolist() == [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]
    assert result.seed_value == 60.0
    result = sweep(kinepoly.loads_scene((EXAMPLES / "four-bar.toml").read_text()), steps=3, start=0.0, stop=90.0)
    assert result.input.values.tolist() == [0.0, 30.0, 60.0, 90.0]
    shifted = sweep(kinepoly.loads_scene((EXAMPLES / "four-bar.toml").read_text()), steps=4, start=100.0, stop=140.0)
    assert shifted.input.values.tolist() == [100.0, 110.0, 120.0, 130.0, 140.0]
    assert (shifted.status == 0).all()


def _kennedy_13(result_row: dict[str, complex]) -> complex:
    """I13 of a four-bar: where line A0A meets line B0B (Aronhold-Kennedy)."""
    a0, a, b0, b = 0j, result_row["A"], complex(100, 0), result_row["B"]
    d1, d2 = a - a0, b - b0
    t = ((b0 - a0).conjugate() * d2).imag / ((d1.conjugate() * d2).imag)
    return a0 + t * d1


def test_centrodes_of_the_coupler_are_where_kennedy_puts_its_instant_center() -> None:
    result = sweep(kinepoly.loads_scene((EXAMPLES / "four-bar.toml").read_text()), steps=72, centrode="3")
    ix, iy = result.column("I_13_x"), result.column("I_13_y")
    lx, ly = result.column("I_13_local_x"), result.column("I_13_local_y")
    theta3 = np.radians(result.column("theta_3").values)
    checked = 0
    for k in range(result.rows):
        point = {p: complex(result.column(f"r_{p}_x").values[k], result.column(f"r_{p}_y").values[k]) for p in "AB"}
        expected = _kennedy_13(point)
        if abs(expected) > 1e4:  # nearly parallel: the centrode runs off to infinity
            continue
        got = complex(ix.values[k], iy.values[k])
        assert ix.valid[k] and abs(got - expected) < 1e-9 * max(1.0, abs(expected))
        # the moving centrode: the same point in link 3's own frame (A at its origin, AB along x)
        local = (got - point["A"]) * complex(math.cos(theta3[k]), -math.sin(theta3[k]))
        assert abs(complex(lx.values[k], ly.values[k]) - local) < 1e-9 * max(1.0, abs(local))
        checked += 1
    assert checked > 50


def test_transmission_angle_is_the_acute_angle_between_coupler_and_rocker() -> None:
    result = sweep(kinepoly.loads_scene((EXAMPLES / "four-bar.toml").read_text()), steps=90)
    mu = result.column("mu_B")
    for k in range(result.rows):
        a = complex(result.column("r_A_x").values[k], result.column("r_A_y").values[k])
        d = abs(a - 100)
        cos_mu = (120**2 + 80**2 - d * d) / (2 * 120 * 80)
        expected = math.degrees(math.asin(math.sqrt(max(0.0, 1 - cos_mu * cos_mu))))
        assert mu.values[k] == pytest.approx(expected, abs=1e-9)


def test_a_slot_through_its_pivot_transmits_at_90_degrees_at_every_row() -> None:
    """The shaper's block A rides in a slot through the lever's pivot B0: A's path about B0 is square to the slot at
    every row, so mu_A is 90 degrees exactly. (Read as the arcsine of the lines' sine, it lost up to 2e-6 degrees
    here, where the arcsine's slope grows without limit.)"""
    result = sweep(kinepoly.loads_scene((EXAMPLES / "shaper.toml").read_text()), steps=3600)
    mu = result.column("mu_A")
    assert mu.valid.sum() == result.rows
    assert np.abs(mu.values - 90.0).max() < 1e-12


def test_parallelogram_never_flips_to_the_anti_parallelogram() -> None:
    text = four_bar(100, 40, 100, 40, 60, 10, 0, guess_b=(120, 35))
    result = sweep(kinepoly.loads_scene(text), steps=360)
    a = result.column("r_A_x").values + 1j * result.column("r_A_y").values
    b = result.column("r_B_x").values + 1j * result.column("r_B_y").values
    valid = result.column("r_B_x").valid
    assert valid.all()  # the change points close (the circles touch) ...
    assert np.abs(b - a - 100).max() < 1e-9  # ... and B - A stays the frame's A0B0 all the way round
    singular = {float(result.input.values[k]) for k in np.flatnonzero(result.status == 2)}
    assert singular == {0.0, 180.0}  # where the four joints line up the velocity lines are parallel
    assert not result.column("omega_3").valid[0] and result.column("theta_3").valid[0]
    omega4 = result.column("omega_4")
    assert np.allclose(omega4.values[omega4.valid], 10.0, rtol=1e-9)  # the rocker turns with the crank


def test_anti_parallelogram_stays_anti() -> None:
    text = four_bar(100, 40, 100, 40, 60, 10, 0, guess_b=(77, -29))
    result = sweep(kinepoly.loads_scene(text), steps=360)
    a = result.column("r_A_x").values + 1j * result.column("r_A_y").values
    b = result.column("r_B_x").values + 1j * result.column("r_B_y").values
    away = np.abs(np.sin(np.radians(result.input.values))) > 0.05  # the two assemblies meet at 0 and 180
    assert np.abs(b - a - 100)[away].min() > 1.0  # never the parallelogram
    _assert_continuous(result, "B", omega=10.0)


def _assert_continuous(result: kinepoly.sweep.SweepResult, point: str, omega: float) -> None:
    """Each step of the point is no longer than its speed over the crank's speed allows (no jump)."""
    p = result.column(f"r_{point}_x").values + 1j * result.column(f"r_{point}_y").values
    speed = np.abs(result.column(f"v_{point}_x").values + 1j * result.column(f"v_{point}_y").values)
    step = math.radians(float(result.input.values[1] - result.input.values[0]))
    valid = result.column(f"v_{point}_x").valid
    both = valid[1:] & valid[:-1]
    allowed = 1.5 * np.maximum(speed[1:], speed[:-1]) / abs(omega) * step + 1e-9
    assert (np.abs(np.diff(p))[both] <= allowed[both]).all()


def test_rows_that_cannot_be_assembled_are_marked_and_left_empty() -> None:
    text = four_bar(100, 60, 50, 45, 40, 10, 0, guess_b=(110, 50))  # a triple rocker: the crank cannot turn
    scene = kinepoly.loads_scene(text)
    result = sweep(scene, steps=73, start=0.0, stop=360.0)
    cannot = result.status == 3
    assert 0 < cannot.sum() < result.rows
    for col in result.columns:
        assert not col.valid[cannot].any()
        assert np.isfinite(col.values).all()
    # the gap is exactly where |A B0| > a3 + a4 or < |a3 - a4|
    theta = np.radians(result.input.values)
    d = np.abs(60 * np.exp(1j * theta) - 100)
    assert np.array_equal(cannot, (d > 95) | (d < 5))
    text_csv = csv_text(result)
    assert "nan" not in text_csv.lower()
    rows = list(csv.DictReader(io.StringIO(text_csv)))
    gap = rows[int(np.flatnonzero(cannot)[0])]
    assert gap["status"] == "cannot-assemble" and gap["v_C_x"] == "" and gap["theta_2"] != ""
    assert "|A B0|" in gap["warnings"] and ">" in gap["warnings"]
    assert any(n.code == "cannot-assemble" for n in result.notices)


def test_default_range_of_a_rocker_input_is_its_swing() -> None:
    text = four_bar(100, 60, 50, 45, 40, 10, 0, guess_b=(110, 50))
    result = sweep(kinepoly.loads_scene(text), steps=41)
    # the crank swings while |A B0| <= a3 + a4 = 95: cos(theta) >= (100^2 + 60^2 - 95^2) / (2 100 60)
    limit = math.degrees(math.acos((100**2 + 60**2 - 95**2) / (2 * 100 * 60)))
    assert not result.periodic
    assert result.input.values[0] == pytest.approx(-limit, abs=1e-6)
    assert result.input.values[-1] == pytest.approx(limit, abs=1e-6)
    assert (result.status[1:-1] <= 1).all()  # the ends are dead points: singular or near it
    assert result.status[0] >= 1 and result.status[-1] >= 1


def test_default_range_of_a_slider_input_is_its_stroke() -> None:
    text = slider_crank(40, 120, 0, 0, 10, 0).split("[input]")[0] + '[input]\nslider = "14"\ns = 130\ns_dot = 100\n'
    result = sweep(kinepoly.loads_scene(text + "\n[guess]\nA = [20, 35]\n"), steps=21)
    assert result.input.name == "s_14"
    assert result.input.values[0] == pytest.approx(80.0, abs=1e-6)  # a3 - a2
    assert result.input.values[-1] == pytest.approx(160.0, abs=1e-6)  # a3 + a2
    a_y = result.column("r_A_y")
    assert (a_y.values[1:-1] > 0).all()  # the crank stays on the side the guess put it


def test_a_newton_groups_range_ends_close_just_inside_its_dead_points() -> None:
    """kc0-six-bar's input swings between two dead points of its K_C(0) group, which Newton's method closes:
    both ends of the default range are rows that close (near-singular, and saying why), and the solve,
    which shares no sweep code, closes 1e-4 degree inside each end and does not close 1e-4 degree beyond it."""
    text = (EXAMPLES / "kc0-six-bar.toml").read_text()
    result = sweep(kinepoly.loads_scene(text), steps=36)
    assert not result.periodic and (result.status <= 1).all()
    for row in (0, result.rows - 1):
        assert result.status_name(row) == "near-singular"
        assert "inside the dead point" in result.warnings[row]
    for end, outward in ((float(result.input.values[0]), -1.0), (float(result.input.values[-1]), 1.0)):
        kinepoly.solve(kinepoly.loads_scene(text.replace("angle = 60", f"angle = {end - outward * 1e-4!r}")))
        with pytest.raises(kinepoly.AssemblyError):
            kinepoly.solve(kinepoly.loads_scene(text.replace("angle = 60", f"angle = {end + outward * 1e-4!r}")))


@pytest.mark.slow  # six Newton sweeps over their whole range
@settings(max_examples=6, deadline=None)
@given(st.floats(-4, 4), st.floats(-4, 4), st.floats(-4, 4), st.floats(-4, 4))
def test_random_newton_groups_range_ends_close(cx: float, cy: float, gx: float, gy: float) -> None:
    """kc0-six-bar with its frame pivots C and G moved a few mm: wherever the input cannot turn fully, both
    ends of the default range close (near-singular, saying why) and equal the solve at that input."""
    text = ((EXAMPLES / "kc0-six-bar.toml").read_text()
            .replace("C = [170, 20]", f"C = [{170 + cx!r}, {20 + cy!r}]")
            .replace("G = [40, -40]", f"G = [{40 + gx!r}, {-40 + gy!r}]"))
    try:
        result = sweep(kinepoly.loads_scene(text), steps=24)
    except kinepoly.AssemblyError:
        assume(False)  # the scene's own input does not close with the pivots moved
        raise
    assume(not result.periodic)
    for row in (0, result.rows - 1):
        assert result.status_name(row) == "near-singular"
        assert "inside the dead point" in result.warnings[row]
        assert compare_row(text, result, row) < 1e-10


def test_csv_columns_are_named_like_the_answer_keys() -> None:
    result = sweep(kinepoly.loads_scene((EXAMPLES / "slider-crank.toml").read_text()), steps=12)
    header = csv_text(result).splitlines()[0].split(",")
    assert header == ["theta_2", "theta_3", "omega_3", "alpha_3", "r_A_x", "r_A_y", "v_A_x", "v_A_y", "a_A_x",
                      "a_A_y", "r_B_x", "r_B_y", "v_B_x", "v_B_y", "a_B_x", "a_B_y", "r_C_x", "r_C_y", "v_C_x",
                      "v_C_y", "a_C_x", "a_C_y", "mu_B", "status", "warnings"]
    text = (EXAMPLES / "slotted-lever.toml").read_text().replace('alpha = ["4"]', 'alpha = ["4"]\nsliders = ["43"]')
    header = csv_text(sweep(kinepoly.loads_scene(text), steps=12)).splitlines()[0].split(",")
    assert header[:4] == ["theta_2", "theta_4", "omega_4", "alpha_4"]
    assert {"v_A@4_x", "a_A@4_y", "s_43", "s_dot_43", "s_ddot_43", "coriolis_43_x", "mu_A"} <= set(header)


def test_csv_values_read_back_to_the_columns() -> None:
    result = sweep(kinepoly.loads_scene((EXAMPLES / "four-bar.toml").read_text()), steps=36)
    rows = list(csv.DictReader(io.StringIO(csv_text(result))))
    assert len(rows) == 36
    for col in result.columns:
        back = np.array([float(r[col.name]) for r in rows])
        assert np.allclose(back, col.values, rtol=1e-14, atol=1e-12 * max(1.0, float(np.abs(col.values).max())))
    assert {r["status"] for r in rows} == {"ok"}


def test_prepared_sweep_runs_again() -> None:
    prepared = prepare_sweep(kinepoly.loads_scene((EXAMPLES / "four-bar.toml").read_text()))
    first = run_sweep(prepared, steps=3600)
    second = run_sweep(prepared, steps=3600)
    assert np.array_equal(first.column("a_C_x").values, second.column("a_C_x").values)
    assert set(first.timing) == {"prepare_s", "range_s", "execute_s", "total_s"}


def test_newton_group_reports_progress() -> None:
    calls: list[tuple[int, int]] = []
    result = sweep(kinepoly.loads_scene((EXAMPLES / "triad.toml").read_text()), steps=200, start=20, stop=50,
                   progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1][0] == calls[-1][1]
    assert (result.status == 0).all()


def test_plot_draws_the_columns() -> None:
    import matplotlib.pyplot as plt

    result = sweep(kinepoly.loads_scene((EXAMPLES / "four-bar.toml").read_text()), steps=90, centrode="3")
    fig = plot_figure(result)
    try:
        axes = [ax for ax in fig.axes if ax.get_visible()]
        titles = [ax.get_title() for ax in axes]
        assert titles[:3] == ["order 0: positions", "order 1: velocities", "order 2: accelerations"]
        assert any(t.startswith("centrodes of link 3") for t in titles)
        omega = {line.get_label(): line for line in axes[1].get_lines()}
        assert np.array_equal(np.asarray(omega["omega_3"].get_ydata()), result.column("omega_3").values)
        hodograph = next(ax for ax in axes if ax.get_title() == "velocity hodographs")
        line = next(ln for ln in hodograph.get_lines() if ln.get_label() == "C")
        drawn = np.asarray(line.get_xdata())  # a full turn's curve closed: its first row again at its end
        assert np.array_equal(drawn[:-1], result.column("v_C_x").values) and drawn[-1] == drawn[0]
    finally:
        plt.close(fig)
    assert plot_png(result).startswith(b"\x89PNG")


def test_plot_windows_on_the_ok_rows_when_flagged_rows_run_off() -> None:
    """kc0-six-bar's two end rows sit a hair inside dead points (near-singular, rates in the thousands): the
    velocity panel and hodograph are windowed on the ok rows, which they show whole, and say so."""
    import matplotlib.pyplot as plt

    result = sweep(kinepoly.loads_scene((EXAMPLES / "kc0-six-bar.toml").read_text()), steps=72)
    ok = result.status == 0
    assert (~ok).sum() == 2
    fig = plot_figure(result)
    try:
        axes = {ax.get_title(): ax for ax in fig.axes if ax.get_visible()}
        rates = np.concatenate([result.column(f"omega_{k}").values for k in "1234"])
        inside = np.concatenate([result.column(f"omega_{k}").values[ok] for k in "1234"])
        low, high = axes["order 1: velocities"].get_ylim()
        assert np.abs(rates).max() > 5 * max(abs(low), abs(high))  # the end rows run off the window
        assert low <= np.percentile(inside, 1) and np.percentile(inside, 99) <= high
        assert axes["order 1: velocities"].get_ylabel().endswith("clipped")
        speeds = np.abs(result.column("v_B_x").values + 1j * result.column("v_B_y").values)
        window = axes["velocity hodographs"].get_xlim()
        assert speeds.max() > 5 * (window[1] - window[0]) and speeds[ok].min() < window[1] - window[0]
    finally:
        plt.close(fig)


def test_cli_writes_csv_and_plot_whole(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    scene = str(EXAMPLES / "four-bar.toml")
    out, png = tmp_path / "sweep.csv", tmp_path / "sweep.png"
    code, stdout, err = run(capsys, "sweep", scene, "--steps", "36", "-o", str(out), "--plot", str(png))
    assert code == 0, err
    assert "36 positions" in stdout
    assert out.read_text().startswith("theta_2,theta_3,")
    assert png.read_bytes().startswith(b"\x89PNG")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sweep.csv", "sweep.png"]  # no temporary left


def test_cli_prints_csv_without_output_files(capsys: pytest.CaptureFixture[str]) -> None:
    code, stdout, _ = run(capsys, "sweep", str(EXAMPLES / "slider-crank.toml"), "--positions", "4", "--from", "0",
                          "--to", "90")
    assert code == 0
    rows = list(csv.DictReader(io.StringIO(stdout)))
    assert [r["theta_2"] for r in rows] == ["0", "22.5", "45", "67.5", "90"]


@pytest.mark.parametrize(("argv", "code", "message"), [
    (["--steps", "1"], 2, "--positions"),
    (["--steps", "10", "--from", "0"], 2, "--from and --to"),
    (["--steps", "10", "--from", "nan", "--to", "3"], 2, "--from"),
    (["--steps", "10", "--from", "30", "--to", "30"], 2, "is empty"),
    (["--steps", "ten"], 2, "--steps"),
    (["--positions", "0"], 2, "--positions"),
    (["--steps", "10", "--centrode", "1"], 2, "--centrode"),
    (["--steps", "10", "--centrode", "9"], 2, "--centrode"),
    (["--steps", "10", "-o", "/no/such/folder/x.csv"], 2, "-o"),
])
def test_cli_bad_arguments(capsys: pytest.CaptureFixture[str], argv: list[str], code: int, message: str) -> None:
    got, _, err = run(capsys, "sweep", str(EXAMPLES / "four-bar.toml"), *argv)
    assert got == code
    assert message in err and "Traceback" not in err


def test_cli_given_scene_and_unassemblable_seed(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "sweep", str(EXAMPLES / "image-point.toml"), "--steps", "10")
    assert code == 2 and "[given]" in err
    bad = tmp_path / "bad.toml"
    bad.write_text(four_bar(100, 40, 20, 20, 60, 10, 0, guess_b=(110, 80)))
    code, _, err = run(capsys, "sweep", str(bad), "--steps", "10")
    assert code == 3 and "scene's own input" in err


def test_progress_bar_only_on_a_terminal(capsys: pytest.CaptureFixture[str]) -> None:
    from kinepoly.cli.sweep import _ProgressBar

    code, _, err = run(capsys, "sweep", str(EXAMPLES / "triad.toml"), "--steps", "300", "--from", "20", "--to", "50",
                       "-o", "-")
    assert code == 0 and "\r" not in err  # captured standard error is not a terminal: no bar
    stream = io.StringIO()
    bar = _ProgressBar(stream)
    bar(150, 300)
    bar(300, 300)
    bar.close()
    text = stream.getvalue()
    assert "50%" in text and "100%" in text and text.endswith("\r")
