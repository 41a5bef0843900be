"""The approximate slider-crank of the course text: the crank-to-rod ratio expansion.

With the crank pivot at the origin, x along the slide (toward the block), the block's line at
y = -e, lambda = r / l (crank over rod) and k = e / l (relative offset), the rod's angle has
sin phi2 = k + lambda sin phi1 exactly; expanding cos phi2 = sqrt(1 - (k + lambda sin phi1)^2)
binomially and keeping two terms gives the block's place and, differentiated, its velocity
and acceleration (the first-, second- and third-order transmission functions):

    x = r [cos phi1 + 1/lambda - (k + lambda sin phi1)^2 / (2 lambda)]
    v = -omega r [sin phi1 + k cos phi1 + (lambda/2) sin 2 phi1]
    a = -epsilon r [sin phi1 + k cos phi1 + (lambda/2) sin 2 phi1]
        - omega^2 r [cos phi1 - k sin phi1 + lambda cos 2 phi1]

The dropped term is -(l/8)(k + lambda sin phi1)^4: an error of about l (k + lambda)^4 / 8,
0.1% of the stroke for lambda = 1/3. It gives only the block (its point and the slider values).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from msgspec import Struct

from kinepoly.geom.vec import Vec
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import LinkInput, SliderSpec

__all__ = ["SliderSeries", "pin_between", "slider_crank_links", "slider_crank_series"]

Array = np.ndarray


def pin_between(mechanism: Mechanism, a: str, b: str) -> Revolute | None:
    """The revolute joint between links ``a`` and ``b``, if any."""
    return next((p for p in mechanism.revolutes if set(p.links) == {a, b}), None)


def _ground_slider(mechanism: Mechanism) -> tuple[SliderSpec, Vec, Vec] | None:
    """The one slider, on the frame: (spec, its line's point, its unit direction), frame coordinates."""
    if len(mechanism.sliders) != 1 or mechanism.sliders[0].guide != mechanism.ground:
        return None
    spec = mechanism.sliders[0]
    e = (float(np.cos(spec.angle_rad)), float(np.sin(spec.angle_rad)))
    return spec, spec.through, e


def slider_crank_links(mechanism: Mechanism) -> tuple[str, str, str, str, str, str, SliderSpec, Vec, Vec] | None:
    """(crank, rod, block, O2, A, B, slider, T, e) of a slider-crank (any input), else None."""
    slide = _ground_slider(mechanism)
    if slide is None or len(mechanism.link_names) != 4 or len(mechanism.revolutes) != 3 or mechanism.ground is None:
        return None
    spec, through, e = slide
    block, ground = spec.block, mechanism.ground
    rod_pin = next((p for p in mechanism.revolutes if block in p.links), None)
    if rod_pin is None or rod_pin.point != spec.point:
        return None
    rod = rod_pin.other(block)
    crank = next((k for k in mechanism.link_names if k not in (ground, rod, block)), None)
    if crank is None:
        return None
    o2, pa = pin_between(mechanism, crank, ground), pin_between(mechanism, crank, rod)
    if o2 is None or pa is None:
        return None
    return crank, rod, block, o2.point, pa.point, spec.point, spec, through, e


class SliderSeries(Struct, frozen=True):
    """The series for one scene: the keys it gives and their values for an array of crank angles."""

    name: str
    keys: tuple[str, ...]
    values: Callable[[Array], dict[str, object]]


def slider_crank_series(mechanism: Mechanism, pose: Pose, keys: list[str]) -> SliderSeries | None:
    """The series where the scene is a crank-driven slider-crank, for the asked keys it can give."""
    parts = slider_crank_links(mechanism)
    inp = mechanism.scene.input
    if parts is None or not isinstance(inp, LinkInput) or inp.link != parts[0]:
        return None
    crank, rod, block, o2, pa, pb, spec, through, e_slide = parts
    ground = mechanism.ground
    assert ground is not None
    g2 = mechanism.local(ground, o2)
    la, lb = mechanism.local(crank, o2), mechanism.local(crank, pa)
    r = float(np.hypot(lb[0] - la[0], lb[1] - la[1]))
    ra, rb = mechanism.local(rod, pa), mechanism.local(rod, pb)
    rod_length = float(np.hypot(rb[0] - ra[0], rb[1] - ra[1]))
    b_now = pose.links[block].world(mechanism.local(block, pb))
    a_now = pose.links[crank].world(mechanism.local(crank, pa))
    toward = 1.0 if (b_now[0] - a_now[0]) * e_slide[0] + (b_now[1] - a_now[1]) * e_slide[1] >= 0 else -1.0
    ex, ey = toward * e_slide[0], toward * e_slide[1]  # the course text's x-axis: toward the block
    y_line = -ey * (through[0] - g2[0]) + ex * (through[1] - g2[1])
    lam, k = r / rod_length, -y_line / rod_length  # the line is at y = -e
    arm0 = float(np.arctan2(lb[1] - la[1], lb[0] - la[0]))
    x_axis = float(np.arctan2(ey, ex))
    w, eps = inp.omega, inp.alpha
    label = pb
    wanted = [key for key in keys if key in (f"points.{label}.position", f"points.{label}.velocity",
                                               f"points.{label}.acceleration", f"sliders.{spec.name}.s",
                                               f"sliders.{spec.name}.s_dot", f"sliders.{spec.name}.s_ddot")]
    if not wanted:
        return None

    def values(t: Array) -> dict[str, object]:
        phi = t + arm0 - x_axis
        x = r * (np.cos(phi) + 1.0 / lam - (k + lam * np.sin(phi)) ** 2 / (2.0 * lam))
        first = np.sin(phi) + k * np.cos(phi) + 0.5 * lam * np.sin(2.0 * phi)
        v = -w * r * first
        a = -eps * r * first - w * w * r * (np.cos(phi) - k * np.sin(phi) + lam * np.cos(2.0 * phi))
        px, py = g2[0] + x * ex - y_line * ey, g2[1] + x * ey + y_line * ex
        along = ex * e_slide[0] + ey * e_slide[1]  # +1 or -1
        s = (px - through[0]) * e_slide[0] + (py - through[1]) * e_slide[1]
        out = {f"points.{label}.position": (px, py), f"points.{label}.velocity": (v * ex, v * ey),
               f"points.{label}.acceleration": (a * ex, a * ey), f"sliders.{spec.name}.s": s,
               f"sliders.{spec.name}.s_dot": along * v, f"sliders.{spec.name}.s_ddot": along * a}
        return {key: out[key] for key in wanted}

    return SliderSeries("series (slider-crank, course text, two terms)", tuple(wanted), values)
