"""The finite-rotation pole of a link between two inputs of a sweep (``kinepoly sweep --centrode LINK --pole A B``).

Both positions are the sweep's: the mechanism is carried from A to B by continuity on the scene's
assembly, so the two positions are of one motion. The geometry is ``engine.finite_pole``'s.
"""

from __future__ import annotations

import numpy as np
from msgspec import Struct

from kinepoly.engine.circle_diagram import pair_name
from kinepoly.engine.finite_pole import FinitePole, finite_pole
from kinepoly.errors import SceneError
from kinepoly.model.pose import LinkPose
from kinepoly.scene.spec import Scene
from kinepoly.sweep.result import NEAR_SINGULAR, SweepResult
from kinepoly.sweep.run import prepare_sweep, run_sweep

__all__ = ["PoleBetween", "pole_between"]


_STEPS = 16
"""Rows the motion from A to B is followed over (continuity needs steps, the pole only the two ends)."""


class PoleBetween(Struct, frozen=True):
    """P12 of a link between inputs ``start`` and ``stop``, every posed link at both, and the instant center at A."""

    found: FinitePole
    start: float
    stop: float
    first: dict[str, LinkPose]
    second: dict[str, LinkPose]
    instant_center: complex | None


def _center(result: SweepResult, name: str) -> complex | None:
    columns = {c.name: c for c in result.columns}
    x, y = columns.get(f"{name}_x"), columns.get(f"{name}_y")
    if x is None or y is None or not (bool(x.valid[0]) and bool(y.valid[0])):
        return None
    return complex(float(x.values[0]), float(y.values[0]))


def pole_between(scene: Scene, link: str, start: float, stop: float) -> PoleBetween:
    """The pole of ``link``'s displacement from input ``start`` to ``stop`` (the input's unit)."""
    if start == stop:
        raise SceneError(f"--pole {start:g} {stop:g}: expected two different inputs (the pole of no displacement is "
                         "not defined; its limit is the instant center, --centrode)")
    prepared = prepare_sweep(scene, link)
    result = run_sweep(prepared, steps=_STEPS, start=start, stop=stop)
    positions = result.positions
    assert positions is not None
    if not (result.status[0] <= NEAR_SINGULAR and result.status[-1] <= NEAR_SINGULAR):
        raise SceneError(f"--pole {start:g} {stop:g}: the mechanism is not assembled (or is singular) at both "
                         "inputs; choose two inputs of one motion")
    rows = np.flatnonzero(result.shown) if result.shown is not None else np.arange(positions.n)
    # the scene's own input may be a hidden row
    first, second = positions.row(int(rows[0])), positions.row(int(rows[-1]))
    ground = prepared.mechanism.ground or ""
    name = f"I_{pair_name((ground, link))}"
    found = finite_pole(prepared.mechanism, link, first[link], second[link])
    return PoleBetween(found, start, stop, first, second, _center(result, name))
