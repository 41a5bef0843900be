"""A cam's sweep columns (the follower's s-v-a and the pressure angle) against closed forms derived here,
and every row against ``kinepoly.solve`` at its input."""

from __future__ import annotations

import cmath
import math
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.sweep_support import compare_row

import kinepoly
from kinepoly.sweep import sweep
from kinepoly.sweep.table import csv_text

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _offset_roller(e: float, radius: float, roller: float, offset: float, theta_deg: float, omega: float,
                   alpha: float = 0.0) -> str:
    """An eccentric disc (centre K at e from the pivot O, radius R) lifting a roller (radius r) on a
    translating follower whose guide is the vertical line x = offset."""
    return f"""
title = "Offset roller follower"
[links]
1 = {{ points = {{ O = [0, 0] }} }}
2 = {{ points = {{ O = [0, 0], K = [{e!r}, 0] }} }}
3 = {{ points = {{ W = [0, 0] }} }}
[[sliders]]
block = "3"
guide = "1"
point = "W"
line = {{ through = [{offset!r}, 0], angle = 90 }}
[[cams]]
cam = "2"
follower = "3"
profile = {{ circle = {{ center = [{e!r}, 0], radius = {radius!r} }} }}
roller = {{ center = "W", radius = {roller!r} }}
[input]
link = "2"
angle = {theta_deg!r}
omega = {omega!r}
alpha = {alpha!r}
[guess]
W = [{offset!r}, {4 * (e + radius + roller)!r}]
[find]
velocity = ["W"]
"""


def _roller_rise(e: float, reach: float, offset: float, theta: complex) -> complex:
    """The roller centre's height y_W: it lies on x = offset at reach = R + r from K = e (cos, sin),
    above K. Written for a complex theta so that the complex step differentiates it."""
    u = offset - e * cmath.cos(theta)
    return e * cmath.sin(theta) + cmath.sqrt(reach * reach - u * u)


def _derivative(f: object, theta: float, order: int) -> float:
    """d^order f / d theta^order by the complex step (first order) on the exact derivative of the lower one."""
    h = 1e-30
    if order == 1:
        return float((f(complex(theta, h)) / h).imag)  # type: ignore[operator]
    step = 1e-5
    return (_derivative(f, theta + step, 1) - _derivative(f, theta - step, 1)) / (2 * step)


def test_flat_faced_translating_follower_s_v_a_is_simple_harmonic() -> None:
    # K = e (cos t, sin t); the face is square to the vertical guide through O and rests on the disc's
    # top, so the slider's s (T's height) is e sin t + R; with t = omega t + alpha t^2 / 2:
    # s_dot = e omega cos t, s_ddot = e (alpha cos t - omega^2 sin t); the normal is along the guide:
    # the pressure angle is zero at every row
    text = (EXAMPLES / "eccentric-cam-flat.toml").read_text().replace("alpha = 0", "alpha = 7")
    result = sweep(kinepoly.loads_scene(text), steps=720)
    t = np.radians(result.input.values)
    e, radius, w, a = 12.0, 35.0, 15.0, 7.0
    s, s_dot, s_ddot = (result.column(n).values for n in ("s_13", "s_dot_13", "s_ddot_13"))
    assert np.max(np.abs(s - (e * np.sin(t) + radius))) <= 1e-12 * (e + radius)
    assert np.max(np.abs(s_dot - e * w * np.cos(t))) <= 1e-12 * e * w
    assert np.max(np.abs(s_ddot - e * (a * np.cos(t) - w * w * np.sin(t)))) <= 1e-12 * e * w * w
    pressure = result.column("pressure_angle_23")
    assert pressure.valid.all() and np.max(np.abs(pressure.values)) <= 1e-12
    assert (result.status == 0).all()


