"""Compound hinges: a pin of k links is k - 1 joints, and the primary center of every two of them.

The toggle press of examples/toggle-press.toml is checked against its own loop equations, written
here from the course texts' complex-number method and shared with nothing in kinepoly:

- loop A0 A K B0:  a2 e^(i th2) + a3 e^(i th3) = (B0 - A0) + a4 e^(i th4);
- loop B0 K C:     B0 + a4 e^(i th4) + a5 e^(i th5) = x_C + i y_C, x_C fixed (the ram's guide).

Differentiated once, each gives two real equations linear in the unknown rates (Cramer's rule);
differentiated twice, the same matrix with the known normal and input terms on the right.
"""

from __future__ import annotations

import cmath
import math
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import kinepoly

EXAMPLE = Path(__file__).parents[2] / "examples" / "toggle-press.toml"
A0, B0 = complex(0, 50), complex(150, 150)
A2, A3, A4, A5, X_C = 30.0, 140.0, 95.0, 105.0, 150.0


def _solve2(m: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    return np.linalg.solve(m, rhs)


def toggle_press(theta2: float, w2: float, al2: float) -> dict[str, complex | float]:
    """Position, velocity and acceleration of the press by its loop equations (K right of A -> B0, C below K)."""
    e2 = cmath.exp(1j * theta2)
    a = A0 + A2 * e2
    # K: |K - A| = a3, |K - B0| = a4, on the side of the example's guess (right of the line A -> B0)
    d = B0 - a
    dist = abs(d)
    along = (dist * dist + A3 * A3 - A4 * A4) / (2 * dist)
    h = math.sqrt(A3 * A3 - along * along)
    k = a + (along - 1j * h) * d / dist
    e3, e4 = (k - a) / A3, (k - B0) / A4
    # C: on the line x = X_C, |C - K| = a5, below K
    y_c = k.imag - math.sqrt(A5 * A5 - (X_C - k.real) ** 2)
    c = complex(X_C, y_c)
    e5 = (c - k) / A5
    # velocities: i a2 w2 e2 + i a3 w3 e3 - i a4 w4 e4 = 0
    m = np.array([[(1j * A3 * e3).real, (-1j * A4 * e4).real], [(1j * A3 * e3).imag, (-1j * A4 * e4).imag]])
    rhs = -1j * A2 * w2 * e2
    w3, w4 = _solve2(m, np.array([rhs.real, rhs.imag]))
    # i a4 w4 e4 + i a5 w5 e5 = i y_c'  (x_C fixed): real part gives w5, imaginary part y_c'
    v_k = 1j * A4 * w4 * e4
    w5 = -v_k.real / (1j * A5 * e5).real
    v_c = v_k + 1j * A5 * w5 * e5
    # accelerations: the same matrix, the normal and input terms known
    known = (1j * al2 - w2 * w2) * A2 * e2 - w3 * w3 * A3 * e3 + w4 * w4 * A4 * e4
    al3, al4 = _solve2(m, np.array([-known.real, -known.imag]))
    a_k = (1j * al4 - w4 * w4) * A4 * e4
    rest = a_k - w5 * w5 * A5 * e5
    al5 = -rest.real / (1j * A5 * e5).real
    a_c = rest + 1j * al5 * A5 * e5
    return {"K": k, "C": c, "v_K": v_k, "v_C": v_c, "a_K": a_k, "a_C": a_c, "w3": w3, "w4": w4, "w5": w5,
            "al3": al3, "al4": al4, "al5": al5}


def _scene_at(theta_deg: float, guess_k: complex, guess_c: complex) -> str:
    text = EXAMPLE.read_text()
    text = text.replace("angle = 40", f"angle = {theta_deg!r}")
    text = text.replace("K = [165, 58]", f"K = [{guess_k.real!r}, {guess_k.imag!r}]")
    return text.replace("C = [150, -45]", f"C = [{guess_c.real!r}, {guess_c.imag!r}]")


def _agree(theta_deg: float) -> None:
    ref = toggle_press(math.radians(theta_deg), 12.0, 0.0)
    solution = kinepoly.solve(kinepoly.loads_scene(_scene_at(theta_deg, complex(ref["K"]), complex(ref["C"]))))
    assert solution.velocity is not None and solution.acceleration is not None
    size, speed = 300.0, max(abs(complex(ref["v_K"])), abs(complex(ref["v_C"])))
    accel = max(abs(complex(ref["a_K"])), abs(complex(ref["a_C"])))
    for label in ("K", "C"):
        assert abs(complex(*solution.position(label)) - complex(ref[label])) <= 1e-10 * size
        assert abs(complex(*solution.velocity.tips[label]) - complex(ref[f"v_{label}"])) <= 1e-10 * speed
        assert abs(complex(*solution.acceleration.tips[label]) - complex(ref[f"a_{label}"])) <= 1e-9 * accel
    omega_scale = max(abs(float(ref[f"w{k}"])) for k in (3, 4, 5))
    alpha_scale = max(abs(float(ref[f"al{k}"])) for k in (3, 4, 5)) + omega_scale ** 2
    for k in ("3", "4", "5"):
        assert abs(solution.velocity.omega[k] - float(ref[f"w{k}"])) <= 1e-10 * omega_scale
        assert abs(solution.acceleration.alpha[k] - float(ref[f"al{k}"])) <= 1e-9 * alpha_scale


def test_the_toggle_press_agrees_with_its_loop_equations() -> None:
    _agree(40.0)


@settings(max_examples=40, deadline=None)
@given(theta_deg=st.floats(0.0, 360.0))
def test_the_toggle_press_agrees_over_its_turn(theta_deg: float) -> None:
    _agree(theta_deg)


def test_a_pin_of_three_links_is_two_joints_and_three_primary_centers() -> None:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLE))
    knee = [j for j in solution.mechanism.revolutes if j.point == "K"]
    assert sorted(j.links for j in knee) == [("3", "4"), ("3", "5")]
    assert solution.centers is not None
    k = complex(*solution.position("K"))
    for pair in ("35", "45"):
        point = solution.centers.centers[pair].place.position
        assert point is not None and abs(complex(*point) - k) <= 1e-9 * 300.0
    every = kinepoly.solve(kinepoly.loads_scene(EXAMPLE.read_text().replace(
        'instant_centers = ["16", "35", "45"]', 'instant_centers = "all"')))
    assert every.centers is not None
    assert len(every.centers.centers) == 15  # six links: 6 * 5 / 2 centers
    for center in every.centers.centers.values():
        assert center.place.position is None or all(math.isfinite(x) for x in center.place.position)
