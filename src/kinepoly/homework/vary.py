"""The ``[vary]`` table of a scene: the ranges ``kinepoly variants`` draws from (a kinepoly extension).

```toml
[vary]
lengths = [0.9, 1.1]          # each link's dimensions times a factor drawn in this range, link by link
links = { "1" = [1, 1] }      # a link's own factor range (here: keep the frame as it is)
angle = [20, 160]             # a link input: theta, in the scene's angle unit
omega = [5, 15]               # rad/s (or unit strings: "300 rpm")
alpha = [0, 0]                # rad/s^2
# a slider input instead: s = [100, 150], s_dot = [-600, -300], s_ddot = [0, 0]
```

Every key is optional; a range not given is the default of :func:`default_ranges`. ``kinepoly
solve`` only checks that ``[vary]`` is a table; this module checks every key and reports
problems as the scene loader does (``FILE:LINE: vary.key: what; expected``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import partial
from typing import Literal

from msgspec import Struct, field

from kinepoly.scene.loader import ProblemReport, read_quantity, show_value, suggest
from kinepoly.scene.problems import no_such
from kinepoly.scene.spec import LinkInput, Scene, SliderInput

__all__ = ["Range", "Ranges", "default_ranges", "read_vary"]

_LINK_KEYS = ("lengths", "links", "angle", "omega", "alpha")
_SLIDER_KEYS = ("lengths", "links", "s", "s_dot", "s_ddot")
_QUANTITY: dict[str, Literal["angle", "omega", "alpha", "length", "speed", "accel"]] = {
    "angle": "angle", "omega": "omega", "alpha": "alpha", "s": "length", "s_dot": "speed", "s_ddot": "accel"}


class Range(Struct, frozen=True):
    """low <= high, in the stored unit (radians for angles, rad/s, the scene's lengths)."""

    low: float
    high: float


class Ranges(Struct, frozen=True):
    """What a variant draws: a factor range per link, and a range per input value (by its spec name)."""

    factors: Mapping[str, Range]
    inputs: Mapping[str, Range] = field(default_factory=dict)


def _spread(value: float) -> Range:
    """Half to one and a half times ``value`` (a zero stays zero)."""
    ends = sorted((0.5 * value, 1.5 * value))
    return Range(ends[0], ends[1])


def default_ranges(scene: Scene) -> Ranges:
    """Lengths 0.9 to 1.1 per link; a link input's angle the whole turn, its omega and alpha half to one and a
    half times the scene's; a slider input's s within a tenth of the mechanism's size, s_dot and s_ddot as omega."""
    factors = {link.name: Range(0.9, 1.1) for link in scene.links}
    inp = scene.input
    if isinstance(inp, LinkInput):
        return Ranges(factors, {"angle_rad": Range(0.0, 2.0 * math.pi), "omega": _spread(inp.omega),
                                "alpha": _spread(inp.alpha)})
    if isinstance(inp, SliderInput):
        size = max((math.hypot(*p.local) for link in scene.links for p in link.points), default=1.0)
        return Ranges(factors, {"s": Range(inp.s - 0.1 * size, inp.s + 0.1 * size), "s_dot": _spread(inp.s_dot),
                                "s_ddot": _spread(inp.s_ddot)})
    return Ranges(factors)


def _range(report: ProblemReport, path: tuple[str, ...], value: object, quantity: str, scene: Scene,
           example: str) -> Range | None:
    if not isinstance(value, list) or len(value) != 2:
        report.add(path, f"expected a range [low, high] like {example}, got {show_value(value)}")
        return None
    if quantity == "factor":
        ends = [_factor(report, path, item) for item in value]
    else:
        ends = [read_quantity(report, path, item, _QUANTITY[quantity], scene.units) for item in value]
    low, high = ends
    if low is None or high is None:
        return None
    if low > high:
        report.add(path, f"{show_value(value)} runs backwards; expected [low, high] with low <= high")
        return None
    return Range(low, high)


def _factor(report: ProblemReport, path: tuple[str, ...], value: object) -> float | None:
    expected = "a factor above 0 (1 keeps the length)"
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        report.add(path, f"expected {expected}, got {show_value(value)}")
        return None
    if value <= 0:
        report.add(path, f"{show_value(value)} is not above 0; expected {expected}")
        return None
    return float(value)


_EXAMPLES = {"lengths": "[0.9, 1.1]", "angle": "[20, 160]", "omega": "[5, 15]", "alpha": "[0, 10]",
             "s": "[100, 150]", "s_dot": "[-600, -300]", "s_ddot": "[0, 0]"}
_SPEC_NAME = {"angle": "angle_rad", "omega": "omega", "alpha": "alpha", "s": "s", "s_dot": "s_dot", "s_ddot": "s_ddot"}


def read_vary(report: ProblemReport, value: object, scene: Scene,
              overrides: Mapping[str, Range] | None = None) -> Ranges:
    """The ranges of ``[vary]`` (``value``; None when absent) over the defaults, then ``overrides`` over both.

    Problems go to ``report``; the caller raises them. ``overrides`` are keyed as ``[vary]`` is
    (``lengths``, ``angle``, ...) in stored units.
    """
    defaults = default_ranges(scene)
    factors, inputs = dict(defaults.factors), dict(defaults.inputs)
    table: Mapping[str, object] = {}
    if isinstance(value, dict):
        table = value
    elif value is not None:
        report.add(("vary",), f"expected a [vary] table of ranges like angle = [20, 160], got {show_value(value)}")
    allowed = _LINK_KEYS if isinstance(scene.input, LinkInput) else _SLIDER_KEYS
    for key, item in table.items():
        path = ("vary", key)
        if key not in allowed:
            other = key in _LINK_KEYS + _SLIDER_KEYS
            driver = "a link" if isinstance(scene.input, LinkInput) else "a slider"
            report.add(path, f"not a key for {driver} input; expected one of {', '.join(allowed)}" if other
                       else f"unknown key; {suggest(key, allowed)}")
        elif key == "lengths":
            lengths = _range(report, path, item, "factor", scene, _EXAMPLES["lengths"])
            if lengths is not None:
                factors = {name: lengths for name in factors}
        elif key != "links":
            drawn = _range(report, path, item, key, scene, _EXAMPLES[key])
            if drawn is not None:
                inputs[_SPEC_NAME[key]] = drawn
    if "links" in table:
        factors.update(_link_factors(report, table["links"], scene))
    for key, drawn in (overrides or {}).items():
        if key == "lengths":
            factors = {name: drawn for name in factors}
        else:
            inputs[_SPEC_NAME[key]] = drawn
    return Ranges(factors, inputs)


def _link_factors(report: ProblemReport, value: object, scene: Scene) -> dict[str, Range]:
    path = ("vary", "links")
    if not isinstance(value, dict):
        report.add(path, f'expected a table of link factor ranges like {{ "1" = [1, 1] }}, got {show_value(value)}')
        return {}
    names = [link.name for link in scene.links]
    out = {}
    for name, item in value.items():
        if name not in names:
            report.add(path + (name,), partial(no_such, "link", name, names))
            continue
        drawn = _range(report, path + (name,), item, "factor", scene, "[0.8, 1.2]")
        if drawn is not None:
            out[name] = drawn
    return out