def test_offset_roller_follower_against_its_closed_form() -> None:
    e, radius, roller, offset, omega = 10.0, 30.0, 8.0, 6.0, 4.0
    result = sweep(kinepoly.loads_scene(_offset_roller(e, radius, roller, offset, 25.0, omega)), steps=360)
    t = np.radians(result.input.values)
    reach = radius + roller
    rise = [_roller_rise(e, reach, offset, float(x)).real for x in t]
    rate = [omega * _derivative(lambda z: _roller_rise(e, reach, offset, z), float(x), 1) for x in t]
    accel = [omega * omega * _derivative(lambda z: _roller_rise(e, reach, offset, z), float(x), 2) for x in t]
    # the normal runs K -> W, the guide is vertical: sin(phi) = |x_W - x_K| / (R + r)
    phi = np.degrees(np.arcsin(np.abs(offset - e * np.cos(t)) / reach))
    assert np.max(np.abs(result.column("s_13").values - rise)) <= 1e-12 * reach
    assert np.max(np.abs(result.column("s_dot_13").values - rate)) <= 1e-12 * reach * omega
    assert np.max(np.abs(result.column("s_ddot_13").values - accel)) <= 1e-7 * reach * omega * omega
    assert np.max(np.abs(result.column("pressure_angle_23").values - phi)) <= 1e-9


@settings(max_examples=40, deadline=None)
@given(st.floats(2.0, 20.0), st.floats(25.0, 60.0), st.floats(2.0, 15.0), st.floats(-0.6, 0.6),
       st.floats(-180.0, 180.0), st.floats(-30.0, 30.0).filter(lambda w: abs(w) > 0.1))
def test_offset_roller_follower_random(e: float, radius: float, roller: float, share: float, theta: float,
                                       omega: float) -> None:
    offset = share * (radius + roller - e)  # the roller reaches the disc at every angle
    result = sweep(kinepoly.loads_scene(_offset_roller(e, radius, roller, offset, theta, omega)), steps=24)
    t = np.radians(result.input.values)
    reach = radius + roller
    rise = np.array([_roller_rise(e, reach, offset, float(x)).real for x in t])
    rate = np.array([omega * _derivative(lambda z: _roller_rise(e, reach, offset, z), float(x), 1) for x in t])
    sine = np.abs(offset - e * np.cos(t)) / reach
    assert np.max(np.abs(result.column("s_13").values - rise)) <= 1e-11 * reach
    assert np.max(np.abs(result.column("s_dot_13").values - rate)) <= 1e-11 * reach * abs(omega)
    phi = np.radians(result.column("pressure_angle_23").values)
    assert np.max(np.abs(np.sin(phi) - sine)) <= 1e-11


