"""One round-number rule (1, 2, 2.5 or 5 times a power of ten) for every scale: the solve's kv and ka, the
layout's panels and scale bars, the animation's frames all take ``present.scales``'."""

from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st

from kinepoly.motion.frames import fitting_scale
from kinepoly.present.scales import nice_floor
from kinepoly.render import layout

_LADDER = (1.0, 2.0, 2.5, 5.0)


def _is_round(x: float) -> bool:
    exponent = math.floor(math.log10(x))
    return any(math.isclose(x, m * 10.0**e, rel_tol=1e-12) for e in (exponent - 1, exponent, exponent + 1)
               for m in _LADDER)


def test_the_layout_takes_the_one_rule() -> None:
    assert layout.nice_floor is nice_floor


@given(st.floats(min_value=1e-9, max_value=1e12))
def test_the_round_floor_is_the_largest_round_number_not_above(x: float) -> None:
    y = nice_floor(x)
    assert _is_round(y) and y <= x * (1.0 + 1e-12)
    above = [m * 10.0**e for e in range(math.floor(math.log10(y)) - 1, math.floor(math.log10(y)) + 2) for m in _LADDER]
    assert all(c <= y * (1.0 + 1e-12) or c > x for c in above)


@given(st.floats(min_value=1e-6, max_value=1e9), st.floats(min_value=10.0, max_value=500.0))
def test_the_animation_scale_is_the_round_floor_of_its_room(radius: float, room_mm: float) -> None:
    assert fitting_scale(radius, room_mm) == nice_floor(room_mm / radius)
    assert fitting_scale(0.0, room_mm) == 1.0 and fitting_scale(math.inf, room_mm) == 1.0