def _rocker_rows(theta: np.ndarray, branch: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The equivalent four-bar O K W P of cam-roller-rocker.toml (OK = 15, KW = R + r = 50, PW = 60,
    P = (75, 35)) by its loop equations: W on both circles, then omega_3 and alpha_3 from the loop's
    derivatives, projected on the coupler K W (omega_2 = 20, alpha_2 = 0). Returns W, omega_3, alpha_3."""
    k = 15.0 * np.exp(1j * theta)
    p = 75.0 + 35.0j
    d = np.abs(p - k)
    along = (50.0**2 - 60.0**2 + d * d) / (2 * d)
    unit = (p - k) / d
    w = k + along * unit + branch * np.sqrt(50.0**2 - along * along) * 1j * unit
    coupler, rocker = w - k, w - p

    def dot(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return np.asarray((x * np.conj(y)).real)

    v_k = 20.0 * 1j * k
    omega3 = dot(v_k, coupler) / dot(1j * rocker, coupler)
    omega_coupler = dot(omega3 * 1j * rocker - v_k, 1j * coupler) / dot(1j * coupler, 1j * coupler)
    # (a_W - a_K) . KW = -omega_KW^2 |KW|^2, a_W = alpha3 i PW - omega3^2 PW, a_K = -400 OK
    alpha3 = (dot(-400.0 * k, coupler) + omega3**2 * dot(rocker, coupler)
              - omega_coupler**2 * 2500.0) / dot(1j * rocker, coupler)
    return w, omega3, alpha3


def test_roller_rocker_columns_against_the_four_bar_loop() -> None:
    # only W's velocity asked: the follower's angle, omega and alpha come with the cam
    text = (EXAMPLES / "cam-roller-rocker.toml").read_text()
    text = text[:text.index("[find]")] + '[find]\nvelocity = ["W"]\n'
    result = sweep(kinepoly.loads_scene(text), steps=360)
    t = np.radians(result.input.values)
    seed = complex(result.column("r_W_x").values[0], result.column("r_W_y").values[0])
    branch = min((1.0, -1.0), key=lambda b: abs(_rocker_rows(t[:1], b)[0][0] - seed))
    w, omega3, alpha3 = _rocker_rows(t, branch)
    p = 75.0 + 35.0j
    theta3 = np.angle(w - p) - math.pi  # W sits at (-60, 0) on the rocker
    assert np.max(np.abs(np.remainder(np.radians(result.column("theta_3").values) - theta3 + math.pi,
                                      2 * math.pi) - math.pi)) <= 1e-12
    assert np.max(np.abs(result.column("omega_3").values - omega3)) <= 1e-11 * np.max(np.abs(omega3))
    assert np.max(np.abs(result.column("alpha_3").values - alpha3)) <= 1e-10 * np.max(np.abs(alpha3))
    # by hand: the force on the roller acts along K W; W moves square to P W
    k = 15.0 * np.exp(1j * t)
    cosine = np.abs(((w - k) * np.conj(1j * (w - p))).real) / (50.0 * 60.0)
    phi = np.degrees(np.arccos(cosine))
    assert np.max(np.abs(result.column("pressure_angle_23").values - phi)) <= 1e-9
    # and it is the complement of the equivalent four-bar's transmission angle at W
    assert np.max(np.abs(result.column("pressure_angle_23").values + result.column("mu_W").values - 90.0)) <= 1e-9


def test_cam_columns_in_the_csv() -> None:
    header = csv_text(sweep(kinepoly.load_scene(EXAMPLES / "eccentric-cam-flat.toml"), steps=4)).splitlines()[0]
    assert header.split(",")[-5:] == ["s_ddot_13", "pressure_angle_23", "mu_T", "status", "warnings"]
    header = csv_text(sweep(kinepoly.load_scene(EXAMPLES / "cam-roller-rocker.toml"), steps=4)).splitlines()[0]
    assert "pressure_angle_23" in header.split(",") and header.count("omega_3") == 1


def test_every_cam_row_equals_the_solve_at_its_input() -> None:
    for name in ("eccentric-cam-flat", "cam-roller-rocker"):
        text = (EXAMPLES / f"{name}.toml").read_text()
        result = sweep(kinepoly.loads_scene(text), steps=36)
        worst = max(compare_row(text, result, row) for row in range(result.rows))
        assert worst <= 1e-10, (name, worst)


def test_plot_draws_the_s_v_a_diagram_and_the_pressure_angle() -> None:
    import matplotlib.pyplot as plt

    from kinepoly.sweep.plots import plot_figure
    from kinepoly.sweep.shown import shown_values

    result = sweep(kinepoly.load_scene(EXAMPLES / "eccentric-cam-flat.toml"), steps=90)
    assert result.followers == (("23", ("s_13", "s_dot_13", "s_ddot_13")),)
    fig = plot_figure(result)
    try:
        by_title = {ax.get_title(): ax for ax in fig.axes if ax.get_visible()}
        stacked = [ax for ax in fig.axes if ax.get_visible() and ax.get_ylabel().split("\n")[0] in
                   ("s_13", "s_dot_13", "s_ddot_13")]
        assert [ax.get_ylabel().split("\n")[0] for ax in stacked] == ["s_13", "s_dot_13", "s_ddot_13"]
        shown = shown_values(result)
        for ax in stacked:  # the plotted vertices are the CSV's column by the number rule, over the cam angle
            x, y = ax.lines[0].get_data()
            name = ax.get_ylabel().split("\n")[0]
            assert np.array_equal(np.asarray(x), result.input.values)
            assert np.array_equal(np.asarray(y), shown[name])
            assert np.allclose(shown[name], result.column(name).values, rtol=1e-9,
                               atol=1e-9 * np.abs(shown[name]).max())
        pressure = next(ax for title, ax in by_title.items() if title.startswith("pressure angles"))
        # a flat face square to its guide: the pressure angle is 0 (the column's 3.5e-15 deg is rounding noise)
        assert np.array_equal(np.asarray(pressure.lines[0].get_ydata()), shown["pressure_angle_23"])
        assert np.abs(result.column("pressure_angle_23").values).max() < 1e-12
    finally:
        plt.close(fig)
